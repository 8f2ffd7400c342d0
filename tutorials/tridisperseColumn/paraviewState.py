"""ParaView state of the tridisperse column: profiles of the three grain
fractions, the air and the flow at the last written time.  Usage: ParaView
states in doc/visualisation.md (paraview --state=paraviewState.py)."""
import os
import sys

sys.path.insert(0, os.environ.get("FOAM_USER_APPBIN", ""))  # openfoam.env
import granularParaView  # noqa: E402 (source etc/openfoam.env if missing)

granularParaView.main(["alpha.small", "alpha.medium", "alpha.large",
                       "alpha.air", "U", "p", "I", "illPosed"])

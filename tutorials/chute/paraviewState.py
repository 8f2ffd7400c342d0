"""ParaView state of the chute: the fields at the last written time, the
layer (0.62 m by 6.2 mm) stretched 10 times vertically.  Usage: ParaView
states in doc/visualisation.md (paraview --state=paraviewState.py)."""
import os
import sys

sys.path.insert(0, os.environ.get("FOAM_USER_APPBIN", ""))  # openfoam.env
import granularParaView  # noqa: E402 (source etc/openfoam.env if missing)

granularParaView.main(["alpha.small", "alpha.large", "alpha.air",
                       "U", "p", "I", "illPosed"], exaggeration=10)

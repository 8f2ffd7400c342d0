"""ParaView state of the segregation column, one cell wide: profiles of the
fields at the last written time.  Usage: ParaView states in
doc/visualisation.md (paraview --state=paraviewState.py)."""
import os
import sys

sys.path.insert(0, os.environ.get("FOAM_USER_APPBIN", ""))  # openfoam.env
import granularParaView  # noqa: E402 (source etc/openfoam.env if missing)

granularParaView.main(["alpha.small", "alpha.large", "alpha.air",
                       "U", "p", "I", "illPosed"])

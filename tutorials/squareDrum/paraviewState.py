"""ParaView state of squareDrum: every phase fraction, the speed, p,
I and the ill-posedness indicator of (2.6) at the last written time, in the
drum as it has turned (the mesh rotates).

In this case's directory, after ./Allrun (pvbatch needs a display: Xvfb):

    paraview --state=paraviewState.py
    pvbatch paraviewState.py --screenshot figures/paraview.png
"""
import os
import sys

# granularParaView is in $FOAM_USER_APPBIN: source etc/openfoam.env
sys.path.insert(0, os.environ.get("FOAM_USER_APPBIN", ""))
import granularParaView  # noqa: E402 (source etc/openfoam.env if not found)

granularParaView.main(["alpha.small", "alpha.large", "alpha.air",
                       "U", "p", "I", "illPosed"])

"""granularfoam: the Python side of granularSegregationFoam.

    granularfoam.exact    the exact solutions of Barker et al. (2021) and
                          the error measures against them
    granularfoam.foamio   readers of what OpenFOAM wrote and sampled
    granularfoam.post     the tutorials' measurements and figures

Installed by ./Allwmake into platforms/<WM_OPTIONS>/python, which
etc/openfoam.env puts on PYTHONPATH; used by the tutorials, the tests
(validation/) and the benchmarks (bench/) alike.
"""

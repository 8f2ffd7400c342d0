"""Smoke tier of the solver: a dynamic (rotating) mesh runs, turns by the
prescribed angle, conserves each phase's volume and keeps the phase
fractions in [0, 1]."""
import math
import re

import numpy as np
import pytest

from cases import foam, fresh_case, run_case, volumes

pytestmark = pytest.mark.smoke

OMEGA = -math.pi / 5        # rad/s, constant/dynamicMeshDict


def read_points(path):
    """Points of an ascii polyMesh/points file as an (n, 3) array."""
    text = path.read_text()
    rows = re.findall(r"^\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)$",
                      text, re.M)
    assert rows, f"no points in {path}"
    return np.array(rows, dtype=float)


def read_minmax(case):
    path = case / "postProcessing" / "bounds" / "0" / "fieldMinMax.dat"
    assert path.is_file(), f"missing {path}"
    data = np.loadtxt(path, comments="#", ndmin=2)
    assert data.shape[0] > 10, f"only {data.shape[0]} steps in {path}"
    return data[:, 1:]


def test_rotating_box(foam_env):
    case = fresh_case("rotatingBox")
    run_case(case)
    t_end = max((d.name for d in case.iterdir()
                 if re.fullmatch(r"[0-9.]+", d.name) and d.name != "0"),
                key=float)

    p0 = read_points(case / "constant" / "polyMesh" / "points")
    p1 = read_points(case / t_end / "polyMesh" / "points")
    a = OMEGA * float(t_end)
    rot = np.array([[math.cos(a), -math.sin(a), 0],
                    [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    assert np.abs(p1 - p0 @ rot.T).max() < 1e-9, "mesh did not turn by omega t"

    t, vol = volumes(case)
    for name, v in vol.items():
        v = np.array(v)
        drift = np.abs(v - v[0]).max() / v[0]
        assert drift < 1e-12, f"{name}: relative volume drift {drift:.3e}"

    bounds = read_minmax(case)
    assert bounds.min() > -1e-10 and bounds.max() < 1 + 1e-10, (
        f"phase fractions outside [0, 1]: [{bounds.min()}, {bounds.max()}]")


GRAIN_PRESSURE = re.compile(
    r"^Grain pressure seen by the rheology: min = (\S+) Pa(.*)$", re.M)


def test_grain_pressure_reported(foam_env):
    """The log gives the lowest pressure seen by the rheology in the grains
    at the start and after every step, and calls it tension below
    -tensionWarning.  The periodic layer (open: p = p_rgh + rho gh) starts
    from p_rgh = 0, so p = rho g.x < 0 in the grains at the start: at the
    top grain cell, -rho g_z z; one step later the pressure holds the
    grains' weight and is positive."""
    case = fresh_case("inclinedLayer", dest="tension/layer")
    foam(case, "foamDictionary", "-entry", "endTime", "-set", "2e-3",
         "system/controlDict")
    foam(case, "foamDictionary", "-entry", "writeInterval", "-set", "2e-3",
         "system/controlDict")
    run_case(case)
    log = (case / "log.granularSegregationFoam").read_text()
    lines = GRAIN_PRESSURE.findall(log)
    steps = log.count("\nTime = ")
    assert steps >= 2 and len(lines) == steps + 1, (
        f"{len(lines)} grain pressure lines for {steps} steps")

    # 60 cells over 6 mm, grains below 5 mm: the top grain cell's centre
    # at 4.95 mm; rho = Phi rho_* = 1500, g_z = -9.81 cos 24
    rho, g_z, z_top = 1500.0, -8.961880939473915, 4.95e-3
    first, note = float(lines[0][0]), lines[0][1]
    assert first == pytest.approx(rho * g_z * z_top, rel=1e-6), lines[0]
    assert "tension in the grains" in note, lines[0]
    last, note = float(lines[-1][0]), lines[-1][1]
    assert last > 0 and "tension" not in note, lines[-1]

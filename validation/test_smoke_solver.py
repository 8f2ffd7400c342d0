"""Smoke tier of the solver: a dynamic (rotating) mesh runs, turns by the
prescribed angle, conserves each phase's volume and keeps the phase
fractions in [0, 1]."""
import math
import re

import numpy as np
import pytest

from cases import fresh_case, run_case, volumes

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

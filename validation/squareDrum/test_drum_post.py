"""Unit tier of the square drum's post-processing (granularfoam.post.drum):
where the grains are below zero pressure, on a synthetic 6 x 6 drum, and
the steps' grain pressure by the phase of the quarter turn.
"""
import math

import numpy as np
import pytest

from granularfoam.post import drum as post

pytestmark = pytest.mark.unit

N = 6
OMEGA = -math.pi / 5


def _synthetic(p_low):
    """A 6 x 6 drum at rest in the lab: air in the top two rows, p = 100
    Pa in the grains but for p_low {(row, column): p}."""
    edges = np.linspace(-0.1, 0.1, N + 1)
    X, Y = np.meshgrid(edges, edges)
    air = np.zeros((N, N))
    air[4:, :] = 1
    p = np.full((N, N), 100.0)
    for cell, value in p_low.items():
        p[cell] = value
    eta = np.full((N, N), 3000.0)
    eta[2, 0], eta[1, 2] = 7.0, 9.0
    inertial = np.full((N, N), 1e-4)
    inertial[1, 2] = 50.0
    return X, Y, {"p": p, "alpha.air": air, "Ux": np.zeros((N, N)),
                  "Uy": np.zeros((N, N)), "etaGranular": eta,
                  "I": inertial}


def test_tension_where(monkeypatch):
    """The lowest grain cell below zero, its distances in cells to the
    wall, the corner and the air, the cells below zero and their largest
    viscosity and inertial number; times without tension left out."""
    fields = {"71.875": _synthetic({(2, 0): -5.0, (1, 2): -1.0}),
              "72.5": _synthetic({})}
    monkeypatch.setattr(post, "grid", lambda case, name, names:
                        fields[name])
    out = post.tension_where("case", ["71.875", "72.5"])
    assert len(out) == 1
    r = out[0]
    assert r["t"] == 71.875
    assert r["quarter_turn_phase_s"] == pytest.approx(1.875)
    assert r["lowest_p"] == -5.0
    assert r["grain_cells_below_zero"] == 2
    assert r["cells_to_wall"] == 0
    assert r["cells_to_corner"] == 2
    assert r["cells_to_air"] == 2.0
    assert r["eta_granular_below_zero_max"] == 9.0
    assert r["I_below_zero_max"] == 50.0
    xc, yc = -0.1 + 0.5 * 0.2 / N, -0.1 + 2.5 * 0.2 / N
    assert r["position_m"] == pytest.approx([xc, yc])
    # At rest in the lab, the drum turns past the cell at |Omega| r
    assert r["speed_relative_to_drum"] == pytest.approx(
        abs(OMEGA) * math.hypot(xc, yc))


def test_tension_by_phase():
    """Steps binned by t mod T/4: counts, those below zero, lowest and
    median per bin; bins without steps left out."""
    t = np.array([0.1, 2.6, 1.3, 1.4, 2.4])
    low = np.array([1.0, -1.0, -3.0, 4.0, -2.0])
    out = post.tension_by_phase(t, low)
    assert [b["phase_s"] for b in out] == [
        pytest.approx([0.0, 0.25]), pytest.approx([1.25, 1.5]),
        pytest.approx([2.25, 2.5])]
    assert [b["steps"] for b in out] == [2, 2, 1]
    assert [b["below_zero"] for b in out] == [1, 1, 1]
    assert [b["lowest_p"] for b in out] == [-1.0, -3.0, -2.0]
    assert [b["median_p"] for b in out] == [0.0, 0.5, -2.0]

"""Measurements of the column collapse (tutorials/columnCollapse) from its
sampled floor row and wall column (system/controlDict, function
`profiles`), its grain volume (function `volumes`) and its written fields:

- front: the right edge of the last floor cell of the deposit, the cells
  with phi^g > 1/2 contiguous from the left wall [m];
- wall height: the grain depth of the wall's column, sum of phi^g dz [m];
- fastest grains: the largest |U| over the cells with phi^g > 1/2 [m/s];
- volume change: the largest |V^g(t) - V^g(0)| / V^g(0) over the run.

    /usr/bin/python3 validation/columnCollapse/post.py <case>

prints them as JSON, each time series by sampled time.
"""
import json
import re
import sys
from pathlib import Path

if __name__ == "__main__" and __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np  # noqa: E402

from cases import profiles, times, volumes  # noqa: E402
from chute import post as fields  # noqa: E402

GRAINS = 0.5                # phi^g above this is "grains"


def parameters(case):
    """Numeric entries of case/system/columnParameters."""
    text = (Path(case) / "system" / "columnParameters").read_text()
    text = re.sub(r"//.*", "", text)
    return {k: float(v) for k, v in re.findall(
        r"^\s*(\w+)\s+([-+0-9.eE]+)\s*;", text, flags=re.M)}


def front(case, time_name):
    """Right edge of the deposit on the floor: the last of the cells with
    phi^g > 1/2 contiguous from the left wall [m] (0: none)."""
    prof = profiles(case, time_name, function="profiles", set_name="floor")
    x, g = prof["z"], prof["alpha.grains"]
    dx = x[1] - x[0]
    outside = np.nonzero(g <= GRAINS)[0]
    n = outside[0] if outside.size else g.size
    return float(x[n - 1] + 0.5 * dx) if n else 0.0


def wall_height(case, time_name):
    """Grain depth of the wall's column of cells [m]."""
    prof = profiles(case, time_name, function="profiles", set_name="wall")
    z, g = prof["z"], prof["alpha.grains"]
    return float(np.sum(g) * (z[1] - z[0]))


def fastest_grains(case, time_name):
    """Largest |U| over the cells with phi^g > 1/2 [m/s]."""
    g = fields.read_field(case, time_name, "alpha.grains")
    U = fields.read_field(case, time_name, "U")
    speed = np.linalg.norm(U[g > GRAINS], axis=1)
    assert speed.size, f"{case}/{time_name}: no cell with phi^g > 1/2"
    return float(speed.max())


def volume_change(case):
    """Largest relative change of the grain volume over the run."""
    _, v = volumes(case)
    vg = np.asarray(v["alpha.grains"])
    assert vg.size >= 2 and vg[0] > 0, f"{case}: no grain volume history"
    return float(np.max(np.abs(vg - vg[0])) / vg[0])


def measure(case):
    """Every number above: time series by sampled time, and the end's."""
    names = times(case, "profiles")
    assert len(names) >= 2, f"{case}: fewer than two sampled times"
    end = names[-1]
    return {
        "times": [float(t) for t in names],
        "front": [front(case, t) for t in names],
        "wall_height": [wall_height(case, t) for t in names],
        "fastest_grains_end": fastest_grains(case, end),
        "volume_change": volume_change(case),
        "end_time": float(end),
    }


if __name__ == "__main__":
    print(json.dumps(measure(Path(sys.argv[1])), indent=2))

"""Measurements of the column collapse (tutorials/columnCollapse) from its
sampled floor row and wall column (system/controlDict, function
`profiles`), its grain volume (function `volumes`) and its written fields:

- front: where phi^g falls through 1/2 along the floor's row of cells,
  from the left wall [m];
- wall height: the grain depth of the wall's column, sum of phi^g dz [m];
- fastest grains: the largest |U| over the cells with phi^g > 1/2 [m/s],
  at the end and at every written time;
- stop: the first sampled time from which the front moves by less than
  STOP over the rest of the run [s];
- volume change: the largest |V^g(t) - V^g(0)| / V^g(0) over the run;
- deposit: the grain depth of every column of cells at the end [m].

    /usr/bin/python3 -m granularfoam.post.columnCollapse <case>... [--out DIR]

prints them as JSON, each time series by sampled time; with --out, draws
the front x_f(t), the height at the wall and the deposits of the cases
into DIR/columnCollapse.png.  Cell centres come from `postProcess -func
writeCellCentres` (granularfoam.foamio), so the OpenFOAM environment must be
sourced.
"""
import argparse
import json
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..foamio import profiles, read_field, times, volumes  # noqa: E402
from . import chute as fields  # noqa: E402

GRAINS = 0.5                # phi^g above this is "grains"
STOP = 1e-3                 # [m] a front that moves less has stopped


def parameters(case):
    """Numeric entries of case/system/columnParameters."""
    return fields.parameters(case, "columnParameters")


def front(case, time_name):
    """The front of the deposit on the floor [m]: where phi^g falls through
    1/2 along the floor's row of cells, from the left wall, linear between
    cell centres (the right wall when it does not; 0 when the first cell
    holds no grains)."""
    prof = profiles(case, time_name, function="profiles", set_name="floor")
    x, g = prof["z"], prof["alpha.grains"]
    below = np.nonzero(g <= GRAINS)[0]
    if not below.size:
        return float(x[-1] + 0.5 * (x[-1] - x[-2]))
    k = below[0]
    if k == 0:
        return 0.0
    s = (g[k - 1] - GRAINS) / (g[k - 1] - g[k])
    return float(x[k - 1] + s * (x[k] - x[k - 1]))


def wall_height(case, time_name):
    """Grain depth of the wall's column of cells [m]."""
    prof = profiles(case, time_name, function="profiles", set_name="wall")
    z, g = prof["z"], prof["alpha.grains"]
    return float(np.sum(g) * (z[1] - z[0]))


def fastest_grains(case, time_name):
    """Largest |U| over the cells with phi^g > 1/2 [m/s]."""
    g = read_field(case, time_name, "alpha.grains")
    U = read_field(case, time_name, "U")
    speed = np.linalg.norm(U[g > GRAINS], axis=1)
    assert speed.size, f"{case}/{time_name}: no cell with phi^g > 1/2"
    return float(speed.max())


def volume_change(case):
    """Largest relative change of the grain volume over the run."""
    _, v = volumes(case)
    vg = np.asarray(v["alpha.grains"])
    assert vg.size >= 2 and vg[0] > 0, f"{case}: no grain volume history"
    return float(np.max(np.abs(vg - vg[0])) / vg[0])


def deposit(case, time_name):
    """Cell-centre x [m] and the grain depth of every column of cells [m]."""
    x, z, f = fields.grid(case, time_name, "alpha.grains")
    return x, f["alpha.grains"].sum(axis=0) * (z[1] - z[0])


def stop_time(times_, fronts):
    """The first of times_ from which the front stays within STOP of its
    final position."""
    fronts = np.asarray(fronts)
    moving = np.nonzero(np.abs(fronts - fronts[-1]) >= STOP)[0]
    k = moving[-1] + 1 if moving.size else 0
    return float(times_[min(k, len(times_) - 1)])


def measure(case):
    """Every number above: time series by sampled time, and the end's."""
    names = times(case, "profiles")
    assert len(names) >= 2, f"{case}: fewer than two sampled times"
    end = names[-1]
    x, h = deposit(case, end)
    fronts = [front(case, t) for t in names]
    speeds = [fastest_grains(case, t) for t in names]
    return {
        "front_stop_time": stop_time([float(t) for t in names], fronts),
        "fastest_grains": speeds,
        "deposit_x": x.tolist(),
        "deposit_h": h.tolist(),
        "times": [float(t) for t in names],
        "front": fronts,
        "wall_height": [wall_height(case, t) for t in names],
        "fastest_grains_end": speeds[-1],
        "volume_change": volume_change(case),
        "end_time": float(end),
    }


def figure(numbers, out):
    """The front x_f(t), the height at the wall h_w(t) and the deposits of
    the runs in numbers ({label: measure(case)}): out/columnCollapse.png."""
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(13, 3.8))
    for label, n in numbers.items():
        ax1.plot(n["times"], n["front"], ".-", label=label)
        ax2.plot(n["times"], n["wall_height"], ".-", label=label)
        ax3.step(n["deposit_x"], n["deposit_h"], where="mid", label=label)
    ax1.set(xlabel="t [s]", ylabel="front on the floor $x_f$ [m]")
    ax2.set(xlabel="t [s]", ylabel="height at the wall [m]")
    ax3.set(xlabel="x [m]", ylabel="deposit: grain depth [m]")
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3)
    ax3.legend(fontsize=8)
    fig.tight_layout()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "columnCollapse.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cases", nargs="+", type=Path)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args()
    numbers = {str(c): measure(c) for c in args.cases}
    print(json.dumps({c: {k: v for k, v in n.items()
                          if not k.startswith("deposit")}
                      for c, n in numbers.items()}, indent=2))
    if args.out:
        print(figure(numbers, args.out))


if __name__ == "__main__":
    main()

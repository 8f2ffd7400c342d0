"""Measurements of the column collapse (tutorials/columnCollapse) from its
sampled floor row and wall column (system/controlDict, function
`profiles`), its grain volume (function `volumes`) and its written fields:

- front: where the deposit's grain depth falls below FRONT_DIAMETERS grain
  diameters, from the left wall [m] (a physical thickness, the same on
  every mesh fine enough to resolve it);
- beyond the front: the fraction of the grain volume that lies beyond it
  (a film ahead of the deposit);
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

from ..foamio import entries, profiles, read_field, times, volumes  # noqa: E402
from . import chute as fields  # noqa: E402

GRAINS = 0.5                # phi^g above this is "grains"
FRONT_DIAMETERS = 4         # the front: where the deposit is 4 d deep
STOP = 1e-3                 # [m] a front that moves less has stopped


def parameters(case):
    """Numeric entries of case/system/columnParameters."""
    return fields.parameters(case, "columnParameters")


def grain_diameter(case):
    """d of the one grain phase `grains` [m]."""
    return entries(Path(case), "constant/granularProperties",
                   ["grains.grains.d"])["grains.grains.d"]


def front(x, h, depth):
    """The deposit's front [m]: scanning the grain depth h of the columns
    of cells (centres x) from the left wall, where it first falls below
    depth, linear between cell centres (the right wall when it does not; 0
    when the first column holds less)."""
    below = np.nonzero(h < depth)[0]
    if not below.size:
        return float(x[-1] + 0.5 * (x[-1] - x[-2]))
    k = below[0]
    if k == 0:
        return 0.0
    s = (h[k - 1] - depth) / (h[k - 1] - h[k])
    return float(x[k - 1] + s * (x[k] - x[k - 1]))


def beyond(x, h, x_front):
    """The fraction of the grain volume of the columns beyond x_front."""
    dx = x[1] - x[0]
    # the column holding the front counts by the part of it beyond
    past = np.clip((x + 0.5 * dx - x_front) / dx, 0, 1)
    return float(np.sum(past * h) / np.sum(h))


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
    """Cell-centre x [m] and the grain depth of every column of cells [m],
    sum of phi^g dz."""
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
    """Every number above: time series by written time, and the end's."""
    names = times(case, "profiles")
    assert len(names) >= 2, f"{case}: fewer than two sampled times"
    end = names[-1]
    depth = FRONT_DIAMETERS * grain_diameter(case)
    fronts, film = [], []
    for t in names:
        x, h = deposit(case, t)
        fronts.append(front(x, h, depth))
        film.append(beyond(x, h, fronts[-1]))
    speeds = [fastest_grains(case, t) for t in names]
    return {
        "front_depth": depth,
        "front_stop_time": stop_time([float(t) for t in names], fronts),
        "fastest_grains": speeds,
        "deposit_x": x.tolist(),
        "deposit_h": h.tolist(),
        "times": [float(t) for t in names],
        "front": fronts,
        "front_peak": max(fronts),
        "beyond_front": film,
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
    ax1.set(xlabel="t [s]", ylabel="front $x_f$ (depth 4 d) [m]")
    ax2.set(xlabel="t [s]", ylabel="height at the wall [m]")
    ax3.set(xlabel="x [m]", ylabel="deposit: grain depth [m]")
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3)
    ax3.legend(fontsize=8)
    return _save(fig, out, "columnCollapse.png")


def _save(fig, out, name):
    """Write fig to out/name (out made where missing); its path."""
    fig.tight_layout()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / name
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def laws(numbers, heights, width, small_a, large_a):
    """The run-out and the final height against the aspect ratio a:
    numbers {a: measure(case)}, heights {a: H0}, the columns' width L0;
    least-squares exponents in log-log of (l_inf - L0)/L0 over small_a and
    over large_a, and of H0/h_inf over a >= 1 (a column of a < 1 keeps its
    top)."""
    a = np.array(sorted(numbers))
    runout = np.array([(numbers[k]["front"][-1] - width) / width for k in a])
    height = np.array([heights[k] / numbers[k]["wall_height"][-1] for k in a])

    def exponent(y, keep):
        keep = np.asarray(keep)
        return float(np.polyfit(np.log(a[keep]), np.log(y[keep]), 1)[0])

    return {
        "aspect_ratio": a.tolist(),
        "runout_over_L0": runout.tolist(),
        "H0_over_h_inf": height.tolist(),
        "runout_exponent_small_a": exponent(runout, np.isin(a, small_a)),
        "runout_exponent_large_a": exponent(runout, np.isin(a, large_a)),
        "runout_exponent": exponent(runout, a > 0),
        "height_exponent": exponent(height, a >= 1),
    }


def runout_figure(fits, out):
    """(l_inf - L0)/L0 and H0/h_inf against a (fits from laws) with the
    published laws: out/runout.png."""
    a = np.array(fits["aspect_ratio"])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    ax1.loglog(a, fits["runout_over_L0"], "o", label="this solver")
    small, large = np.linspace(0.4, 3, 20), np.linspace(2.5, 8, 20)
    # Lube et al. (2005); Lajeunesse et al. (2005) found the same regimes
    ax1.loglog(small, 1.2 * small, "k--", lw=1,
               label=r"$1.2a$, $1.9a^{2/3}$ (Lube et al. 2005)")
    ax1.loglog(large, 1.9 * large ** (2 / 3), "k--", lw=1)
    k = int(np.argmin(np.abs(a - 3.33)))
    ax1.loglog(large, fits["runout_over_L0"][k] * (large / a[k]) ** 0.9,
               "k:", lw=1, label=r"slope 0.9 (Balmforth & Kerswell 2005)")
    ax1.set(xlabel="a = H0/L0", ylabel=r"$(l_\infty - L_0)/L_0$")
    ax2.loglog(a, fits["H0_over_h_inf"], "o", label="this solver")
    ax2.loglog(large, fits["H0_over_h_inf"][k] * (large / a[k]) ** 0.6,
               "k:", lw=1, label="slope 0.6 (Balmforth & Kerswell 2005)")
    ax2.set(xlabel="a = H0/L0", ylabel=r"$H_0/h_\infty$")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    return _save(fig, out, "runout.png")


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

"""A movie of phi^s in the square drum (tutorials/squareDrum), as the
paper's movie 6: one frame per written time of a window, in the lab frame,
the air blank, written as an animated GIF by matplotlib's Pillow writer.

    /usr/bin/python3 -m granularfoam.post.drumMovie CASE [--start T0] [--end T1] \\
        [--fps 8] [--out CASE/figures/movie_phis.gif]

The window is the last revolution (10 s) by default.  The tutorial writes
every 0.625 s, 16 frames a revolution; for a smooth movie, rerun the last
revolution from its first written time with a shorter write interval (sed,
not foamDictionary, for controlDict: foamDictionary would write its
$macros out expanded):

    sed -i 's/^startFrom .*/startFrom startTime;/; s/^startTime .*/startTime 70;/' system/controlDict
    foamDictionary system/drumParameters -entry writeInterval -set 0.125

and run the solver as the run was run (`granularSegregationFoam`, or
`mpirun -np 2 granularSegregationFoam -parallel` then
`reconstructPar -newTimes`).
"""
import argparse
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.animation import PillowWriter  # noqa: E402

from ..foamio import time_names  # noqa: E402
from .drum import PERIOD, drum_axes, grid, small_fraction  # noqa: E402

DPI = 100


def frames(case, start=None, end=None):
    """The written times of case in [start, end] (the last revolution by
    default) that hold the phases."""
    names = time_names(case)
    assert names, f"{case}: no written time"
    last = float(names[-1])
    t0 = last - PERIOD if start is None else start
    t1 = last if end is None else end
    chosen = [n for n in names if t0 - 1e-9 <= float(n) <= t1 + 1e-9]
    assert chosen, f"{case}: no written time in [{t0:g}, {t1:g}]"
    return chosen


def movie(case, out, start=None, end=None, fps=8):
    """Write the GIF of phi^s over the window; return its times."""
    names = frames(case, start, end)
    # Every field read before the writer opens: an error in the loop of
    # its context would be hidden by the writer's own on closing
    shots = [grid(case, n, ["alpha.small", "alpha.large", "alpha.air"])
             for n in names]
    out.parent.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(4.6, 4))
    writer = PillowWriter(fps=fps)
    with writer.saving(fig, str(out), DPI):
        for k, (name, (X, Y, f)) in enumerate(zip(names, shots)):
            ax.clear()
            pc = ax.pcolormesh(X, Y, small_fraction(f), cmap="viridis",
                               vmin=0, vmax=1, shading="flat")
            drum_axes(ax, X, Y)
            ax.set_title(f"t = {float(name):.3f} s", fontsize=9)
            if k == 0:
                fig.colorbar(pc, ax=ax, label=r"$\varphi^s$")
            writer.grab_frame()
    plt.close(fig)
    return [float(n) for n in names]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", type=Path)
    parser.add_argument("--start", type=float, default=None,
                        help="first time [s] (default: the last written "
                             "time less one revolution)")
    parser.add_argument("--end", type=float, default=None,
                        help="last time [s] (default: the last written)")
    parser.add_argument("--fps", type=int, default=8)
    parser.add_argument("--out", type=Path, default=None)
    args = parser.parse_args(argv)
    if args.fps < 1:
        parser.error(f"--fps {args.fps}: at least 1 frame a second")
    out = args.out or args.case / "figures" / "movie_phis.gif"
    times = movie(args.case, out, args.start, args.end, args.fps)
    print(f"{out}: {len(times)} frames, t = {times[0]:g} to {times[-1]:g} s")


if __name__ == "__main__":
    main()

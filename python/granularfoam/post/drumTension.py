"""Tension in the grains of the square drum, step by step.

From a written time of a drum case, the case runs again over a window with
every step written, with the coupling settings given; every step's lowest
pressure in the grains (phi^a < 1/2), the grain cells whose rheology saw no
pressure (pGranular at its floor p_min) and the sign changes of that lowest
pressure from one step to the next (a pressure that flips every step is a
coupling that did not converge, not a physical tension).

    /usr/bin/python3 -m granularfoam.post.drumTension CASE --start 78.5542643977331778 \\
        --end 78.75 [--set PIMPLE.nCorrectors=30 ...] [--label NAME] [--out JSON]

--set edits system/fvSolution (ENTRY=VALUE).  The window runs in
CASE/../tension_<label> (removed first), its log in
log.granularSegregationFoam there.  From a start time as set up (0, with
no p written) the window begins at its first step.  With --out the numbers
are merged into that JSON file under "tension" -> label.
"""
import argparse
import json
import re
import shutil
import sys
from pathlib import Path

import numpy as np

from ..foamio import read_field, run, set_entry, time_names

GRAINS = 0.5
P_FLOOR = 1e-6          # pGranular at or below this: the rheology saw none


def step_table(case, names):
    """Per written time: (t, lowest p in the grains, grain cells with
    pGranular at its floor, largest I in the grains)."""
    rows = []
    for t in names:
        a = read_field(case, t, "alpha.air")
        g = a < GRAINS
        p = read_field(case, t, "p")
        pg = read_field(case, t, "pGranular")
        inertial = read_field(case, t, "I")
        rows.append((float(t), float(p[g].min()), int(np.sum(pg[g] <= P_FLOOR)),
                     float(inertial[g].max())))
    return rows


def window(case, start, end, settings, label):
    """Run case from time `start` to `end` writing every step; return the
    window's case directory."""
    case = Path(case)
    work = case.parent / f"tension_{label}"
    if work.exists():
        shutil.rmtree(work)
    work.mkdir()
    for part in ("constant", "system", start):
        shutil.copytree(case / part, work / part)
    for entry, value in (("startFrom", "latestTime"), ("endTime", end),
                         ("writeControl", "timeStep"), ("writeInterval", 1),
                         ("writeCompression", "off")):
        set_entry(work, "system/controlDict", entry, value)
    for entry, value in settings:
        set_entry(work, "system/fvSolution", entry, value)
    (work / "log.granularSegregationFoam").write_text(
        run(work, "granularSegregationFoam", timeout=3600))
    return work


def summary(rows, settings, first_is_step=False):
    """The window's numbers from step_table's rows; the first row is the
    written state it starts from, or with first_is_step its first step."""
    low = np.array([r[1] for r in rows])
    flips = int(np.sum(np.sign(low[1:]) != np.sign(low[:-1])))
    return {
        "settings": dict(settings),
        "window_s": [rows[0][0], rows[-1][0]],
        "steps": len(rows) - (0 if first_is_step else 1),
        "lowest_p_grains_Pa": float(low.min()),
        "steps_with_negative_p_grains": int(np.sum(low < 0)),
        "sign_changes_of_lowest_p": flips,
        "most_grain_cells_pGranular_at_floor": int(max(r[2] for r in rows)),
        "largest_I_grains": float(max(r[3] for r in rows)),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", type=Path)
    parser.add_argument("--start", required=True,
                        help="a written time of the case, as its name")
    parser.add_argument("--end", required=True, type=float)
    parser.add_argument("--set", nargs="*", default=[],
                        metavar="ENTRY=VALUE")
    parser.add_argument("--label", default="window")
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    settings = []
    for s in args.set:
        m = re.fullmatch(r"([\w.]+)=(.+)", s)
        if not m:
            parser.error(f"--set {s} is not ENTRY=VALUE")
        settings.append((m.group(1), m.group(2)))
    if not (args.case / args.start).is_dir():
        parser.error(f"no time {args.start} in {args.case}")
    work = window(args.case, args.start, args.end, settings, args.label)
    names = time_names(work)
    set_up = not any((work / names[0] / f).is_file() for f in ("p", "p.gz"))
    if set_up:
        names = names[1:]       # a start time as set up: no p written yet
    rows = step_table(work, names)
    out = summary(rows, settings, first_is_step=set_up)
    out["command"] = ("/usr/bin/python3 -m granularfoam.post.drumTension "
                      + " ".join(
        argv if argv is not None else sys.argv[1:]))
    print(json.dumps(out, indent=1))
    if args.out:
        data = json.loads(args.out.read_text()) if args.out.exists() else {}
        data.setdefault("tension", {})[args.label] = out
        args.out.write_text(json.dumps(data, indent=2) + "\n")


if __name__ == "__main__":
    main()

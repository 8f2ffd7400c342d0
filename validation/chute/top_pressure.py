"""Section 5.1's top pressure: the outflow of the chute (post.outflow, at
the last sampled time) of runs that differ only in the pressure p of the
open top (0/p_rgh, top), side by side, and the largest relative
difference of each number against the first run:

    /usr/bin/python3 validation/chute/top_pressure.py CASE [CASE ...] [--out FILE]

The paper (section 5.1) uses 1e-3 Pa and states that 1e-6 Pa gives the same
outflow.  FILE defaults to validation/chute/measured/top_pressure.json.
The cases are the chute tutorial with the top's p set (SETUP below).
"""
import argparse
import json
import re
from pathlib import Path

from granularfoam.foamio import read_text
from granularfoam.post.chute import outflow
from grain_size import PISO_SETTING


SETUP = ("for P in 1e-3 1e-6; do cp -r tutorials/chute p$P && "
         "(cd p$P && foamDictionary 0.orig/p_rgh -entry "
         "boundaryField.top.p -set \"uniform $P\" && ./Allrun -serial "
         + PISO_SETTING + "); done")


def top_pressure(case):
    """p of the top patch in case/0.orig/p_rgh."""
    m = re.search(r"\btop\s*\{[^}]*\bp\s+uniform\s+([-+0-9.eE]+)\s*;",
                  read_text(Path(case) / "0.orig" / "p_rgh"))
    assert m, f"no top pressure in {case}/0.orig/p_rgh"
    return float(m.group(1))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cases", nargs="+", type=Path)
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve()
                        .parent / "measured" / "top_pressure.json")
    args = parser.parse_args(argv)
    runs = {f"top p = {top_pressure(c):g} Pa": outflow(c)[0]
            for c in args.cases}
    first = next(iter(runs.values()))
    differences = {
        label: {k: abs(v - first[k]) / max(abs(first[k]), 1e-300)
                for k, v in numbers.items() if k not in ("end_time", "dz")}
        for label, numbers in list(runs.items())[1:]}
    result = {"runs": runs, "relative_difference_to_first": differences,
              "setup": SETUP,
              "command": "/usr/bin/python3 validation/chute/top_pressure.py "
                         + " ".join(c.name for c in args.cases)}
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()

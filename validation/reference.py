#!/usr/bin/python3
"""The tolerances and regression guards of the checked numbers
(validation/reference.json), read by the `check` fixture of conftest.py.

    /usr/bin/python3 validation/reference.py            # print the entries
    /usr/bin/python3 validation/reference.py --update   # guards from the
                                                        # last test runs

Each entry holds the paper's tolerance, the value measured by the last runs
(validation/results/status.json, written by every pytest session) and the
guard: about 3 x that value, rounded up to two digits, at least 1e-12 (the
round-off of the checks that compare two runs), at most the tolerance.  A
tenfold regression then fails even where the tolerance would let it pass.
--update sets measured and guard of every check in status.json whose test
passed, and keeps the tolerances; a check that is not in the file yet needs
its tolerance written there first.
"""
import argparse
import json
import math
import sys
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
REFERENCE = PROJECT / "validation" / "reference.json"
STATUS = PROJECT / "validation" / "results" / "status.json"
FLOOR = 1e-12


def guard(measured, tolerance):
    """3 x measured rounded up to two significant digits, in
    [FLOOR, tolerance]."""
    g = 3.0 * abs(measured)
    if g > 0:
        e = math.floor(math.log10(g)) - 1
        g = math.ceil(g / 10.0**e) * 10.0**e
    return min(tolerance, max(g, FLOOR))


def update(reference, status):
    """Measured values and guards of reference's checks from status; the
    labels of status that reference lacks."""
    missing = []
    for entry in status.values():
        if entry.get("outcome") != "passed":
            continue
        for c in entry.get("checks", []):
            ref = reference["checks"].get(c["label"])
            if ref is None:
                missing.append(c["label"])
                continue
            ref["measured"] = c["measured"]
            ref["guard"] = guard(c["measured"], ref["tolerance"])
    return missing


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--update", action="store_true",
                        help="set the guards from " + str(STATUS))
    args = parser.parse_args()
    reference = json.loads(REFERENCE.read_text())
    if args.update:
        if not STATUS.is_file():
            sys.exit(f"{STATUS} missing: run the tests first (./Alltest)")
        missing = update(reference, json.loads(STATUS.read_text()))
        if missing:
            sys.exit("no tolerance in " + str(REFERENCE) + " for: "
                     + "; ".join(sorted(set(missing))))
        REFERENCE.write_text(json.dumps(reference, indent=1, sort_keys=True,
                                        ensure_ascii=False) + "\n")
    for label, ref in sorted(reference["checks"].items()):
        print(f"{label}: measured {ref['measured']:.3g}, guard "
              f"{ref['guard']:.3g}, tolerance {ref['tolerance']:.3g}")


if __name__ == "__main__":
    main()

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
An entry with "bound": "lower" holds a number that must stay above its
tolerance (a slowdown, a step ratio): its guard is about a third of the
measured value, rounded down to two digits, at least the tolerance.
--update sets measured and guard of every check in status.json whose test
passed, and keeps the tolerances; a check that is not in the file yet needs
its tolerance written there first (with measured and guard null).
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


def _two_digits(x, rounding):
    """x > 0 rounded to two significant digits by rounding (ceil, floor)."""
    e = math.floor(math.log10(x)) - 1
    return rounding(round(x / 10.0**e, 9)) * 10.0**e


def guard(measured, tolerance, lower=False):
    """An upper bound: 3 x measured rounded up to two significant digits, in
    [FLOOR, tolerance].  A lower bound (lower): measured / 3 rounded down to
    two significant digits, at least tolerance."""
    if lower:
        g = abs(measured) / 3.0
        return max(tolerance, _two_digits(g, math.floor) if g > 0 else 0.0)
    g = 3.0 * abs(measured)
    if g > 0:
        g = _two_digits(g, math.ceil)
    return min(tolerance, max(g, FLOOR))


def is_lower(ref):
    """Whether a reference entry is a lower bound."""
    return ref.get("bound", "upper") == "lower"


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
            ref["guard"] = guard(c["measured"], ref["tolerance"],
                                 is_lower(ref))
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
        side = ">" if is_lower(ref) else "<"
        print(f"{label}: measured {ref['measured']}, guard {side} "
              f"{ref['guard']}, tolerance {side} {ref['tolerance']}")


if __name__ == "__main__":
    main()

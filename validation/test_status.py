"""Unit tier: the validation status table (validation/status.py) shows each
test file's counts and every checked number, failures included."""
import pytest

import status

pytestmark = pytest.mark.unit


def entry(outcome, checks=(), commit="abc", seconds=2.0):
    return {"outcome": outcome, "seconds": seconds, "checks": list(checks),
            "commit": commit, "date": "2026-11-22 10:00 UTC"}


def test_table_counts_and_checks():
    ok = {"label": "u vs Bagnold, L2", "measured": 0.00096,
          "tolerance": 0.01, "guard": 0.003, "paper": "(5.4)",
          "percent": True, "passed": True}
    bad = {"label": "max |drift|", "measured": 2e-12, "tolerance": 1e-11,
           "guard": 1e-12, "paper": None, "percent": False, "passed": False}
    text = status.table({
        "a/test_x.py::test_one": entry("passed", [ok]),
        "a/test_x.py::test_two": entry("failed", [bad], commit="def"),
        "test_y.py::test_three": entry("passed", seconds=3.0),
    })
    assert "| `a/test_x.py` | 1 | 1 | 4 |" in text
    assert "| `test_y.py` | 1 | 0 | 3 |" in text
    assert "| all | 2 | 1 | 7 |" in text
    assert "| u vs Bagnold, L2 | 0.096 % | < 0.3 % | < 1 % | (5.4) | pass |" \
        in text
    assert "| max \\|drift\\| | 2e-12 | < 1e-12 | < 1e-11 |  | FAIL |" in text
    assert "`abc`, `def`" in text

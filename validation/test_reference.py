"""Unit tier: the tolerances and regression guards of the checked numbers
(validation/reference.json, validation/reference.py)."""
import json

import pytest

import reference

pytestmark = pytest.mark.unit


def test_guard_rule():
    """About 3 x the measured value, rounded up to two digits, at least
    1e-12, at most the tolerance."""
    assert reference.guard(0.0016, 0.01) == pytest.approx(0.0048)
    assert reference.guard(0.00162, 0.01) == pytest.approx(0.0049)
    assert reference.guard(1e-16, 1e-9) == 1e-12
    assert reference.guard(0.5, 0.01) == 0.01
    assert reference.guard(0.0, 0.01) == 1e-12


def test_lower_guard_rule():
    """A lower bound: about a third of the measured value, rounded down to
    two digits, at least the tolerance."""
    assert reference.guard(0.30, 0.05, lower=True) == pytest.approx(0.1)
    assert reference.guard(0.317, 0.05, lower=True) == pytest.approx(0.1)
    assert reference.guard(0.35, 0.05, lower=True) == pytest.approx(0.11)
    assert reference.guard(0.1, 0.05, lower=True) == 0.05
    assert reference.guard(0.0, 0.05, lower=True) == 0.05


def test_every_entry_guards_below_its_tolerance():
    """Each entry: 0 < guard <= tolerance, the measured value below the
    guard (for a lower bound: tolerance <= guard < measured), and the guard
    of the rule."""
    entries = json.loads(reference.REFERENCE.read_text())["checks"]
    assert len(entries) >= 25, len(entries)
    for label, ref in entries.items():
        lower = reference.is_lower(ref)
        if lower:
            assert ref["guard"] >= ref["tolerance"], (label, ref)
            assert ref["measured"] > ref["guard"], (label, ref)
        else:
            assert 0 < ref["guard"] <= ref["tolerance"], (label, ref)
            assert ref["measured"] < ref["guard"], (label, ref)
        assert ref["guard"] == reference.guard(
            ref["measured"], ref["tolerance"], lower), (label, ref)


def test_update_sets_measured_and_guard():
    """--update takes the passed tests' checks of a status file."""
    ref = {"checks": {"u, L2": {"tolerance": 0.01, "measured": 0.002,
                                "guard": 0.006}}}
    status = {"t::a": {"outcome": "passed", "checks": [
                  {"label": "u, L2", "measured": 0.001}]},
              "t::b": {"outcome": "failed", "checks": [
                  {"label": "u, L2", "measured": 0.5}]},
              "t::c": {"outcome": "passed", "checks": [
                  {"label": "new", "measured": 0.1}]}}
    assert reference.update(ref, status) == ["new"]
    assert ref["checks"]["u, L2"] == {"tolerance": 0.01, "measured": 0.001,
                                      "guard": 0.003}

"""Unit tier: the C++ unit tests of libgranularRheology and the
well-posedness utility on the paper's table 1."""
import re

import pytest

from conftest import executable, run

pytestmark = pytest.mark.unit


def test_granular_rheology_unit_tests(foam_env, tmp_path):
    """Every law of every selection table, the rheology chain, bad input."""
    proc = run([executable("Test-granularRheology")], cwd=tmp_path)
    out = proc.stdout + proc.stderr
    failed = [line for line in out.splitlines() if line.startswith("FAIL")]
    assert not failed, "\n".join(failed)
    summary = re.search(r"^(\d+) passed, (\d+) failed$", out, re.M)
    assert summary, f"no summary line in the output:\n{out[-2000:]}"
    passed, nfail = int(summary.group(1)), int(summary.group(2))
    assert nfail == 0 and proc.returncode == 0, out[-2000:]
    # The suite holds 101 checks: fewer means a check was lost
    assert passed >= 101, f"only {passed} checks ran"


def parse_ranges(log):
    """{phase: [(lo, hi), ...]} from the granularWellPosedness log."""
    ranges, phase = {}, None
    for line in log.splitlines():
        m = re.match(r"grain phase (\S+): frictionLaw (\S+)", line)
        if m:
            phase = m.group(1)
            ranges[phase] = []
            continue
        m = re.match(r"    well posed for I in \[(\S+), (\S+)\]", line)
        if m and phase:
            ranges[phase].append((float(m.group(1)), float(m.group(2))))
    return ranges


def test_well_posedness_utility_table1(foam_env, case_copy):
    """Table 1: Jop well posed on [0.00397, 0.28016], Barker-Gray on
    [0, 16.9918] (ERRATA item 1)."""
    case = case_copy("wellPosedness")
    proc = run(["./Allrun"], cwd=case)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    log_file = case / "log.granularWellPosedness"
    assert log_file.is_file(), "the utility wrote no log"
    log = log_file.read_text()
    assert "\nEnd" in log and "FOAM FATAL" not in log, log[-2000:]

    r = parse_ranges(log)
    assert set(r) == {"BarkerGray", "Jop"}, r
    (lo, hi), = r["Jop"]
    assert lo == pytest.approx(0.003972, rel=1e-4)
    assert hi == pytest.approx(0.280166, rel=1e-5)
    (lo, hi), = r["BarkerGray"]
    assert lo == 0.0
    assert hi == pytest.approx(16.9918, rel=5e-5)

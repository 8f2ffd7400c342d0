"""Unit tier: the C++ unit tests of libgranularRheology and of the parts of
libgranularMixture, and the well-posedness utility on the paper's table 1."""
import re
import shutil
import tempfile

import numpy as np
import pytest

from conftest import executable, run
from chute.figure1 import parse_ranges, run_utility

pytestmark = pytest.mark.unit


def _unit_run():
    """Run Test-granularRheology once: (its output, exit status), or (the
    reason it could not run, None)."""
    path = shutil.which("Test-granularRheology")
    if not path:
        return "Test-granularRheology not found on PATH: was ./Allwmake run?", \
            None
    with tempfile.TemporaryDirectory() as tmp:
        proc = run([path], cwd=tmp)
    return proc.stdout + proc.stderr, proc.returncode


UNIT_OUT, UNIT_RC = _unit_run()

# Each check the suite printed, in order: (description, passed)
UNIT_ITEMS = [(m.group(2), m.group(1) == "PASS") for m in
              re.finditer(r"^(PASS|FAIL) (.*)$", UNIT_OUT, re.M)]


def _item_id(item):
    return item[0]


@pytest.mark.parametrize("item", UNIT_ITEMS or [("no check ran", False)],
                         ids=_item_id)
def test_granular_rheology_unit_check(foam_env, item):
    """One check of the C++ unit tests of libgranularRheology (every law of
    every selection table, the rheology chain, bad input), as the suite
    printed it."""
    description, passed = item
    assert UNIT_ITEMS, f"Test-granularRheology printed no check:\n{UNIT_OUT[-2000:]}"
    assert passed, f"FAIL {description}"


def test_granular_rheology_unit_suite(foam_env):
    """The suite ran to its summary and exit status 0, with its 101
    checks: fewer means a check was lost."""
    summary = re.search(r"^(\d+) passed, (\d+) failed$", UNIT_OUT, re.M)
    assert summary, f"no summary line in the output:\n{UNIT_OUT[-2000:]}"
    passed, failed = int(summary.group(1)), int(summary.group(2))
    assert (passed, failed) == (sum(p for _, p in UNIT_ITEMS),
                                sum(not p for _, p in UNIT_ITEMS)), summary
    assert failed == 0 and UNIT_RC == 0, UNIT_OUT[-2000:]
    assert passed >= 101, f"only {passed} checks ran"


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


def test_granular_mixture_parts(foam_env, case_copy):
    """Test-granularMixture: the parts of libgranularMixture on the
    segregation column (gravity split, phases, the pairwise fluxes' (2.12)
    and (2.17), one transport step's volumes and bounds, the time-step
    parts, the air's pressure level), 15 checks, each printed PASS or
    FAIL."""
    case = case_copy("segregationColumn")
    shutil.copytree(case / "0.orig", case / "0")
    for cmd in (["blockMesh"], ["setGranularFields"]):
        proc = run(cmd, cwd=case)
        assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr
    path = shutil.which("Test-granularMixture")
    assert path, "Test-granularMixture not found on PATH: was ./Allwmake run?"
    proc = run([path], cwd=case)
    out = proc.stdout + proc.stderr
    items = re.findall(r"^(PASS|FAIL) (.*)$", out, re.M)
    failed = [d for s, d in items if s == "FAIL"]
    assert not failed, "\n".join(failed)
    summary = re.search(r"^(\d+) passed, (\d+) failed$", out, re.M)
    assert summary, f"no summary line in the output:\n{out[-2000:]}"
    assert (int(summary.group(1)), int(summary.group(2))) == (len(items), 0)
    assert len(items) >= 15 and proc.returncode == 0, out[-2000:]


def test_well_posedness_table(foam_env, case_copy):
    """granularWellPosedness -table (figure 1): the indicator it writes
    agrees with the ranges it prints, to one point of the log-spaced table,
    and mu of the Barker-Gray law vanishes towards I = 0 (the creep branch)
    while Jop's tends to mu_s."""
    case = case_copy("wellPosedness")
    log, cols = run_utility(case)
    I = cols["I"]
    step = I[1] / I[0]
    for phase in ("Jop", "BarkerGray"):
        ranges = parse_ranges(log)[phase]
        well = cols[f"wellPosed.{phase}"] > 0.5
        inside = np.zeros_like(well)
        for lo, hi in ranges:
            inside |= (I >= lo * step) & (I <= hi / step)
        near = np.zeros_like(well)
        for lo, hi in ranges:
            near |= (I >= lo / step) & (I <= hi * step)
        assert np.all(well[inside]), phase
        assert not np.any(well & ~near), phase
    assert cols["mu.BarkerGray"][0] < 0.3 < cols["mu.Jop"][0]
    assert cols["mu.Jop"][0] == pytest.approx(0.342, rel=1e-4)

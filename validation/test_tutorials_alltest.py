"""Smoke tier: tutorials/Alltest runs every tutorial's Allrun -test (a few
steps, as ESI's foamRunTutorials -test), each to its test endTime."""
import re

import pytest

from conftest import committed_copy, run

pytestmark = pytest.mark.smoke

# The endTime of each tutorial's -test (testOption in its Allrun)
TEST_END = {"bulbousHead": 0.005, "chute": 0.005, "columnCollapse": 0.01,
            "segregationColumn": 0.05, "squareDrum": 0.02,
            "tridisperseColumn": 0.05}


def test_tutorials_alltest(foam_env, tmp_path):
    """Every tutorial with an Allrun runs -test: the solver reaches the test
    endTime in a few steps, without figures; the others run as they are."""
    tutorials = committed_copy("tutorials", tmp_path / "tutorials")
    out = tmp_path / "runs"
    proc = run([str(tutorials / "Alltest"), str(out)], cwd=tutorials)
    report = proc.stdout + proc.stderr
    assert proc.returncode == 0, report
    names = sorted(p.parent.name for p in tutorials.glob("*/Allrun"))
    assert re.findall(r"^(\S+): ran \(-test\)$", report, re.M) == names, \
        report
    for name, end in TEST_END.items():
        case = out / name
        log = (case / "log.granularSegregationFoam").read_text()
        assert re.search(r"^End\s*$", log, re.M), log[-2000:]
        times = sorted(float(p.name) for p in case.iterdir()
                       if re.fullmatch(r"[0-9.eE+-]+", p.name))
        assert times[-1] == pytest.approx(end, rel=1e-9), (name, times)
        steps = len(re.findall(r"^Time = ", log, re.M))
        assert 0 < steps <= 100, (name, steps)
        assert not (case / "figures").exists(), f"{name}: figures in -test"

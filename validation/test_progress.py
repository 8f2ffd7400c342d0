"""Smoke tier: the solver's progress report.  At the start and at every write
the log shows the volume of every phase and the segregation index, and an
estimate of the time to finish; the numbers must be those of the fields it
writes (recomputed here from the written fields and cell volumes)."""
import re

import numpy as np
import pytest

from cases import foam, fresh_case, log_reports
from granularfoam.foamio import read_field

pytestmark = pytest.mark.smoke

PHASES = ("alpha.air", "alpha.small", "alpha.large")


def segregation_index(alphas, V):
    """Danckwerts' intensity of segregation of the grain phases, weighted by
    the grain volume, from the fractions clipped at zero
    (granularPhases::segregationIndex)."""
    clipped = [np.maximum(a, 0) for a in alphas[1:]]
    grains = sum(clipped)
    w = V * grains
    c = [np.where(grains > 1e-150, a / np.maximum(grains, 1e-150),
                  1 / len(clipped)) for a in clipped]
    mean = [np.sum(w * ci) / w.sum() for ci in c]
    var = sum(np.sum(w * (ci - m) ** 2) / w.sum() for ci, m in zip(c, mean))
    return np.sqrt(var / sum(m * (1 - m) for m in mean))


def test_progress_report(foam_env):
    case = fresh_case("segregationColumn", "progress", tutorial=True)
    foam(case, "./Allrun", "-endTime", "4", "-writeInterval", "2")
    log = (case / "log.granularSegregationFoam").read_text()

    found = log_reports(log)
    assert sorted(found, key=float) == ["0", "2", "4"], (
        f"reports at times {list(found)}, expected the start and two writes")

    foam(case, "postProcess", "-func", "writeCellVolumes", "-time", "0:")
    indices = {}
    for time_name, (vols, index) in found.items():
        V = read_field(case, time_name, "V")
        alphas = [read_field(case, time_name, name) for name in PHASES]
        assert set(vols) == set(PHASES), f"t = {time_name}: phases {vols}"
        for name, alpha in zip(PHASES, alphas):
            expected = np.sum(V * alpha)
            assert abs(vols[name] - expected) <= 1e-9 * expected, (
                f"t = {time_name}: {name} volume {vols[name]} logged, "
                f"{expected} in the fields")
        assert index is not None, f"t = {time_name}: no segregation index"
        expected = segregation_index(alphas, V)
        # the fields are written to 10 significant digits
        assert abs(index - expected) < 1e-7, (
            f"t = {time_name}: segregation index {index} logged, "
            f"{expected} from the fields")
        indices[float(time_name)] = index

    # A uniform mix at the start, segregating in time
    assert indices[0] < 1e-9, f"initial segregation index {indices[0]}"
    assert 0 < indices[2] < indices[4] < 1, f"segregation index {indices}"

    eta = re.findall(r"^Progress: t = (\S+) of (\S+) s \((\d+) %\), "
                     r"estimated time to finish (\d+) h (\d+) min (\d+) s$",
                     log, re.M)
    # at every write (and once a minute of wall clock, not reached here)
    shown = {(t, p) for t, _, p, *_ in eta}
    assert {("2", "50"), ("4", "100")} <= shown, f"progress lines {eta}"
    assert eta[-1][:3] == ("4", "4", "100"), f"last progress line {eta[-1]}"
    assert eta[-1][3:] == ("0", "0", "0"), f"time left at the end {eta[-1]}"

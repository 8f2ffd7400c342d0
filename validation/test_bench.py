"""Unit tier: the benchmark's configurations (bench/generate.py) follow
the tutorials they stand for, and its report (bench/report.py) shows every
configuration it is given."""
import sys
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "bench"))
import generate  # noqa: E402  (bench/ is not a package)
import report  # noqa: E402

pytestmark = pytest.mark.unit


def test_krylov_configuration_is_the_chute_tutorials_coupling(tmp_path):
    """The Krylov configuration of a generated chute case reads, entry by
    entry, as the chute tutorial's fvSolution; its adjusted time step takes
    the tutorial's maxCo and maxDeltaT; the explicit one keeps the common
    fvSolution's PISO."""
    tutorial = PROJECT / "tutorials" / "chute" / "system"
    case = tmp_path / "krylov"
    params = generate.prepare(case, "chute", "granular-krylov", 20, 4, 0,
                              [1], interval=0.01)
    for entry in generate.KRYLOV:
        assert " ".join(generate.foam_value(
            case / "system" / "fvSolution", entry).split()) == " ".join(
            generate.foam_value(tutorial / "fvSolution", entry).split())
    assert generate.foam_value(case / "system" / "fvSolution",
                               "PIMPLE/pressureCoupling") == "Krylov"
    assert params["maxCo"] == generate.foam_scalar(
        tutorial / "controlDict", "maxCo")
    assert params["maxDeltaT"] == generate.foam_scalar(
        tutorial / "chuteParameters", "maxDeltaT")
    explicit = tmp_path / "explicit"
    params = generate.prepare(explicit, "chute", "granular", 20, 4, 0, [1],
                              interval=0.01)
    assert params["maxCo"] == generate.ADJUSTABLE_STEP["maxCo"]
    assert generate.foam_value(explicit / "system" / "fvSolution",
                               "PIMPLE/momentumPredictor") == "no"


def test_report_gives_every_configuration_its_speed_up():
    """The time-per-simulated-second table gives each row its own speed-up
    over the explicit run; a results file of the implicit alone still
    renders."""
    rows = [{"case": "chute", "solver": s, "mesh": "155x16", "cells": 2480,
             "ranks": 1, "interval_s": 0.2, "steps": n,
             "deltaT_median_s": 0.2 / n, "viscous_cfl_median": 1.0,
             "wall_per_simulated_s": w, "cpu_per_simulated_s": w,
             "application": "granularSegregationFoam"}
            for s, n, w in (("granular", 3000, 120.0),
                            ("granular-implicit", 80, 30.0),
                            ("granular-krylov", 40, 10.0))]
    speedup = {r["solver"]: {"wall": 120.0 / r["wall_per_simulated_s"],
                             "cpu": 120.0 / r["cpu_per_simulated_s"]}
               for r in rows[1:]}
    lines = report.adaptive_table({"summary": rows, "speedup": speedup})
    assert lines[-2].endswith("| 4.0, 4.0 |")
    assert lines[-1].endswith("| 12.0, 12.0 |")
    assert "(Krylov, the chute's)" in lines[-1]
    old = report.adaptive_table({"summary": rows[:2],
                                 "speedup": speedup["granular-implicit"]})
    assert old[-1].endswith("| 4.0, 4.0 |")

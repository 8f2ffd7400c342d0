"""Unit tier: the coupling harness's states taken from a written time of a
run (bench/harness states --states RUN@TIME)."""
import argparse
import sys
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "bench"))
import harness  # noqa: E402  (bench/ is not a package)

pytestmark = pytest.mark.unit


def test_a_run_state_is_named_run_at_time():
    assert harness.run_state("/runs/N150K@9.375") == (Path("/runs/N150K"),
                                                      "9.375")
    assert harness.run_state("drum100") is None
    assert harness.state_name("/runs/N150K@9.375") == "/runs/N150K@9.375"
    assert harness.state_name("drum100") == "drum100"
    with pytest.raises(argparse.ArgumentTypeError, match="RUN@TIME"):
        harness.state_name("drum1000")


def test_a_run_state_and_its_runs_stay_in_the_harness_directory():
    name = "/runs/N150K@9.375"
    assert harness.state_dir(name) == harness.WORK / "states" / "N150K_t9.375"
    edits = ["system/fvSolution:maxAlphaSubCycles=5"]
    assert harness.state_dir(name, edits).parent == harness.WORK / "states"
    run = harness.run_name(name, 0.0035, 10, "Krylov-BFBt-20", edits)
    assert "/" not in run and run.startswith("N150K_t9.375_dt0.0035_n10_")


def _run(tmp_path, drum=True, fields=True):
    run = tmp_path / "N150K"
    (run / "constant" / "polyMesh").mkdir(parents=True)
    (run / "constant" / "polyMesh" / "points").write_text("points")
    (run / "system").mkdir()
    (run / "system" / "controlDict").write_text("controlDict")
    if drum:
        (run / "system" / "drumParameters").write_text("N 150;")
    (run / "9.375").mkdir()
    if fields:
        (run / "9.375" / "U.gz").write_bytes(b"U")
        (run / "9.375" / "p_rgh.gz").write_bytes(b"p_rgh")
    return run


def test_copy_run_state_takes_the_written_time_with_system_and_constant(
        tmp_path, monkeypatch):
    monkeypatch.setattr(harness, "WORK", tmp_path / "work")
    run = _run(tmp_path)
    name = f"{run}@9.375"
    case = harness.state_dir(name)
    case.mkdir(parents=True)
    assert harness.copy_run_state(name, case) == "9.375"
    assert (case / "9.375" / "U.gz").read_bytes() == b"U"
    assert (case / "9.375" / "p_rgh.gz").read_bytes() == b"p_rgh"
    assert (case / "constant" / "polyMesh" / "points").read_text() == "points"
    assert (case / "system" / "controlDict").read_text() == "controlDict"
    # a drum has no base: no base row, outlet or normal velocity
    assert harness.normal_of(name) is None


def test_a_chute_run_state_has_its_base_normal_to_z(tmp_path, monkeypatch):
    monkeypatch.setattr(harness, "WORK", tmp_path / "work")
    run = _run(tmp_path, drum=False)
    name = f"{run}@9.375"
    case = harness.state_dir(name)
    case.mkdir(parents=True)
    harness.copy_run_state(name, case)
    assert harness.normal_of(name) == 2


def test_a_time_without_reconstructed_fields_is_refused(tmp_path,
                                                         monkeypatch):
    monkeypatch.setattr(harness, "WORK", tmp_path / "work")
    run = _run(tmp_path, fields=False)
    name = f"{run}@9.375"
    case = harness.state_dir(name)
    case.mkdir(parents=True)
    with pytest.raises(ValueError, match="reconstructPar -time 9.375"):
        harness.copy_run_state(name, case)

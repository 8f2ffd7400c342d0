"""Unit tier: the benchmark's configurations (bench/generate.py) follow
the tutorials they stand for, and its report (bench/report.py) shows every
configuration it is given."""
import sys
from pathlib import Path

import pytest

from granularfoam.foamio import edit

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


def _whole(tutorial_status="ok"):
    run = {"steps": 25000, "cpu_seconds": 850.0, "cpu_per_simulated_s": 34.0,
           "ms_per_step": 34.0, "pressure_solutions_per_step": 20.0,
           "status": "ok", "outlet_l2_u_bagnold": 0.00164,
           "outlet_l2_phis_gray_chugunov": 0.00559,
           "outlet_depth_averaged_phis": 0.6741,
           "outlet_change_last_interval_u": 4.8e-4,
           "outlet_change_last_interval_phis": 1e-3}
    tutorial = dict(run, steps=1900, cpu_seconds=170.0,
                    cpu_per_simulated_s=6.8, ms_per_step=89.5,
                    pressure_solutions_per_step=9.0,
                    outlet_depth_averaged_phis=0.6740,
                    status=tutorial_status)
    return {"command": "bench/run", "whole": {
        "case": "chute", "mesh": "155x40", "ranks": 1, "end_time": 25,
        "side_by_side": True,
        "settings": {"reference": {"coupling": "PISO-20", "sub_cycles": 0,
                                   "max_delta_t": 1e-3},
                     "tutorial": {"coupling": "tutorial",
                                  "sub_cycles": None, "max_delta_t": None}},
        "runs": {"reference": run, "tutorial": tutorial},
        "speedup": 850.0 / 170.0}}


def test_report_shows_both_whole_runs_and_the_speed_up():
    """The whole-run section has the reference's and the tutorial's rows,
    each with its own cost and outflow, and the speed-up; a run that did
    not end well shows its status and no outflow; no whole runs, no
    section."""
    lines = report.whole_section(_whole())
    rows = [x for x in lines if x.startswith("| reference")
            or x.startswith("| tutorial")]
    assert len(rows) == 2
    assert "| 25000 | 850 | 34 | 34 | 20.0 | 0.164% | 0.559% | 0.6741 |" \
        in rows[0]
    assert "| 1900 | 170 | 6.8 | 89.5 | 9.0 | 0.164% | 0.559% | 0.6740 |" \
        in rows[1]
    assert lines[-1] == ("Speed-up of the tutorial over the reference "
                         "(CPU): **5.00**.")
    failed = report.whole_section(_whole("failed (exit 1) at t = 3 s"))
    row = next(x for x in failed if x.startswith("| tutorial"))
    assert row.endswith("|  |  |  |  |  | failed (exit 1) at t = 3 s |")
    assert report.whole_section({"whole": None}) == []


def test_whole_runs_are_the_reference_and_the_tutorial_unchanged():
    """bench/run's whole runs: the reference is 20 PISO correctors with the
    transport in the momentum step at 1e-3 s; the tutorial's run changes
    nothing of the tutorial's fvSolution."""
    import bench
    import harness
    assert bench.WHOLE["reference"] == {"coupling": "PISO-20",
                                        "sub_cycles": 0,
                                        "max_delta_t": 1e-3}
    tutorial = bench.WHOLE["tutorial"]
    assert harness.coupling_settings(tutorial["coupling"]) == {}
    assert tutorial["sub_cycles"] is None
    assert tutorial["max_delta_t"] is None
    assert harness.coupling_settings("PISO-20") == {
        "PIMPLE.pressureCoupling": "PISO", "PIMPLE.nCorrectors": 20,
        "PIMPLE.nRheologyCorrectors": 0, "PIMPLE.KrylovFinal": None}


def _fv_solution_case(tmp_path, tutorial):
    """A case in tmp_path with the tutorial's system/fvSolution alone:
    (the case, its fvSolution)."""
    case = tmp_path / "case"
    (case / "system").mkdir(parents=True)
    fvSolution = case / "system" / "fvSolution"
    fvSolution.write_text((PROJECT / "tutorials" / tutorial / "system"
                           / "fvSolution").read_text())
    return case, fvSolution


def test_a_named_coupling_is_the_whole_steps_coupling(tmp_path):
    """A coupling the harness names replaces the case's: on the drum
    tutorial's fvSolution with a rheology corrector and KrylovFinal, which
    would otherwise change the step, the reference's Krylov coupling
    leaves no rheology corrector and no KrylovFinal; tutorial changes
    nothing."""
    import harness
    case, fvSolution = _fv_solution_case(tmp_path, "squareDrum")
    edit(fvSolution, [(r"(\n[ \t]*viscousStress\s+\w+;)",
                       r"\n    nRheologyCorrectors 1;"
                       r"\n    KrylovFinal { $Krylov; maxIter 2; }\1")])
    text = fvSolution.read_text()
    assert generate.foam_value(fvSolution, "PIMPLE/nRheologyCorrectors") \
        == "1"
    assert "KrylovFinal" in text
    harness.set_coupling(case, harness.TUTORIAL_NAME)
    assert fvSolution.read_text() == text
    harness.set_coupling(case, harness.DRUM_REFERENCE[0])
    assert generate.foam_value(fvSolution, "PIMPLE/nRheologyCorrectors") \
        == "0"
    assert generate.foam_value(fvSolution, "PIMPLE/Krylov/maxIter") == "30"
    assert generate.foam_value(fvSolution, "PIMPLE/Krylov/tolerance") \
        == "0.001"
    assert "KrylovFinal" not in fvSolution.read_text()


def test_whole_run_status_keeps_to_one_table_row():
    """A status of several lines (an assertion's message) renders within
    its row."""
    results = _whole("ran; no outflow to measure: no phi^s = 1/2: [-- --\n"
                     " -- --] | " + "x" * 200)
    lines = report.whole_section(results)
    row = next(x for x in lines if x.startswith("| tutorial"))
    assert "\n" not in row and row.endswith("... |")
    assert row.count("|") == 13


def test_harness_edits_reach_the_phases_solver_entry(tmp_path):
    """--edit system/fvSolution:nLimiterIter=N, maxAlphaSubCycles=M,
    nAlphaSubCycles=N and transportFlux=W change the phases' solver entry
    ("alpha.*"), which foamDictionary cannot scope; a count below 1 is
    refused."""
    import harness
    case, fvSolution = _fv_solution_case(tmp_path, "chute")
    harness.apply_edits(case, ["system/fvSolution:nLimiterIter=2",
                               "system/fvSolution:maxAlphaSubCycles=7"])
    assert generate.foam_value(fvSolution,
                               'solvers/"alpha.*"/nLimiterIter') == "2"
    assert generate.foam_value(fvSolution,
                               'solvers/"alpha.*"/maxAlphaSubCycles') == "7"
    harness.apply_edits(case, ["system/fvSolution:maxAlphaSubCycles=0"])
    assert generate.foam_value(fvSolution,
                               'solvers/"alpha.*"/nAlphaSubCycles') == "1"
    harness.apply_edits(case, ["system/fvSolution:nAlphaSubCycles=4"])
    assert generate.foam_value(fvSolution,
                               'solvers/"alpha.*"/nAlphaSubCycles') == "4"
    for flux in ("midStep", "startOfStep"):
        harness.apply_edits(case, [f"system/fvSolution:transportFlux={flux}"])
        assert generate.foam_value(
            fvSolution, 'solvers/"alpha.*"/transportFlux') == flux
        assert generate.foam_value(
            fvSolution, 'solvers/"alpha.*"/nAlphaSubCycles') == "4"
    with pytest.raises(ValueError, match="nLimiterIter=0"):
        harness.apply_edits(case, ["system/fvSolution:nLimiterIter=0"])
    with pytest.raises(ValueError, match="nAlphaSubCycles=0"):
        harness.apply_edits(case, ["system/fvSolution:nAlphaSubCycles=0"])


def test_harness_edits_replace_a_regex_keyed_solver_entry(tmp_path):
    """--edit system/fvSolution:solvers."(U|UFinal)"={...} replaces the
    entry whose name is a regular expression, keeping the others; a field's
    name that is not there (U) is added beside the regular expression, a
    regular expression that is not there and a value that is not a
    dictionary are refused."""
    import harness
    case, fvSolution = _fv_solution_case(tmp_path, "squareDrum")
    harness.apply_edits(case, [
        'system/fvSolution:solvers."(U|UFinal)"={ solver GAMG; '
        'smoother GaussSeidel; tolerance 1e-10; relTol 0.1; }'])
    assert generate.foam_value(fvSolution,
                               'solvers/"(U|UFinal)"/solver') == "GAMG"
    assert generate.foam_value(fvSolution,
                               'solvers/"(U|UFinal)"/relTol') == "0.1"
    assert generate.foam_value(fvSolution,
                               'solvers/"pcorr.*"/solver') == "PCG"
    harness.apply_edits(case, [
        'system/fvSolution:solvers.U={ solver smoothSolver; '
        'smoother symGaussSeidel; }'])
    assert generate.foam_value(fvSolution, "solvers/U/solver") \
        == "smoothSolver"
    assert generate.foam_value(fvSolution,
                               'solvers/"(U|UFinal)"/solver') == "GAMG"
    harness.apply_edits(case, [
        'system/fvSolution:solvers.U={ solver PBiCG; preconditioner DILU; }'])
    assert generate.foam_value(fvSolution, "solvers/U/solver") == "PBiCG"
    assert fvSolution.read_text().count("PBiCG;") == 1
    with pytest.raises(AssertionError, match="not in"):
        harness.apply_edits(case, [
            'system/fvSolution:solvers."(V|VFinal)"={ solver GAMG; }'])
    with pytest.raises(ValueError, match="not a dictionary"):
        harness.apply_edits(case, [
            'system/fvSolution:solvers."pcorr.*"=PCG'])


def test_log_cost_counts_the_krylov_iterations_of_the_window():
    """log_cost gives the Krylov coupling's iterations and its inner
    solvers' iterations per step over the steps of the window only, and
    no such keys for a log without the Krylov coupling."""
    from granularfoam.foamio import log_cost
    log = "\n".join([
        "Time = 1", "Krylov coupling: BFBt, 30 iterations (900 of the inner "
        "solvers), residual 1 -> 0.1 m/s", "ExecutionTime = 1 s",
        "Time = 2", "Krylov coupling: CahouetChabard, 10 iterations (100 of "
        "the inner solvers), residual 1 -> 0.1 m/s",
        "Pressure coupling: 11 pressure solutions", "ExecutionTime = 3 s",
        "Time = 3", "Krylov coupling: CahouetChabard, 20 iterations (300 of "
        "the inner solvers), residual 1 -> 0.1 m/s",
        "Pressure coupling: 21 pressure solutions", "ExecutionTime = 6 s"])
    cost = log_cost(log, start=1)
    assert cost == {"steps": 2, "cpu_seconds": 5.0,
                    "pressure_solutions_per_step": 16.0,
                    "krylov_iterations_per_step": 15.0,
                    "inner_iterations_per_step": 200.0}
    assert "krylov_iterations_per_step" not in log_cost(
        "Time = 1\nPressure coupling: 20 pressure solutions\n"
        "ExecutionTime = 1 s")


def test_profile_shares_leave_out_the_solver_lifetimes(tmp_path):
    """The harness's profile shares: each section's total over the time
    loop's, a section under two parents summed, the linear solvers'
    lifetime sections (lduMatrix::solver.*) and the sections below the
    smallest share left out."""
    import harness
    sections = [("application::main", 1, 10.5), ("time.run() case", 10, 10),
                ("granular::Krylov", 10, 6), ("granular::Krylov::residual",
                                              10, 1),
                ("granular::Krylov::residual", 20, 0.5),
                ("lduMatrix::solver.p_rghKrylov", 10, 5.9),
                ("fvMatrix::solve.p_rgh", 10, 0.95),
                ("granular::UEqn", 10, 0.05)]
    body = "".join(
        f"    trigger{i}\n    {{\n        id {i};\n"
        f"        description     \"{d}\";\n        calls           {c};\n"
        f"        totalTime       {t};\n        childTime       0;\n    }}\n"
        for i, (d, c, t) in enumerate(sections))
    (tmp_path / "1" / "uniform").mkdir(parents=True)
    (tmp_path / "1" / "uniform" / "profiling").write_text(
        "profiling\n{\n" + body + "}\n")
    (tmp_path / "1" / "alpha.air").write_text("")
    assert harness.profile_shares(tmp_path) == {
        "granular::Krylov": 0.6, "granular::Krylov::residual": 0.15,
        "fvMatrix::solve.p_rgh": 0.095}


def test_drum_rows_give_the_cost_per_simulated_second(monkeypatch):
    """A whole drum row and a row of part of a revolution: CPU per
    simulated second and the eight revolutions' projection in hours; the
    part's row without the monitor's columns."""
    partial = {"source": "/runs/N200", "N": 200, "start": 70.0,
               "end": 70.5, "source_coupling": "Krylov CahouetChabard 30",
               "coupling": "tutorial", "edits": [], "ranks": 2,
               "steps": 160, "cpu_seconds": 225.0,
               "pressure_solutions_per_step": 31.0,
               "status": "ok; part of a revolution, its cost alone"}
    monkeypatch.setattr(report, "coupling_runs",
                        lambda section: [partial])
    lines = report.whole_drum_section()
    row = next(x for x in lines if x.startswith("| 200 "))
    assert row == ("| 200 | 70–70.5 | the source's fvSolution (Krylov "
                   "CahouetChabard 30) | 160 | 225 | 450 | 10.0 |  | "
                   "31.0 |  |  |  |  | ok; part of a revolution, its cost "
                   "alone |")


def test_drum_rows_from_a_state_compare_with_the_reference_revolution(
        monkeypatch):
    """From a state (no source run), a revolution's J, surface angle and
    peak speed are given against the reference revolution
    (harness.DRUM_REFERENCE) from the same state and window, with its
    speed-up; the reference's own row says 1; a revolution from another
    window has neither; one of another date has the differences without
    the speed-up, as has one against bench/run's reference revolution
    (another invocation)."""
    import harness
    name, edits = harness.DRUM_REFERENCE
    state = {"source": "/runs/N100M", "N": 100, "start": 70.0, "end": 80.0,
             "source_coupling": "Krylov BFBt 20", "ranks": 2,
             "pressure_solutions_per_step": 20.0,
             "surface_angle_range_deg": [21.0, 25.0],
             "lowest_p_grains": -20.0, "steps_with_negative_p_grains": 900,
             "status": "ok; the source is a state, not a run",
             "date": "2026-12-06"}
    ref = dict(state, coupling=name, edits=list(edits), steps=10000,
               cpu_seconds=2500.0, J_end=0.025,
               surface_angle_mean_deg=23.5, peak_speed_mean=0.24,
               peak_speed_max=0.28)
    run = dict(state, coupling="Krylov-CahouetChabard-20",
               edits=["system/fvSolution:transportFlux=midStep"],
               steps=2500, cpu_seconds=500.0, J_end=0.0245,
               surface_angle_mean_deg=23.5, peak_speed_mean=0.234,
               peak_speed_max=0.28)
    other = dict(run, start=60.0, end=70.0)
    monkeypatch.setattr(report, "coupling_runs",
                        lambda section: [ref, run, other])
    rows = {x.split(" | ")[1]: x for x in report.whole_drum_section()
            if x.startswith("| 100 ") and "transportFlux" in x}
    assert rows["70–80"] == (
        "| 100 | 70–80 | Krylov-CahouetChabard-20 `transportFlux=midStep` | "
        "2500 | 500 | 50 | 1.1 | 5.0 | 20.0 | 0.0245 (-2.0%) | "
        "23.50 (+0.0%) | 0.234 (-2.5%) / 0.280 (+0.0%) | -20.0 (900) | "
        "ok; the source is a state, not a run |")
    assert rows["60–70"].split(" | ")[6:9] == ["1.1", "", "20.0"]
    assert "0.0245 | " in rows["60–70"]
    ref_row = next(x for x in report.whole_drum_section()
                   if f"| {name} " in x)
    assert ref_row.split(" | ")[7] == "1"

    later = dict(run, date="2026-12-07")
    bench_ref = dict(ref, start=60.0, end=70.0, date="2026-12-06")
    monkeypatch.setattr(report, "coupling_runs",
                        lambda section: [ref, later, other])
    rows = {x.split(" | ")[1]: x for x in report.whole_drum_section(
        {"drum": {"runs": {"reference": bench_ref}}})
        if x.startswith("| 100 ") and "transportFlux" in x}
    assert rows["70–80"].split(" | ")[6:10] == [
        "1.1", "", "20.0", "0.0245 (-2.0%)"]
    assert rows["60–70"].split(" | ")[6:10] == [
        "1.1", "", "20.0", "0.0245 (-2.0%)"]


def test_drum_profile_columns_keep_a_pipe_inside_its_cell(monkeypatch):
    """The drum profile table: a column a profiled run, headed by its
    edits without the profiling one, its sections' shares; the | of a
    regex-keyed solver edit escaped so that the row keeps its cells."""
    run = {"source": "/runs/N200", "N": 200, "start": 70.0, "end": 70.1,
           "coupling": "tutorial",
           "source_coupling": "Krylov CahouetChabard 30",
           "edits": ["system/controlDict:profiling={ active true; }",
                     'system/fvSolution:solvers."(U|UFinal)"={ relTol 0; }'],
           "steps": 50, "cpu_seconds": 40.0,
           "pressure_solutions_per_step": 21.0,
           "krylov_iterations_per_step": 19.75,
           "inner_iterations_per_step": 500.0,
           "profile_shares": {"granular::Krylov": 0.58,
                              "fvMatrix::solve.pcorr": 0.132},
           "status": "ok; part of a revolution, its cost alone"}
    monkeypatch.setattr(report, "coupling_runs", lambda section: [run])
    lines = report.drum_profile_section()
    assert lines[4] == ('| section | N = 200, 70–70.1 s, the source\'s '
                        'fvSolution (Krylov CahouetChabard 30) '
                        '`solvers."(U\\|UFinal)"={ relTol 0; }` |')
    assert "| CPU per step [s] | 0.800 |" in lines
    assert "| Krylov iterations / step | 19.8 |" in lines
    assert lines[-2:] == ["| `granular::Krylov` | 58.0% |",
                          "| `fvMatrix::solve.pcorr` | 13.2% |"]


@pytest.mark.parametrize("duration", ["0", "10.5"])
def test_harness_drum_refuses_a_duration_beyond_a_revolution(
        tmp_path, capsys, duration):
    """bench/harness drum --duration outside (0, 10] s: a usage error
    naming the value, before anything runs."""
    import harness
    (tmp_path / "processor0").mkdir()
    with pytest.raises(SystemExit) as exit_info:
        harness.main(["drum", "--source", str(tmp_path), "--start", "70",
                      "--duration", duration, "--no-store"])
    assert exit_info.value.code == 2
    assert f"--duration {float(duration):g}: not in (0, 10] s" in \
        capsys.readouterr().err


def test_harness_drum_interleaves_variants_and_stores_the_median(
        tmp_path, monkeypatch, capsys):
    """bench/harness drum --variant ... --repeat K runs every variant (on
    top of --edit) K times, interleaved, and stores for each the median of
    its CPU seconds with every repetition's; --repeat 0 and a bad edit in
    a variant are usage errors."""
    import harness
    (tmp_path / "processor0").mkdir()
    calls, stored = [], []
    cpu = iter([12.0, 21.0, 16.0, 26.0, 10.0, 20.0])

    def fake(source, start, coupling, edits, duration=None, files=None):
        calls.append(list(edits))
        c = next(cpu)
        return {"source": str(source), "start": start, "end": start + 0.4,
                "coupling": coupling, "edits": list(edits),
                "cpu_seconds": c, "window_cpu_seconds": c,
                "status": "ok; part of a revolution, its cost alone"}
    monkeypatch.setattr(harness, "whole_drum", fake)
    monkeypatch.setattr(harness, "store_drum",
                        lambda entries, command: stored.extend(entries))
    base = "system/fvSolution:PIMPLE.Krylov.innerRelTol=0.1"
    other = "system/fvSolution:PIMPLE.correctPhi=no"
    assert harness.main(["drum", "--source", str(tmp_path), "--start", "20",
                         "--duration", "0.4", "--couplings", "tutorial",
                         "--edit", base, "--variant", "--variant", other,
                         "--repeat", "3"]) == 0
    assert calls == [[base], [base, other]] * 3
    last = {tuple(e["edits"]): e for e in stored}
    assert last[(base,)]["cpu_seconds"] == 12.0
    assert last[(base,)]["cpu_seconds_repeats"] == [12.0, 16.0, 10.0]
    assert last[(base, other)]["cpu_seconds"] == 21.0
    assert last[(base, other)]["window_cpu_seconds"] == 21.0
    for bad in (["--repeat", "0"], ["--variant", "nonsense"]):
        with pytest.raises(SystemExit) as exit_info:
            harness.main(["drum", "--source", str(tmp_path), "--start",
                          "20", "--no-store", *bad])
        assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert "--repeat 0: not a positive integer" in err
    assert "edit 'nonsense' is not DICT:ENTRY=VALUE" in err


def test_harness_rows_show_the_references_own_run(monkeypatch):
    """An entry of the reference coupling run against itself (bench/harness
    run --couplings R --reference R) has no errors: its row gives its cost
    and names it the reference."""
    own = {"state": "/runs/N150K@30", "time": 30.0, "dt": 0.004,
           "steps": 10, "coupling": "Krylov-CahouetChabard-200-tol1e-8",
           "edits": [], "reference": "Krylov-CahouetChabard-200-tol1e-8",
           "status": "ok", "pressure_solutions_per_step": 40.9,
           "cpu_ms_per_step": 2640.0}
    monkeypatch.setattr(report, "coupling_runs", lambda section: [own])
    row = next(x for x in report.harness_section()
               if x.startswith("| /runs/N150K@30 "))
    assert row == ("| /runs/N150K@30 | – | 0.004 | 10 | "
                   "Krylov-CahouetChabard-200-tol1e-8 (the reference) | "
                   "– | – | – | – | – | 41 | 2.6e+03 |")


def test_drum_part_is_the_reference_and_the_tutorial_unchanged():
    """bench/run's drum part: the reference is the drum's reference
    revolution of bench/harness drum; the tutorial's run changes nothing
    of the source's files."""
    import bench
    import harness
    assert bench.DRUM["reference"] == harness.DRUM_REFERENCE
    coupling, edits = bench.DRUM["tutorial"]
    assert harness.coupling_settings(coupling) == {} and edits == ()


def _drum_state(tmp_path, time="20"):
    """A stand-in of a decomposed drum run: the tutorial's case files and
    processor0/<time>."""
    import bench
    import harness
    source = tmp_path / "N100"
    for name in (*harness.DRUM_FILES, "system/drumParameters"):
        (source / name).parent.mkdir(parents=True, exist_ok=True)
        (source / name).write_bytes((bench.DRUM_TUTORIAL / name)
                                    .read_bytes())
    (source / "processor0" / time).mkdir(parents=True)
    (source / "processor0" / time / "alpha.air").write_text("")
    (source / "processor0" / "constant").mkdir()
    return source


def test_drum_source_must_be_a_decomposed_drum_run(tmp_path):
    """The drum part runs from a decomposed drum run at a time it wrote:
    a missing time or an undecomposed case is refused, naming what is
    wrong; without a source, --parts drum is refused."""
    import bench
    source = _drum_state(tmp_path)
    assert bench.drum_source_problems(source, 20) == []
    assert bench.drum_source_problems(source, 30) == [
        "processor0 has no time 30"]
    assert bench.drum_source_problems(tmp_path, 20)[0].startswith(
        "not a decomposed run of tutorials/squareDrum")
    with pytest.raises(SystemExit):
        bench.parse_args(["--parts", "drum"])
    with pytest.raises(SystemExit):
        bench.parse_args(["--parts", "drum", "--drum-source", str(source),
                          "--drum-start", "30"])
    args = bench.parse_args(["--parts", "drum", "--drum-source",
                             str(source), "--drum-start", "20"])
    assert args.parts == ["drum"]
    assert "drum" not in bench.parse_args([]).parts


def test_drum_runs_take_the_tutorials_files(tmp_path, monkeypatch):
    """Both drum runs of bench/run start from the state with the tutorial's
    fvSolution, fvSchemes and controlDict, whatever the source's were;
    the reference's coupling is then set on them."""
    import bench
    import generate
    import harness
    source = _drum_state(tmp_path)
    fv = source / "system" / "fvSolution"
    fv.write_text(fv.read_text().replace("maxIter         20;",
                                         "maxIter         7;"))
    monkeypatch.setattr(harness, "WORK", tmp_path / "work")
    monkeypatch.setattr(harness.subprocess, "call", lambda *a, **k: 1)
    result = bench.run_drum(source, 20, None, "bench/run")
    for name, run in result["runs"].items():
        assert run["status"] == "failed (exit 1)"
        case = next((tmp_path / "work" / "drum").glob(f"*files-*{name}*"
                    if name == "tutorial" else "*files-*Krylov*"))
        iters = generate.foam_value(case / "system" / "fvSolution",
                                    "PIMPLE/Krylov/maxIter")
        assert iters == ("20" if name == "tutorial" else "30")
        # the reference's controlDict is edited (maxDeltaT)
        same = harness.DRUM_FILES[1:] if name == "tutorial" else \
            ("system/fvSchemes",)
        for f in same:
            assert (case / f).read_bytes() == (bench.DRUM_TUTORIAL / f
                                               ).read_bytes()


def test_parts_not_run_keep_their_results():
    """--parts drum takes the other parts' keys from the earlier results
    file and writes its own."""
    import bench
    kept = {k: f"old {k}" for keys in bench.PARTS.values() for k in keys}
    new = {k: f"new {k}" for keys in bench.PARTS.values() for k in keys}
    merged = bench.keep_parts(dict(new), kept, ["drum"])
    assert merged["drum"] == "new drum"
    assert merged["whole"] == "old whole"
    assert merged["summary"] == "old summary"
    assert merged["per_simulated_second"] == "old per_simulated_second"


def _drum_results(tutorial_status="ok"):
    window = {"J_end": 0.026, "surface_angle_mean_deg": 23.44,
              "peak_speed_mean": 0.2359, "peak_speed_max": 0.29,
              "lowest_p_grains": -3.0, "steps_with_negative_p_grains": 4}
    ref = dict(window, steps=10007, cpu_seconds=2677.0, ms_per_step=267.5,
               pressure_solutions_per_step=31.0, status="ok")
    tut = dict(window, J_end=0.0247, peak_speed_mean=0.2305, steps=2608,
               cpu_seconds=460.0, ms_per_step=176.4,
               pressure_solutions_per_step=19.0, status=tutorial_status)
    if tutorial_status == "ok":
        for key in ("J_end", "surface_angle_mean_deg", "peak_speed_mean",
                    "peak_speed_max"):
            tut[f"{key}_vs_reference"] = tut[key] / ref[key] - 1
    else:
        for key in window:
            del tut[key]
    return {"command": "bench/run", "drum": {
        "case": "squareDrum", "N": 100, "ranks": 2, "source": "/runs/N100",
        "start": 20.0, "end": 30.0, "command": "bench/run --parts drum",
        "date": "2026-12-07T10:00:00+00:00",
        "machine": {"cpu": "AMD EPYC", "cpus": 2},
        "settings": {"reference": {"coupling": "Krylov-CC-30",
                                   "edits": ["a=1"]},
                     "tutorial": {"coupling": "tutorial", "edits": []}},
        "runs": {"reference": ref, "tutorial": tut},
        "speedup": 2677.0 / 460.0}}


def test_report_shows_both_drum_revolutions_and_the_speed_up():
    """The drum section has the reference's and the tutorial's rows, the
    tutorial's differences from the reference, its own command and the
    speed-up; a failed run shows its status; no drum part, no section."""
    lines = report.drum_section(_drum_results())
    assert lines[2] == "    bench/run --parts drum"
    assert lines[4].startswith("(2026-12-07, AMD EPYC, 2 cores;")
    rows = [x for x in lines if x.startswith("| reference")
            or x.startswith("| tutorial")]
    assert len(rows) == 2
    assert rows[0].startswith("| reference | 10007 | 2677 | 268 | 31.0 | "
                              "0.0260 | 23.44 | 0.236 / 0.290 | -3.0 (4) |")
    assert "| 0.0247 (-5.0%) | 23.44 (+0.0%) | 0.231 (-2.3%) / 0.290 " \
        "(+0.0%) |" in rows[1]
    assert lines[-1] == ("Speed-up of the tutorial over the reference "
                         "(CPU): **5.82**.")
    failed = report.drum_section(_drum_results("failed (exit 1)"))
    row = next(x for x in failed if x.startswith("| tutorial"))
    assert row.endswith("|  |  |  |  | failed (exit 1) |")
    assert report.drum_section({"drum": None}) == []
    assert report.drum_section({}) == []


def test_drum_rows_from_a_state_compare_with_bench_runs_reference(
        monkeypatch):
    """A harness revolution from the state of bench/run's drum part is
    compared with that part's reference revolution when coupling.json has
    none: its J, surface angle and peak speed, not its CPU (another
    invocation)."""
    import harness  # noqa: F401 (sys.modules["harness"] below)
    results = _drum_results()
    ref = results["drum"]["runs"]["reference"]
    ref.update(source="/runs/N100", start=20.0, end=30.0,
               coupling="Krylov-CC-30", edits=["a=1"])
    run = dict(ref, coupling="Krylov-CahouetChabard-20",
               edits=["system/fvSolution:PIMPLE.correctPhi=no"], N=100,
               source_coupling="Krylov CahouetChabard 20", steps=2000,
               cpu_seconds=535.4, J_end=0.0247, peak_speed_mean=0.2336,
               surface_angle_range_deg=[21.0, 25.0])
    monkeypatch.setattr(report, "coupling_runs", lambda section: [run])
    monkeypatch.setattr(
        sys.modules["harness"], "DRUM_REFERENCE", ("Krylov-CC-30", ("a=1",)))
    row = next(x for x in report.whole_drum_section(results)
               if "correctPhi" in x)
    assert "0.0247 (-5.0%)" in row and "0.234 (-1.0%)" in row
    assert row.split(" | ")[7] == ""
    row = next(x for x in report.whole_drum_section({}) if "correctPhi" in x)
    assert "| 5.0 |" not in row and "(-5.0%)" not in row

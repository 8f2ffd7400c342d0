"""The Krylov coupling (fvSolution PIMPLE pressureCoupling Krylov) solves the
same discrete step as the PISO correctors: iterated to a tight tolerance it
reaches the velocity and pressure of 200 PISO correctors with p_rgh solved
to 1e-13, on the square drum (rotating mesh, closed domain, pressure level
from the air) on 16 x 16 cells over three steps of 1 ms.  Every step logs
its iterations and residual against the RMS speed, and says so when the
tolerance was not reached within maxIter."""
import re
import shutil

import numpy as np
import pytest

from cases import edit, fresh_case, run, set_entry, small_drum
from granularfoam.foamio import read_field

pytestmark = pytest.mark.smoke

FV = "system/fvSolution"
STEPS = 3
DT = 1e-3
END = f"{STEPS * DT:g}"

PISO_200 = [(r"nCorrectors         \d+;",
             "nCorrectors         200;\n    pressureCoupling    PISO;"),
            (r"tolerance       1e-9;\n        relTol          0.01;",
             "tolerance       1e-13;\n        relTol          0;")]

KRYLOV_LINE = (r"^Krylov coupling: (\w+), (\d+) iterations \(\d+ of the inner "
               r"solvers\), residual (\S+) -> (\S+) m/s, (\S+) of the RMS "
               r"speed(.*)$")


def krylov(preconditioner, max_iter, tolerance, inner="1e-10"):
    return [(r"nCorrectors         \d+;",
             "nCorrectors         1;\n    pressureCoupling    Krylov;\n"
             f"    Krylov {{ preconditioner {preconditioner}; "
             f"maxIter {max_iter}; tolerance {tolerance}; "
             f"innerRelTol {inner}; }}")]


@pytest.fixture(scope="module")
def base(foam_env):
    return small_drum("krylov/base", n=16, end_time=END, delta_t=f"{DT:g}",
                      controls=[(r"writePrecision  10;",
                                 "writePrecision  17;")])


def _run(base, tmp_path, name, edits, controls=()):
    case = tmp_path / name
    shutil.copytree(base, case)
    edit(case / FV, edits)
    if controls:
        edit(case / "system" / "controlDict", list(controls))
    res = run(["granularSegregationFoam"], case, timeout=600)
    log = res.stdout + res.stderr
    assert res.returncode == 0, log[-3000:]
    assert (case / END / "U").is_file(), f"{case} did not write {END}"
    return case, log


def _rel(a, b):
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def _assert_at_piso_200(case, ref, what, iterations):
    """U and p of case at the end within 1e-6 (relative L2) of ref's, the
    200 PISO correctors'."""
    du = _rel(read_field(case, END, "U"), read_field(ref, END, "U"))
    dp = _rel(read_field(case, END, "p"), read_field(ref, END, "p"))
    print(f"{what} against PISO-200: U {du:.2e}, p {dp:.2e}; "
          f"iterations per step {iterations}")
    assert du < 1e-6, f"U differs from PISO-200 by {du:.3e}"
    assert dp < 1e-6, f"p differs from PISO-200 by {dp:.3e}"


def test_krylov_reaches_the_piso_fixed_point(base, tmp_path):
    ref, _ = _run(base, tmp_path, "piso200", PISO_200)
    case, log = _run(base, tmp_path, "krylov", krylov("BFBt", 300, "1e-9"))

    steps = re.findall(r"^Krylov coupling: BFBt, (\d+) iterations "
                       r"\(\d+ of the inner solvers\), residual (\S+) -> (\S+) m/s, (\S+) of the RMS "
                       r"speed$", log, re.M)
    assert len(steps) == STEPS, log[-3000:]
    assert all(float(r) <= 1e-9 for _, _, _, r in steps), steps

    _assert_at_piso_200(case, ref, "Krylov (BFBt, 1e-9)",
                        [int(n) for n, _, _, _ in steps])


def test_cahouet_chabard_with_backward_reaches_the_piso_fixed_point(
        base, tmp_path):
    """The Cahouet-Chabard preconditioner serves ddt(rho,U) backward (its
    floor of the inertia the scheme's 1 + dt/(dt + dt0) times rho/dt, 1.5
    from the second step on here): iterated to a tight tolerance the
    Krylov coupling reaches the velocity and pressure of 200 PISO
    correctors with the same scheme."""
    backward = [(r"default Euler;", "default backward;")]

    def run_backward(name, edits):
        case = tmp_path / name
        shutil.copytree(base, case)
        edit(case / "system" / "fvSchemes", backward)
        return _run(case, tmp_path, name + "-run", edits)

    ref, _ = run_backward("piso200", PISO_200)
    case, log = run_backward("krylov", krylov("CahouetChabard", 300,
                                              "1e-9"))
    steps = re.findall(KRYLOV_LINE, log, re.M)
    assert len(steps) == STEPS, log[-3000:]
    assert all(p[0] == "CahouetChabard" and float(p[4]) <= 1e-9
               and not p[5] for p in steps), steps

    _assert_at_piso_200(case, ref, "Krylov (Cahouet-Chabard, backward, 1e-9)",
                        [int(p[1]) for p in steps])


def test_krylov_says_when_not_converged(base, tmp_path):
    _, log = _run(base, tmp_path, "krylov1", krylov("PISO", 1, "1e-9"))
    lines = re.findall(r"^Krylov coupling: PISO, 1 iterations .*$", log,
                       re.M)
    assert len(lines) == STEPS, log[-3000:]
    for line in lines:
        m = re.search(r"not converged to tolerance (\S+) within maxIter 1$",
                      line)
        assert m and float(m.group(1)) == 1e-9, line


def test_krylov_final_settings_take_the_final_outer_iteration(base,
                                                              tmp_path):
    """With two outer iterations, Krylov's settings serve the first and
    KrylovFinal's the second (final) one of every step."""
    edits = krylov("BFBt", 300, "1e-9") + [
        (r"nOuterCorrectors\s+\d+;", "nOuterCorrectors    2;"),
        (r"Krylov \{", "KrylovFinal { preconditioner PISO; maxIter 1; "
                       "tolerance 1e-9; }\n    Krylov {")]
    _, log = _run(base, tmp_path, "krylovFinal", edits)
    lines = re.findall(r"^Krylov coupling: .*$", log, re.M)
    assert len(lines) == 2 * STEPS, log[-3000:]
    for first, final in zip(lines[::2], lines[1::2]):
        assert first.startswith("Krylov coupling: BFBt, ") \
            and "not converged" not in first, first
        m = re.search(r"not converged to tolerance (\S+) within maxIter 1$",
                      final)
        assert final.startswith("Krylov coupling: PISO, 1 iterations ") \
            and m and float(m.group(1)) == 1e-9, final



def test_rheology_correctors_iterate_the_viscosity(base, tmp_path):
    """nRheologyCorrectors 3 solves the momentum and pressure equations
    four times a step, each pass from the last one's velocity with the
    rheology evaluated again: a pass starts from a residual above the one
    the last pass ended at (the viscosity changed) and the changes shrink
    from pass to pass (the Picard iteration on the rheology contracts).
    Krylov's settings serve the passes before the last, KrylovFinal's the
    last.  Without the explicit transpose stress (transposeStress none),
    which a pass would update from the new velocity as well, the rheology
    is all that changes between passes.  The passes after the first
    start from the last one's velocity: one momentum predictor a step (the
    solver's log lines, switched on here)."""
    edits = krylov("BFBt", 300, "1e-9") + [
        (r"nOuterCorrectors\s+\d+;",
         "nOuterCorrectors    1;\n    nRheologyCorrectors 3;\n"
         "    transposeStress     none;"),
        (r"Krylov \{", "KrylovFinal { preconditioner CahouetChabard; "
                       "maxIter 300; tolerance 1e-10; }\n    Krylov {")]
    _, log = _run(base, tmp_path, "rheologyCorrectors", edits,
                  [(r"SolverPerformance 0;", "SolverPerformance 1;")])
    lines = re.findall(KRYLOV_LINE, log, re.M)
    assert len(lines) == 4 * STEPS, log[-3000:]
    steps = re.split(r"^Time = \S+$", log, flags=re.M)[1:]
    assert len(steps) == STEPS, log[-3000:]
    predictors = [len(re.findall(r"Solving for Ux,", step)) for step in steps]
    assert predictors == [1] * STEPS, predictors
    for step in range(STEPS):
        passes = lines[4 * step:4 * step + 4]
        assert [p[0] for p in passes] == ["BFBt"] * 3 + ["CahouetChabard"], \
            passes
        assert all(float(p[4]) <= 1e-9 and not p[5] for p in passes[:3]), \
            passes
        assert float(passes[3][4]) <= 1e-10 and not passes[3][5], passes
        start = [float(p[2]) for p in passes]
        end = [float(p[3]) for p in passes]
        print(f"step {step + 1}: residuals at the start of the passes "
              f"{start}, at their ends {end}")
        # Each later pass starts above where the last one ended ...
        assert all(s > 100 * e for s, e in zip(start[1:], end[:-1])), \
            (start, end)
        # ... and the rheology's changes shrink from pass to pass (by a
        # factor of 5-20 a pass here)
        assert start[1] > start[2] > start[3], start
        assert start[3] < 0.1 * start[1], start


def test_the_step_starts_from_the_last_pressure(foam_env, tmp_path):
    """startPressure p starts the step from the last pressure
    p where the transport changed the density (p_rgh -= (rho - rho_0) gh):
    the chute on 40 x 16 cells from rest to 0.3 s, the grains' front
    crossing cells every step, the Krylov coupling's initial residual is a
    fraction of the one startPressure p_rgh (multiphaseInterFoam's
    p_rgh kept) leaves, whose p_rgh jumps by (rho^g - rho^a) gh where the
    surface moved (measured: a ninth, median over the steps after the
    twentieth)."""
    chute = fresh_case("chute", dest="krylov/startPressure", tutorial=True)
    for key, value in (("nx", 40), ("nz", 16), ("endTime", 0.3),
                       ("writeInterval", 0.3)):
        set_entry(chute, "system/chuteParameters", key, value)
    shutil.copytree(chute / "0.orig", chute / "0")
    assert run(["blockMesh"], chute).returncode == 0
    residuals = {}
    for start in ("p", "p_rgh"):
        case = tmp_path / start
        shutil.copytree(chute, case)
        set_entry(case, FV, "PIMPLE.startPressure", start)
        res = run(["granularSegregationFoam"], case, timeout=600)
        log = res.stdout + res.stderr
        assert res.returncode == 0, log[-3000:]
        assert (case / "0.3" / "U").is_file(), f"{case} did not write 0.3"
        assert f"each step starts from the last {start}\n" in log
        first = [float(m[2]) for m in re.findall(KRYLOV_LINE, log, re.M)]
        assert len(first) > 40, len(first)
        residuals[start] = np.median(first[20:])
    ratio = residuals["p_rgh"] / residuals["p"]
    print(f"median initial residual: p {residuals['p']:.3g}, "
          f"p_rgh {residuals['p_rgh']:.3g} m/s ({ratio:.1f} times)")
    assert ratio > 3, residuals

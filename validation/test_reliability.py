"""Reliability at CI size: an exact restart (the Bagnold layer and the
drum), the decomposePar/reconstructPar round trip (scotch and metis), and
degenerate states that must run and stay finite.

Each case runs in validation/results/reliability/<name>/.  The measured
differences are written to validation/results/reliability/*.json.
"""
import re
import shutil
import subprocess
import time

import numpy as np
import pytest

from cases import (NUMBER, RESULTS, edit, foam, foam_output, fresh_case, run,
                   set_decomposition, small_drum, write_results)
from granularfoam.foamio import cell_centres, read_field
from granularfoam.post import drum as post

pytestmark = pytest.mark.smoke

HERE = "reliability"
PHASES = ("alpha.air", "alpha.small", "alpha.large")
RHO_AIR, G = 1.0, 9.81      # the drum's air density and |g|


def _field_files(case, time_name):
    """Names of the fields written at a time (no directories)."""
    d = case / time_name
    assert d.is_dir(), f"{case} wrote no time {time_name}"
    return sorted(p.name for p in d.iterdir() if p.is_file())


def _max_relative_difference(a_case, b_case, time_name):
    """{field: max |a - b| / max |a|} of every field written at time_name
    by both cases; the two must have written the same fields."""
    names = _field_files(a_case, time_name)
    assert names == _field_files(b_case, time_name), (
        _field_files(a_case, time_name), _field_files(b_case, time_name))
    out = {}
    for name in names:
        a = read_field(a_case, time_name, name)
        b = read_field(b_case, time_name, name)
        assert a.shape == b.shape, (name, a.shape, b.shape)
        assert np.all(np.isfinite(a)) and np.all(np.isfinite(b)), name
        scale = float(np.abs(a).max())
        out[name] = float(np.abs(a - b).max()) / scale if scale > 0 else \
            float(np.abs(b).max())
    return out


def _set_end(case, path, key, value):
    """Set `key value;` in case/path (a plain file, no #include edits)."""
    edit(case / path, [(rf"\n{key}\s+[^;\n]+;", f"\n{key} {value};")])


def _restart_pair(make, name, end_file, half, end):
    """Two copies of the case make(dest) returns: one runs to `end`, the
    other to `half`, stops, and restarts from there (startFrom latestTime)
    to `end`.  The restart must start at `half`: its log says so."""
    whole = make(f"{HERE}/restart-{name}-whole")
    foam(whole, "granularSegregationFoam")
    split = make(f"{HERE}/restart-{name}-split")
    _set_end(split, end_file, "endTime", half)
    foam(split, "granularSegregationFoam")
    assert (split / half).is_dir()
    _set_end(split, end_file, "endTime", end)
    _set_end(split, "system/controlDict", "startFrom", "latestTime")
    log = foam_output(split, "granularSegregationFoam")[0]
    first = re.search(r"\nTime = (\S+)\n", log)
    assert first and float(first.group(1)) > float(half), (
        f"the second run did not continue from {half}: its first step is "
        f"{first.group(1) if first else None}")
    return whole, split


FULL_PRECISION = [(r"writePrecision\s+\d+;", "writePrecision  17;")]


def _layer(dest):
    """The inclined Bagnold layer (validation/cases/inclinedLayer), ascii
    at 17 digits, written every 0.02 s."""
    case = fresh_case("inclinedLayer", dest=dest)
    edit(case / "system" / "controlDict", FULL_PRECISION + [
        (r"\nwriteInterval\s+\S+;", "\nwriteInterval   0.02;"),
        (r"\nendTime\s+\S+;", "\nendTime         0.04;")])
    shutil.copytree(case / "0.orig", case / "0")
    foam(case, "blockMesh")
    foam(case, "setFields")
    return case


def _layer_implicit(dest):
    """The layer at 28 degrees with the implicit stress (momentum
    predictor, the default coupling), adjustable steps."""
    case = _layer(dest)
    zeta = np.radians(28.0)
    edit(case / "constant" / "g", [(r"value\s+\([^)]*\);",
          f"value ({9.81*np.sin(zeta):.15g} 0 {-9.81*np.cos(zeta):.15g});")])
    edit(case / "system" / "fvSolution", [
        (r"momentumPredictor\s+\w+;",
         "momentumPredictor yes;\n    viscousStress   implicit;")])
    return case


def _column(dest):
    """tutorials/segregationColumn, ascii at 17 digits, to 0.2 s, written
    every 0.1 s (adjustable steps, an open top)."""
    case = fresh_case("segregationColumn", dest=dest, tutorial=True)
    edit(case / "system" / "columnParameters", [
        (r"\nendTime\s+[^;]+;", "\nendTime 0.2;"),
        (r"\nwriteInterval\s+[^;]+;", "\nwriteInterval 0.1;")])
    edit(case / "system" / "controlDict", FULL_PRECISION)
    shutil.copytree(case / "0.orig", case / "0")
    foam(case, "blockMesh")
    foam(case, "setGranularFields")
    return case


def _drum(dest, adjust):
    """The drum on 12 x 12 cells, ascii at 17 digits, written every 0.1 s:
    fixed steps of 5e-3 s, or the tutorial's adjustable step."""
    return small_drum(dest, n=12, end_time="0.4", write_interval="0.1",
                      delta_t="5e-3", adjust=adjust, controls=FULL_PRECISION)


# The Krylov coupling with the transport sub-cycled: its iterations end at
# a tolerance, so a restart that changed the step in the last bit would
# show in the fields
KRYLOV = [(r"nCorrectors         \d+;",
           "nCorrectors         1;\n    pressureCoupling    Krylov;\n"
           "    Krylov { preconditioner BFBt; maxIter 20; tolerance 1e-2; }"),
          (r"\b(?:max|n)AlphaSubCycles \d+;", "maxAlphaSubCycles 5;")]


def _drum_krylov(dest):
    """The drum of _drum with the adjustable step and the Krylov coupling."""
    return small_drum(dest, n=12, end_time="0.4", write_interval="0.1",
                      delta_t="5e-3", adjust=True, controls=FULL_PRECISION,
                      prepare=lambda case: edit(
                          case / "system" / "fvSolution", KRYLOV))


def _drum_krylov_mid_step(dest):
    """_drum_krylov with the phases transported with the flux at the middle
    of the step (transportFlux midStep: the flux of the previous step's
    start is read at the restart)."""
    return small_drum(dest, n=12, end_time="0.4", write_interval="0.1",
                      delta_t="5e-3", adjust=True, controls=FULL_PRECISION,
                      prepare=lambda case: edit(
                          case / "system" / "fvSolution", KRYLOV + [
                              (r"maxAlphaSubCycles 5;",
                               "maxAlphaSubCycles 5; transportFlux midStep;")]))


# What the solver reads at a restart; the other fields it writes (I, dbar,
# shearRate, ...) are recomputed from these
STATE = {"U", "Uf", "p", "p_rgh", "phi", "rAU", "meshPhi",
         "phiStepStart"} | set(PHASES)


# name: (make, dictionary with endTime, half, end)
RESTARTS = {
    "layer": (_layer, "system/controlDict", "0.02", "0.04"),
    "layer-implicit": (_layer_implicit, "system/controlDict", "0.02", "0.04"),
    "column": (_column, "system/columnParameters", "0.1", "0.2"),
    "drum": (lambda d: _drum(d, False), "system/drumParameters", "0.2", "0.4"),
    "drum-adjustable": (lambda d: _drum(d, True), "system/drumParameters",
                        "0.2", "0.4"),
    "drum-krylov-adjustable": (_drum_krylov, "system/drumParameters",
                               "0.2", "0.4"),
    "drum-krylov-mid-step": (_drum_krylov_mid_step, "system/drumParameters",
                             "0.2", "0.4"),
}


@pytest.mark.parametrize("which", list(RESTARTS))
def test_restart(foam_env, which):
    """Stop at a written time, restart from it (startFrom latestTime): at
    the end every field the solver reads at a restart (U, p, p_rgh, phi,
    every phase fraction; with the moving mesh Uf, meshPhi and, with
    correctPhi, rAU) equals
    the uninterrupted run's bit for bit (fields written at 17 digits), in
    open domains (the layer with the explicit and the implicit stress, the
    column) and in the turning drum, with fixed and adjustable steps, and
    with the Krylov coupling and the adjustable step (the phases
    transported with the flux at the start of the step and at its middle).
    A difference in the last bit anywhere (a step landing on a write time
    counted from the restart's start) grows to 1e-6 with the tutorial's
    Krylov coupling, whose inner solutions end at a relative 0.1."""
    make, end_file, half, end = RESTARTS[which]
    whole, split = _restart_pair(make, which, end_file, half, end)
    diff = _max_relative_difference(whole, split, end)
    write_results(RESULTS / HERE, f"restart-{which}", diff)
    assert {"U", "p", "p_rgh", "alpha.air", "alpha.small"} <= set(diff), diff
    # The start of the step's flux is written when midStep uses it
    assert ("phiStepStart" in diff) == ("mid-step" in which), diff
    checked = {k: v for k, v in diff.items() if k in STATE}
    assert max(checked.values()) == 0, checked


@pytest.mark.parametrize("flux", ["startOfStep", "midStep"])
def test_outer_iterations_transport_every_phase_from_the_step_start(
        foam_env, flux):
    """Picard iterations (nOuterCorrectors 2, (4.7)) with the transport in
    fixed sub-cycles (nAlphaSubCycles 3) on the turning drum, with the flux
    of the step's start and of its middle (transportFlux): each outer
    iteration transports every phase from the start of the step, so that
    every phase's volume stays constant to 1e-10 (relative) and the
    fractions within [-1e-10, 1 + 1e-10]; a phase transported on from the
    previous iteration's end would move the grains twice a step."""
    case = small_drum(
        f"{HERE}/outer-iterations-{flux}", n=12, end_time="0.1",
        delta_t="5e-3",
        prepare=lambda c: edit(c / "system" / "fvSolution", [
            (r"nOuterCorrectors\s+\d+;", "nOuterCorrectors 2;"),
            (r"\b(?:max|n)AlphaSubCycles \d+;",
             f"nAlphaSubCycles 3; transportFlux {flux};")]))
    log = foam_output(case, "granularSegregationFoam")[0]
    assert len(re.findall(r"^PIMPLE: iteration 2$", log, re.M)) == 20
    v = post.volumes(case)
    assert v["t"][-1] == pytest.approx(0.1), v["t"][-1]
    for phase in ("air", "small", "large"):
        drift = np.max(np.abs(v[phase] / v[phase][0] - 1))
        assert drift < 1e-10, (phase, drift)
    lo, hi = post.bounds(case)
    assert lo > -1e-10 and hi < 1 + 1e-10, (lo, hi)


@pytest.fixture(scope="module")
def drum_run(foam_env):
    """A 10 x 10 drum run to 0.2 s with writes at 0.1 and 0.2 s (moving
    mesh: the points are written with the fields)."""
    case = small_drum(f"{HERE}/roundTrip", n=10, end_time="0.2",
                      write_interval="0.1", adjust=True)
    foam(case, "granularSegregationFoam")
    return case


def _points(case, time_name):
    """The point list of case/time_name/polyMesh/points (ascii), as text."""
    text = (case / time_name / "polyMesh" / "points").read_text()
    m = re.search(r"\n\d+\n\(.*\)", text, re.S)
    assert m, f"no points in {case}/{time_name}"
    return m.group()


@pytest.mark.parametrize("method", ["scotch", "metis"])
def test_decompose_reconstruct_round_trip(drum_run, method, tmp_path):
    """decomposePar then reconstructPar gives back every field of every
    time, value for value.  v1912's decomposePar does not split the moved
    points of a time: a parallel restart from such a time is refused with
    a message, not run on the mesh of t = 0."""
    case = tmp_path / "case"
    shutil.copytree(drum_run, case)
    set_decomposition(case, method)
    log = foam_output(case, "decomposePar", "-time", "0:")[0]
    assert f"decompositionMethod {method}" in log, log[-2000:]
    times = ["0", "0.1", "0.2"]
    for t in times:
        assert (case / "processor1" / t).is_dir(), (method, t)
        shutil.rmtree(case / t)
    foam(case, "reconstructPar", "-withZero", "-time", "0:")
    for t in times:
        diff = _max_relative_difference(drum_run, case, t)
        assert diff and max(diff.values()) == 0, (method, t, diff)

    res = run(["mpirun", "-np", "2", "granularSegregationFoam", "-parallel"],
              case, timeout=300)
    out = res.stdout + res.stderr
    assert res.returncode > 0, out[-2000:]
    assert "FOAM FATAL" in out and "polyMesh/points" in out, out[-2000:]


def test_parallel_moved_points(drum_run, tmp_path):
    """A 2-rank run of the same drum from t = 0: reconstructPar writes the
    moved points of every time, equal to the serial run's (both follow the
    solid-body rotation of the time)."""
    case = tmp_path / "case"
    shutil.copytree(drum_run, case)
    for t in ("0.1", "0.2"):
        shutil.rmtree(case / t)
    foam(case, "decomposePar")
    foam(case, "mpirun", "-np", "2", "granularSegregationFoam", "-parallel")
    foam(case, "reconstructPar")
    for t in ("0.1", "0.2"):
        assert _points(case, t) == _points(drum_run, t), t


def _degenerate(name, edits):
    """An 8 x 8 drum run for 0.2 s after the edits (file, regex,
    replacement); returns the case."""
    case = small_drum(f"{HERE}/{name}", n=8, end_time="0.2",
                      write_interval="0.1", adjust=True)
    for path, pattern, replacement in edits:
        edit(case / path, [(pattern, replacement)])
    if any(path in (SETUP, "constant/dynamicMeshDict")
           for path, _, _ in edits):
        shutil.rmtree(case / "0")
        shutil.copytree(case / "0.orig", case / "0")
        foam(case, "setGranularFields")
    foam(case, "granularSegregationFoam")
    return case


SETUP = "system/setGranularFieldsDict"
DEGENERATE = {
    "pure-air": [(SETUP, r"point\s+\([^)]*\);", "point (0 -1 0);")],
    "pure-grains": [(SETUP, r"point\s+\([^)]*\);", "point (0 1 0);")],
    # the air then needs a direction of its own (antiGravity is refused)
    "zero-gravity": [("constant/g", r"value\s+\([^)]*\);",
                      "value (0 0 0);"),
                     ("constant/granularProperties",
                      r"direction\s+antiGravity;", "direction (0 1 0);")],
    # the drum monitor then needs the period of (7.6) given
    "zero-shear": [("constant/dynamicMeshDict", r"omega\s+[^;]+;",
                    "omega 0;"),
                   ("system/controlDict", r"(surfaceRadius[^\n]*\n)",
                    r"\g<1>        period 10;\n")],
}


@pytest.mark.parametrize("name", list(DEGENERATE))
def test_degenerate_state(foam_env, name):
    """Pure air, pure grains, zero gravity and a drum at rest run to the
    end: every field finite, every volume conserved to 1e-10, every
    fraction in [-1e-10, 1 + 1e-10] and summing to 1 within 1e-10."""
    case = _degenerate(name, DEGENERATE[name])
    inv = post.function_table(case, "invariants", "granularInvariants.dat")
    assert inv[-1, 0] == pytest.approx(0.2)
    balance, lo, hi = inv[:, 1:10:3], inv[:, 2:10:3], inv[:, 3:10:3]
    assert np.all(inv[:, 11] == 0), "non-finite cells"
    assert np.max(np.abs(balance)) < 1e-10, np.max(np.abs(balance))
    assert lo.min() > -1e-10 and hi.max() < 1 + 1e-10, (lo.min(), hi.max())
    assert np.max(inv[:, 10]) < 1e-10, np.max(inv[:, 10])
    U = read_field(case, "0.2", "U")
    p = read_field(case, "0.2", "p")
    air = read_field(case, "0.2", "alpha.air")
    assert np.all(np.isfinite(U)) and np.all(np.isfinite(p))
    numbers = {"max_balance": float(np.max(np.abs(balance))),
               "min_alpha": float(lo.min()), "max_alpha": float(hi.max()),
               "max_sum_error": float(np.max(inv[:, 10])),
               "max_speed": float(np.linalg.norm(U, axis=1).max()),
               "p_range": [float(p.min()), float(p.max())]}
    write_results(RESULTS / HERE, name, numbers)
    if name == "pure-air":
        assert np.all(air == 1)
    if name == "pure-grains":
        assert np.all(air == 0)
        # Without air the pressure is levelled at its minimum: p - rho^a g y
        # vanishes at the top and the grains carry their weight, rho* Phi g
        # over the height between the highest and lowest cell centres
        y = cell_centres(case, "0.2")[:, 1]
        rel = p + RHO_AIR * G * y
        assert abs(rel.min()) < 1e-9 * p.max(), rel.min()
        weight = 2500 * 0.6 * G * (y.max() - y.min())
        assert p.max() == pytest.approx(weight, rel=0.01), (p.max(), weight)
    if name == "zero-shear":
        # The bed at rest stays at rest: measured 2e-10 m/s, the pressure
        # solver's residual flow (the turning drum's walls move 0.063 m/s)
        assert numbers["max_speed"] < 1e-6, numbers["max_speed"]


def _viscous_parts(log):
    """The viscous part of (4.11) of each step in a solver log."""
    return [float(v) for v in re.findall(r"\nCFL \(4\.11\) max: .*? viscous "
                                         rf"= ({NUMBER})", log)]


# What the solver logs once it has read granularProperties again
REREAD = "the air, the rheology, the segregation and the diffusion laws"


def test_granular_properties_read_while_running(foam_env):
    """With runTimeModifiable, an edit of constant/granularProperties
    during a run takes effect: etaMax halved from 300 to 150 Pa s halves the
    viscous part of (4.11), which the capped viscosity of the drum's static
    grains sets, from the step after the log says it re-read the file; a
    grain phase renamed during the run stops it with a FatalIOError naming
    the dictionary, without a stack trace."""
    case = small_drum(f"{HERE}/modifiable", n=8, end_time="100",
                      write_interval="100", delta_t="1e-4",
                      controls=[(r"\nrunTimeModifiable\s+\w+;",
                                 "\nrunTimeModifiable yes;\n"
                                 "OptimisationSwitches "
                                 "{ fileModificationSkew 0; }")])
    props = case / "constant" / "granularProperties"

    def run_and_edit(old, new):
        log_path = case / "log.modifiable"
        with open(log_path, "w") as log:
            proc = subprocess.Popen(["granularSegregationFoam"], cwd=case,
                                    stdout=log, stderr=subprocess.STDOUT)
            try:
                _wait_for(log_path, proc, lambda t: t.count("\nTime = ") >= 20)
                text = props.read_text()
                assert old in text, old
                props.write_text(text.replace(old, new, 1))
                _wait_for(log_path, proc, lambda t: REREAD in t
                          or "FOAM FATAL" in t or proc.poll() is not None)
                _wait_for(log_path, proc, lambda t: proc.poll() is not None
                          or t.split(REREAD, 1)[-1].count("\nTime = ")
                          >= 5)
            finally:
                if proc.poll() is None:
                    proc.kill()
                proc.wait()
        return proc.returncode, log_path.read_text()

    rc, log = run_and_edit("etaMax          $etaMax;", "etaMax          150;")
    assert REREAD in log and "FOAM FATAL" not in log, log[-3000:]
    before, after = log.split(REREAD, 1)
    v0, v1 = _viscous_parts(before)[-1], _viscous_parts(after)
    assert len(v1) >= 2, after[-2000:]
    assert v1[-1] == pytest.approx(0.5 * v0, rel=0.01), (v0, v1)
    write_results(RESULTS / HERE, "modifiable",
                  {"viscous_part_before": v0, "viscous_part_after": v1[-1]})

    props.write_text(props.read_text().replace("etaMax          150;",
                                               "etaMax          $etaMax;"))
    rc, log = run_and_edit("grains\n{\n    small\n", "grains\n{\n    fine\n")
    assert rc == 1, (rc, log[-3000:])
    message = log[log.index("FOAM FATAL IO ERROR"):]
    assert "grains" in message and "changed during the run" in message, \
        message[:2000]
    assert "printStack" not in log and "#0 " not in log, log[-3000:]


def _wait_for(log_path, proc, ready, timeout=120):
    """Poll the log until ready(text) holds; fail after timeout seconds."""
    start = time.monotonic()
    while time.monotonic() - start < timeout:
        text = log_path.read_text()
        if ready(text):
            return text
        if proc.poll() is not None and not ready(text):
            raise AssertionError(f"the solver ended (exit {proc.returncode})"
                                 f":\n{text[-3000:]}")
        time.sleep(0.2)
    raise AssertionError(f"timed out:\n{log_path.read_text()[-3000:]}")

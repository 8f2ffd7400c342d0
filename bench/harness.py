"""One-step convergence harness of the pressure-velocity-stress coupling.

From a written state of a case it runs a few time steps at a fixed step
with a coupling setting, and compares the fields reached with those of a
reference coupling (200 PISO correctors, p_rgh solved to 1e-13 every
time) run from the same state over the same steps:

- the relative L2 error of U over the grains (alpha.air < 1/2 in the
  reference) and over the air, separately;
- the largest |w| (the velocity normal to the base) in the air, against
  the reference's;
- the relative L2 error of p in the row of cells along the base;
- the relative L2 error of U over the grains of the last ten columns
  (the chute's outlet);
- the pressure solutions per step and the CPU milliseconds per step.

    bench/harness states [--states chute1 layer2d ...]
    bench/harness run [--states ...] [--dt 1e-3 4e-3] [--steps 1 10]
                      [--couplings PISO-4 PISO-10 SIMPLEC-1 Krylov-BFBt-10 ...]
                      [--edit DICT:ENTRY=VALUE ...] [--label NAME]
    bench/harness chute [--couplings ...] [--end-time 25] [--sub-cycles M]
                        [--max-delta-t DT] [--edit DICT:ENTRY=VALUE ...]
    bench/harness drum --source RUN --start T [--couplings ...]
                       [--edit DICT:ENTRY=VALUE ...]
    bench/harness spectrum [--states ...] [--dt 4e-3] [--preconditioners ...]

`chute` runs the whole chute tutorial from rest with each coupling and
records its cost and its outflow against the exact solutions under
"whole_chute"; `drum` runs one revolution of the square drum from a
written time of a decomposed drum run with each coupling and records its
cost, J, surface angle, peak speed and grain pressure against the run's
own over the same revolution under "whole_drum".

A state named RUN@TIME is the written time TIME of the run in the
directory RUN (reconstructed, serial): `states --states RUN@TIME` copies
it, so that a coupling can be judged on a developed flow of a long run.

`states` writes the states into bench/work/harness/states (git-ignored);
`run` appends its measurements to bench/coupling.json under "harness"
(an entry with the same state, step, steps, coupling and edits is
replaced).  --edit changes a dictionary of the case (for example
constant/granularProperties:air.eta=1e-2; system/fvSolution:
maxAlphaSubCycles=M sets the phases' sub-cycles, nLimiterIter=N their
limiter's iterations, nAlphaSubCycles=N a fixed number of sub-cycles,
transportFlux=midStep the flux they are transported with;
system/fvSolution:solvers."(U|UFinal)"={...}
replaces a solver entry whose name is a regular expression): `states --edit` runs the
state with it from the start, and `run --edit` runs the candidates and their
reference with it from that state, so that a change of the model is
judged against its own converged step.  See bench/README.md.
"""
import argparse
import datetime
import hashlib
import json
import math
import platform
import re
import shutil
import signal
import statistics
import subprocess
import sys
from pathlib import Path

import numpy as np

from granularfoam.foamio import (cell_centres, edit, log_cost, parameters as
                                 read_parameters, read_field, read_text,
                                 run as foam, set_entry, time_names)
from granularfoam.post import drum

ROOT = Path(__file__).resolve().parent.parent

WORK = ROOT / "bench" / "work" / "harness"
RESULTS = ROOT / "bench" / "coupling.json"
SOLVER = "granularSegregationFoam"
GRAINS = 0.5                    # alpha.air below this is grains
OUTLET_COLUMNS = 10

# The reference: PISO with 200 correctors, every p_rgh solution to 1e-13,
# the coupling named REFERENCE_NAME
REFERENCE_NAME = "reference"
REFERENCE = {
    "PIMPLE.pressureCoupling": "PISO",
    "PIMPLE.nCorrectors": 200,
    "PIMPLE.pRghTolerance": 0,
    "solvers.p_rgh.tolerance": 1e-13,
    "solvers.p_rgh.relTol": 0,
    "solvers.p_rghFinal.tolerance": 1e-13,
    "solvers.p_rghFinal.relTol": 0,
}
# The case's own coupling, as its fvSolution gives it
TUTORIAL_NAME = "tutorial"
# The drum's reference revolution (bench/harness drum): the Krylov coupling
# converged to 1e-3 at the chute reference's step, the phases transported in
# the momentum step; PISO is no reference on the drum (doc/solver.md)
DRUM_REFERENCE = ("Krylov-CahouetChabard-30-tol1e-3",
                  ("system/fvSolution:maxAlphaSubCycles=0",
                   "system/controlDict:maxDeltaT=1e-3"))
# The files of a drum case that set its coupling, schemes and time control
DRUM_FILES = ("system/fvSolution", "system/fvSchemes", "system/controlDict")


# --------------------------------------------------------------------------
# States
# --------------------------------------------------------------------------

def _outputs(directory, names):
    """What a case wrote (time directories, logs, decompositions, figures):
    left out of copies of the case."""
    return [n for n in names if re.fullmatch(r"[0-9.eE+-]+", n)
            or n.startswith(("log.", "processor")) or n in
            ("figures", "postProcessing", "movingFrame", "VTK")]


def _chute(end_time):
    """The chute tutorial (155 x 40) from rest to end_time, serial."""
    def make(case):
        shutil.copytree(ROOT / "tutorials" / "chute", case,
                        ignore=_outputs)
        set_entry(case, "system/chuteParameters", "endTime", end_time)
        set_entry(case, "system/chuteParameters", "writeInterval", end_time)
        shutil.copytree(case / "0.orig", case / "0")
        foam(case, "blockMesh")
        return end_time
    return make


def _layer2d(case, end_time=0.2, columns=10, length=0.04, h=5e-3,
             amplitude=0.1):
    """The periodic inclined layer on `columns` columns of 4 mm x 0.1 mm
    cells (the chute's aspect ratio is 26, this 40), its surface a sine of
    +-amplitude*h over the length; run from rest to end_time."""
    shutil.copytree(ROOT / "validation" / "cases" / "inclinedLayer", case,
                    ignore=_outputs)
    mm = 1e3 * length
    block = case / "system" / "blockMeshDict"
    text = block.read_text()
    text = text.replace("(0.1 0 0) (0.1 0.1 0)", f"({mm:g} 0 0) ({mm:g} 0.1 0)")
    text = text.replace("(0.1 0 6) (0.1 0.1 6)", f"({mm:g} 0 6) ({mm:g} 0.1 6)")
    text = text.replace("(1 1 $nz)", f"({columns} 1 $nz)")
    assert text.count(f"({mm:g} ") == 4 and f"({columns} 1 $nz)" in text, (
        "the inclined layer's blockMeshDict is not the expected one")
    block.write_text(text)
    boxes = []
    for i in range(columns):
        x0, x1 = i * length / columns, (i + 1) * length / columns
        top = h * (1 + amplitude * math.sin(2 * math.pi * 0.5 * (x0 + x1)
                                            / length))
        boxes.append(
            f"boxToCell {{ box ({x0!r} -1 -1) ({x1!r} 1 {top!r}); "
            "fieldValues ( volScalarFieldValue alpha.air 0 "
            "volScalarFieldValue alpha.small 0.5 "
            "volScalarFieldValue alpha.large 0.5 ); }")
    sfd = case / "system" / "setFieldsDict"
    text = sfd.read_text()
    start = text.index("regions")
    sfd.write_text(text[:start] + "regions\n(\n    "
                   + "\n    ".join(boxes) + "\n);\n")
    for entry, value in (("PIMPLE.momentumPredictor", "yes"),
                         ("PIMPLE.viscousStress", "implicit"),
                         ("PIMPLE.nCorrectors", 20)):
        set_entry(case, "system/fvSolution", entry, value)
    for entry, value in (("endTime", end_time), ("writeInterval", end_time),
                         ("functions", "{}")):
        set_entry(case, "system/controlDict", entry, value)
    shutil.copytree(case / "0.orig", case / "0")
    foam(case, "blockMesh")
    foam(case, "setFields")
    return end_time


def _drum(end_time, n=50):
    """The square drum tutorial on n x n cells from its start to end_time
    (8.75 s: a quarter turn from the diagonal, where the rising corner
    sits highest), serial."""
    def make(case):
        shutil.copytree(ROOT / "tutorials" / "squareDrum", case,
                        ignore=_outputs)
        for entry, value in (("N", n), ("endTime", end_time),
                             ("writeInterval", end_time)):
            set_entry(case, "system/drumParameters", entry, value)
        shutil.copytree(case / "0.orig", case / "0")
        foam(case, "blockMesh")
        foam(case, "setGranularFields")
        set_entry(case, "system/controlDict", "writeCompression", "off")
        return end_time
    return make


def _layer2d_square(case):
    """The periodic layer on square cells: 41 columns of 0.1 mm x 0.1 mm
    over 4.1 mm, the same sine surface; to tell the cells' aspect ratio
    from the rest."""
    return _layer2d(case, columns=41, length=0.0041)


STATES = {
    "chute1": _chute(1),
    "chute20": _chute(20),
    "layer2d": _layer2d,
    "layer2dSquare": _layer2d_square,
    "drum50": _drum(8.75),
    "drum100": _drum(1.5, n=100),
    "drum100start": _drum(0.25, n=100),
    "drum150start": _drum(0.25, n=150),
}

# The direction normal to the base (the layers and the chute: z); none for
# the drum, whose walls turn: no base row, outlet or normal velocity there
NORMAL = {"chute1": 2, "chute20": 2, "layer2d": 2, "layer2dSquare": 2,
          "drum50": None, "drum100": None, "drum100start": None,
          "drum150start": None}


# The longest edits' part of a directory name
TAG_LENGTH = 100


def _tag(edits):
    """A directory-name part for the edits: readable, and for long edits
    (whole solver dictionaries) shortened with a hash of the whole so that
    the run directories stay within the file system's 255 characters."""
    tag = "-".join(re.sub(r"[^\w.]+", "_", e) for e in edits)
    if len(tag) <= TAG_LENGTH:
        return tag
    digest = hashlib.sha1(tag.encode()).hexdigest()[:10]
    return f"{tag[:TAG_LENGTH - 11]}_{digest}"


# A state taken from a written time of a run: RUN@TIME
RUN_STATE = re.compile(r"(.+)@([0-9.eE+-]+)")


def run_state(name):
    """(run directory, time name) of a state named RUN@TIME; None for the
    states of STATES."""
    m = RUN_STATE.fullmatch(name)
    return (Path(m.group(1)), m.group(2)) if m else None


def state_name(text):
    """argparse type of a state: a name of STATES or RUN@TIME."""
    if text in STATES or run_state(text):
        return text
    raise argparse.ArgumentTypeError(
        f"state '{text}' is not one of {', '.join(sorted(STATES))} "
        "or RUN@TIME (a written time of a run)")


def normal_of(name, edits=()):
    """The axis normal to the base of a state (None for the drum)."""
    if name in NORMAL:
        return NORMAL[name]
    drum = (state_dir(name, edits) / "system" / "drumParameters").exists()
    return None if drum else 2


def state_base(name):
    """The state's part of directory names: RUNNAME_tTIME for RUN@TIME."""
    run = run_state(name)
    return f"{run[0].name}_t{run[1]}" if run else name


def state_dir(name, edits=()):
    """The state `name` of the case with the edits made from its start
    (for RUN@TIME: made at TIME)."""
    base = state_base(name)
    return WORK / "states" / (f"{base}_{_tag(edits)}" if edits else base)


def copy_run_state(name, case):
    """Copy the written time of the run RUN@TIME (its reconstructed
    fields, constant and system) to case; return the time name."""
    run, time_name = run_state(name)
    source = run / time_name
    if not (source / "U").exists() and not (source / "U.gz").exists():
        raise ValueError(f"state {name}: no reconstructed fields in "
                         f"{source} (reconstructPar -time {time_name})")
    for part in ("constant", "system"):
        shutil.copytree(run / part, case / part)
    shutil.copytree(source, case / time_name)
    return time_name


def run_solver(case, timeout):
    """Run the solver in case, its output in case/log.<solver>; return
    (how it ended: "ok", a signal's name or "exit N", the log's text)."""
    log = case / f"log.{SOLVER}"
    with open(log, "w") as out:
        res = subprocess.run([SOLVER, "-case", str(case)], stdout=out,
                             stderr=subprocess.STDOUT, timeout=timeout)
    how = ("ok" if res.returncode == 0
           else signal.Signals(-res.returncode).name if res.returncode < 0
           else f"exit {res.returncode}")
    return how, log.read_text()


def make_state(name, edits=()):
    """Run the case of state `name`, with the edits, to its time; write its
    cell centres."""
    case = state_dir(name, edits)
    if case.exists():
        shutil.rmtree(case)
    case.parent.mkdir(parents=True, exist_ok=True)
    if run_state(name):
        copy_run_state(name, case)
        apply_edits(case, edits)
    else:
        end_time = STATES[name](case)
        apply_edits(case, edits)
        set_entry(case, "system/controlDict", "writePrecision", 17)
        print(f"harness: state {name}: running to t = {end_time} s",
              flush=True)
        how, text = run_solver(case, 6 * 3600)
        if how != "ok":
            times = re.findall(r"^Time = (\S+)", text, re.M)
            status = (f"the state failed ({how}) at t = "
                      f"{times[-1] if times else 0} s of {end_time} s")
            print(f"harness: state {name}: {status}", flush=True)
            return {"state": name, "time": float(end_time), "dt": None,
                    "steps": 0, "coupling": "state", "edits": list(edits),
                    "status": status}
    time_name = latest_time(case)
    cell_centres(case, time_name)
    print(f"harness: state {name}: t = {time_name}", flush=True)
    return None


def latest_time(case):
    """Name of the latest time directory of case that holds fields."""
    names = time_names(case)
    assert names, f"no time directory in {case}"
    return names[-1]


# --------------------------------------------------------------------------
# Runs
# --------------------------------------------------------------------------

def coupling_settings(name):
    """fvSolution entries of a coupling named like PISO-10, SIMPLEC-1 or
    Krylov-BFBt-10 (preconditioner BFBt, PISO or CahouetChabard, at most
    10 iterations; a suffix -tol1e-4 sets the tolerance, -inner1e-3
    innerRelTol); reference-N is the reference with N correctors, to
    measure how far the reference is from its own converged step;
    tutorial: none, the case's own.  A named coupling is all of the step's
    coupling: no rheology corrector and no KrylovFinal of the case's (None
    removes the entry)."""
    if name == TUTORIAL_NAME:
        return {}
    return dict(_coupling_entries(name), **{
        "PIMPLE.nRheologyCorrectors": 0, "PIMPLE.KrylovFinal": None})


def set_coupling(case, name):
    """Set the coupling name (coupling_settings) in case's fvSolution."""
    for entry, value in coupling_settings(name).items():
        set_entry(case, "system/fvSolution", entry, value)


def _coupling_entries(name):
    """The entries that make the coupling name (coupling_settings)."""
    if name == REFERENCE_NAME:
        return dict(REFERENCE)
    m = re.fullmatch(r"reference-(\d+)", name)
    if m and int(m.group(1)) >= 1:
        return dict(REFERENCE, **{"PIMPLE.nCorrectors": int(m.group(1))})
    m = re.fullmatch(r"Krylov-(BFBt|PISO|CahouetChabard)-(\d+)"
                     r"(?:-tol([0-9.e-]+))?"
                     r"(?:-inner([0-9.e-]+))?", name)
    if m and int(m.group(2)) >= 1:
        settings = {"PIMPLE.pressureCoupling": "Krylov",
                    "PIMPLE.Krylov": "{}",
                    "PIMPLE.Krylov.preconditioner": m.group(1),
                    "PIMPLE.Krylov.maxIter": int(m.group(2))}
        if m.group(3):
            settings["PIMPLE.Krylov.tolerance"] = m.group(3)
        if m.group(4):
            settings["PIMPLE.Krylov.innerRelTol"] = m.group(4)
        return settings
    m = re.fullmatch(r"(PISO|SIMPLEC)-(\d+)", name)
    if not m or int(m.group(2)) < 1:
        raise ValueError(f"coupling '{name}' is not PISO-N, SIMPLEC-N "
                         "(N >= 1), Krylov-BFBt-N, Krylov-PISO-N, "
                         "Krylov-CahouetChabard-N, reference, "
                         "reference-N or tutorial")
    return {"PIMPLE.pressureCoupling": m.group(1),
            "PIMPLE.nCorrectors": int(m.group(2))}


def parse_edit(text):
    m = re.fullmatch(r"([\w./]+):([\w.()|\"*-]+)=(.+)", text)
    if not m:
        raise ValueError(f"edit '{text}' is not DICT:ENTRY=VALUE")
    return m.group(1), m.group(2), m.group(3)


def apply_edit(case, dictionary, entry, value):
    """Set the entry of a dictionary of case.  maxAlphaSubCycles,
    nAlphaSubCycles, nLimiterIter and transportFlux of system/fvSolution go
    to the phases' solver entry, whose name is a regular expression
    ("alpha.*") that foamDictionary cannot scope: M sub-cycles at most, or 0
    for the transport in the momentum step (nAlphaSubCycles 1); N
    sub-cycles every step; the MULES limiter's iterations; the flux the
    phases are transported with (a word the solver checks)."""
    if dictionary == "system/fvSolution" and entry.startswith("solvers."):
        replace_solver(case, entry[len("solvers."):], value)
        return
    if dictionary != "system/fvSolution" or entry not in (
            "maxAlphaSubCycles", "nAlphaSubCycles", "nLimiterIter",
            "transportFlux"):
        set_entry(case, dictionary, entry, value)
        return
    fvSolution = case / "system" / "fvSolution"
    if entry == "transportFlux":
        if not re.fullmatch(r"\w+", value):
            raise ValueError(f"{entry}={value}: not a word")
        if re.search(r"transportFlux\s+\w+;", fvSolution.read_text()):
            edit(fvSolution, [(r"transportFlux\s+\w+;",
                               f"transportFlux {value};")])
        else:
            edit(fvSolution, [(r"((?:max|n)AlphaSubCycles\s+\d+;)",
                               rf"\1 transportFlux {value};")])
        return
    if entry != "maxAlphaSubCycles" and int(value) < 1:
        raise ValueError(f"{entry}={value}: not a positive integer")
    if entry == "nLimiterIter":
        edit(fvSolution,
             [(r"nLimiterIter\s+\d+;", f"nLimiterIter {int(value)};")])
        return
    if entry == "maxAlphaSubCycles" and int(value) == 0:
        entry, value = "nAlphaSubCycles", 1
    edit(fvSolution,
         [(r"(?:max|n)AlphaSubCycles\s+\d+;", f"{entry} {int(value)};")])


def replace_solver(case, key, value):
    """Replace the entry `key { ... }` (without sub-dictionaries) of
    fvSolution's solvers by `key value`, for the keys that foamDictionary
    cannot scope (regular expressions such as "(U|UFinal)" or "pcorr.*",
    which -set rewrites into an entry of their first match).  value is a
    dictionary in braces.  A key that is a field's name (a word) and not
    there is added first in solvers: OpenFOAM takes a literal key before
    the regular expressions, so `U` alone gives the Krylov coupling's
    inner momentum solutions their own solver while the predictor keeps
    "(U|UFinal)"'s (it solves UFinal in the final outer iteration).  A
    regular expression that is not there is refused."""
    if not re.fullmatch(r"\{.*\}", value.strip()):
        raise ValueError(f"solvers.{key}={value}: not a dictionary in braces")
    fvSolution = case / "system" / "fvSolution"
    entry = r"^([ \t]*)" + re.escape(key) + r"\s*\{[^{}]*\}"
    if re.fullmatch(r"\w+", key) and not re.search(
            entry, fvSolution.read_text(), flags=re.M):
        edit(fvSolution,
             [(r"^(solvers\s*\{[ \t]*\n)",
               lambda m: f"{m.group(1)}    {key} {value.strip()}\n")],
             flags=re.M)
        return
    edit(fvSolution,
         [(entry, lambda m: f"{m.group(1)}{key} {value.strip()}")],
         flags=re.M)


def apply_edits(case, edits):
    """Make every DICT:ENTRY=VALUE edit in case."""
    for dictionary, entry, value in map(parse_edit, edits):
        apply_edit(case, dictionary, entry, value)


def run_name(state, dt, steps, coupling, edits):
    return (f"{state_base(state)}_dt{dt:g}_n{steps}_{coupling}"
            + (f"_{_tag(edits)}" if edits else ""))


def run_steps(state, dt, steps, coupling, edits, debug=False):
    """Run `steps` steps of dt from the state with the coupling and edits
    (debug: the Krylov coupling's debug switch on); return (case, status,
    pressure solutions per step, CPU ms per step)."""
    source = state_dir(state, edits)
    t0 = latest_time(source)
    case = WORK / "runs" / run_name(state, dt, steps, coupling, edits)
    if case.exists():
        shutil.rmtree(case)
    case.mkdir(parents=True)
    for part in ("constant", "system", t0):
        shutil.copytree(source / part, case / part)
    end = float(t0) + steps * dt
    for entry, value in (("startFrom", "latestTime"),
                         ("adjustTimeStep", "no"), ("deltaT", repr(dt)),
                         ("endTime", repr(end)),
                         # once, at the end: runTime counts from the start
                         # time (a restart keeps its time index, so an
                         # interval of `steps` time steps need not end on
                         # the last); writing every step cost more than a
                         # step
                         ("writeControl", "runTime"),
                         ("writeInterval", repr(end - float(t0))),
                         ("writePrecision", 17),
                         ("timePrecision", 10), ("functions", "{}")):
        set_entry(case, "system/controlDict", entry, value)
    set_coupling(case, coupling)
    if debug:
        set_entry(case, "system/controlDict", "DebugSwitches",
                  "{ granularKrylovCoupling 1; }")
    # The edits are in the state's files already
    how, text = run_solver(case, 3600)
    solutions = [int(n) for n in
                 re.findall(r"Pressure coupling: (\d+) pressure solutions",
                            text)]
    cpu = [float(s) for s in re.findall(r"^ExecutionTime = ([0-9.eE+-]+) s",
                                        text, re.M)]
    if how != "ok" or len(solutions) != steps:
        fatal = re.findall(r"^--> FOAM FATAL.*\n+(.*)", text, re.M)
        return case, (f"failed ({how}) after {len(solutions)} of {steps} "
                      "steps" + (f": {fatal[-1].strip()}" if fatal
                                 else "")), None, None
    last = float(latest_time(case))
    assert math.isclose(last, end, rel_tol=1e-9), (
        f"{case}: the last written time {last} is not the end {end}")
    ms = (1e3 * (cpu[-1] - cpu[0]) / (steps - 1)) if steps > 1 else None
    return case, "ok", sum(solutions) / steps, ms


def _rel(a, b):
    """Relative L2 norm of a - b against b (NaN if b is zero)."""
    norm = float(np.sqrt(np.sum(np.square(b))))
    err = float(np.sqrt(np.sum(np.square(a - b))))
    return err / norm if norm > 0 else (0.0 if err == 0 else math.nan)


def compare(case, ref, source, normal=2):
    """Errors of the fields of case against ref (both at their last time),
    on the cell centres of the state `source`; `normal` the axis normal to
    the base (None: no base, outlet or normal velocity)."""
    C = read_field(source, latest_time(source), "C")
    t, tr = latest_time(case), latest_time(ref)
    assert math.isclose(float(t), float(tr), rel_tol=1e-9), (
        f"{case} ended at {t}, its reference at {tr}")
    U, Ur = read_field(case, t, "U"), read_field(ref, tr, "U")
    p, pr = read_field(case, t, "p"), read_field(ref, tr, "p")
    grains = read_field(ref, tr, "alpha.air") < GRAINS
    air = ~grains
    out = {
        "finite": bool(np.all(np.isfinite(U)) and np.all(np.isfinite(p))),
        "l2_u_grains": _rel(U[grains], Ur[grains]),
        "l2_u_air": _rel(U[air], Ur[air]),
        "min_p_grains": float(p[grains].min()),
        "min_p_grains_reference": float(pr[grains].min()),
        "max_w_air": None, "max_w_air_reference": None,
        "l2_p_base": None, "l2_u_last_columns": None,
    }
    if normal is None:
        return out
    z = C[:, normal]
    base = z < z.min() + 0.5 * np.min(np.diff(np.unique(np.round(z, 12))))
    xs = np.unique(np.round(C[:, 0], 12))
    outlet = grains & (C[:, 0] >= xs[max(0, len(xs) - OUTLET_COLUMNS)]
                       - 1e-12)
    out.update({
        "max_w_air": (float(np.max(np.abs(U[air, normal])))
                      if air.any() else 0.0),
        "max_w_air_reference": (float(np.max(np.abs(Ur[air, normal])))
                                if air.any() else 0.0),
        "l2_p_base": _rel(p[base], pr[base]),
        "l2_u_last_columns": (_rel(U[outlet], Ur[outlet])
                              if len(xs) > OUTLET_COLUMNS and outlet.any()
                              else None),
    })
    return out


def _rounded(d):
    return {k: (float(f"{v:.3g}") if isinstance(v, float)
                and math.isfinite(v) else v) for k, v in d.items()}


def reference(state, dt, steps, edits, references, name=REFERENCE_NAME):
    """(case, pressure solutions per step, CPU ms per step) of the
    reference coupling `name` from the state with the edits, run once and
    cached; a failed reference gives its status in the place of the
    case."""
    key = (state, dt, steps, tuple(edits), name)
    if key not in references:
        case, status, sol, ms = run_steps(state, dt, steps, name, edits)
        references[key] = (case if status == "ok" else status, sol, ms)
    return references[key]


def measure(state, dt, steps, coupling, edits, references,
            reference_name=REFERENCE_NAME):
    """One candidate against its reference (the coupling reference_name)."""
    ref, ref_sol, ref_ms = reference(state, dt, steps, edits, references,
                                     reference_name)
    entry = {"state": state,
             "time": float(latest_time(state_dir(state, edits))),
             "dt": dt, "steps": steps, "coupling": coupling,
             "edits": list(edits), "reference": reference_name}
    reference_ok = not isinstance(ref, str)
    if coupling == reference_name:
        entry.update(status="ok" if reference_ok else ref,
                     pressure_solutions_per_step=ref_sol,
                     cpu_ms_per_step=ref_ms)
        return _rounded(entry)
    case, status, sol, ms = run_steps(state, dt, steps, coupling, edits)
    if status == "ok" and not reference_ok:
        status = f"ok, but the reference {ref}"
    entry.update(status=status, pressure_solutions_per_step=sol,
                 cpu_ms_per_step=ms, reference_cpu_ms_per_step=ref_ms)
    if status == "ok":
        entry.update(compare(case, ref, state_dir(state, edits),
                             normal_of(state, edits)))
    return _rounded(entry)


def spectrum(state, dt, preconditioner, edits):
    """The Ritz values of the preconditioned operator in one step from the
    state: the eigenvalues of the Hessenberg matrix of a Krylov solution
    of up to 30 iterations (the granularKrylovCoupling debug switch logs
    it). All near 1: the preconditioner is near the inverse; spread over
    [a, b]: GMRES needs about sqrt(b/a) times more iterations."""
    coupling = f"Krylov-{preconditioner}-30-tol1e-6"
    case, status, sol, ms = run_steps(state, dt, 1, coupling, edits,
                                      debug=True)
    entry = {"state": state, "time": float(latest_time(state_dir(state,
                                                                 edits))),
             "dt": dt, "preconditioner": preconditioner,
             "edits": list(edits), "status": status}
    if status != "ok":
        return entry
    text = (case / f"log.{SOLVER}").read_text()
    blocks = text.split("Krylov coupling: Hessenberg matrix")
    assert len(blocks) > 1, f"{case}: no Hessenberg matrix in the log"
    rows = []
    for line in blocks[-1].splitlines()[1:]:
        if not line.strip():
            break
        rows.append([float(x) for x in line.split()])
    H = np.array(rows)
    k = H.shape[1]
    ritz = np.linalg.eigvals(H[:k, :k])
    ritz = ritz[np.argsort(-np.abs(ritz))]
    last = re.findall(r"^Krylov coupling: \S+, (\d+) iterations .*?, "
                      r"residual (\S+) -> (\S+) m/s", text, re.M)[-1]
    entry.update(iterations=int(last[0]),
                 relative_residual=float(f"{float(last[2]) / float(last[1]):.3g}"),
                 ritz_largest=float(f"{abs(ritz[0]):.3g}"),
                 ritz_smallest=float(f"{abs(ritz[-1]):.3g}"),
                 ritz=[[float(f"{z.real:.3g}"), float(f"{z.imag:.3g}")]
                       for z in ritz])
    return entry


def store_spectra(entries, command):
    store_runs(
        "krylov_spectra",
        "Ritz values (real, imaginary) of the Krylov coupling's "
        "preconditioned operator in one step of dt from a state "
        "(bench/harness spectrum): the eigenvalues of the Hessenberg matrix "
        "of up to 30 FGMRES iterations. The nearer all are to 1, the better "
        "the preconditioner; relative_residual is the reduction reached.",
        lambda e: (e["state"], e["dt"], e["preconditioner"],
                   tuple(e["edits"])),
        entries, command)


def machine():
    model = ""
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            model = line.split(":", 1)[1].strip()
            break
    return f"{platform.node()}: {model}, {len(list(Path('/sys/devices/system/cpu').glob('cpu[0-9]*')))} cores"


def store_runs(section, description, key, entries, command):
    """Merge entries, stamped with the date, the machine and the command,
    into bench/coupling.json[section]["runs"]; an entry with the same key
    replaces the older one."""
    data = json.loads(RESULTS.read_text()) if RESULTS.exists() else {}
    part = data.setdefault(section, {})
    part["description"] = description
    runs = part.setdefault("runs", [])
    new = {key(e) for e in entries}
    stamp = {"date": datetime.date.today().isoformat(), "machine": machine(),
             "command": command}
    runs[:] = [e for e in runs if key(e) not in new] + [
        dict(e, **stamp) for e in entries]
    RESULTS.write_text(json.dumps(data, indent=1) + "\n")


def store(entries, command):
    store_runs(
        "harness",
        "One-step convergence harness (bench/harness, bench/README.md): "
        "from a written state, `steps` fixed steps of `dt` with a coupling, "
        "against the reference coupling from the same state: `reference` "
        "(PISO, 200 correctors, p_rgh to 1e-13) unless the entry's "
        "`reference` names another coupling. l2_u_grains / l2_u_air: relative L2 of "
        "U over the grains (alpha.air < 1/2) / the air; max_w_air: largest "
        "|U_z| in the air; l2_p_base: relative L2 of p along the base; "
        "l2_u_last_columns: relative L2 of U over the grains of the last "
        "ten columns; min_p_grains: the lowest p in the grains (and the "
        "reference's); cpu_ms_per_step over steps 2 to `steps`, serial.",
        lambda e: (e["state"], e["dt"], e["steps"], e["coupling"],
                   tuple(e["edits"]), e.get("reference", REFERENCE_NAME)),
        entries, command)


def whole_chute(coupling, end_time, sub_cycles, max_delta_t, edits):
    """The chute tutorial from rest to end_time, serial, with the coupling
    (and, if given, maxAlphaSubCycles and maxDeltaT, then the edits); the
    steady outflow against the exact solutions (granularfoam.post.chute)
    and the cost."""
    tag = "_".join(filter(None, [
        coupling, f"sub{sub_cycles}" if sub_cycles is not None else "",
        f"dt{max_delta_t:g}" if max_delta_t else "",
        _tag(edits) if edits else ""]))
    case = WORK / "chute" / tag
    if case.exists():
        shutil.rmtree(case)
    case.parent.mkdir(parents=True, exist_ok=True)
    shutil.copytree(ROOT / "tutorials" / "chute", case,
                    # what a run of the tutorial left in it
                    ignore=shutil.ignore_patterns(
                        "0", "[1-9]*", "log.*", "postProcessing",
                        "processor*", "VTK", "figures", "movingFrame",
                        "decomposeParDict.np*"))
    set_entry(case, "system/chuteParameters", "endTime", end_time)
    set_coupling(case, coupling)
    if sub_cycles is not None:
        apply_edit(case, "system/fvSolution", "maxAlphaSubCycles",
                   sub_cycles)
    if max_delta_t:
        set_entry(case, "system/controlDict", "maxDeltaT", max_delta_t)
    apply_edits(case, edits)
    shutil.copytree(case / "0.orig", case / "0")
    foam(case, "blockMesh")
    print(f"harness: chute {tag}: running to t = {end_time} s", flush=True)
    how, text = run_solver(case, 12 * 3600)
    return chute_entry(case, how, text, coupling, end_time, sub_cycles,
                       max_delta_t, edits)


def chute_entry(case, how, text, coupling, end_time, sub_cycles, max_delta_t,
                edits):
    """The whole_chute entry of a run of the chute in case that ended as
    `how` with the log `text`."""
    from granularfoam.post.chute import outflow
    entry = {"coupling": coupling, "end_time": float(end_time),
             "max_alpha_sub_cycles": sub_cycles,
             "max_delta_t": max_delta_t, "edits": list(edits)}
    entry.update(log_cost(text))
    if how != "ok":
        times = re.findall(r"^Time = (\S+)", text, re.M)
        entry["status"] = (f"failed ({how}) at t = "
                           f"{times[-1] if times else 0} s")
        return entry
    try:
        numbers, _ = outflow(case)
    except AssertionError as err:
        entry["status"] = f"ran; no outflow to measure: {err}"
        return entry
    numbers.pop("dz")
    entry.update(status="ok", **{k: float(f"{v:.6g}")
                                 for k, v in numbers.items()})
    shares = profile_shares(case)
    if shares:
        entry["profile_shares"] = shares
    return entry


def profile_shares(case, smallest=0.01):
    """With OpenFOAM's profiling on (controlDict profiling { active true;
    }): each profiled section's share of the time loop's wall time in
    <latest time>/uniform/profiling, the sections of at least `smallest`;
    None without profiling.  A section's share includes its children's."""
    path = case / latest_time(case) / "uniform" / "profiling"
    if not path.is_file():
        return None
    sections = re.findall(r'description\s+"([^"]*)";\s*calls\s+\d+;'
                          r'\s*totalTime\s+([0-9.eE+-]+);', path.read_text())
    loop = [float(t) for d, t in sections if d.startswith("time.run()")]
    assert loop, f"{path}: no time loop"
    shares = {}
    for description, seconds in sections:
        share = float(seconds) / loop[0]
        # lduMatrix::solver.*: v1912 times a solver over the life of its
        # object (GAMG's coarsest-level solver spans its parent's solution)
        if share >= smallest and not description.startswith(
                ("application::", "time.run()", "lduMatrix::solver.")):
            # the same section under two parents: their sum
            shares[description] = round(shares.get(description, 0) + share,
                                        3)
    return shares


def store_whole(entries, command):
    store_runs(
        "whole_chute",
        "The chute tutorial (155 x 40) from rest to end_time, serial, with "
        "a coupling (bench/harness chute): steps, CPU seconds, pressure "
        "solutions per step, and the outflow at the end against Bagnold "
        "(5.4), Gray & Chugunov (5.8) and (5.10) with its change over the "
        "last written second (granularfoam.post.chute outflow).",
        lambda e: (e["coupling"], e["end_time"], e["max_alpha_sub_cycles"],
                   e["max_delta_t"], tuple(e["edits"])),
        entries, command)


def whole_drum(source, start, coupling, edits, duration=None,
               files=None):
    """One revolution of a drum run from its written time `start`, on the
    source run's decomposition: the source's case (its processor
    directories at `start`) with the coupling and the edits; the
    rotatingDrum monitor over the revolution against the source run's
    over the same window (granularfoam.post.drum).  With a duration
    shorter than a revolution, the run of that duration and its cost
    alone.  files: a case whose system/fvSolution, fvSchemes and
    controlDict replace the source's before the coupling and the edits
    (bench/run's drum part: the tutorial's)."""
    duration = duration or drum.PERIOD
    end = start + duration
    source = Path(source).resolve()
    ranks = sorted(source.glob("processor[0-9]*"))
    assert ranks, f"{source}: no processor directories"
    start_name = _written(ranks[0], start)
    n = int(read_parameters(source, "drumParameters")["N"])
    case = WORK / "drum" / "_".join(filter(None, [
        f"N{n}", f"t{start:g}",
        f"d{duration:g}" if duration != drum.PERIOD else "",
        f"files-{Path(files).name}" if files else "", coupling,
        _tag(edits)]))
    if case.exists():
        shutil.rmtree(case)
    shutil.copytree(source, case, ignore=_state_of_run(source, start_name))
    if files:
        for name in DRUM_FILES:
            shutil.copyfile(Path(files) / name, case / name)
    set_entry(case, "system/drumParameters", "endTime", end)
    set_entry(case, "system/drumParameters", "writeInterval", duration)
    set_coupling(case, coupling)
    apply_edits(case, edits)
    print(f"harness: drum {case.name}: {len(ranks)} ranks, t = {start_name} "
          f"to {end:g} s", flush=True)
    with open(case / f"log.{SOLVER}", "w") as out:
        rc = subprocess.call(
            ["mpirun", "-np", str(len(ranks)), SOLVER, "-parallel",
             "-case", str(case)], stdout=out, stderr=subprocess.STDOUT)
    return drum_entry(case, source, start, end, coupling, edits, rc)


def drum_entry(case, source, start, end, coupling, edits, rc):
    """The whole_drum entry of the run in case of the source run from start
    to end, which ended with exit code rc."""
    source = Path(source).resolve()
    entry = {"source": str(source),
             "N": int(read_parameters(source, "drumParameters")["N"]),
             "start": start, "end": end,
             "source_coupling": drum.coupling(source), "coupling": coupling,
             "edits": list(edits),
             "ranks": len(list(source.glob("processor[0-9]*")))}
    entry.update(log_cost((case / f"log.{SOLVER}").read_text()))
    shares = profile_shares(case / "processor0")
    if shares:
        entry["profile_shares"] = shares
    if rc != 0:
        entry["status"] = f"failed (exit {rc})"
        return entry
    if end - start < drum.PERIOD - 1e-9:
        entry["status"] = "ok; part of a revolution, its cost alone"
        return entry
    window = drum_window(case, start)
    if window is None:
        entry["status"] = "ran; the monitor ends before the end"
        return entry
    entry.update(window, status="ok")
    if not (source / "postProcessing" / "drum").is_dir():
        entry["status"] = "ok; the source is a state, not a run"
        return entry
    ref = drum_window(source, start)
    entry["source_window"] = ref
    if ref is None:
        entry["status"] = "ok; the source run does not reach the end"
        return entry
    for key in ("J_end", "surface_angle_mean_deg", "peak_speed_mean",
                "peak_speed_max"):
        entry[f"{key}_vs_source"] = entry[key] / ref[key] - 1
    return entry


def _state_of_run(source, time_name):
    """copytree's ignore of a decomposed run: the case without its
    outputs, and of each processor directory the mesh and time_name."""
    def ignore(directory, names):
        if Path(directory) == source:
            return [x for x in _outputs(directory, names)
                    if not x.startswith("processor")]
        if (Path(directory).parent == source
                and Path(directory).name.startswith("processor")):
            return [x for x in names if x not in ("constant", time_name)]
        return []
    return ignore


def _written(directory, t):
    """The name of the time directory of t in directory."""
    names = [x.name for x in directory.iterdir()
             if re.fullmatch(r"[0-9.eE+-]+", x.name)
             and abs(float(x.name) - t) < 1e-6]
    assert names, f"{directory}: no time {t:g}"
    return names[0]


def drum_window(case, start):
    """The rotatingDrum monitor of case over (start, start + T]: J at the
    end, the surface angle and the peak speed; the lowest pressure seen by
    the rheology in the grains over the steps; the CPU of the steps.
    None if the monitor ends before start + T."""
    m = drum.monitor(case)
    end = start + drum.PERIOD
    if m["t"][-1] < end - 1e-9:
        return None
    w = (m["t"] > start + 1e-9) & (m["t"] <= end + 1e-9)
    t, low = drum.grain_pressure_steps(case)
    steps = (t > start + 1e-9) & (t <= end + 1e-9)
    cost = [log_cost(read_text(log), start, end) for log in
            sorted(Path(case).glob(f"log.{SOLVER}*"))]
    return {"J_end": drum.revolution_change(case, m, end),
            "surface_angle_mean_deg": float(np.mean(m["angle"][w])),
            "surface_angle_range_deg": [float(m["angle"][w].min()),
                                        float(m["angle"][w].max())],
            "peak_speed_mean": float(np.mean(m["peak"][w])),
            "peak_speed_max": float(m["peak"][w].max()),
            "lowest_p_grains": float(low[steps].min()),
            "steps_with_negative_p_grains": int(np.sum(low[steps] < 0)),
            "window_steps": sum(c["steps"] for c in cost),
            "window_cpu_seconds": sum(c["cpu_seconds"] or 0.0
                                      for c in cost)}


def repeated(entries):
    """One entry of the same run made len(entries) times: the last, with
    the median of their CPU seconds (and of their window's) and the CPU
    seconds of each (cpu_seconds_repeats); the first failure's status if
    one failed."""
    e = dict(entries[-1])
    if len(entries) > 1:
        for key in ("cpu_seconds", "window_cpu_seconds"):
            values = [x[key] for x in entries if x.get(key) is not None]
            if values:
                e[key] = float(statistics.median(values))
        e["cpu_seconds_repeats"] = [x.get("cpu_seconds") for x in entries]
        failed = [x for x in entries if not x["status"].startswith("ok")]
        if failed:
            e["status"] = failed[0]["status"]
    return e


def store_drum(entries, command):
    store_runs(
        "whole_drum",
        "One revolution of the square drum (or, with --duration, part of "
        "one: its cost alone) from a written time of a run or a state "
        "(bench/harness drum), on its decomposition, with a "
        "coupling: steps, CPU seconds (master), pressure solutions per "
        "step; J of (7.6) at the end, the surface angle and the peak "
        "speed over the revolution (the rotatingDrum monitor), the lowest "
        "pressure seen by the rheology in the grains over the steps; the "
        "same of the source run over the same window (source_window) and "
        "the relative differences (*_vs_source).",
        lambda e: (e["source"], e["start"], e["end"], e["coupling"],
                   tuple(e["edits"])),
        entries, command)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="bench/harness",
                                     description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="what", required=True)
    ps = sub.add_parser("states", help="write the states")
    ps.add_argument("--states", nargs="+", type=state_name,
                    default=["chute1", "layer2d"])
    ps.add_argument("--edit", nargs="+", default=[],
                    metavar="DICT:ENTRY=VALUE")
    pr = sub.add_parser("run", help="measure couplings from the states")
    pr.add_argument("--states", nargs="+", type=state_name,
                    default=["chute1", "layer2d"])
    pr.add_argument("--dt", nargs="+", type=float, default=[1e-3, 4e-3])
    pr.add_argument("--steps", nargs="+", type=int, default=[1, 10])
    pr.add_argument("--couplings", nargs="+",
                    default=["PISO-4", "PISO-10", "PISO-20", "SIMPLEC-1",
                             "SIMPLEC-3"])
    pr.add_argument("--edit", nargs="+", default=[],
                    metavar="DICT:ENTRY=VALUE")
    pr.add_argument("--reference", default=REFERENCE_NAME,
                    help="the coupling the others are compared with "
                         "(default: reference, 200 PISO correctors with "
                         "p_rgh to 1e-13)")
    pr.add_argument("--no-store", action="store_true",
                    help="print, do not write bench/coupling.json")
    pc = sub.add_parser("chute", help="whole chute runs, one a coupling")
    pc.add_argument("--couplings", nargs="+", default=["PISO-10"])
    pc.add_argument("--end-time", type=float, default=25)
    pc.add_argument("--sub-cycles", type=int, default=None,
                    help="maxAlphaSubCycles M; 0: nAlphaSubCycles 1 (the "
                    "transport in the momentum step); default: the "
                    "tutorial's")
    pc.add_argument("--max-delta-t", type=float, default=None)
    pc.add_argument("--edit", nargs="+", default=[],
                    metavar="DICT:ENTRY=VALUE")
    pc.add_argument("--no-store", action="store_true",
                    help="print, do not write bench/coupling.json")
    pd = sub.add_parser("drum", help="one drum revolution from a written "
                        "time of a run, one a coupling")
    pd.add_argument("--source", required=True,
                    help="a decomposed drum run (its processor directories)")
    pd.add_argument("--start", type=float, required=True,
                    help="a time the source wrote [s]")
    pd.add_argument("--couplings", nargs="+", default=["Krylov-BFBt-20"])
    pd.add_argument("--duration", type=float, default=None,
                    help="simulated seconds, less than a revolution: the "
                    "cost alone (default: one revolution)")
    pd.add_argument("--edit", nargs="+", default=[],
                    metavar="DICT:ENTRY=VALUE")
    pd.add_argument("--variant", nargs="*", action="append",
                    metavar="DICT:ENTRY=VALUE",
                    help="a set of edits beside --edit's; each --variant "
                    "(an empty one: --edit's alone) is run with every "
                    "coupling, one after the other")
    pd.add_argument("--repeat", type=int, default=1,
                    help="run the variants and couplings this many times, "
                    "interleaved; each entry's CPU is the median "
                    "(default 1)")
    pd.add_argument("--no-store", action="store_true",
                    help="print, do not write bench/coupling.json")
    pk = sub.add_parser("spectrum", help="Ritz values of the Krylov "
                        "coupling's preconditioned operator")
    pk.add_argument("--states", nargs="+", type=state_name,
                    default=["chute1", "layer2d", "layer2dSquare"])
    pk.add_argument("--dt", nargs="+", type=float, default=[4e-3])
    pk.add_argument("--preconditioners", nargs="+", default=["BFBt", "PISO"],
                    choices=["BFBt", "PISO", "CahouetChabard"])
    pk.add_argument("--edit", nargs="+", default=[],
                    metavar="DICT:ENTRY=VALUE")
    pk.add_argument("--no-store", action="store_true",
                    help="print, do not write bench/coupling.json")
    args = parser.parse_args(argv)
    variants = getattr(args, "variant", None) or [[]]
    try:
        for e in args.edit + [e for v in variants for e in v]:
            parse_edit(e)
    except ValueError as err:
        parser.error(str(err))
    if getattr(args, "repeat", 1) < 1:
        parser.error(f"--repeat {args.repeat}: not a positive integer")
    command = "bench/harness " + " ".join(argv if argv is not None
                                          else sys.argv[1:])
    if args.what == "spectrum":
        for state in args.states:
            if not state_dir(state, args.edit).is_dir():
                parser.error(f"no state {state_dir(state, args.edit).name}: "
                             f"run bench/harness states --states {state} "
                             "first")
        for state in args.states:
            for dt in args.dt:
                for pc in args.preconditioners:
                    e = spectrum(state, dt, pc, args.edit)
                    print(json.dumps({k: v for k, v in e.items()
                                      if k != "ritz"}), flush=True)
                    if not args.no_store:
                        store_spectra([e], command)
        return 0
    if args.what == "drum" and not any(
            Path(args.source).glob("processor[0-9]*")):
        parser.error(f"--source {args.source}: no processor directories "
                     "(a decomposed drum run)")
    if args.what == "drum" and args.duration is not None and not (
            0 < args.duration <= drum.PERIOD):
        parser.error(f"--duration {args.duration:g}: not in (0, "
                     f"{drum.PERIOD:g}] s")
    if args.what in ("chute", "drum"):
        try:
            for c in args.couplings:
                coupling_settings(c)
        except ValueError as err:
            parser.error(str(err))
        if args.what == "chute":
            for coupling in args.couplings:
                e = whole_chute(coupling, args.end_time, args.sub_cycles,
                                args.max_delta_t, args.edit)
                print(json.dumps(e), flush=True)
                if not args.no_store:
                    store_whole([e], command)
            return 0
        runs = {}
        for _ in range(args.repeat):
            for extra in variants:
                for coupling in args.couplings:
                    e = whole_drum(args.source, args.start, coupling,
                                   args.edit + extra, args.duration)
                    print(json.dumps(e), flush=True)
                    same = runs.setdefault((coupling, tuple(extra)), [])
                    same.append(e)
                    if not args.no_store:
                        store_drum([repeated(same)], command)
        return 0
    if args.what == "states":
        try:
            failed = [e for e in (make_state(name, args.edit)
                                  for name in args.states) if e]
        except ValueError as err:
            parser.error(str(err))
        if failed:
            store(failed, command)
        return 1 if failed else 0
    try:
        for c in args.couplings + [args.reference]:
            coupling_settings(c)
        for e in args.edit:
            parse_edit(e)
    except ValueError as err:
        parser.error(str(err))
    if any(d <= 0 for d in args.dt) or any(n < 1 for n in args.steps):
        parser.error("need --dt > 0 and --steps >= 1")
    for s in args.states:
        if not state_dir(s, args.edit).is_dir():
            parser.error(f"no state {state_dir(s, args.edit).name}: run "
                         f"bench/harness states --states {s} "
                         + " ".join(["--edit"] + args.edit if args.edit
                                    else []) + " first")
    references, entries = {}, []
    for state in args.states:
        for dt in args.dt:
            for steps in args.steps:
                for coupling in args.couplings:
                    e = measure(state, dt, steps, coupling, args.edit,
                                references, args.reference)
                    entries.append(e)
                    print(json.dumps(e), flush=True)
                    if not args.no_store:
                        store([e], command)
    return 0


if __name__ == "__main__":
    sys.exit(main())

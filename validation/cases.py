"""Running the verification cases and reading what OpenFOAM sampled.

A case runs in validation/results/<name>/ (wiped first, git-ignored), so
its logs, fields, errors file and figure stay for the reader.  Every step
that fails (a tool's exit status, a missing output) is an assertion
failure, never a skip.
"""
import json
import re
import shutil
import time

from conftest import PROJECT, committed_copy, run
from granularfoam.foamio import (  # noqa: F401 (the tests read them here)
    edit, entries, grain_profiles, last_two, profiles, set_entry, times,
    volumes)
from granularfoam.foamio import run as run_tool

RESULTS = PROJECT / "validation" / "results"
NUMBER = r"[-+0-9.eE]+"


def fresh_case(name, dest=None, tutorial=False):
    """Copy validation/cases/<name> (tutorials/<name> if tutorial), as HEAD
    holds it (committed_copy), to validation/results/<dest or name>."""
    dst = RESULTS / (dest or name)
    if dst.exists():
        shutil.rmtree(dst)
    return committed_copy(
        f"{'tutorials' if tutorial else 'validation/cases'}/{name}", dst)


def foam_output(case, *cmd, timeout=3600):
    """Run a command in case (foamio.run: a non-zero exit status raises);
    return (stdout, seconds)."""
    start = time.monotonic()
    out = run_tool(case, *cmd, timeout=timeout)
    return out, time.monotonic() - start


def foam(case, *cmd, timeout=3600):
    """Run a command in case (a non-zero exit status raises); return its
    seconds."""
    return foam_output(case, *cmd, timeout=timeout)[1]


def run_case(case, script="./Allrun"):
    """Run the case's Allrun (or another script); seconds it took."""
    return foam(case, script)


def write_results(case, name, numbers):
    """Write numbers (a dict) to case/<name>.json; return its path."""
    path = case / f"{name}.json"
    path.write_text(json.dumps(numbers, indent=2, sort_keys=True) + "\n")
    return path


def set_decomposition(case, method):
    """Use method (scotch or metis) in case/system/decomposeParDict."""
    edit(case / "system" / "decomposeParDict",
         [(r"\nmethod\s+\w+;", f"\nmethod          {method};")])


SIDEWALL = "tutorials/squareDrum/constant/fvOptions.sidewall"


def sidewall_friction(case, **entries):
    """Give case the sidewall friction: constant/fvOptions from the drum's
    constant/fvOptions.sidewall as HEAD holds it (the one example of
    granularSidewallFriction, as ./Allrun -sidewall uses it), each entry of
    the dictionary sidewallFriction set to its value, or removed where the
    value is None."""
    fv = committed_copy(SIDEWALL, case / "constant" / "fvOptions")
    for key, value in entries.items():
        entry = f"sidewallFriction/{key}"
        if value is None:
            foam(case, "foamDictionary", "-entry", entry, "-remove",
                 "constant/fvOptions")
        else:
            set_entry(case, "constant/fvOptions", entry, value)
    return fv


def small_drum(dest, n=8, end_time="1e-4", write_interval=None,
               delta_t="1e-4", adjust=False, controls=(), prepare=None):
    """tutorials/squareDrum on n x n cells in validation/results/<dest>,
    with etaMax 300 Pa s (the numbers the tests state, e.g. the viscous
    part of (4.11) an edit halves, are for it): ascii and uncompressed,
    blockMesh and setGranularFields run.  Without
    adjust, fixed steps of delta_t; controls are (regex, replacement) pairs
    applied to system/controlDict after these settings; prepare, a function
    of the case, changes it further before blockMesh."""
    case = fresh_case("squareDrum", dest=dest, tutorial=True)
    edit(case / "system" / "drumParameters",
         [(rf"\n{key}\s+[^;]+;", f"\n{key} {value};")
          for key, value in (("N", n), ("endTime", end_time),
                             ("writeInterval", write_interval or end_time),
                             ("etaMax", 300))])
    settings = [(r"writeCompression\s+on;", "writeCompression off;"),
                (r"\ndeltaT\s+\S+;", f"\ndeltaT {delta_t};")]
    if not adjust:
        settings.append((r"adjustTimeStep\s+yes;", "adjustTimeStep  no;"))
    edit(case / "system" / "controlDict", settings + list(controls))
    if prepare:
        prepare(case)
    shutil.copytree(case / "0.orig", case / "0")
    foam(case, "blockMesh")
    foam(case, "setGranularFields")
    return case


def log_reports(log):
    """The solver's progress reports (granularPhases::report) in its log:
    {time name: [volumes {phase: V}, segregation index]}; the first report
    is at the start time, the others follow their "Time = " line."""
    out, time_name = {}, "0"
    for line in log.splitlines():
        m = re.match(r"^Time = (\S+)$", line)
        if m:
            time_name = m.group(1)
        if line.startswith("Phase volumes:"):
            vols = dict(re.findall(rf"(alpha\.\w+) = ({NUMBER})", line))
            out[time_name] = [{k: float(v) for k, v in vols.items()}, None]
        m = re.match(rf"^Segregation index \(.*\) = ({NUMBER})$", line)
        if m:
            out[time_name][1] = float(m.group(1))
    return out

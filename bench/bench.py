"""The benchmark driver behind bench/run (see bench/README.md).

Generates the cases (generate.py) in bench/work/, runs every solver
configuration (stock, granular, granular-implicit, granular-krylov) on every
case, mesh and rank count the same number of fixed time steps, repeated
--reps times (the repetitions interleaved, so that a slow spell of the
machine spreads over all configurations); then the time per simulated
second: the granular solver, explicit, implicit and Krylov, serial, on the
chute's 155 x 16 mesh over --interval simulated seconds with the time step
adjusted to the CFL (4.11); then whole runs of the chute tutorial (155 x 40,
from rest to --whole-end-time) with the reference coupling and with the
tutorial's own, side by side on two cores (bench/harness's whole_chute);
then, given a written state of the square drum tutorial (--drum-source,
--drum-start), one revolution from it with the drum's reference coupling
and with the tutorial's own, one after the other on the state's ranks
(bench/harness's whole_drum).  --parts runs some of these parts and keeps
the others' results from bench/results.json.  Writes bench/results.json and
BENCHMARKS.md (report.py).
"""

import argparse
import concurrent.futures
import datetime
import hashlib
import json
import os
import platform
import re
import resource
import shlex
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

import generate
import harness
import report

BENCH = generate.BENCH
REPO = generate.REPO
WORK = BENCH / "work"
RESULTS = BENCH / "results.json"
MARKDOWN = REPO / "BENCHMARKS.md"

RANKS = (1, 2)
MESHES = ("155x16", "400x40")
STEPS = 500
INTERVAL = 0.2
QUICK = {"meshes": ("155x16",), "steps": 20, "reps": 1, "interval": 0.02,
         "whole_end_time": 1}
# The time per simulated second: case, mesh, solver configurations (serial)
ADAPTIVE = {"case": "chute", "mesh": (155, 16),
            "solvers": ("granular", "granular-implicit",
                        "granular-krylov")}
MPIRUN = ("mpirun", "--oversubscribe", "--bind-to", "none")
# Whole runs of the chute tutorial, serial, side by side: the reference
# (20 PISO correctors, the transport in the momentum step, maxDeltaT 1e-3)
# and the tutorial as its files say
WHOLE_END_TIME = 25
WHOLE = {
    "reference": {"coupling": "PISO-20", "sub_cycles": 0,
                  "max_delta_t": 1e-3},
    "tutorial": {"coupling": harness.TUTORIAL_NAME, "sub_cycles": None,
                 "max_delta_t": None},
}

# One drum revolution from a written state of the drum tutorial (a run of
# tutorials/squareDrum, any N), on the state's ranks, with the tutorial's
# fvSolution, fvSchemes and controlDict: the reference coupling
# (harness.DRUM_REFERENCE) and the tutorial's own, one after the other
DRUM = {"reference": harness.DRUM_REFERENCE,
        "tutorial": (harness.TUTORIAL_NAME, ())}
DRUM_TUTORIAL = REPO / "tutorials" / "squareDrum"
DRUM_METRICS = ("J_end", "surface_angle_mean_deg", "peak_speed_mean",
                "peak_speed_max")
# The parts of a run and the keys of results.json each writes; a part not
# run keeps its keys from the results file
PARTS = {
    "steps": ("quick", "command", "date", "machine", "software",
              "settings", "configs", "runs", "summary"),
    "per-simulated-second": ("per_simulated_second",),
    "chute": ("whole",),
    "drum": ("drum",),
}

EXECUTION = re.compile(
    r"^ExecutionTime = ([-+.0-9eE]+) s\s+ClockTime = ([-+.0-9eE]+) s",
    re.MULTILINE)
NUMBER = r"([-+.0-9eE]+|nan|inf)"
STEP_TIME = re.compile(r"^Time = ([-+.0-9eE]+)$", re.MULTILINE)
DELTA_T = re.compile(r"^deltaT = ([-+.0-9eE]+)(?: \(limited by .*\))?$",
                     re.MULTILINE)
CFL = re.compile(
    rf"^CFL \(4\.11\) max: convective = {NUMBER} viscous = {NUMBER} "
    rf"segregation = {NUMBER} diffusion = {NUMBER} total = {NUMBER} "
    r"\(largest part: (\w+)\)", re.MULTILINE)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="bench/run",
        description="Time per cell per step of granularSegregationFoam "
                    "(explicit and implicit viscous stress) against stock "
                    "multiphaseInterFoam, and its time per simulated "
                    "second, explicit and implicit (bench/README.md).")
    parser.add_argument("--reps", type=int,
                        help="repetitions of every run (default 3; 1 with "
                             "--quick)")
    parser.add_argument("--steps", type=int,
                        help=f"time steps per run (default {STEPS}; "
                             f"{QUICK['steps']} with --quick)")
    parser.add_argument("--k0", type=int,
                        help="the timing runs from the end of step k0 to the "
                             "last step (default steps/10, at least 1)")
    parser.add_argument("--meshes", nargs="+", metavar="NXxNZ",
                        help=f"meshes (default {' '.join(MESHES)}; "
                             f"{QUICK['meshes'][0]} with --quick)")
    parser.add_argument("--ranks", type=int, nargs="+", choices=RANKS,
                        default=list(RANKS),
                        help="MPI ranks (default 1 2; 1 alone on a busy "
                             "machine)")
    parser.add_argument("--interval", type=float, metavar="SECONDS",
                        help="simulated interval of the time per simulated "
                             f"second (default {INTERVAL}; "
                             f"{QUICK['interval']} with --quick; 0 leaves "
                             "it out)")
    parser.add_argument("--max-delta-t", type=float, default=1.0,
                        metavar="SECONDS",
                        help="maxDeltaT of the time per simulated second "
                             "(default 1: no cap; the tutorial's is 1e-3)")
    parser.add_argument("--whole-end-time", type=float, metavar="SECONDS",
                        help="end time of the whole chute runs (default "
                             f"{WHOLE_END_TIME}; {QUICK['whole_end_time']} "
                             "with --quick; 0 leaves them out)")
    parser.add_argument("--drum-source", type=Path, metavar="DIR",
                        help="a decomposed run of tutorials/squareDrum (any "
                             "N): the drum part runs one revolution from "
                             "its written time --drum-start with the "
                             "tutorial's files, with the reference coupling "
                             "and with the tutorial's (default: no drum "
                             "part)")
    parser.add_argument("--drum-start", type=float, metavar="SECONDS",
                        help="the written time of --drum-source to start "
                             "from")
    parser.add_argument("--drum-duration", type=float, metavar="SECONDS",
                        help="run this much of the revolution (its cost "
                             "alone, no accuracy; default a revolution)")
    parser.add_argument("--parts", nargs="+", choices=list(PARTS),
                        help="run these parts and keep the others' results "
                             "from bench/results.json (default: steps, "
                             "per-simulated-second, chute, and drum with "
                             "--drum-source)")
    parser.add_argument("--quick", action="store_true",
                        help="develop the harness: the small mesh, "
                             f"{QUICK['steps']} steps, 1 repetition, "
                             f"{QUICK['interval']} s simulated; "
                             "labelled quick, not a measurement")
    args = parser.parse_args(argv)
    if args.reps is None:
        args.reps = QUICK["reps"] if args.quick else 3
    if args.steps is None:
        args.steps = QUICK["steps"] if args.quick else STEPS
    if args.meshes is None:
        args.meshes = list(QUICK["meshes"] if args.quick else MESHES)
    if args.k0 is None:
        args.k0 = max(1, args.steps // 10)
    if args.interval is None:
        args.interval = QUICK["interval"] if args.quick else INTERVAL
    if args.whole_end_time is None:
        args.whole_end_time = (QUICK["whole_end_time"] if args.quick
                               else WHOLE_END_TIME)
    if (args.interval < 0 or args.max_delta_t <= 0
            or args.whole_end_time < 0):
        parser.error("need --interval >= 0, --max-delta-t > 0 and "
                     "--whole-end-time >= 0")
    if args.reps < 1 or args.steps < 2 or not 1 <= args.k0 < args.steps:
        parser.error("need reps >= 1 and 1 <= k0 < steps")
    meshes = []
    for mesh in args.meshes:
        match = re.fullmatch(r"(\d+)x(\d+)", mesh)
        if not match:
            parser.error(f"mesh '{mesh}' is not NXxNZ (e.g. 155x16)")
        meshes.append((int(match[1]), int(match[2])))
    args.meshes = meshes
    args.ranks = sorted(set(args.ranks))
    if args.ranks[0] != 1:
        parser.error("--ranks needs 1, the reference of the efficiency")
    if args.parts is None:
        args.parts = [p for p in PARTS
                      if p != "drum" or args.drum_source is not None]
    if "drum" in args.parts:
        if args.drum_source is None or args.drum_start is None:
            parser.error("the drum part needs --drum-source DIR and "
                         "--drum-start SECONDS")
        problems = drum_source_problems(args.drum_source, args.drum_start)
        if problems:
            parser.error(f"--drum-source {args.drum_source}: "
                         + "; ".join(problems))
        if args.drum_duration is not None and args.drum_duration <= 0:
            parser.error("need --drum-duration > 0")
    elif args.drum_source is not None:
        parser.error("--drum-source without the drum part in --parts")
    if set(args.parts) != set(PARTS) and not RESULTS.exists():
        parser.error(f"--parts {' '.join(args.parts)} keeps the other "
                     f"parts from {RESULTS.relative_to(REPO)}, which is "
                     "missing")
    return args


def keep_parts(results, kept, parts):
    """results with the keys of every part not in parts taken from kept
    (the results file of an earlier run)."""
    for part, keys in PARTS.items():
        if part not in parts:
            results.update({k: kept.get(k) for k in keys})
    return results


def drum_source_problems(source, start):
    """Why source cannot serve the drum part from its written time start:
    not a decomposed drum run, or no such time.  Empty if it can."""
    source = Path(source)
    ranks = sorted(source.glob("processor[0-9]*"))
    if not ranks or not (source / "system" / "drumParameters").is_file():
        return ["not a decomposed run of tutorials/squareDrum (no "
                "processor directories or no system/drumParameters)"]
    times = [x.name for x in ranks[0].iterdir()
             if re.fullmatch(r"[0-9.eE+-]+", x.name)]
    if not any(abs(float(x) - start) < 1e-6 for x in times):
        return [f"{ranks[0].name} has no time {start:g}"]
    return []


def command_output(*cmd):
    return subprocess.run(list(cmd), check=True, capture_output=True,
                          text=True).stdout


def load_average():
    return [float(x) for x in Path("/proc/loadavg").read_text().split()[:3]]


def cpu_seconds():
    """(busy CPU seconds of the whole machine, CPU seconds of our finished
    children): their increments over a run give the load of other users."""
    fields = [int(x) for x in Path("/proc/stat").read_text()
              .splitlines()[0].split()[1:]]
    # user nice system idle iowait irq softirq steal
    busy = sum(fields[:3]) + sum(fields[5:8])
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (busy / os.sysconf("SC_CLK_TCK"),
            children.ru_utime + children.ru_stime)


def machine():
    cpu = {}
    for line in command_output("lscpu").splitlines():
        key, _, value = line.partition(":")
        cpu[key.strip()] = value.strip()
    mem_kb = int(re.search(r"MemTotal:\s+(\d+)",
                           Path("/proc/meminfo").read_text())[1])
    return {
        "cpu": cpu.get("Model name", "unknown"),
        "cpus": int(cpu.get("CPU(s)", 0)),
        "cores_per_socket": cpu.get("Core(s) per socket"),
        "threads_per_core": cpu.get("Thread(s) per core"),
        "sockets": cpu.get("Socket(s)"),
        "memory_GB": round(mem_kb / 1024 ** 2, 1),
        "kernel": platform.release(),
        "os": platform.freedesktop_os_release().get("PRETTY_NAME", "")
              if hasattr(platform, "freedesktop_os_release") else "",
    }


def sha256(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def executables():
    """The executable of every solver configuration: Debian's stock binary
    and the project's build (explicit, implicit and Krylov)."""
    granular = shutil.which("granularSegregationFoam")
    appbin = os.environ.get("FOAM_USER_APPBIN", "")
    if not granular or not granular.startswith(appbin):
        sys.exit("bench/run: granularSegregationFoam is not in "
                 "$FOAM_USER_APPBIN; build the project (./Allwmake)")
    stock = "/usr/bin/multiphaseInterFoam"
    if not os.access(stock, os.X_OK):
        sys.exit(f"bench/run: {stock} not found (Debian's openfoam package)")
    return {"stock": stock, "granular": granular,
            "granular-implicit": granular, "granular-krylov": granular}


def software(exes):
    git = ["git", "-C", str(REPO)]
    dirty = command_output(*git, "status", "--porcelain", "--",
                           "applications", "src").split("\n")
    library = Path(os.environ["FOAM_USER_LIBBIN"]) / "libgranularRheology.so"
    return {
        "openfoam": os.environ.get("WM_PROJECT_VERSION", ""),
        "mpi": command_output("mpirun", "--version").splitlines()[0],
        "commit": command_output(*git, "rev-parse", "HEAD").strip(),
        "uncommitted_sources": [line[3:] for line in dirty if line],
        "binaries": {
            str(p): sha256(p)
            for p in (exes["stock"], exes["granular"], library)},
    }


def parse_log(path, steps):
    """ExecutionTime and ClockTime at the end of every step."""
    text = Path(path).read_text(errors="replace")
    if "FOAM FATAL" in text or "FOAM aborting" in text:
        raise RuntimeError(f"the solver failed: see {path}")
    pairs = [(float(a), float(b)) for a, b in EXECUTION.findall(text)]
    if len(pairs) != steps:
        raise RuntimeError(f"{path}: {len(pairs)} time steps, not {steps}")
    return [a for a, _ in pairs], [b for _, b in pairs]


def run_one(case_dir, exe, ranks, rep, steps, k0, cells):
    """One run of the solver; its timing from the log, its peak RSS."""
    tag = f"np{ranks}.rep{rep}"
    log = case_dir / f"log.{Path(exe).name}.{tag}"
    rss_prefix = case_dir / f"rss.{tag}"
    for old in case_dir.glob(f"rss.{tag}.*"):
        old.unlink()
    cmd = [str(BENCH / "rankrss"), str(rss_prefix), exe]
    if ranks > 1:
        cmd = [*MPIRUN[:1], "-np", str(ranks), *MPIRUN[1:], *cmd, "-parallel"]
    load_before = load_average()
    busy0, ours0 = cpu_seconds()
    start = time.monotonic()
    with open(log, "w") as out:
        proc = subprocess.run(cmd, cwd=case_dir, stdout=out,
                              stderr=subprocess.STDOUT,
                              env=generate.case_env(case_dir))
    wall = time.monotonic() - start
    busy1, ours1 = cpu_seconds()
    if proc.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed in {case_dir} "
                           f"(exit {proc.returncode}); see {log}")
    execution, clock = parse_log(log, steps)
    rss = []
    for rank in range(ranks):
        lines = (rss_prefix.parent / f"{rss_prefix.name}.{rank}") \
            .read_text().split()
        rss.append(int(lines[-1]))
    per_step = (execution[-1] - execution[k0 - 1]) / (steps - k0)
    return {
        "ranks": ranks, "rep": rep,
        "log": str(log.relative_to(REPO)),
        "command": shlex.join(cmd),
        "execution_k0_s": execution[k0 - 1],
        "execution_last_s": execution[-1],
        "clock_k0_s": clock[k0 - 1],
        "clock_last_s": clock[-1],
        "s_per_step": per_step,
        "us_per_cell_step": per_step / cells * 1e6,
        "wall_s": round(wall, 3),
        "rss_kB": rss,
        "rss_MB": sum(rss) / 1024,
        "cpu_s": round(ours1 - ours0, 3),
        # cores used by other processes during the run (ours excluded)
        "other_load": round(max(0.0, (busy1 - busy0) - (ours1 - ours0))
                            / wall, 3),
        "load_before": load_before,
        "load_after": load_average(),
    }


def run_adaptive(case_dir, exe, rep, interval):
    """One serial run over the simulated interval with the time step
    adjusted: its steps, time steps, viscous CFL parts and times.  The
    times run from the end of step 1 (start-up and the first step left
    out, as k0 in the fixed-step runs) to the end of the last step: CPU
    from ExecutionTime, wall from the arrival of the ExecutionTime lines
    (ClockTime has a resolution of 1 s)."""
    tag = f"np1.rep{rep}"
    log = case_dir / f"log.{Path(exe).name}.{tag}"
    cmd = [exe]
    load_before = load_average()
    busy0, ours0 = cpu_seconds()
    start = time.monotonic()
    stamps = []
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, cwd=case_dir, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True,
                                errors="replace",
                                env=generate.case_env(case_dir))
        for line in proc.stdout:
            if line.startswith("ExecutionTime = "):
                stamps.append(time.monotonic() - start)
            out.write(line)
        proc.wait()
    wall = time.monotonic() - start
    busy1, ours1 = cpu_seconds()
    if proc.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed in {case_dir} "
                           f"(exit {proc.returncode}); see {log}")
    text = log.read_text(errors="replace")
    if "FOAM FATAL" in text or "FOAM aborting" in text:
        raise RuntimeError(f"the solver failed: see {log}")
    loop = text.partition("Starting time loop")[2]
    execution = [float(a) for a, _ in EXECUTION.findall(loop)]
    times = [float(t) for t in STEP_TIME.findall(loop)]
    deltas = [float(d) for d in DELTA_T.findall(loop)]
    # (4.11) as printed before every step, with the previous step's Delta t
    cfl = CFL.findall(loop)
    steps = len(execution)
    if not (steps >= 2 and len(times) == steps and len(deltas) == steps
            and len(cfl) == steps and len(stamps) == steps):
        raise RuntimeError(f"{log}: {steps} ExecutionTime, {len(times)} "
                           f"Time, {len(deltas)} deltaT, {len(cfl)} CFL "
                           "lines: not one of each per step")
    if times[-1] < interval * (1 - 1e-6) - 0.5 * deltas[-1]:
        raise RuntimeError(f"{log}: stopped at t = {times[-1]}, not "
                           f"{interval}")
    simulated = times[-1] - times[0]
    viscous = [float(c[1]) for c in cfl]
    limited = {}
    for c in cfl:
        limited[c[5]] = limited.get(c[5], 0) + 1
    return {
        "ranks": 1, "rep": rep,
        "log": str(log.relative_to(REPO)),
        "command": shlex.join(cmd),
        "steps": steps,
        "t_first_s": times[0], "t_last_s": times[-1],
        "deltaT_min_s": min(deltas), "deltaT_median_s":
            statistics.median(deltas), "deltaT_max_s": max(deltas),
        "viscous_cfl_median": statistics.median(viscous),
        "viscous_cfl_max": max(viscous),
        "limited_by": limited,
        "execution_first_s": execution[0],
        "execution_last_s": execution[-1],
        "wall_first_s": round(stamps[0], 3),
        "wall_last_s": round(stamps[-1], 3),
        "cpu_per_simulated_s": (execution[-1] - execution[0]) / simulated,
        "wall_per_simulated_s": (stamps[-1] - stamps[0]) / simulated,
        "wall_s": round(wall, 3),
        "cpu_s": round(ours1 - ours0, 3),
        "other_load": round(max(0.0, (busy1 - busy0) - (ours1 - ours0))
                            / wall, 3),
        "load_before": load_before,
        "load_after": load_average(),
    }


def summarise_adaptive(configs, runs):
    """Medians over the repetitions of every configuration, and the
    speed-up of every other configuration over the explicit one (explicit
    time over its time per simulated second), by solver."""
    rows = []
    for config in configs:
        mine = [r for r in runs if r["config"] == config["name"]]

        def median(key):
            return statistics.median(r[key] for r in mine)

        rows.append({
            "config": config["name"], "case": config["case"],
            "solver": config["solver"],
            "application": generate.APPLICATION[config["solver"]],
            "mesh": config["mesh"], "cells": config["cells"], "ranks": 1,
            "interval_s": config["interval"], "reps": len(mine),
            "steps": median("steps"),
            "deltaT_median_s": median("deltaT_median_s"),
            "viscous_cfl_median": median("viscous_cfl_median"),
            "wall_per_simulated_s": median("wall_per_simulated_s"),
            "cpu_per_simulated_s": median("cpu_per_simulated_s"),
            "wall_per_simulated_s_min":
                min(r["wall_per_simulated_s"] for r in mine),
            "cpu_per_simulated_s_min":
                min(r["cpu_per_simulated_s"] for r in mine),
        })
    explicit = next(r for r in rows if r["solver"] == "granular")
    speedup = {
        row["solver"]: {
            "wall": explicit["wall_per_simulated_s"]
                    / row["wall_per_simulated_s"],
            "cpu": explicit["cpu_per_simulated_s"]
                   / row["cpu_per_simulated_s"],
            "deltaT": row["deltaT_median_s"] / explicit["deltaT_median_s"],
            "steps": explicit["steps"] / row["steps"],
        }
        for row in rows if row is not explicit}
    return rows, speedup


def ms_per_step(entry):
    """CPU milliseconds per step of a whole run's entry; None without."""
    cpu = entry.get("cpu_seconds")
    return 1000 * cpu / entry["steps"] if cpu and entry.get("steps") else None


def cpu_ratio(ref, tut):
    """The reference's CPU seconds over the tutorial's; None without."""
    return (ref["cpu_seconds"] / tut["cpu_seconds"]
            if ref.get("cpu_seconds") and tut.get("cpu_seconds") else None)


def run_whole(end_time):
    """The whole chute runs of WHOLE, side by side (one process each), and
    the reference's CPU time over the tutorial's."""
    with concurrent.futures.ProcessPoolExecutor(len(WHOLE)) as pool:
        futures = {name: pool.submit(harness.whole_chute, c["coupling"],
                                     end_time, c["sub_cycles"],
                                     c["max_delta_t"], [])
                   for name, c in WHOLE.items()}
        runs = {name: f.result() for name, f in futures.items()}
    for name, entry in runs.items():
        entry["configuration"] = name
        cpu = entry.get("cpu_seconds")
        entry["cpu_per_simulated_s"] = cpu / end_time if cpu else None
        entry["ms_per_step"] = ms_per_step(entry)
        print(f"bench/run: whole chute, {name}: {entry['status']}, "
              f"{entry['steps']} steps, {cpu} CPU s", flush=True)
    ref, tut = runs["reference"], runs["tutorial"]
    speedup = cpu_ratio(ref, tut)
    return {"case": "chute", "mesh": "155x40", "ranks": 1,
            "end_time": end_time, "side_by_side": True,
            "settings": WHOLE, "runs": runs, "speedup": speedup}


def run_drum(source, start, duration, command):
    """One revolution (or duration) of the drum from the written time start
    of source with the tutorial's fvSolution, fvSchemes and controlDict,
    with the reference coupling and with the tutorial's, one after the
    other on the source's ranks; the tutorial's CPU time against the
    reference's and its J, surface angle and peak speed against the
    reference's."""
    runs = {}
    for name, (coupling, edits) in DRUM.items():
        entry = harness.whole_drum(source, start, coupling, list(edits),
                                   duration, files=DRUM_TUTORIAL)
        entry["configuration"] = name
        entry["files"] = str(DRUM_TUTORIAL.relative_to(REPO))
        if entry["status"].startswith("ok") and "J_end" in entry:
            # whether the source run reaches the end does not matter here
            entry["status"] = "ok"
        cpu = entry.get("cpu_seconds")
        entry["ms_per_step"] = ms_per_step(entry)
        runs[name] = entry
        print(f"bench/run: drum, {name}: {entry['status']}, "
              f"{entry.get('steps')} steps, {cpu} CPU s", flush=True)
    ref, tut = runs["reference"], runs["tutorial"]
    speedup = cpu_ratio(ref, tut)
    if all("J_end" in r for r in (ref, tut)):
        for key in DRUM_METRICS:
            tut[f"{key}_vs_reference"] = tut[key] / ref[key] - 1
    return {"case": "squareDrum", "N": ref["N"], "ranks": ref["ranks"],
            "source": str(Path(source).resolve()), "start": start,
            "end": ref["end"], "settings": {
                name: {"coupling": c, "edits": list(e)}
                for name, (c, e) in DRUM.items()},
            "runs": runs, "speedup": speedup, "command": command,
            "date": datetime.datetime.now().astimezone().isoformat(
                timespec="seconds")}


def summarise(configs, runs, ranks_used):
    """Min and median over the repetitions, the ratio to stock and the
    parallel efficiency, one row per configuration and rank count."""
    rows = []
    for config in configs:
        for ranks in ranks_used:
            mine = [r for r in runs
                    if r["config"] == config["name"] and r["ranks"] == ranks]
            us = [r["us_per_cell_step"] for r in mine]
            rows.append({
                "config": config["name"], "case": config["case"],
                "solver": config["solver"],
                "application": generate.APPLICATION[config["solver"]],
                "mesh": config["mesh"], "cells": config["cells"],
                "ranks": ranks, "steps": config["steps"],
                "k0": config["k0"], "deltaT": config["deltaT"],
                "reps": len(us),
                "us_min": min(us), "us_median": statistics.median(us),
                "rss_MB": max(r["rss_MB"] for r in mine),
            })
    for row in rows:
        stock = next(s for s in rows
                     if s["solver"] == "stock" and s["case"] == row["case"]
                     and s["mesh"] == row["mesh"]
                     and s["ranks"] == row["ranks"])
        row["ratio_min"] = row["us_min"] / stock["us_min"]
        row["ratio_median"] = row["us_median"] / stock["us_median"]
        serial = next(s for s in rows
                      if s["config"] == row["config"] and s["ranks"] == 1)
        # t1/(N tN): the same cells, so the times per cell and step will do
        row["efficiency_min"] = (serial["us_min"]
                                 / (row["ranks"] * row["us_min"]))
        row["efficiency_median"] = (serial["us_median"]
                                    / (row["ranks"] * row["us_median"]))
    return rows


def main(argv):
    args = parse_args(argv)
    exes = executables()
    command = shlex.join(["bench/run", *argv])
    results = {
        "quick": args.quick,
        "command": command,
        "date": datetime.datetime.now().astimezone().isoformat(
            timespec="seconds"),
        "machine": machine(),
        "software": software(exes),
        "settings": {
            "meshes": [f"{nx}x{nz}" for nx, nz in args.meshes],
            "steps": args.steps, "k0": args.k0, "reps": args.reps,
            "ranks": args.ranks, "mpirun": shlex.join(MPIRUN),
            "deltaT": {f"{nx}x{nz}": generate.delta_t(nx, nz)
                       for nx, nz in args.meshes},
            "solvers": list(generate.SOLVERS),
            "implicit_fvSolution": generate.IMPLICIT,
            "krylov_fvSolution": generate.krylov_entries(),
        },
    }

    configs = []
    for nx, nz in (args.meshes if "steps" in args.parts else []):
        mesh = f"{nx}x{nz}"
        shutil.rmtree(WORK / mesh, ignore_errors=True)
        for case in generate.CASES:
            for solver in generate.SOLVERS:
                name = f"{mesh}/{case}-{solver}"
                case_dir = WORK / name
                print(f"bench/run: generating {case_dir.relative_to(REPO)}",
                      flush=True)
                params = generate.prepare(case_dir, case, solver, nx, nz,
                                          args.steps, args.ranks)
                configs.append({
                    "name": name, "case": case, "solver": solver,
                    "mesh": mesh, "dir": case_dir,
                    "cells": params["cells"], "steps": args.steps,
                    "k0": args.k0, "deltaT": params["deltaT"],
                })

    adaptive = []
    if args.interval > 0 and "per-simulated-second" in args.parts:
        nx, nz = ADAPTIVE["mesh"]
        shutil.rmtree(WORK / "adaptive", ignore_errors=True)
        for solver in ADAPTIVE["solvers"]:
            name = f"adaptive/{nx}x{nz}/{ADAPTIVE['case']}-{solver}"
            case_dir = WORK / name
            print(f"bench/run: generating {case_dir.relative_to(REPO)}",
                  flush=True)
            params = generate.prepare(case_dir, ADAPTIVE["case"], solver,
                                      nx, nz, 0, [1], interval=args.interval,
                                      max_delta_t=args.max_delta_t)
            adaptive.append({
                "name": name, "case": ADAPTIVE["case"], "solver": solver,
                "mesh": f"{nx}x{nz}", "dir": case_dir,
                "cells": params["cells"], "interval": args.interval,
                "deltaT_initial": params["deltaT"],
                "maxCo": params["maxCo"], "maxDeltaT": params["maxDeltaT"],
            })

    runs = []
    total = args.reps * len(configs) * len(args.ranks)
    for rep in range(1, args.reps + 1):
        for config in configs:
            for ranks in args.ranks:
                record = run_one(config["dir"], exes[config["solver"]],
                                 ranks, rep, args.steps, args.k0,
                                 config["cells"])
                record["config"] = config["name"]
                runs.append(record)
                print(f"bench/run: [{len(runs)}/{total}] rep {rep} "
                      f"{config['name']} np {ranks}: "
                      f"{record['us_per_cell_step']:.3f} us/cell/step, "
                      f"{record['rss_MB']:.0f} MB, "
                      f"{record['wall_s']:.1f} s", flush=True)
                (WORK / "results.partial.json").write_text(
                    json.dumps(runs, indent=1))

    adaptive_runs = []
    for rep in range(1, args.reps + 1):
        for config in adaptive:
            record = run_adaptive(config["dir"], exes[config["solver"]], rep,
                                  args.interval)
            record["config"] = config["name"]
            adaptive_runs.append(record)
            print(f"bench/run: [{len(adaptive_runs)}/"
                  f"{args.reps * len(adaptive)}] rep {rep} {config['name']} "
                  f"over {args.interval:g} s: {record['steps']} steps, "
                  f"median deltaT {record['deltaT_median_s']:.3g} s, "
                  f"viscous CFL {record['viscous_cfl_median']:.3g}, "
                  f"{record['cpu_per_simulated_s']:.3g} CPU s per "
                  f"simulated s, {record['wall_s']:.1f} s", flush=True)
            (WORK / "results.partial.json").write_text(
                json.dumps({"runs": runs, "adaptive_runs": adaptive_runs},
                           indent=1))

    whole = None
    if args.whole_end_time > 0 and "chute" in args.parts:
        whole = run_whole(args.whole_end_time)
        whole.update(command=command, date=results["date"],
                     machine=results["machine"],
                     software=results["software"])

    drum = None
    if "drum" in args.parts:
        drum = run_drum(args.drum_source, args.drum_start,
                        args.drum_duration, command)
        drum.update(machine=results["machine"], software=results["software"])

    for config in configs + adaptive:
        config["dir"] = str(config["dir"].relative_to(REPO))
    results["configs"] = configs
    results["runs"] = runs
    results["summary"] = summarise(configs, runs, args.ranks)
    results["per_simulated_second"] = None
    if adaptive:
        rows, speedup = summarise_adaptive(adaptive, adaptive_runs)
        results["per_simulated_second"] = {
            "settings": {
                "case": ADAPTIVE["case"], "mesh": adaptive[0]["mesh"],
                "ranks": 1, "interval_s": args.interval,
                "reps": args.reps,
                "controlDict": {**generate.ADJUSTABLE_STEP,
                                "maxDeltaT": args.max_delta_t,
                                "deltaT": adaptive[0]["deltaT_initial"],
                                **{"krylov": {"maxCo": c["maxCo"],
                                              "maxDeltaT": c["maxDeltaT"]}
                                   for c in adaptive
                                   if c["solver"] == "granular-krylov"}},
            },
            "configs": adaptive,
            "runs": adaptive_runs,
            "summary": rows,
            "speedup": speedup,
        }
    results["whole"] = whole
    results["drum"] = drum
    if set(args.parts) != set(PARTS):
        keep_parts(results, json.loads(RESULTS.read_text()), args.parts)
    RESULTS.write_text(json.dumps(results, indent=1) + "\n")
    report.write(results, MARKDOWN)
    print(f"bench/run: wrote {RESULTS.relative_to(REPO)} and "
          f"{MARKDOWN.relative_to(REPO)}")


if __name__ == "__main__":
    main(sys.argv[1:])

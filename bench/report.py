"""The results writer: BENCHMARKS.md from the numbers of bench/run.

bench/run calls write(); to render BENCHMARKS.md again from
bench/results.json (after editing this file, say):

    /usr/bin/python3 bench/report.py
"""

import json
import sys
from pathlib import Path

BENCH = Path(__file__).resolve().parent
REPO = BENCH.parent

# A run is flagged when other processes used more than this many cores
BUSY = 0.1

CASE_TITLE = {
    "chute": "chute (open)",
    "drum": "drum-like (closed)",
}


def number(x, decimals=3):
    return f"{x:.{decimals}f}"


def machine_lines(results):
    m, s = results["machine"], results["software"]
    cores = (f"{m['cpus']} CPUs ({m['sockets']} socket x "
             f"{m['cores_per_socket']} cores x {m['threads_per_core']} "
             f"thread(s))")
    uncommitted = s["uncommitted_sources"]
    commit = f"`{s['commit'][:12]}`"
    if uncommitted:
        commit += (" with uncommitted changes in "
                   + ", ".join(f"`{p}`" for p in uncommitted)
                   + " (the binaries below are what ran)")
    lines = [
        f"- CPU: {m['cpu']}, {cores}, {m['memory_GB']} GB",
        f"- System: {m['os']}, Linux {m['kernel']}",
        f"- Date: {results['date']}",
        f"- OpenFOAM {s['openfoam']} (Debian's binaries), {s['mpi']}",
        f"- Repository: {commit}",
    ]
    for path, digest in s["binaries"].items():
        shown = path.replace(str(REPO) + "/", "")
        lines.append(f"- `{shown}`: sha256 `{digest[:16]}`")
    return lines


def table(results):
    head = ("| case | solver | cells | ranks | steps | µs/(cell·step) min "
            "| median | ratio vs stock | peak RSS MB | parallel efficiency |")
    lines = [head, "|---|---|---|---|---|---|---|---|---|---|"]
    for row in results["summary"]:
        nx, nz = row["mesh"].split("x")
        ratio = ("1" if row["solver"] == "stock"
                 else number(row["ratio_median"], 2))
        efficiency = ("" if row["ranks"] == 1
                      else f"{100 * row['efficiency_median']:.0f} %")
        lines.append(
            f"| {CASE_TITLE[row['case']]} | {row['application']} "
            f"| {row['cells']} ({nx} × {nz}) | {row['ranks']} "
            f"| {row['steps']} | {number(row['us_min'])} "
            f"| {number(row['us_median'])} | {ratio} "
            f"| {row['rss_MB']:.0f} | {efficiency} |")
    return lines


def warnings(results):
    lines = []
    busy = [r for r in results["runs"] if r["other_load"] > BUSY]
    if busy:
        worst = max(busy, key=lambda r: r["other_load"])
        lines.append(
            f"- **The machine was not idle**: other processes used more "
            f"than {BUSY} cores during {len(busy)} of "
            f"{len(results['runs'])} runs (at most "
            f"{worst['other_load']:.2f} cores, {worst['config']} on "
            f"{worst['ranks']} rank(s)); the MPI runs suffer most. "
            "Per-run loads: `other_load` in bench/results.json.")
    for note in results["drift"]:
        lines.append(f"- {note}: the benchmark runs its own copy.")
    return lines


def write(results, path):
    s = results["settings"]
    lines = ["# Benchmarks", ""]
    if results["quick"]:
        lines += [
            "> **QUICK RUN** (`bench/run --quick`): "
            f"{s['steps']} steps, {s['reps']} repetition(s), the small mesh. "
            "It checks that the harness works end to end; its numbers are "
            "not a measurement (start-up dominates, ExecutionTime has a "
            "resolution of 0.01 s). Run `bench/run` on an idle machine for "
            "the benchmark.",
            ""]
    lines += [
        "Time per cell per time step of `granularSegregationFoam` against "
        "stock `multiphaseInterFoam` (v1912, Debian's binary) on the same "
        "meshes, the same fixed time steps, schemes and linear solvers. "
        "The cases, what differs between the solvers and why: "
        "[bench/README.md](bench/README.md). Raw numbers: "
        "`bench/results.json`.",
        "",
        "## Machine",
        "",
        *machine_lines(results),
        "",
        "## Command",
        "",
        f"    {results['command']}",
        "",
        f"{s['steps']} time steps per run, timed from the end of step "
        f"{s['k0']} to the last; {s['reps']} repetition(s) of every run, "
        "interleaved; fixed time step "
        + ", ".join(f"{dt:g} s on {mesh}" for mesh, dt in s["deltaT"].items())
        + "; "
        + (f"MPI: `{s['mpirun']} -np 2 ... -parallel`, decomposePar "
           "`simple` (2 1 1)." if 2 in s["ranks"] else "serial runs only."),
        "",
        "## Results",
        "",
        *table(results),
        "",
        "- µs/(cell·step): the solver's own `ExecutionTime` (CPU seconds of "
        "the master rank) at the last step minus at step k0, over the "
        "steps between them and the cells of the whole mesh; minimum and "
        "median over the repetitions.",
        "- ratio vs stock: median over the median of stock "
        "multiphaseInterFoam on the same case, mesh and ranks.",
        "- peak RSS: the peak resident set of every rank (`/usr/bin/time -f "
        "%M`) summed over the ranks, the largest of the repetitions.",
        "- parallel efficiency: t1/(2 t2) of the medians, t1 and t2 the "
        "times per step on 1 and 2 ranks.",
    ]
    notes = warnings(results)
    if notes:
        lines += ["", "## Warnings", "", *notes]
    Path(path).write_text("\n".join(lines) + "\n")


def main():
    results = json.loads((BENCH / "results.json").read_text())
    write(results, REPO / "BENCHMARKS.md")


if __name__ == "__main__":
    sys.exit(main())

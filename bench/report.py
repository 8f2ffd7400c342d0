"""The results writer: BENCHMARKS.md from the numbers of bench/run.

bench/run calls write(); to render BENCHMARKS.md again from
bench/results.json and bench/tutorials.json (after editing either, say):

    /usr/bin/python3 bench/report.py
"""

import json
import re
import sys
import textwrap
from pathlib import Path

BENCH = Path(__file__).resolve().parent
REPO = BENCH.parent

# A run is flagged when other processes used more than this many cores
BUSY = 0.1

CASE_TITLE = {
    "chute": "chute (open)",
    "drum": "drum-like (closed)",
}

SOLVER_TITLE = {
    "stock": "multiphaseInterFoam",
    "granular": "granularSegregationFoam",
    "granular-implicit": "granularSegregationFoam (implicit)",
    "granular-krylov": "granularSegregationFoam (Krylov, the chute's)",
}


def solver_title(row):
    return SOLVER_TITLE.get(row["solver"], row["application"])


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
        # From the project's platforms/ on: the checkout's folder varies
        shown = path[path.find("platforms/"):] if "platforms/" in path \
            else path
        lines.append(f"- `{shown}`: sha256 `{digest[:16]}`")
    return lines


def table_row(cells):
    """A row of a Markdown table; a | within a cell escaped."""
    return "| " + " | ".join(re.sub(r"(?<!\\)\|", r"\\|", str(c))
                             for c in cells) + " |"


def edit_list(edits):
    """The --edit entries of a run, without their dictionaries."""
    return ", ".join("`" + e.split(":", 1)[-1] + "`" for e in edits)


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
            f"| {CASE_TITLE[row['case']]} | {solver_title(row)} "
            f"| {row['cells']} ({nx} × {nz}) | {row['ranks']} "
            f"| {row['steps']} | {number(row['us_min'])} "
            f"| {number(row['us_median'])} | {ratio} "
            f"| {row['rss_MB']:.0f} | {efficiency} |")
    return lines


def significant(x, digits=3):
    return f"{x:.{digits}g}"


def adaptive_table(adaptive):
    head = ("| case | solver | cells | ranks | simulated s | steps "
            "| median Δt s | median viscous CFL | wall s per simulated s "
            "| CPU s per simulated s | speed-up (wall, CPU) |")
    lines = [head, "|---|---|---|---|---|---|---|---|---|---|---|"]
    speedup = adaptive["speedup"]
    if "wall" in speedup:           # a results file of the implicit alone
        speedup = {"granular-implicit": speedup}
    for row in adaptive["summary"]:
        nx, nz = row["mesh"].split("x")
        mine = speedup.get(row["solver"])
        faster = ("1" if mine is None
                  else f"{mine['wall']:.1f}, {mine['cpu']:.1f}")
        lines.append(
            f"| {CASE_TITLE[row['case']]} | {solver_title(row)} "
            f"| {row['cells']} ({nx} × {nz}) | {row['ranks']} "
            f"| {row['interval_s']:g} | {row['steps']:g} "
            f"| {significant(row['deltaT_median_s'])} "
            f"| {significant(row['viscous_cfl_median'])} "
            f"| {significant(row['wall_per_simulated_s'])} "
            f"| {significant(row['cpu_per_simulated_s'])} | {faster} |")
    return lines


def adaptive_section(results):
    adaptive = results.get("per_simulated_second")
    if not adaptive:
        return []
    s = adaptive["settings"]
    c = s["controlDict"]
    return [
        "## Time per simulated second",
        "",
        f"    {results['command']}",
        "",
        "(the same command as the table above; `--interval 0` leaves this "
        "one out). Every run is `granularSegregationFoam`, serial, in "
        + " and ".join(f"`{c['dir']}`" for c in adaptive["configs"])
        + ". "
        f"The chute on {s['mesh'].replace('x', ' × ')}, serial, "
        f"{s['interval_s']:g} s simulated from rest, "
        f"{s['reps']} repetition(s) (interleaved with each other, after "
        "the runs above); the time step adjusted to the CFL (4.11): "
        f"controlDict `adjustTimeStep {c['adjustTimeStep']}; "
        f"maxCo {c['maxCo']:g}; maxAlphaCo {c['maxAlphaCo']:g}; "
        f"maxDeltaT {c['maxDeltaT']:g};`, from deltaT {c['deltaT']:g} s "
        "(growing by at most 20 % a step). Explicit: the common "
        "fvSolution; implicit: PIMPLE `"
        + implicit_entries(results) + "`"
        + ("; Krylov: `" + krylov_entries(results) + "`, "
           f"maxCo {c['krylov']['maxCo']:g} and maxDeltaT "
           f"{c['krylov']['maxDeltaT']:g} (the chute tutorial's)"
           if "krylov" in c else "") + ".",
        "",
        *adaptive_table(adaptive),
        "",
        "- steps, median Δt: the steps the solver took over the interval "
        "and the median of their Δt; median over the repetitions.",
        "- median viscous CFL: the median over the steps of the viscous "
        "part of (4.11) the solver prints before every step (with the "
        "previous step's Δt), i.e. Δt over the viscous-CFL step; with "
        "`viscousStress implicit` it does not limit Δt.",
        "- wall and CPU s per simulated s: from the end of the first step "
        "(start-up left out) to the end of the last, over the simulated "
        "time between them; CPU from `ExecutionTime`, wall from the "
        "arrival of its log lines; median over the repetitions.",
        "- speed-up: the explicit run's time per simulated second over the "
        "row's (medians).",
    ]


def status_cell(r):
    """The status of run r in one table cell, however long the reason."""
    status = " ".join(str(r["status"]).replace("|", "/").split())
    return status if len(status) <= 80 else status[:77] + "..."


def speedup_lines(speedup):
    """The closing line of a reference-against-tutorial section."""
    return ["", "Speed-up of the tutorial over the reference (CPU): "
            + (f"**{speedup:.2f}**." if speedup else "—.")]


def whole_section(results):
    """The whole chute runs of bench/run: the reference coupling and the
    tutorial's, side by side."""
    whole = results.get("whole")
    if not whole:
        return []
    runs = whole["runs"]
    lines = [
        "## Whole runs: the reference against the tutorial",
        "",
        f"    {whole.get('command', results['command'])}",
        "",
        "(the same command as the tables above, after them; "
        "`--whole-end-time 0` leaves this one out). The chute tutorial "
        f"({whole['mesh'].replace('x', ' × ')}) from rest to "
        f"{whole['end_time']:g} s, serial, the two runs side by side on "
        "the two cores: the reference, "
        f"{whole['settings']['reference']['coupling']} with the phases' "
        "transport in the momentum step and maxDeltaT "
        f"{whole['settings']['reference']['max_delta_t']:g} s, and the "
        "tutorial as its files say (`tutorials/chute/system`). The outflow "
        "at the end against Bagnold (5.4), Gray & Chugunov (5.8) and the "
        "depth-averaged φ^s of (5.10) (0.6744), and its change over the "
        "last written second (`granularfoam.post.chute`; `bench/harness "
        "chute` runs other couplings the same way).",
        "",
        "| run | steps | CPU [s] | CPU s per simulated s | ms per step | "
        "pressure solutions / step | u vs (5.4) | φ^s vs (5.8) | φ̄^s | "
        "u change, last second | φ^s change, last second | status |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    g = dash_or
    for name in ("reference", "tutorial"):
        r = runs[name]
        ok = r["status"] == "ok"
        cells = [name, g(r["steps"], "{}"), g(r["cpu_seconds"], "{:.0f}"),
                 g(r["cpu_per_simulated_s"], "{:.3g}"),
                 g(r["ms_per_step"], "{:.3g}"),
                 g(r["pressure_solutions_per_step"], "{:.1f}")]
        cells += outflow_cells(r, ok)
        cells.append(status_cell(r))
        lines.append(table_row(cells))
    return lines + speedup_lines(whole.get("speedup"))


def drum_window_cells(r, diff):
    """The cells of drum revolution r's monitor: J at the end, the mean
    surface angle, the peak speed's mean / largest, each followed by
    diff(key), and the lowest grain pressure (steps below zero)."""
    return [
        dash_or(r["J_end"], "{:.4f}") + diff("J_end"),
        f"{r['surface_angle_mean_deg']:.2f}"
        + diff("surface_angle_mean_deg"),
        f"{r['peak_speed_mean']:.3f}{diff('peak_speed_mean')} / "
        f"{r['peak_speed_max']:.3f}{diff('peak_speed_max')}",
        f"{r['lowest_p_grains']:.1f} "
        f"({r['steps_with_negative_p_grains']})"]


def drum_section(results):
    """The drum part of bench/run: one revolution from a written state of
    the drum tutorial with the reference coupling and with the tutorial's,
    the tutorial's speed-up and its J, surface angle and peak speed against
    the reference's."""
    d = results.get("drum")
    if not d:
        return []
    ref_coupling = d["settings"]["reference"]["coupling"]
    ref_edits = d["settings"]["reference"]["edits"]
    lines = [
        "## Drum revolution: the reference against the tutorial",
        "",
        f"    {d['command']}",
        "",
        f"({d['date'][:10]}, {d['machine']['cpu']}, "
        f"{d['machine']['cpus']} cores; `--parts drum` runs this part "
        "alone.) The "
        f"square drum tutorial at N = {d['N']} from its written time "
        f"{d['start']:g} s (`{d['source']}`, a run of "
        "`tutorials/squareDrum`) to "
        f"{d['end']:g} s, on its {d['ranks']} ranks with the tutorial's "
        "fvSolution, fvSchemes and controlDict, one run after the "
        f"other: the reference, `{ref_coupling}` with "
        f"{edit_list(ref_edits)} (the coupling converged at the chute "
        "reference's step, the phases transported in the momentum step; "
        "`bench/harness drum` names it the same way), and the tutorial as "
        "its files say. J of (7.6) at the end, the surface angle and the "
        "peak speed over the revolution (the `rotatingDrum` monitor), the "
        "lowest pressure seen by the rheology in the grains over the "
        "steps; the tutorial's relative difference from the reference in "
        "brackets.",
        "",
        "| run | steps | CPU [s] | ms per step | pressure solutions / step "
        "| J at the end | surface angle, mean [deg] | peak speed, mean / "
        "max [m/s] | lowest p grains [Pa] (steps < 0) | status |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    g = dash_or

    def vs(r, key):
        d = r.get(f"{key}_vs_reference")
        return "" if d is None else f" ({d:+.1%})"

    for name in ("reference", "tutorial"):
        r = d["runs"][name]
        cells = [name, g(r.get("steps"), "{}"),
                 g(r.get("cpu_seconds"), "{:.0f}"),
                 g(r.get("ms_per_step"), "{:.3g}"),
                 g(r.get("pressure_solutions_per_step"), "{:.1f}")]
        if "J_end" in r:
            cells += drum_window_cells(r, lambda key: vs(r, key))
        else:
            cells += ["", "", "", ""]
        cells.append(status_cell(r))
        lines.append(table_row(cells))
    return lines + speedup_lines(d.get("speedup"))


def tutorials_section():
    """The tutorials' run times, measured by hand with the commands given
    (bench/tutorials.json): runs of minutes to hours that bench/run does
    not repeat."""
    path = BENCH / "tutorials.json"
    if not path.exists():
        return []
    runs = json.loads(path.read_text())["runs"]
    lines = [
        "## Tutorial run times",
        "",
        "Measured by hand on these 2-core machines (not always the machine "
        "above: the column 'measured' says when and beside what) with the "
        "command of each row; the numbers are in `bench/tutorials.json` and "
        "rendered here by `bench/report.py`. CPU: the solver's "
        "`ExecutionTime` (one rank); wall: its `ClockTime`.",
        "",
        "| case | mesh | settings | simulated | CPU s | wall s | "
        "to the steady state | result | measured | command |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in runs:
        cells = [r["case"], r["mesh"], r["settings"], r["simulated"],
                 r.get("cpu_s", "–"), r.get("wall_s", "–"),
                 r.get("to_steady", "–"), r["result"], r["measured"],
                 f"`{r['command']}`"]
        lines.append(table_row(cells))
    return lines


def coupling_order(name):
    """Sort key of a coupling name: its family, preconditioner, count and
    the rest (PISO-10, Krylov-BFBt-20-tol1e-3)."""
    m = re.match(r"([A-Za-z]+)-(?:([A-Za-z]+)-)?(\d+)(.*)", name)
    if not m:
        return (name, "", 0, "")
    return (m.group(1), m.group(2) or "", int(m.group(3)), m.group(4))


def dash_or(x, fmt="{:.3g}"):
    """x formatted, or a dash for None."""
    return "–" if x is None else fmt.format(x)


def coupling_runs(section):
    """The runs of a section of bench/coupling.json (none without it)."""
    path = BENCH / "coupling.json"
    return (json.loads(path.read_text()).get(section, {}).get("runs", [])
            if path.exists() else [])


def outflow_cells(r, ok):
    """The outflow columns of a whole chute run r (granularfoam.post.chute
    outflow): u vs (5.4), phi^s vs (5.8), phi-bar^s and their changes over
    the last second; empty unless ok."""
    return [dash_or(r.get(key), fmt) if ok else ""
            for key, fmt in (("outlet_l2_u_bagnold", "{:.3%}"),
                             ("outlet_l2_phis_gray_chugunov", "{:.3%}"),
                             ("outlet_depth_averaged_phis", "{:.4f}"),
                             ("outlet_change_last_interval_u", "{:.2g}"),
                             ("outlet_change_last_interval_phis", "{:.2g}"))]


def whole_chute_section():
    """Whole chute runs with a coupling (bench/harness chute)."""
    runs = coupling_runs("whole_chute")
    if not runs:
        return []
    lines = [
        "## Whole chute runs by coupling",
        "",
        "`bench/harness chute` (see `bench/README.md`): the chute tutorial "
        "(155 × 40) from rest, serial, once per coupling; the outflow at the "
        "end against Bagnold (5.4), Gray & Chugunov (5.8) and the "
        "depth-averaged φ^s of (5.10) (0.6744), and its change over the "
        "last written second (u: of its maximum; φ^s: the largest absolute "
        "change). CPU seconds compare between runs of one date, which ran "
        "side by side on the two cores. Numbers in `bench/coupling.json` "
        "(`whole_chute`).",
        "",
        "| coupling | maxAlphaSubCycles | maxDeltaT [s] | end [s] | steps | "
        "CPU [s] | pressure solutions / step | u vs (5.4) | φ^s vs (5.8) | "
        "φ̄^s | u change, last second | φ^s change, last second | date | "
        "status |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]

    g = dash_or

    for r in sorted(runs, key=lambda r: (r["end_time"],
                                         *coupling_order(r["coupling"]))):
        ok = r["status"] == "ok"
        cells = [r["coupling"] + (" " + ", ".join(
                     "`" + e.split(":", 1)[-1] + "`" for e in r["edits"])
                     if r["edits"] else ""),
                 ("1, in the step" if r["max_alpha_sub_cycles"] == 0
                  else g(r["max_alpha_sub_cycles"], "{}")),
                 g(r["max_delta_t"]), g(r["end_time"]), g(r["steps"], "{}"),
                 g(r["cpu_seconds"], "{:.0f}"),
                 g(r["pressure_solutions_per_step"], "{:.1f}"),
                 *outflow_cells(r, ok),
                 g(r.get("date"), "{}"),
                 r["status"]]
        lines.append(table_row(cells))
    return lines


def drum_coupling(r):
    """The coupling of drum revolution r as the table names it: the
    harness's coupling name, or for the source case's own fvSolution
    (harness.TUTORIAL_NAME) the source's coupling."""
    import harness
    if r["coupling"] == harness.TUTORIAL_NAME:
        return f"the source's fvSolution ({r['source_coupling']})"
    return r["coupling"]


def is_drum_reference(q):
    """Whether the drum revolution q is a reference revolution
    (harness.DRUM_REFERENCE) that ended well."""
    import harness
    name, edits = harness.DRUM_REFERENCE
    return (q["coupling"] == name and sorted(q["edits"]) == sorted(edits)
            and q["status"].startswith("ok") and "J_end" in q)


def drum_reference(runs, r):
    """The reference revolution of r's source and window among runs; None
    if there is none, and for the reference itself."""
    for q in runs:
        if (q is not r and is_drum_reference(q)
                and (q["source"], q["start"], q["end"])
                == (r["source"], r["start"], r["end"])):
            return q
    return None


def whole_drum_section(results=None):
    """One drum revolution from a written time, by coupling (bench/harness
    drum), against the run it started from or, from a state, against the
    reference revolution (of bench/harness drum, or of bench/run's drum
    part in results)."""
    from granularfoam.post import drum
    import harness
    runs = coupling_runs("whole_drum")
    if not runs:
        return []
    bench_drum = (results or {}).get("drum")
    references = (runs + [bench_drum["runs"]["reference"]] if bench_drum
                  else runs)
    lines = [
        "## Whole drum revolutions by coupling",
        "",
        "`bench/harness drum` (see `bench/README.md`): one revolution of "
        "the square drum from a written time of a run, on that run's "
        "decomposition, once per coupling; J of (7.6) at the end, the "
        "surface angle and the peak speed over the revolution (the "
        "`rotatingDrum` monitor) and the lowest pressure seen by the "
        "rheology in the grains over the steps, each with the source run's "
        "over the same revolution and the relative difference. CPU: the "
        "master rank's, per simulated second, and projected to the eight "
        "revolutions of the tutorial (80 s) on as many cores as ranks. A "
        "row of part of a revolution (`--duration`) gives that cost alone. "
        "From a state (not a run) the differences are against the "
        "reference revolution from the same state (here or in bench/run's "
        "drum part): "
        f"`{harness.DRUM_REFERENCE[0]}` with "
        f"{edit_list(list(harness.DRUM_REFERENCE[1]))} (the coupling "
        "converged at the chute reference's step, the phases transported "
        "in the momentum step); the speed-up only against such a "
        "revolution here of the same date, as CPU seconds compare between "
        "rows run one after the other: the machine's speed moves by up to "
        "a fifth within a day (the same settings here and in bench/run's "
        "drum part). "
        "Numbers in `bench/coupling.json` (`whole_drum`).",
        "",
        "| N | revolution [s] | coupling | steps | CPU [s] | CPU / "
        "simulated s | 8 revolutions, projected [h] | speed-up vs the "
        "reference | pressure "
        "solutions / step | J at the end | surface angle, mean [deg] | "
        "peak speed, mean / max [m/s] | lowest p grains [Pa] (steps < 0) "
        "| status |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]

    g = dash_or

    def per_second(cpu, r):
        """CPU per simulated second and the eight revolutions' hours."""
        if cpu is None:
            return ["", ""]
        rate = cpu / (r["end"] - r["start"])
        return [f"{rate:.0f}", f"{rate * 8 * drum.PERIOD / 3600:.1f}"]

    def vs(r, key, ref):
        d = r.get(f"{key}_vs_source")
        if d is None and ref is not None:
            d = r[key] / ref[key] - 1
        return "" if d is None else f" ({d:+.1%})"

    def speed_up(r, ref):
        """Against a reference revolution of bench/harness drum of the
        same date only: bench/run's reference ran in another invocation,
        and the machine's speed moves between them (see the text)."""
        if is_drum_reference(r):
            return "1"
        if (ref is None or not r.get("cpu_seconds")
                or not any(ref is q for q in runs)
                or ref.get("date") != r.get("date")):
            return ""
        return f"{ref['cpu_seconds'] / r['cpu_seconds']:.1f}"

    sources = {}
    for r in sorted(runs, key=lambda r: (r["N"], r["start"],
                                         *coupling_order(r["coupling"]))):
        ok = r["status"].startswith("ok")
        src = r.get("source_window")
        if src and (r["source"], r["start"]) not in sources:
            sources[(r["source"], r["start"])] = True
            lines.append(
                f"| {r['N']} | {r['start']:g}–{r['end']:g} | the "
                f"source run ({r['source_coupling']}) | "
                f"{src['window_steps']} | "
                f"{src['window_cpu_seconds']:.0f} | "
                + " | ".join(per_second(src['window_cpu_seconds'], r))
                + " | | | "
                f"{g(src['J_end'], '{:.4f}')} | "
                f"{src['surface_angle_mean_deg']:.2f} | "
                f"{src['peak_speed_mean']:.3f} / {src['peak_speed_max']:.3f}"
                f" | {src['lowest_p_grains']:.1f} "
                f"({src['steps_with_negative_p_grains']}) | |")
        name = " ".join(filter(None, [drum_coupling(r),
                                      edit_list(r["edits"])]))
        ref = drum_reference(references, r) if not src else None
        cpu = g(r["cpu_seconds"], "{:.0f}")
        if r.get("cpu_seconds_repeats"):
            cpu += f" (median of {len(r['cpu_seconds_repeats'])})"
        cells = [r["N"], f"{r['start']:g}–{r['end']:g}", name,
                 r["steps"], cpu,
                 *per_second(r["cpu_seconds"], r),
                 speed_up(r, ref) if ok and "J_end" in r else "",
                 g(r["pressure_solutions_per_step"], "{:.1f}")]
        if ok and "J_end" in r:
            cells += drum_window_cells(r, lambda key: vs(r, key, ref))
        else:
            cells += ["", "", "", ""]
        cells.append(r["status"])
        lines.append(table_row(cells))
    return lines


def profile_section():
    """The time shares of the whole chute runs made with OpenFOAM's
    profiling on (bench/harness chute --edit
    "system/controlDict:profiling={ active true; }")."""
    runs = [r for r in coupling_runs("whole_chute")
            if r.get("profile_shares")]
    if not runs:
        return []
    lines = [
        "## Where a whole chute run spends its time",
        "",
        "OpenFOAM's profiling of whole chute runs (the rows above with "
        "`profiling`): each section's share of the time loop, its children "
        "included. The linear solvers' own sections "
        "(`lduMatrix::solver.*`) are left out: v1912 times a solver over "
        "the life of its object, so that GAMG's coarsest-level solver "
        "(`coarsestLevelCorr`) spans nearly all of its parent's solution; "
        "`fvMatrix::solve.*` and the `granular::Krylov::*Solve` sections "
        "time the solutions. Numbers in "
        "`bench/coupling.json` (`whole_chute`, `profile_shares`).",
        "",
    ]
    for r in runs:
        lines += [f"{r['coupling']}, maxAlphaSubCycles "
                  f"{r['max_alpha_sub_cycles']}, maxDeltaT "
                  f"{r['max_delta_t']:g} s, {r['steps']} steps, "
                  f"{r['cpu_seconds']:.0f} s CPU:", "",
                  "| section | share of the time loop |", "|---|---|"]
        for name, share in sorted(r["profile_shares"].items(),
                                  key=lambda kv: -kv[1]):
            lines.append(f"| `{name}` | {share:.1%} |")
        lines.append("")
    return lines[:-1]


def drum_profile_section():
    """The time shares of the drum runs made with OpenFOAM's profiling on
    (bench/harness drum --edit "system/controlDict:profiling={ active
    true; }"), one column a run, the master rank's profile."""
    profile = "system/controlDict:profiling={ active true; }"
    runs = [r for r in coupling_runs("whole_drum")
            if r.get("profile_shares")]
    if not runs:
        return []
    names = sorted({n for r in runs for n in r["profile_shares"]},
                   key=lambda n: -max(r["profile_shares"].get(n, 0)
                                      for r in runs))
    lines = [
        "## Where a drum step spends its time",
        "",
        "OpenFOAM's profiling of the drum runs of *Whole drum revolutions* "
        "made with `profiling`, on the master rank: each section's share of "
        "the time loop, its children included (the linear solvers' own "
        "sections are left out, as for the chute). Columns: N, the window, "
        "the coupling and the other edits; then the CPU per step and the "
        "Krylov iterations and inner iterations per step. Numbers in "
        "`bench/coupling.json` (`whole_drum`, `profile_shares`).",
        "",
        table_row(["section"] + [
            " ".join(filter(None, [
                f"N = {r['N']}, {r['start']:g}–{r['end']:g} s, "
                + drum_coupling(r),
                edit_list(e for e in r["edits"] if e != profile)]))
            for r in runs]),
        "|---" * (len(runs) + 1) + "|",
        table_row(["CPU per step [s]"] + [
            dash_or(r["cpu_seconds"] / r["steps"]
                    if r["steps"] and r["cpu_seconds"] is not None else None,
                    "{:.3f}") for r in runs]),
        table_row(["Krylov iterations / step"] + [
            dash_or(r.get("krylov_iterations_per_step"), "{:.1f}")
            for r in runs]),
        table_row(["inner iterations / step"] + [
            dash_or(r.get("inner_iterations_per_step"), "{:.0f}")
            for r in runs]),
    ]
    for name in names:
        lines.append(table_row([f"`{name}`"] + [
            f"{r['profile_shares'][name]:.1%}"
            if name in r["profile_shares"] else "–" for r in runs]))
    return lines


def spectra_section():
    """Ritz values of the Krylov coupling (bench/harness spectrum)."""
    runs = coupling_runs("krylov_spectra")
    if not runs:
        return []
    lines = [
        "## Spectrum of the preconditioned Krylov coupling",
        "",
        "`bench/harness spectrum` (see `bench/README.md`): one step of Δt "
        "from a state with up to 30 FGMRES iterations; the Ritz values are "
        "the eigenvalues of the Hessenberg matrix, an estimate of the "
        "spectrum of the preconditioned operator (all 1 for an exact "
        "preconditioner). Numbers in `bench/coupling.json` "
        "(`krylov_spectra`).",
        "",
        "| state | model edits | Δt [s] | preconditioner | iterations | "
        "residual reduced to | Ritz values, smallest–largest \\|λ\\| |",
        "|---|---|---|---|---|---|---|",
    ]
    order = {"chute1": 0, "chute20": 1, "layer2d": 2, "layer2dSquare": 3,
             "drum50": 4}
    for r in sorted(runs, key=lambda r: (order.get(r["state"], 9),
                                         r["edits"], r["dt"],
                                         r["preconditioner"])):
        edits = ", ".join("`" + e.split(":", 1)[-1] + "`"
                          for e in r["edits"]) or "–"
        if r["status"] != "ok":
            cells = [r["state"], edits, f"{r['dt']:g}", r["preconditioner"],
                     r["status"], "", ""]
        else:
            cells = [r["state"], edits, f"{r['dt']:g}", r["preconditioner"],
                     str(r["iterations"]), f"{r['relative_residual']:.2g}",
                     f"{r['ritz_smallest']:.3g}–{r['ritz_largest']:.3g}"]
        lines.append(table_row(cells))
    return lines


def harness_section():
    """The coupling harness's measurements (bench/coupling.json, written
    by bench/harness): every coupling against 200 correctors from the same
    state, over the same steps."""
    runs = coupling_runs("harness")
    if not runs:
        return []
    lines = [
        "## Convergence of the coupling within a step",
        "",
        "`bench/harness` (see `bench/README.md`): from a written state, "
        "each coupling runs `steps` fixed steps of Δt, serial; errors are "
        "relative L2 norms against the reference of 200 PISO correctors "
        "(p_rgh to 1e-13) from the same state over the same steps: U over "
        "the grains (φ^a < ½) and over the air, p along the base. A model "
        "edit (`bench/harness states --edit`) is judged against its own "
        "reference. A row whose coupling reads \"A vs B\" is judged against "
        "the coupling B instead (`bench/harness run --reference B`). Numbers "
        "in `bench/coupling.json` (`harness`), rendered here by "
        "`bench/report.py`; each row's command and date are there.",
        "",
        "| state | model edits | Δt [s] | steps | coupling | U grains | "
        "U air | p base | max \\|w\\| air (reference) [m/s] | "
        "lowest p grains (reference) [Pa] | "
        "pressure solutions / step | CPU ms / step (reference) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]

    def edits(r):
        return edit_list(r["edits"]) or "–"

    def steps(r):
        """Steps compared (of the steps run, where they differ)."""
        run = r.get("steps_run", r["steps"])
        shown = "?" if r["steps"] is None else str(r["steps"])
        return shown if run == r["steps"] else f"{shown} of {run}"

    def g(x):
        return "–" if x is None else f"{x:.2g}"

    def coupling(r):
        ref = r.get("reference", "reference")
        return r["coupling"] + ("" if ref == "reference" else f" vs {ref}")

    order = {"chute1": 0, "chute20": 1, "layer2d": 2, "drum50": 3}
    for r in sorted(runs, key=lambda r: (
            order.get(r["state"], 9), r["edits"], r["dt"] or 0,
            r.get("steps_run", r["steps"]) or 0,
            *coupling_order(r["coupling"]))):
        head = [r["state"], edits(r), g(r["dt"]), steps(r)]
        if r["status"] != "ok":
            cells = head + [coupling(r), r["status"], "", "", "", "", "", ""]
        elif r["coupling"] == r.get("reference", "reference"):
            # The reference's own run: its cost, no error
            cells = head + [r["coupling"] + " (the reference)", "–", "–",
                            "–", "–", "–",
                            g(r["pressure_solutions_per_step"]),
                            g(r["cpu_ms_per_step"])]
        else:
            cells = head + [
                coupling(r), g(r["l2_u_grains"]), g(r["l2_u_air"]),
                g(r["l2_p_base"]),
                f"{g(r['max_w_air'])} ({g(r['max_w_air_reference'])})",
                f"{g(r.get('min_p_grains'))} "
                f"({g(r.get('min_p_grains_reference'))})",
                g(r["pressure_solutions_per_step"]),
                f"{g(r['cpu_ms_per_step'])} "
                f"({g(r.get('reference_cpu_ms_per_step'))})"]
        lines.append(table_row(cells))
    return lines


def _entries(entries):
    """fvSolution entries as they read in the file, e.g.
    'momentumPredictor yes; viscousStress implicit; ...'."""
    return " ".join(f"{k.split('/')[-1]} {v}" + ("" if v.endswith("}")
                                                   else ";")
                    for k, v in entries.items())


def implicit_entries(results):
    """The implicit configuration's fvSolution entries."""
    return _entries(results["settings"].get("implicit_fvSolution", {}))


def krylov_entries(results):
    """The Krylov configuration's fvSolution entries (the chute
    tutorial's coupling) in their blocks, e.g. 'PIMPLE { ... } "alpha.*"
    { maxAlphaSubCycles 20; }'."""
    blocks = {}
    for k, v in results["settings"].get("krylov_fvSolution", {}).items():
        *block, key = k.split("/")
        blocks.setdefault(block[-1], {})[key] = v
    return " ".join(f"{b} {{ {_entries(e)} }}" for b, e in blocks.items())


def warnings(results):
    lines = []
    adaptive = results.get("per_simulated_second") or {}
    all_runs = results["runs"] + adaptive.get("runs", [])
    busy = [r for r in all_runs if r["other_load"] > BUSY]
    if busy:
        worst = max(busy, key=lambda r: r["other_load"])
        lines.append(
            f"- **The machine was not idle**: other processes used more "
            f"than {BUSY} cores during {len(busy)} of "
            f"{len(all_runs)} runs (at most "
            f"{worst['other_load']:.2f} cores, {worst['config']} on "
            f"{worst['ranks']} rank(s)); the MPI runs suffer most. "
            "Per-run loads: `other_load` in bench/results.json.")
    return lines


def write(results, path):
    s = results["settings"]
    adaptive = results.get("per_simulated_second")
    implicit = s.get("implicit_fvSolution", {})
    lines = ["# Benchmarks", ""]
    if results["quick"]:
        simulated = (f", {adaptive['settings']['interval_s']:g} s "
                     "simulated" if adaptive else "")
        lines += [
            "> **QUICK RUN** (`bench/run --quick`): "
            f"{s['steps']} steps, {s['reps']} repetition(s), the small mesh"
            f"{simulated}. "
            "It checks that the harness works end to end; its numbers are "
            "not a measurement (start-up dominates, ExecutionTime has a "
            "resolution of 0.01 s). Run `bench/run` on an idle machine for "
            "the benchmark.",
            ""]
    lines += [
        "Time per cell per time step of `granularSegregationFoam`, with "
        "the viscous stress explicit (the paper's) and implicit "
        "(`viscousStress implicit`)"
        + (" and with the chute tutorial's Krylov coupling"
           if s.get("krylov_fvSolution") else "") + ", against "
        "stock `multiphaseInterFoam` (v1912, Debian's binary) on the same "
        "meshes, the same fixed time steps, schemes and linear solvers"
        + ("; then the time per simulated second of the granular solver, "
           + ("explicit, implicit and Krylov"
              if s.get("krylov_fvSolution") else "explicit and implicit")
           + ", with the time step adjusted to its CFL. "
           if adaptive else ". ") +
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
        "- granularSegregationFoam (implicit): fvSolution PIMPLE `"
        + implicit_entries(results) + "` at the same fixed Δt: a momentum solve and "
        f"{implicit.get('PIMPLE/nCorrectors', '?')} pressure correctors "
        "a step instead of 2, so a step costs more"
        + ("; the time step it allows is in the next table."
           if adaptive else "."),
    ]
    if s.get("krylov_fvSolution"):
        lines += [
            "- granularSegregationFoam (Krylov, the chute's): the chute "
            "tutorial's coupling, fvSolution `" + krylov_entries(results)
            + "`, at the same fixed Δt: a momentum solve, the Krylov "
            "iterations (each an inner momentum and pressure solution) and "
            "a final pressure corrector a step"
            + ("; the time step it allows is in the next table."
               if adaptive else ".")]
    for section in (adaptive_section(results), whole_section(results),
                    drum_section(results)):
        if section:
            lines += ["", *section]
    for section in (harness_section(), spectra_section(),
                    whole_chute_section(), profile_section(),
                    whole_drum_section(results), drum_profile_section(),
                    tutorials_section()):
        if section:
            lines += ["", *section]
    notes = warnings(results)
    if notes:
        lines += ["", "## Warnings", "", *notes]
    Path(path).write_text("\n".join(lines) + "\n")


TWO_COMMANDS_BEGIN = "<!-- two-commands: rendered by bench/report.py -->"
TWO_COMMANDS_END = "<!-- end two-commands -->"


def two_commands_lines(t):
    """README.md's paragraphs on ./Allrun and ./Alltest from the times of
    bench/twocommands (bench/twocommands.json)."""
    lab = t["chute_lab_frame_clock_s"]
    moving = t["chute_moving_frame_clock_s"]
    where = f"on a fresh clone on {t['cores']} cores"
    if t["load_before"] > 0.5:
        where += f" (load {t['load_before']:g} at the start)"
    paragraphs = [
        "Set up, build and run the chute of §5 on its default mesh (0 to "
        "25 s, then 8 to 14 s in the frame of the front), leaving figures "
        f"3–6 in `tutorials/chute/figures/` ({t['allrun_s'] / 60:.1f} min "
        f"{where}: {lab:.0f} s for the lab frame on {t['cores']} ranks, "
        f"{moving:.0f} s for the frame of the front, the rest for the "
        "set-up, the build and the figures):",
        "    ./Allrun",
        "Set up, build and run the tests (`./Allrun` then `./Alltest`, what "
        f"CI runs, took {(t['allrun_s'] + t['alltest_s']) / 60:.0f} min "
        f"{where}, the {t['tests_passed']} tests "
        f"{t['tests_s'] / 60:.0f} min of it; `bench/twocommands` measures it, "
        "into `bench/twocommands.json`):",
        "    ./Alltest",
    ]
    lines = []
    for p in paragraphs:
        lines += [p if p.startswith("    ") else textwrap.fill(p, 76), ""]
    return lines[:-1]


def render_readme(path=REPO / "README.md"):
    """Replaces the paragraphs between README.md's two-commands markers by
    those of bench/twocommands.json."""
    times = json.loads((BENCH / "twocommands.json").read_text())
    text = Path(path).read_text()
    begin = text.index(TWO_COMMANDS_BEGIN) + len(TWO_COMMANDS_BEGIN)
    end = text.index(TWO_COMMANDS_END)
    Path(path).write_text(text[:begin] + "\n"
                          + "\n".join(two_commands_lines(times)) + "\n"
                          + text[end:])


def main():
    results = json.loads((BENCH / "results.json").read_text())
    write(results, REPO / "BENCHMARKS.md")
    if (BENCH / "twocommands.json").exists():
        render_readme()


if __name__ == "__main__":
    sys.exit(main())

"""Figure 1 of Barker et al. (2021): the friction laws of Jop et al. (2.7)
and Barker & Gray (2.8) with table 1's parameters, where each is well posed
by (2.6), I_1 and I_max, all from libgranularRheology through its utility
granularWellPosedness (the ranges it prints, the table of mu(I) and of the
indicator that -table writes):

    /usr/bin/python3 validation/chute/figure1.py tutorials/wellPosedness [--out DIR]

writes DIR/figure1.png and DIR/figure1.json (default DIR:
validation/chute/measured).  The OpenFOAM environment must be sourced.
"""
import argparse
import json
import re
import subprocess
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

I_RANGE = (1e-7, 100.0)         # the scan of the utility and the plot
POINTS = 1200


def parse_ranges(log):
    """{phase: [(lo, hi), ...]} of the well-posed ranges printed by
    granularWellPosedness (of the law of each phase, not of the unregularised
    law it also prints for a Barker-Gray phase)."""
    ranges, phase = {}, None
    for line in log.splitlines():
        m = re.match(r"grain phase (\S+): frictionLaw (\S+)", line)
        if m:
            phase = m.group(1)
            ranges[phase] = []
            continue
        m = re.match(r"    well posed for I in \[(\S+), (\S+)\]", line)
        if m and phase:
            ranges[phase].append((float(m.group(1)), float(m.group(2))))
    return ranges


def run_utility(case):
    """Run granularWellPosedness with -table in case: (its log, the table
    as a dict of columns)."""
    table = Path(case).resolve() / "figure1.dat"
    proc = subprocess.run(
        ["granularWellPosedness", "-Imin", str(I_RANGE[0]), "-Imax",
         str(I_RANGE[1]), "-table", str(table), "-points", str(POINTS)],
        cwd=case, capture_output=True, text=True, check=True)
    names = table.read_text().splitlines()[0].lstrip("# ").split()
    data = np.loadtxt(table, comments="#")
    return proc.stdout, {n: data[:, k] for k, n in enumerate(names)}


def I1_of(log):
    """I_1 of the Barker-Gray phase, as the utility prints it."""
    m = re.search(r"^\s+I1 = (\S+)$", log, re.M)
    assert m, "no I1 in the utility's log"
    return float(m.group(1))


def figure1(log, cols, out):
    """mu(I) of both laws, their well-posed ranges shaded, I_1 marked."""
    ranges = parse_ranges(log)
    I1 = I1_of(log)
    I = cols["I"]
    colours = {"Jop": "tab:red", "BarkerGray": "tab:blue"}
    fig, (ax, inset) = plt.subplots(1, 2, figsize=(10, 4),
                                    gridspec_kw={"width_ratios": [2, 1]})
    for phase in ("Jop", "BarkerGray"):
        mu = cols[f"mu.{phase}"]
        for a in (ax, inset):
            a.plot(I, mu, color=colours[phase],
                   label=f"{phase} " + ("(2.7)" if phase == "Jop" else "(2.8)"))
            for lo, hi in ranges[phase]:
                a.axvspan(max(lo, I[0]), hi, color=colours[phase],
                          alpha=0.12 if phase == "Jop" else 0.06)
    for a in (ax, inset):
        mu_jop = cols["mu.Jop"]
        a.axhline(mu_jop[-1], color="k", ls="--", lw=0.8)
        a.plot([I1], [np.interp(I1, I, cols["mu.BarkerGray"])], "o",
               color="tab:green", label=f"I_1 = {I1:g}")
        a.set_xlabel("I")
    ax.set_xscale("log")
    ax.set_xlim(*I_RANGE)
    ax.set_ylim(0, 0.8)
    ax.set_ylabel(r"$\mu(I)$")
    (jl, jh), = ranges["Jop"]
    bh = ranges["BarkerGray"][-1][1]
    ax.set_title(f"well posed: Jop [{jl:.5f}, {jh:.5f}], Barker–Gray "
                 f"[0, {bh:.4f}]", fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    inset.set_xlim(0, 0.012)
    inset.set_ylim(0, 0.45)
    inset.set_title("creep branch of (2.8), I < I_1", fontsize=9)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=150)
    plt.close(fig)
    return {"Jop_well_posed": [jl, jh], "BarkerGray_well_posed": [0.0, bh],
            "BarkerGray_I_max": bh, "I1": I1}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("case", type=Path)
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).resolve().parent / "measured")
    args = parser.parse_args(argv)
    log, cols = run_utility(args.case)
    numbers = figure1(log, cols, args.out / "figure1.png")
    numbers["command"] = ("/usr/bin/python3 validation/chute/figure1.py "
                          "tutorials/wellPosedness")
    (args.out / "figure1.json").write_text(json.dumps(numbers, indent=2)
                                           + "\n")
    print(json.dumps(numbers, indent=2))


if __name__ == "__main__":
    main()

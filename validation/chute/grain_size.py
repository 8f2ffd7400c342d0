"""The chute's length and time scales against the grain diameter d: runs of
tutorials/chute that differ only in d (both grain phases), each measured
for the four statements of the paper on them (section 5):

- figure 3: "by 20 cm downstream the homogeneously mixed region
  completely disappears": x_mix, the first x from which the grains' mixed
  thickness (chute.mixed_thickness: phi^s between 0.25 and 0.75) stays
  below MIXED h, at the last lab-frame time, and the first x from which it
  stays at its value at the outlet (the width of the steady transition,
  a cell or two); beside them the meeting point of Gray & Thornton's
  shocks (appendix A);
- figure 4: "the flow is steady at t = 10 s": the first written time at
  which the front is in the last column, the first written time from
  which the outlet's u and phi^s
  stay within 1 % (relative L2) of their last values, and the outflow at
  10 s against Bagnold (5.4) and Gray & Chugunov (5.8);
- figure 5: the front in the moving frame (the run continued from 4 s, as
  in the paper) against (5.17) for chi = 1 and 5/4, which the paper shows
  visibly apart: xi where h reaches 1/2 and 0.9 of h_inf; where the front
  has reached the outlet by 4 s, from a longer chute (--front);
- Fr (5.18) and ubar (5.16) of each d.

    /usr/bin/python3 validation/chute/grain_size.py CASE [CASE ...]
        [--front CASE=LONG ...] [--out DIR] [--readme README]

CASE is a lab-frame run with its moving-frame continuation in
CASE/movingFrame, or in LONG/movingFrame where --front names one (SETUP
below); DIR (default validation/chute/measured)
receives grain_size.json, grain_size.png (the mixed thickness along the
chute), and figure4_d<d>.png (at 10 s) and figure5_d<d>.png of each case; with --readme the table of
the runs is rendered into README between its markers
(<!-- grain size --> ... <!-- end of grain size -->).
"""
import argparse
import json
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from granularfoam.exact import bagnold, errors, grayChugunov  # noqa: E402
from granularfoam.exact import chute as exact  # noqa: E402
from granularfoam.foamio import profiles, time_names, times  # noqa: E402
from granularfoam.post import chute  # noqa: E402

# Allrun options of the chute studies in validation/chute/measured: 20 PISO
# correctors at steps up to 4e-3 s with up to 5 transport sub-cycles, the
# setting they were measured with (the tutorial's own is the Krylov coupling)
PISO_SETTING = "-coupling PISO -maxCo 0.9 -maxDeltaT 4e-3 -maxAlphaSubCycles 5"
SETUP = ("for D in 143 270 500; do cp -r tutorials/chute chute_d$D && "
         "(cd chute_d$D && ./Allrun -serial " + PISO_SETTING + " -d ${D}e-6 "
         "-endTime 25 -writeInterval 0.5 && ./Allrun-movingFrame -start 4 "
         "-endTime 14); done; cp -r tutorials/chute chute_d143_long && "
         "(cd chute_d143_long && ./Allrun -serial " + PISO_SETTING + " -d 143e-6 "
         "-Lx 1.24 -nx 310 -endTime 4 -writeInterval 0.5 && "
         "./Allrun-movingFrame -start 4 -endTime 14)")
PAPER = {"x_mix_m": 0.20, "steady_by_s": 10.0,
         "figure5": "the computed front between the chi = 1 and 5/4 curves,"
                    " which are visibly apart"}
MIXED = 0.1             # of h: a thinner mixed layer counts as gone
STEADY = 1e-2           # relative L2 of the outlet profiles to their last
T_FIGURE4 = 10.0        # s, the paper's figure 4


def trailing_start(flags):
    """Index of the first of the trailing run of true flags (len(flags)
    when the last is false)."""
    k = len(flags)
    while k > 0 and flags[k - 1]:
        k -= 1
    return k


def outlet_history(case, h):
    """Per sampled time of the outlet column: (t, z (n,), u (n,), phi^s
    (n,)) over the cells wholly below the inflow depth h."""
    out = []
    for t in times(case, "profiles"):
        prof = profiles(case, t, function="profiles", set_name="outlet")
        z = prof["z"]
        inside = z + 0.5 * (z[1] - z[0]) <= h
        phis = chute.small_fraction(prof["alpha.small"],
                                    prof["alpha.large"]).filled(0.0)
        out.append((float(t), z[inside], prof["U"][inside, 0],
                    phis[inside]))
    return out


def steady_time(history):
    """The first time from which u and phi^s at the outlet stay within
    STEADY (relative L2) of their last values."""
    u_end, p_end = history[-1][2], history[-1][3]
    k = trailing_start([errors.l2_relative(u, u_end) < STEADY
                        and errors.l2_relative(p, p_end) < STEADY
                        for _, _, u, p in history])
    return history[k][0] if k < len(history) else float("nan")


def figure4(case, out, d, h, pe, phibar):
    """Figure 4 at the outlet at T_FIGURE4 (the paper's time)."""
    prof = profiles(case, chute._time_name(case, T_FIGURE4, "profiles"),
                    function="profiles", set_name="outlet")
    phis = chute.small_fraction(prof["alpha.small"], prof["alpha.large"],
                                prof["alpha.air"])
    return chute.figure4(prof["z"], prof["U"][:, 0], phis, out, h, pe,
                         phibar, where=f"the outlet at t = {T_FIGURE4:g} s",
                         d=d)["path"]


def measure(case, out):
    par = chute.parameters(case)
    h, lx = par["h"], par["Lx"]
    d = chute.grain_diameter(case)
    names = [t for t in time_names(case) if float(t) > 0.0]
    hist = chute.history(case, names)
    last_column = lx * (1.0 - 0.5 / par["nx"])
    left = hist["t"][hist["front"] >= last_column - 1e-9]
    x, thickness = chute.mixed_thickness(case, names[-1])

    def settled(below):
        """The first x from which below holds to the outlet."""
        k = trailing_start(below)
        return float(x[k]) if k < len(x) else float("nan")
    outlet = outlet_history(case, h)
    at10 = [r for r in outlet if abs(r[0] - T_FIGURE4) < 1e-9]
    assert at10, f"{case}: no outlet sample at {T_FIGURE4} s"
    _, z, u10, p10 = at10[0]
    pe = grayChugunov.peclet(chute.T3.f_sl, h, chute.T3.D_sl, chute.ZETA)
    phibar = chute.downstream_phibar(h)
    res = {
        "case": Path(case).name, "d_m": d,
        "ubar_m_s": float(exact.depth_averaged_velocity(h, chute.ZETA, d=d)),
        "Fr": float(exact.froude(h, chute.ZETA, d=d)),
        "x_mix_m": settled(thickness < MIXED * h),
        "x_mix_outlet_value_m": settled(thickness <= thickness[-1] + 1e-12),
        "x_shock_meeting_m": float(exact.shock_meeting_point(
            h, chute.ZETA, chute.T3.f_sl, d=d)),
        "front_at_outlet_s": float(left[0]) if left.size else float("nan"),
        "outlet_steady_from_s": steady_time(outlet),
        "outlet_at_10s_l2_u_bagnold": errors.l2_relative(
            u10, bagnold.velocity(z, h, chute.ZETA, d=d)),
        "outlet_at_10s_l2_phis_gray_chugunov": errors.l2_relative(
            p10, grayChugunov.phi_s(z / h, pe, phibar)),
        "lab_end_time_s": float(names[-1]),
    }
    res["figure4"] = Path(figure4(case, out / f"figure4_d{d * 1e6:.0f}um.png",
                                  d, h, pe, phibar)).name
    return res, (x, thickness)


def front(case, out):
    """Figure 5 of the moving-frame continuation at its last time."""
    moving = Path(case) / "movingFrame"
    names = time_names(moving)
    t = names[-1]
    x, z, f = chute.grid(moving, t, ["alpha.air"])
    surface = chute.free_surface(z, f["alpha.air"])
    h = chute.parameters(case)["h"]
    d = chute.grain_diameter(case)
    r = chute.figure5(x, surface, out,
                      x_front=chute.front_position(x, surface,
                                                   chute._spacing(z)),
                      h_inf=h, d=d)
    return {"moving_frame_from_s": float(time_names(moving)[0]),
            "moving_frame_time_s": float(t),
            "xi_computed_m": r["xi_computed"], "xi_chi1_m": r["xi_chi1"],
            "xi_chi54_m": r["xi_chi54"], "figure": Path(r["path"]).name}


def figure(curves, out):
    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    ax.axhline(MIXED * chute.T3.h * 1e3, color="0.5", lw=0.8)
    for name, (d, x, thickness, x_mix, x_meet) in curves.items():
        line, = ax.plot(x * 100, thickness * 1e3,
                        label=f"d = {d * 1e3:.3g} mm")
        ax.axvline(x_meet * 100, color=line.get_color(), ls=":", lw=1)
        if np.isfinite(x_mix):
            ax.plot([x_mix * 100], [np.interp(x_mix, x, thickness) * 1e3],
                    "o", color=line.get_color())
    ax.axvline(PAPER["x_mix_m"] * 100, color="k", ls="--", lw=1,
               label="paper: mixed region gone by 20 cm")
    ax.set_xlabel("$x$ (cm)")
    ax.set_ylabel("mixed thickness, $0.25 < \\varphi^s < 0.75$ (mm)")
    ax.set_xlim(0, 40)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    ax.set_title("Steady flow: the mixed region along the chute (dots: "
                 "x_mix; dotted: Gray & Thornton's shocks meet)", fontsize=9)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=150, bbox_inches="tight")
    plt.close(fig)


README_BEGIN, README_END = "<!-- grain size -->", "<!-- end of grain size -->"


def table(result):
    """Markdown: the paper's statements against each run."""
    runs = sorted(result["runs"].values(), key=lambda r: r["d_m"])

    def cm(x):
        return f"{x * 100:.1f}"
    rows = [
        ("ū (5.16) [m/s], Fr (5.18)", "–", lambda r:
         f"{r['ubar_m_s']:.3f}, {r['Fr']:.2f}"),
        ("figure 3: mixed region gone by x [cm]: below h/10; at its outlet "
         "value (Gray & Thornton's shocks meet at)", "20", lambda r:
         f"{cm(r['x_mix_m'])}; {cm(r['x_mix_outlet_value_m'])} "
         f"({cm(r['x_shock_meeting_m'])})"),
        ("figure 4: front at the outlet, outlet steady from [s]",
         "steady at 10", lambda r:
         f"{r['front_at_outlet_s']:g}, {r['outlet_steady_from_s']:g}"),
        ("figure 4 at t = 10 s: outlet u vs Bagnold, φ^s vs (5.8)", "–",
         lambda r: f"{r['outlet_at_10s_l2_u_bagnold'] * 100:.2f} %, "
         f"{r['outlet_at_10s_l2_phis_gray_chugunov'] * 100:.1f} %"),
        ("figure 5: ξ(½h∞) [cm] computed; χ = 1; χ = 5/4",
         "between the χ curves, visibly apart", lambda r: "; ".join(
             cm(r["figure5"][k]["0.5"]) for k in
             ("xi_computed_m", "xi_chi1_m", "xi_chi54_m"))),
        ("figure 5: ξ(0.9h∞) [cm] computed; χ = 1; χ = 5/4", "", lambda r:
         "; ".join(cm(r["figure5"][k]["0.9"]) for k in
                   ("xi_computed_m", "xi_chi1_m", "xi_chi54_m"))),
    ]
    head = ("| | paper | " + " | ".join(
        f"d = {r['d_m'] * 1e3:.3g} mm" for r in runs) + " |")
    lines = [head, "|---" * (len(runs) + 2) + "|"]
    for name, paper, fn in rows:
        lines.append(f"| {name} | {paper} | "
                     + " | ".join(fn(r) for r in runs) + " |")
    return "\n".join(lines)


def write_readme(path, result):
    text = path.read_text()
    i, j = text.find(README_BEGIN), text.find(README_END)
    assert 0 <= i < j, f"no {README_BEGIN} markers in {path}"
    path.write_text(text[:i + len(README_BEGIN)] + "\n\n" + table(result)
                    + "\n\n" + text[j:])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cases", nargs="+", type=Path)
    parser.add_argument("--front", nargs="*", default=[], metavar="CASE=LONG",
                        help="take figure 5 of CASE from LONG/movingFrame")
    parser.add_argument("--readme", type=Path, default=None)
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve()
                        .parent / "measured")
    args = parser.parse_args(argv)
    longer = {}
    for item in args.front:
        case, sep, long = item.partition("=")
        if not sep:
            parser.error(f"--front {item} is not CASE=LONG")
        longer[Path(case).name] = Path(long)
    runs, curves = {}, {}
    for case in args.cases:
        res, (x, thickness) = measure(case, args.out)
        key = f"d{res['d_m'] * 1e6:.0f}um"
        source = longer.get(case.name, case)
        res["figure5"] = front(source, args.out / f"figure5_{key}.png")
        res["figure5"]["case"] = source.name
        runs[key] = res
        curves[key] = (res["d_m"], x, thickness, res["x_mix_m"],
                       res["x_shock_meeting_m"])
    figure(curves, args.out / "grain_size.png")
    result = {"paper": PAPER, "runs": runs, "setup": SETUP,
              "command": "/usr/bin/python3 validation/chute/grain_size.py "
                         + " ".join(c.name for c in args.cases)
                         + "".join(f" --front {c}={p.name}"
                                   for c, p in longer.items())}
    path = args.out / "grain_size.json"
    path.write_text(json.dumps(result, indent=2) + "\n")
    if args.readme:
        write_readme(args.readme, json.loads(path.read_text()))
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()

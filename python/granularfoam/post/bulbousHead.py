"""Post-processing of tutorials/bulbousHead (section 6.2, figure 8).

Measures, at every written time, the front position, the head height and
the upstream depth from the free surface (phi^a = 1/2), and the small-grain
fraction in the head; draws figure 8 (phi^s and log10 I near the front) and
the front and head histories of the coupled run against the run without
frictional feedback (-monodisperse).

    /usr/bin/python3 -m granularfoam.post.bulbousHead <case> [<monodisperse>]
        [--time 5.2] [--out figures] [--length 0.25]

The field readers and the free-surface measures are those of the chute
(granularfoam.post.chute).
"""
import argparse
import json
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import chute  # noqa: E402

# The head: this far behind the front.  The bulge of the coupled run forms
# at the rear of the large-rich region, by the breaking wave, 15-22 cm behind
# the front at 10-15 s (5.9 mm against 5.0 mm upstream); a window of 10 cm
# saw only the thinning front and reported no bulge
HEAD_LENGTH = 0.25  # [m]
UPSTREAM_GAP = 0.3  # [m] the upstream flow: from 0.05 m to this far behind


def measure(case, time_name):
    """Front, head and upstream measures of one written time:
    {'t', 'front' (the free surface above one cell, m), 'head' (highest
    free surface within HEAD_LENGTH behind the front, m), 'x_head' (where),
    'upstream' (median free surface over 0.05 m <= x <= front -
    UPSTREAM_GAP, NaN if empty), 'phi_s_head' (mean phi^s in the grains
    within 2 cm behind the front), 'phi_s_upstream_surface' (phi^s in the
    top grain cell, median over the upstream columns)}."""
    x, z, f = chute.grid(case, time_name,
                         ["alpha.air", "alpha.small", "alpha.large"])
    a = f["alpha.air"]
    dz = chute._spacing(z)
    hs = chute.free_surface(z, a)
    front = chute.front_position(x, hs, dz)
    phi = chute.small_fraction(f["alpha.small"], f["alpha.large"], a)
    head = (x >= front - HEAD_LENGTH) & (x <= front)
    up = (x >= 0.05) & (x <= front - UPSTREAM_GAP)
    tip = (x >= front - 0.02) & (x <= front)
    k_head = int(np.argmax(np.where(head, hs, -1.0)))
    # the breaking size-segregation wave: where the small grains at the
    # base give way to the large-rich front (base phi^s falls through 1/2)
    wave = np.nonzero((phi[0] < 0.5) & ~np.ma.getmaskarray(phi[0]))[0]
    top = np.maximum(np.sum(a < chute.GRAINS, axis=0) - 1, 0)
    surface_phi = phi.filled(np.nan)[top, np.arange(x.size)]
    return {
        "t": float(time_name), "front": front,
        "head": float(hs[k_head]) if head.any() else float("nan"),
        "x_head": float(x[k_head]) if head.any() else float("nan"),
        "upstream": float(np.median(hs[up])) if up.any() else float("nan"),
        "phi_s_head": float(np.ma.mean(phi[:, tip])) if tip.any()
        and np.ma.count(phi[:, tip]) else float("nan"),
        "phi_s_upstream_surface": float(np.median(surface_phi[up]))
        if up.any() else float("nan"),
        "breaking_wave": float(x[wave[0]]) if wave.size else float("nan"),
        "dz": float(dz),
    }


def history(case):
    """measure() at every written time t > 0: {key: numpy array}."""
    rows = [measure(case, t) for t in chute.time_names(case)
            if float(t) > 0.0]
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}


def figure8(case, time_name, out, length=0.25):
    """Figure 8: (a) phi^s and (b) log10 I in the grains (alpha.air < 0.5)
    over the last `length` metres behind the front at time_name."""
    x, z, f = chute.grid(case, time_name,
                         ["alpha.air", "alpha.small", "alpha.large", "I"])
    a = f["alpha.air"]
    front = chute.front_position(x, chute.free_surface(z, a),
                                 chute._spacing(z))
    sel = (x >= front - length) & (x <= front + 0.05 * length)
    grains = a[:, sel] < chute.GRAINS
    phi = chute.small_fraction(f["alpha.small"][:, sel],
                               f["alpha.large"][:, sel], a[:, sel])
    with np.errstate(divide="ignore", invalid="ignore"):
        logI = np.ma.masked_array(np.log10(f["I"][:, sel]), mask=~grains)
    xe, ze = chute._edges(x[sel]) * 1e3, chute._edges(z) * 1e3
    fig, axes = plt.subplots(2, 1, figsize=(9.0, 4.8), sharex=True)
    for ax, data, title, cmap, lim in (
            (axes[0], phi, r"(a) $\varphi^s$", "coolwarm_r", (0, 1)),
            (axes[1], logI, r"(b) $\log_{10} I$", "viridis", (None, None))):
        ax.set_facecolor("0.85")
        m = ax.pcolormesh(xe, ze, data, cmap=cmap, vmin=lim[0], vmax=lim[1],
                          shading="flat", rasterized=True)
        fig.colorbar(m, ax=ax, pad=0.01)
        ax.set_title(title, fontsize=9, loc="left")
        ax.set_ylabel("$z$ (mm)")
    axes[-1].set_xlabel("$x$ (mm)")
    fig.suptitle(f"Figure 8: the bulbous head at $t$ = {time_name} s "
                 "(grey: air)", fontsize=10)
    fig.savefig(out, dpi=150, bbox_inches="tight")
    plt.close(fig)
    return str(out)


def figure_history(histories, out):
    """Front position and head height against time, one line per run
    ({label: history})."""
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.6))
    for label, hist in histories.items():
        axes[0].plot(hist["t"], hist["front"] * 1e3, "o-", ms=3, label=label)
        axes[1].plot(hist["t"], hist["head"] * 1e3, "o-", ms=3,
                     label=f"{label}: head")
        axes[1].plot(hist["t"], hist["upstream"] * 1e3, "--",
                     label=f"{label}: upstream")
    axes[0].set_ylabel("front position (mm)")
    axes[1].set_ylabel("free-surface height (mm)")
    for ax in axes:
        ax.set_xlabel("$t$ (s)")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    plt.close(fig)
    return str(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("monodisperse", nargs="?")
    ap.add_argument("--time", default="5.2")
    ap.add_argument("--out", default="figures")
    ap.add_argument("--length", type=float, default=0.25,
                    help="figure 8 shows this far behind the front [m]")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    runs = {"coupled": args.case}
    if args.monodisperse:
        runs["no feedback"] = args.monodisperse
    histories = {k: history(c) for k, c in runs.items()}
    figure8(args.case, args.time, out / "figure8.png", length=args.length)
    figure_history(histories, out / "front_history.png")
    numbers = {k: {q: v.tolist() for q, v in h.items()}
               for k, h in histories.items()}
    (out / "bulbousHead.json").write_text(json.dumps(numbers, indent=1))
    for k, h in histories.items():
        print(k)
        for row in zip(*(h[q] for q in ("t", "front", "head", "upstream",
                                          "breaking_wave", "phi_s_head"))):
            print("  t %5.2f  front %.4f  head %.5f  upstream %.5f  "
                  "wave %.4f  phi_s head %.3f" % row)


if __name__ == "__main__":
    main()

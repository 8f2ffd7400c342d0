"""Sidewall friction in the square drum: the surface avalanche
and the segregated core with and without the friction of the end walls
(tutorials/squareDrum, ./Allrun -sidewall W MUW).

At every written time from --from on (the steady avalanche regime):

- the flowing-layer depth on the mid-line: the line through the drum's
  axis normal to the free surface (the rotatingDrum monitor's inclination;
  the drum turns clockwise, so the surface falls towards +x), sampled at
  0.5 mm steps by linear interpolation between cell centres; the surface
  is where phi^a = 1/2, and the depth is where the speed relative to the
  drum, |u - Omega k x r| (7.3), falls below FRACTION of its largest value
  on the line, and where I falls below I_1 (table 4: the creep boundary of
  figure 10); the creep speed of the body 5 cm below the surface;
- the segregated core: the area of the grains (phi^a < 1/2) that are
  small-rich, phi^s = alpha.small/(alpha.small + alpha.large) > 0.75
  (and > 0.6), the area still mixed, |phi^s - 1/2| < 0.05, and of that the
  central core of section 7.3: the connected mixed region (cells sharing
  a face) that holds the cell nearest the axis;
- the surface inclination and the peak relative speed (the monitor).

    /usr/bin/python3 -m granularfoam.post.drumSidewall NOWALL WALL \\
        [--from 10] [--out DIR] [--readme README]

writes sidewall.json (means over the times, and every time) and
sidewall.png; with --readme README it renders the table into that README
between its markers (<!-- drum sidewall results --> ...).
"""
import argparse
import json
import math
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from scipy.interpolate import LinearNDInterpolator  # noqa: E402
from scipy.ndimage import label  # noqa: E402

from ..foamio import time_names  # noqa: E402
from .drum import (I1, drum_axes, _save, centres,  # noqa: E402
                   grid, monitor, parameters, relative_speed,
                   replace_between, sidewall, small_fraction)

FRACTION = 0.25         # of the line's largest relative speed: the base
                        # of the flowing layer (the body creeps at 10-15 %
                        # of it without the walls, so not less)
RICH = (0.75, 0.6)      # phi^s thresholds of the small-rich region
MIXED = 0.05            # |phi^s - 1/2| below it: the mixed core
STEP = 5e-4             # [m] sampling step on the mid-line
CREEP_DEPTH = 0.05      # [m] below the surface: the body's creep speed
FIELDS = ["U", "I", "alpha.air", "alpha.small", "alpha.large"]


def state(case, name, angle_deg):
    """One written time: the mid-line profile and the areas."""
    L = parameters(case)["L"]
    X, Y, f = grid(case, name, FIELDS)
    xc, yc = centres(X, Y)
    speed = relative_speed(f, xc, yc)
    grains = f["alpha.air"] < 0.5
    phis = small_fraction(f)          # NaN in the air
    area = (2 * L / xc.shape[0]) ** 2           # uniform square cells

    a = math.radians(angle_deg)
    n = np.array([math.sin(a), math.cos(a)])    # upward surface normal
    s = np.arange(-1.4 * L, 1.4 * L, STEP)
    pts = np.outer(s, n)
    xy = np.c_[xc.ravel(), yc.ravel()]
    air = LinearNDInterpolator(xy, f["alpha.air"].ravel())(pts)
    u = LinearNDInterpolator(xy, speed.ravel())(pts)
    inertial = LinearNDInterpolator(xy, f["I"].ravel())(pts)
    inside = np.isfinite(air) & np.isfinite(u)
    s, air, u, inertial = s[inside], air[inside], u[inside], inertial[inside]
    k = int(np.argmax((air >= 0.5) & (s > 0)))
    assert k > 0 and air[k] >= 0.5, f"{case}/{name}: no surface on the line"
    s_surf = s[k - 1] + (0.5 - air[k - 1]) / (air[k] - air[k - 1]) \
        * (s[k] - s[k - 1])
    # a surface normal to the line has air above and grains below it
    assert np.interp(s_surf + 0.02, s, air) > 0.9 \
        and np.interp(s_surf - 0.02, s, air) < 0.1, (
            f"{case}/{name}: the line is not normal to the surface")

    below = s < s_surf
    depth, ub = s_surf - s[below][::-1], u[below][::-1]   # from the surface
    peak = float(ub.max())
    j = int(np.argmax(ub))
    slow = np.nonzero(ub[j:] < FRACTION * peak)[0]
    assert slow.size, f"{case}/{name}: the whole line flows"
    m = j + slow[0]
    delta = depth[m - 1] + (ub[m - 1] - FRACTION * peak) \
        / (ub[m - 1] - ub[m]) * (depth[m] - depth[m - 1])
    Ib = inertial[below][::-1]
    creep = np.nonzero(Ib < I1)[0]
    assert creep.size, f"{case}/{name}: I > I_1 on the whole line"

    mixed = grains & (np.abs(phis - 0.5) < MIXED)
    regions, _ = label(mixed)
    axis = np.unravel_index(np.argmin(np.hypot(xc, yc)), xc.shape)
    core = (regions == regions[axis]) & mixed[axis]

    out = {"t": float(name), "surface_angle_deg": angle_deg,
           "surface_distance_from_axis": float(s_surf),
           "midline_peak_speed": peak, "flowing_depth": float(delta),
           "depth_I_above_I1": float(depth[creep[0]]),
           "creep_speed": float(np.interp(CREEP_DEPTH, depth, ub)),
           "mixed_area": float(area * mixed.sum()),
           "central_core_area": float(area * core.sum()),
           "grain_area": float(area * grains.sum())}
    for r in RICH:
        out[f"small_rich_area_{r:g}"] = float(area * np.sum(
            grains & (phis > r)))
    profile = {"depth": depth, "speed": ub}
    maps = {"X": X, "Y": Y, "phis": phis,
            "core": core,
            "line": (s_surf, n)}
    return out, profile, maps


def measure(case, t_from):
    """state() at every written time t >= t_from: (rows, last profile,
    last maps)."""
    m = monitor(case)
    names = [n for n in time_names(case) if float(n) >= t_from - 1e-9]
    assert names, f"{case}: no time written after {t_from} s"
    rows = []
    for name in names:
        angle = float(np.interp(float(name), m["t"], m["angle"]))
        row, profile, maps = state(case, name, angle)
        rows.append(row)
    return rows, profile, maps


def summary(rows, case, t_from):
    m = monitor(case)
    late = m["t"] >= t_from
    keys = [k for k in rows[0] if k != "t"]
    out = {k: float(np.mean([r[k] for r in rows])) for k in keys}
    out.update({f"{k}_range": [float(min(r[k] for r in rows)),
                               float(max(r[k] for r in rows))]
                for k in ("flowing_depth", "depth_I_above_I1",
                          "small_rich_area_0.75", "mixed_area",
                          "central_core_area")})
    out["monitor_surface_angle_mean_deg"] = float(np.nanmean(m["angle"][late]))
    out["monitor_peak_speed_mean"] = float(np.mean(m["peak"][late]))
    out["times"] = len(rows)
    out["from"] = t_from
    out["to"] = rows[-1]["t"]
    return out


def figure(results, out):
    fig = plt.figure(figsize=(11, 7.5))
    ax = fig.add_subplot(2, 3, 1)
    for label, (rows, profile, maps, s) in results.items():
        ax.plot(profile["speed"], profile["depth"] * 100, label=label)
        ax.axhline(s["flowing_depth"] * 100, ls=":", lw=0.8,
                   color=ax.lines[-1].get_color())
    ax.invert_yaxis()
    ax.set_ylim(8, 0)
    ax.set_xlabel(r"$|\mathbf{u} - \Omega\mathbf{k}\times\mathbf{r}|$ [m/s]")
    ax.set_ylabel("depth below the surface on the mid-line [cm]")
    ax.set_title(f"t = {rows[-1]['t']:g} s (dotted: mean depth, "
                 f"{FRACTION:g} of the peak)", fontsize=8)
    ax.legend(fontsize=7)
    for i, keys, label in (
            (2, ("flowing_depth", "depth_I_above_I1"), "depth [cm]"),
            (3, ("small_rich_area_0.75", "central_core_area"),
             r"area [cm$^2$]")):
        ax = fig.add_subplot(2, 3, i)
        for name, (rows, _, _, _) in results.items():
            for key, style in zip(keys, ("o-", "s--")):
                scale = 1e4 if "area" in key else 100
                ax.plot([r["t"] for r in rows], [r[key] * scale for r in rows],
                        style, ms=2, label=f"{name}: {key}")
        ax.set_xlabel("t [s]")
        ax.set_ylabel(label)
        ax.legend(fontsize=6)
    for i, (name, (rows, _, maps, _)) in enumerate(results.items()):
        ax = fig.add_subplot(2, 3, 4 + i)
        pc = ax.pcolormesh(maps["X"], maps["Y"], maps["phis"],
                           cmap="viridis", vmin=0, vmax=1, shading="flat")
        xc, yc = centres(maps["X"], maps["Y"])
        for field, level, colour in (
                (np.nan_to_num(maps["phis"], nan=0.0), RICH[0], "w"),
                (maps["core"] * 1.0, 0.5, "r")):
            if field.min() < level < field.max():
                ax.contour(xc, yc, field, [level], colors=colour,
                           linewidths=0.8)
        s_surf, n = maps["line"]
        ax.plot([0, s_surf * n[0]], [0, s_surf * n[1]], "r-", lw=0.8)
        drum_axes(ax, maps["X"], maps["Y"])
        ax.set_title(f"{name}, t = {rows[-1]['t']:g} s", fontsize=8)
    fig.colorbar(pc, ax=fig.axes[3:], shrink=0.7,
                 label=r"$\varphi^s$ (white 0.75, red core)")
    _save(fig, out)


README_BEGIN = "<!-- drum sidewall results -->"
README_END = "<!-- end of drum sidewall results -->"


def table(numbers):
    """Markdown rows of sidewall.json's two runs (means over the written
    times, ranges in brackets)."""
    runs = [numbers["no walls"], numbers["sidewall friction"]]

    def walls(r):
        w = r.get("sidewall")
        return ("no walls" if not w else
                f"W = {w['W'] * 100:g} cm, μ_w = {w['muW']:g}")

    def mean_range(key, scale, unit, fmt="{:.2f}"):
        def cell(r):
            text = fmt.format(r[key] * scale) + unit
            if f"{key}_range" in r:
                lo, hi = r[f"{key}_range"]
                text += (f" ({fmt.format(lo * scale)}–"
                         f"{fmt.format(hi * scale)})")
            return text
        return cell
    rows = [
        ("surface inclination (monitor)", lambda r:
         f"{r['monitor_surface_angle_mean_deg']:.1f}°"),
        ("peak speed relative to the drum (monitor)", lambda r:
         f"{r['monitor_peak_speed_mean']:.3f} m/s"),
        ("flowing depth on the mid-line, "
         f"{FRACTION:g} of the peak speed",
         mean_range("flowing_depth", 100, " cm")),
        ("depth with I > I_1 on the mid-line",
         mean_range("depth_I_above_I1", 100, " cm")),
        (f"creep speed of the body {CREEP_DEPTH * 100:g} cm below the "
         "surface", lambda r: f"{r['creep_speed']:.2g} m/s"),
        (f"small-rich area, φ^s > {RICH[0]:g}",
         mean_range(f"small_rich_area_{RICH[0]:g}", 1e4, " cm²", "{:.0f}")),
        (f"small-rich area, φ^s > {RICH[1]:g}",
         mean_range(f"small_rich_area_{RICH[1]:g}", 1e4, " cm²", "{:.0f}")),
        ("central core", mean_range("central_core_area", 1e4, " cm²",
                                    "{:.1f}")),
        ("grain area", mean_range("grain_area", 1e4, " cm²", "{:.0f}")),
    ]
    first = runs[0]
    lines = [f"| mean over {first['from']:g}–{first['to']:g} s (range) | "
             + " | ".join(walls(r) for r in runs) + " |",
             "|---|---|---|"]
    for name, fn in rows:
        lines.append(f"| {name} | " + " | ".join(fn(r) for r in runs) + " |")
    return "\n".join(lines)


def write_readme(path, numbers):
    """Replace the table between the drum README's sidewall markers."""
    path.write_text(replace_between(path.read_text(), README_BEGIN,
                                    README_END, table(numbers)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("nowall", type=Path)
    parser.add_argument("wall", type=Path)
    parser.add_argument("--from", dest="t_from", type=float, default=10.0)
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--readme", type=Path, default=None,
                        help="render sidewall.json into this README, "
                             "between its drum sidewall results markers")
    args = parser.parse_args(argv)
    out = args.out or args.wall / "figures"
    results, numbers = {}, {}
    for label, case in (("no walls", args.nowall),
                        ("sidewall friction", args.wall)):
        rows, profile, maps = measure(case, args.t_from)
        s = summary(rows, case, args.t_from)
        fv = case / "constant" / "fvOptions"
        s["case"] = str(case)
        s["fvOptions"] = fv.is_file()
        s["sidewall"] = sidewall(case)
        results[label] = (rows, profile, maps, s)
        numbers[label] = dict(s, every_time=rows)
    assert not numbers["no walls"]["fvOptions"], "NOWALL has an fvOptions"
    assert numbers["sidewall friction"]["fvOptions"], "WALL has no fvOptions"
    figure(results, out / "sidewall.png")
    out.mkdir(parents=True, exist_ok=True)
    (out / "sidewall.json").write_text(json.dumps(numbers, indent=2))
    if args.readme:
        write_readme(args.readme, numbers)
    print(json.dumps({k: {kk: vv for kk, vv in v.items()
                          if kk != "every_time"}
                      for k, v in numbers.items()}, indent=2))


if __name__ == "__main__":
    main()

"""Post-processing and figures of the chute tutorial (tutorials/chute),
section 5 of Barker et al. (2021): figures 2-6.

Reads the ascii fields of the solver's time directories, maps them onto
the (z, x) grid of the single blockMesh block, extracts the free surface,
the front and the trapped air, and draws the paper's figures against the
exact solutions of granularfoam.exact.  Used by the chute's tests
(validation/chute, numbers) and as a script (figures):

    /usr/bin/python3 -m granularfoam.post.chute <case> [--out DIR]

Cell centres come from `postProcess -func writeCellCentres` (written into
the case once per time), so the OpenFOAM environment (etc/openfoam.env)
must be sourced unless the time directories already hold C.
"""
import argparse
import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import colors  # noqa: E402

from ..exact import bagnold, chute, errors, grayChugunov  # noqa: E402
from ..foamio import (cell_centres, entries,  # noqa: E402
                      parameters as _parameters, profiles, read_field,
                      read_text, time_names)

ZETA = bagnold.ZETA                 # 24 degrees
T3 = grayChugunov.TABLE3            # f_sl = 7e-3, D_sl = 1e-6, h = 5e-3
PHI0 = 0.5                          # small-grain fraction of the inflow (5.2)
GRAINS = 0.5                        # alpha.air below this is "grains"
DPI = 150
LETTERS = "abcdefghij"



# --------------------------------------------------------------------------
# Reading OpenFOAM output
# --------------------------------------------------------------------------

def _levels(v):
    """Distinct coordinates of v (sorted, clustered to a relative tolerance
    of 1e-6 of the extent) and the index of each entry among them."""
    order = np.sort(v)
    tol = 1e-6 * max(order[-1] - order[0], np.finfo(float).tiny)
    starts = np.concatenate(([True], np.diff(order) > tol))
    group = np.cumsum(starts) - 1
    levels = np.bincount(group, weights=order) / np.bincount(group)
    index = np.searchsorted(levels + tol, v)
    return levels, index


def grid(case, time_name, names):
    """Fields on the structured grid of the chute: returns (x (nx,),
    z (nz,), {name: array (nz, nx)}), row 0 at the base.  A vector field
    name gives its components name+'x' and name+'z' (e.g. 'Ux', 'Uz')."""
    c = cell_centres(case, time_name)
    x, ix = _levels(c[:, 0])
    z, iz = _levels(c[:, 2])
    n = c.shape[0]
    assert x.size * z.size == n, (
        f"{case}: {x.size} x {z.size} columns and rows for {n} cells: "
        "not a single structured block")
    hits = np.zeros((z.size, x.size), dtype=int)
    np.add.at(hits, (iz, ix), 1)
    assert np.all(hits == 1), f"{case}: cells do not fill the grid once"
    out = {}
    for name in ([names] if isinstance(names, str) else names):
        f = read_field(case, time_name, name)
        assert f.shape[0] == n, f"{name}: {f.shape[0]} values, {n} cells"
        if f.ndim == 1:
            out[name] = _place(f, iz, ix, z.size, x.size)
        else:
            out[name + "x"] = _place(f[:, 0], iz, ix, z.size, x.size)
            out[name + "z"] = _place(f[:, 2], iz, ix, z.size, x.size)
    return x, z, out


def _place(values, iz, ix, nz, nx):
    a = np.empty((nz, nx))
    a[iz, ix] = values
    return a


def parameters(case, dictionary="chuteParameters"):
    """Numeric entries of case/system/<dictionary> (the chute's: Lx, Lz, h,
    nx, ...)."""
    return _parameters(case, dictionary)


def grain_diameter(case):
    """d of the grains in case/constant/granularProperties, as
    foamDictionary expands it (the tutorials take it from
    system/chuteParameters); the chute's grains share one d (table 1:
    0.5 mm)."""
    found = set(entries(Path(case), "constant/granularProperties",
                        ["grains.small.d", "grains.large.d"]).values())
    assert len(found) == 1, (
        f"{case}: the grains' d are {sorted(found)}, not one value")
    return found.pop()


def frame_velocity(case, time_name):
    """x component of the inflow's frameVelocity recorded in U (0 when the
    case runs in the lab frame)."""
    text = read_text(Path(case) / str(time_name) / "U")
    m = re.search(r"frameVelocity\s*\(\s*(\S+)\s+\S+\s+\S+\s*\)", text)
    return float(m.group(1)) if m else 0.0


# --------------------------------------------------------------------------
# Measurements
# --------------------------------------------------------------------------

def free_surface(z, phi_air, level=0.5):
    """Free-surface height of each column of phi_air (nz, nx): the height
    where phi_air rises through `level` going up from the grains (linear
    between cell centres).  The paper (figure 5) takes "the contour of
    phi^a = 0"; on a discrete, sharp interface that contour is taken at
    phi^a = 0.5.  Columns without grains (every cell >= level, including a
    bottom cell >= level with nothing below level above it) give 0.  Air
    trapped at the base (bottom cells >= level under grains) does not end
    the search: the surface is where the air rises through `level` above
    the lowest grain cell.  A column of grains up to the top gives the top
    cell centre."""
    a = np.asarray(phi_air, dtype=float)
    z = np.asarray(z, dtype=float)
    below = a < level
    has = below.any(axis=0)
    k0 = np.argmax(below, axis=0)                   # lowest grain cell
    rows = np.arange(a.shape[0])[:, None]
    above = (a >= level) & (rows > k0[None, :])
    ends = above.any(axis=0)
    k = np.argmax(above, axis=0)                    # first air cell above
    km = np.maximum(k - 1, 0)
    cols = np.arange(a.shape[1])
    a0, a1 = a[km, cols], a[k, cols]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.clip((level - a0) / (a1 - a0), 0.0, 1.0)
    h = z[km] + np.nan_to_num(s) * (z[k] - z[km])
    h = np.where(ends, h, z[-1])
    return np.where(has, h, 0.0)


def grain_depth(z, phi_air):
    """Grain depth of each column: the integral of 1 - phi_air over the
    column (cell height from the uniform spacing of z); insensitive to air
    trapped at the base."""
    z = np.asarray(z, dtype=float)
    dz = (z[-1] - z[0]) / (z.size - 1)
    return np.sum(1.0 - np.asarray(phi_air, dtype=float), axis=0) * dz


def front_position(x, h, threshold):
    """Front of the flow: the largest x where h exceeds threshold, linear
    between the last such column and the next; x[-1] when the flow leaves
    the domain, NaN when h nowhere exceeds threshold."""
    x = np.asarray(x, dtype=float)
    h = np.asarray(h, dtype=float)
    over = np.nonzero(h > threshold)[0]
    if over.size == 0:
        return float("nan")
    i = over[-1]
    if i == x.size - 1:
        return float(x[-1])
    s = (h[i] - threshold) / (h[i] - h[i + 1])
    return float(x[i] + s * (x[i + 1] - x[i]))


def front_foot(x, phi_air, level=0.5):
    """Foot of the phi^a = level contour on the bottom row of cell centres:
    the largest x where the bottom-row phi_air is below level, linear to
    the next column (sub-cell front position for figure 5; x[-1] when the
    grains reach the outlet, NaN without grains on the base)."""
    return front_position(x, -np.asarray(phi_air, dtype=float)[0], -level)


def trapped_air(x, z, phi_air, h_surface, dx, dz, front, min_cells=2.0):
    """Air trapped under the grains, in the bottom cell row of the columns
    beneath the flow: behind the front (x < front) where the free surface
    h_surface (free_surface, which looks past air trapped at the base)
    lies at least min_cells cells above the base, so that the thin toe of
    the front, thinner than min_cells cells, is not counted.  Returns
    `integral` = sum of phi_air over those bottom cells times dx dz (m^2 per
    unit width), their `mean` and `max` phi_air, `columns` their number,
    `excess` = the same integral of the bottom cell's phi_air in excess of
    the least phi_air above it beneath the surface (air lying under
    denser grains; zero for a uniformly diluted toe), and `below_surface`
    = the integral of phi_air over all cells beneath h_surface in those
    columns (air inside the layer, m^2 per unit width)."""
    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    a = np.asarray(phi_air, dtype=float)
    hs = np.asarray(h_surface, dtype=float)
    beneath = (x < front) & (hs >= min_cells * dz)
    bottom = a[0, beneath]
    if bottom.size == 0:
        return {"integral": 0.0, "mean": 0.0, "max": 0.0, "columns": 0,
                "excess": 0.0, "below_surface": 0.0}
    inside = (z[:, None] < hs[None, :]) & beneath[None, :]
    above = inside.copy()
    above[0] = False
    least = np.min(np.where(above, a, np.inf), axis=0)[beneath]
    excess = np.clip(bottom - least, 0.0, None)
    excess[~np.isfinite(excess)] = 0.0
    return {"integral": float(bottom.sum() * dx * dz),
            "mean": float(bottom.mean()),
            "max": float(bottom.max()),
            "columns": int(bottom.size),
            "excess": float(excess.sum() * dx * dz),
            "below_surface": float(a[inside].sum() * dx * dz)}


def precursor(x, phi_air, front, dx, dz, level=0.1):
    """Grains ahead of the front (a precursor sheet that free_surface does
    not see while its phi^a > 0.5): `tip` = the largest x where the
    bottom-row grain fraction 1 - phi^a exceeds level (front_position),
    `volume` = the integral of 1 - phi^a over the columns x > front (m^2
    per unit width)."""
    x = np.asarray(x, dtype=float)
    g = 1.0 - np.asarray(phi_air, dtype=float)
    return {"tip": front_position(x, g[0], level),
            "volume": float(g[:, x > front].sum() * dx * dz)}


def _time_name(case, t, function):
    """The sampled time directory name matching t (a name or a number)."""
    base = Path(case) / "postProcessing" / function
    if (base / str(t)).is_dir():
        return str(t)
    names = [d.name for d in base.iterdir() if d.is_dir()]
    match = [n for n in names if math.isclose(float(n), float(t),
                                              rel_tol=1e-9, abs_tol=1e-12)]
    assert match, f"no sampled time {t} in {base}"
    return match[0]


def steady_change(case, set_name, t1, t2, function="profiles"):
    """Largest change of the sampled U_x and alpha.small of a `profiles`
    set between the sampled times t1 and t2: {'Ux': ..., 'alpha.small':
    ...} (absolute, m/s and volume fraction)."""
    case = Path(case)
    a = profiles(case, _time_name(case, t1, function), function=function,
                 set_name=set_name)
    b = profiles(case, _time_name(case, t2, function), function=function,
                 set_name=set_name)
    return {"Ux": float(np.max(np.abs(b["U"][:, 0] - a["U"][:, 0]))),
            "alpha.small": float(np.max(np.abs(b["alpha.small"]
                                               - a["alpha.small"])))}


def small_fraction(alpha_small, alpha_large, alpha_air=None):
    """phi^s = alpha.small/(alpha.small + alpha.large), masked (numpy
    masked array) where alpha_air > 0.5 or no grains are present."""
    s = np.asarray(alpha_small, dtype=float)
    g = s + np.asarray(alpha_large, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = s / g
    mask = ~(g > 1e-12)
    if alpha_air is not None:
        mask |= np.asarray(alpha_air) > GRAINS
    return np.ma.masked_array(np.where(mask, 0.0, phi), mask=mask)


def mixed_thickness(case, time_name, band=(0.25, 0.75)):
    """The grains' mixed thickness of every column at a time: the grain
    volume per unit length (sum of phi^g dz) of the cells whose phi^s lies
    within band.  Returns (x (nx,), thickness (nx,))."""
    x, z, f = grid(case, time_name, ["alpha.air", "alpha.small",
                                     "alpha.large"])
    grains = f["alpha.small"] + f["alpha.large"]
    phis = small_fraction(f["alpha.small"], f["alpha.large"],
                          f["alpha.air"]).filled(0.0)
    mixed = (f["alpha.air"] < GRAINS) & (phis > band[0]) & (phis < band[1])
    return x, np.sum(np.where(mixed, grains, 0.0), axis=0) * _spacing(z)


def downstream_phibar(h=T3.h, zeta=ZETA, phi0=PHI0):
    """Depth-averaged phi^s far downstream (5.10): the flux of the uniform
    inflow phi0 carried by the Bagnold profile (0.6744 for table 3)."""
    pe = grayChugunov.peclet(T3.f_sl, h, T3.D_sl, zeta)
    return grayChugunov.downstream_mean(
        phi0, lambda zh: bagnold.velocity(zh * h, h, zeta), pe)


def outflow(case, set_name="outlet", h=T3.h):
    """The steady outflow: the column sampled at the last time against
    Bagnold (5.4) with the case's d, Gray & Chugunov (5.8) and (5.10), and
    its change since the time sampled before.  Returns (numbers, arrays):
    numbers for the results files, arrays (z, u, phis, Pe, phibar) for
    figure 4."""
    from scipy.optimize import brentq
    sampled = time_names(case)
    assert len(sampled) >= 2, \
        f"{case}: the outflow needs two sampled times, found {sampled}"
    t_prev, t_end = sampled[-2], sampled[-1]
    prof = profiles(case, t_end, function="profiles", set_name=set_name)
    z = prof["z"]
    dz = z[1] - z[0]
    inside = z + 0.5 * dz <= h          # cells wholly below the inflow depth
    grains = prof["alpha.small"] + prof["alpha.large"]

    u = prof["U"][:, 0]
    u_exact = bagnold.velocity(z[inside], h, ZETA, d=grain_diameter(case))
    l2_u = errors.l2_relative(u[inside], u_exact)

    phis = small_fraction(prof["alpha.small"], prof["alpha.large"])
    Pe = grayChugunov.peclet(T3.f_sl, h, T3.D_sl, ZETA)
    phibar = downstream_phibar(h)
    phis_exact = grayChugunov.phi_s(z[inside] / h, Pe, phibar)
    l2_phis = errors.l2_relative(phis[inside], phis_exact)

    # Height of phi^s = 1/2 (the transition), computed and (5.8)
    assert phis[0] > 0.5 and np.any(phis < 0.5), f"no phi^s = 1/2: {phis}"
    z_half = float(free_surface(z, (1.0 - phis)[:, None])[0])
    z_half_exact = float(brentq(
        lambda zz: grayChugunov.phi_s(zz / h, Pe, phibar) - 0.5, 0.0, h))

    # (5.10): depth average of phi^s over the grains, phi^s weighted by the
    # grain fraction so the interface cell counts once
    depth = float(np.sum(grains) * dz)
    phibar_computed = float(np.sum(prof["alpha.small"]) * dz / depth)

    prev = profiles(case, t_prev, function="profiles", set_name=set_name)
    change_u = float(np.abs(prev["U"][:, 0] - u).max() / u_exact.max())
    change_phis = float(np.abs(
        small_fraction(prev["alpha.small"], prev["alpha.large"])
        - phis)[grains > 0.5].max())

    numbers = {
        "end_time": float(t_end),
        "outlet_l2_u_bagnold": l2_u,
        "outlet_l2_phis_gray_chugunov": l2_phis,
        "outlet_phis_half_height": z_half,
        "exact_phis_half_height": z_half_exact,
        "outlet_depth_averaged_phis": phibar_computed,
        "theory_depth_averaged_phis": phibar,
        "outlet_grain_depth": depth, "Pe": Pe,
        "outlet_change_last_interval_u": change_u,
        "outlet_change_last_interval_phis": change_phis,
        "dz": dz,
    }
    return numbers, (z, u, phis, Pe, phibar)


def history(case, names=None, behind=0.1):
    """Front and air measures of the written times (names, default all
    t > 0): {'t', 'front' (free surface above one cell), 'foot'
    (front_foot), 'h_upstream' (median free surface over 0.1 m <= x <=
    front - behind, NaN if empty), 'depth_upstream' (the same for
    grain_depth), 'trapped', 'trapped_max', 'trapped_excess' (trapped_air
    integral, max and excess; m^2), 'sheet_tip', 'grains_ahead'
    (precursor tip and volume)}: numpy arrays."""
    names = [t for t in (names or time_names(case)) if float(t) > 0.0]
    rows = []
    for t in names:
        x, z, f = grid(case, t, ["alpha.air"])
        a = f["alpha.air"]
        dx, dz = _spacing(x), _spacing(z)
        hs = free_surface(z, a)
        front = front_position(x, hs, dz)
        up = (x >= 0.1) & (x <= front - behind)
        tr = trapped_air(x, z, a, hs, dx, dz, front)
        pre = precursor(x, a, front, dx, dz)
        rows.append((float(t), front, front_foot(x, a),
                     np.median(hs[up]) if up.any() else np.nan,
                     np.median(grain_depth(z, a)[up]) if up.any()
                     else np.nan, tr["integral"], tr["max"],
                     tr["excess"], pre["tip"], pre["volume"]))
    cols = np.array(rows, dtype=float).reshape(-1, 10).T
    keys = ("t", "front", "foot", "h_upstream", "depth_upstream",
            "trapped", "trapped_max", "trapped_excess", "sheet_tip",
            "grains_ahead")
    return dict(zip(keys, cols))


# --------------------------------------------------------------------------
# Figures
# --------------------------------------------------------------------------

def _save(fig, out):
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return str(out)


def _edges(c):
    """Cell edges of uniformly spaced centres c."""
    d = (c[-1] - c[0]) / (c.size - 1) if c.size > 1 else 1.0
    return np.concatenate(([c[0] - d / 2], c + d / 2))


def _spacing(c):
    return float((c[-1] - c[0]) / (c.size - 1))


def figure2(runs, out):
    """Figure 2: the air fraction phi^a of each run (label, case, time) over
    0 <= x <= 3 x_F (x_F: grain depth one cell, grain_depth), with the
    trapped air of trapped_air in the titles.  Returns {'path',
    'runs': [{'label', 'time', 'front', 'trapped': trapped_air(...)}]}."""
    results = []
    n = len(runs)
    fig, axes = plt.subplots(n, 1, squeeze=False, figsize=(8.5, 2.3 * n),
                             constrained_layout=True)
    mesh = None
    for k, ((label, case, time_name), ax) in enumerate(zip(runs,
                                                          axes[:, 0])):
        x, z, f = grid(case, time_name, ["alpha.air"])
        a = f["alpha.air"]
        dx, dz = _spacing(x), _spacing(z)
        lz = z[-1] + dz / 2
        front = front_position(x, grain_depth(z, a), dz)
        trapped = trapped_air(x, z, a, free_surface(z, a), dx, dz, front)
        results.append({"label": label, "time": str(time_name),
                        "front": front, "trapped": trapped})
        xmax = x[-1] + dx / 2
        if np.isfinite(front):
            xmax = min(xmax, max(3.0 * front, 2.0 * lz, 4.0 * dx))
        mesh = ax.pcolormesh(_edges(x) * 1e3, _edges(z) * 1e3, a,
                             cmap="coolwarm", vmin=0.0, vmax=1.0,
                             shading="flat", rasterized=True)
        ax.set_xlim(0.0, xmax * 1e3)
        ax.set_ylim(0.0, lz * 1e3)
        if np.isfinite(front):
            ax.axvline(front * 1e3, color="k", lw=0.8, ls=":")
        ax.set_ylabel("$z$ (mm)")
        air = trapped["integral"] * 1e6
        air = 0.0 if abs(air) < 1e-12 else air
        excess = trapped["excess"] * 1e6
        ax.set_title(f"({LETTERS[k]}) {label}, $t$ = {time_name} s\n"
                     f"bottom-cell air behind the front {air:.3g} mm$^2$ "
                     f"(mean $\\varphi^a$ {max(trapped['mean'], 0.0):.3f}"
                     f", max {max(trapped['max'], 0.0):.2f}), under "
                     f"denser grains {excess:.3g} mm$^2$", fontsize=9)
    axes[-1, 0].set_xlabel("$x$ (mm)")
    fig.suptitle("Figure 2: air fraction $\\varphi^a$ "
                 "(dotted: front)", fontsize=10)
    fig.colorbar(mesh, ax=axes[:, 0].tolist(), label="$\\varphi^a$",
                 shrink=0.9)
    return {"path": _save(fig, out), "runs": results}


def figure3(case, time_names, out, h=T3.h, f=T3.f_sl, phi0=PHI0, d=None):
    """Figure 3: phi^s inside the grains (alpha.air < 0.5) at the given
    times, one panel each, vertically stretched; the last panel with Gray &
    Thornton's (2005) shocks (appendix A, dashed).  Returns {'path',
    'fronts': {time: x_F}, 'x', 'z_half': height of phi^s = 1/2 in each
    column at the last time, 'z_final': the final shock (A3)}."""
    n = len(time_names)
    fig, axes = plt.subplots(n, 1, squeeze=False, sharex=True,
                             figsize=(10.0, 1.35 * n + 0.9))
    fronts = {}
    mesh = None
    x = z = None
    for k, (t, ax) in enumerate(zip(time_names, axes[:, 0])):
        x, z, fl = grid(case, t, ["alpha.air", "alpha.small",
                                  "alpha.large"])
        phis = small_fraction(fl["alpha.small"], fl["alpha.large"],
                              fl["alpha.air"])
        fronts[str(t)] = front_position(
            x, grain_depth(z, fl["alpha.air"]), _spacing(z))
        mesh = ax.pcolormesh(_edges(x), _edges(z) * 1e3, phis,
                             cmap="coolwarm", vmin=0.0, vmax=1.0,
                             shading="flat", rasterized=True)
        ax.set_facecolor("0.93")
        ax.set_ylim(0.0, _edges(z)[-1] * 1e3)
        ax.set_ylabel("$z$ (mm)")
        ax.text(0.005, 0.93, f"({LETTERS[k]}) $t$ = {t} s",
                transform=ax.transAxes, va="top", fontsize=9)
    # height where phi^s falls through 1/2 in the columns of the last time
    # (free_surface of 1 - phi^s, air counted as 0 small grains)
    z_half = free_surface(z, 1.0 - np.ma.filled(phis, 0.0))
    xs = np.linspace(0.0, x[-1] + _spacing(x) / 2, 600)
    lines = chute.shock_lines(xs, h, ZETA, f, phi0, d=d)
    ax = axes[-1, 0]
    for zline, name in zip(lines, ("lower", "upper", "final")):
        ax.plot(xs, zline * 1e3, "k--", lw=1.0,
                label="Gray & Thornton (2005) shocks (A1)-(A3)"
                if name == "lower" else None)
    ax.legend(loc="lower center", fontsize=8, framealpha=0.8)
    ax.set_xlabel("$x$ (m)")
    ax.set_xlim(0.0, x[-1] + _spacing(x) / 2)
    fig.suptitle("Figure 3: small-particle concentration $\\varphi^s$ "
                 "(vertical stretched; grey: air)", fontsize=10)
    fig.colorbar(mesh, ax=axes[:, 0].tolist(), label="$\\varphi^s$",
                 shrink=0.8, pad=0.01)
    return {"path": _save(fig, out), "fronts": fronts, "x": x,
            "z_half": z_half, "z_final": float(lines[2][-1])}


def figure4(z, u, phis, out, h, Pe, phibar, zeta=ZETA,
            where="the outlet", d=None):
    """Figure 4: (a) sampled downslope velocity u(z) (circles) against the
    Bagnold profile (5.4) of depth h (grain diameter d, default table 1's),
    (b) sampled phi^s against Gray &
    Chugunov (5.8)-(5.11) with Pe and phibar.  phis is NaN or masked in
    the air (small_fraction): those velocities are drawn grey and left out
    of the errors.  `where` names the sampled column in the title.
    Returns {'path', 'u_l2', 'phis_l2', 'phis_mean'}: relative L2 errors
    over the cells wholly below h (z the uniformly spaced cell centres; the
    interface cell left out, as validation/chute/test_chute.py), and the
    mean of the sampled phi^s over the grain cells with centres z <= h."""
    z = np.asarray(z, dtype=float)
    u = np.asarray(u, dtype=float)
    phis = np.ma.filled(np.ma.asarray(phis, dtype=float), np.nan)
    dz = z[1] - z[0] if z.size > 1 else 0.0
    inside = (z + 0.5 * dz <= h) & (z >= 0.0)
    zz = np.linspace(0.0, h, 200)
    u_ex = bagnold.velocity(zz, h, zeta, d=d)
    p_ex = grayChugunov.phi_s(zz / h, Pe, phibar)
    grains = np.isfinite(phis)
    ok_u = inside & np.isfinite(u) & grains
    ok_p = inside & np.isfinite(phis)
    u_l2 = _l2(u[ok_u], bagnold.velocity(z[ok_u], h, zeta, d=d))
    p_l2 = _l2(phis[ok_p], grayChugunov.phi_s(z[ok_p] / h, Pe, phibar))
    fig, (a, b) = plt.subplots(1, 2, figsize=(8.0, 3.8), sharey=True)
    a.plot(u_ex, zz * 1e3, "k-", label="Bagnold (5.4)")
    a.plot(u[grains], z[grains] * 1e3, "o", mfc="none", mec="C3",
           label="computed")
    if (~grains).any():
        a.plot(u[~grains], z[~grains] * 1e3, "o", mfc="none", mec="0.6",
               label="computed, air ($\\varphi^a > 0.5$)")
    a.set_xlabel("$u$ (m s$^{-1}$)")
    a.set_ylabel("$z$ (mm)")
    a.set_title(f"(a) rel. L2 error {u_l2:.2g}", fontsize=9)
    a.axhline(h * 1e3, color="0.6", lw=0.6, ls=":")
    a.legend(fontsize=8, loc="upper left")
    b.plot(p_ex, zz * 1e3, "k-",
           label=f"Gray & Chugunov (5.8), $Pe$ = {Pe:.2f},\n"
                 f"$\\overline{{\\varphi^s}}$ = {phibar:.4f}")
    b.plot(phis, z * 1e3, "o", mfc="none", mec="C3", label="computed")
    b.set_xlabel("$\\varphi^s$")
    b.set_xlim(-0.02, 1.02)
    b.axhline(h * 1e3, color="0.6", lw=0.6, ls=":")
    b.set_title(f"(b) rel. L2 error {p_l2:.2g}", fontsize=9)
    b.legend(fontsize=8, loc="upper right")
    fig.suptitle("Figure 4: steady downslope velocity and small-particle "
                 f"concentration at {where}", fontsize=10)
    below = (z <= h) & (z >= 0.0) & np.isfinite(phis)
    mean = float(np.mean(phis[below])) if below.any() else float("nan")
    return {"path": _save(fig, out), "u_l2": u_l2, "phis_l2": p_l2,
            "phis_mean": mean}


def _l2(c, e):
    """errors.l2_relative, NaN on no points (a figure title, not a test)."""
    return errors.l2_relative(c, e) if c.size else float("nan")


def _xi_at(xi, h, level):
    """Position where h first reaches level going upstream from the front
    (xi ordered increasingly, h -> 0 at the front); NaN if it never does."""
    xi = np.asarray(xi, dtype=float)
    h = np.asarray(h, dtype=float)
    order = np.argsort(xi)[::-1]            # from downstream to upstream
    xs, hs = xi[order], h[order]
    over = np.nonzero(hs >= level)[0]
    if over.size == 0:
        return float("nan")
    i = over[0]
    if i == 0:
        return float(xs[0])
    s = (level - hs[i - 1]) / (hs[i] - hs[i - 1])
    return float(xs[i - 1] + s * (xs[i] - xs[i - 1]))


def figure5(x, h_computed, out, x_front=None, h_inf=T3.h, zeta=ZETA,
            levels=(0.5, 0.9), d=None):
    """Figure 5: the computed free surface h(x) in the moving frame against
    the travelling fronts of (5.17) with (5.21) for chi = 1 and 5/4 (grain
    diameter d in Fr of (5.18), default table 1's), all
    fronts (h -> 0) placed at xi = 0.  The computed front is x_front, by
    default front_position(x, h, 0) (the first column without grains, to
    within a cell; pass front_foot(x, phi_air) for sub-cell precision).
    Returns {'path', 'x_front', 'h_upstream' (median h more than 0.15 m
    behind the front, NaN if none), 'h_inf', and for each level L the xi
    (m) where h first reaches L h_inf going upstream from the front:
    'xi_computed', 'xi_chi1', 'xi_chi54' ({L: xi})}."""
    x = np.asarray(x, dtype=float)
    h = np.asarray(h_computed, dtype=float)
    xf = front_position(x, h, 0.0) if x_front is None else float(x_front)
    xi = x - xf
    far = xi < -0.15
    h_up = float(np.median(h[far])) if far.any() else float("nan")
    p = chute.TABLE1 if d is None else dataclasses.replace(chute.TABLE1, d=d)
    xi1, h1 = chute.front_shape(h_inf, zeta, 1.0, p=p)
    xi54, h54 = chute.front_shape(h_inf, zeta, 1.25, p=p)
    res = {"x_front": xf, "h_upstream": h_up, "h_inf": h_inf,
           "xi_computed": {}, "xi_chi1": {}, "xi_chi54": {}}
    for L in levels:
        res["xi_computed"][L] = _xi_at(xi[xi <= 0.0], h[xi <= 0.0],
                                       L * h_inf)
        res["xi_chi1"][L] = _xi_at(xi1, h1, L * h_inf)
        res["xi_chi54"][L] = _xi_at(xi54, h54, L * h_inf)
    # the computed surface behind the front, closed at (x_front, 0)
    behind = (xi < 0.0) & (h > 0.0)
    xc = np.append(xi[behind], 0.0)
    hc = np.append(h[behind], 0.0)
    fig, ax = plt.subplots(figsize=(8.0, 3.6))
    ax.plot(xc * 100, hc * 1e3, "r-", lw=1.6,
            label="computed ($\\varphi^a$ = 0.5 contour)")
    ax.plot(xi1 * 100, h1 * 1e3, "k--", label="depth averaged, $\\chi$ = 1")
    ax.plot(xi54 * 100, h54 * 1e3, "b--",
            label="depth averaged, $\\chi$ = 5/4")
    lo = max(xi[0], min(xi1[0], xi54[0]))
    ax.set_xlim(lo * 100, 1.0)
    ax.set_ylim(0.0, 1.2 * max(h_inf, np.max(h)) * 1e3)
    ax.set_xlabel("$\\xi = x - u_F t$ (cm)")
    ax.set_ylabel("$h$ (mm)")
    ax.legend(fontsize=8, loc="lower left")
    ax.grid(alpha=0.3)
    ax.set_title("Figure 5: steadily travelling front, fronts aligned at "
                 f"$\\xi$ = 0 (computed front at $x$ = {xf * 100:.2f} cm "
                 "in the moving frame)", fontsize=9)
    res["path"] = _save(fig, out)
    return res


def figure6(case_movingFrame, time_name, ubar, out, length=0.15,
            pressure="p"):
    """Figure 6: the fields inside the grains (alpha.air < 0.5) over the
    last `length` metres behind the front of the moving-frame run:
    (a) u + ubar, (b) w, (c) streamlines of (u, w) in the moving frame,
    (d) pressure (field `pressure`), (e) log10 I.  Returns {'path',
    'x_front' (front_foot), 'u_max', 'w_min', 'w_max', 'p_max',
    'log10I_min', 'log10I_max'} over the plotted grains."""
    x, z, f = grid(case_movingFrame, time_name,
                   ["alpha.air", "U", pressure, "I"])
    xf = front_foot(x, f["alpha.air"])
    if not np.isfinite(xf):
        xf = x[-1]
    sel = (x >= xf - length) & (x <= xf + 0.1 * length)
    xs, grains = x[sel], f["alpha.air"][:, sel] < GRAINS

    def masked(a):
        return np.ma.masked_array(a[:, sel], mask=~grains)

    u = masked(f["Ux"])
    w = masked(f["Uz"])
    p = masked(f[pressure])
    with np.errstate(divide="ignore", invalid="ignore"):
        logI = np.ma.masked_invalid(np.log10(masked(f["I"])))
    xe, ze = _edges(xs) * 100, _edges(z) * 1e3
    fig, axes = plt.subplots(5, 2, figsize=(9.0, 10.5),
                             gridspec_kw={"width_ratios": (50, 1),
                                          "hspace": 0.45, "wspace": 0.02})
    wmax = float(np.ma.max(abs(w))) if w.count() else 1.0
    wnorm = colors.Normalize(-wmax, wmax)       # white at w = 0
    panels = [
        (u + ubar, "(a) downslope velocity $u + \\bar u$ (m s$^{-1}$), "
         "frame of the base", "viridis", None),
        (w, "(b) slope-normal velocity $w$ (m s$^{-1}$)", "RdBu_r", wnorm),
        (None, "(c) streamlines of $(u, w)$ in the moving frame", None,
         None),
        (p, f"(d) pressure {pressure} (Pa)", "magma", None),
        (logI, "(e) $\\log_{10} I$", "plasma", None)]
    for (ax, cax), (data, title, cmap, norm) in zip(axes, panels):
        ax.set_facecolor("0.85")
        ax.set_ylabel("$z$ (mm)")
        ax.set_title(title, fontsize=9, loc="left")
        ax.set_xlim(xe[0], xe[-1])
        ax.set_ylim(ze[0], ze[-1])
        if data is None:
            cax.set_visible(False)
            # streamlines of the whole field in the plotted units (x in
            # cm, z in mm), traced both ways from seeds inside the grains
            # on a line near the upstream end and one near the front; the
            # air is then covered (the free surface is a streamline of a
            # steadily travelling front)
            ax.pcolormesh(xe, ze, np.ma.masked_array(
                np.zeros(grains.shape), mask=~grains),
                cmap=colors.ListedColormap(["white"]), shading="flat",
                rasterized=True)
            uu = f["Ux"][:, sel] * 100
            ww = f["Uz"][:, sel] * 1e3
            zs = z * 1e3
            seeds = []
            for xs0 in (xs[0] + 0.02 * length, xf - 0.2 * length):
                j = min(np.searchsorted(xs, xs0), xs.size - 1)
                top = zs[grains[:, j]].max() if grains[:, j].any() else 0
                seeds += [(xs0 * 100, zz) for zz in
                          np.linspace(zs[0], top, 8)[1:-1]]
            kw = dict(color="k", linewidth=0.7, arrowsize=0.7,
                      density=(4, 1), start_points=np.array(seeds))
            try:
                ax.streamplot(xs * 100, zs, uu, ww,
                              broken_streamlines=False, **kw)
            except TypeError:       # matplotlib < 3.6
                ax.streamplot(xs * 100, zs, uu, ww, **kw)
            ax.pcolormesh(xe, ze, np.ma.masked_array(
                np.zeros(grains.shape), mask=grains),
                cmap=colors.ListedColormap(["0.85"]), shading="flat",
                rasterized=True, zorder=3)
            continue
        m = ax.pcolormesh(xe, ze, data, cmap=cmap, norm=norm,
                          shading="flat", rasterized=True)
        fig.colorbar(m, cax=cax)
    for ax in axes[:-1, 0]:
        ax.tick_params(labelbottom=False)
    axes[-1, 0].set_xlabel("$x$ (cm) in the moving frame")
    fig.suptitle(f"Figure 6: flow fields in the front after $t$ = "
                 f"{time_name} s (moving frame, $\\bar u$ = {ubar:.4f} "
                 "m s$^{-1}$; grey: air)", fontsize=10, y=0.93)

    def stat(a, fn):
        return float(fn(a)) if a.count() else float("nan")

    res = {"x_front": xf, "u_max": stat(u + ubar, np.ma.max),
           "w_min": stat(w, np.ma.min), "w_max": stat(w, np.ma.max),
           "p_max": stat(p, np.ma.max),
           "log10I_min": stat(logI, np.ma.min),
           "log10I_max": stat(logI, np.ma.max)}
    res["path"] = _save(fig, out)
    return res


# --------------------------------------------------------------------------
# Command line
# --------------------------------------------------------------------------

def _figure3_times(case, names, n=5):
    """n - 1 times spread over those with the front inside the domain, and
    the latest time."""
    names = [t for t in names if float(t) > 0.0]
    if len(names) <= n:
        return names
    lx = parameters(case).get("Lx")
    inside = []
    for t in names[:-1]:
        x, z, f = grid(case, t, ["alpha.air"])
        xf = front_position(x, grain_depth(z, f["alpha.air"]), _spacing(z))
        if lx is None or xf < 0.98 * lx:
            inside.append(t)
    pool = inside if len(inside) >= n - 1 else names[:-1]
    pick = np.unique(np.round(np.linspace(0, len(pool) - 1, n - 1))
                     .astype(int))
    return [pool[i] for i in pick] + [names[-1]]


def _print_history(case, names):
    hist = history(case, names)
    print(f"{case}:")
    print("   t (s)  front (m)  foot (m)  h up (mm)  depth up (mm)  "
          "base air (mm^2)  max base phi^a  excess (mm^2)  sheet tip (m)  "
          "grains ahead (mm^2)")
    for r in zip(*hist.values()):
        print(f"  {r[0]:6g}  {r[1]:9.4f}  {r[2]:8.4f}  {r[3] * 1e3:9.4f}  "
              f"{r[4] * 1e3:13.4f}  {r[5] * 1e6:15.3g}  {r[6]:14.3g}  "
              f"{r[7] * 1e6:13.3g}  {r[8]:13.4f}  {r[9] * 1e6:19.3g}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", type=Path, help="chute tutorial case")
    parser.add_argument("--out", type=Path, default=None,
                        help="figure directory (default <case>/figures)")
    parser.add_argument("--times", nargs="+", default=None,
                        help="times of figure 3 (default: chosen)")
    args = parser.parse_args(argv)
    case = args.case.resolve()
    out = (args.out or case / "figures").resolve()
    names = [t for t in time_names(case) if float(t) > 0.0]
    assert names, f"no written times in {case}"
    latest = names[-1]
    par = parameters(case)
    h = par.get("h", T3.h)
    d = grain_diameter(case)

    _print_history(case, names)
    res = figure3(case, args.times or _figure3_times(case, names),
                  out / "figure3.png", h=h, d=d)
    print(f"wrote {res['path']}  (fronts: "
          + ", ".join(f"t={t}: {x:.4f} m" for t, x in res["fronts"].items())
          + ")")

    # figure 4 at the outlet (as in the paper) and, when sampled, at
    # x = 0.3 m, away from the outlet's drawdown
    pe = grayChugunov.peclet(T3.f_sl, h, T3.D_sl, ZETA)
    phibar = downstream_phibar(h)
    sampled_time = _time_name(case, latest, "profiles")
    for set_name, name, where in (("outlet", "figure4.png", "the outlet"),
                                  ("x0.3", "figure4_x0.3.png",
                                   "x = 0.3 m")):
        folder = case / "postProcessing" / "profiles" / sampled_time
        files = list(folder.glob(set_name + "_*"))
        if set_name != "outlet" and not any(
                f.read_text().strip() for f in files):
            continue        # the set lies outside a shorter chute
        sampled = profiles(case, sampled_time, function="profiles",
                           set_name=set_name)
        phis = small_fraction(sampled["alpha.small"], sampled["alpha.large"],
                              sampled["alpha.air"])
        res = figure4(sampled["z"], sampled["U"][:, 0], phis, out / name,
                      h, pe, phibar, where=where, d=d)
        print(f"wrote {res['path']}  (t = {latest} s, {where}: u L2 "
              f"{res['u_l2']:.3g}, phi^s L2 {res['phis_l2']:.3g}, mean "
              f"phi^s {res['phis_mean']:.4f} vs {phibar:.4f})")

    moving = case / "movingFrame"
    moved = time_names(moving) if moving.is_dir() else []
    if moved:
        _print_history(moving, moved)
        mt = moved[-1]
        x, z, f = grid(moving, mt, ["alpha.air"])
        surface = free_surface(z, f["alpha.air"])
        res = figure5(x, surface, out / "figure5.png",
                      x_front=front_position(x, surface, _spacing(z)),
                      h_inf=h, d=d)
        print(f"wrote {res['path']}  (t = {mt} s, x_F = "
              f"{res['x_front']:.4f} m, xi(h/h_inf) computed "
              f"{res['xi_computed']}, chi=1 {res['xi_chi1']}, chi=5/4 "
              f"{res['xi_chi54']})")
        ubar = frame_velocity(moving, mt) or float(
            chute.depth_averaged_velocity(h, ZETA, d=d))
        res = figure6(moving, mt, ubar, out / "figure6.png")
        print(f"wrote {res['path']}  (t = {mt} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

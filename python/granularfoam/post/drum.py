"""Post-processing and figures of the square rotating drum
(tutorials/squareDrum), section 7 of Barker et al. (2021): figures 10, 11
and 13, the small-rich lobes and their period.

Reads what the case wrote: the rotatingDrum monitor (J(t) of (7.6), the
free-surface angle, the peak speed relative to the drum), the phase volumes
and bounds, the `rings` sets (phi^s on circles about the axis, sampled by
OpenFOAM) and the ascii fields and moved points of the time directories.

    /usr/bin/python3 -m granularfoam.post.drum CASE [CASE ...] [--out DIR] [--readme README]

writes the numbers of every case into OUT/drum.json and figure13.png (J(t)
of every run in OUT/drum.json, from its J_series or, for an entry without
one, J at each revolution), and for every case, keyed
by its mesh, coupling, cap and the advection scheme when it is not the
tutorial's (N50_30correctors_etaMax3000, N50_30correctors_etaMax300_linear,
N100_KrylovCahouetChabard20_etaMax3000),
figure10 and figure11 (a run that reached 80 s), the
lobes plot and revolutions (phi^s at t = 10, 20, ... s), and its numbers
into drum.json; with several cases also
settings.png (phi^s and the shear rate of each at its last common written
times); with --readme README the runs of OUT/drum.json are rendered into
that README between its markers named after OUT's folder
(<!-- drum results: NAME --> ... <!-- end of drum results: NAME -->).
"""
import argparse
import json
import math
import re
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from scipy.signal import find_peaks  # noqa: E402

from ..foamio import (function_table, log_cost,  # noqa: E402
                      parameters as _parameters, read_field, read_text, run,
                      time_names)
from .drumTension import step_table  # noqa: E402

DPI = 150
PERIOD = 10.0                   # s, one revolution at Omega = -pi/5
OMEGA = -2 * math.pi / PERIOD   # rad/s, clockwise (section 7.1)
I1 = 0.01886                    # table 4: below it the law creeps
ALPHA_SCHEME = "vanLeer"        # the tutorial's div(phi,alpha)
LOBE_RING = "r0.6"              # the circle on which lobes are counted
LOBE_PROMINENCE = 0.1           # of phi^s, for a lobe to count
LOBE_ANNULUS = (0.4, 0.9)       # radii / L of lobe_profile's annulus
LOBE_BINS = 72                  # its sectors, 5 degrees each
LOBE_PROMINENCE_ANNULUS = 0.05  # of its mean phi^s, for a lobe to count
LOBE_MATCH = math.radians(20)   # a lobe's largest move between writes
FIG11_FIRST, FIG11_LAST = 72.5, 78.75   # panels (b)-(l) of figure 11
J_SERIES_STEP = 0.25            # s, J(t) kept in drum.json for figure 13


# --------------------------------------------------------------------------
# Reading
# --------------------------------------------------------------------------

def parameters(case):
    """Numeric entries of case/system/drumParameters (N, L, etaMax, ...)."""
    return _parameters(case, "drumParameters")


def _fv_solution(case):
    """case/system/fvSolution without its comments."""
    return re.sub(r"//.*", "", read_text(Path(case) / "system" / "fvSolution"))


def n_correctors(case):
    """nCorrectors of the PIMPLE dictionary of case/system/fvSolution (the
    last entry: a later entry overrides an earlier one, as in OpenFOAM's
    dictionaries)."""
    found = re.findall(r"\bnCorrectors\s+(\d+)\s*;", _fv_solution(case))
    assert found, f"no nCorrectors in {case}/system/fvSolution"
    return int(found[-1])


def coupling(case):
    """The pressure-velocity coupling of case/system/fvSolution, as the
    tables name it: "30 correctors", or "Krylov CahouetChabard 20" (the
    preconditioner and the largest iteration count, each when fvSolution
    sets it: the solver holds their defaults).  Later entries override
    earlier ones, and Krylov dictionaries merge, as in OpenFOAM's."""
    text = _fv_solution(case)
    found = re.findall(r"\bpressureCoupling\s+(\w+)\s*;", text)
    if not found or found[-1] != "Krylov":
        return f"{n_correctors(case)} correctors"
    settings = {}
    for body in re.findall(r"\bKrylov\s*\{([^}]*)\}", text):
        for key in ("preconditioner", "maxIter"):
            values = re.findall(rf"\b{key}\s+(\w+)\s*;", body)
            if values:
                settings[key] = values[-1]
    return " ".join(["Krylov"] + [settings[k] for k in
                                  ("preconditioner", "maxIter")
                                  if k in settings])


def alpha_scheme(case):
    """The scheme of div(phi,alpha) in case/system/fvSchemes (the advection
    of the phases), e.g. vanLeer."""
    text = re.sub(r"//.*", "", read_text(Path(case) / "system" / "fvSchemes"))
    m = re.search(r"div\(phi,alpha\)\s+Gauss\s+([^;]+);", text)
    assert m, f"no div(phi,alpha) in {case}/system/fvSchemes"
    return m.group(1).strip()


def sidewall(case):
    """The end walls' friction of case/constant/fvOptions (./Allrun
    -sidewall W MUW): {'W': gap [m], 'muW': coefficient}, or None without
    a granularSidewallFriction there."""
    path = Path(case) / "constant" / "fvOptions"
    if not path.is_file():
        return None
    text = re.sub(r"//.*", "", read_text(path))
    if not re.search(r"\btype\s+granularSidewallFriction\s*;", text):
        return None
    values = {k: re.findall(rf"\b{k}\s+([-+.\deE]+)\s*;", text)
              for k in ("W", "muW")}
    assert all(values.values()), f"{path}: no W or muW"
    return {k: float(v[-1]) for k, v in values.items()}


FILL = 0.7                      # the paper's fill fraction, H = 0.04 m (7.1)


def fill(case):
    """The fill fraction of the drum, (H + L)/(2 L), from the grains'
    initial surface in case/system/setGranularFieldsDict (a flat surface
    through `point` with the tutorial's `normal` (0 1 0))."""
    path = Path(case) / "system" / "setGranularFieldsDict"
    text = re.sub(r"//.*", "", read_text(path))
    normal = re.search(r"\bnormal\s*\(([^)]*)\)", text)
    point = re.search(r"\bpoint\s*\(([^)]*)\)", text)
    assert point and normal, f"{path}: no point or normal"
    assert [float(x) for x in normal.group(1).split()] == [0, 1, 0], \
        f"{path}: a normal other than (0 1 0)"
    L = parameters(case)["L"]
    return (float(point.group(1).split()[1]) + L) / (2 * L)


def label(case):
    """The key of a run in drum.json and its figures: N, correctors and
    etaMax, the advection scheme when it is not the tutorial's, the end
    walls' gap and friction where the case has them, and the fill when it
    is not the paper's."""
    par = parameters(case)
    key = (f"N{int(par['N'])}_{coupling(case).replace(' ', '')}"
           f"_etaMax{par['etaMax']:g}")
    if alpha_scheme(case) != ALPHA_SCHEME:
        key += "_" + re.sub(r"\W+", "", alpha_scheme(case))
    walls = sidewall(case)
    if walls:
        key += f"_walls{walls['W']:g}m_muW{walls['muW']:g}"
    filled = fill(case)
    if abs(filled - FILL) > 1e-9:
        key += f"_fill{filled * 100:.0f}"
    return key


def body_shear_rate(case, names):
    """The median shear rate 2|D| over the grains (phi^a < 1/2) at each
    written time of names: in the rotating body the rigid rotation has no
    strain, so this measures the body's creep (per second)."""
    out = []
    for name in names:
        shear = read_field(case, name, "shearRate")
        air = read_field(case, name, "alpha.air")
        out.append(float(np.median(shear[air < 0.5])))
    return out


def grain_pressure_steps(case):
    """Every step's lowest pressure seen by the rheology in the grains, as
    the solver logs it ("Grain pressure seen by the rheology: min = ...")
    in case/log.granularSegregationFoam and its continuations: arrays of
    the step's time and that pressure."""
    logs = sorted(Path(case).glob("log.granularSegregationFoam*"))
    assert logs, f"no solver log in {case}"
    t, low = [], []
    for log in logs:
        now = None
        for line in read_text(log).splitlines():
            if line.startswith("Time = "):
                now = float(line.split()[2])
            elif line.startswith("Grain pressure seen by the rheology: min"):
                if now is not None:     # not the state read at the start
                    t.append(now)
                    low.append(float(line.split("=")[1].split()[0]))
    assert t, f"no grain pressure in the logs of {case}"
    return np.array(t), np.array(low)


def monitor(case):
    """The rotatingDrum monitor: {'t', 'J', 'angle', 'peak'} arrays."""
    a = function_table(case, "drum", "rotatingDrum.dat")
    return {"t": a[:, 0], "J": a[:, 1], "angle": a[:, 2], "peak": a[:, 3]}


def volumes(case):
    """The phase volumes: {'t', 'air', 'small', 'large'} arrays."""
    a = function_table(case, "volumes", "volFieldValue.dat")
    return {"t": a[:, 0], "air": a[:, 1], "small": a[:, 2],
            "large": a[:, 3]}


def bounds(case):
    """Smallest minimum and largest maximum of all phase fractions."""
    a = function_table(case, "bounds", "fieldMinMax.dat")
    return float(a[:, 1::2].min()), float(a[:, 2::2].max())


def points(case, time_name):
    """The moved mesh points of a time (n, 3); at t = 0, where the drum
    has not turned, the points of constant/polyMesh."""
    where = Path(case) / str(time_name) / "polyMesh" / "points"
    if float(time_name) == 0 and not where.is_file():
        where = Path(case) / "constant" / "polyMesh" / "points"
    text = read_text(where)
    body = text[text.index("FoamFile"):]
    body = body[body.index("}") + 1:]
    m = re.search(r"(\d+)\s*\(", body)
    assert m, f"{case}/{time_name}: cannot parse points"
    n = int(m.group(1))
    values = np.array(body[m.end():].replace("(", " ").replace(")", " ")
                      .split()[:3 * n], dtype=float)
    return values.reshape(n, 3)


def grid(case, time_name, names):
    """Fields of the N x N block at a time, in the lab frame: (X, Y)
    corners (N+1, N+1) of the moved mesh and {name: (N, N)}; vectors give
    name+'x' and name+'y'.  blockMesh numbers cells and points x first."""
    N = int(parameters(case)["N"])
    p = points(case, time_name)
    assert p.shape[0] == 2 * (N + 1) ** 2, (
        f"{case}: {p.shape[0]} points, not a {N} x {N} x 1 block")
    X = p[:(N + 1) ** 2, 0].reshape(N + 1, N + 1)
    Y = p[:(N + 1) ** 2, 1].reshape(N + 1, N + 1)
    out = {}
    for name in names:
        f = read_field(case, time_name, name)
        assert f.shape[0] == N * N, f"{name}: {f.shape[0]} values"
        if f.ndim == 1:
            out[name] = f.reshape(N, N)
        else:
            out[name + "x"] = f[:, 0].reshape(N, N)
            out[name + "y"] = f[:, 1].reshape(N, N)
    return X, Y, out


def centres(X, Y):
    """Cell centres (N, N) of the moved block from its corners (grid)."""
    return (0.25 * (X[:-1, :-1] + X[1:, :-1] + X[:-1, 1:] + X[1:, 1:]),
            0.25 * (Y[:-1, :-1] + Y[1:, :-1] + Y[:-1, 1:] + Y[1:, 1:]))


def small_fraction(f):
    """phi^s = phi^s_g/(phi^s_g + phi^l_g) in the grains (phi^a < 1/2),
    NaN in the air, from the fields of grid."""
    grains = f["alpha.small"] + f["alpha.large"]
    return np.where(f["alpha.air"] < 0.5,
                    f["alpha.small"] / np.maximum(grains, 1e-12), np.nan)


def relative_speed(f, xc, yc, omega=OMEGA):
    """|u - Omega k x r| (7.3), the speed relative to the drum, from the
    components 'Ux', 'Uy' of grid at the centres xc, yc."""
    return np.hypot(f["Ux"] + omega * yc, f["Uy"] - omega * xc)


def sample_rings(case):
    """Sample the circles of system/ringsDict on every written time (by
    OpenFOAM's postProcess, on the moved meshes), again whenever the latest
    written time has no samples (a run continued since)."""
    rings = Path(case) / "postProcessing" / "rings"
    if not (rings / time_names(case)[-1]).is_dir():
        run(case, "postProcess", "-dict", "system/ringsDict", "-fields",
             "(alpha.small alpha.air I)")


def ring(case, time_name, name=LOBE_RING):
    """phi^s, phi^a and I sampled on a circle (the `rings` sets): the lab
    angle [rad, 0..2pi) and {'alpha.small', 'alpha.air', 'I'}."""
    folder = Path(case) / "postProcessing" / "rings" / str(time_name)
    files = sorted(folder.glob(f"{name}_*.xy"))
    assert files, f"no ring {name} in {folder}"
    a = np.loadtxt(files[0])
    header = files[0].name[len(name) + 1:-3].split("_")
    assert sorted(header) == ["I", "alpha.air", "alpha.small"], header
    assert a.shape[1] == 3 + len(header), f"{files[0]}: {a.shape[1]} columns"
    theta = np.mod(np.arctan2(a[:, 1], a[:, 0]), 2 * math.pi)
    order = np.argsort(theta)
    return theta[order], {h: a[order, 3 + k] for k, h in enumerate(header)}


def _time_name(case, t):
    names = [n for n in time_names(case) if abs(float(n) - t) < 1e-6]
    assert names, f"{case}: no time directory at t = {t}"
    return names[0]


# --------------------------------------------------------------------------
# Measurements
# --------------------------------------------------------------------------

def _body(f):
    """The quasi-static body on a ring: grains (phi^a < 1/2) below the
    creep boundary (I < I_1), i.e. not in the surface avalanche."""
    return (f["alpha.air"] < 0.5) & (f["I"] < I1)


def _has_time(case, t):
    """Whether case has a written time t."""
    try:
        _time_name(case, t)
    except AssertionError:
        return False
    return True


def _circular_peaks(g, valid, prominence):
    """Indices of the peaks of g around a closed circle of prominence at
    least `prominence`, among the valid points; the others are set to the
    valid points' largest value, so that no peak is made by a gap's
    edge."""
    if not valid.any():
        return np.array([], dtype=int)
    g = np.where(valid, g, g[valid].max())
    n = g.size
    peaks, _ = find_peaks(np.concatenate((g, g, g)), prominence=prominence)
    peaks = peaks[(peaks >= n) & (peaks < 2 * n)] - n
    return peaks[valid[peaks]]


def lobes(case, time_name):
    """Small-rich lobes crossing the LOBE_RING circle at a time: their lab
    angles [rad].  A lobe is a peak of phi^s of prominence LOBE_PROMINENCE
    within the body (_body)."""
    theta, f = ring(case, time_name)
    return theta[_circular_peaks(f["alpha.small"], _body(f),
                                 LOBE_PROMINENCE)]


def lobe_profile(X, Y, f, radii=LOBE_ANNULUS, bins=LOBE_BINS):
    """phi^s of the body (_body: grains below the creep boundary, not the
    avalanche) in the annulus radii[0] L < r < radii[1] L about the axis,
    area-weighted mean per sector of the lab angle, from the fields of grid
    (alpha.small, alpha.large, alpha.air, I): the sectors' centre angles
    [rad] and means (nan where a sector has no body cell).  The lobes and
    the arms of the pattern are radial: here they are peaks."""
    L = np.max(np.hypot(X, Y)) / math.sqrt(2)
    xc, yc = centres(X, Y)
    r = np.hypot(xc, yc)
    cells = _body(f) & (r > radii[0] * L) & (r < radii[1] * L)
    V = cell_areas(X, Y)[cells]
    k = (np.mod(np.arctan2(yc[cells], xc[cells]), 2 * math.pi)
         / (2 * math.pi) * bins).astype(int) % bins
    total = np.bincount(k, V * small_fraction(f)[cells], bins)
    area = np.bincount(k, V, bins)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(area > 0, total / area, np.nan)
    return (np.arange(bins) + 0.5) * 2 * math.pi / bins, mean


def lobe_angles(X, Y, f, prominence=LOBE_PROMINENCE_ANNULUS):
    """The lobes of the body at a time: the lab angles [rad] of the peaks
    of lobe_profile of prominence at least `prominence`, each placed
    between its sectors by the parabola through its sector and the two
    beside it (where both are in the body)."""
    theta, mean = lobe_profile(X, Y, f)
    valid = np.isfinite(mean)
    peaks = _circular_peaks(np.where(valid, mean, 0.0), valid, prominence)
    n, width = mean.size, 2 * math.pi / mean.size
    out = []
    for k in peaks:
        a, b, c = mean[(k - 1) % n], mean[k], mean[(k + 1) % n]
        curve = a - 2 * b + c
        shift = (0.5 * (a - c) / curve
                 if np.isfinite(a + c) and curve < 0 else 0.0)
        out.append(theta[k] + shift * width)
    return np.array(out)


def lobe_spacing(angles):
    """The median angle [rad] between neighbouring lobes (angles about the
    axis), leaving out the largest gap, the one across the air and the
    avalanche; None with fewer than two lobes.  n lobes spread around the
    drum are 2 pi/n apart."""
    if len(angles) < 2:
        return None
    a = np.sort(np.mod(angles, 2 * math.pi))
    gaps = np.diff(np.append(a, a[0] + 2 * math.pi))
    return float(np.median(np.delete(gaps, np.argmax(gaps))))


def tension_where(case, names):
    """Where the grains (phi^a < 1/2) are below zero pressure at the
    written times `names`: per time with any, the lowest p, the grain cells
    below zero, the lowest cell's distance to the nearest wall, to the
    nearest corner and to the nearest air cell (phi^a >= 1/2) in cells,
    its speed relative to the drum and lab position, the time's phase in
    the quarter turn, and the largest granular viscosity and inertial
    number of the cells below zero."""
    out = []
    for name in names:
        X, Y, f = grid(case, name, ["p", "alpha.air", "U", "etaGranular",
                                    "I"])
        grains = f["alpha.air"] < 0.5
        p = np.where(grains, f["p"], np.inf)
        i, j = np.unravel_index(np.argmin(p), p.shape)
        if p[i, j] >= 0:
            continue
        n = p.shape[0]
        air = np.argwhere(~grains)
        xc, yc = centres(X, Y)
        out.append({
            "t": float(name),
            "quarter_turn_phase_s": float(name) % (PERIOD / 4),
            "lowest_p": float(p[i, j]),
            "grain_cells_below_zero": int(np.sum(p < 0)),
            "eta_granular_below_zero_max": float(
                f["etaGranular"][p < 0].max()),
            "I_below_zero_max": float(f["I"][p < 0].max()),
            "cells_to_wall": int(min(i, j, n - 1 - i, n - 1 - j)),
            "cells_to_corner": int(max(min(i, n - 1 - i),
                                       min(j, n - 1 - j))),
            "cells_to_air": float(np.min(np.hypot(air[:, 0] - i,
                                                  air[:, 1] - j))),
            "speed_relative_to_drum": float(
                relative_speed(f, xc, yc)[i, j]),
            "position_m": [float(xc[i, j]), float(yc[i, j])]})
    return out


def tension_by_phase(t, low, bins=10):
    """The steps' lowest grain pressure by the phase of the quarter turn
    (t mod T/4, the drum's square repeats every quarter turn): per bin the
    steps, those below zero, the lowest and the median."""
    phase = np.mod(t, PERIOD / 4)
    edges = np.linspace(0, PERIOD / 4, bins + 1)
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        s = (phase >= a) & (phase < b)
        if s.any():
            out.append({"phase_s": [float(a), float(b)],
                        "steps": int(s.sum()),
                        "below_zero": int(np.sum(low[s] < 0)),
                        "lowest_p": float(low[s].min()),
                        "median_p": float(np.median(low[s]))})
    return out


def lobe_period(case, names):
    """Period [s] of the lobes' rotation in the lab frame: the angular
    shift that best maps phi^s of the body on the circle at one write time
    onto the next (least squares over the ring's 2-degree shifts),
    averaged; with the shifts, to show their spread."""
    rates = []
    for a, b in zip(names[:-1], names[1:]):
        th, f0 = ring(case, a)
        _, f1 = ring(case, b)
        b0, b1 = _body(f0), _body(f1)
        dt = float(b) - float(a)
        n = th.size
        best = None
        for s in range(-n // 2, n // 2):
            mask = np.roll(b0, s) & b1
            if mask.sum() < n // 4:
                continue
            err = np.mean((np.roll(f0["alpha.small"], s)[mask]
                           - f1["alpha.small"][mask]) ** 2)
            if best is None or err < best[0]:
                best = (err, s)
        if best is not None:
            rates.append(best[1] * 2 * math.pi / n / dt)
    rate = float(np.mean(rates))
    return 2 * math.pi / abs(rate) if rate else math.inf, rate, rates


def _drum_move(a0, t0, a1, t1):
    """The move in the drum's frame (a lab angle minus Omega t) from the
    lab angle a0 at t0 to a1 at t1 [rad], wrapped to (-pi, pi]."""
    return np.angle(np.exp(1j * ((a1 - OMEGA * t1) - (a0 - OMEGA * t0))))


def lobe_tracks(angles, times, match=LOBE_MATCH):
    """The lobes followed from write to write: lobe angles (lobe_angles,
    one array per written time of `times`) in the drum's frame (the lab
    angle minus Omega t), each lobe joined to the nearest lobe of the time
    before within `match` [rad], nearest pairs first, one to one (the lobes
    are 90 degrees or more apart and move a few degrees between writes; one
    further away has formed or left the body).  A list of tracks, each a
    list of (time, lab angle [rad]) in time order."""
    tracks, open_ = [], {}          # open_: lobe index at the last time
    for k, (a, t) in enumerate(zip(angles, times)):
        a = np.asarray(a, dtype=float)
        joined = {}
        if k:
            a0, t0 = np.asarray(angles[k - 1], dtype=float), times[k - 1]
            pairs = sorted(
                (abs(g), i, j) for i, x in enumerate(a)
                for j, g in enumerate(_drum_move(a0, t0, x, t)))
            used = set()
            for g, i, j in pairs:
                if g <= match and i not in joined and j not in used:
                    joined[i] = open_[j]
                    used.add(j)
        now = {}
        for i, x in enumerate(a):
            if i not in joined:
                tracks.append([])
                joined[i] = len(tracks) - 1
            tracks[joined[i]].append((t, float(x)))
            now[i] = joined[i]
        open_ = now
    return tracks


def lobe_drift(angles, times, match=LOBE_MATCH):
    """How fast the lobes move against the drum [rad/s]: the median of the
    moves in the drum's frame of the lobes followed by lobe_tracks over
    their intervals, and the number of moves.  Negative: clockwise, as the
    drum turns, so lobes that turn faster than the drum drift negative."""
    moves = [_drum_move(a0, t0, a1, t1) / (t1 - t0)
             for track in lobe_tracks(angles, times, match)
             for (t0, a0), (t1, a1) in zip(track[:-1], track[1:])]
    return (float(np.median(moves)) if moves else None), len(moves)


def lobe_lives(angles, times, match=LOBE_MATCH):
    """The lobes seen both to form and to leave the body within `times`
    (lobe_tracks that start after the first time and end before the last):
    per lobe its life [s] and the lab angles [degrees, anticlockwise from
    +x] at which it was first and last seen."""
    return [{"life_s": track[-1][0] - track[0][0],
             "first_deg": math.degrees(track[0][1]) % 360,
             "last_deg": math.degrees(track[-1][1]) % 360}
            for track in lobe_tracks(angles, times, match)
            if track[0][0] > times[0] and track[-1][0] < times[-1]]


def quarter_turn_map(field):
    """The cells' values a quarter turn of the drum later moved back to
    where the cells were: the drum turns clockwise, so the cell that
    reaches, after a quarter turn, the lab position cell (i, j) held
    before lies a quarter turn anticlockwise of it in the block
    (np.rot90 of the (N, N) arrays of grid)."""
    return np.rot90(field)


def quarter_turn_changes(case, names):
    """How the small-grain pattern repeats over a quarter turn (T/4, the
    drum's square repeats in the lab every quarter turn).  For each written
    time t of names with t + T/4 written: the mean |phi^s(t + T/4) -
    phi^s(t)| over the grains of both (phi^a < 1/2) in the lab frame
    ('lab': small when the pattern is locked to the walls' quarter-turn
    forcing) and in the drum frame ('drum': small when it is frozen in the
    drum), the pattern's four-fold asymmetry in the drum frame
    ('asymmetry': phi^s against itself a quarter turn on) and the mean
    |phi^s - its mean| over the grains ('variation', the scale).  Means
    over the times."""
    rows = []
    fields = ["alpha.small", "alpha.large", "alpha.air"]
    read = {}       # phi^s by time name: each written time read once

    def small(name):
        if name not in read:
            read[name] = small_fraction(grid(case, name, fields)[2])
        return read[name]
    for a in names:
        try:
            b = _time_name(case, float(a) + PERIOD / 4)
        except AssertionError:
            continue
        s0, s1 = small(a), small(b)
        moved, turned = quarter_turn_map(s1), quarter_turn_map(s0)

        def change(x, y):
            both = np.isfinite(x) & np.isfinite(y)
            return float(np.mean(np.abs(x - y)[both]))
        grains = s0[np.isfinite(s0)]
        rows.append((change(moved, s0), change(s1, s0), change(turned, s0),
                     float(np.mean(np.abs(grains - grains.mean())))))
    if not rows:
        return None
    m = np.mean(rows, axis=0)
    return {"lab": float(m[0]), "drum": float(m[1]),
            "asymmetry": float(m[2]), "variation": float(m[3]),
            "pairs": len(rows)}


def flat_surface(theta, angle_deg, area, L):
    """The distance from the axis, along the upward normal (sin a, cos a)
    of a flat surface at inclination a = angle_deg (falling towards +x,
    as the drum monitor measures it), at which the square drum of half
    width L turned by theta [rad] holds `area` [m^2] below the surface:
    where the surface would stand if the grains only followed the walls
    (section 7.2: it rises and falls each quarter turn)."""
    from scipy.optimize import brentq
    c, s_ = math.cos(theta), math.sin(theta)
    square = L * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], float)
    square = square @ np.array([[c, s_], [-s_, c]])
    a = math.radians(angle_deg)
    n = np.array([math.sin(a), math.cos(a)])

    def below(d):
        """Area of the square where n.x < d (the polygon clipped by the
        half plane, Sutherland-Hodgman), by the shoelace formula."""
        h = square @ n - d
        poly = []
        for k in range(4):
            p, q, hp, hq = square[k], square[(k + 1) % 4], h[k], h[(k + 1) % 4]
            if hp <= 0:
                poly.append(p)
            if hp * hq < 0:
                poly.append(p + hp / (hp - hq) * (q - p))
        if len(poly) < 3:
            return 0.0
        x, y = np.array(poly).T
        return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    return brentq(lambda d: below(d) - area, -1.5 * L, 1.5 * L, xtol=1e-9)


def surface_rise(case, rows, names):
    """The free surface's distance from the axis on the mid-line (rows of
    drumSidewall.measure at the written times names) against a flat
    surface at the same inclination holding the grains' area
    (flat_surface): {'t', 'measured_m', 'flat_m'} and the range of each
    over the times and their correlation."""
    L = parameters(case)["L"]
    X, Y, f = grid(case, names[0], ["alpha.air"])
    area = float(np.sum((1 - f["alpha.air"]) * cell_areas(X, Y)))
    t = [r["t"] for r in rows]
    measured = [r["surface_distance_from_axis"] for r in rows]
    flat = [flat_surface(OMEGA * r["t"], r["surface_angle_deg"], area, L)
            for r in rows]
    return {"t": t, "measured_m": measured, "flat_m": flat,
            "measured_range_m": float(np.ptp(measured)),
            "flat_range_m": float(np.ptp(flat)),
            "correlation": float(np.corrcoef(measured, flat)[0, 1])}


def cell_areas(X, Y):
    """Areas (N, N) of the moved block's cells from their corners (grid),
    by the shoelace formula."""
    x = (X[:-1, :-1], X[:-1, 1:], X[1:, 1:], X[1:, :-1])
    y = (Y[:-1, :-1], Y[:-1, 1:], Y[1:, 1:], Y[1:, :-1])
    return 0.5 * np.abs(sum(x[i] * y[(i + 1) % 4] - x[(i + 1) % 4] * y[i]
                            for i in range(4)))


def change_over_period(case, t, period=PERIOD):
    """J(t) of (7.6) from the written fields of t and t - T (T = period):
    sum |phi^s(t) - phi^s(t - T)| V / sum V, phi^s the field the monitor
    follows (alpha.small), the cells fixed points of the turning drum.
    None when either time is not written."""
    if not (_has_time(case, t) and _has_time(case, t - period)):
        return None
    now, before = _time_name(case, t), _time_name(case, t - period)
    X, Y, f = grid(case, now, ["alpha.small"])
    _, _, f0 = grid(case, before, ["alpha.small"])
    V = cell_areas(X, Y)
    return float(np.sum(np.abs(f["alpha.small"] - f0["alpha.small"]) * V)
                 / np.sum(V))


def revolution_change(case, m, t):
    """J at t from the monitor m; where the monitor has no sample of
    t - T (after a restart it keeps only the written fields of the
    revolution before), from the written fields (change_over_period);
    nan when neither has it."""
    at = np.flatnonzero(np.abs(m["t"] - t) < 1e-6)
    if at.size and np.isfinite(m["J"][at[-1]]):
        return float(m["J"][at[-1]])
    J = change_over_period(case, t)
    return math.nan if J is None else J


def J_series(m, step=J_SERIES_STEP):
    """J(t) of the monitor m at the multiples of step (s) where it is
    finite, for the results file: {'t': [...], 'J': [...]} (4 digits).
    After a restart the monitor has J only where t - T is a written time
    (nan between), so those stretches are thinned to those points."""
    k = np.round(m["t"] / step)
    keep = (np.abs(m["t"] - k * step) < 1e-6) & np.isfinite(m["J"])
    return {"t": [round(float(x), 6) for x in m["t"][keep]],
            "J": [float(f"{x:.4g}") for x in m["J"][keep]]}


def run_cost(case):
    """Steps and CPU seconds of the run, from the solver's logs in case
    (log.granularSegregationFoam and its continuations log.*Foam.*): the
    number of time steps and the sum over the logs of the last
    ExecutionTime (of the master process, in a parallel run)."""
    logs = sorted(Path(case).glob("log.granularSegregationFoam*"))
    assert logs, f"no solver log in {case}"
    costs = [log_cost(read_text(log)) for log in logs]
    return {"steps": sum(c["steps"] for c in costs),
            "cpu_seconds": sum(c["cpu_seconds"] or 0.0 for c in costs)}


def summary(case):
    """The numbers of a case: J at each revolution, conservation, bounds,
    angle and speed statistics, lobes and their period."""
    par = parameters(case)
    m = monitor(case)
    v = volumes(case)
    out = {"N": int(par["N"]), "nCorrectors": n_correctors(case),
           "coupling": coupling(case),
           "etaMax": par["etaMax"], "alphaScheme": alpha_scheme(case),
           "sidewall": sidewall(case), "fill": fill(case),
           "endTime": float(m["t"][-1])}
    out.update(run_cost(case))
    out["J_revolution"] = {
        f"{k * PERIOD:g}": revolution_change(case, m, k * PERIOD)
        for k in range(1, int(m["t"][-1] / PERIOD + 1e-9) + 1)}
    out["J_series"] = J_series(m)
    for ph in ("air", "small", "large"):
        out[f"volume_drift_{ph}"] = float(
            np.max(np.abs(v[ph] / v[ph][0] - 1)))
    out["alpha_min"], out["alpha_max"] = bounds(case)
    # After 20 s, or over the last revolution of a run that ended before
    # 20 s
    late = m["t"] >= (2 * PERIOD if m["t"][-1] > 2 * PERIOD
                      else m["t"][-1] - PERIOD)
    # The monitor fits the surface within surfaceRadius of the axis; a
    # surface further out (a fuller drum) has no inclination (nan)
    fitted = np.isfinite(m["angle"][late])
    out["surface_angle_mean_deg"] = (float(np.mean(
        m["angle"][late][fitted])) if fitted.any() else None)
    out["surface_angle_range_deg"] = ([
        float(np.min(m["angle"][late][fitted])),
        float(np.max(m["angle"][late][fitted]))] if fitted.any() else None)
    out["peak_speed_mean"] = float(np.mean(m["peak"][late]))
    out["peak_speed_max"] = float(np.max(m["peak"][late]))
    sample_rings(case)
    names = [n for n in time_names(case)
             if float(n) >= m["t"][-1] - PERIOD - 1e-9]
    # The lowest pressure in the grains (phi^a < 1/2) at the written times
    # of the last revolution: p is levelled on the air, so this is the
    # pressure seen by the rheology to within rho^a g.x (1.4 Pa)
    lowest = [row[1] for row in step_table(case, names)]
    out["lowest_p_grains_last_revolution"] = min(lowest)
    out["written_times_with_negative_p_grains"] = int(
        sum(1 for x in lowest if x < 0))
    t, low = grain_pressure_steps(case)
    last = t >= m["t"][-1] - PERIOD - 1e-9
    out["lowest_p_grains_steps_last_revolution"] = float(low[last].min())
    out["steps_with_negative_p_grains_last_revolution"] = [
        int(np.sum(low[last] < 0)), int(np.sum(last))]
    out["tension_by_quarter_turn_phase_last_revolution"] = \
        tension_by_phase(t[last], low[last])
    out["tension_written_times_last_revolution"] = tension_where(case, names)
    out["lowest_p_grains_steps_all"] = float(low.min())
    out["steps_with_negative_p_grains_all"] = [int(np.sum(low < 0)),
                                               len(low)]
    out["body_shear_rate_median_last_revolution"] = float(
        np.mean(body_shear_rate(case, names)))
    # The flowing depth on the line through the axis normal to the surface
    # (drumSidewall.state; the paper: at most about 1.6 cm)
    # (drumSidewall.state; the paper: at most about 1.6 cm), which needs
    # the monitor's inclination at every written time
    from .drumSidewall import measure
    if np.all(np.isfinite(np.interp([float(n) for n in names], m["t"],
                                    m["angle"]))):
        rows = measure(case, float(names[0]))[0]
        depths = [r["flowing_depth"] for r in rows]
        out["flowing_depth_last_revolution_m"] = [float(np.mean(depths)),
                                                  float(np.max(depths))]
        out["depth_I_above_I1_last_revolution_m"] = float(
            np.mean([r["depth_I_above_I1"] for r in rows]))
        out["surface_rise_last_revolution"] = surface_rise(case, rows, names)
    out["quarter_turn_change_last_revolution"] = quarter_turn_changes(
        case, names)
    angles = [lobe_angles(*grid(case, n, ["alpha.small", "alpha.large",
                                          "alpha.air", "I"]))
              for n in names]
    out["lobes_annulus_last_revolution"] = [len(a) for a in angles]
    out["lobes_annulus_median"] = float(np.median([len(a) for a in angles]))
    drift, matches = lobe_drift(angles, [float(n) for n in names])
    out["lobe_drift_deg_s"] = None if drift is None else math.degrees(drift)
    out["lobe_drift_matches"] = matches
    lives = lobe_lives(angles, [float(n) for n in names])
    out["lobe_lives_last_revolution"] = lives
    out["lobe_life_s_median"] = (float(np.median([x["life_s"]
                                                  for x in lives]))
                                 if lives else None)
    spacing = [lobe_spacing(a) for a in angles]
    spacing = [x for x in spacing if x is not None]
    out["lobe_spacing_deg_median"] = (float(np.degrees(np.median(spacing)))
                                      if spacing else None)
    counts = [len(lobes(case, n)) for n in names]
    out["lobes_last_revolution"] = counts
    out["lobes_median"] = float(np.median(counts))
    period, rate, rates = lobe_period(case, names)
    out["lobe_period_s"] = period
    out["lobe_rate_rad_s"] = rate
    out["lobe_rate_spread_rad_s"] = [float(min(rates)), float(max(rates))]
    return out


def _json_safe(x):
    """NaN and infinities as null (JSON has no NaN)."""
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_json_safe(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


# --------------------------------------------------------------------------
# Figures
# --------------------------------------------------------------------------

def _save(fig, out):
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    assert out.is_file() and out.stat().st_size > 0, out


def figure13(numbers, out):
    """J(t) of (7.6) of every run of the results file (drum.json's run
    entries; figure 13): the monitor's series where the entry has one
    (J_series), else J at each revolution (J_revolution), marked.  Returns
    what was drawn: [(key, t, J), ...]."""
    runs = sorted(((k, v) for k, v in numbers.items()
                   if isinstance(v, dict) and "N" in v),
                  key=lambda kv: (kv[1]["N"], kv[0]))
    drawn = []
    fig, ax = plt.subplots(figsize=(6.5, 3.5))
    for key, r in runs:
        if r.get("J_series"):
            t, J = r["J_series"]["t"], r["J_series"]["J"]
            style = dict(ls="-")
        else:
            t = [float(k) for k in r["J_revolution"]]
            J = list(r["J_revolution"].values())
            style = dict(ls="--", marker="o", ms=3)
        ok = [(a, b) for a, b in zip(t, J) if b is not None
              and math.isfinite(b)]
        t, J = [a for a, _ in ok], [b for _, b in ok]
        ax.plot(t, J, label=key.replace("_", ", "), **style)
        drawn.append((key, t, J))
    ax.set_xlabel("t [s]")
    ax.set_ylabel(r"$\mathcal{J}(t)$  (7.6)")
    ax.set_xlim(0, None)
    ax.set_ylim(0, None)
    ax.legend(fontsize=7)
    ax.set_title("Change of the small-grain fraction over one revolution")
    _save(fig, out)
    return drawn


def figure_cases(cases, out, n_times=4):
    """phi^s (upper row of each case) and log10 of the shear rate 2|D|
    (lower row) in the grains, at the last n_times written times common to
    all the cases, a quarter turn apart: the settings side by side.  The
    shear rate in the body is its creep (the rigid rotation has none)."""
    common = set.intersection(*[{round(float(n), 6) for n in time_names(c)}
                                for c in cases])
    quarter = [t for t in sorted(common)
               if abs(t / (PERIOD / 4) - round(t / (PERIOD / 4))) < 1e-6
               and t > 0]
    times = quarter[-n_times:]
    fig, axes = plt.subplots(2 * len(cases), len(times), squeeze=False,
                             figsize=(2.4 * len(times), 4.6 * len(cases)))
    for i, case in enumerate(cases):
        for j, t in enumerate(times):
            X, Y, f = grid(case, _time_name(case, t),
                           ["alpha.small", "alpha.large", "alpha.air",
                            "shearRate"])
            body = f["alpha.air"] < 0.5
            phis = small_fraction(f)
            shear = np.where(body, np.log10(np.maximum(f["shearRate"], 1e-6)),
                             np.nan)
            pc = axes[2 * i, j].pcolormesh(X, Y, phis, cmap="viridis",
                                           vmin=0, vmax=1, shading="flat")
            ps = axes[2 * i + 1, j].pcolormesh(X, Y, shear, cmap="magma",
                                               vmin=-3, vmax=1.5,
                                               shading="flat")
            for ax in axes[2 * i:2 * i + 2, j]:
                drum_axes(ax, X, Y)
            axes[2 * i, j].set_title(f"{label(case)}\nt = {t:g} s",
                                     fontsize=7)
            axes[2 * i + 1, j].set_title(
                f"median 2|D| {np.median(f['shearRate'][body]):.3f} 1/s",
                fontsize=7)
    fig.subplots_adjust(right=0.85)
    fig.colorbar(pc, cax=fig.add_axes([0.88, 0.55, 0.02, 0.3]),
                 label=r"$\varphi^s$")
    fig.colorbar(ps, cax=fig.add_axes([0.88, 0.15, 0.02, 0.3]),
                 label=r"$\log_{10} 2|D|$ [1/s]")
    _save(fig, out)


def drum_axes(ax, X, Y):
    ax.set_aspect("equal")
    ax.set_xlim(-0.145, 0.145)
    ax.set_ylim(-0.145, 0.145)
    ax.set_xticks([])
    ax.set_yticks([])
    edge = np.concatenate((np.c_[X[0, :], Y[0, :]], np.c_[X[:, -1], Y[:, -1]],
                           np.c_[X[-1, ::-1], Y[-1, ::-1]],
                           np.c_[X[::-1, 0], Y[::-1, 0]]))
    ax.plot(edge[:, 0], edge[:, 1], "k-", lw=0.8)


def figure11(case, out):
    """phi^s at t = 10 s and every 0.625 s from 72.5 to 78.75 s (figure 11),
    in the lab frame, the air blank."""
    times = [PERIOD] + list(np.arange(FIG11_FIRST, FIG11_LAST + 1e-9, 0.625))
    fig, axes = plt.subplots(3, 4, figsize=(10, 7.8))
    for ax, t, letter in zip(axes.flat, times, "abcdefghijkl"):
        name = _time_name(case, t)
        X, Y, f = grid(case, name, ["alpha.small", "alpha.large", "alpha.air"])
        phis = small_fraction(f)
        pc = ax.pcolormesh(X, Y, phis, cmap="viridis", vmin=0, vmax=1,
                           shading="flat")
        drum_axes(ax, X, Y)
        ax.set_title(f"({letter}) t = {t:g} s", fontsize=9)
    fig.colorbar(pc, ax=axes, shrink=0.6, label=r"$\varphi^s$")
    _save(fig, out)


def figure_revolutions(case, out):
    """phi^s at the end of every revolution written (t = 10, 20, ... s),
    the drum back in its starting orientation each time: how the pattern
    develops, and figure 11(a) at 10 s, for a run that has not reached
    80 s as well; red: the lobes lobe_angles counts, across its annulus.
    Returns the times drawn."""
    times = [k * PERIOD for k in range(1, 9)
             if _has_time(case, k * PERIOD)]
    assert times, f"{case} has not written t = {PERIOD:g} s"
    fig, axes = plt.subplots(2, 4, figsize=(10, 5.4))
    for ax in axes.flat:
        ax.set_axis_off()
    L = parameters(case)["L"]
    for ax, t in zip(axes.flat, times):
        X, Y, f = grid(case, _time_name(case, t),
                       ["alpha.small", "alpha.large", "alpha.air", "I"])
        pc = ax.pcolormesh(X, Y, small_fraction(f), cmap="viridis",
                           vmin=0, vmax=1, shading="flat")
        for a in lobe_angles(X, Y, f):      # the lobes counted, radially
            r = np.array(LOBE_ANNULUS) * L
            ax.plot(r * math.cos(a), r * math.sin(a), "r-", lw=1)
        ax.set_axis_on()
        drum_axes(ax, X, Y)
        ax.set_title(f"t = {t:g} s", fontsize=9)
    fig.colorbar(pc, ax=axes, shrink=0.6, label=r"$\varphi^s$")
    fig.suptitle(label(case).replace("_", ", "), fontsize=9)
    _save(fig, out)
    return times


def figure10(case, out, times=(78.75, 80.0)):
    """|u - u_rot|, p and log10 I at two times (figure 10); on log10 I the
    creep boundary I = I_1 (solid) and the edge of the region where the
    viscosity cap (4.12) is active (dashed)."""
    par = parameters(case)
    fig, axes = plt.subplots(3, len(times), figsize=(4.2 * len(times), 11))
    for j, t in enumerate(times):
        name = _time_name(case, t)
        X, Y, f = grid(case, name, ["U", "p", "I", "etaGranular",
                                    "alpha.air"])
        xc, yc = centres(X, Y)
        air = f["alpha.air"] >= 0.5
        speed = np.where(air, np.nan, relative_speed(f, xc, yc))
        p = np.where(air, np.nan, f["p"])
        logI = np.where(air, np.nan, np.log10(np.maximum(f["I"], 1e-12)))
        capped = np.where(air, 0.0, (f["etaGranular"]
                                     >= (1 - 1e-6) * par["etaMax"]) * 1.0)
        for i, (v, label, cmap) in enumerate((
                (speed, r"$|\hat{\mathbf{u}}|$ [m/s]", "magma"),
                (p, "p [Pa]", "viridis"),
                (logI, r"$\log_{10} I$", "coolwarm"))):
            ax = axes[i, j]
            lim = dict(vmin=-5, vmax=1) if i == 2 else {}
            pc = ax.pcolormesh(X, Y, v, cmap=cmap, shading="flat", **lim)
            if i == 2:
                ax.contour(xc, yc, np.where(air, np.nan, f["I"]), [I1],
                           colors="k", linewidths=0.8)
                ax.contour(xc, yc, capped, [0.5], colors="k",
                           linewidths=0.8, linestyles="--")
            drum_axes(ax, X, Y)
            fig.colorbar(pc, ax=ax, shrink=0.8, label=label)
            ax.set_title(f"t = {t:g} s", fontsize=9)
    _save(fig, out)


def figure_lobes(case, out):
    """phi^s on the circle r = 0.6 L against the lab angle and time (the
    lobes are the bright stripes; their slope is their rotation)."""
    names = [n for n in time_names(case) if float(n) > 0]
    rows = []
    for n in names:
        th, f = ring(case, n)
        rows.append(np.where(_body(f), f["alpha.small"], np.nan))
    fig, ax = plt.subplots(figsize=(6.5, 4))
    pc = ax.pcolormesh(np.degrees(th), [float(n) for n in names],
                       np.array(rows), cmap="viridis", vmin=0, vmax=1,
                       shading="nearest")
    fig.colorbar(pc, ax=ax, label=r"$\varphi^s$ on r = 0.6 L (body: $I < I_1$)")
    ax.set_xlabel("lab angle [deg]")
    ax.set_ylabel("t [s]")
    _save(fig, out)


README_BEGIN = "<!-- drum results: {} -->"
README_END = "<!-- end of drum results: {} -->"
PAPER_BEGIN = "<!-- drum against the paper: {} -->"
PAPER_END = "<!-- end of drum against the paper: {} -->"
# What section 7 of the paper reports, for paper_table
PAPER = {
    "lobes": "3, towards the corners",
    "lobe_period": "faster than the drum: a period of about 7.5 s (§7.3), "
                   "so −12°/s",
    "J_change": "small: settled after about four revolutions (figure 13)",
    "surface_angle": "close to ζ_s = 20.16° (§7.2)",
    "flowing_depth": "at most about 1.6 cm (§7.2)",
    "lowest_p": "none below zero (figure 10)",
}


def _runs(numbers):
    """The run entries of drum.json's numbers, by mesh, coupling, cap."""
    runs = [v for v in numbers.values() if isinstance(v, dict) and "N" in v]
    return sorted(runs, key=lambda r: (r["N"], r["nCorrectors"],
                                       r["etaMax"], bool(r.get("sidewall")),
                                       r.get("coupling", "")))


def _run_title(r):
    """A run's column title: mesh, coupling, cap, the advection scheme
    when it is not the tutorial's, the end walls and the fill."""
    return (f"N = {r['N']}, "
            f"{r.get('coupling', str(r['nCorrectors']) + ' correctors')}, "
            f"η_max {r['etaMax']:g}"
            + (f", {r['alphaScheme']}" if r.get("alphaScheme", ALPHA_SCHEME)
               != ALPHA_SCHEME else "")
            + (", end walls {W:g} m apart, μ_w {muW:g}".format(
                **r["sidewall"]) if r.get("sidewall") else "")
            + (f", fill {r['fill'] * 100:.0f} %"
               if abs(r.get("fill", FILL) - FILL) > 1e-9 else ""))


def results_table(numbers):
    """Markdown rows of the runs in numbers (drum.json's run entries)."""
    runs = _runs(numbers)

    def g(x, fmt="{:.3g}"):
        return "–" if x is None else fmt.format(x)
    rows = [
        ("J at 10, 20, …, 80 s", lambda r: ", ".join(
            g(v, "{:.4f}") for v in r["J_revolution"].values())),
        ("surface inclination after 20 s (a shorter run: its last "
         "revolution), mean (range)", lambda r:
         f"{r['surface_angle_mean_deg']:.1f}° "
         f"({r['surface_angle_range_deg'][0]:.1f}–"
         f"{r['surface_angle_range_deg'][1]:.1f}°)"
         if r.get("surface_angle_mean_deg") is not None else
         "– (no surface within the monitor's surfaceRadius)"),
        ("peak speed relative to the drum, mean / max [m/s]", lambda r:
         f"{r['peak_speed_mean']:.3f} / {r['peak_speed_max']:.3f}"),
        ("median shear rate in the grains (the body's creep), last "
         "revolution [1/s]", lambda r: g(r.get(
             "body_shear_rate_median_last_revolution"))),
        ("flowing depth on the mid-line (speed above a quarter of its "
         "peak), last revolution, mean / max [cm]", lambda r: "–"
         if "flowing_depth_last_revolution_m" not in r else
         f"{r['flowing_depth_last_revolution_m'][0] * 100:.2f} / "
         f"{r['flowing_depth_last_revolution_m'][1] * 100:.2f}"),
        ("rise and fall of the free surface on the mid-line, last "
         "revolution: its range / a flat surface's holding the grains' "
         "area (correlation) [mm]", lambda r: "–"
         if not r.get("surface_rise_last_revolution") else
         "{:.1f} / {:.1f} ({:.3f})".format(
             r["surface_rise_last_revolution"]["measured_range_m"] * 1e3,
             r["surface_rise_last_revolution"]["flat_range_m"] * 1e3,
             r["surface_rise_last_revolution"]["correlation"])),
        ("mean change of φ^s over a quarter turn, last revolution, in the "
         "lab / in the drum (its mean deviation)", lambda r: "–"
         if not r.get("quarter_turn_change_last_revolution") else
         "{lab:.3f} / {drum:.3f} ({variation:.3f})".format(
             **r["quarter_turn_change_last_revolution"])),
        ("small-rich lobes in the body (`lobe_angles`), median over the "
         "last revolution; the angle between neighbours", _lobes_cell),
        ("the lobes' life in the body (`lobe_lives`: from forming to "
         "leaving, the lobes seen to do both in the last revolution), "
         "median / longest [s] (lobes); lab angles where they form and "
         "leave, mean",
         _lives_cell),
        ("small-rich lobes on r = 0.6 L, median over the last revolution",
         lambda r: g(r["lobes_median"], "{:g}")),
        ("lowest p in the grains, written times of the last revolution [Pa]",
         lambda r: f"{r['lowest_p_grains_last_revolution']:.1f} "
                   f"({r['written_times_with_negative_p_grains']} of "
                   f"{len(r['lobes_last_revolution'])} times below 0)"),
        ("lowest p in the grains over the steps of the last revolution "
         "[Pa] (steps below 0)", lambda r: "–"
         if "lowest_p_grains_steps_last_revolution" not in r else
         f"{r['lowest_p_grains_steps_last_revolution']:.1f} "
         f"({r['steps_with_negative_p_grains_last_revolution'][0]} of "
         f"{r['steps_with_negative_p_grains_last_revolution'][1]})"),
        ("steps, CPU [s] (master process)", lambda r: "–"
         if "steps" not in r else f"{r['steps']}, {r['cpu_seconds']:.0f}"),
        ("phase volumes, largest relative drift", lambda r: g(max(
            r["volume_drift_air"], r["volume_drift_small"],
            r["volume_drift_large"]), "{:.1e}")),
        ("fractions, min / max", lambda r:
         f"{r['alpha_min']:.1e} / {r['alpha_max']:g}"),
    ]
    head = "| | " + " | ".join(_run_title(r) for r in runs) + " |"
    lines = [head, "|---" * (len(runs) + 1) + "|"]
    for name, fn in rows:
        cells = [fn(r) for r in runs]
        if any(c != "–" for c in cells):    # a row no run measured: left out
            lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _lobes_cell(r):
    """Lobe count and spacing of a run entry, for the tables."""
    if r.get("lobes_annulus_median") is None:
        return "–"
    spacing = r.get("lobe_spacing_deg_median")
    return (f"{r['lobes_annulus_median']:g}" if spacing is None else
            f"{r['lobes_annulus_median']:g}, {spacing:.0f}° apart")


def _lives_cell(r):
    """The lobes' life in the body and where they form and leave (the
    angles' circular mean)."""
    lives = r.get("lobe_lives_last_revolution")
    if not lives:
        return "–"

    def mean_deg(key):
        z = np.mean([np.exp(1j * math.radians(x[key])) for x in lives])
        return math.degrees(np.angle(z)) % 360
    return "{:.2f} / {:.2f} s ({}), {:.0f}° → {:.0f}°".format(
        r["lobe_life_s_median"], max(x["life_s"] for x in lives),
        len(lives), mean_deg("first_deg"), mean_deg("last_deg"))


def _drift_cell(r):
    """The lobes' drift against the drum and their period in the lab."""
    drift = r.get("lobe_drift_deg_s")
    if drift is None:
        return "–"
    lab = abs(math.degrees(OMEGA) + drift)
    return (f"{drift:+.1f}°/s; {360 / lab:.1f} s" if lab
            else f"{drift:+.1f}°/s")


def paper_table(numbers):
    """Markdown rows comparing the runs of numbers (drum.json's run
    entries) with what section 7 of the paper reports (PAPER)."""
    runs = _runs(numbers)

    def change(r):
        J = r["J_revolution"]
        if J.get("80") is None or J.get("40") is None:
            return "–"
        return f"{J['80'] / J['40'] - 1:+.0%}"
    rows = [
        ("small-rich lobes in the body (`lobe_angles`), median over the "
         "last revolution; the angle between neighbours", PAPER["lobes"],
         _lobes_cell),
        ("the lobes' motion against the drum (`lobe_drift`, last "
         "revolution; negative: ahead of the drum); their period in the "
         "lab", PAPER["lobe_period"], _drift_cell),
        ("J(80 s)/J(40 s) − 1, the change over the last four revolutions",
         PAPER["J_change"], change),
        ("surface inclination, mean after 20 s", PAPER["surface_angle"],
         lambda r: "–" if r.get("surface_angle_mean_deg") is None else
         f"{r['surface_angle_mean_deg']:.1f}°"),
        ("flowing depth on the mid-line, largest over the last revolution",
         PAPER["flowing_depth"], lambda r: "–"
         if "flowing_depth_last_revolution_m" not in r else
         f"{r['flowing_depth_last_revolution_m'][1] * 100:.1f} cm"),
        ("lowest grain pressure over the steps of the last revolution",
         PAPER["lowest_p"], lambda r: "–"
         if "lowest_p_grains_steps_last_revolution" not in r else
         f"{r['lowest_p_grains_steps_last_revolution']:.0f} Pa"),
    ]
    head = "| | paper (N = 200) | " + " | ".join(
        _run_title(r) for r in runs) + " |"
    lines = [head, "|---" * (len(runs) + 2) + "|"]
    for name, paper, fn in rows:
        lines.append(f"| {name} | {paper} | "
                     + " | ".join(fn(r) for r in runs) + " |")
    return "\n".join(lines)


def replace_between(text, begin, end, body):
    """text with body between the markers begin and end."""
    i, j = text.find(begin), text.find(end)
    assert 0 <= i < j, f"no markers {begin} ... {end}"
    return text[:i + len(begin)] + "\n\n" + body + "\n\n" + text[j:]


def write_readme(path, numbers, name):
    """Replace the table between the markers of the drum README named
    name (the results folder's name: measured, etaMax, ...), and the
    comparison with the paper between its own markers where the README
    has them."""
    text = replace_between(path.read_text(), README_BEGIN.format(name),
                            README_END.format(name), results_table(numbers))
    if PAPER_BEGIN.format(name) in text:
        text = replace_between(text, PAPER_BEGIN.format(name),
                                PAPER_END.format(name), paper_table(numbers))
    path.write_text(text)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cases", nargs="+", type=Path)
    parser.add_argument("--out", type=Path, default=None)
    parser.add_argument("--readme", type=Path, default=None,
                        help="render the runs of OUT/drum.json into this "
                             "README, between its drum results markers")
    args = parser.parse_args(argv)
    cases = sorted(args.cases, key=lambda c: (parameters(c)["N"],
                                              n_correctors(c),
                                              parameters(c)["etaMax"]))
    out = args.out or cases[-1] / "figures"
    if len(cases) > 1:
        figure_cases(cases, out / "settings.png")
    numbers = {}
    for case in cases:
        s = summary(case)
        key = label(case)
        numbers[key] = s
        if s["endTime"] >= 80 - 1e-6:
            figure11(case, out / f"figure11_{key}.png")
            figure10(case, out / f"figure10_{key}.png")
        figure_lobes(case, out / f"lobes_{key}.png")
        figure_revolutions(case, out / f"revolutions_{key}.png")
    numbers = _json_safe(numbers)
    # Other entries of drum.json (the tension windows of drumTension) stay
    path = out / "drum.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    data.update(numbers)
    path.write_text(json.dumps(data, indent=2) + "\n")
    figure13(data, out / "figure13.png")
    if args.readme:
        write_readme(args.readme, data, out.name)
    print(json.dumps(numbers, indent=2))


if __name__ == "__main__":
    main()

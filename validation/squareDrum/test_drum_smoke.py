"""Smoke tier of the square drum (tutorials/squareDrum): a coarse drum for
a tenth of a revolution, serial and on 2 ranks.  The initial state (7.1)-
(7.2) of setGranularFields, the conservation of every phase's volume, the
bounds of the phase fractions, the pressure level of the closed drum, and
J of (7.6) recomputed from the written fields.
"""
import math
import re
import shutil

import numpy as np
import pytest

from cases import edit, foam, foam_output, fresh_case, set_decomposition
from granularfoam.foamio import read_field, cell_centres
from granularfoam.post import drum as post

pytestmark = pytest.mark.smoke

N = 15              # H = 0.04 m cuts the 8th row of cells in half
END = "1"           # s: 36 degrees of rotation
PERIOD = "0.5"      # s: the period of (7.6) in the test, so J exists
L, H = 0.1, 0.04
OMEGA = -math.pi / 5
RHO_AIR, G = 1.0, 9.81


def _set_period(case, period):
    """Give the rotatingDrum monitor a short period (T of (7.6))."""
    edit(case / "system" / "controlDict",
         [(r"(surfaceRadius[^\n]*\n)",
           r"\g<1>        period          " + period + ";\n")])


def _run(dest, *options, method="scotch"):
    case = fresh_case("squareDrum", dest=dest, tutorial=True)
    _set_period(case, PERIOD)
    set_decomposition(case, method)
    foam(case, "./Allrun", "-N", str(N), "-endTime", END,
         "-writeInterval", PERIOD, *options)
    return case


@pytest.fixture(scope="module")
def serial(foam_env):
    return _run("squareDrum_smoke/serial")


@pytest.fixture(scope="module")
def parallel(foam_env):
    return _run("squareDrum_smoke/parallel", "-parallel")


@pytest.fixture(scope="module")
def parallel_metis(foam_env):
    return _run("squareDrum_smoke/parallel-metis", "-parallel",
                method="metis")


def test_initial_state(serial):
    """(7.1): grains 50:50 below Z = H with the cut row at exactly half,
    air above; (7.2): U = Omega k x r at the cell centres."""
    case = serial
    C = cell_centres(case, "0")
    small = read_field(case, "0", "alpha.small")
    large = read_field(case, "0", "alpha.large")
    air = read_field(case, "0", "alpha.air")
    dx = 2 * L / N
    below = np.clip((H - (C[:, 1] - 0.5 * dx)) / dx, 0, 1)
    assert np.any((below > 0) & (below < 1)), "no cell is cut by Z = H"
    assert np.allclose(small, 0.5 * below, rtol=0, atol=1e-12)
    assert np.allclose(large, 0.5 * below, rtol=0, atol=1e-12)
    assert np.allclose(air, 1 - below, rtol=0, atol=1e-12)
    U = read_field(case, "0", "U")
    exact = np.c_[-OMEGA * C[:, 1], OMEGA * C[:, 0]]
    # written with 10 digits (writePrecision)
    assert np.allclose(U[:, :2], exact, rtol=1e-9, atol=1e-15)
    assert np.all(U[:, 2] == 0)


@pytest.mark.parametrize("which", ["serial", "parallel", "parallel_metis"])
def test_conservation_and_bounds(which, request):
    """Every phase's volume constant to 1e-10 (relative) while the mesh
    turns; every fraction within [-1e-10, 1 + 1e-10]."""
    case = request.getfixturevalue(which)
    v = post.volumes(case)
    assert v["t"][-1] == pytest.approx(float(END)), v["t"][-1]
    grains0 = (H + L) * 2 * L * (2 * L / N)
    assert v["small"][0] == pytest.approx(0.5 * grains0, rel=1e-9)
    for phase in ("air", "small", "large"):
        drift = np.max(np.abs(v[phase] / v[phase][0] - 1))
        assert drift < 1e-10, (phase, drift)
    lo, hi = post.bounds(case)
    assert lo > -1e-10 and hi < 1 + 1e-10, (lo, hi)


@pytest.mark.parametrize("which", ["serial", "parallel", "parallel_metis"])
def test_invariants(which, request):
    """granularInvariants, counted every step: each phase's volume balance
    to 1e-10, the sum of the fractions 1 to 1e-12, no NaN or Inf."""
    case = request.getfixturevalue(which)
    a = post.function_table(case, "invariants", "granularInvariants.dat")
    assert a[-1, 0] == pytest.approx(float(END))
    balance, lo, hi = a[:, 1:10:3], a[:, 2:10:3], a[:, 3:10:3]
    assert np.max(np.abs(balance)) < 1e-10, np.max(np.abs(balance))
    assert lo.min() > -1e-10 and hi.max() < 1 + 1e-10
    assert np.max(a[:, 10]) < 1e-12, np.max(a[:, 10])
    assert np.all(a[:, 11] == 0)


def test_pressure_level(serial):
    """The reference cell has turned into the grains, yet the air keeps
    the pressure level (p - rho^a g.x = pRefValue = 0 on average over the
    pure air) and the grains carry their weight."""
    case = serial
    t = post.time_names(case)[-1]
    C = cell_centres(case, t)
    p = read_field(case, t, "p")
    air = read_field(case, t, "alpha.air")
    pure = air >= 0.99
    assert pure.sum() > 0
    level = np.mean(p[pure] + RHO_AIR * G * C[pure, 1])
    weight = 1500 * G * 0.05
    assert abs(level) < 1e-6 * weight, level
    assert np.max(p) > weight, np.max(p)
    assert air[0] < 0.01, "the reference cell 0 should be in the grains"


def test_change_over_period(serial):
    """J of (7.6) written by rotatingDrum equals the mean of |phi^s(t) -
    phi^s(t - T)| of the written fields (uniform cells), as the post's
    change_over_period computes it."""
    case = serial
    m = post.monitor(case)
    t1 = float(END)
    t0 = t1 - float(PERIOD)
    k = np.argmin(np.abs(m["t"] - t1))
    assert abs(m["t"][k] - t1) < 1e-9
    J = np.mean(np.abs(read_field(case, f"{t1:g}", "alpha.small")
                       - read_field(case, f"{t0:g}", "alpha.small")))
    assert J > 1e-4, "phi^s did not change: no segregation"
    assert m["J"][k] == pytest.approx(J, rel=1e-6, abs=1e-9)
    # The post's J from the written fields, where a restarted monitor
    # has no sample of t - T
    assert post.change_over_period(case, t1, float(PERIOD)) == \
        pytest.approx(J, rel=1e-6, abs=1e-9)
    assert post.change_over_period(case, t1 + 1, float(PERIOD)) is None
    assert np.all(np.isnan(m["J"][m["t"] < float(PERIOD) - 1e-9]))
    assert np.all(np.isfinite(m["angle"])) and np.all(m["peak"] >= 0)


@pytest.mark.parametrize("which", ["parallel", "parallel_metis"])
def test_serial_parallel(serial, which, request):
    """2 ranks (scotch or metis) follow the serial run: surface angle, peak
    speed and J within what the solver tolerances allow (the PISO
    correctors stop at a relative tolerance of 0.01, which depends on the
    decomposition; measured with scotch: 2.2e-4 degrees, 2.1e-4 and 1.6e-5
    relative)."""
    parallel = request.getfixturevalue(which)
    log = (parallel / "log.decomposePar").read_text()
    method = "metis" if which.endswith("metis") else "scotch"
    assert re.search(rf"\b{method}\b", log, re.I), log[-1000:]
    a, b = post.monitor(serial), post.monitor(parallel)
    assert np.array_equal(a["t"], b["t"])
    assert np.allclose(a["angle"], b["angle"], rtol=0, atol=0.01)
    assert np.allclose(a["peak"], b["peak"], rtol=5e-3, atol=1e-6)
    assert np.allclose(a["J"], b["J"], rtol=1e-3, equal_nan=True)


@pytest.mark.parametrize("which", ["serial", "parallel"])
def test_post_reads_every_step(which, request):
    """granularfoam.post.drum reads one lowest grain pressure per time
    step from the solver's log (on 2 ranks, the master's), in the order of
    the steps, each the value the step logged, and names the coupling
    fvSolution sets."""
    case = request.getfixturevalue(which)
    log = (case / "log.granularSegregationFoam").read_text()
    steps = [float(t) for t in re.findall(r"^Time = (\S+)", log, re.M)]
    logged = [float(p) for p in re.findall(
        r"^Time = \S+$.*?^Grain pressure seen by the rheology: min = (\S+)",
        log, re.M | re.S)]
    t, low = post.grain_pressure_steps(case)
    assert len(t) == len(steps) == len(logged) > 10, (len(t), len(steps))
    assert np.array_equal(t, steps) and np.array_equal(low, logged)
    def setting(entry, option="-value"):
        return foam_output(case, "foamDictionary", "system/fvSolution",
                           "-entry", entry, option)[0].split()

    if ("pressureCoupling" in setting("PIMPLE", "-keywords")
            and setting("PIMPLE.pressureCoupling")[-1] == "Krylov"):
        expected = ("Krylov " + setting("PIMPLE.Krylov.preconditioner")[-1]
                    + " " + setting("PIMPLE.Krylov.maxIter")[-1])
    else:
        expected = f"{int(setting('PIMPLE.nCorrectors')[-1])} correctors"
    assert post.coupling(case) == expected


def test_post_names_the_krylov_coupling(serial, tmp_path):
    """With fvSolution PIMPLE { pressureCoupling Krylov; Krylov { ... } }
    the runs' key and tables name the preconditioner and iterations; a
    later entry overrides an earlier one, as OpenFOAM reads it."""
    case = tmp_path / "krylov"
    (case / "system").mkdir(parents=True)
    shutil.copy(serial / "system" / "fvSolution", case / "system")
    edit(case / "system" / "fvSolution",
         [(r"nCorrectors\s+\d+;", "nCorrectors 12;\n    pressureCoupling "
           "Krylov;\n    Krylov { preconditioner CahouetChabard; maxIter 8; }")])
    assert post.coupling(case) == "Krylov CahouetChabard 8"
    edit(case / "system" / "fvSolution",
         [(r"maxIter 8; \}", "maxIter 8; }\n    pressureCoupling PISO;")])
    assert post.coupling(case) == "12 correctors"


def test_movie(serial, tmp_path):
    """granularfoam.post.drumMovie: one frame per written time of the
    window, each phi^s as figure 11 draws it."""
    from PIL import Image
    from granularfoam.post import drumMovie

    out = tmp_path / "movie.gif"
    times = drumMovie.movie(serial, out)
    written = [float(t) for t in post.time_names(serial)]
    assert times == written and len(times) == 3, times
    with Image.open(out) as gif:
        assert gif.n_frames == len(times)
        # The frames differ: the drum turned 36 degrees between the first
        # and the last
        first = np.asarray(gif.convert("RGB"))
        gif.seek(gif.n_frames - 1)
        last = np.asarray(gif.convert("RGB"))
    assert first.shape == last.shape and np.any(first != last)
    late = drumMovie.movie(serial, tmp_path / "late.gif", start=0.4)
    assert late == written[1:]


def test_monitor_says_once_when_no_surface_is_within_reach(foam_env, serial):
    """With surfaceRadius shorter than the surface's distance from the
    axis (4 cm) the monitor finds no surface to fit: it writes the
    inclination as nan and says so once in the log; the tutorial's run
    finds one at every sample and says nothing."""
    case = fresh_case("squareDrum", dest="squareDrum_smoke/noSurface",
                      tutorial=True)
    edit(case / "system" / "controlDict",
         [(r"surfaceRadius\s+#eval\{[^}]*\};", "surfaceRadius   0.01;")])
    foam(case, "./Allrun", "-N", str(N), "-endTime", "0.1",
         "-writeInterval", "0.1")
    log = (case / "log.granularSegregationFoam").read_text()
    assert log.count("no free surface (air fraction 1/2) within "
                     "surfaceRadius 0.01 m") == 1
    m = post.monitor(case)
    assert m["t"].size > 1 and np.all(np.isnan(m["angle"]))
    assert "no free surface" not in \
        (serial / "log.granularSegregationFoam").read_text()

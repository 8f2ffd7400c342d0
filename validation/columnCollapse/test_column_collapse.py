"""The column collapse (tutorials/columnCollapse): one grain phase, the
monodisperse mu(I) flow with the air segregated out of it.

Nine runs, two at a time (one core each), on 5 mm cells (10 grain
diameters): the tutorial as its files say (column aspect ratio a = H0/L0 =
3.33), the same on 2.5 mm cells, at half the largest time step, and six
aspect ratios a = 0.5, 1, 2, 3.33, 5 and 7 (L0 = 0.06 m) in boxes long
enough for their run-out.  The front is where the deposit's grain depth
falls below 4 grain diameters (granularfoam.post.columnCollapse).
Checked:

1. the grain volume is conserved (every run);
2. the deposit is at rest: its height at the wall no longer changes over
   the last half second, and from half a second after its front has
   stopped on, its fastest grains move at the creep speed of
   the viscosity cap (about tau h / eta_max: 3.5e-5 m/s for 70 Pa under
   5 cm at eta_max = 1e5 Pa s), far below the collapse's 1 m/s;
3. the run-out l_inf - L0 and the deposit's height at the wall are the
   same on 5 mm and 2.5 mm cells, and at half the time step; the front
   does not retreat after its peak on 2.5 mm cells;
4. every run's front stops short of the box's far wall; the grains beyond
   the front (a film one cell thick ahead of the deposit, which reaches the
   far wall) shrink with the cells;
5. the run-out of the tall columns scales with the aspect ratio as the
   published laws say: (l_inf - L0)/L0 ~ a^n over a >= 3.33 with n between
   the 2/3 of Lube et al. (2005) and Lajeunesse et al. (2005) and
   Balmforth & Kerswell's (2005) 0.9 +- 0.1 (wide channels), a least-squares
   fit in log-log.  The exponent over a <= 2 is recorded in the fits, not
   checked (tutorials/columnCollapse/README.md);
6. the final height h_inf at the wall scales as Balmforth & Kerswell
   measured in wide channels, H0/h_inf ~ a^0.6, over a >= 1 (a column of
   a = 0.5 keeps its top: h_inf = H0).

Numbers: validation/results/columnCollapse/columnCollapse.json; the
figures columnCollapse.png and runout.png beside it.
"""
import subprocess

import numpy as np
import pytest

from cases import RESULTS, fresh_case, set_entry, write_results
from granularfoam.post import columnCollapse as post

pytestmark = pytest.mark.validation

L0 = 0.06                   # [m] the columns' width (the tutorial's)
CELL = 0.005                # [m] the tutorial's cells
# a: (H0, Lx, Lz) [m], each box long enough for the run-out of its column
ASPECT = {0.5: (0.03, 0.2, 0.1), 1: (0.06, 0.3, 0.1), 2: (0.12, 0.4, 0.15),
          3.33: (0.2, 0.6, 0.3), 5: (0.3, 0.8, 0.35), 7: (0.42, 1.0, 0.5)}
SMALL_A, LARGE_A = (0.5, 1, 2), (3.33, 5, 7)
LARGE_A_EXPONENT = 0.8      # the middle of [2/3 (Lube et al., Lajeunesse
                            # et al.), 0.9 (Balmforth & Kerswell)]
BK_HEIGHT_EXPONENT = 0.6    # Balmforth & Kerswell (2005): H/h_inf ~ a^0.6
REST = 0.5                  # [s] the last REST seconds: the deposit at rest


def _sweep_options(h0, lx, lz):
    return ("-H0", str(h0), "-Lx", str(lx), "-Lz", str(lz),
            "-nx", str(round(lx / CELL)), "-nz", str(round(lz / CELL)))


# name: (Allrun options, {dictionary: {entry: value}}), the longest first
RUNS = {
    "2.5mm": (("-nx", "240", "-nz", "120", "-endTime", "1"), {}),
    **{f"a{a:g}": (_sweep_options(*ASPECT[a]), {}) for a in (7, 5)},
    "5mm-dt/2": ((), {"system/controlDict": {"maxDeltaT": 5e-4}}),
    "5mm": ((), {}),
    **{f"a{a:g}": (_sweep_options(*ASPECT[a]), {}) for a in (2, 1, 0.5)},
}
SWEEP = {a: ("5mm" if a == 3.33 else f"a{a:g}") for a in ASPECT}


@pytest.fixture(scope="module")
def runs(foam_env):
    """Every run of RUNS, two at a time; their numbers and the figure."""
    cases, waiting, running = {}, list(RUNS), {}
    while waiting or running:
        while waiting and len(running) < 2:
            name = waiting.pop(0)
            options, settings = RUNS[name]
            case = fresh_case("columnCollapse",
                              "columnCollapse-" + name.replace("/", "_"),
                              tutorial=True)
            for dictionary, values in settings.items():
                for key, value in values.items():
                    set_entry(case, dictionary, key, value)
            cases[name] = case
            running[name] = subprocess.Popen(
                ["./Allrun", "-serial", *options], cwd=case,
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        name = next(iter(running))
        p = running.pop(name)
        out, _ = p.communicate(timeout=3600)
        assert p.returncode == 0, f"{name}: Allrun failed\n{out[-3000:]}"
        log = (cases[name] / "log.granularSegregationFoam").read_text()
        assert log.rstrip().endswith("End"), f"{name}: solver did not finish"
    numbers = {name: post.measure(case) for name, case in cases.items()}
    fits = post.laws({a: numbers[name] for a, name in SWEEP.items()},
                     {a: box[0] for a, box in ASPECT.items()}, L0,
                     SMALL_A, LARGE_A)
    out = RESULTS / "columnCollapse"
    out.mkdir(parents=True, exist_ok=True)
    write_results(out, "columnCollapse", {"runs": numbers, "fits": fits})
    post.figure({n: numbers[n] for n in ("5mm", "2.5mm", "5mm-dt/2")}, out)
    post.runout_figure(fits, out)
    return cases, numbers, fits


def _dz(case):
    p = post.parameters(case)
    return p["Lz"] / p["nz"]


def test_column_collapse_volume(runs, check):
    """The grain volume over the run, every run."""
    _, numbers, _ = runs
    check("column collapse: grain volume, largest relative change",
          max(n["volume_change"] for n in numbers.values()))


def test_column_collapse_at_rest(runs, check):
    """The tutorial's deposit: height at the wall and fastest grains."""
    cases, numbers, _ = runs
    n = numbers["5mm"]
    t = np.array(n["times"])
    h = np.array(n["wall_height"])
    assert t[-1] - t[0] > REST, f"the run ends at {t[-1]} s"
    h = h[t >= t[-1] - REST - 1e-9]
    check("column collapse: wall height over the last 0.5 s, range in cells",
          (h.max() - h.min()) / _dz(cases["5mm"]))
    check("column collapse: fastest grains at the end, m/s",
          n["fastest_grains_end"])
    # 0.5 s after the front has stopped
    later = t >= n["front_stop_time"] + REST - 1e-9
    assert later.any(), (
        f"the front stops at {n['front_stop_time']} s, the run ends at "
        f"{t[-1]} s")
    check("column collapse: fastest grains 0.5 s after the front stopped, m/s",
          max(np.array(n["fastest_grains"])[later]))
    # The collapse itself: the grains left the wall
    assert n["wall_height"][-1] < 0.5 * post.parameters(cases["5mm"])["H0"]


def test_column_collapse_converged(runs, check):
    """The run-out and the height at the wall on 2.5 mm cells and at half
    the step against the tutorial's 5 mm; the front's retreat after its
    peak on 2.5 mm."""
    _, numbers, _ = runs
    runout = {name: numbers[name]["front"][-1] - L0
              for name in ("5mm", "2.5mm", "5mm-dt/2")}
    h = {name: numbers[name]["wall_height"][-1]
         for name in ("5mm", "2.5mm", "5mm-dt/2")}
    check("column collapse: run-out, 5 mm against 2.5 mm, relative",
          abs(runout["5mm"] - runout["2.5mm"]) / runout["2.5mm"])
    check("column collapse: run-out, half the step, relative",
          abs(runout["5mm"] - runout["5mm-dt/2"]) / runout["5mm-dt/2"])
    check("column collapse: wall height, 5 mm against 2.5 mm, relative",
          abs(h["5mm"] - h["2.5mm"]) / h["2.5mm"])
    check("column collapse: wall height, half the step, relative",
          abs(h["5mm"] - h["5mm-dt/2"]) / h["5mm-dt/2"])
    fine = numbers["2.5mm"]
    check("column collapse: front's retreat after its peak, 2.5 mm, "
          "relative to the run-out",
          (fine["front_peak"] - fine["front"][-1]) / runout["2.5mm"])


def test_column_collapse_in_the_box(runs):
    """Every deposit's front ends short of its box's far wall."""
    cases, numbers, _ = runs
    for name, n in numbers.items():
        lx = post.parameters(cases[name])["Lx"]
        assert n["front"][-1] < lx - 5 * CELL, (
            f"{name}: the front at {n['front'][-1]:.3f} m of {lx} m")


def test_column_collapse_film(runs, check):
    """The grains beyond the front (a film one cell thick that runs ahead
    of the deposit) shrink with the cells: on 2.5 mm against 5 mm."""
    _, numbers, _ = runs
    check("column collapse: grains beyond the front, 2.5 mm over 5 mm",
          numbers["2.5mm"]["beyond_front"][-1]
          / numbers["5mm"]["beyond_front"][-1])


def test_column_collapse_runout_scaling(runs, check):
    """(l_inf - L0)/L0 ~ a^n over a >= 3.33 against the band between the
    2/3 of Lube et al. and Lajeunesse et al. (2005) and Balmforth &
    Kerswell's 0.9 (wide channels)."""
    _, _, fits = runs
    check("column collapse: exponent of the run-out in a >= 3.33, "
          "against 0.8",
          abs(fits["runout_exponent_large_a"] - LARGE_A_EXPONENT),
          paper="Lajeunesse et al. (2005), Balmforth & Kerswell (2005)")


def test_column_collapse_height_scaling(runs, check):
    """H0/h_inf ~ a^n over a >= 1: n against Balmforth & Kerswell's 0.6
    (wide channels)."""
    _, _, fits = runs
    check("column collapse: exponent of H0/h_inf in a, against 0.6",
          abs(fits["height_exponent"] - BK_HEIGHT_EXPONENT),
          paper="Balmforth & Kerswell (2005)")

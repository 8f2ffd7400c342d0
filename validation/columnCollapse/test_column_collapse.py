"""The column collapse (tutorials/columnCollapse): one grain phase, the
monodisperse mu(I) flow with the air segregated out of it.

Seven runs, two at a time (one core each), to the tutorial's end time:
the tutorial as its files say (1 cm cells, column aspect ratio a = H0/L0 =
3.33), on 5 mm cells, at half the largest time step, and four aspect
ratios a = 1.5, 2, 3.33 and 4.5 (L0 = 0.06 m) in a box 0.8 m long.
Checked:

1. the grain volume is conserved (every run);
2. the deposit is at rest: its height at the wall no longer changes over
   the last half second, and from half a second after its front has
   stopped on, its fastest grains move at the creep speed of
   the viscosity cap (about tau h / eta_max: 3.5e-5 m/s for 70 Pa under
   5 cm at eta_max = 1e5 Pa s), far below the collapse's 1 m/s;
3. the deposit's height at the wall is the same on 1 cm and 5 mm cells,
   and at half the time step; so is the front at half the time step;
4. the column has spread: its front on the floor lies well beyond L0;
5. the final height at the wall h_inf scales with the aspect ratio as
   Balmforth & Kerswell (2005) measured in wide channels, H0/h_inf ~ a^0.6
   (the exponent of a least-squares fit over the four aspect ratios).

The run-out is not mesh-converged on these meshes (the front lies further
out on 5 mm cells than on 1 cm); its exponent, (l_inf - L0)/L0 ~ a^n
(Balmforth & Kerswell: n = 0.9 +- 0.1 in wide channels), is recorded with
the fit, not checked.

Numbers: validation/results/columnCollapse/columnCollapse.json; the
figure columnCollapse.png beside it.
"""
import subprocess

import numpy as np
import pytest

from cases import RESULTS, fresh_case, set_entry, write_results
from granularfoam.post import columnCollapse as post

pytestmark = pytest.mark.validation

L0 = 0.06                   # [m] the columns' width (the tutorial's)
ASPECT = {"a1.5": 0.09, "a2": 0.12, "a3.33": 0.2, "a4.5": 0.27}   # H0 [m]
SWEEP_BOX = {"Lx": 0.8, "nx": 80}          # room for the run-out of a = 4.5
BK_HEIGHT_EXPONENT = 0.6    # Balmforth & Kerswell (2005): H/h_inf ~ a^0.6
REST = 0.5                  # [s] the last REST seconds: the deposit at rest

# name: (Allrun options, {dictionary: {entry: value}})
RUNS = {
    "1cm": ((), {}),
    "5mm": (("-nx", "120", "-nz", "60"), {}),
    "1cm-dt/2": ((), {"system/controlDict": {"maxDeltaT": 5e-4}}),
    **{name: (("-H0", str(h0)), {"system/columnParameters": SWEEP_BOX})
       for name, h0 in ASPECT.items()},
}


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
    h0 = np.array(list(ASPECT.values()))
    a = h0 / L0
    height = h0 / np.array([numbers[n]["wall_height"][-1] for n in ASPECT])
    runout = np.array([(numbers[n]["front"][-1] - L0) / L0 for n in ASPECT])
    fits = {
        "aspect_ratio": a.tolist(),
        "H0_over_h_inf": height.tolist(),
        "runout_over_L0": runout.tolist(),
        "height_exponent": float(np.polyfit(np.log(a), np.log(height), 1)[0]),
        "runout_exponent": float(np.polyfit(np.log(a), np.log(runout),
                                            1)[0]),
    }
    out = RESULTS / "columnCollapse"
    out.mkdir(parents=True, exist_ok=True)
    write_results(out, "columnCollapse", {"runs": numbers, "fits": fits})
    post.figure(numbers, out)
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
    """The deposit on 1 cm: height at the wall and fastest grains."""
    cases, numbers, _ = runs
    n = numbers["1cm"]
    t = np.array(n["times"])
    h = np.array(n["wall_height"])
    assert t[-1] - t[0] > REST, f"the run ends at {t[-1]} s"
    h = h[t >= t[-1] - REST - 1e-9]
    check("column collapse: wall height over the last 0.5 s, range in cells",
          (h.max() - h.min()) / _dz(cases["1cm"]))
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
    assert n["wall_height"][-1] < 0.5 * post.parameters(cases["1cm"])["H0"]


def test_column_collapse_converged(runs, check):
    """The deposit's height at the wall on 5 mm cells and at half the step,
    the front at half the step, against the tutorial's run."""
    cases, numbers, _ = runs
    h = {name: numbers[name]["wall_height"][-1]
         for name in ("1cm", "5mm", "1cm-dt/2")}
    check("column collapse: wall height, 1 cm against 5 mm, relative",
          abs(h["1cm"] - h["5mm"]) / h["5mm"])
    check("column collapse: wall height, half the step, relative",
          abs(h["1cm"] - h["1cm-dt/2"]) / h["1cm-dt/2"])
    p = post.parameters(cases["1cm"])
    check("column collapse: front, half the step, in cells",
          abs(numbers["1cm"]["front"][-1] - numbers["1cm-dt/2"]["front"][-1])
          / (p["Lx"] / p["nx"]))


def test_column_collapse_spread(runs, check):
    """The front on the floor at the end over the column's width."""
    cases, numbers, _ = runs
    check("column collapse: front on the floor over L0, 1 cm",
          numbers["1cm"]["front"][-1] / post.parameters(cases["1cm"])["L0"])


def test_column_collapse_height_scaling(runs, check):
    """H0/h_inf ~ a^n over the four aspect ratios: n against Balmforth &
    Kerswell's 0.6 (wide channels)."""
    _, _, fits = runs
    check("column collapse: exponent of H0/h_inf in a, against 0.6",
          abs(fits["height_exponent"] - BK_HEIGHT_EXPONENT),
          paper="Balmforth & Kerswell (2005)")

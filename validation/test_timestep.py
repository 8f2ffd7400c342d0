"""A time step beyond the viscous CFL: the periodic layer with
the viscous stress implicit (fvSolution PIMPLE viscousStress implicit).

The layer of test_verification.py (table 1 rheology, table 3 segregation,
50 cells over h, from rest to t = 1.75 s) is run with momentumPredictor
yes, viscousStress implicit and 4 PISO correctors at three caps on Delta t.
The ratio of the step reached to the viscous-CFL step is the viscous part
of (4.11) that the solver prints (it no longer limits the step).  Each run
must give Bagnold (5.4) to 1 % and Gray-Chugunov (5.8) to 2 % (the
explicit run gives 0.096 % and 0.177 %), at a step at least 10 times the
viscous-CFL step.  Numbers: validation/results/timestep/timestep.json.
"""
import math
import re

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cases import (RESULTS, fresh_case, last_two, profiles,  # noqa: E402
                   run_case, set_entry, write_results)
from granularfoam.exact import bagnold, errors, grayChugunov  # noqa: E402

pytestmark = pytest.mark.validation

H = 5e-3
ZETA = math.radians(24.0)
TABLE3 = grayChugunov.TABLE3
MAX_DELTA_T = (3e-5, 3e-4, 1e-3)    # [s]; the viscous-CFL step is ~4e-6 s

CFL_LINE = re.compile(r"^CFL \(4\.11\) max: .*viscous = (\S+)", re.M)


def run_implicit(max_dt):
    case = fresh_case("inclinedLayer", f"timestep/layer-{max_dt:g}")
    fv = "system/fvSolution"
    set_entry(case, fv, "PIMPLE/momentumPredictor", "yes")
    set_entry(case, fv, "PIMPLE/viscousStress", "implicit")
    set_entry(case, fv, "PIMPLE/nCorrectors", 4)
    set_entry(case, "system/controlDict", "maxDeltaT", max_dt)
    seconds = run_case(case)
    log = (case / "log.granularSegregationFoam").read_text()
    assert "Viscous stress: implicit" in log, "the implicit stress was not used"
    ratios = [float(x) for x in CFL_LINE.findall(log)]
    assert ratios, "no CFL lines in the log"
    steps = log.count("\nTime = ")
    return case, seconds, ratios, steps


@pytest.fixture(scope="module")
def runs(foam_env):
    return {dt: run_implicit(dt) for dt in MAX_DELTA_T}


def layer_errors(case):
    t_prev, t_end = last_two(case)
    prof = profiles(case, t_end)
    z = prof["z"]
    grains = z < H
    u = prof["U"][grains, 0]
    u_exact = bagnold.velocity(z[grains], H, ZETA)
    phi = prof["alpha.small"][grains]
    Pe = grayChugunov.peclet(TABLE3.f_sl, H, TABLE3.D_sl, ZETA)
    prev = profiles(case, t_prev)
    return {
        "end_time": float(t_end),
        "l2_u_bagnold": errors.l2_relative(u, u_exact),
        "l2_phis_gray_chugunov": errors.l2_relative(
            phi, grayChugunov.phi_s(z[grains] / H, Pe, 0.5)),
        "depth_averaged_phis": float(phi.mean()),
        "change_u_last_interval": float(
            np.abs(prev["U"][grains, 0] - u).max() / u_exact.max()),
    }, z[grains], u, phi


def test_layer_beyond_viscous_cfl(runs, check):
    table = []
    fig, axs = plt.subplots(1, 2, figsize=(8, 4), sharey=True)
    zz = np.linspace(0, H, 200)
    Pe = grayChugunov.peclet(TABLE3.f_sl, H, TABLE3.D_sl, ZETA)
    axs[0].plot(bagnold.velocity(zz, H, ZETA), zz / H, "k-", label="(5.4)")
    axs[1].plot(grayChugunov.phi_s(zz / H, Pe, 0.5), zz / H, "k-",
                label="(5.8)")
    for dt, (case, seconds, ratios, steps) in runs.items():
        numbers, z, u, phi = layer_errors(case)
        numbers.update({
            "max_delta_t": dt,
            # Delta t over the viscous-CFL step, over the run's last half
            "viscous_cfl_ratio_median": float(
                np.median(ratios[len(ratios) // 2:])),
            "viscous_cfl_ratio_max": float(max(ratios)),
            "steps": steps, "solver_seconds": seconds})
        table.append(numbers)
        label = f"{numbers['viscous_cfl_ratio_median']:.0f}x viscous CFL"
        axs[0].plot(u, z / H, "o", ms=3, mfc="none", label=label)
        axs[1].plot(phi, z / H, "o", ms=3, mfc="none", label=label)
    axs[0].set_xlabel("u [m/s]")
    axs[1].set_xlabel(r"$\varphi^s$")
    axs[0].set_ylabel("z/h")
    for ax in axs:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(RESULTS / "timestep" / "timestep-layer.png", dpi=120)
    plt.close(fig)
    write_results(RESULTS / "timestep", "timestep", {
        "case": "inclinedLayer, viscousStress implicit, nCorrectors 4",
        "runs": table})

    for n in table:
        where = f"implicit stress, layer at maxDeltaT {n['max_delta_t']:g} s"
        ratio = f"Δt {n['viscous_cfl_ratio_median']:.0f} × viscous CFL"
        check(f"{where}: u change over the last interval, of max",
              n["change_u_last_interval"], ratio)
        check(f"{where}: depth-averaged φ^s vs its initial 0.5, abs",
              abs(n["depth_averaged_phis"] - 0.5), ratio)
        check(f"{where}: u vs Bagnold, L2", n["l2_u_bagnold"],
              f"(5.4); {ratio}", percent=True)
        check(f"{where}: φ^s vs (5.8), L2", n["l2_phis_gray_chugunov"],
              f"(5.8); {ratio}", percent=True)
    # A lower bound: the largest step 10 times the viscous-CFL step at least
    check("implicit stress, layer: largest median Δt over the viscous-CFL "
          "step", max(n["viscous_cfl_ratio_median"] for n in table))


DELTA_T_LINE = re.compile(r"^deltaT = (\S+) \(limited by (.*)\)$", re.M)


def test_time_step_names_its_limit(runs):
    """Every step's deltaT line names what set it: maxDeltaT where the cap
    binds (the implicit layer at 3e-5 s, beyond its CFL bound), a CFL
    bound or the damped growth where it does not (1e-3 s)."""
    counts = {}
    for dt, (case, _, _, steps) in runs.items():
        log = (case / "log.granularSegregationFoam").read_text()
        lines = DELTA_T_LINE.findall(log)
        assert len(lines) == log.count("\ndeltaT = "), (
            f"a deltaT line of {case} names no limit")
        assert len(lines) >= steps - 1, f"{case}: {len(lines)} deltaT lines"
        # (setDeltaT then fits the step to the next write time, within 1 %)
        for value, limit in lines:
            if limit == "maxDeltaT":
                assert float(value) == pytest.approx(dt, rel=1e-2), (
                    f"limited by maxDeltaT {dt} at deltaT = {value}")
        counts[dt] = {k: sum(1 for _, lim in lines if lim.startswith(k))
                      for k in ("maxDeltaT", "maxCo", "maxAlphaCo", "growth")}
    capped, free = counts[min(MAX_DELTA_T)], counts[max(MAX_DELTA_T)]
    assert capped["maxDeltaT"] > 0.9 * sum(capped.values()), counts
    assert free["maxCo"] + free["maxAlphaCo"] > 0.5 * sum(free.values()), (
        counts)

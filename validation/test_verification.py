"""Verification of granularSegregationFoam on 1D columns.

1. Static column, constant f and D: phi^s against Gray & Chugunov (5.8)-(5.11)
   with Pe = f h / D, each phase's volume conserved to 1e-12.
2. Periodic layer at 24 degrees (table 1, one-way): u against Bagnold (5.4),
   p against (5.3), a sharp air-grain interface with no air at the base.
3. The same layer, table 3 segregation: phi^s against Gray & Chugunov with
   Pe = 31.97 (5.9).
4. The layer on 2 MPI ranks (scotch) against the serial run.

Each case runs in validation/results/<case>/ and leaves there its errors
(<case>.json) beside its figure (<case>.png).
"""
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cases import (fresh_case, last_two, profiles, run_case,  # noqa: E402
                   set_entry, times, volumes, write_results)
from granularfoam.exact import bagnold, errors, grayChugunov  # noqa: E402

pytestmark = pytest.mark.validation

H = 5e-3                    # grain depth [m]
ZETA = math.radians(24.0)   # slope of the layer
TABLE3 = grayChugunov.TABLE3


def plot_gray_chugunov(case, name, zhat, phi, Pe, t_end, l2):
    """phi^s against (5.8) on z/h, saved as case/<name>.png."""
    fig, ax = plt.subplots(figsize=(4, 4))
    zh = np.linspace(0, 1, 400)
    ax.plot(grayChugunov.phi_s(zh, Pe, 0.5), zh, "k-",
            label=f"Gray & Chugunov, Pe = {Pe:.2f}")
    ax.plot(phi, zhat, "o", ms=3, mfc="none", label=f"solver, t = {t_end} s")
    ax.set_xlabel(r"$\varphi^s$")
    ax.set_ylabel(r"$z/h$")
    ax.set_title(f"{name}: L2 = {100 * l2:.3f} %")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(case / f"{name}.png", dpi=120)
    plt.close(fig)


# ---------------------------------------------------------------------------
# 1. Static column
# ---------------------------------------------------------------------------

def test_static_column(foam_env, check):
    case = fresh_case("staticColumn")
    seconds = run_case(case)

    t_prev, t_end = last_two(case)
    prof = profiles(case, t_end)
    z, phi = prof["z"], prof["alpha.small"]
    assert len(z) == 100, f"expected the 100 cell centres, got {len(z)}"

    Pe = TABLE3.f_sl * H / TABLE3.D_sl          # vertical: cos(0) = 1
    exact = grayChugunov.phi_s(z / H, Pe, 0.5)
    l2 = errors.l2_relative(phi, exact)
    change = float(np.abs(phi - profiles(case, t_prev)["alpha.small"]).max())

    t, vol = volumes(case)
    drift = {name: float(np.max(np.abs(np.array(v) - v[0])) / max(v[0], 1e-300))
             for name, v in vol.items() if v[0] > 0}
    assert set(drift) == {"alpha.small", "alpha.large"}, drift
    assert len(t) > 100, f"only {len(t)} volume samples"

    write_results(case, "staticColumn", {
        "Pe": Pe, "l2_phi_s": l2, "tolerance_l2": 0.01,
        "max_change_last_interval": change,
        "volume_drift_relative": drift, "tolerance_volume": 1e-12,
        "cells_over_depth": len(z), "end_time": float(t_end),
        "solver_seconds": seconds})

    plot_gray_chugunov(case, "staticColumn", z / H, phi, Pe, t_end, l2)

    check("static column: φ^s change over the last interval, max abs",
          change)
    check("static column, 100 cells: φ^s vs Gray & Chugunov, L2", l2,
          "(5.8)", percent=True)
    for name, d in drift.items():
        check(f"static column: {name} volume drift (relative)", d)


# ---------------------------------------------------------------------------
# 2.-3. Periodic inclined layer (one run serves both)
# ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def layer(foam_env):
    case = fresh_case("inclinedLayer")
    seconds = run_case(case)
    return case, seconds


def interface_width(z, air):
    """Distance between the 10 % and 90 % levels of the air fraction,
    interpolated linearly between cell centres (air rises with z)."""
    def level(a):
        k = int(np.argmax(air >= a))
        assert k > 0, f"air fraction never crosses {a}"
        return z[k - 1] + (a - air[k - 1]) * (z[k] - z[k - 1]) / (air[k] - air[k - 1])
    return level(0.9) - level(0.1)


def test_layer_bagnold(layer, check):
    case, seconds = layer
    t_prev, t_end = last_two(case)
    prof = profiles(case, t_end)
    z = prof["z"]
    dz = z[1] - z[0]
    grains = z < H

    u = prof["U"][grains, 0]
    u_exact = bagnold.velocity(z[grains], H, ZETA)
    l2_u = errors.l2_relative(u, u_exact)
    u_prev = profiles(case, t_prev)["U"][grains, 0]
    change_u = float(np.abs(u - u_prev).max() / u_exact.max())

    p = prof["pGranular"][grains]
    p_exact = bagnold.pressure(z[grains], H, ZETA)
    l2_p = errors.l2_relative(p, p_exact)

    air = prof["alpha.air"]
    width = interface_width(z, air)
    air_base = float(air[0])
    air_in_grains = float(air[z < H - 3 * dz].max())

    I_zeta = bagnold.inertial_number_zeta(ZETA)
    results = {
        "I_zeta": I_zeta, "l2_u": l2_u, "tolerance_l2_u": 0.01,
        "max_change_u_last_interval_relative": change_u,
        "l2_p": l2_p, "tolerance_l2_p": 0.01,
        "interface_width_10_90_cells": width / dz, "tolerance_width_cells": 3,
        "air_at_base": air_base, "max_air_below_interface": air_in_grains,
        "cells_over_depth": int(grains.sum()), "end_time": float(t_end),
        "solver_seconds": seconds}
    write_results(case, "inclinedLayer-bagnold", results)

    fig, axs = plt.subplots(1, 3, figsize=(10, 4), sharey=True)
    zz = np.linspace(0, H, 200)
    axs[0].plot(bagnold.velocity(zz, H, ZETA), zz / H, "k-", label="Bagnold (5.4)")
    axs[0].plot(u, z[grains] / H, "o", ms=3, mfc="none", label="solver")
    axs[0].set_xlabel("u [m/s]")
    axs[0].set_title(f"L2 = {100 * l2_u:.3f} %")
    axs[1].plot(bagnold.pressure(zz, H, ZETA), zz / H, "k-", label="(5.3)")
    axs[1].plot(p, z[grains] / H, "o", ms=3, mfc="none", label="solver")
    axs[1].set_xlabel("p [Pa]")
    axs[1].set_title(f"L2 = {100 * l2_p:.3f} %")
    axs[2].plot(air, z / H, "o-", ms=3, mfc="none")
    axs[2].set_xlabel(r"$\varphi^a$")
    axs[2].set_title(f"10-90 % width {width / dz:.2f} cells")
    axs[0].set_ylabel(r"$z/h$")
    for ax in axs[:2]:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(case / "inclinedLayer-bagnold.png", dpi=120)
    plt.close(fig)

    written = ("alpha.air", "alpha.small", "alpha.large", "U", "p", "p_rgh",
               "I", "etaGranular", "shearRate", "dbar", "illPosed",
               "pGranular")
    missing = [f for f in written if not (case / t_end / f).is_file()]
    assert not missing, f"fields not written at t = {t_end}: {missing}"
    check("inclined layer: u change over the last interval, of max",
          change_u)
    check("inclined layer, 50 cells over h: u vs Bagnold, L2", l2_u,
          "(5.4)", percent=True)
    check("inclined layer: p vs lithostatic, L2", l2_p, "(5.3)",
          percent=True)
    check("inclined layer: free surface, 10-90 % width of φ^a in cells",
          width / dz, "(4.3)-(4.5)")
    check("inclined layer: φ^a left at the base", air_base, "(4.3)-(4.5)")
    check("inclined layer: φ^a inside the grains, max", air_in_grains,
          "(4.3)-(4.5)")


def test_layer_gray_chugunov(layer, check):
    case, seconds = layer
    t_prev, t_end = last_two(case)
    prof = profiles(case, t_end)
    z = prof["z"]
    grains = z < H
    phi = prof["alpha.small"][grains]

    Pe = grayChugunov.peclet(TABLE3.f_sl, H, TABLE3.D_sl, ZETA)
    phibar = float(phi.mean())
    exact = grayChugunov.phi_s(z[grains] / H, Pe, 0.5)
    l2 = errors.l2_relative(phi, exact)
    change = float(np.abs(
        phi - profiles(case, t_prev)["alpha.small"][grains]).max())

    write_results(case, "inclinedLayer-grayChugunov", {
        "Pe": Pe, "l2_phi_s": l2, "tolerance_l2": 0.02,
        "depth_averaged_phi_s": phibar,
        "max_change_last_interval": change,
        "end_time": float(t_end), "solver_seconds": seconds})

    plot_gray_chugunov(case, "inclinedLayer-grayChugunov", z[grains] / H,
                       phi, Pe, t_end, l2)

    assert abs(Pe - 31.97) < 0.005, f"Pe = {Pe}"
    check("inclined layer: depth-averaged φ^s vs its initial 0.5, abs",
          abs(phibar - 0.5))
    check("inclined layer: φ^s change over the last interval, max abs",
          change)
    check("inclined layer: φ^s vs Gray & Chugunov, L2", l2, "(5.8)",
          percent=True)


# ---------------------------------------------------------------------------
# 4. Serial against 2 MPI ranks
# ---------------------------------------------------------------------------

PARALLEL_END = 0.02     # [s]: enough steps for the flow and the segregation
                        # fluxes to be far from their initial values


def test_layer_parallel(foam_env, check):
    fields = ("U", "alpha.air", "alpha.small", "alpha.large", "p")
    runs = {}
    for name, script in (("serial", "./Allrun"),
                         ("parallel", "./Allrun-parallel")):
        case = fresh_case("inclinedLayer", f"inclinedLayer-{name}")
        set_entry(case, "system/controlDict", "endTime", PARALLEL_END)
        set_entry(case, "system/controlDict", "writeInterval", PARALLEL_END)
        runs[name] = (case, run_case(case, script))

    t_end = times(runs["serial"][0])[-1]
    assert times(runs["parallel"][0])[-1] == t_end
    a = profiles(runs["serial"][0], t_end)
    b = profiles(runs["parallel"][0], t_end)
    diffs = {}
    for f in fields:
        scale = max(float(np.abs(a[f]).max()), 1e-300)
        diffs[f] = float(np.abs(a[f] - b[f]).max() / scale)
    log = (runs["parallel"][0] / "log.granularSegregationFoam").read_text()
    assert "nProcs : 2" in log, "the parallel run did not use 2 ranks"

    write_results(runs["parallel"][0], "inclinedLayer-parallel", {
        "end_time": float(t_end), "max_relative_difference": diffs,
        "tolerance": 1e-8,
        "serial_seconds": runs["serial"][1],
        "parallel_seconds": runs["parallel"][1]})

    speed = float(np.abs(a["U"][:, 0]).max())
    assert speed > 1e-3, f"the layer did not start to flow: max u = {speed}"
    for f, d in diffs.items():
        check(f"inclined layer: {f}, 2 ranks vs serial (max relative)", d)

"""Sidewall friction: the fvOption granularSidewallFriction
against the exact solution of a layer between two walls.

The periodic layer of test_verification.py (table 1, zeta = 24 deg,
h = 5 mm under 1 mm of air, 50 cells over h, from rest) with the Coulomb
friction of walls W = 3 cm apart, mu_w = 0.25 (Jop, Forterre & Pouliquen
2005), to 2 s with the implicit viscous stress (4 correctors, Delta t at
most 3e-4 s), against (SW1)-(SW2) of python/granularfoam/exact/sidewall.py: the
friction mu(z) = tan(zeta) - mu_w (h - z)/W goes from 0.404 at the base
(> mu_s = 0.342: the whole layer flows) to tan(zeta) at the surface, and
the surface moves 36 % slower than Bagnold's (5.4).  Numbers and figure:
validation/results/sidewall/.
"""
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cases import (fresh_case, last_two, profiles, run_case,  # noqa: E402
                   set_entry, sidewall_friction, write_results)
from granularfoam.exact import bagnold, errors, sidewall  # noqa: E402
from granularfoam.exact.rheology import TABLE1  # noqa: E402

pytestmark = pytest.mark.validation

H = 5e-3                    # grain depth [m]
ZETA = math.radians(24.0)   # slope
MU_W = 0.25                 # wall friction coefficient
W = 0.03                    # gap [m]
END_TIME = 2.0              # [s]: steady from about 1.5 s


def test_sidewall_layer(foam_env, check):
    """Layer between sidewalls: u against the exact solution (SW1)-(SW2)"""
    case = fresh_case("inclinedLayer", "sidewall")
    sidewall_friction(case, muW=MU_W, W=W, wallVelocity="(0 0 0)")
    fv, cd = "system/fvSolution", "system/controlDict"
    set_entry(case, fv, "PIMPLE/momentumPredictor", "yes")
    set_entry(case, fv, "PIMPLE/viscousStress", "implicit")
    set_entry(case, fv, "PIMPLE/nCorrectors", 4)
    set_entry(case, cd, "maxDeltaT", 3e-4)
    set_entry(case, cd, "endTime", END_TIME)
    seconds = run_case(case)
    log = (case / "log.granularSegregationFoam").read_text()
    assert "Selecting finite volume options type granularSidewallFriction" \
        in log, "the sidewall friction was not selected"

    t_prev, t_end = last_two(case)
    assert float(t_end) == END_TIME, f"the run ended at {t_end}"
    prof = profiles(case, t_end)
    z = prof["z"]
    grains = z < H
    zg = z[grains]
    u = prof["U"][grains, 0]
    u_exact = sidewall.velocity(zg, H, ZETA, MU_W, W)
    u_bagnold = bagnold.velocity(zg, H, ZETA)
    l2 = errors.l2_relative(u, u_exact)
    change = float(np.abs(u - profiles(case, t_prev)["U"][grains, 0]).max()
                   / u_exact.max())
    slowdown = 1.0 - u[-1] / u_bagnold[-1]
    slowdown_exact = 1.0 - u_exact[-1] / u_bagnold[-1]

    write_results(case, "sidewall", {
        "muW": MU_W, "W": W, "h": H, "zeta_deg": math.degrees(ZETA),
        "mu_base": float(sidewall.friction(0.0, H, ZETA, MU_W, W)),
        "l2_u": l2,
        "l2_u_against_bagnold": errors.l2_relative(u, u_bagnold),
        "surface_slowdown_vs_bagnold": slowdown,
        "surface_slowdown_exact": slowdown_exact,
        "max_change_u_last_interval_relative": change,
        "cells_over_depth": int(grains.sum()), "end_time": float(t_end),
        "solver_seconds": seconds})

    fig, axs = plt.subplots(1, 2, figsize=(8, 4), sharey=True)
    zz = np.linspace(0.0, H, 200)
    axs[0].plot(sidewall.velocity(zz, H, ZETA, MU_W, W), zz / H, "k-",
                label=f"exact (SW2), $\\mu_w$ = {MU_W}, W = {100 * W:g} cm")
    axs[0].plot(bagnold.velocity(zz, H, ZETA), zz / H, "k--",
                label="Bagnold (5.4), no walls")
    axs[0].plot(u, zg / H, "o", ms=3, mfc="none", label=f"solver, t = {t_end} s")
    axs[0].set_xlabel("u [m/s]")
    axs[0].set_ylabel("z/h")
    axs[0].set_title(f"L2 = {100 * l2:.3f} %")
    axs[0].legend(fontsize=7)
    axs[1].plot(sidewall.friction(zz, H, ZETA, MU_W, W), zz / H, "k-",
                label=r"(SW1) $\tan\zeta - \mu_w (h - z)/W$")
    axs[1].axvline(math.tan(ZETA), color="k", ls="--", lw=0.8,
                   label=r"$\tan\zeta$")
    axs[1].axvline(TABLE1.mus, color="grey", ls=":", lw=0.8,
                   label=r"$\mu_s$")
    axs[1].set_xlabel(r"$\mu$")
    axs[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(case / "sidewall.png", dpi=120)
    plt.close(fig)

    check("layer between sidewalls: u change over the last interval, of max",
          change)
    # A lower bound: the walls slow the surface by 20 % of Bagnold's at least
    check("layer between sidewalls: surface slowdown against Bagnold",
          slowdown, f"(SW2): {slowdown_exact:.3f}")
    check("layer between sidewalls, 50 cells over h: u vs (SW2), L2", l2, "Jop et al. (2005)", percent=True)

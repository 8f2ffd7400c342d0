"""Steady uniform flow of a segregated bidisperse mixture down an inclined
plane with segregation-induced frictional feedback, section 6.1 and
figure 7.

The composition phi^s(z) is prescribed (Gray & Chugunov's (5.8)-(5.11) for
figure 7), the pressure is lithostatic (5.3) and the volume-fraction weighted
friction (3.3) of two Jop et al. laws (6.2) gives the depth-dependent
inertial number (6.3); the velocity follows from (6.5).

Every function of z takes the small-particle composition ``phi`` either as a
callable phi(z) (z in m, returning values in [0, 1]) or as a constant in
[0, 1]; phi^l = 1 - phi^s.  The two phases are rheology.Table1 instances:
their mus, mud and d are used per phase, I0 (equal for both, as (6.2)
assumes), Phi and g are taken from the small phase.  Figure 7 uses
SMALL = table 1 with muInf = 0 and LARGE = table 1 with mus = 1.2 mus and
muInf = 0 (same diameter d = 0.5 mm); a general bidisperse mixture is made
with dataclasses.replace(SMALL, d=d_s) etc.
"""
import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.integrate import solve_ivp

from . import grayChugunov
from . import bagnold
from .bagnold import ZETA
from .grayChugunov import TABLE3, peclet
from .rheology import TABLE1, _result

SMALL = replace(TABLE1, muInf=0.0)
LARGE = replace(TABLE1, mus=1.2 * TABLE1.mus, muInf=0.0)


@dataclass(frozen=True)
class Figure7:
    """Slope, depth and segregation parameters of figure 7: zeta = 24 deg,
    table 3 (f_sl, D_sl, h) and the depth-averaged small-particle
    concentration phibar = 0.5 (SI units)."""
    zeta: float = ZETA
    h: float = TABLE3.h
    f_sl: float = TABLE3.f_sl
    D_sl: float = TABLE3.D_sl
    phibar: float = 0.5


FIG7 = Figure7()


def composition(z, c=FIG7):
    """Small-particle concentration of figure 7: Gray & Chugunov's (5.8)
    with A_GC from (5.11), zhat = z/h and Pe = f_sl h cos zeta/D_sl (5.9)
    (31.97 for table 3), depth average (5.10) c.phibar."""
    Pe = peclet(c.f_sl, c.h, c.D_sl, c.zeta)
    return grayChugunov.phi_s(np.asarray(z, dtype=float) / c.h, Pe,
                              c.phibar)


def _fraction(z, phi):
    """phi^s at the heights z: phi(z) for a callable, else the constant."""
    z = np.asarray(z, dtype=float)
    v = phi(z) if callable(phi) else phi
    v = np.broadcast_to(np.asarray(v, dtype=float), z.shape)
    if np.any(v < 0.0) or np.any(v > 1.0) or np.any(np.isnan(v)):
        raise ValueError("phi^s must lie in [0, 1]")
    return v


def mu_bar_s(z, phi=composition, small=SMALL, large=LARGE):
    """Weighted static friction (6.4a): phi^s mus^s + phi^l mus^l."""
    v = _fraction(z, phi)
    return _result(v * small.mus + (1.0 - v) * large.mus)


def mu_bar_d(z, phi=composition, small=SMALL, large=LARGE):
    """Weighted dynamic friction (6.4b): phi^s mud^s + phi^l mud^l."""
    v = _fraction(z, phi)
    return _result(v * small.mud + (1.0 - v) * large.mud)


def mean_diameter(z, phi=composition, small=SMALL, large=LARGE):
    """Local mean grain diameter (6.6) (= (3.1)):
    dbar = phi^s d^s + phi^l d^l."""
    v = _fraction(z, phi)
    return _result(v * small.d + (1.0 - v) * large.d)


def _check_I0(small, large):
    if small.I0 != large.I0:
        raise ValueError("(6.3) assumes the same I0 for both phases")


def inertial_number(z, phi=composition, zeta=FIG7.zeta, small=SMALL,
                    large=LARGE):
    """Depth-dependent inertial number (6.3),
    I = I0 (tan zeta - mubar_s)/(mubar_d - tan zeta), mubar from (6.4a,b):
    the solution of (6.1) for two Jop laws (6.2) with the same I0.
    ValueError where tan zeta is outside (mubar_s, mubar_d) (no steady
    flow)."""
    _check_I0(small, large)
    t = math.tan(zeta)
    ms = np.asarray(mu_bar_s(z, phi, small, large))
    md = np.asarray(mu_bar_d(z, phi, small, large))
    if np.any(ms >= t) or np.any(md <= t):
        raise ValueError("tan zeta must lie between mubar_s and mubar_d")
    return _result(small.I0 * (t - ms) / (md - t))


def inertial_number_root(fractions, laws, zeta=FIG7.zeta):
    """Inertial number of steady uniform flow with the weighted friction
    (3.3), i.e. the root of (6.1): sum_nu phi^nu mu^nu(I) = tan zeta, by
    brentq, for any increasing friction callables laws[nu](I) (e.g.
    lambda I: rheology.mu_jop(I, SMALL)) and volume fractions
    fractions[nu] summing to one.  For two Jop laws (6.2) with the same I0
    this is (6.3)."""
    fractions = [float(v) for v in fractions]
    if len(fractions) != len(laws) or abs(sum(fractions) - 1.0) > 1e-12 \
            or min(fractions) < 0.0:
        raise ValueError("need one fraction >= 0 per law, summing to 1")
    return bagnold.inertial_number_zeta_root(
        zeta, None,
        lambda I, _: sum(v * float(law(I)) for v, law in zip(fractions, laws)))


def _check_depth(z, h):
    z = np.asarray(z, dtype=float)
    if np.any(z < 0.0) or np.any(z > h):
        raise ValueError("the solution holds for 0 <= z <= h only")
    return z


def integrate_from_base(rhs, z, rtol, atol):
    """u at the heights z (an array, any order) of du/dz = rhs(z, u) with
    no slip u(0) = 0, by solve_ivp (DOP853): the velocity ODEs (6.5) and
    (6.14)."""
    zs, back = np.unique(z.ravel(), return_inverse=True)
    if zs[-1] == 0.0:
        return _result(np.zeros_like(z))
    sol = solve_ivp(rhs, (0.0, zs[-1]), [0.0], method="DOP853", t_eval=zs,
                    rtol=rtol, atol=atol)
    if not sol.success:
        raise RuntimeError(sol.message)
    return _result(sol.y[0][back].reshape(z.shape))


def velocity(z, phi=composition, h=FIG7.h, zeta=FIG7.zeta, small=SMALL,
             large=LARGE, rtol=1e-11):
    """Downslope velocity: the ODE (6.5),
    du/dz = I(z)/dbar(z) sqrt(Phi g cos zeta) (h - z)^{1/2}, I from (6.3),
    dbar from (6.6), integrated by solve_ivp (DOP853) from the no-slip base
    u(0) = 0 to the heights z (any order, 0 <= z <= h)."""
    z = _check_depth(z, h)
    scale = math.sqrt(small.Phi * small.g * math.cos(zeta))

    def rhs(zz, u):
        return [inertial_number(zz, phi, zeta, small, large)
                / mean_diameter(zz, phi, small, large)
                * scale * math.sqrt(max(h - zz, 0.0))]

    return integrate_from_base(rhs, z, rtol, atol=1e-16)


def velocity_uniform(z, phi, h=FIG7.h, zeta=FIG7.zeta, small=SMALL,
                     large=LARGE):
    """Closed form for a uniform composition phi^s = phi (a constant):
    Bagnold's (5.4) with the constant I of (6.3) and d = dbar of (6.6),
    u = 2 I/(3 dbar) sqrt(Phi g cos zeta) (h^{3/2} - (h - z)^{3/2})."""
    z = _check_depth(z, h)
    if callable(phi) or np.ndim(phi) != 0:
        raise ValueError("velocity_uniform needs a constant phi")
    I = inertial_number(0.0, phi, zeta, small, large)
    d = mean_diameter(0.0, phi, small, large)
    return _result(2.0 * I / (3.0 * d)
                   * math.sqrt(small.Phi * small.g * math.cos(zeta))
                   * (h ** 1.5 - (h - z) ** 1.5))


def figure7(path, solver_I=None, solver_u=None, n=400):
    """Draw figure 7 into path (matplotlib, Agg): (a) I(z), (b) u(z) in
    m/s, z in mm on the vertical axis; the stratified solution (composition,
    FIG7) in black, the uniform solutions dashed: pure large (phi^s = 0)
    red, pure small (phi^s = 1) blue, phi^s = 0.5 everywhere green.
    solver_I, solver_u: optional (z [m], values) pairs drawn as markers."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = FIG7.h
    z = np.linspace(0.0, h, n)
    fig, (a, b) = plt.subplots(1, 2, figsize=(8, 4), sharey=True)
    a.plot(inertial_number(z), 1e3 * z, "k-", label="stratified")
    b.plot(velocity(z), 1e3 * z, "k-", label="stratified")
    for phi, style, label in ((0.0, "r--", "pure large"),
                              (1.0, "b--", "pure small"),
                              (0.5, "g--", r"$\varphi^s = 0.5$")):
        a.plot(inertial_number(z, phi) * np.ones_like(z), 1e3 * z, style,
               label=label)
        b.plot(velocity_uniform(z, phi), 1e3 * z, style, label=label)
    for ax, pts in ((a, solver_I), (b, solver_u)):
        if pts is not None:
            ax.plot(np.asarray(pts[1]), 1e3 * np.asarray(pts[0]), "o", ms=3,
                    mfc="none", color="0.3", label="solver")
    a.set_xlabel("$I$")
    a.set_ylim(0.0, 1e3 * h)
    return finish_figure(fig, a, b, "$z$ (mm)", "$u$ (m/s)", "lower right",
                         path)


def finish_figure(fig, a, b, ylabel, xlabel_b, legend_loc, path):
    """Labels, titles (a), (b), legend and the file of a two-panel profile
    figure (figures 7 and 9); returns path."""
    import matplotlib.pyplot as plt
    a.set_ylabel(ylabel)
    b.set_xlabel(xlabel_b)
    a.set_title("(a)")
    b.set_title("(b)")
    b.set_xlim(left=0.0)
    b.legend(loc=legend_loc, fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path

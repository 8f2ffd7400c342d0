"""Steady segregation in Tripathi & Khakhar's (2011) DEM column with the
segregation law of Trewhela, Ancey & Gray (2021), section 6.3 and figure 9:
table 2, the exact concentration (6.9)-(6.11), the nondimensional Bagnold
profile (6.12), I_zeta (6.13) as corrected in ERRATA item 3, the velocity
ODE (6.14), and the concentration ODE with C != 0 solved numerically.

Everything is nondimensional with the scalings (6.7a-d): zhat = z/d^s,
hhat = h/d^s, uhat = u/sqrt(g d^s); the base is zhat = 0, the free surface
zhat = hhat.

Derivation of the concentration ODE (used by dphi_dzhat).  At steady state
with u = u(z) e_x and phi^s = phi(z), (2.19) reduces to
d/dz[f_sl phi^s phi^l (g/|g|).e_z] = d/dz[D_sl dphi^s/dz], and
(g/|g|).e_z = -cos zeta, so one integration with the no-flux condition
(2.17) at the base or surface gives
    D_sl dphi^s/dz = -f_sl cos zeta phi^s phi^l.
With (6.8a,b) the factor 2 ||D|| dbar^2 cancels:
    A dphi^s/dz = -B rho_* g cos zeta (R - 1)(1 + E phi^l (R - 1))
                   phi^s phi^l / (C rho_* g dbar + p).
Here g in (6.8a) is taken as the magnitude |g| (an assumption: the paper
does not say; it is the choice for which, with C = 0, rho_*, g and zeta
cancel as the paper states for (6.9); with g cos zeta in (6.8a) a factor
cos zeta would remain in (6.9)).  With the lithostatic pressure (5.3),
p = rho_* Phi g cos zeta (h - z), dividing by rho_* g d^s and writing
dbar = d^s (phi^s + R phi^l) = d^s dbarhat:
    dphi/dzhat = -B (R - 1) phi^s phi^l (1 + E phi^l (R - 1))
                 / (A [C dbarhat/cos zeta + Phi (hhat - zhat)]),
which for C = 0 is (6.9).
"""
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq
from scipy.special import expit

from .rheology import _result
from .stratified import finish_figure, integrate_from_base


@dataclass(frozen=True)
class Table2:
    """Table 2: nondimensional constants of the diffusion (3.7) and
    segregation (3.9) laws of Trewhela et al. (2021)."""
    A: float = 0.108
    B: float = 0.3744
    C: float = 0.2712
    E: float = 2.0957


TABLE2 = Table2()


@dataclass(frozen=True)
class DEMColumn:
    """Tripathi & Khakhar's (2011) column of section 6.3: slope zeta
    (radians), size ratio R = d^l/d^s, depth hhat = h/d^s, the friction
    mus, mud and I0 of the paper's fit (figure 9 caption) and the solids
    volume fraction Phi."""
    zeta: float = math.radians(25.0)
    R: float = 1.5
    hhat: float = 30.0
    mus: float = math.tan(math.radians(20.16))
    mud: float = math.tan(math.radians(37.65))
    I0: float = 0.5106
    Phi: float = 0.6


DEM = DEMColumn()


def lambdas(p=DEM, t=TABLE2):
    """Exponents (6.11a-c):
    lambda1 = Phi A/(B (R - 1)), lambda2 = Phi A E/(B (1 + E (R - 1))),
    lambda3 = Phi A/(B (R - 1)(1 + E (R - 1)))."""
    r1 = p.R - 1.0
    return (p.Phi * t.A / (t.B * r1),
            p.Phi * t.A * t.E / (t.B * (1.0 + t.E * r1)),
            p.Phi * t.A / (t.B * r1 * (1.0 + t.E * r1)))


def _log_G(phi, p, t):
    """log G(phi) with G = (1 - phi)^{-l1} (1 + E (1 - phi)(R - 1))^{l2}
    phi^{l3}, so that (6.10) reads hhat - zhat = K G(phi)."""
    l1, l2, l3 = lambdas(p, t)
    return (-l1 * math.log1p(-phi) + l2 * math.log1p(t.E * (1.0 - phi)
                                                      * (p.R - 1.0))
            + l3 * math.log(phi))


def _softplus(x):
    return x + math.log1p(math.exp(-x)) if x > 0.0 else \
        math.log1p(math.exp(x))


def _log_G_logit(s, p, t):
    """log G at phi = expit(s), without cancellation near phi = 0 or 1."""
    l1, l2, l3 = lambdas(p, t)
    return (l1 * _softplus(s) + l2 * math.log1p(t.E * (p.R - 1.0)
                                                * float(expit(-s)))
            - l3 * _softplus(-s))


def zhat(phi_s, K, p=DEM, t=TABLE2):
    """Exact solution (6.10) of (6.9), as height for a concentration:
    zhat = hhat - K (1 - phi)^{-l1} (1 + E (1 - phi)(R - 1))^{l2} phi^{l3},
    lambdas from (6.11), 0 < phi < 1, K > 0.  G increases from 0 (phi = 0)
    to infinity (phi -> 1), so phi^s is 0 at the surface zhat = hhat and
    increases downward (dphi/dzhat < 0, the sign of (6.9))."""
    phi = np.asarray(phi_s, dtype=float)
    if np.any(phi <= 0.0) or np.any(phi >= 1.0) or K <= 0.0:
        raise ValueError("(6.10) needs 0 < phi < 1 and K > 0")
    l1, l2, l3 = lambdas(p, t)
    return _result(p.hhat - K * (1.0 - phi) ** (-l1)
                   * (1.0 + t.E * (1.0 - phi) * (p.R - 1.0)) ** l2
                   * phi ** l3)


def _phi_point(zh, logK, p, t):
    """Inverse of (6.10) at one height: brentq on s = logit(phi), where
    log G is increasing from -inf to +inf (bracket widened as needed)."""
    if zh < 0.0 or zh > p.hhat:
        raise ValueError("(6.10) holds for 0 <= zhat <= hhat only")
    if zh == p.hhat:
        return 0.0
    target = math.log(p.hhat - zh) - logK

    def f(s):
        return _log_G_logit(s, p, t) - target

    lo, hi = -1.0, 1.0
    while f(lo) > 0.0:
        lo *= 2.0
    while f(hi) < 0.0:
        hi *= 2.0
    s = brentq(f, lo, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps,
               maxiter=500)
    return float(expit(s))


def phi_s(zhat_, K, p=DEM, t=TABLE2):
    """Small-particle concentration of Trewhela et al.'s solution (6.10),
    inverted for phi^s at the heights zhat in [0, hhat] by brentq per point
    (in logit(phi)); phi^s(hhat) = 0, decreasing in zhat, and defined on all
    of [0, hhat] for every K > 0 (the base value phi^s(0) < 1 solves
    K G(phi) = hhat)."""
    if K <= 0.0:
        raise ValueError("K must be positive")
    logK = math.log(K)
    z = np.asarray(zhat_, dtype=float)
    out = np.array([_phi_point(float(v), logK, p, t) for v in z.ravel()])
    return _result(out.reshape(z.shape))


def _mean_from_base(phi0, logG0, p, t):
    """Depth average (5.10) of (6.10) over [0, hhat] from the base value
    phi0 = phi^s(0), G(phi0) = exp(logG0) = hhat/K: integrating by parts in
    phi, (1/hhat) int phi dzhat = phi0 - int_0^phi0 G(phi) dphi / G(phi0).
    The integral is split at phi0/2 and the end-point factors phi^{l3} and
    (1 - phi)^{-l1} are removed by the substitutions u = phi^{1 + l3} and
    (for phi0 > 1/2 and l1 < 1) v = (1 - phi)^{1 - l1}, leaving smooth
    integrands for quad."""
    l1, l2, l3 = lambdas(p, t)
    a = t.E * (p.R - 1.0)
    m = 0.5 * phi0

    def lower(u):           # phi^{l3} dphi = du/(1 + l3)
        phi = u ** (1.0 / (1.0 + l3))
        return (1.0 - phi) ** (-l1) * (1.0 + a * (1.0 - phi)) ** l2 \
            / (1.0 + l3)

    def upper(v):           # (1 - phi)^{-l1} dphi = -dv/(1 - l1)
        w = v ** (1.0 / (1.0 - l1))
        return (1.0 - w) ** l3 * (1.0 + a * w) ** l2 / (1.0 - l1)

    # the result phi0 - integral/G(phi0) is wanted to ~1e-14 phi0
    kw = dict(epsabs=1e-15 * phi0 * math.exp(logG0), epsrel=1e-13,
              limit=200)
    integral = quad(lower, 0.0, m ** (1.0 + l3), **kw)[0]
    if l1 < 1.0 and phi0 > 0.5:
        integral += quad(upper, (1.0 - phi0) ** (1.0 - l1),
                         (1.0 - m) ** (1.0 - l1), **kw)[0]
    else:
        integral += quad(lambda phi: math.exp(_log_G(phi, p, t)), m, phi0,
                         **kw)[0]
    return phi0 - integral * math.exp(-logG0)


def depth_average(K, p=DEM, t=TABLE2):
    """Depth average (5.10) of phi^s from (6.10) for the constant K > 0,
    (1/hhat) int_0^hhat phi^s dzhat (see _mean_from_base)."""
    phi0 = _phi_point(0.0, math.log(K), p, t)
    return _mean_from_base(phi0, math.log(p.hhat / K), p, t)


# logit of the base value: phi0 = expit(S_MAX) is the largest float below 1
# that keeps 1 - phi0 resolved; it bounds phibar at about 1 - 4e-6.
S_MIN, S_MAX = -40.0, 36.0


def K_from_phibar(phibar, p=DEM, t=TABLE2):
    """Integration constant K of (6.10) for the depth-averaged concentration
    phibar in (0, 1).  Mapping: K = hhat/G(phi0) with the base value
    phi0 = phi^s(0) in (0, 1); K in (0, inf) <-> phi0 in (1, 0) <->
    phibar in (1, 0), all monotone, and every K > 0 gives a profile on all
    of [0, hhat] (phi0 < 1 always, phi^s(hhat) = 0).  brentq in
    s0 = logit(phi0) on [S_MIN, S_MAX]; phibar very close to 0 or 1
    (beyond about 1e-18 and 1 - 4e-6) is refused: use the pure phases."""
    if not 0.0 < phibar < 1.0:
        raise ValueError("phibar must lie in (0, 1); 0 and 1 are uniform")

    def excess(s0):
        return _mean_from_base(float(expit(s0)), _log_G_logit(s0, p, t),
                               p, t) - phibar

    if excess(S_MIN) > 0.0 or excess(S_MAX) < 0.0:
        raise ValueError(f"phibar = {phibar} too close to 0 or 1")
    s0 = brentq(excess, S_MIN, S_MAX, xtol=1e-14,
                rtol=4 * np.finfo(float).eps, maxiter=500)
    return p.hhat * math.exp(-_log_G_logit(s0, p, t))


def dphi_dzhat(zhat_, phi, p=DEM, t=TABLE2, C=0.0):
    """Steady concentration ODE (see the module docstring):
    dphi/dzhat = -B (R - 1) phi phil (1 + E phil (R - 1))
                 / (A [C dbarhat/cos zeta + Phi (hhat - zhat)]),
    phil = 1 - phi, dbarhat = phi + R phil.  C = 0 (the default) is (6.9);
    C = t.C is the full law (6.8a)."""
    phil = 1.0 - phi
    den = t.A * (C * (phi + p.R * phil) / math.cos(p.zeta)
                 + p.Phi * (p.hhat - zhat_))
    return -t.B * (p.R - 1.0) * phi * phil * (1.0 + t.E * phil
                                               * (p.R - 1.0)) / den


def phi_s_numeric(phibar, C=TABLE2.C, p=DEM, t=TABLE2, rtol=1e-11):
    """Steady concentration for the segregation law (6.8a) with C >= 0:
    the ODE dphi_dzhat integrated by solve_ivp (DOP853) from the base with
    the shooting value phi0 = phi^s(0) found by brentq (in logit(phi0)) so
    that the depth average over [0, hhat] is phibar in (0, 1).  For C = 0
    the ODE is singular at the surface (phi -> 0 there like
    (hhat - zhat)^{1/lambda3}); it is then integrated to hhat (1 - 1e-12).
    Returns (phi0, phi) with phi(zhat) a callable (dense output, clipped to
    [0, 1])."""
    if not 0.0 < phibar < 1.0:
        raise ValueError("phibar must lie in (0, 1); 0 and 1 are uniform")
    if C < 0.0:
        raise ValueError("C must be >= 0")
    z_end = p.hhat if C > 0.0 else p.hhat * (1.0 - 1e-12)

    def rhs(zz, y):
        return [dphi_dzhat(zz, y[0], p, t, C), y[0]]

    def solve(s0, dense=False):
        sol = solve_ivp(rhs, (0.0, z_end), [float(expit(s0)), 0.0],
                        method="DOP853", rtol=rtol, atol=1e-14,
                        dense_output=dense)
        if not sol.success:
            raise RuntimeError(sol.message)
        return sol

    def excess(s0):
        return solve(s0).y[1, -1] / p.hhat - phibar

    s0 = brentq(excess, S_MIN, S_MAX, xtol=1e-13,
                rtol=4 * np.finfo(float).eps, maxiter=500)
    sol = solve(s0, dense=True)

    def phi(zhat_):
        z = np.asarray(zhat_, dtype=float)
        if np.any(z < 0.0) or np.any(z > p.hhat):
            raise ValueError("phi holds for 0 <= zhat <= hhat only")
        return _result(np.clip(sol.sol(z)[0], 0.0, 1.0))

    return float(expit(s0)), phi


def concentration(phibar, C=0.0, p=DEM, t=TABLE2):
    """phi^s(zhat) as a callable for phibar in [0, 1]: the constants 0 and
    1 for the pure phases, else (6.10) with K_from_phibar (C = 0) or
    phi_s_numeric (C > 0)."""
    if phibar in (0.0, 1.0):
        return lambda zhat_: _result(np.full(np.shape(zhat_), phibar))
    if C == 0.0:
        K = K_from_phibar(phibar, p, t)
        return lambda zhat_: phi_s(zhat_, K, p, t)
    return phi_s_numeric(phibar, C, p, t)[1]


def I_zeta(p=DEM):
    """Equation (6.13) with the denominator of ERRATA item 3:
    I_zeta = I0 (tan zeta - mus)/(mud - tan zeta), the inverse of the Jop
    law (2.7) at tan zeta."""
    tz = math.tan(p.zeta)
    return p.I0 * (tz - p.mus) / (p.mud - tz)


def _check_depth(zhat_, p):
    z = np.asarray(zhat_, dtype=float)
    if np.any(z < 0.0) or np.any(z > p.hhat):
        raise ValueError("the solution holds for 0 <= zhat <= hhat only")
    return z


def u_bagnold_hat(zhat_, p=DEM):
    """Nondimensional Bagnold profile (6.12):
    uhat = 2/3 I_zeta sqrt(Phi cos zeta) (hhat^{3/2} - (hhat - zhat)^{3/2}),
    I_zeta from (6.13) (ERRATA item 3)."""
    z = _check_depth(zhat_, p)
    return _result(2.0 / 3.0 * I_zeta(p) * math.sqrt(p.Phi
                                                     * math.cos(p.zeta))
                   * (p.hhat ** 1.5 - (p.hhat - z) ** 1.5))


def velocity_hat(zhat_, phi, p=DEM, rtol=1e-11):
    """Velocity ODE (6.14),
    duhat/dzhat = I_zeta sqrt(Phi cos zeta) (hhat - zhat)^{1/2}
                  / (phi^s + R phi^l),
    no slip uhat(0) = 0, integrated by solve_ivp (DOP853) to the heights
    zhat (any order).  phi is a callable phi^s(zhat) (e.g. concentration())
    or a constant; phi^s = 1 gives (6.12), phi^s = 0 gives (6.12)/R."""
    def dbarhat(zz):
        v = float(phi(zz)) if callable(phi) else float(phi)
        return v + p.R * (1.0 - v)

    return velocity_hat_dbar(zhat_, dbarhat, p, rtol)


def velocity_hat_dbar(zhat_, dbarhat, p=DEM, rtol=1e-11):
    """(6.14) for any number of grain sizes:
    duhat/dzhat = I_zeta sqrt(Phi cos zeta) (hhat - zhat)^{1/2}/dbarhat,
    with dbarhat(zhat) = dbar/d^s of (3.1), sum_nu phi^nu d^nu/d^s (the
    generalised inertial number (3.2) at the constant I_zeta of (6.13)),
    no slip uhat(0) = 0, by solve_ivp (DOP853) to the heights zhat."""
    z = _check_depth(zhat_, p)
    scale = I_zeta(p) * math.sqrt(p.Phi * math.cos(p.zeta))

    def rhs(zz, u):
        return [scale * math.sqrt(max(p.hhat - zz, 0.0)) / dbarhat(zz)]

    return integrate_from_base(rhs, z, rtol, atol=1e-14)


PHIBARS = (0.0, 0.3, 0.5, 0.7, 1.0)   # the five cases of figure 9


def figure9(path, phibars=PHIBARS, C=0.0, solver_phi=None, solver_u=None,
            n=200):
    """Draw figure 9 into path (matplotlib, Agg) without the DEM data:
    (a) phi^s(zhat) and (b) uhat(zhat) for each phibar (lines; (6.10) for
    C = 0, phi_s_numeric for C > 0; velocity (6.14)).  solver_phi,
    solver_u: optional dicts phibar -> (zhat, values) drawn as markers in
    the colour of that phibar."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = DEM
    z = np.linspace(0.0, p.hhat, n)
    fig, (a, b) = plt.subplots(1, 2, figsize=(8, 4), sharey=True)
    colours = plt.cm.plasma(np.linspace(0.0, 0.85, len(phibars)))
    for phibar, col in zip(phibars, colours):
        phi = concentration(phibar, C, p)
        label = rf"$\bar\varphi^s = {100 * phibar:.0f}\%$"
        a.plot(phi(z), z, "-", color=col, label=label)
        b.plot(velocity_hat(z, phi, p), z, "-", color=col, label=label)
        for ax, pts in ((a, solver_phi), (b, solver_u)):
            if pts is not None and phibar in pts:
                ax.plot(np.asarray(pts[phibar][1]),
                        np.asarray(pts[phibar][0]), "o", ms=3, mfc="none",
                        color=col)
    a.set_xlabel(r"$\varphi^s$")
    a.set_xlim(-0.02, 1.02)     # the pure phases lie on 0 and 1
    a.set_ylim(0.0, p.hhat)
    return finish_figure(fig, a, b, r"$\hat z$", r"$\hat u$", "upper left",
                         path)

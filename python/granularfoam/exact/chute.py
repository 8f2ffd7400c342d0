"""Chute flow of section 5: depth-averaged Bagnold flow, the steadily
travelling front of section 5.6 and Gray & Thornton's (2005) concentration
shocks of appendix A."""
import math

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from .bagnold import ZETA, inertial_number_zeta, velocity
from .rheology import TABLE1, _result, mu_high

# The front ODE (5.17) reaches h_inf only as xi -> -infinity: near h_inf,
# h_inf - h ~ exp(xi/L) with L = [(chi - 1) Fr^2 + 1]/|dmu/dh(h_inf)|
# (about 12 h_inf for table 1 at 24 deg), so every further factor 10 in
# 1 - h/h_inf only appends a uniform stretch L ln 10 upstream.  front_shape
# stops at H_TOP h_inf, where the thickness is within 0.1 % of h_inf.
H_TOP = 0.999


def _bagnold_scale(zeta, d, p):
    """The factor I_zeta/d sqrt(Phi g cos zeta) common to (5.4), (5.16) and
    (A4); I_zeta from (5.6), d defaults to p.d."""
    d = p.d if d is None else d
    return inertial_number_zeta(zeta, p) / d \
        * math.sqrt(p.Phi * p.g * math.cos(zeta))


def depth_averaged_velocity(h, zeta, d=None, p=TABLE1):
    """Depth average (5.14a) of the Bagnold profile (5.4), equations (5.16)
    and (5.19) with I = I_zeta: ubar = 2 I_zeta/(5 d) sqrt(Phi g cos zeta)
    h^{3/2}."""
    h = np.asarray(h, dtype=float)
    return _result(0.4 * _bagnold_scale(zeta, d, p) * h ** 1.5)


def froude(h, zeta, d=None, p=TABLE1):
    """Froude number (5.18) of Bagnold flow of depth h:
    Fr = ubar/sqrt(g h cos zeta) with ubar from (5.16)."""
    h = np.asarray(h, dtype=float)
    return _result(depth_averaged_velocity(h, zeta, d, p)
                   / np.sqrt(p.g * h * math.cos(zeta)))


def shape_factor_bagnold(h=5e-3, zeta=ZETA, d=None, p=TABLE1):
    """Shape factor chi = mean(u^2)/mean(u)^2 (5.14) of the Bagnold profile
    (5.4), by quad; 5/4 for any h, zeta and d (section 5.6)."""
    def mean(g):
        return quad(g, 0.0, h, epsabs=0.0, epsrel=1e-13)[0] / h

    def u(z):
        return velocity(z, h, zeta, d, p)

    return mean(lambda z: u(z) ** 2) / mean(u) ** 2


def basal_friction(h, h_inf, zeta, p=TABLE1):
    """Regularised depth-averaged basal friction (5.21): the high-I branch
    of (2.8) evaluated at I = I_zeta (h_inf/h)^{3/2}, equation (5.20).
    Valid while I > I1, i.e. for h < h_inf (I_zeta/I1)^{2/3}."""
    h = np.asarray(h, dtype=float)
    return mu_high(inertial_number_zeta(zeta, p) * (h_inf / h) ** 1.5, p)


def front_slope(h, h_inf, zeta, chi, p=TABLE1):
    """dh/dxi of the travelling-front ODE (5.17),
    [(chi - 1) Fr_inf^2 h_inf/h + 1] dh/dxi = tan zeta - mu(h),
    with Fr_inf from (5.18) (d = p.d) and mu from (5.21)."""
    h = np.asarray(h, dtype=float)
    fr2 = froude(h_inf, zeta, p=p) ** 2
    return _result((math.tan(zeta) - basal_friction(h, h_inf, zeta, p))
                   / ((chi - 1.0) * fr2 * h_inf / h + 1.0))


def front_shape(h_inf, zeta, chi, p=TABLE1, n=400, h_top=H_TOP):
    """Steadily travelling front of section 5.6: the ODE (5.17) with the
    friction (5.21), integrated as xi(h) = int_0^h dh'/(dh/dxi) by
    solve_ivp from the front (h = 0, xi = 0) up to h = h_top h_inf (see
    H_TOP).  The integrand vanishes at h = 0 (friction ~ h^{-3/2}), so the
    front pins: -xi ~ h^{5/2} (chi = 1) or h^{3/2} (chi > 1) there.
    Returns arrays (xi, h) of n points ordered from upstream
    (xi < 0, h = h_top h_inf) to the front (xi = 0, h = 0); the h samples
    are uniform near the front and logarithmic in h_inf - h upstream."""
    def dxi_dh(h, xi):
        return [0.0 if h <= 0.0 else 1.0 / front_slope(h, h_inf, zeta,
                                                       chi, p)]

    t = np.linspace(0.0, 1.0, n)
    h = h_inf * (1.0 - (1.0 - h_top) ** t)
    sol = solve_ivp(dxi_dh, (0.0, h[-1]), [0.0], method="DOP853",
                    t_eval=h, rtol=1e-11, atol=1e-14 * h_inf)
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol.y[0][::-1], h[::-1]


def streamfunction(z, h, zeta, d=None, p=TABLE1):
    """Streamfunction (A4) of the Bagnold profile (5.4),
    psi(z) = int_0^z u dz' = 2 I_zeta sqrt(Phi g cos zeta)/(15 d)
             (2 (h - z)^{5/2} - 2 h^{5/2} + 5 h^{3/2} z), 0 <= z <= h."""
    z = np.asarray(z, dtype=float)
    if np.any(z < 0.0) or np.any(z > h):
        raise ValueError("(A4) holds for 0 <= z <= h only")
    return _result(2.0 * _bagnold_scale(zeta, d, p) / 15.0
                   * (2.0 * (h - z) ** 2.5 - 2.0 * h ** 2.5
                      + 5.0 * h ** 1.5 * z))


def shock_meeting_point(h, zeta, f, d=None, p=TABLE1):
    """Downstream position x = psi(h)/(f cos zeta) where the lower and upper
    shocks (A1), (A2) meet the final shock (A3)."""
    return streamfunction(h, h, zeta, d, p) / (f * math.cos(zeta))


def shock_lines(x, h, zeta, f, phi0, d=None, p=TABLE1):
    """Heights z of Gray & Thornton's (2005) shocks, appendix A, at the
    downstream positions x >= 0: returns (z_lower, z_upper, z_final) with
    psi_lower = f phi0 x cos zeta (A1) and
    psi_upper = psi(h) - f (1 - phi0) x cos zeta (A2) for x <= x_meet,
    psi_final = phi0 psi(h) (A3) for x >= x_meet, x_meet from
    shock_meeting_point (all three coincide there); NaN where a shock does
    not exist.  psi is mapped
    back to z by inverting (A4) with brentq on [0, h]."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    if np.any(x < 0.0) or not 0.0 < phi0 < 1.0:
        raise ValueError("need x >= 0 and 0 < phi0 < 1")
    psi_h = streamfunction(h, h, zeta, d, p)
    x_meet = shock_meeting_point(h, zeta, f, d, p)
    fc = f * math.cos(zeta)
    before = x <= x_meet
    psis = (np.where(before, phi0 * fc * x, np.nan),
            np.where(before, psi_h - (1.0 - phi0) * fc * x, np.nan),
            np.where(x >= x_meet, phi0 * psi_h, np.nan))

    def height(psi):
        if np.isnan(psi):
            return np.nan
        return brentq(lambda z: streamfunction(z, h, zeta, d, p) - psi,
                      0.0, h, xtol=1e-15 * h, rtol=4 * np.finfo(float).eps)

    return tuple(np.array([height(s) for s in psi]) for psi in psis)

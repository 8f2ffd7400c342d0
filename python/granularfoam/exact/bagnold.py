"""Steady uniform Bagnold flow down an inclined plane, section 5.2, and the
air inflow profile above it (ERRATA item 4)."""
import math

import numpy as np
from scipy.optimize import brentq

from .rheology import TABLE1, _result, mu_barker_gray

ZETA = math.radians(24.0)  # slope angle of sections 5 and 6


def inertial_number_zeta(zeta, p=TABLE1):
    """Closed form (5.6) of I_zeta = mu^{-1}(tan zeta) (5.5) for the
    partially regularised law (2.8): valid for muInf > 0 and I_zeta > I1,
    a ValueError otherwise (use inertial_number_zeta_root)."""
    if p.muInf <= 0.0:
        raise ValueError("(5.6) needs muInf > 0")
    t = math.tan(zeta)
    I = (t - p.mud + math.sqrt((p.mud - t) ** 2
                               + 4.0 * (t - p.mus) * p.muInf * p.I0)) \
        / (2.0 * p.muInf)
    if not I > p.I1:
        raise ValueError(f"(5.6) gives I = {I} <= I1 = {p.I1}: tan zeta "
                         "lies on the creep branch of (2.8)")
    return I


def inertial_number_zeta_root(zeta, p=TABLE1, law=mu_barker_gray):
    """I_zeta = mu^{-1}(tan zeta), equation (5.5), by scipy brentq for any
    increasing friction law law(I, p), e.g. (2.7) or (2.8)."""
    t = math.tan(zeta)

    def f(I):
        return law(I, p) - t

    if f(0.0) > 0.0:
        raise ValueError("tan zeta is below mu(0): no steady flow")
    hi = 1.0
    while f(hi) <= 0.0:
        hi *= 2.0
        if hi > 1e12:
            raise ValueError("tan zeta is not reached by the friction law")
    return brentq(f, 0.0, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps,
                  maxiter=500)


def pressure(z, h, zeta, p=TABLE1):
    """Lithostatic pressure (5.3): p = rhoStar Phi g (h - z) cos zeta for
    z <= h, zero above the free surface z = h."""
    z = np.asarray(z, dtype=float)
    return _result(p.rhoStar * p.Phi * p.g * np.clip(h - z, 0.0, None)
                   * math.cos(zeta))


def velocity(z, h, zeta, d=None, p=TABLE1):
    """Bagnold velocity profile (5.4) for 0 <= z <= h:
    u = 2 I_zeta/(3 d) sqrt(Phi g cos zeta) (h^{3/2} - (h - z)^{3/2}),
    I_zeta from (5.6); d defaults to p.d."""
    z = np.asarray(z, dtype=float)
    if np.any(z < 0.0) or np.any(z > h):
        raise ValueError("(5.4) holds for 0 <= z <= h only")
    d = p.d if d is None else d
    return _result(2.0 * inertial_number_zeta(zeta, p) / (3.0 * d)
                   * math.sqrt(p.Phi * p.g * math.cos(zeta))
                   * (h ** 1.5 - (h - z) ** 1.5))


def air_velocity(z, h, Lz, zeta, d=None, p=TABLE1):
    """Air inflow profile, equation (5.7) as corrected in ERRATA item 4,
    for h <= z <= Lz:
    u_p = rho_a g sin zeta/(2 eta_a) (2 Lz (z - h) + h^2 - z^2) + u_B(h),
    the solution of eta_a u'' = -rho_a g sin zeta with u'(Lz) = 0 and
    u(h) = u_Bagnold(h) (5.4)."""
    z = np.asarray(z, dtype=float)
    if np.any(z < h) or np.any(z > Lz):
        raise ValueError("(5.7) holds for h <= z <= Lz only")
    c = p.rho_air * p.g * math.sin(zeta) / (2.0 * p.eta_air)
    return _result(c * (2.0 * Lz * (z - h) + h ** 2 - z ** 2)
                   + velocity(h, h, zeta, d, p))

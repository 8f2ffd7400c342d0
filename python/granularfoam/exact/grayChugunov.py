"""Gray & Chugunov (2006) steady segregation-diffusion solution, section 5.5,
with the segregation parameters of table 3."""
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import expit


@dataclass(frozen=True)
class Table3:
    """Table 3: segregation velocity magnitudes (m/s), diffusivities
    (m^2/s) and inflow thickness h (m)."""
    f_sl: float = 7e-3
    f_al: float = 0.1
    f_as: float = 0.1
    D_sl: float = 1e-6
    D_al: float = 0.0
    D_as: float = 0.0
    h: float = 5e-3


TABLE3 = Table3()


def peclet(f, h, D, zeta):
    """Segregation Peclet number, equation (5.9): Pe = f h cos zeta / D."""
    return f * h * math.cos(zeta) / D


def log_A_GC(Pe, phibar):
    """log of A_GC, equation (5.11), in a form that neither overflows nor
    cancels: log A = -Pe phibar + log(1 - e^{-Pe(1 - phibar)})
                     - log(1 - e^{-Pe phibar})."""
    phibar = np.asarray(phibar, dtype=float)
    with np.errstate(divide="ignore"):
        return (-Pe * phibar + np.log1p(-np.exp(-Pe * (1.0 - phibar)))
                - np.log(-np.expm1(-Pe * phibar)))


def A_GC(Pe, phibar):
    """Constant A_GC of equation (5.11):
    A = (e^{-Pe phibar} - e^{-Pe})/(1 - e^{-Pe phibar})."""
    return float(np.exp(log_A_GC(Pe, phibar)))


def phi_s(zhat, Pe, phibar):
    """Small-particle concentration, equation (5.8):
    phi_s = 1/(1 + A_GC exp(Pe zhat)), zhat = z/h in [0, 1], A_GC from
    (5.11) so that the depth average (5.10) is phibar."""
    zhat = np.asarray(zhat, dtype=float)
    phi = expit(-(log_A_GC(Pe, phibar) + Pe * zhat))
    return float(phi) if np.ndim(phi) == 0 else phi


def _transition(Pe, phibar):
    """zhat where phi_s = 1/2, as a quad break point (empty if outside)."""
    z = -float(log_A_GC(Pe, phibar)) / Pe
    return [z] if 0.0 < z < 1.0 else []


def depth_average(Pe, phibar):
    """Depth average (5.10) of phi_s (5.8) over zhat in [0, 1] by quad
    (equals phibar: the check of (5.11))."""
    return quad(phi_s, 0.0, 1.0, args=(Pe, phibar), epsabs=0.0,
                epsrel=1e-13, limit=200, points=_transition(Pe, phibar))[0]


def downstream_mean(phi0, u_profile, Pe):
    """Downstream depth average phibar of (5.10) at steady state (section
    5.5): the small-particle flux of (5.8) with A_GC (5.11) equals that of
    the uniform inflow phi0, int_0^1 phi_s u dzhat = phi0 int_0^1 u dzhat,
    solved for phibar by brentq. u_profile(zhat) is the downslope velocity
    as a function of zhat = z/h (its scale cancels), e.g. Bagnold (5.4)."""
    if not 0.0 < phi0 < 1.0:
        raise ValueError("phi0 must lie in (0, 1)")
    flux_in = phi0 * quad(u_profile, 0.0, 1.0, epsabs=0.0, epsrel=1e-13,
                          limit=200)[0]

    def excess(phibar):
        flux = quad(lambda zh: phi_s(zh, Pe, phibar) * u_profile(zh),
                    0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200,
                    points=_transition(Pe, phibar))[0]
        return flux - flux_in

    eps = 1e-12
    return brentq(excess, eps, 1.0 - eps, xtol=1e-14,
                  rtol=4 * np.finfo(float).eps)

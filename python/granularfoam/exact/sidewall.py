"""Steady uniform flow of a layer down a slope between two flat sidewalls a
gap W apart (Jop, Forterre & Pouliquen 2005, J. Fluid Mech. 541): the exact
solution that verifies the fvOption granularSidewallFriction.

With the wall friction per unit volume f_w = -2 mu_w p/W u/|u| (JFP), p the
lithostatic pressure (5.3), p = rho g cos(zeta) (h - z) with rho = Phi
rhoStar, and a stress-free surface z = h, the downslope momentum balance
d tau/dz + rho g sin(zeta) - 2 mu_w p/W = 0 integrates from h to z to

    tau(z) = rho g sin(zeta) (h - z) - mu_w rho g cos(zeta) (h - z)^2/W,

so that the friction tau/p that the mu(I) law must supply is

    mu(z) = tan(zeta) - mu_w (h - z)/W.                            (SW1)

Its inverse gives I(z) (any increasing law: (2.7) or (2.8)), and the
inertial number (3.2) for simple shear, I = |du/dz| d/sqrt(p/rhoStar),
gives the velocity with no slip at the base:

    u(z) = int_0^z I(z')/d sqrt(Phi g cos(zeta) (h - z')) dz'.      (SW2)

With mu_w = 0 it is Bagnold's profile (5.4).
"""
import math

import numpy as np
from scipy.integrate import quad

from .bagnold import inertial_number_zeta_root
from .rheology import TABLE1, _result, mu_barker_gray


def friction(z, h, zeta, muW, W):
    """(SW1): mu(z) = tan(zeta) - mu_w (h - z)/W for 0 <= z <= h."""
    z = np.asarray(z, dtype=float)
    if np.any(z < 0.0) or np.any(z > h):
        raise ValueError("(SW1) holds for 0 <= z <= h only")
    return _result(math.tan(zeta) - muW * (h - z) / W)


def inertial_number(z, h, zeta, muW, W, p=TABLE1, law=mu_barker_gray):
    """I(z) = mu^{-1}(mu(z)) of (SW1) by brentq (the inversion of (5.5)
    at the local friction); a ValueError where mu(z) is below mu_s, where
    the layer would not flow on the law's dynamic branch."""
    mu = np.atleast_1d(friction(z, h, zeta, muW, W))
    if np.any(mu <= p.mus):
        raise ValueError(f"mu = {mu.min():.4f} <= mu_s = {p.mus} at the "
                         "base: the whole layer does not flow")
    I = np.array([inertial_number_zeta_root(math.atan(m), p, law)
                  for m in mu])
    return _result(I if np.ndim(z) else I[0])


def velocity(z, h, zeta, muW, W, d=None, p=TABLE1, law=mu_barker_gray):
    """u(z) of (SW2), by scipy quad from the base (u(0) = 0)."""
    d = p.d if d is None else d
    c = math.sqrt(p.Phi * p.g * math.cos(zeta)) / d

    def dudz(s):
        return inertial_number(s, h, zeta, muW, W, p, law) * c \
            * math.sqrt(max(h - s, 0.0))

    zs = np.atleast_1d(np.asarray(z, dtype=float))
    if np.any(zs < 0.0) or np.any(zs > h):
        raise ValueError("(SW2) holds for 0 <= z <= h only")
    u = np.array([quad(dudz, 0.0, zi, epsabs=0.0, epsrel=1e-12,
                       limit=200)[0] for zi in zs])
    return _result(u if np.ndim(z) else u[0])

"""Unit tier: the exact solution of a layer between sidewalls
(python/granularfoam/exact/sidewall.py, (SW1)-(SW2))."""
import math

import numpy as np
import pytest

from granularfoam.exact import bagnold, rheology, sidewall

pytestmark = pytest.mark.unit

P = rheology.TABLE1
ZETA = bagnold.ZETA
H = 5e-3


def test_no_wall_friction_is_bagnold():
    """mu_w = 0 gives Bagnold's profile (5.4)."""
    z = np.linspace(0.0, H, 11)
    u = bagnold.velocity(z, H, ZETA)
    assert np.allclose(sidewall.velocity(z, H, ZETA, 0.0, 0.03), u,
                       rtol=1e-12, atol=1e-12 * u.max())


def test_momentum_balance():
    """u of (SW2) satisfies d tau/dz + rho g sin(zeta) - 2 mu_w p/W = 0
    with tau = mu(I) p, I = u' d/sqrt(p/rhoStar) (3.2) and p of (5.3),
    by central differences, and u(0) = 0."""
    muW, W, dz = 0.25, 0.03, 1e-6
    z = np.linspace(0.1 * H, 0.9 * H, 9)
    rho = P.Phi * P.rhoStar

    def tau(s):
        du = (sidewall.velocity(s + dz, H, ZETA, muW, W)
              - sidewall.velocity(s - dz, H, ZETA, muW, W)) / (2 * dz)
        p = bagnold.pressure(s, H, ZETA)
        return rheology.mu_barker_gray(du * P.d / np.sqrt(p / P.rhoStar)) * p

    dtau = (tau(z + 10 * dz) - tau(z - 10 * dz)) / (20 * dz)
    residual = dtau + rho * P.g * math.sin(ZETA) \
        - 2 * muW * bagnold.pressure(z, H, ZETA) / W
    assert np.abs(residual).max() < 1e-4 * rho * P.g * math.sin(ZETA)
    assert sidewall.velocity(0.0, H, ZETA, muW, W) == 0.0


def test_refuses_a_layer_that_does_not_flow():
    """mu(0) <= mu_s (walls too close) is a ValueError, as is z > h."""
    with pytest.raises(ValueError, match="does not flow"):
        sidewall.inertial_number(0.0, H, ZETA, 0.25, 0.01)
    with pytest.raises(ValueError):
        sidewall.friction(2 * H, H, ZETA, 0.25, 0.03)

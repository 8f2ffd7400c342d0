"""Unit tier: the exact solutions of python/granularfoam/exact against the numbers
the paper states (sections 2.1, 5.2, 5.5 and ERRATA)."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from granularfoam.exact import bagnold, errors, grayChugunov, rheology

pytestmark = pytest.mark.unit

ZETA = bagnold.ZETA
P = rheology.TABLE1
T3 = grayChugunov.TABLE3


def bagnold_shape(zhat):
    """Bagnold velocity (5.4) as a function of zhat = z/h, table 3 depth."""
    return bagnold.velocity(zhat * T3.h, T3.h, ZETA)


def pe_table3():
    return grayChugunov.peclet(T3.f_sl, T3.h, T3.D_sl, ZETA)


def test_inertial_number_zeta():
    """(5.6) at 24 deg with table 1: about 0.0620, equal to the brentq
    inverse of (2.8), and mu(I_zeta) = tan 24 deg."""
    I = bagnold.inertial_number_zeta(ZETA)
    assert abs(I - 0.0620) < 5e-4
    assert abs(I - bagnold.inertial_number_zeta_root(ZETA)) < 1e-10
    assert abs(rheology.mu_barker_gray(I) - math.tan(ZETA)) < 1e-12


def test_barker_gray_continuous_at_I1():
    """The two branches of (2.8) meet at I1 with A from (2.9)."""
    assert abs(rheology.mu_creep(P.I1) - rheology.mu_high(P.I1)) < 1e-12
    assert rheology.mu_barker_gray(0.0) == 0.0


def test_peclet_table3():
    """(5.9) with table 3: Pe = 31.97."""
    assert abs(pe_table3() - 31.97) < 0.005


@pytest.mark.parametrize("phibar", [0.1, 0.5, 0.6744, 0.9])
def test_phi_s_depth_average(phibar):
    """(5.8) with A_GC (5.11) integrates to phibar over [0, 1] (5.10)."""
    Pe = pe_table3()
    assert abs(quad(grayChugunov.phi_s, 0.0, 1.0, args=(Pe, phibar),
                    epsabs=0.0, epsrel=1e-13, limit=200)[0]
               - phibar) < 1e-10


def test_downstream_mean_bagnold():
    """Inflow phi0 = 0.5 through the Bagnold profile: phibar = 0.6744."""
    m = grayChugunov.downstream_mean(0.5, bagnold_shape, pe_table3())
    assert abs(m - 0.6744) < 1e-4


def test_air_profile_ode_and_bcs():
    """ERRATA item 4: eta_a u'' = -rho_a g sin zeta on (h, Lz),
    u'(Lz) = 0, u(h) = u_Bagnold(h) (finite differences)."""
    h, Lz, dz = T3.h, 2 * T3.h, 1e-5
    z = np.linspace(h + dz, Lz - dz, 50)
    u = bagnold.air_velocity
    d2 = (u(z + dz, h, Lz, ZETA) - 2 * u(z, h, Lz, ZETA)
          + u(z - dz, h, Lz, ZETA)) / dz ** 2
    rhs = -P.rho_air * P.g * math.sin(ZETA) / P.eta_air
    assert np.allclose(d2, rhs, rtol=1e-5, atol=0.0)
    # second-order one-sided difference at the top
    du_top = (3 * u(Lz, h, Lz, ZETA) - 4 * u(Lz - dz, h, Lz, ZETA)
              + u(Lz - 2 * dz, h, Lz, ZETA)) / (2 * dz)
    assert abs(du_top) < 1e-6 * abs(rhs) * (Lz - h)
    assert u(h, h, Lz, ZETA) == bagnold.velocity(h, h, ZETA)


def test_l2_relative_and_read_raw(tmp_path):
    """The error helper and the sampled-set reader."""
    f = tmp_path / "line_U.xy"
    f.write_text("# z Ux\n0 0\n0.5 1\n1 2 \n")
    data = errors.read_raw(f)
    assert data.shape == (3, 2)
    assert errors.l2_relative(data[:, 1], data[:, 1]) == 0.0
    assert errors.l2_relative([0.0, 3.0], [0.0, 4.0]) == pytest.approx(0.25)

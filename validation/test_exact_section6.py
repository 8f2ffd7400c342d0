"""Unit tier: the exact solutions of section 6 (python/granularfoam/exact/stratified.py
for section 6.1 and figure 7, python/granularfoam/exact/trewhela.py for section 6.3
and figure 9) against hand-derived numbers and independent computations."""
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from granularfoam.exact import bagnold, rheology, stratified, trewhela

pytestmark = pytest.mark.unit

F7 = stratified.FIG7
H = F7.h
T24 = math.tan(math.radians(24.0))
DEM = trewhela.DEM
T2 = trewhela.TABLE2

# (6.3) by hand with table 1, mu_s^l = 1.2 x 0.342 = 0.4104, mu_d = 0.557
I_SMALL = 0.069 * (T24 - 0.342) / (0.557 - T24)
I_LARGE = 0.069 * (T24 - 0.4104) / (0.557 - T24)
I_MIX = 0.069 * (T24 - 0.5 * (0.342 + 0.4104)) / (0.557 - T24)


def jop(p):
    return lambda I: rheology.mu_jop(I, p)


# ---------------------------------------------------------------- 6.1


def test_parameters_figure7():
    """Table 1 with mu_s^l = 1.2 mu_s and mu_inf = 0, 24 deg, table 3."""
    assert stratified.LARGE.mus == pytest.approx(0.4104, abs=1e-15)
    assert stratified.SMALL.mus == 0.342
    assert stratified.SMALL.muInf == stratified.LARGE.muInf == 0.0
    assert stratified.SMALL.d == stratified.LARGE.d == 0.5e-3
    assert (F7.h, F7.f_sl, F7.D_sl, F7.phibar) == (5e-3, 7e-3, 1e-6, 0.5)
    assert F7.zeta == bagnold.ZETA


@pytest.mark.parametrize("phi, I_hand", [(1.0, I_SMALL), (0.0, I_LARGE),
                                         (0.5, I_MIX)])
def test_uniform_inertial_number_by_hand(phi, I_hand):
    """(6.3) for uniform compositions equals the hand formula."""
    assert stratified.inertial_number(0.3 * H, phi) == \
        pytest.approx(I_hand, rel=1e-14)


def test_uniform_inertial_number_values():
    """The hand values: 0.0637 (small), 0.0215 (large), 0.0426 (mix)."""
    assert abs(I_SMALL - 0.06373) < 1e-5
    assert abs(I_LARGE - 0.02150) < 1e-5
    assert abs(I_MIX - 0.04261) < 1e-5


@pytest.mark.parametrize("phi", [0.0, 0.2, 0.5, 0.9, 1.0])
def test_weighted_friction_root_equals_6_3(phi):
    """brentq on (6.1) with two Jop laws (6.2) equals (6.3), and the
    weighted friction (3.3) at that I is tan zeta."""
    laws = (jop(stratified.SMALL), jop(stratified.LARGE))
    I = stratified.inertial_number_root((phi, 1.0 - phi), laws)
    assert I == pytest.approx(stratified.inertial_number(0.0, phi),
                              rel=1e-12)
    assert phi * laws[0](I) + (1 - phi) * laws[1](I) == \
        pytest.approx(T24, rel=1e-14)


def test_pure_small_is_monodisperse_inverse():
    """Pure small: (6.3) = the inverse of the Jop law (5.5) by bagnold's
    brentq, and the uniform velocity is Bagnold (5.4) with that I."""
    I = bagnold.inertial_number_zeta_root(F7.zeta, stratified.SMALL,
                                          law=rheology.mu_jop)
    assert stratified.inertial_number(0.0, 1.0) == pytest.approx(I,
                                                                 rel=1e-12)
    P = stratified.SMALL
    u_h = 2 * I / (3 * P.d) * math.sqrt(P.Phi * P.g * math.cos(F7.zeta)) \
        * H ** 1.5
    assert stratified.velocity_uniform(H, 1.0) == pytest.approx(u_h,
                                                                rel=1e-12)


def test_weighted_averages_and_mean_diameter():
    """(6.4a,b) and (6.6) as weighted sums, general diameters."""
    small = replace(stratified.SMALL, d=1e-3)
    large = replace(stratified.LARGE, mud=0.6, d=2e-3)
    z = np.array([0.0, 0.5, 1.0])
    phi = np.array([1.0, 0.25, 0.0])
    assert np.allclose(stratified.mu_bar_s(z, phi, small, large),
                       [0.342, 0.25 * 0.342 + 0.75 * 0.4104, 0.4104],
                       rtol=1e-15, atol=0)
    assert np.allclose(stratified.mu_bar_d(z, phi, small, large),
                       [0.557, 0.25 * 0.557 + 0.75 * 0.6, 0.6],
                       rtol=1e-15, atol=0)
    assert np.allclose(stratified.mean_diameter(z, phi, small, large),
                       [1e-3, 1.75e-3, 2e-3], rtol=1e-15, atol=0)


def test_composition_depth_average_and_grading():
    """Gray & Chugunov (5.8) with table 3 and phibar = 0.5: depth average
    0.5, small at the base, large at the top, phi = 1/2 at z = h/2."""
    avg = quad(stratified.composition, 0.0, H, epsabs=0.0, epsrel=1e-13,
               limit=200, points=[H / 2])[0] / H
    assert abs(avg - 0.5) < 1e-10
    assert stratified.composition(0.0) > 0.9999
    assert stratified.composition(H) < 1e-6
    assert abs(stratified.composition(H / 2) - 0.5) < 1e-12


def test_stratified_inertial_number_switches():
    """I(z) decreases from the pure-small value at the base to the
    pure-large value at the top, and equals the mix value at z = h/2."""
    z = np.linspace(0.0, H, 101)
    I = stratified.inertial_number(z)
    assert np.all(np.diff(I) < 0.0)
    assert abs(I[0] / I_SMALL - 1) < 1e-5
    assert abs(I[-1] / I_LARGE - 1) < 1e-5
    assert abs(I[50] / I_MIX - 1) < 1e-12


@pytest.mark.parametrize("phi", [0.0, 0.5, 1.0])
def test_velocity_ode_equals_closed_form(phi):
    """The ODE (6.5) for uniform composition equals (5.4) with (6.3)."""
    z = np.linspace(0.0, H, 21)
    u_ode = stratified.velocity(z, phi)
    u_cf = stratified.velocity_uniform(z, phi)
    assert np.max(np.abs(u_ode - u_cf)) < 1e-10 * u_cf[-1]


def test_stratified_velocity_by_quadrature():
    """u(z) of the ODE (6.5) equals quad of its right-hand side."""
    P = stratified.SMALL
    scale = math.sqrt(P.Phi * P.g * math.cos(F7.zeta))

    def rhs(z):
        return stratified.inertial_number(z) \
            / stratified.mean_diameter(z) * scale * math.sqrt(H - z)

    for zz in (0.3 * H, 0.6 * H, H):
        ref = quad(rhs, 0.0, zz, epsabs=0.0, epsrel=1e-12, limit=200,
                   points=[H / 2] if zz > H / 2 else None)[0]
        assert stratified.velocity(zz) == pytest.approx(ref, rel=1e-9)


def test_stratified_velocity_figure7_shape():
    """Figure 7(b): u(0) = 0, increasing, between pure large and pure
    small, on the pure-small curve near the base, parallel to the pure-
    large curve near the top, and faster than the uniform mix at the top."""
    z = np.linspace(0.0, H, 101)
    u = stratified.velocity(z)
    us = stratified.velocity_uniform(z, 1.0)
    ul = stratified.velocity_uniform(z, 0.0)
    um = stratified.velocity_uniform(z, 0.5)
    assert u[0] == 0.0
    assert np.all(np.diff(u) > 0.0)
    assert np.all(ul[1:] < u[1:]) and np.all(u[1:] <= us[1:])
    assert np.max(np.abs(u[:21] - us[:21])) < 1e-5 * us[-1]
    top = slice(80, None)
    shift = u[top] - ul[top]
    assert np.ptp(shift) < 1e-5 * u[-1]
    assert u[-1] > 1.1 * um[-1]


def test_stratified_input_checks():
    """z outside [0, h], phi outside [0, 1] and tan zeta <= mubar_s are
    refused."""
    with pytest.raises(ValueError):
        stratified.velocity(1.1 * H)
    with pytest.raises(ValueError):
        stratified.inertial_number(0.0, 1.2)
    with pytest.raises(ValueError):
        stratified.inertial_number(0.0, 0.0, zeta=math.radians(22.0))


# ---------------------------------------------------------------- 6.3


def test_table2_and_dem_column():
    assert (T2.A, T2.B, T2.C, T2.E) == (0.108, 0.3744, 0.2712, 2.0957)
    assert (DEM.R, DEM.hhat, DEM.I0, DEM.Phi) == (1.5, 30.0, 0.5106, 0.6)
    assert math.degrees(DEM.zeta) == pytest.approx(25.0, rel=1e-15)


def test_lambdas_by_hand():
    """(6.11a-c) with table 2, R = 1.5, Phi = 0.6."""
    l1, l2, l3 = trewhela.lambdas()
    assert l1 == pytest.approx(0.0648 / 0.1872, rel=1e-14)
    assert l2 == pytest.approx(0.0648 * 2.0957 / (0.3744 * 2.04785),
                               rel=1e-14)
    assert l3 == pytest.approx(0.0648 / (0.1872 * 2.04785), rel=1e-14)


def test_I_zeta_errata3():
    """(6.13) with the ERRATA-3 denominator: 0.1659, and the Jop law (2.7)
    with mus, mud, I0 of the DEM fit gives tan 25 deg there."""
    tz = math.tan(math.radians(25.0))
    I = trewhela.I_zeta()
    assert abs(I - 0.1659) < 1e-4
    mus, mud, I0 = DEM.mus, DEM.mud, DEM.I0
    assert (mus * I0 + mud * I) / (I0 + I) == pytest.approx(tz, rel=1e-14)


def five_point(f, x, dx):
    return (f(x - 2 * dx) - 8 * f(x - dx) + 8 * f(x + dx)
            - f(x + 2 * dx)) / (12 * dx)


def test_closed_form_satisfies_6_9():
    """(6.10) satisfies (6.9): 1/(dzhat/dphi) by a 5-point difference in
    phi equals the right-hand side of (6.9) to 1e-8 (relative)."""
    K = 11.0
    phi = np.linspace(0.05, 0.95, 19)
    dz = five_point(lambda v: trewhela.zhat(v, K), phi, 1e-4)
    zh = trewhela.zhat(phi, K)
    rhs = trewhela.dphi_dzhat(zh, phi)
    assert np.all(rhs < 0.0)
    assert np.max(np.abs(1.0 / dz / rhs - 1.0)) < 1e-8
    # (6.9) as printed, independently of dphi_dzhat
    R, A, B, E = DEM.R, T2.A, T2.B, T2.E
    printed = -B * (R - 1) * phi * (1 - phi) * (1 + E * (1 - phi) * (R - 1)) \
        / (DEM.Phi * A * (DEM.hhat - zh))
    assert np.allclose(rhs, printed, rtol=1e-14, atol=0)


def test_phi_s_inverts_6_10():
    """phi_s inverts (6.10), is 0 at the surface, decreasing in zhat, and
    its slope (5-point difference in zhat) is (6.9)."""
    K = 6.4
    z = np.linspace(0.0, 29.0, 30)
    phi = trewhela.phi_s(z, K)
    assert np.allclose(trewhela.zhat(phi, K), z, rtol=0, atol=1e-11)
    assert trewhela.phi_s(DEM.hhat, K) == 0.0
    assert np.all(np.diff(phi) < 0.0) and phi[0] < 1.0
    zi = z[1:-1]
    slope = five_point(lambda v: trewhela.phi_s(v, K), zi, 1e-3)
    assert np.allclose(slope, trewhela.dphi_dzhat(zi, phi[1:-1]),
                       rtol=1e-7, atol=1e-12)


@pytest.mark.parametrize("phibar", [0.3, 0.5, 0.7])
def test_K_reproduces_phibar(phibar):
    """K from brentq: quad over zhat of the inverted (6.10) gives phibar to
    1e-10; K decreases as phibar increases."""
    K = trewhela.K_from_phibar(phibar)
    avg = quad(trewhela.phi_s, 0.0, DEM.hhat, args=(K,), epsabs=0.0,
               epsrel=1e-12, limit=200)[0] / DEM.hhat
    assert abs(avg - phibar) < 1e-10
    assert trewhela.K_from_phibar(phibar + 0.05) < K
    assert abs(trewhela.depth_average(K) - phibar) < 1e-12


def test_dphi_dzhat_with_C():
    """The C-law ODE by hand at one point; C = 0 is (6.9)."""
    zh, phi = 10.0, 0.4
    R, A, B, C, E = DEM.R, T2.A, T2.B, T2.C, T2.E
    dbar = phi + R * (1 - phi)
    ref = -B * (R - 1) * phi * (1 - phi) * (1 + E * (1 - phi) * (R - 1)) \
        * math.cos(DEM.zeta) / (A * (C * dbar + DEM.Phi
                                     * math.cos(DEM.zeta) * (30 - zh)))
    assert trewhela.dphi_dzhat(zh, phi, C=C) == pytest.approx(ref,
                                                              rel=1e-14)
    assert trewhela.dphi_dzhat(zh, phi, C=0.0) == pytest.approx(
        -B * (R - 1) * phi * (1 - phi) * (1 + E * (1 - phi) * (R - 1))
        / (DEM.Phi * A * (30 - zh)), rel=1e-14)


def test_shooting_C0_equals_closed_form():
    """The shooting solution with C = 0 equals (6.10) to 1e-6."""
    K = trewhela.K_from_phibar(0.5)
    phi0, phi = trewhela.phi_s_numeric(0.5, C=0.0)
    z = np.linspace(0.0, DEM.hhat, 61)
    assert np.max(np.abs(phi(z) - trewhela.phi_s(z, K))) < 1e-6
    assert abs(phi0 - trewhela.phi_s(0.0, K)) < 1e-6


def test_shooting_with_C():
    """With C = 0.2712: depth average phibar (quad of the dense output),
    phi^s > 0 at the surface, and close to the C = 0 profile (the paper:
    C 'makes very little difference'), here within 0.03."""
    phi0, phi = trewhela.phi_s_numeric(0.5)
    avg = quad(phi, 0.0, DEM.hhat, epsabs=0.0, epsrel=1e-10,
               limit=200)[0] / DEM.hhat
    assert abs(avg - 0.5) < 1e-8
    assert 0.0 < phi(DEM.hhat) < 1e-4
    z = np.linspace(0.0, DEM.hhat, 61)
    assert np.all(np.diff(phi(z)) < 0.0)
    diff = np.max(np.abs(phi(z) - trewhela.concentration(0.5)(z)))
    assert 1e-3 < diff < 0.03


def test_velocity_pure_phases_6_12():
    """(6.14) with phibar = 1 is (6.12), with phibar = 0 it is (6.12)/R."""
    z = np.linspace(0.0, DEM.hhat, 31)
    ub = trewhela.u_bagnold_hat(z)
    u1 = trewhela.velocity_hat(z, trewhela.concentration(1.0))
    u0 = trewhela.velocity_hat(z, trewhela.concentration(0.0))
    assert np.max(np.abs(u1 - ub)) < 1e-8
    assert np.max(np.abs(u0 - ub / DEM.R)) < 1e-8
    # (6.12) by hand at the surface
    ref = 2 / 3 * trewhela.I_zeta() * math.sqrt(0.6 * math.cos(DEM.zeta)) \
        * 30 ** 1.5
    assert ub[-1] == pytest.approx(ref, rel=1e-14)


def test_velocity_monotone_in_phibar():
    """Surface velocities decrease with the small-particle content, lying
    between (6.12)/R and (6.12); each profile increases with zhat."""
    z = np.linspace(0.0, DEM.hhat, 16)
    top = [trewhela.u_bagnold_hat(DEM.hhat) / DEM.R]
    for phibar in (0.3, 0.5, 0.7):
        u = trewhela.velocity_hat(z, trewhela.concentration(phibar))
        assert u[0] == 0.0 and np.all(np.diff(u) > 0.0)
        top.append(u[-1])
    top.append(trewhela.u_bagnold_hat(DEM.hhat))
    assert np.all(np.diff(top) > 0.0)


def test_stratified_ode_is_6_14():
    """stratified.velocity (6.5) with d^s = 1, d^l = R, g = 1, h = hhat and
    the DEM friction is the nondimensional (6.14) of trewhela."""
    small = replace(rheology.TABLE1, mus=DEM.mus, mud=DEM.mud, muInf=0.0,
                    I0=DEM.I0, d=1.0, g=1.0, Phi=DEM.Phi)
    large = replace(small, d=DEM.R)
    phi = trewhela.concentration(0.5)
    z = np.array([5.0, 15.0, 30.0])
    u_dim = stratified.velocity(z, phi, DEM.hhat, DEM.zeta, small, large)
    assert np.allclose(u_dim, trewhela.velocity_hat(z, phi), rtol=1e-9,
                       atol=0)


def test_figures_write_png(tmp_path):
    """figure7 and figure9 draw PNG files, with solver markers overlaid."""
    z = np.linspace(0.0, H, 5)
    f7 = stratified.figure7(tmp_path / "figure7.png",
                            solver_I=(z, stratified.inertial_number(z)),
                            solver_u=(z, stratified.velocity(z)), n=50)
    zh = np.linspace(0.0, DEM.hhat, 5)
    f9 = trewhela.figure9(tmp_path / "figure9.png", phibars=(0.0, 0.5),
                          solver_phi={0.5: (zh, 0.5 * np.ones(5))}, n=30)
    for f in (f7, f9):
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"

"""Unit tier: the chute solutions of python/granularfoam/exact/chute.py (section 5.6
travelling front, appendix A shocks) against quadratures of the Bagnold
profile (5.4) and the printed closed forms, tables 1 and 3."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from granularfoam.exact import bagnold, chute, grayChugunov, rheology

pytestmark = pytest.mark.unit

ZETA = bagnold.ZETA
P = rheology.TABLE1
T3 = grayChugunov.TABLE3
H = T3.h
I_ZETA = bagnold.inertial_number_zeta(ZETA)


def integral(g, a, b):
    return quad(g, a, b, epsabs=0.0, epsrel=1e-13, limit=200)[0]


def mu_printed(h, h_inf):
    """(5.21) as printed in the paper."""
    num = (P.mus * P.I0 * h ** 1.5 + P.mud * I_ZETA * h_inf ** 1.5
           + P.muInf * I_ZETA ** 2 * (h_inf / math.sqrt(h)) ** 3)
    return num / (P.I0 * h ** 1.5 + I_ZETA * h_inf ** 1.5)


# Fr^2 (5.18) of table 3 flow, ubar from quad of the Bagnold profile
FR2 = (integral(lambda z: bagnold.velocity(z, H, ZETA), 0.0, H) / H) ** 2 \
    / (P.g * H * math.cos(ZETA))


def dxi_dh_printed(h, chi):
    """1/(dh/dxi) from (5.17), (5.18) and the printed (5.21), h_inf = H."""
    return (((chi - 1.0) * FR2 * H / h + 1.0)
            / (math.tan(ZETA) - mu_printed(h, H)))


@pytest.mark.parametrize("h,d", [(H, None), (2e-3, None), (8e-3, 1e-3)])
def test_depth_averaged_velocity_is_mean_of_bagnold(h, d):
    """(5.16)/(5.19) equals (1/h) int_0^h u_Bagnold dz (5.14a)."""
    mean = integral(lambda z: bagnold.velocity(z, h, ZETA, d), 0.0, h) / h
    assert abs(chute.depth_averaged_velocity(h, ZETA, d) - mean) \
        < 1e-12 * mean


def test_table3_velocity_and_froude():
    """h = 5 mm, d = 0.5 mm, 24 deg: ubar = 0.04067 m/s (by hand:
    2 x 0.062006/(5 x 0.5e-3) x sqrt(0.6 x 9.81 cos 24) x 0.005^1.5);
    (5.18) Fr = ubar/sqrt(g h cos zeta) = 2 I_zeta sqrt(Phi) h/(5 d),
    independent of g, = 0.1921."""
    ubar = chute.depth_averaged_velocity(H, ZETA)
    assert abs(ubar - 0.04067) < 1e-5
    fr = chute.froude(H, ZETA)
    assert abs(fr - ubar / math.sqrt(P.g * H * math.cos(ZETA))) < 1e-15
    assert abs(fr - 2 * I_ZETA * math.sqrt(P.Phi) * H / (5 * P.d)) < 1e-14
    assert abs(fr - 0.1921) < 1e-4


@pytest.mark.parametrize("h,zeta", [(H, ZETA), (2e-3, math.radians(22))])
def test_shape_factor_bagnold(h, zeta):
    """chi (5.14c) of the Bagnold profile by quad is 5/4 (section 5.6)."""
    assert abs(chute.shape_factor_bagnold(h, zeta) - 1.25) < 1e-12


@pytest.mark.parametrize("ratio", [0.05, 0.3, 0.5, 1.0, 2.0])
def test_basal_friction_is_printed_5_21(ratio):
    """mu_high(I_zeta (h_inf/h)^{3/2}) (2.8), (5.20) equals the printed
    (5.21); tan zeta at h = h_inf."""
    mu = chute.basal_friction(ratio * H, H, ZETA)
    assert abs(mu - mu_printed(ratio * H, H)) < 1e-13
    if ratio == 1.0:
        assert abs(mu - math.tan(ZETA)) < 1e-13


def test_basal_friction_diverges_at_zero_depth():
    """h -> 0: mu ~ muInf I_zeta (h_inf/h)^{3/2} (no precursor layer)."""
    h = np.array([1e-4, 1e-6, 1e-8]) * H
    ratio = chute.basal_friction(h, H, ZETA) \
        / (P.muInf * I_ZETA * (H / h) ** 1.5)
    assert np.all(np.abs(ratio - 1.0) < [0.05, 5e-5, 5e-8])


@pytest.fixture(scope="module", params=[1.0, 1.25])
def front(request):
    chi = request.param
    xi, h = chute.front_shape(H, ZETA, chi)
    return chi, xi, h


def test_front_ends_and_monotonic(front):
    """Front at xi = 0 with h = 0; upstream end h = H_TOP h_inf, xi < 0;
    xi increasing and h decreasing towards the front."""
    _, xi, h = front
    assert xi.shape == h.shape == (400,)
    assert xi[-1] == 0.0 and h[-1] == 0.0
    assert abs(h[0] - chute.H_TOP * H) < 1e-15
    assert np.all(np.diff(xi) > 0.0) and np.all(np.diff(h) < 0.0)
    assert np.all(h < H)


def test_front_xi_matches_quadrature(front):
    """xi(h) from solve_ivp equals -int_0^h |dxi/dh| by quad, with (5.17)
    and the printed (5.21) coded independently here."""
    chi, xi, h = front
    for i in (0, 50, 200, 350, 398):
        ref = integral(lambda s: dxi_dh_printed(s, chi), 0.0, h[i])
        assert abs(xi[i] - ref) < 1e-8 * abs(ref)


def test_front_ode_residual_finite_differences(front):
    """Second-order differences dxi/dh (np.gradient) on the returned curve
    satisfy (5.17), to the truncation error of the 400-point grid; the
    point next to the tip, where xi ~ h^{5/2} or h^{3/2} is not smooth,
    is excluded."""
    chi, xi, h = front
    fd = np.gradient(xi, h)[1:-2]
    exact = np.array([dxi_dh_printed(s, chi) for s in h[1:-2]])
    rel = np.abs(fd / exact - 1.0)
    assert np.max(rel) < 1e-2 and np.median(rel) < 2e-4


def test_front_approaches_h_inf_exponentially(front):
    """Upstream, h_inf - h ~ exp(xi/L) with the linearisation of (5.17):
    L = [(chi - 1) Fr^2 + 1]/|dmu/dh(h_inf)|."""
    chi, xi, h = front
    dh = 1e-6 * H
    dmu = (chute.basal_friction(H + dh, H, ZETA)
           - chute.basal_friction(H - dh, H, ZETA)) / (2 * dh)
    L = ((chi - 1.0) * chute.froude(H, ZETA) ** 2 + 1.0) / abs(dmu)
    k = np.polyfit(xi[:5], np.log(H - h[:5]), 1)[0]
    assert abs(k * L - 1.0) < 5e-3


def test_front_pins_with_power_law():
    """Near the front, (5.17) with mu ~ muInf I_zeta (h_inf/h)^{3/2} gives
    -xi = (2/3 a h^{3/2} + 2/5 h^{5/2})/(muInf I_zeta h_inf^{3/2}),
    a = (chi - 1) Fr^2 h_inf: h ~ (-xi)^{2/5} for chi = 1 and
    (-xi)^{2/3} for chi > 1, an infinite slope at xi = 0."""
    fr2 = chute.froude(H, ZETA) ** 2
    for chi in (1.0, 1.25):
        xi, h = chute.front_shape(H, ZETA, chi, n=20000)
        a = (chi - 1.0) * fr2 * H
        sel = (h > 0.0) & (h < 2e-3 * H)
        asym = -(2 / 3 * a * h[sel] ** 1.5 + 0.4 * h[sel] ** 2.5) \
            / (P.muInf * I_ZETA * H ** 1.5)
        assert sel.sum() >= 3
        assert np.all(np.abs(xi[sel] / asym - 1.0) < 3e-3)
        # the secant slope steepens towards the front, to more than 200
        # times the slope (5.17) at h_inf/2
        secant = np.diff(h[-4:]) / np.diff(xi[-4:])
        assert np.all(np.diff(secant) < 0.0)
        assert secant[-1] < 200.0 * chute.front_slope(0.5 * H, H, ZETA, chi)


def test_front_shapes_differ_with_chi():
    """chi = 5/4 (Bagnold) gives a longer front than plug flow chi = 1:
    xi at h = h_inf/2 by quad of (5.17) vs the interpolated curves."""
    half = {}
    for chi in (1.0, 1.25):
        xi, h = chute.front_shape(H, ZETA, chi, n=2000)
        half[chi] = np.interp(0.5 * H, h[::-1], xi[::-1])
        ref = integral(lambda s: dxi_dh_printed(s, chi), 0.0, 0.5 * H)
        assert abs(half[chi] - ref) < 1e-4 * abs(ref)
    assert half[1.25] < half[1.0] < 0.0
    assert half[1.0] - half[1.25] > 0.03 * abs(half[1.0])


@pytest.mark.parametrize("zhat", [0.0, 0.1, 0.5, 0.9, 1.0])
def test_streamfunction_is_integral_of_bagnold(zhat):
    """(A4) equals int_0^z u_Bagnold dz'; psi(h) = h ubar (5.16)."""
    z = zhat * H
    psi = chute.streamfunction(z, H, ZETA)
    ref = integral(lambda s: bagnold.velocity(s, H, ZETA), 0.0, z)
    assert abs(psi - ref) <= 1e-12 * abs(chute.streamfunction(H, H, ZETA))
    if zhat == 1.0:
        ubar = chute.depth_averaged_velocity(H, ZETA)
        assert abs(psi - H * ubar) < 1e-13 * H * ubar


def test_shocks_meet_and_final_height():
    """Table 3 shocks (phi0 = 0.5): lower from z = 0 and upper from z = h
    at x = 0 meet the final shock at x = psi(h)/(f cos zeta) = 3.18 cm;
    the final shock carries the inflow small-particle flux,
    int_0^{z_f} u = phi0 int_0^h u."""
    f, phi0 = T3.f_sl, 0.5
    x_meet = chute.shock_meeting_point(H, ZETA, f)
    ubar = chute.depth_averaged_velocity(H, ZETA)
    assert abs(x_meet - H * ubar / (f * math.cos(ZETA))) < 1e-15
    assert abs(x_meet - 0.03180) < 1e-5
    x = np.array([0.0, 0.5, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 3.0]) * x_meet
    lo, up, fin = chute.shock_lines(x, H, ZETA, f, phi0)
    assert lo[0] == 0.0 and abs(up[0] - H) < 1e-15
    assert np.all(np.isnan([lo[4], lo[5], up[4], up[5], fin[0], fin[2]]))
    z_f = fin[-1]
    assert np.all(fin[3:] == z_f)
    assert abs(lo[3] - z_f) < 1e-12 * H and abs(up[3] - z_f) < 1e-12 * H
    assert abs(lo[2] - z_f) < 1e-6 * H and abs(up[2] - z_f) < 1e-6 * H
    assert lo[1] < z_f < up[1]
    flux = integral(lambda s: bagnold.velocity(s, H, ZETA), 0.0, z_f)
    assert abs(flux - phi0 * H * ubar) < 1e-10 * H * ubar


@pytest.mark.parametrize("phi0", [0.3, 0.5, 0.8])
def test_shock_speeds_are_jump_conditions(phi0):
    """In (x, psi) coordinates (2.19) without diffusion reads
    d phi/dx + d/dpsi(-f cos zeta phi(1 - phi)) = 0; the shocks recovered
    from z (inverting (A4)) move at [F]/[phi]: f phi0 cos zeta (lower,
    phi 1 | phi0), -f (1 - phi0) cos zeta (upper, phi0 | 0)."""
    f = T3.f_sl
    fc = f * math.cos(ZETA)
    x_meet = chute.shock_meeting_point(H, ZETA, f)
    x = np.array([0.2, 0.6]) * x_meet
    lo, up, _ = chute.shock_lines(x, H, ZETA, f, phi0)

    def flux(phi):
        return -fc * phi * (1.0 - phi)

    for z, (below, above) in ((lo, (1.0, phi0)), (up, (phi0, 0.0))):
        psi = chute.streamfunction(z, H, ZETA)
        speed = (psi[1] - psi[0]) / (x[1] - x[0])
        rh = (flux(above) - flux(below)) / (above - below)
        assert abs(speed - rh) < 1e-9 * fc

"""The steady tridisperse solution of python/granularfoam/exact/tridisperse.py: its
reduction to Gray & Chugunov's (5.8), the zero-net-flux balance of (2.13)
and (2.15) as printed, the depth averages, (2.10), and bad input."""
import dataclasses
import math

import numpy as np
import pytest

from granularfoam.exact import grayChugunov, trewhela, tridisperse

pytestmark = pytest.mark.unit

C3 = tridisperse.COLUMN


def bidisperse(f=7e-3, D=1e-6, h=5e-3):
    """Two sizes with table 3's f_sl and D_sl (Pe = 31.7 at 25 degrees)."""
    return tridisperse.Column(d=(1e-3, 2e-3), h=h, f=(((0, 1), f),),
                              D=(((0, 1), D),))


@pytest.mark.parametrize("phibar", [0.1, 0.3, 0.5, 0.9])
def test_reduces_to_gray_chugunov(phibar):
    """n = 2: phi^s = (5.8) with A_GC (5.11) and Pe (5.9)."""
    c = bidisperse()
    z = np.linspace(0.0, 1.0, 101)
    phi = tridisperse.steady_profiles([phibar, 1.0 - phibar], c, z)
    Pe = grayChugunov.peclet(7e-3, c.h, 1e-6, c.zeta)
    exact = grayChugunov.phi_s(z, Pe, phibar)
    assert np.max(np.abs(phi[0] - exact)) < 1e-8
    assert np.max(np.abs(phi[0] + phi[1] - 1.0)) < 1e-14


def test_absent_phase_is_bidisperse():
    """phibar^m = 0: the small-large pair alone, (5.8) with f_sl, D_sl."""
    z = np.linspace(0.0, 1.0, 51)
    phi = tridisperse.steady_profiles([0.4, 0.0, 0.6], C3, z)
    f, D = dict(C3.f)[(0, 2)], dict(C3.D)[(0, 2)]
    Pe = grayChugunov.peclet(f, C3.h, D, C3.zeta)
    assert np.all(phi[1] == 0.0)
    assert np.max(np.abs(phi[0] - grayChugunov.phi_s(z, Pe, 0.4))) < 1e-8


@pytest.mark.parametrize("phibar", [(1 / 3, 1 / 3, 1 / 3), (0.5, 0.3, 0.2),
                                    (0.01, 0.98, 0.01), (0.05, 0.05, 0.9)])
def test_zero_net_flux_and_averages(phibar):
    """(2.13) = (2.15) along z for every phase (the steady no-flux state,
    checked with finite-difference derivatives of the profiles, not the
    log form the solver of the ODE uses), depth averages phibar and sum
    phi = 1 (2.10)."""
    z = np.linspace(0.0, 1.0, 4001)
    phi = tridisperse.steady_profiles(phibar, C3, z)
    D, W = tridisperse.pair_matrices(C3)
    dphi = np.gradient(phi, z, axis=1, edge_order=2)
    scale = np.abs(W).max()
    worst = max(np.abs(tridisperse.net_flux(phi[:, k], dphi[:, k], D, W)).max()
                for k in range(z.size)) / scale
    assert worst < 1e-6, worst
    means = np.trapz(phi, z, axis=1)
    assert np.max(np.abs(means - np.asarray(phibar))) < 1e-6
    assert np.max(np.abs(phi.sum(axis=0) - 1.0)) < 1e-12
    assert phi.min() > 0.0


def test_equal_diffusivities_explicit():
    """With D_nl = D the system is explicit: psi_n' = -(1/D) sum W_nl phi^l
    (up to the common shift fixed by sum phi psi' = 0)."""
    c = dataclasses.replace(C3, D=tuple((ij, 2e-5) for ij, _ in C3.D))
    D, W = tridisperse.pair_matrices(c)
    rng = np.random.default_rng(1)
    for _ in range(20):
        phi = rng.dirichlet((1.0, 1.0, 1.0))
        explicit = -(W @ phi) / 2e-5
        explicit -= phi @ explicit
        assert np.allclose(tridisperse.dpsi_dzhat(phi, D, W), explicit,
                           rtol=1e-12, atol=1e-12 * np.abs(explicit).max())


def test_mirror_symmetry():
    """f_sm = f_ml, D_sm = D_ml and phibar^s = phibar^l: phi^s(z) =
    phi^l(h - z) and phi^m is symmetric about h/2."""
    z = np.linspace(0.0, 1.0, 101)
    phi = tridisperse.steady_profiles([0.3, 0.4, 0.3], C3, z)
    assert np.max(np.abs(phi[0] - phi[2][::-1])) < 1e-8
    assert np.max(np.abs(phi[1] - phi[1][::-1])) < 1e-8


def test_velocity_monodisperse_is_bagnold():
    """One size present: (6.14) with dbar = d is Bagnold's (6.12) scaled
    by d^s/d."""
    z = np.linspace(0.0, 1.0, 31)
    p = dataclasses.replace(trewhela.DEM, hhat=C3.h / C3.d[0])
    for k, ratio in enumerate(np.asarray(C3.d) / C3.d[0]):
        phibar = np.eye(3)[k]
        u = tridisperse.velocity_hat(z, phibar, C3)
        bagnold = trewhela.u_bagnold_hat(z * p.hhat, p) / ratio
        assert np.max(np.abs(u - bagnold)) < 1e-8 * bagnold.max()


@pytest.mark.parametrize("phibar", [(0.5, 0.5, 0.1), (1.2, -0.1, -0.1),
                                    (0.5, 0.5)])
def test_bad_fractions(phibar):
    with pytest.raises(ValueError, match="phibar"):
        tridisperse.steady_profiles(phibar, C3)


def test_bad_pairs():
    with pytest.raises(ValueError, match="distinct"):
        tridisperse.pair_matrices(dataclasses.replace(C3, d=(1e-3, 1e-3, 2e-3)))
    with pytest.raises(ValueError, match="pair"):
        tridisperse.pair_matrices(dataclasses.replace(C3, f=C3.f[:2]))
    with pytest.raises(ValueError, match="pair"):
        tridisperse.pair_matrices(
            dataclasses.replace(C3, D=(((0, 1), 0.0),) + C3.D[1:]))


def test_column_matches_tutorial_defaults(tmp_path):
    """COLUMN is the tutorial's tridisperseParameters (read as text, as
    HEAD holds it)."""
    from conftest import committed_copy
    text = committed_copy(
        "tutorials/tridisperseColumn/system/tridisperseParameters",
        tmp_path / "tridisperseParameters").read_text()
    values = {k: float(v) for k, v in
              (line.split(";")[0].split() for line in text.splitlines()
               if line.split() and line.split()[0] in tridisperse.KEYS)}
    assert set(values) == set(tridisperse.KEYS)
    c, phibar = tridisperse.from_parameters(values)
    assert c == C3
    assert math.isclose(phibar.sum(), 1.0, abs_tol=1e-12)

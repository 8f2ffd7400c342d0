"""Steady segregation of n grain sizes in a periodic inclined layer with
constant pairwise segregation velocities f_ij (2.13) and Maxwell-Stefan
diffusivities D_ij (2.15): the general theory of section 2.2 beyond the
paper's bidisperse cases (tutorials/tridisperseColumn).

Derivation.  The layer 0 <= z <= h (z the slope normal, x downslope) flows
steadily with u = u(z) e_x and phi^nu = phi^nu(z), so div(phi^nu u) = 0
and (2.11) reduces to d/dz(F^nu_z - D^nu_z) = 0.  The base (a wall) and
the free surface carry no flux of any grain phase ((2.17), and the air
above holds no grains), so the integration constant vanishes:

    F^nu . e_z = D^nu . e_z              for every phase nu.

In the solver, as in (2.19), the segregation of every grain pair is along
gravity: e_{nu lambda} = sigma_{nu lambda} g/|g| with sigma = +1 when
d^nu < d^lambda (the smaller grain moves with g) and -1 otherwise, which
satisfies (2.14b); (g/|g|).e_z = -cos zeta.  With (2.13) and (2.15):

    -cos zeta phi^nu sum_l sigma_nl f_nl phi^l
        = sum_l D_nl (phi^l dphi^nu/dz - phi^nu dphi^l/dz).

The fractions are positive, so divide by phi^nu and write psi = log phi,
zhat = z/h and W_nl = sigma_nl f_nl h cos zeta (antisymmetric: (2.14a,b)):

    sum_l D_nl phi^l (psi_n' - psi_l') = -sum_l W_nl phi^l,   ' = d/dzhat

that is M psi' = r with M_nn = sum_{l != n} D_nl phi^l, M_nl = -D_nl phi^l,
r_n = -sum_l W_nl phi^l.  M's rows vanish on the vector 1 (psi' is only
defined up to a common shift, which leaves phi = softmax(psi) alone) and
phi^T M = 0 by D_nl = D_ln, while phi^T r = 0 by W_nl = -W_ln: the n
equations are consistent and one of them is the sum of the others (this is
(2.12)).  The shift is fixed by sum_n phi^n psi_n' = 0 (then sum phi stays
1, (2.10)): psi' solves K psi' = r with K = M + 1 phi^T, which is regular
whenever two phases are present (K x = 0 gives phi^T x = 0, then M x = 0,
x = c 1 and c = 0).

The n - 1 free values psi(0) (psi^n(0) = 0) are fixed by the depth averages
int_0^1 phi^nu dzhat = phibar^nu (the case's initial composition, which
segregation and diffusion conserve in the periodic layer): shooting from
the base with solve_ivp (DOP853), the averages integrated with the ODE, and
scipy.optimize.root on the n - 1 residuals.  A phase with phibar = 0 is
absent (phi = 0) and drops out.

Special case n = 2 (small s, large l): D_sl phi^l (psi_s' - psi_l') =
-W_sl phi^l, and psi_s - psi_l = logit(phi^s), so
d logit(phi^s)/dzhat = -f_sl h cos zeta/D_sl = -Pe (5.9) and
phi^s = 1/(1 + A_GC exp(Pe zhat)), Gray & Chugunov's (5.8), A_GC from the
depth average (5.10)-(5.11).  With D_nl = D for every pair the system is
explicit: psi_n' = -(1/D) sum_l W_nl phi^l.

Velocity: the three sizes share one friction law, so with the lithostatic
pressure (5.3) mu(I) = tan zeta gives I = I_zeta (6.13) at every height and
the generalised inertial number (3.2) with dbar (3.1) gives (6.14) with
dbar/d^s = sum phi^nu d^nu/d^s (trewhela.velocity_hat_dbar).
"""
import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import root
from scipy.special import softmax

from . import trewhela
from .stratified import finish_figure


@dataclass(frozen=True)
class Column:
    """tutorials/tridisperseColumn/system/tridisperseParameters: diameters
    d (m, small to large), depth h (m), slope zeta (radians), pairwise f
    (m/s) and D (m^2/s) as {(i, j): value} over the grain indices."""
    d: tuple = (1e-3, 1.5e-3, 2e-3)
    h: float = 0.03
    zeta: float = math.radians(25.0)
    f: tuple = (((0, 1), 5e-3), ((1, 2), 5e-3), ((0, 2), 1e-2))
    D: tuple = (((0, 1), 2e-5), ((1, 2), 2e-5), ((0, 2), 3e-5))


COLUMN = Column()
NAMES = ("small", "medium", "large")
PAIRS = {(0, 1): "SmallMedium", (1, 2): "MediumLarge", (0, 2): "SmallLarge"}
# the entries of tridisperseParameters that from_parameters reads
KEYS = ("ds", "dm", "dl", "h", "phiSmall", "phiMedium", "phiLarge") + tuple(
    k + v for v in PAIRS.values() for k in ("f", "D"))


def from_parameters(v, zeta=COLUMN.zeta):
    """(Column, phibar) from the values {key: float} of KEYS in
    tridisperseParameters (the slope is constant/g's, 25 degrees)."""
    c = Column(d=(v["ds"], v["dm"], v["dl"]), h=v["h"], zeta=zeta,
               f=tuple((ij, v["f" + s]) for ij, s in PAIRS.items()),
               D=tuple((ij, v["D" + s]) for ij, s in PAIRS.items()))
    return c, np.array([v["phiSmall"], v["phiMedium"], v["phiLarge"]])


def pair_matrices(c=COLUMN):
    """Symmetric D_nl and antisymmetric W_nl = sigma_nl f_nl h cos zeta
    (sigma = +1 when d^n < d^l), n x n; every pair must be given."""
    n = len(c.d)
    if len(set(c.d)) != n or min(c.d) <= 0.0:
        raise ValueError(f"the diameters must be positive and distinct: {c.d}")
    D, W = np.zeros((n, n)), np.zeros((n, n))
    given_f, given_D = dict(c.f), dict(c.D)
    for i in range(n):
        for j in range(i + 1, n):
            f_ij = given_f.get((i, j), given_f.get((j, i)))
            D_ij = given_D.get((i, j), given_D.get((j, i)))
            if f_ij is None or D_ij is None or f_ij < 0.0 or D_ij <= 0.0:
                raise ValueError(f"pair ({i}, {j}) needs f >= 0 and D > 0")
            sigma = 1.0 if c.d[i] < c.d[j] else -1.0
            D[i, j] = D[j, i] = D_ij
            W[i, j] = sigma * f_ij * c.h * math.cos(c.zeta)
            W[j, i] = -W[i, j]
    return D, W


def dpsi_dzhat(phi, D, W):
    """psi' = K^{-1} r of the module docstring: the zero-net-flux balance
    of (2.13) and (2.15) for psi = log phi, with sum phi psi' = 0."""
    M = -D * phi[np.newaxis, :]
    M[np.diag_indices_from(M)] = (D * phi[np.newaxis, :]).sum(axis=1)
    K = M + np.outer(np.ones_like(phi), phi)
    r = -(W * phi[np.newaxis, :]).sum(axis=1)
    return np.linalg.solve(K, r)


def net_flux(phi, dphi, D, W):
    """F^nu - D^nu along e_z, times h, for fractions phi and their zhat
    derivatives dphi (arrays of n): (2.13) and (2.15) as printed, the
    residual the steady state must zero (a check independent of the psi
    form)."""
    seg = -phi * (W * phi[np.newaxis, :]).sum(axis=1)
    dif = (D * (phi[np.newaxis, :] * dphi[:, np.newaxis]
                - phi[:, np.newaxis] * dphi[np.newaxis, :])).sum(axis=1)
    return seg - dif


def _shoot(psi0, D, W, zhat=None, rtol=1e-11):
    n = len(psi0)

    def rhs(_, y):
        phi = softmax(y[:n])
        return np.concatenate([dpsi_dzhat(phi, D, W), phi])

    sol = solve_ivp(rhs, (0.0, 1.0), np.concatenate([psi0, np.zeros(n)]),
                    method="DOP853", rtol=rtol, atol=1e-13, t_eval=zhat)
    if not sol.success:
        raise RuntimeError(sol.message)
    return sol


def steady_profiles(phibar, c=COLUMN, zhat=None, tol=1e-10):
    """phi^nu(zhat) at the heights zhat = z/h in [0, 1] (array, ascending)
    of the steady state with depth averages phibar (n fractions summing to
    1); returns an (n, len(zhat)) array.  Shooting on psi(0), see the module
    docstring."""
    phibar = np.asarray(phibar, dtype=float)
    D, W = pair_matrices(c)
    if phibar.shape != (len(c.d),) or np.any(phibar < 0.0) \
            or abs(phibar.sum() - 1.0) > 1e-12:
        raise ValueError(f"phibar must be {len(c.d)} fractions summing to "
                         f"1: {phibar}")
    zhat = np.linspace(0.0, 1.0, 201) if zhat is None else \
        np.asarray(zhat, dtype=float)
    if np.any(zhat < 0.0) or np.any(zhat > 1.0) or np.any(np.diff(zhat) < 0):
        raise ValueError("zhat must be ascending in [0, 1]")
    out = np.zeros((len(c.d), zhat.size))
    present = np.flatnonzero(phibar > 0.0)
    if present.size == 1:
        out[present[0]] = 1.0
        return out
    Dp, Wp, target = D[np.ix_(present, present)], W[np.ix_(present, present)], \
        phibar[present]

    # the unknowns are psi(0) shifted by the uniform mix's log fractions
    # and by 1, so that the finite-difference Jacobian of root (steps
    # relative to |x|) is taken with steps of order 1e-8 and not of the
    # order of the round-off of log(phibar)
    guess = np.log(target[:-1] / target[-1]) - 1.0

    def residual(x):
        sol = _shoot(np.append(x + guess, 0.0), Dp, Wp)
        return sol.y[present.size:-1, -1] - target[:-1]

    # hybr, Powell's, first; Levenberg-Marquardt where it stalls (strongly
    # unequal mixes, e.g. phibar = (0.01, 0.98, 0.01))
    for method in ("hybr", "lm"):
        res = root(residual, np.ones(present.size - 1), method=method,
                   options={"xtol": 1e-13})
        if res.success and np.max(np.abs(res.fun)) <= tol:
            break
    if not res.success or np.max(np.abs(res.fun)) > tol:
        raise RuntimeError(f"shooting did not converge: {res.message}, "
                           f"residual {res.fun}")
    psi0 = np.append(res.x + guess, 0.0)
    sol = _shoot(psi0, Dp, Wp, zhat=zhat)
    out[present] = softmax(sol.y[:present.size], axis=0)
    return out


def velocity_hat(zhat, phibar, c=COLUMN):
    """u/sqrt(g d^s) at zhat = z/h of the steady layer: (6.14) with
    dbar/d^s = sum phi^nu d^nu/d^s (3.1) and the column's friction
    (trewhela.DEM: the Jop fit of section 6.3, Phi = 0.6) at c's slope and
    h/d^s."""
    zhat = np.asarray(zhat, dtype=float)
    ratios = np.asarray(c.d) / c.d[0]
    fine = np.linspace(0.0, 1.0, 2001)
    phi = steady_profiles(phibar, c, fine)
    dbar = ratios @ phi
    p = dataclasses.replace(trewhela.DEM, zeta=c.zeta, hhat=c.h / c.d[0])
    return trewhela.velocity_hat_dbar(
        zhat * p.hhat, lambda zz: float(np.interp(zz / p.hhat, fine, dbar)),
        p)


def figure(path, phibar, c=COLUMN, solver=None, n=201):
    """phi^nu(z) (a) and u(z) (b), z in mm: theory as lines, the solver's
    profiles as markers.  solver: optional dict with 'z' (m), 'phi' ((n,
    m) grain fractions) and 'u' (m/s)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    zhat = np.linspace(0.0, 1.0, n)
    phi = steady_profiles(phibar, c, zhat)
    u = velocity_hat(zhat, phibar, c) * math.sqrt(9.81 * c.d[0])
    fig, (a, b) = plt.subplots(1, 2, figsize=(8, 4), sharey=True)
    colours = ("tab:blue", "tab:green", "tab:red")
    for k in range(len(c.d)):
        label = rf"$\varphi^{{{NAMES[k][0]}}}$, $d$ = {1e3 * c.d[k]:g} mm"
        a.plot(phi[k], 1e3 * c.h * zhat, "-", color=colours[k], label=label)
        if solver is not None:
            a.plot(solver["phi"][k], 1e3 * solver["z"], "o", ms=3, mfc="none",
                   color=colours[k])
    b.plot(u, 1e3 * c.h * zhat, "k-", label="theory (6.14), (3.1)")
    if solver is not None:
        b.plot(solver["u"], 1e3 * solver["z"], "ko", ms=3, mfc="none",
               label="granularSegregationFoam")
    a.set_xlabel(r"$\varphi^\nu$ (per unit grain volume)")
    a.set_xlim(-0.02, 1.02)
    a.set_ylim(0.0, 1e3 * c.h)
    a.legend(loc="center right", fontsize=8)
    return finish_figure(fig, a, b, r"$z$ (mm)", r"$u$ (m/s)", "upper left",
                         path)

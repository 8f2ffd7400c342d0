"""Friction laws of section 2.1 and the bulk-flow parameters of table 1."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Table1:
    """Table 1: frictional parameters (Barker & Gray 2017 glass beads) and
    the bulk-flow simulation parameters (SI units)."""
    mus: float = 0.342
    mud: float = 0.557
    muInf: float = 0.05
    I0: float = 0.069
    alpha: float = 1.9
    I1: float = 0.004
    d: float = 0.5e-3        # m
    rhoStar: float = 2500.0  # kg m^-3, intrinsic grain density
    Phi: float = 0.6         # solids volume fraction
    rho_air: float = 1.0     # kg m^-3
    eta_air: float = 1e-3    # kg (m s)^-1
    g: float = 9.81          # m s^-2


TABLE1 = Table1()


def _result(x):
    """A float for scalar input, an array otherwise."""
    return float(x) if np.ndim(x) == 0 else x


def mu_jop(I, p=TABLE1):
    """Jop et al. friction law, equation (2.7):
    mu = (mus I0 + mud I)/(I0 + I)."""
    I = np.asarray(I, dtype=float)
    return _result((p.mus * p.I0 + p.mud * I) / (p.I0 + I))


def log_A(p=TABLE1):
    """log of the matching constant A of equation (2.9),
    log A = log I1 + alpha (I0 + I1)^2/(mus I0 + mud I1 + muInf I1^2)^2,
    kept in log form so that A itself never overflows."""
    num = p.mus * p.I0 + p.mud * p.I1 + p.muInf * p.I1 ** 2
    return np.log(p.I1) + p.alpha * (p.I0 + p.I1) ** 2 / num ** 2


def mu_creep(I, p=TABLE1):
    """Low-I (creep) branch of equation (2.8), I <= I1:
    mu = sqrt(alpha/log(A/I)) with A from (2.9); mu(0) = 0."""
    I = np.asarray(I, dtype=float)
    with np.errstate(divide="ignore"):
        return _result(np.sqrt(p.alpha / (log_A(p) - np.log(I))))


def mu_high(I, p=TABLE1):
    """High-I branch of equation (2.8), I > I1:
    mu = (mus I0 + mud I + muInf I^2)/(I0 + I)."""
    I = np.asarray(I, dtype=float)
    return _result((p.mus * p.I0 + p.mud * I + p.muInf * I ** 2)
                   / (p.I0 + I))


def mu_barker_gray(I, p=TABLE1):
    """Barker & Gray partially regularised friction law, equation (2.8)
    with A from (2.9): mu_creep for I <= I1, mu_high for I > I1."""
    I = np.asarray(I, dtype=float)
    low = I <= p.I1
    # each branch evaluated only where it applies (no log of large I etc.)
    return _result(np.where(low, mu_creep(np.where(low, I, p.I1), p),
                            mu_high(np.where(low, p.I1, I), p)))

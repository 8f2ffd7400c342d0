"""Error norms against the exact solutions and the reader of OpenFOAM
sampled-set output (no paper equation: helpers of section 5.5's
comparisons, figure 4)."""
import numpy as np


def l2_relative(computed, exact):
    """Relative discrete L2 error on the same points (figure 4
    comparisons): sqrt(sum (c - e)^2)/sqrt(sum e^2)."""
    c = np.asarray(computed, dtype=float)
    e = np.asarray(exact, dtype=float)
    if c.shape != e.shape:
        raise ValueError(f"shapes differ: {c.shape} vs {e.shape}")
    norm = np.sqrt(np.sum(e ** 2))
    if norm == 0.0:
        raise ValueError("exact solution is zero: relative error undefined")
    return float(np.sqrt(np.sum((c - e) ** 2)) / norm)


def read_raw(path):
    """An OpenFOAM 'sets' raw/xy output file (whitespace-separated
    columns, '#' comments) as a 2-D numpy array, one row per point."""
    data = np.loadtxt(path, comments="#", ndmin=2)
    if data.size == 0:
        raise ValueError(f"no data in {path}")
    return data

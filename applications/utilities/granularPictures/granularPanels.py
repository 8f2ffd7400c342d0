"""granularPanels: what a picture of a granularSegregationFoam case shows.

Shared by granularPictures (matplotlib, from foamToVTK's files) and
granularParaView (ParaView's OpenFOAM reader), so that both draw the same
panels: the fields and their order, labels, colour maps and colour limits;
the plane they are seen in (normal to the mesh's thinnest direction); the
vertical exaggeration of a thin layer; and a column one cell wide drawn as
profiles.  Plain Python and numpy: no VTK, matplotlib or ParaView here.
"""
import numpy as np

AIR = "alpha.air"
GRAINS_BELOW = 0.5          # a cell is in the grains where phi^a < 1/2
GRAINS_ONLY = ("I", "illPosed")
AXES = "xyz"
MAX_ASPECT = 12.0           # a thin layer is exaggerated to at most 1:12


def order(names):
    """The fields of names that are drawn, in the order of the paper: the
    grain phases, the air, U, p, I, illPosed."""
    phases = sorted((k for k in names if k.startswith("alpha.")),
                    key=lambda k: (k == AIR, k))
    return phases + [k for k in ("U", "p", "I", "illPosed") if k in names]


def label(field, log=False):
    """Matplotlib mathtext label of a field (ParaView renders it too); log
    for I drawn as log10 I, not on a logarithmic colour scale."""
    if field.startswith("alpha."):
        symbol = "a" if field == AIR else field.split(".", 1)[1]
        return rf"$\phi^{{\mathrm{{{symbol}}}}}$"
    return {"U": "speed (m/s)",
            "p": r"$p$ (Pa)",
            "I": r"$\log_{10} I$ (grains)" if log else r"$I$ (grains)",
            "illPosed": "ill posed (2.6)\n(grains)"}[field]


def colormap(field):
    """Matplotlib name of the field's colour map."""
    if field.startswith("alpha."):
        return "viridis"
    return {"U": "magma", "p": "cividis", "I": "plasma",
            "illPosed": "coolwarm"}[field]


def robust(values, grains):
    """Colour limits of a field: its 1st and 99th percentiles in the grains
    (the air at an outlet or a free surface would set the scale otherwise);
    None where that range is empty."""
    inside = values if grains is None else values[grains]
    inside = inside[np.isfinite(inside)]
    if inside.size == 0:
        return None
    lo, hi = np.percentile(inside, [1.0, 99.0])
    return (float(lo), float(hi)) if hi > lo else None


def limits(field, values, grains):
    """Colour limits of a field's values (the speed for U, log10 I for I):
    [0, 1] for fractions and the indicator, the robust range of the speed
    and of log10 I, None (the full range) for p."""
    if field.startswith("alpha.") or field == "illPosed":
        return (0.0, 1.0)
    if field in ("U", "I"):
        return robust(values, grains)
    return None


def grains_mask(air):
    """Cells in the grains, phi^a < 1/2 (None without an air fraction)."""
    return None if air is None else air < GRAINS_BELOW


def plane(extent):
    """The view of a mesh of the given extents (x, y, z): (normal, (right,
    up)), the thinnest direction and the other two in order, so that x is
    to the right and z (or y in an x-y mesh) up."""
    normal = int(np.argmin(extent))
    right, up = (k for k in range(3) if k != normal)
    return normal, (right, up)


def exaggeration(width, height):
    """Default vertical exaggeration: at most 1:12 on the page."""
    return max(1.0, width / (MAX_ASPECT * height))


def is_thin(width, shown_height):
    """A thin layer (wider than 3:1 as shown) is drawn as stacked panels."""
    return width / shown_height > 3


def columns(panels, thin):
    """Number of columns of the grid of panels."""
    if thin:
        return 1
    return 4 if panels > 6 else 3 if panels > 4 else 2


def is_column(centres, size):
    """One cell across: every cell centre (n, 2) at the same in-plane
    coordinate in one direction (size: the mesh's largest extent)."""
    return bool(np.any(np.ptp(centres, axis=0) <= 1e-6 * size))


def along(centres):
    """Index (into the columns of centres) of a column's length."""
    return int(np.argmax(np.ptp(centres, axis=0)))

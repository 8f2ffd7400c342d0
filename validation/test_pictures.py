"""Smoke tier: granularPictures, the tutorials' field pictures.

The pictures must show what was computed: on a small square drum turned by
45 degrees (the mesh moves), every polygon of the cut drawn is one cell of
the mesh, at its centre, carrying that cell's values of every field; the
polygons tile the drum.  Bad options fail with a message naming them."""
import importlib.machinery
import importlib.util
import math
import subprocess

import numpy as np
import pytest
from scipy.spatial import cKDTree

from cases import foam, small_drum
from granularfoam.foamio import read_field
from conftest import executable

pytestmark = pytest.mark.smoke

N = 8
L = 0.2                       # the drum's side (tutorials/squareDrum)
OMEGA = math.pi / 5           # its rate of turn, rad/s
T = "1.25"                    # a turn of pi/4: the square stands on a corner
FIELDS = ("alpha.air", "alpha.small", "alpha.large", "p", "I", "illPosed")


def load_tool():
    """The installed granularPictures as a module (it has no .py suffix)."""
    path = executable("granularPictures")
    loader = importlib.machinery.SourceFileLoader("granularPictures", path)
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def drum(foam_env):
    case = small_drum("pictures/drum", n=N, end_time=T, delta_t="5e-3")
    foam(case, "granularSegregationFoam")
    foam(case, "granularPictures", "-latestTime")
    foam(case, "postProcess", "-time", T, "-func", "writeCellCentres")
    return case


def test_picture_written(drum):
    png = drum / "figures" / f"fields_{T}.png"
    assert png.is_file(), f"no {png}"
    assert png.stat().st_size > 20000, f"{png}: {png.stat().st_size} bytes"


def test_polygons_are_the_cells(drum):
    tool = load_tool()
    vtus = tool.foam_to_vtk(drum, [T], "VTK")
    assert len(vtus) == 1, vtus
    polygons, axes, thickness, fields = tool.cut(next(iter(vtus.values())))
    assert axes == (0, 1)
    assert len(polygons) == N * N

    # the tiling: total area, and the square turned by 45 degrees
    area = sum(0.5 * abs(np.dot(q[:, 0], np.roll(q[:, 1], 1))
                         - np.dot(q[:, 1], np.roll(q[:, 0], 1)))
               for q in polygons)
    assert area == pytest.approx(L * L, rel=1e-6)
    corners = np.concatenate(polygons)
    half_diagonal = L / math.sqrt(2)
    assert np.abs(corners).max(axis=0) == pytest.approx(
        [half_diagonal, half_diagonal], rel=1e-5)
    turned = OMEGA * float(T)
    assert turned == pytest.approx(math.pi / 4)

    # each polygon at its own cell's centre, one to one
    centres = read_field(drum, T, "C")[:, :2]
    centroids = np.array([q.mean(axis=0) for q in polygons])
    distance, cell = cKDTree(centres).query(centroids)
    assert distance.max() < 1e-6 * L, distance.max()
    assert np.unique(cell).size == N * N

    # and carrying that cell's values
    for name in FIELDS + ("U",):
        exact = read_field(drum, T, name)[cell]
        drawn = fields[name]
        scale = max(np.abs(exact).max(), 1e-30)
        assert np.abs(drawn - exact).max() <= 1e-6 * scale, name
    assert thickness > 0


def test_bad_options(drum):
    tool = executable("granularPictures")
    bad = [(["-time", "99"], "-time 99: not written"),
           (["-exaggeration", "-1"], "-exaggeration -1.0: must be > 0"),
           (["-case", str(drum / "system")], "is not a case")]
    for args, message in bad:
        run = subprocess.run([tool, "-case", str(drum)] + args,
                             capture_output=True, text=True)
        assert run.returncode != 0, args
        assert message in run.stderr, (args, run.stderr)

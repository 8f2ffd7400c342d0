"""Smoke tier: the tutorials' ParaView states (granularParaView), headless.

Every flow tutorial runs a few steps (the drum is the small drum of
test_pictures, turned by 45 degrees) and its own paraviewState.py is run by
pvbatch under Xvfb, as doc/visualisation.md (ParaView states) says.
Checked on the picture and on pvbatch's summary line:

- the PNG has the size of its grid of views, and every view shows the
  field: several colours in the mesh area (a chart: its curve);
- the threshold of the grain-only panels takes whole cells: its cells are
  exactly those with phi^a < 1/2 in the written field, the air threshold
  the rest;
- orientation: in the drum the air is above the grains; in a thin layer
  the inflow is on the left and the base at the bottom (a mirrored or
  upside-down camera fails), and the mesh is drawn with the stated
  vertical exaggeration;
- a case with no written time, a field not written, a directory that is
  not a case and an unknown option each fail with status 1 and a message
  naming the case and the field.

A missing pvbatch or Xvfb is a failure, never a skip.
"""
import os
import re
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

from cases import foam, fresh_case, small_drum
from granularfoam.post.chute import parameters, read_field, time_names
from conftest import committed_copy, executable

pytestmark = pytest.mark.smoke

SCREEN = "1920x1200x24"
WHITE = np.array([255, 255, 255])
SERIES = np.array([26, 77, 179])      # the charts' curve colour
VIEW = (480, 420)                     # granularParaView.VIEW, CHART, BAR
CHART = (230, 520)
BAR = 110
# Short runs: (Allrun end time, fields the state shows, grid of views)
RUNS = {
    "squareDrum": (None, 7, (4, 2)),
    "chute": ("0.05", 7, (1, 7)),
    "bulbousHead": ("0.1", 7, (1, 7)),
    "segregationColumn": ("0.2", 7, (7, 1)),
    "tridisperseColumn": ("0.2", 8, (8, 1)),
    "columnCollapse": ("0.05", 6, (3, 2)),
}
THIN = {"chute": 10.0, "bulbousHead": 8.0}    # their states' exaggerations
SUMMARY = re.compile(
    r"^(?P<png>\S+): (?P<cells>\d+) cells, (?P<grains>\d+) in the grains "
    r"\(phi\^a < 1/2\) and (?P<air>\d+) in the air by threshold, "
    r"t = (?P<t>\S+), fields (?P<fields>[^,]+), (?P<n>\d+) "
    r"(?P<kind>views|charts).*, (?P<ncol>\d+) x (?P<nrow>\d+), "
    r"(?P<w>\d+) x (?P<h>\d+) px$", re.M)


@pytest.fixture(scope="module")
def display(tmp_path_factory):
    """An Xvfb display for pvbatch (Debian's ParaView renders through GLX:
    --force-offscreen-rendering without a display aborts).  Xvfb chooses a
    free display number and writes it to -displayfd once it accepts
    clients: a display whose socket merely exists made the first pvbatch
    abort in glXCreate (seen once in 10 runs)."""
    xvfb = executable("Xvfb")
    executable("pvbatch")
    log = tmp_path_factory.mktemp("xvfb") / "Xvfb.log"
    ready_r, ready_w = os.pipe()
    with open(log, "w") as out:
        server = subprocess.Popen(
            [xvfb, "-displayfd", str(ready_w), "-screen", "0", SCREEN,
             "-nolisten", "tcp"],
            stdin=subprocess.DEVNULL, stdout=out, stderr=out,
            pass_fds=(ready_w,))
    os.close(ready_w)
    with os.fdopen(ready_r) as ready:
        number = ready.readline().strip()     # EOF if Xvfb exits
    assert server.poll() is None and number.isdigit(), (
        f"Xvfb did not start: {log.read_text()[-2000:]}")
    yield f":{number}", log
    server.terminate()
    server.wait(timeout=30)


@pytest.fixture(scope="module")
def runs(foam_env):
    """The tutorials' short runs, made once: {name: case}."""
    made = {}

    def run(name):
        if name not in made:
            end = RUNS[name][0]
            if end is None:
                case = small_drum(f"paraview/{name}", n=12, end_time="1.25",
                                  delta_t="5e-3")
                foam(case, "granularSegregationFoam")
            else:
                case = fresh_case(name, dest=f"paraview/{name}",
                                  tutorial=True)
                foam(case, "./Allrun", "-endTime", end,
                     "-writeInterval", end)
            made[name] = case
        return made[name]
    return run


def pvbatch(display, case, *args):
    """pvbatch on the case's paraviewState.py (the copy in the case)."""
    state = case / "paraviewState.py"
    assert state.is_file(), f"no {state}"
    name, log = display
    for attempt in (1, 2):
        res = subprocess.run(
            [executable("pvbatch"), str(state), *args], capture_output=True,
            text=True, timeout=300, env=dict(os.environ, DISPLAY=name))
        # Debian's pvbatch aborts now and then in creating its X window,
        # before the state runs (seen on a loaded machine): once more then
        if res.returncode == 0 or "CreateAWindow" not in res.stdout + res.stderr:
            break
    res.stderr += f"\n[Xvfb {name}, attempt {attempt}: {log.read_text()[-1000:]}]"
    return res


def colours(pixels, least=20):
    """The colours that cover at least `least` pixels, white left out."""
    flat = pixels.reshape(-1, 3)
    values, counts = np.unique(flat, axis=0, return_counts=True)
    keep = (counts >= least) & np.any(values != WHITE, axis=1)
    return values[keep]


def near(pixels, colour, tolerance=30):
    """Mask of the pixels within tolerance of colour."""
    return np.abs(pixels.astype(int) - colour).sum(axis=-1) <= tolerance


def regions(image, ncol, nrow, margin=8):
    """The pixels of each place of the grid, row by row, without the
    separators (the layout rounds its splits by a few pixels)."""
    h, w, _ = image.shape
    return [image[r * h // nrow + margin:(r + 1) * h // nrow - margin,
                  c * w // ncol + margin:(c + 1) * w // ncol - margin]
            for r in range(nrow) for c in range(ncol)]


@pytest.mark.parametrize("name", list(RUNS))
def test_state_renders_the_case(display, runs, name):
    """The tutorial's state renders its last time: the grid, the colours
    of every view, the whole-cell threshold, the orientation."""
    case = runs(name)
    _, nfields, (ncol, nrow) = RUNS[name]
    png = case / "figures" / "paraview.png"
    png.unlink(missing_ok=True)
    res = pvbatch(display, case, "--screenshot", str(png))
    assert res.returncode == 0, (res.stdout + res.stderr)[-3000:]
    m = SUMMARY.search(res.stdout)
    assert m, f"no summary line in:\n{res.stdout}"
    assert png.is_file(), f"pvbatch wrote no {png}"

    # the threshold: whole cells, exactly phi^a < 1/2 of the written field
    t = time_names(case)[-1]
    assert float(m["t"]) == pytest.approx(float(t))
    air = read_field(case, t, "alpha.air")
    assert int(m["cells"]) == air.size
    assert int(m["grains"]) == int(np.sum(air < 0.5))
    assert int(m["air"]) == int(np.sum(air >= 0.5))

    # the grid and the size of the picture
    fields = m["fields"].split()
    assert len(fields) == int(m["n"]) == nfields
    assert (int(m["ncol"]), int(m["nrow"])) == (ncol, nrow)
    image = np.asarray(Image.open(png).convert("RGB"))
    assert image.shape[1::-1] == (int(m["w"]), int(m["h"]))
    if m["kind"] == "charts":
        assert image.shape[1::-1] == (ncol * CHART[0], nrow * CHART[1])
    elif name == "squareDrum":
        assert image.shape[1::-1] == (ncol * VIEW[0], nrow * VIEW[1])
    else:
        assert max(image.shape[:2]) >= 1190      # scaled to the screen
        assert image.shape[1] <= 1920 and image.shape[0] <= 1200

    places = regions(image, ncol, nrow)
    if m["kind"] == "charts":
        for field, chart in zip(fields, places):
            curve = near(chart, SERIES, 60).sum()
            assert curve > 100, f"{name} {field}: {curve} pixels of curve"
        return
    views = {}
    for k, (field, view) in enumerate(zip(fields, places)):
        mesh = view[25 if k == 0 else 0:, :view.shape[1] - BAR]  # no title
        found = colours(mesh)
        need = 2 if field in ("illPosed", "I") or name in THIN else 4
        assert len(found) >= need, (
            f"{name} {field}: {len(found)} colours {found.tolist()}")
        views[field] = mesh
    for blank in places[len(fields):]:
        assert np.all(blank == WHITE), f"{name}: an empty place not blank"

    if name == "squareDrum":
        # phi^a (viridis): air yellow above the purple grains
        view = views["alpha.air"]
        rows = np.nonzero(near(view, np.array([253, 231, 37])))[0]
        grains = np.nonzero(near(view, np.array([68, 1, 84])))[0]
        assert rows.size > 100 and grains.size > 100
        assert rows.mean() < grains.mean() - 20, (rows.mean(), grains.mean())
        return

    if name == "columnCollapse":
        # phi^a (viridis): the column's purple grains against the left wall,
        # left of and below the yellow air
        view = views["alpha.air"]
        ya, xa = np.nonzero(near(view, np.array([253, 231, 37])))
        yg, xg = np.nonzero(near(view, np.array([68, 1, 84])))
        assert xa.size > 100 and xg.size > 100
        assert xg.mean() < xa.mean() - 20, (xg.mean(), xa.mean())
        assert yg.mean() > ya.mean(), (yg.mean(), ya.mean())
        return

    # a thin layer: the mesh box, the inflow's grains on the left, the base
    # at the bottom, the exaggeration
    par = parameters(case)
    view = views["I"]
    inside = ~near(view, WHITE, 6)
    ys, xs = np.nonzero(inside)
    top, bottom, left, right = ys.min(), ys.max(), xs.min(), xs.max()
    aspect = (right - left + 1) / (bottom - top + 1)
    assert aspect == pytest.approx(
        par["Lx"] / (THIN[name] * par["Lz"]), rel=0.04)
    level = view.astype(int)
    neutral = (np.ptp(level, axis=-1) < 8) & (level.min(axis=-1) >= 200)
    coloured = inside & ~neutral      # not the air's grey nor its edges
    cy, cx = np.nonzero(coloured)
    assert cx.size > 20, f"{name}: no grains drawn in the I view"
    assert cx.mean() < left + 0.1 * (right - left), "grains not on the left"
    assert cy.mean() > 0.5 * (top + bottom), "grains not at the bottom"


@pytest.fixture(scope="module")
def broken(runs, tmp_path_factory):
    """Copies of the drum's output: without its last time, without the
    field I there."""
    drum = runs("squareDrum")
    t = time_names(drum)[-1]
    out = {}
    for kind in ("notime", "nofield"):
        case = tmp_path_factory.mktemp("paraview") / f"drum_{kind}"
        shutil.copytree(drum, case)
        (case / "drum.foam").unlink(missing_ok=True)
        if kind == "notime":
            shutil.rmtree(case / t)
        else:
            (case / t / "I").unlink()
        out[kind] = case
    return out, t


def test_bad_cases(display, broken):
    """Not a case, no written time, a field not written, an unknown
    option: exit status 1, a message naming the case and the field, no
    picture."""
    cases, t = broken
    png = cases["notime"].parent / "never.png"
    bad = [(cases["notime"], [], f"{cases['notime']}: no written time"),
           (cases["nofield"], [],
            f"{cases['nofield']}: no field I at t = {float(t):g}"),
           (cases["nofield"], ["--case", str(cases["nofield"] / "system")],
            f"{cases['nofield'] / 'system'} is not a case"),
           (cases["nofield"], ["--colour"], "unknown option --colour")]
    for case, args, message in bad:
        res = pvbatch(display, case, "--screenshot", str(png), *args)
        assert res.returncode == 1, (args, res.returncode, res.stderr[-2000:])
        assert f"granularParaView: error: {message}" in res.stderr, (
            message, res.stderr[-2000:])
        assert not png.exists()


def test_every_flow_tutorial_has_a_state(tmp_path):
    """Every tutorial with a 0.orig (a flow case) has a paraviewState.py,
    tested above, naming every phase fraction of 0.orig (the tutorials as
    HEAD holds them)."""
    tutorials = committed_copy("tutorials", tmp_path / "tutorials")
    flows = sorted(p.parent.name for p in tutorials.glob("*/0.orig"))
    assert flows == sorted(RUNS)
    for name in flows:
        text = (tutorials / name / "paraviewState.py").read_text()
        for alpha in (tutorials / name / "0.orig").glob("alpha.*"):
            assert f'"{alpha.name}"' in text, (name, alpha.name)

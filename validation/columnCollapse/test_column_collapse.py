"""The column collapse (tutorials/columnCollapse): one grain phase, the
monodisperse mu(I) flow with the air segregated out of it.

The tutorial runs as its files say (1 cm cells, to 1.5 s) and on 5 mm cells,
side by side.  Checked:

1. the grain volume is conserved (the balance of the phase transport);
2. the deposit is at rest: its height at the wall no longer changes over
   the last half second, and its fastest grains move at the creep speed of
   the viscosity cap (about tau h / eta_max: 3.5e-5 m/s for 70 Pa under
   5 cm at eta_max = 1e5 Pa s), far below the collapse's 1 m/s;
3. the deposit's height at the wall is the same on 1 cm and 5 mm cells;
4. the column has spread: its front on the floor is well beyond the
   column's width L0.

The run-out itself is not mesh-converged on these meshes (the front moves
from 0.37 m on 1 cm to 0.45 m on 5 mm); it is recorded, not checked.

Numbers: validation/results/columnCollapse/columnCollapse.json.
"""
import subprocess

import numpy as np
import pytest

from cases import RESULTS, fresh_case, write_results
from columnCollapse import post

pytestmark = pytest.mark.validation

MESHES = {"1cm": (), "5mm": ("-nx", "120", "-nz", "60")}
REST = 0.5                  # [s] the last REST seconds: the deposit at rest


@pytest.fixture(scope="module")
def runs(foam_env):
    """Both meshes at once (one core each), to the tutorial's end time."""
    cases, procs = {}, {}
    for name, args in MESHES.items():
        case = fresh_case("columnCollapse", f"columnCollapse-{name}",
                          tutorial=True)
        cases[name] = case
        procs[name] = subprocess.Popen(
            ["./Allrun", "-serial", *args], cwd=case,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    for name, p in procs.items():
        out, _ = p.communicate(timeout=3600)
        assert p.returncode == 0, f"{name}: Allrun failed\n{out[-3000:]}"
        log = (cases[name] / "log.granularSegregationFoam").read_text()
        assert log.rstrip().endswith("End"), f"{name}: solver did not finish"
    numbers = {name: post.measure(case) for name, case in cases.items()}
    out = RESULTS / "columnCollapse"
    out.mkdir(parents=True, exist_ok=True)
    write_results(out, "columnCollapse", numbers)
    return cases, numbers


def _rest(numbers):
    """Wall heights over the last REST seconds."""
    t = np.array(numbers["times"])
    h = np.array(numbers["wall_height"])
    assert t[-1] - t[0] > REST, f"the run ends at {t[-1]} s"
    return h[t >= t[-1] - REST - 1e-9]


def test_column_collapse_volume(runs, check):
    """The grain volume over the run, both meshes."""
    _, numbers = runs
    check("column collapse: grain volume, largest relative change",
          max(n["volume_change"] for n in numbers.values()))


def test_column_collapse_at_rest(runs, check):
    """The deposit on 1 cm: height at the wall and fastest grains."""
    cases, numbers = runs
    n = numbers["1cm"]
    dz = float(post.parameters(cases["1cm"])["Lz"]) \
        / float(post.parameters(cases["1cm"])["nz"])
    h = _rest(n)
    check("column collapse: wall height over the last 0.5 s, range in cells",
          (h.max() - h.min()) / dz)
    check("column collapse: fastest grains at the end, m/s",
          n["fastest_grains_end"])
    # The collapse itself: the grains left the wall
    assert n["wall_height"][-1] < 0.5 * post.parameters(cases["1cm"])["H0"]


def test_column_collapse_mesh(runs, check):
    """The deposit's height at the wall on 1 cm against 5 mm cells."""
    _, numbers = runs
    h1, h5 = numbers["1cm"]["wall_height"][-1], \
        numbers["5mm"]["wall_height"][-1]
    check("column collapse: wall height, 1 cm against 5 mm, relative",
          abs(h1 - h5) / h5)


def test_column_collapse_spread(runs, check):
    """The front on the floor at the end over the column's width."""
    cases, numbers = runs
    L0 = post.parameters(cases["1cm"])["L0"]
    check("column collapse: front on the floor over L0, 1 cm",
          numbers["1cm"]["front"][-1] / L0)

"""Smoke tier: round-off in the mixture's diagnostics.

The base is validation/cases/staticColumn on 20 cells over its 5 mm: grains
in the lower half, air above, a few fixed steps with writes.

- Two identical phases (one size, Trewhela's segregation (3.9), which
  vanishes for R = 1), fully mixed, with the grain fractions -1e-13 in the
  air (as MULES leaves them where it undershoots): the run reaches its
  writes and every logged segregation index is finite and 0 (a uniform
  mix), every monitored invariant finite.
"""
import math
import re

import numpy as np
import pytest

from cases import edit, foam, fresh_case, log_reports, run
from conftest import executable

pytestmark = pytest.mark.smoke

NZ = 20                 # cells over the column's 5 mm
GRAIN_CELLS = 10        # grains in the lower half, air above
UNDERSHOOT = -1e-13     # a grain fraction in the air, as MULES leaves it
STEPS = 4               # fixed steps of DELTA_T, a write every 2
DELTA_T = 1e-5

GP = "constant/granularProperties"

def alpha_file(name, values):
    """An alpha.<name> field file of the column with the given cell values
    (written with 17 digits: -1e-13 stays -1e-13)."""
    cells = "\n".join(repr(float(v)) for v in values)
    return f"""FoamFile
{{
    version     2.0;
    format      ascii;
    class       volScalarField;
    location    "0";
    object      alpha.{name};
}}

dimensions      [0 0 0 0 0 0 0];
internalField   nonuniform List<scalar> {len(values)}
(
{cells}
);
boundaryField
{{
    "(base|top)"    {{ type zeroGradient; }}
    sides           {{ type empty; }}
}}
"""


def column(dest, phases):
    """The static column on NZ cells in validation/results/<dest>, meshed,
    with 0/ from 0.orig, STEPS fixed steps and a write every 2 steps, and a
    granularInvariants monitor of the phases (alpha.air first)."""
    case = fresh_case("staticColumn", dest=dest)
    edit(case / "system" / "blockMeshDict", [(r"\nnz\s+\d+;", f"\nnz  {NZ};")])
    monitor = " ".join(f"alpha.{p}" for p in phases)
    edit(case / "system" / "controlDict", [
        (r"\nendTime\s+[^;]+;", f"\nendTime {STEPS * DELTA_T:g};"),
        (r"\ndeltaT\s+[^;]+;", f"\ndeltaT {DELTA_T:g};"),
        (r"\nwriteControl\s+[^;]+;", "\nwriteControl timeStep;"),
        (r"\nwriteInterval\s+[^;]+;", "\nwriteInterval 2;"),
        (r"\nadjustTimeStep\s+yes;", "\nadjustTimeStep no;"),
        (r"\nfunctions\n\{.*\n\}\n",
         "\nfunctions\n{\n    invariants\n    {\n"
         "        type granularInvariants;\n"
         "        libs (\"libgranularRheology.so\");\n"
         f"        phases ({monitor});\n    }}\n}}\n"),
    ], flags=re.S)
    (case / "0").mkdir()
    for name in ("U", "p_rgh"):
        (case / "0" / name).write_text((case / "0.orig" / name).read_text())
    foam(case, "blockMesh")
    return case


def solve(case):
    """Run the solver; (exit status, log)."""
    res = run([executable("granularSegregationFoam")], case, timeout=300)
    return res.returncode, res.stdout + res.stderr


def invariants(case):
    """The granularInvariants table: (header names, rows)."""
    path = case / "postProcessing" / "invariants" / "0" / "granularInvariants.dat"
    assert path.is_file(), f"missing {path}"
    header, rows = None, []
    for line in path.read_text().splitlines():
        if line.startswith("# Time"):
            header = line[1:].split()
        elif line and not line.startswith("#"):
            rows.append(line.split())
    assert header and rows, f"empty {path}"
    return header, rows


# ---------------------------------------------------------------------------
# Two identical phases, fully mixed, round-off below zero in the air
# ---------------------------------------------------------------------------

def test_identical_mixed_phases_roundoff(foam_env):
    """Two identical, fully mixed phases with grain fractions -1e-13 in the
    air: the run reaches its writes, and the segregation index logged at the
    start and at each write is 0 (finite), the invariants finite."""
    case = column("monodisperse/identical", ("air", "small", "large"))
    # Trewhela's law (3.9) of two phases of one size: f = 0 (R = 1)
    edit(case / GP, [(r"model constant; f 7e-3;", "model Trewhela;")])
    grains = np.arange(NZ) < GRAIN_CELLS
    small = np.where(grains, 0.5, UNDERSHOOT)
    air = np.where(grains, 0.0, 1 - 2 * UNDERSHOOT)
    for name, values in (("air", air), ("small", small), ("large", small)):
        (case / "0" / f"alpha.{name}").write_text(alpha_file(name, values))

    rc, log = solve(case)
    (case / "log.granularSegregationFoam").write_text(log)
    assert rc == 0, f"exit {rc} (a signal if < 0):\n{log[-3000:]}"

    reports = log_reports(log)
    expected = ["0"] + [f"{k * DELTA_T:g}" for k in range(2, STEPS + 1, 2)]
    assert sorted(reports, key=float) == expected, (
        f"reports at {list(reports)}, expected {expected}")
    for time_name, (vols, index) in reports.items():
        assert index is not None, f"t = {time_name}: no segregation index"
        assert math.isfinite(index) and 0 <= index < 1e-6, (
            f"t = {time_name}: segregation index {index} of a uniform mix")
        assert all(math.isfinite(v) for v in vols.values()), vols

    header, rows = invariants(case)
    values = np.array([[float(x) for x in r] for r in rows])
    assert np.isfinite(values).all(), f"non-finite invariants:\n{rows}"
    assert (values[:, header.index("nonFinite")] == 0).all()

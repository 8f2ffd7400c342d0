"""Smoke tier: monodisperse cases and round-off in the mixture's diagnostics.

The base is validation/cases/staticColumn on 20 cells over its 5 mm: grains
in the lower half, air above, a few fixed steps with writes.

- Two identical phases (one size, Trewhela's segregation (3.9), which
  vanishes for R = 1), fully mixed, with the grain fractions -1e-13 in the
  air (as MULES leaves them where it undershoots): the run reaches its
  writes and every logged segregation index is finite and 0 (a uniform
  mix), every monitored invariant finite.
- One grain phase, the recipe of doc/model.md, without segregation and
  diffusion (or with both empty): setGranularFields sets it, the solver
  runs and writes, the log shows the phase volumes and no segregation
  index, the base pressure is the weight Phi rho_* g h of the grains (plus
  the air's), and granularPictures draws it.
- One grain phase given a pair law (segregation or diffusion): refused with
  a FatalIOError naming granularProperties, the keyword and the entry.
- The square drum (tutorials/squareDrum, 8 x 8) with one grain phase:
  setGranularFields sets it, and rotatingDrum, granularInvariants and the
  volumes monitor the phases through two steps.
"""
import math
import re

import numpy as np
import pytest

from cases import (NUMBER, edit, foam, foam_output, fresh_case, log_reports,
                   run, small_drum, volumes)
from conftest import PROJECT, executable
from granularfoam.foamio import read_field

pytestmark = pytest.mark.smoke

NZ = 20                 # cells over the column's 5 mm
GRAIN_CELLS = 10        # grains in the lower half, air above
H = 5e-3                # column height [m]
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


def table(case, function, name):
    """A function object's table postProcessing/<function>/0/<name>:
    (header names, rows of words)."""
    path = case / "postProcessing" / function / "0" / name
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

    assert_finite_invariants(case)


def assert_finite_invariants(case):
    """Every value of the granularInvariants monitor is finite, no cell holds
    a NaN."""
    header, rows = table(case, "invariants", "granularInvariants.dat")
    values = np.array([[float(x) for x in r] for r in rows])
    assert np.isfinite(values).all(), f"non-finite invariants:\n{rows}"
    assert (values[:, header.index("nonFinite")] == 0).all(), rows


# ---------------------------------------------------------------------------
# One grain phase
# ---------------------------------------------------------------------------

def doc_recipe():
    """The granularProperties of the monodisperse recipe of doc/model.md: the
    code block after its heading "Monodisperse (one grain phase)"."""
    text = (PROJECT / "doc" / "model.md").read_text()
    start = text.find("\n## Monodisperse (one grain phase)\n")
    assert start >= 0, "no monodisperse recipe in doc/model.md"
    m = re.search(r"\n```\n(.*?\n)```\n", text[start:], re.S)
    assert m, "no code block after the monodisperse recipe in doc/model.md"
    return m.group(1)

SET_FIELDS = f"""FoamFile
{{
    version     2.0;
    format      ascii;
    class       dictionary;
    location    "system";
    object      setGranularFieldsDict;
}}

grains
{{
    point       (0 0 {GRAIN_CELLS / NZ * H!r});
    normal      (0 0 1);
    fractions   {{ grains 1; }}
}}

velocity        (0 0 0);
"""


def one_phase(dest, pairs):
    """The column with the monodisperse granularProperties of doc/model.md,
    its one grain phase 'grains' in the lower half, set by setGranularFields;
    pairs: 'absent' (no segregation, no diffusion), 'empty' (both empty) or
    the text added to the recipe."""
    case = column(dest, ("air", "grains"))
    added = {"absent": "", "empty": "segregation { }\ndiffusion { }\n"}
    path = case / GP
    header = path.read_text()
    header = header[:header.index("// * * *")]
    path.write_text(header + doc_recipe() + added.get(pairs, pairs))
    for name in ("air", "grains"):
        (case / "0" / f"alpha.{name}").write_text(alpha_file(name, [0] * NZ))
    (case / "system" / "setGranularFieldsDict").write_text(SET_FIELDS)
    foam(case, executable("setGranularFields"))
    return case


def rheology_entry(case, key):
    """The first number given to key in constant/granularProperties."""
    text = (case / GP).read_text()
    m = re.search(rf"^\s*{key}\s+({NUMBER});", text, re.M)
    assert m, f"no {key} in {case / GP}"
    return float(m.group(1))


@pytest.mark.parametrize("pairs", ["absent", "empty"])
def test_one_grain_phase_runs(foam_env, pairs):
    """One grain phase, segregation and diffusion absent or empty: the run
    writes, logs the volumes and no segregation index; the base pressure is
    the grains' weight Phi rho_* g h plus the air's; granularPictures draws
    the written time."""
    case = one_phase(f"monodisperse/one_{pairs}", pairs)
    rc, log = solve(case)
    (case / "log.granularSegregationFoam").write_text(log)
    assert rc == 0, f"exit {rc} (a signal if < 0):\n{log[-3000:]}"

    reports = log_reports(log)
    last = f"{STEPS * DELTA_T:g}"
    assert last in reports, f"no report at the last write {last}: {reports}"
    for time_name, (vols, index) in reports.items():
        assert set(vols) == {"alpha.air", "alpha.grains"}, vols
        assert abs(vols["alpha.grains"] / vols["alpha.air"] - 1) < 1e-9, (
            f"t = {time_name}: grains fill half the column: {vols}")
        assert index is None, f"t = {time_name}: segregation index {index}"
    assert "Segregation index" not in log

    for name in ("alpha.grains", "alpha.air", "U", "p"):
        assert (case / last / name).is_file(), f"{name} not written at {last}"

    # Hydrostatic: p between the lowest and the highest cell centre is the
    # weight of the mixture, rho = phi^g Phi rho_* + phi^a rho^a (4.7a)
    p = read_field(case, last, "p")
    alpha = read_field(case, last, "alpha.grains")
    rho = (alpha * rheology_entry(case, "Phi") * rheology_entry(case, "rhoStar")
           + (1 - alpha) * rheology_entry(case, "rho"))
    weight = 9.81 * H / NZ * (rho.sum() - (rho[0] + rho[-1]) / 2)
    assert abs(p[0] - p[-1] - weight) < 1e-3 * weight, (
        f"base pressure {p[0]} Pa, top {p[-1]} Pa, weight {weight} Pa")

    out, _ = foam_output(case, executable("granularPictures"),
                         "-latestTime", "-name", "one")
    png = case / "figures" / f"one_{last}.png"
    assert png.is_file() and png.stat().st_size > 1000, out
    assert "alpha.grains" in out, out


@pytest.mark.parametrize("keyword,law", [
    ("segregation", "model constant; f 7e-3;"),
    ("diffusion", "model constant; D 1e-6;"),
])
def test_one_grain_phase_pair_refused(foam_env, keyword, law):
    """One grain phase with a pair law: a FatalIOError naming
    granularProperties, the keyword, the entry and the one grain phase;
    no crash, no field written."""
    entry = f"{keyword}\n{{\n    grainsGrains {{ phases (grains grains); {law} }}\n}}\n"
    case = one_phase(f"monodisperse/pair_{keyword}", entry)
    rc, log = solve(case)
    assert rc > 0, f"exit {rc} (a signal if < 0)\n{log[-3000:]}"
    assert "FOAM FATAL IO ERROR" in log, log[-3000:]
    message = log[log.index("FOAM FATAL"):]
    for word in ("granularProperties", keyword, "grainsGrains",
                 "one grain phase"):
        assert word in message, f"{word!r} not in\n{message[:2000]}"
    written = [d.name for d in case.iterdir()
               if re.fullmatch(r"[0-9.e+-]+", d.name) and d.name != "0"]
    assert not written, f"fields written: {written}"


# ---------------------------------------------------------------------------
# The square drum with one grain phase
# ---------------------------------------------------------------------------

def monodisperse_drum(case):
    """The drum's grains made one phase, 'grains', of the small grains' size
    and law, without pairs, in every file that names the phases; the
    monitors write every step."""
    edit(case / GP, [
        (r"\n    large\n    \{.*?\n    \}\n", "\n"),
        (r"\n    small\n    \{", "\n    grains\n    {"),
        (r"\nsegregation\n\{.*?\n\}\n", "\n"),
        (r"\ndiffusion\n\{.*?\n\}\n", "\n"),
    ], flags=re.S)
    edit(case / "system" / "setGranularFieldsDict",
         [(r"fractions\s+\{[^}]*\}", "fractions   { grains 1; }")])
    orig = case / "0.orig"
    (orig / "alpha.grains").write_text(
        (orig / "alpha.small").read_text().replace("alpha.small", "alpha.grains"))
    (orig / "alpha.small").unlink()
    (orig / "alpha.large").unlink()
    phases = r"\(alpha\.air alpha\.small alpha\.large\)"
    edit(case / "system" / "controlDict",
         [(phases, "(alpha.air alpha.grains)")] * 3 + [
             (r"field           alpha\.small;", "field alpha.grains;")]
         + [(r"writeInterval   0\.05;", "writeInterval 1e-4;")] * 4)


def test_one_grain_phase_drum(foam_env):
    """The square drum with one grain phase runs two steps; rotatingDrum
    writes a finite surface angle and peak speed (J is nan before a
    revolution), the invariants and the volumes are finite, and no
    segregation index is logged."""
    case = small_drum("monodisperse/drum", n=8, end_time="2e-4",
                      write_interval="1e-4", delta_t="1e-4",
                      prepare=monodisperse_drum)
    rc, log = solve(case)
    (case / "log.granularSegregationFoam").write_text(log)
    assert rc == 0, f"exit {rc} (a signal if < 0):\n{log[-3000:]}"
    assert "Segregation index" not in log

    header, rows = table(case, "drum", "rotatingDrum.dat")
    assert len(rows) == 2, f"drum monitor rows {rows}"
    for row in rows:
        assert row[header.index("J")] == "nan", row
        angle = float(row[header.index("surfaceAngle[deg]")])
        speed = float(row[header.index("peakSpeed[m/s]")])
        assert 0 <= angle <= 90 and math.isfinite(speed), row

    assert_finite_invariants(case)
    _, vols = volumes(case)
    assert set(vols) == {"alpha.air", "alpha.grains"}, set(vols)
    assert all(np.isfinite(v).all() and min(v) > 0 for v in vols.values())

"""An opening that grains fall through (doc/solver.md, "Openings"): the
column collapse (tutorials/columnCollapse, 1 cm cells) with a hole in its
floor under the column, cut from the walls by topoSet and createPatch.

1. The grains drain through it, and the volume each phase loses is the
   time integral of its outflow through the hole (the granularInvariants
   balance) to 1e-10, with continuity solved to round-off (p_rghFinal to
   1e-13; the balance follows the pressure tolerance, as on the chute).
2. granularInvariants writes the lowest grain pressure of each step, as
   the log gives it.
3. In air alone, the hole at the air's hydrostatic pressure below the
   open top (p = rho^a g L_z) leaves the air at rest; at p = 0 instead,
   the same as the top, the air is driven through the box.
"""
import json
import re
import shutil

import numpy as np
import pytest

from cases import (RESULTS, edit, foam, foam_output, fresh_case, volumes,
                   write_results)
from granularfoam.foamio import read_field
from granularfoam.foamio import function_table

pytestmark = pytest.mark.smoke

LZ = 0.3                  # box height, system/columnParameters
RHO_AIR = 1.0             # constant/granularProperties air rho
G = 9.81                  # constant/g
P_HYDROSTATIC = RHO_AIR * G * LZ
HOLE = (0.02, 0.05)       # x range of the hole in the floor [m]

TOPO_SET = """FoamFile { version 2.0; format ascii; class dictionary;
           object topoSetDict; }
actions
(
    {
        name    openingFaces;
        type    faceSet;
        action  new;
        source  boxToFace;
        box     (%r -1 -1e-4) (%r 1 1e-4);
    }
);
""" % HOLE

CREATE_PATCH = """FoamFile { version 2.0; format ascii; class dictionary;
           object createPatchDict; }
pointSync false;
patches
(
    {
        name            opening;
        patchInfo       { type patch; }
        constructFrom   set;
        set             openingFaces;
    }
);
"""

# The opening's conditions: what doc/solver.md gives
OPENING = {
    "p_rgh": "opening { type granularPrghPressure; p uniform %r; "
             "value uniform 0; }",
    "U": "opening { type pressureInletOutletVelocity; "
         "value uniform (0 0 0); }",
    "alpha.grains": "opening { type inletOutlet; inletValue uniform 0; "
                    "value uniform 0; }",
    "alpha.air": "opening { type inletOutlet; inletValue uniform 1; "
                 "value uniform 1; }",
}


def opening_case(dest, p_opening, grains, end_time):
    """The collapse with the hole at p = p_opening, set up and run serially
    (the manual route: blockMesh, topoSet, createPatch, 0, setFields);
    with grains, p_rghFinal solved to 1e-13."""
    case = fresh_case("columnCollapse", dest=f"opening/{dest}",
                      tutorial=True)
    (case / "system" / "topoSetDict").write_text(TOPO_SET)
    (case / "system" / "createPatchDict").write_text(CREATE_PATCH)
    for name, entry in OPENING.items():
        text = entry % p_opening if "%r" in entry else entry
        edit(case / "0.orig" / name,
             [(r"\n(    frontAndBack\s)", "\n    " + text + r"\n\1")])
    edit(case / "system" / "columnParameters",
         [(r"\nnx\s+[^;]+;", "\nnx 60;"), (r"\nnz\s+[^;]+;", "\nnz 30;"),
          (r"\nendTime\s+[^;]+;", f"\nendTime {end_time};"),
          (r"\nwriteInterval\s+[^;]+;", f"\nwriteInterval {end_time};")])
    edit(case / "system" / "controlDict",
         [(r"(invariants[^}]*writeInterval\s+)100;", r"\g<1>1;")], re.S)
    if grains:
        edit(case / "system" / "fvSolution",
             [(r"p_rghFinal      \{ \$p_rgh; relTol 0; \}",
               "p_rghFinal      { $p_rgh; tolerance 1e-13; relTol 0; }")])
    else:
        # Air at rest: OpenFOAM normalises the residual by the field's own
        # variation, which is zero, so GAMG ran its 1000 iterations a solve
        edit(case / "system" / "fvSolution",
             [(r"relTol          0.01;", "relTol          0.01;\n"
               "        maxIter         50;")])
    foam(case, "blockMesh")
    foam(case, "topoSet")
    foam(case, "createPatch", "-overwrite")
    shutil.copytree(case / "0.orig", case / "0")
    if grains:
        foam(case, "setFields")
    log, _ = foam_output(case, "granularSegregationFoam")
    return case, log


@pytest.fixture(scope="module")
def drained(foam_env):
    """The grains case, run to 0.2 s: (case, log)."""
    return opening_case("grains", P_HYDROSTATIC, grains=True,
                        end_time="0.2")


def test_grains_drain_and_balance(drained):
    case, _ = drained
    t, vol = volumes(case)
    v = np.array(vol["alpha.grains"])
    lost = (v[0] - v[-1]) / v[0]
    print(f"grains lost through the hole by t = {t[-1]} s: {lost:.1%}")
    assert lost > 0.02, f"only {lost:.3%} of the grains left through the hole"

    a = function_table(case, "invariants", "granularInvariants.dat")
    # columns: t, then balance, min, max of alpha.air and of alpha.grains,
    # max |sum - 1|, non-finite cells
    balance_air, balance_grains = np.abs(a[:, 1]), np.abs(a[:, 4])
    print(f"largest balance: air {balance_air.max():.2e}, grains "
          f"{balance_grains.max():.2e}")
    assert len(a) > 50, f"only {len(a)} rows of invariants"
    assert balance_grains.max() < 1e-10, balance_grains.max()
    assert balance_air.max() < 1e-10, balance_air.max()
    record({"grains_lost_fraction": float(lost), "end_time": float(t[-1]),
            "largest_balance_air": float(balance_air.max()),
            "largest_balance_grains": float(balance_grains.max())})
    assert a[:, 5].min() > -1e-12 and a[:, 6].max() < 1 + 1e-12, (
        "alpha.grains outside [0, 1]")
    assert (a[:, 8] == 0).all(), "non-finite cells"


def test_invariants_report_grain_pressure(drained):
    """granularInvariants writes, after each step, the lowest pressure seen
    by the rheology in the grains, as the solver's log gives it."""
    case, log = drained
    lines = re.findall(r"^Grain pressure seen by the rheology: min = (\S+) Pa",
                       log, re.M)
    path = sorted((case / "postProcessing" / "invariants").glob(
        "*/granularInvariants.dat"))[-1]
    header = [h for h in path.read_text().splitlines()
              if h.startswith("#")][-1]
    names = header.split()[1:]         # "Time", then the columns
    assert "minGrainPressure" in names, header
    k = names.index("minGrainPressure")
    a = function_table(case, "invariants", "granularInvariants.dat")
    steps = log.count("\nTime = ")
    assert len(a) == steps and len(lines) == steps + 1, (
        f"{len(a)} rows, {len(lines)} log lines, {steps} steps")
    logged = np.array([float(x) for x in lines[1:]])
    assert np.allclose(a[:, k], logged, rtol=1e-9, atol=1e-9), (
        np.abs(a[:, k] - logged).max())


def record(numbers):
    """Merge numbers into validation/results/opening/opening.json."""
    path = RESULTS / "opening" / "opening.json"
    old = json.loads(path.read_text()) if path.exists() else {}
    old.update(numbers)
    write_results(RESULTS / "opening", "opening", old)


def _max_speed(case, end_time):
    return float(np.linalg.norm(read_field(case, end_time, "U"),
                                axis=1).max())


def test_air_at_rest_with_hydrostatic_opening(foam_env):
    end = "0.01"
    still = _max_speed(opening_case("air_hydrostatic", P_HYDROSTATIC,
                                    grains=False, end_time=end)[0], end)
    driven = _max_speed(opening_case("air_p0", 0.0, grains=False,
                                     end_time=end)[0], end)
    record({"air_alone_end_time": float(end),
            "air_speed_hydrostatic_opening": still,
            "air_speed_opening_at_0_Pa": driven})
    print(f"largest air speed at {end} s: hole at rho^a g L_z "
          f"{still:.2e} m/s, at 0 Pa {driven:.2e} m/s")
    assert still < 1e-6, f"air moves at {still:.3e} m/s"
    assert driven > 1e3 * max(still, 1e-9), (
        f"at p = 0 the air moves at only {driven:.3e} m/s")

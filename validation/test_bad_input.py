"""Bad input: every malformed case stops before the first time step with a
FatalIOError (or FatalError) that names the file, the keyword and the bad
value; never a crash, a core dump, or a written field.

The base case is the square drum (tutorials/squareDrum) on 8 x 8 cells,
set up once; each test copies it, breaks one entry, and runs the solver
for one step.  Its well-formed copy runs (test_base_runs), so a failure
below is the broken entry's.
"""
import re
import shutil

import pytest

from cases import edit, run, sidewall_friction, small_drum
from granularfoam.foamio import time_names

pytestmark = pytest.mark.smoke

GP = "constant/granularProperties"
FV = "system/fvSolution"
CD = "system/controlDict"
DM = "constant/dynamicMeshDict"

SMALL_BG = (r"frictionLaw     BarkerGray;\n        BarkerGrayCoeffs\n"
            r"        \{[^}]*\}")

INTERNAL = r"internalField\s+nonuniform\s+List<scalar>\s*\d+\s*\(.*?\)\s*;"

# (id, file, pattern, replacement, words the message must contain)
CASES = [
    ("no-grains", GP, r"\ngrains\n\{.*?\n\}\n", "\n",
     ["granularProperties", "grains"]),
    ("no-segregation", GP, r"\nsegregation\n\{.*?\n\}\n", "\n",
     ["granularProperties", "segregation"]),
    ("no-diffusion", GP, r"\ndiffusion\n\{.*?\n\}\n", "\n",
     ["granularProperties", "diffusion"]),
    ("no-air", GP, r"\nair\n\{.*?\n\}\n", "\n",
     ["granularProperties", "air"]),
    ("no-friction-law", GP, r"frictionLaw     BarkerGray;", "",
     ["granularProperties", "frictionLaw"]),
    ("unknown-friction-law", GP, r"frictionLaw     BarkerGray;",
     "frictionLaw     BarkerGrey;",
     ["granularProperties", "frictionLaw", "BarkerGrey", "BarkerGray"]),
    ("unknown-segregation", GP, r"model       Trewhela;",
     "model       Trewela;",
     ["granularProperties", "model", "Trewela", "Trewhela"]),
    ("unknown-diffusion", GP, r"model       UtterBehringer;",
     "model       Utter;",
     ["granularProperties", "model", "Utter", "UtterBehringer"]),
    ("unknown-mixture-rule", GP, r"mixtureRule     weightedFriction;",
     "mixtureRule     weighted;",
     ["granularProperties", "mixtureRule", "weighted"]),
    ("unknown-sharpening", GP, r"sharpening      segregation;",
     "sharpening      sharp;",
     ["granularProperties", "sharpening", "sharp"]),
    ("d-zero", GP, r"d               1e-3;", "d               0;",
     ["granularProperties", "d", "0"]),
    ("d-negative", GP, r"d               2e-3;", "d               -2e-3;",
     ["granularProperties", "d", "-0.002"]),
    ("rhoStar-negative", GP, r"rhoStar         2500;",
     "rhoStar         -2500;",
     ["granularProperties", "rhoStar", "-2500"]),
    ("air-rho-zero", GP, r"rho             1;", "rho             0;",
     ["granularProperties", "rho", "0"]),
    ("Phi-above-one", GP, r"Phi             0.6;", "Phi             1.2;",
     ["granularProperties", "Phi", "1.2"]),
    ("etaMax-zero", GP, r"etaMax          \$etaMax;",
     "etaMax          0;", ["granularProperties", "etaMax", "0"]),
    ("Jop-mus-above-mud", GP, SMALL_BG,
     "frictionLaw Jop; JopCoeffs { mus 0.8; mud 0.5; I0 0.5106; }",
     ["granularProperties", "mus", "0.8", "mud"]),
    ("BarkerGray-mus-above-mud", GP, r"mus     0.3671359;",
     "mus     0.9;", ["granularProperties", "mus", "0.9", "mud"]),
    ("pair-unknown-phase", GP, r"phases      \(small large\);\n        model       Trewhela",
     "phases      (small medium);\n        model       Trewhela",
     ["granularProperties", "phases", "medium"]),
    ("pair-twice", GP, r"\}\n\ndiffusion\n\{",
     "    twice { phases (large small); model constant; f 1e-3; }\n}\n"
     "\ndiffusion\n{",
     ["granularProperties", "small", "large"]),
    ("diffusion-air-grains", GP, r"phases      \(small large\);\n        model       UtterBehringer",
     "phases      (air small);\n        model       UtterBehringer",
     ["granularProperties", "phases", "air"]),
    ("negative-Trewhela-B", GP, r"B 0.3744;", "B -0.3744;",
     ["granularProperties", "B", "-0.3744"]),
    ("zero-air-direction", GP, r"direction       antiGravity;",
     "direction       (0 0 0);",
     ["granularProperties", "direction", "(0 0 0)"]),
    ("air-direction-without-gravity", "constant/g",
     r"value\s+\([^)]*\);", "value (0 0 0);",
     ["granularProperties", "direction", "antiGravity", "zero"]),
    ("unknown-air-direction", GP, r"direction       antiGravity;",
     "direction       upwards;",
     ["granularProperties", "direction", "upwards"]),
    ("zero-body-force-direction", GP, r"\nsegregation\n\{",
     "\nbodyForceDirections ((1 0 0) (0 0 0));\n\nsegregation\n{",
     ["granularProperties", "bodyForceDirections", "(0 0 0)"]),
    ("negative-tension-warning", GP, r"\nsegregation\n\{",
     "\ntensionWarning -5;\n\nsegregation\n{",
     ["granularProperties", "tensionWarning", "-5"]),
    ("negative-air-f", GP, r"f               1;", "f               -1;",
     ["granularProperties", "f", "-1"]),
    ("alpha-above-one", "0/alpha.small", INTERNAL,
     "internalField   uniform 1.5;",
     ["alpha.small", "1.5"]),
    ("alpha-wrong-dimensions", "0/alpha.small", r"dimensions\s+\[[^\]]*\];",
     "dimensions      [0 1 0 0 0 0 0];",
     ["0/alpha.small", "dimensions", "[0 1 0 0 0 0 0]", "dimensionless"]),
    ("alphas-not-summing", "0/alpha.air", INTERNAL,
     "internalField   uniform 0.5;",
     ["sum", "1"]),
    ("nan-velocity", "0/U", r"internalField\s+nonuniform\s+List<vector>\s*\d+\s*\(.*?\)\s*\)\s*;",
     "internalField   uniform (nan 0 0);", ["U"]),
    ("implicit-without-predictor", FV, r"momentumPredictor   yes;",
     "momentumPredictor   no;",
     ["fvSolution", "viscousStress", "implicit", "momentumPredictor"]),
    ("unknown-viscous-stress", FV, r"viscousStress       implicit;",
     "viscousStress       semi;",
     ["fvSolution", "viscousStress", "semi"]),
    ("d-not-a-number", GP, r"d               1e-3;", "d               abc;",
     ["granularProperties", "d", "abc", "number"]),
    ("grains-not-a-dictionary", GP, r"\ngrains\n\{.*?\n\}\n", "\ngrains 5;\n",
     ["granularProperties", "grains", "5", "sub-dictionary"]),
    ("air-not-a-dictionary", GP, r"\nair\n\{.*?\n\}\n", "\nair 1;\n",
     ["granularProperties", "air", "1", "sub-dictionary"]),
    ("unknown-transpose-stress", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    transposeStress     half;",
     ["fvSolution", "transposeStress", "half", "gradEta"]),
    ("unknown-pressure-coupling", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    pressureCoupling    SIMPLE;",
     ["fvSolution", "pressureCoupling", "SIMPLE", "SIMPLEC"]),
    ("unknown-krylov-preconditioner", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    Krylov { preconditioner ILU; }",
     ["fvSolution", "preconditioner", "ILU", "BFBt"]),
    ("zero-krylov-iterations", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    Krylov { maxIter 0; }",
     ["fvSolution", "maxIter", "0"]),
    ("krylov-tolerance-above-one", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    Krylov { tolerance 2; }",
     ["fvSolution", "tolerance", "2"]),
    ("negative-krylov-inner-tolerance", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    Krylov { innerRelTol -0.1; }",
     ["fvSolution", "innerRelTol", "-0.1"]),
    ("krylov-not-a-dictionary", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    Krylov 5;",
     ["fvSolution", "Krylov", "5", "sub-dictionary"]),
    ("zero-krylov-final-iterations", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    KrylovFinal { maxIter 0; }",
     ["fvSolution", "KrylovFinal", "maxIter", "0"]),
    ("krylov-final-not-a-dictionary", FV, r"viscousStress       implicit;",
     "viscousStress       implicit;\n    KrylovFinal 5;",
     ["fvSolution", "KrylovFinal", "5", "sub-dictionary"]),
    ("zero-correctors", FV, r"nCorrectors         \d+;",
     "nCorrectors         0;",
     ["fvSolution", "nCorrectors", "0"]),
    ("negative-pressure-tolerance", FV, r"nCorrectors         (\d+);",
     "nCorrectors         \\1;\n    pRghTolerance       -1e-3;",
     ["fvSolution", "pRghTolerance", "-0.001"]),
    ("negative-rheology-correctors", FV, r"nCorrectors         (\d+);",
     "nCorrectors         \\1;\n    nRheologyCorrectors -1;",
     ["fvSolution", "nRheologyCorrectors", "-1"]),
    ("unknown-start-pressure", FV, r"nCorrectors         (\d+);",
     "nCorrectors         \\1;\n    startPressure       rho;",
     ["fvSolution", "startPressure", "rho", "p_rgh"]),
    ("zero-max-sub-cycles", FV, r"maxAlphaSubCycles 5;",
     "maxAlphaSubCycles 0;",
     ["fvSolution", "maxAlphaSubCycles", "0"]),
    ("fixed-and-adaptive-sub-cycles", FV, r"maxAlphaSubCycles 5;",
     "nAlphaSubCycles 2; maxAlphaSubCycles 3;",
     ["fvSolution", "nAlphaSubCycles", "maxAlphaSubCycles", "2", "3"]),
    ("unknown-transport-flux", FV, r"maxAlphaSubCycles 5;",
     "maxAlphaSubCycles 5; transportFlux endOfStep;",
     ["fvSolution", "transportFlux", "endOfStep", "midStep"]),
    ("drum-interval-not-dividing", CD,
     r"writeInterval   0.05;               // divides",
     "writeInterval   0.03;               // divides",
     ["controlDict", "writeInterval", "0.03"]),
    ("drum-zero-axis", DM, r"axis        \(0 0 1\);", "axis        (0 0 0);",
     ["dynamicMeshDict", "axis", "(0 0 0)"]),
    ("drum-unknown-field", CD, r"field           alpha\.small;",
     "field           alpha.medium;",
     ["controlDict", "field", "alpha.medium", "alpha.small"]),
    ("invariants-unknown-phase", CD,
     r"phases          \(alpha\.air alpha\.small alpha\.large\);",
     "phases          (alpha.air alpha.medium);",
     ["controlDict", "phases", "alpha.medium", "alpha.small"]),
]


@pytest.fixture(scope="module")
def base(foam_env):
    """The drum on 8 x 8 cells, ascii and uncompressed, set up, one step of
    1e-4 s (no time is written)."""
    return small_drum("bad_input/base", n=8, end_time="1e-4",
                      write_interval="0.625", delta_t="1e-4")


def _solve(case):
    res = run(["granularSegregationFoam"], case, timeout=120)
    return res.returncode, res.stdout + res.stderr


def test_base_runs(base, tmp_path):
    """The unbroken copy runs its step and ends."""
    case = tmp_path / "ok"
    shutil.copytree(base, case)
    rc, out = _solve(case)
    assert rc == 0, out[-2000:]
    assert "\nEnd" in out


@pytest.mark.parametrize("name,path,pattern,replacement,words", CASES,
                         ids=[c[0] for c in CASES])
def test_refused(base, tmp_path, name, path, pattern, replacement, words):
    case = tmp_path / name
    shutil.copytree(base, case)
    edit(case / path, [(pattern, replacement)], flags=re.S)
    before = {t: sorted(p.name for p in (case / t).iterdir())
              for t in time_names(case, field=None)}

    _assert_refused(case, name, words, before)


def test_unread_phase_file_warns(base, tmp_path):
    """A 0/alpha.<name> file that matches no phase (a misspelt or a
    left-over phase) is not read, and the log says so, naming the file;
    the run goes on."""
    case = tmp_path / "unread-phase-file"
    shutil.copytree(base, case)
    shutil.copy(case / "0" / "alpha.small", case / "0" / "alpha.smal")
    rc, out = _solve(case)
    assert rc == 0, out[-2000:]
    warnings = [w for w in re.findall(r"--> FOAM Warning :.*?\n\n", out, re.S)
                if "is not read" in w]
    assert len(warnings) == 1, out[:4000]
    assert "0/alpha.smal\" is not read" in warnings[0], warnings[0]
    assert "alpha.small" in warnings[0], warnings[0]


def test_cahouet_chabard_needs_euler_or_backward(base, tmp_path):
    """The Krylov coupling's CahouetChabard preconditioner takes the
    coefficient of rho/dt of the Euler or the backward time derivative:
    with another ddt scheme the solver stops at its first use with a
    FatalIOError naming fvSchemes, the preconditioner and the scheme."""
    case = tmp_path / "cahouet-chabard-crank-nicolson"
    shutil.copytree(base, case)
    edit(case / FV, [(r"nCorrectors         \d+;",
                      "nCorrectors         1;\n    pressureCoupling    Krylov;"
                      "\n    Krylov { preconditioner CahouetChabard; }")])
    edit(case / "system/fvSchemes",
         [(r"default Euler;", "default CrankNicolson 0.9;")])
    before = {t: sorted(p.name for p in (case / t).iterdir())
              for t in time_names(case, field=None)}
    _assert_refused(case, "cahouet-chabard-crank-nicolson",
                    ["fvSchemes", "CahouetChabard", "Euler or backward",
                     "CrankNicolson"],
                    before)


# The sidewall friction (constant/fvOptions, granularSidewallFriction):
# (id, entries set on the drum's fvOptions.sidewall (None: removed), words)
SIDEWALL_CASES = [
    ("sidewall-muW-negative", {"muW": -1}, ["fvOptions", "muW", "-1"]),
    ("sidewall-W-zero", {"W": 0}, ["fvOptions", "W", "0", "> 0"]),
    ("sidewall-W-negative", {"W": -0.01}, ["fvOptions", "W", "-0.01"]),
    ("sidewall-no-muW", {"muW": None}, ["fvOptions", "Missing", "muW"]),
    ("sidewall-no-W", {"W": None}, ["fvOptions", "Missing", "'W'"]),
    ("sidewall-uSmall-zero", {"uSmall": 0}, ["fvOptions", "uSmall", "0"]),
    ("sidewall-unknown-wall-motion", {"wallVelocity": "spinning"},
     ["fvOptions", "wallVelocity", "spinning", "rotation"]),
]


def test_sidewall_runs(base, tmp_path):
    """The drum's fvOptions.sidewall as it is is selected and runs its
    step."""
    case = tmp_path / "sidewall-ok"
    shutil.copytree(base, case)
    sidewall_friction(case)
    rc, out = _solve(case)
    assert rc == 0, out[-2000:]
    assert "options type granularSidewallFriction" in out, out[-3000:]
    assert "walls turning with the mesh" in out, out[-3000:]


@pytest.mark.parametrize("name,entries,words", SIDEWALL_CASES,
                         ids=[c[0] for c in SIDEWALL_CASES])
def test_sidewall_refused(base, tmp_path, name, entries, words):
    case = tmp_path / name
    shutil.copytree(base, case)
    sidewall_friction(case, **entries)
    before = {t: sorted(p.name for p in (case / t).iterdir())
              for t in time_names(case, field=None)}
    _assert_refused(case, name, words, before)


# system/setGranularFieldsDict, read by setGranularFields:
# (id, pattern, replacement, words the message must contain)
SF = "system/setGranularFieldsDict"
SET_FIELDS_CASES = [
    ("fractions-sum", r"fractions   \{[^}]*\}",
     "fractions   { small 0.5; large 0.4; }",
     ["setGranularFieldsDict", "fractions", "0.9", "not 1"]),
    ("fraction-above-one", r"fractions   \{[^}]*\}",
     "fractions   { small 1.5; large 0; }",
     ["setGranularFieldsDict", "small", "1.5", "[0, 1]"]),
    ("fraction-negative", r"fractions   \{[^}]*\}",
     "fractions   { small -0.5; large 1.5; }",
     ["setGranularFieldsDict", "small", "-0.5"]),
    ("fraction-unknown-phase", r"fractions   \{[^}]*\}",
     "fractions   { small 0.5; medium 0.5; }",
     ["setGranularFieldsDict", "medium", "small", "large"]),
    ("normal-zero", r"normal      \([^)]*\);", "normal      (0 0 0);",
     ["setGranularFieldsDict", "normal", "(0 0 0)"]),
    ("velocity-unknown", r"velocity        rotation;",
     "velocity        spinning;",
     ["setGranularFieldsDict", "velocity", "spinning", "rotation"]),
]


@pytest.mark.parametrize("name,pattern,replacement,words", SET_FIELDS_CASES,
                         ids=[c[0] for c in SET_FIELDS_CASES])
def test_set_fields_refused(base, tmp_path, name, pattern, replacement,
                            words):
    """setGranularFields stops with a FatalIOError naming the dictionary,
    the keyword and the value, and leaves every file of the start time as
    it was (the files of 0.orig, so that a write would change them)."""
    case = tmp_path / name
    shutil.copytree(base, case)
    shutil.rmtree(case / "0")
    shutil.copytree(case / "0.orig", case / "0")
    edit(case / SF, [(pattern, replacement)], flags=re.S)
    before = {p.name: p.read_bytes() for p in (case / "0").iterdir()}

    res = run(["setGranularFields"], case, timeout=120)
    out = res.stdout + res.stderr
    assert res.returncode > 0, f"{name}: exit {res.returncode}\n{out[-3000:]}"
    assert "FOAM FATAL IO ERROR" in out, out[-3000:]
    message = _fatal_message(out)
    missing = [w for w in words if w not in message]
    assert not missing, f"{name}: {missing} not in\n{message[:2000]}"
    after = {p.name: p.read_bytes() for p in (case / "0").iterdir()}
    assert after == before, f"{name}: files of 0 changed"


def _fatal_message(out):
    """OpenFOAM's fatal message in out, without the function signature and
    source file it prints after it (which name types such as the
    enumerations, so a keyword found there is not the message's)."""
    return "\n".join(
        line for line in out[out.index("FOAM FATAL"):].splitlines()
        if not line.strip().startswith(("From ", "in file ")))


def _assert_refused(case, name, words, before):
    """The solver exits non-zero with a FOAM FATAL message holding every
    word (_fatal_message), no core dump, and writes no field."""
    rc, out = _solve(case)

    assert rc > 0, f"{name}: exit {rc} (a signal if < 0)\n{out[-3000:]}"
    assert "core dumped" not in out.lower() and "sigsegv" not in out.lower()
    assert "FOAM FATAL" in out, out[-3000:]
    message = _fatal_message(out)
    missing = [w for w in words if w not in message]
    assert not missing, f"{name}: {missing} not in\n{message[:2000]}"
    after = {t: sorted(p.name for p in (case / t).iterdir())
             for t in time_names(case, field=None)}
    assert after == before, f"{name}: fields written: {after}"

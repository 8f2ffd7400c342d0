"""Case generation for the benchmark (bench/README.md).

A case directory is the overlay of template trees from bench/cases/:

    common/                 mesh, controlDict, fvSchemes, fvSolution,
                            decomposeParDict, setFieldsDict, g
    <case>/                 0.orig: 'chute' (open box, the tutorial's inflow)
                            or 'drum' (the same box closed)
    stock/                  multiphaseInterFoam: transportProperties
    granular/<case>/        granularSegregationFoam: granularProperties

plus two generated files: system/benchParameters (mesh, time step, number of
steps, time-step control, application) and system/inletProfile (the chute's
inflow tabulated on the inlet faces).  The implicit configuration of the
granular solver ('granular-implicit') is the granular case with three
entries of its system/fvSolution changed by foamDictionary (IMPLICIT), the
Krylov configuration ('granular-krylov') the granular case with the chute
tutorial's coupling (KRYLOV).  Then
blockMesh, setFields and, for MPI runs, decomposePar.  Nothing here is
edited by hand after generation.
"""

import functools
import math
import os
import shutil
import subprocess
from pathlib import Path

BENCH = Path(__file__).resolve().parent
TEMPLATES = BENCH / "cases"
REPO = BENCH.parent

CASES = ("chute", "drum")
SOLVERS = ("stock", "granular", "granular-implicit", "granular-krylov")
APPLICATION = {"stock": "multiphaseInterFoam",
               "granular": "granularSegregationFoam",
               "granular-implicit": "granularSegregationFoam",
               "granular-krylov": "granularSegregationFoam"}

# 'granular-implicit': the common fvSolution with these PIMPLE entries set by
# foamDictionary on the generated case: the viscous stress solved implicitly
# in the momentum predictor (its part of (4.11) no longer limits Delta t),
# and the 20 pressure correctors of tutorials/chute
IMPLICIT = {
    "PIMPLE/momentumPredictor": "yes",
    "PIMPLE/viscousStress": "implicit",
    "PIMPLE/nCorrectors": "20",
}

# 'granular-krylov': the chute tutorial's default coupling, these entries
# of tutorials/chute/system/fvSolution read at generation time (so the
# benchmark follows the tutorial) and set on the common fvSolution; with the
# time step adjusted, also the tutorial's maxCo (controlDict) and maxDeltaT
# (chuteParameters) (KRYLOV_STEP)
KRYLOV = (
    "PIMPLE/momentumPredictor",
    "PIMPLE/viscousStress",
    "PIMPLE/pressureCoupling",
    "PIMPLE/Krylov",
    'solvers/"alpha.*"/maxAlphaSubCycles',
)
KRYLOV_STEP = {"maxCo": "system/controlDict",
               "maxDeltaT": "system/chuteParameters"}

# Time-step control (controlDict, through benchParameters): fixed Delta t
# for the time per cell and step, or adjusted to the total CFL (4.11) for
# the time per simulated second
FIXED_STEP = {"adjustTimeStep": "no", "maxCo": 0.9, "maxAlphaCo": 0.9,
              "maxDeltaT": 1}
ADJUSTABLE_STEP = {"adjustTimeStep": "yes", "maxCo": 0.9, "maxAlphaCo": 0.9}

# Files taken from tutorials/chute as they are, at generation time (so the
# benchmark follows the tutorial): {file in the case: for which solvers}
FROM_TUTORIAL = {
    "system/fvSchemes": "all",
    "constant/g": "all",
    "constant/turbulenceProperties": "all",
    "constant/granularProperties": "granular chute",
    "system/chuteParameters": "granular chute",    # granularProperties' d
}

# The chute's box and grain layer (tutorials/chute/system/chuteParameters)
LX = 0.62       # [m]
LZ = 6.2e-3     # [m]
H = 5e-3        # [m]

# Fixed time step: this fraction of the viscous limit of the granular
# solver's CFL (4.11), (eta_max/rho_grains) G dt, with the larger eta_max of
# the two cases (the chute's 2 Pa s) and G = 0.5 sum_f |S_f| delta_f / V at
# its largest, in a corner cell: 1.5 (1/dx^2 + 1/dz^2) (a wall face's
# delta is 2/dx)
VISCOUS_CFL = 0.8


def foam_value(path, entry):
    """One entry of an OpenFOAM dictionary, through foamDictionary, run in
    the dictionary's case (where its #include "$FOAM_CASE/..." resolve)."""
    path = Path(path).resolve()
    case = (path.parent.parent if path.parent.name in ("system", "constant")
            else path.parent)
    out = subprocess.run(
        ["foamDictionary", str(path), "-entry", entry, "-value"],
        check=True, capture_output=True, text=True, cwd=case,
        env=dict(os.environ, PWD=str(case))).stdout
    return out.strip()


def foam_scalar(path, entry):
    return float(foam_value(path, entry))


def gravity():
    """g from tutorials/chute/constant/g: (|g|, sin zeta, cos zeta)."""
    text = foam_value(REPO / "tutorials/chute/constant/g", "value")
    gx, gy, gz = (float(c) for c in text.strip("()").split())
    mag = math.sqrt(gx * gx + gy * gy + gz * gz)
    return mag, gx / mag, -gz / mag


def granular_properties(case):
    """constant/granularProperties of a case: the tutorial's for the chute,
    the template's for the drum-like box."""
    if case == "chute":
        return REPO / "tutorials/chute/constant/granularProperties"
    return TEMPLATES / f"granular/{case}/constant/granularProperties"


def grain_density():
    """Phi*rhoStar of the granular cases (and rho of stock's grain phases)."""
    props = granular_properties("chute")
    return foam_scalar(props, "Phi") * foam_scalar(props, "rhoStar")


def eta_max():
    return max(
        foam_scalar(granular_properties(case), "etaMax")
        for case in CASES)


def delta_t(nx, nz):
    """The fixed time step of every run on an nx x nz mesh, rounded down to
    one significant digit."""
    nu = eta_max() / grain_density()
    limit = VISCOUS_CFL / (nu * 1.5 * ((nx / LX) ** 2 + (nz / LZ) ** 2))
    scale = 10.0 ** math.floor(math.log10(limit))
    return math.floor(limit / scale) * scale


class Bagnold:
    """The chute's inflow, as BagnoldInletVelocity computes it
    (src/granularRheology/BagnoldFlow): Bagnold (5.4) with
    I_zeta = mu^-1(tan zeta) of the small grains' Barker-Gray law (5.6),
    and the air profile (5.7) (ERRATA 4) above h."""

    def __init__(self):
        props = granular_properties("chute")
        law = "grains.small.BarkerGrayCoeffs."
        assert foam_value(props, "grains.small.frictionLaw") == "BarkerGray"
        mus, mud, mu_inf, i0, i1 = (
            foam_scalar(props, law + k)
            for k in ("mus", "mud", "muInf", "I0", "I1"))
        self.d = foam_scalar(props, "grains.small.d")
        self.phi = foam_scalar(props, "Phi")
        self.rho_air = foam_scalar(props, "air.rho")
        self.eta_air = foam_scalar(props, "air.eta")
        self.g, self.sin, self.cos = gravity()
        mu = self.sin / self.cos
        # Above I_1 (the high branch, (2.8)): the positive root of
        # mu_inf I^2 + (mu_d - mu) I + (mu_s - mu) I_0 = 0
        assert (mus * i0 + mud * i1 + mu_inf * i1 ** 2) / (i0 + i1) < mu
        b, c = mud - mu, (mus - mu) * i0
        self.i_zeta = (-b + math.sqrt(b * b - 4 * mu_inf * c)) / (2 * mu_inf)

    def u(self, z):
        coeff = (2 * self.i_zeta / (3 * self.d)
                 * math.sqrt(self.phi * self.g * self.cos))
        zg = min(max(z, 0.0), H)
        u_grains = coeff * (H ** 1.5 - (H - zg) ** 1.5)
        if z <= H:
            return u_grains
        za = min(z, LZ)
        return (self.rho_air * self.g * self.sin / (2 * self.eta_air)
                * (2 * LZ * (za - H) + H * H - za * za) + u_grains)


def inlet_profile(nz):
    """The text of system/inletProfile: the inflow on the nz inlet faces,
    velocity at the face centres, grain fraction by the part of the face
    below h (as layeredInletFraction (5.2)), a 50:50 mix."""
    flow = Bagnold()
    dz = LZ / nz
    u = [flow.u((j + 0.5) * dz) for j in range(nz)]
    grains = [min(max((H - j * dz) / dz, 0.0), 1.0) for j in range(nz)]

    def scalars(values):
        return (f"nonuniform List<scalar> {len(values)} ("
                + " ".join(f"{v:.12g}" for v in values) + ")")

    vectors = (f"nonuniform List<vector> {nz} ("
               + " ".join(f"({v:.12g} 0 0)" for v in u) + ")")
    return (
        "// Generated by bench/generate.py: the chute's inflow on "
        f"{nz} faces,\n// I_zeta = {flow.i_zeta:.6g}, u(h) = "
        f"{flow.u(H):.6g} m/s\n\n"
        f"Uinlet              {vectors};\n"
        f"alpha_air_inlet     {scalars([1 - g for g in grains])};\n"
        f"alpha_small_inlet   {scalars([0.5 * g for g in grains])};\n"
        f"alpha_large_inlet   {scalars([0.5 * g for g in grains])};\n")


def foam_header(obj):
    return (
        "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
        "    class       dictionary;\n    location    \"system\";\n"
        f"    object      {obj};\n}}\n\n")


def case_env(case_dir):
    """The environment with PWD set to the case (OpenFOAM warns otherwise)."""
    return dict(os.environ, PWD=str(Path(case_dir).resolve()))


def run_tool(case_dir, *cmd):
    """Run an OpenFOAM utility in the case, its output in log.<utility>."""
    log = case_dir / f"log.{cmd[0]}"
    with open(log, "w") as out:
        proc = subprocess.run(list(cmd), cwd=case_dir, stdout=out,
                              stderr=subprocess.STDOUT, env=case_env(case_dir))
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed in {case_dir} "
                           f"(exit {proc.returncode}); see {log}")


def count_cells(case_dir):
    owner = (case_dir / "constant/polyMesh/owner").read_text()
    for token in owner.split("note")[1].split('"')[1].split():
        if token.startswith("nCells:"):
            return int(token.split(":")[1])
    raise RuntimeError(f"no nCells in {case_dir}/constant/polyMesh/owner")


@functools.lru_cache(maxsize=None)
def _krylov_entries():
    """The chute tutorial's entries KRYLOV, read once a run."""
    path = REPO / "tutorials/chute/system/fvSolution"
    return tuple((entry, " ".join(foam_value(path, entry).split()))
                 for entry in KRYLOV)


def krylov_entries():
    """The chute tutorial's entries KRYLOV, as foamDictionary reads them
    (a dictionary on one line)."""
    return dict(_krylov_entries())


def configuration(solver):
    """The fvSolution entries that make the configuration of `solver` out
    of the common fvSolution (none for stock and the explicit one)."""
    if solver == "granular-implicit":
        return dict(IMPLICIT)
    if solver == "granular-krylov":
        return krylov_entries()
    return {}


def set_entries(case_dir, entries):
    """entries set in the case's fvSolution by foamDictionary (which
    expands the file's $macros as it rewrites it), then read back."""
    fv_solution = Path(case_dir) / "system/fvSolution"
    for entry, value in entries.items():
        run_tool(case_dir, "foamDictionary", str(fv_solution),
                 "-entry", entry, "-set", value)
    for entry, value in entries.items():
        got = " ".join(foam_value(fv_solution, entry).split())
        if got != value:
            raise RuntimeError(f"{fv_solution}: {entry} is {got}, "
                               f"not {value}")


def prepare(case_dir, case, solver, nx, nz, steps, ranks, interval=None,
            max_delta_t=1.0):
    """Generate the case in case_dir (replaced if present) and return its
    parameters: steps fixed time steps or, with interval, the simulated
    interval [s] with the time step adjusted (ADJUSTABLE_STEP, at most
    max_delta_t)."""
    assert case in CASES and solver in SOLVERS
    case_dir = Path(case_dir)
    if case_dir.exists():
        shutil.rmtree(case_dir)
    overlays = [TEMPLATES / "common", TEMPLATES / case,
                TEMPLATES / ("stock" if solver == "stock"
                             else f"granular/{case}")]
    for tree in overlays:
        if tree.is_dir():
            shutil.copytree(tree, case_dir, dirs_exist_ok=True)
    for name, who in FROM_TUTORIAL.items():
        if who == "all" or (solver != "stock" and case == "chute"):
            (case_dir / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(REPO / "tutorials/chute" / name, case_dir / name)
    set_entries(case_dir, configuration(solver))

    dt = delta_t(nx, nz)
    params = {
        "application": APPLICATION[solver],
        "Lx": LX, "Lz": LZ, "h": H, "nx": nx, "nz": nz,
        "deltaT": dt, "nSteps": steps, "endTime": steps * dt,
        "writeInterval": steps + 1, "nRanks": max(ranks),
        **FIXED_STEP,
    }
    if interval is not None:
        # From deltaT (the fixed step: the first step, which the solver
        # shrinks further if (4.11) asks for it) up, by at most 20 % a step;
        # no write: the write interval is longer than any run
        params.update(ADJUSTABLE_STEP, maxDeltaT=max_delta_t, nSteps=0,
                      endTime=interval, writeInterval=10 ** 9)
        if solver == "granular-krylov":
            tutorial = {key: foam_scalar(REPO / "tutorials/chute" / path,
                                         key)
                        for key, path in KRYLOV_STEP.items()}
            params.update(maxCo=tutorial["maxCo"], maxDeltaT=min(
                max_delta_t, tutorial["maxDeltaT"]))
    text = foam_header("benchParameters") + "// Generated by bench/generate.py\n\n"
    for key, value in params.items():
        text += f"{key:<16}{value if isinstance(value, (int, str)) else format(value, '.12g')};\n"
    (case_dir / "system/benchParameters").write_text(text)
    (case_dir / "system/inletProfile").write_text(
        foam_header("inletProfile") + inlet_profile(nz))

    shutil.copytree(case_dir / "0.orig", case_dir / "0")
    run_tool(case_dir, "blockMesh")
    run_tool(case_dir, "setFields")
    if max(ranks) > 1:
        run_tool(case_dir, "decomposePar", "-force")
    params["cells"] = count_cells(case_dir)
    return params

"""Readers of what OpenFOAM wrote: the ascii fields of the time
directories, dictionary entries (foamDictionary, or the numeric entries of
a plain dictionary), and the output of the sets, volFieldValue and similar
function objects in postProcessing/; and `run`, an OpenFOAM tool in a case.
Every reader fails (an exception) on a missing output, never returns
nothing."""
import gzip
import re
import subprocess
from pathlib import Path

import numpy as np

from .exact import errors

_NCOMP = {"scalar": 1, "vector": 3, "sphericalTensor": 1, "symmTensor": 6,
          "tensor": 9}


def run(case, *cmd, timeout=3600):
    """Run the command cmd (an OpenFOAM tool and its arguments) in case;
    return its standard output.  A non-zero exit status raises, with the
    end of the tool's output."""
    res = subprocess.run(list(cmd), cwd=case, capture_output=True, text=True,
                         timeout=timeout)
    if res.returncode != 0:
        raise RuntimeError(
            f"{' '.join(cmd)} failed in {case} (exit {res.returncode}):\n"
            + (res.stdout + res.stderr)[-3000:])
    return res.stdout


def set_entry(case, dictionary, entry, value):
    """foamDictionary -entry entry -set value on case/dictionary; value
    None removes the entry (-remove, nothing if it is not there)."""
    if value is None:
        run(case, "foamDictionary", "-entry", entry, "-remove", dictionary)
        return
    run(case, "foamDictionary", "-entry", entry, "-set", str(value),
        dictionary)


def edit(path, edits, flags=0):
    """Apply (regex, replacement) pairs to the file path in turn, each to
    its first match; a pattern that does not match is an assertion
    failure."""
    text = path.read_text()
    for pattern, replacement in edits:
        text, n = re.subn(pattern, replacement, text, count=1, flags=flags)
        assert n == 1, f"{pattern!r} not in {path}"
    path.write_text(text)


def read_text(path):
    """Text of an OpenFOAM file, plain or .gz; assertion if absent."""
    path = Path(path)
    if not path.is_file() and Path(str(path) + ".gz").is_file():
        with gzip.open(str(path) + ".gz", "rt") as f:
            return f.read()
    assert path.is_file(), f"no field file {path}"
    return path.read_text()


def parameters(case, dictionary):
    """Numeric entries of the plain dictionary case/system/<dictionary>
    (e.g. the tutorials' chuteParameters, drumParameters): {name: float}."""
    text = read_text(Path(case) / "system" / dictionary)
    text = re.sub(r"//.*", "", text)
    return {k: float(v) for k, v in re.findall(
        r"^\s*(\w+)\s+([-+0-9.eE]+)\s*;", text, flags=re.M)}


def n_cells(case):
    """Number of cells, from the note of constant/polyMesh/owner."""
    text = read_text(Path(case) / "constant" / "polyMesh" / "owner")
    m = re.search(r"nCells:\s*(\d+)", text)
    assert m, f"no nCells in the owner file of {case}"
    return int(m.group(1))


def read_field(case, time_name, name):
    """internalField of the ascii volField case/time_name/name: array (n,)
    for scalars, (n, k) for vectors (k = 3) and tensors; `uniform` values
    are repeated over the n cells of the mesh."""
    path = Path(case) / str(time_name) / name
    text = read_text(path)
    assert re.search(r"format\s+ascii\s*;", text), f"{path} is not ascii"
    start = text.find("internalField")
    assert start >= 0, f"no internalField in {path}"
    rest = text[start + len("internalField"):]
    m = re.match(r"\s*uniform\s+([^;]*);", rest)
    if m:
        value = np.array(m.group(1).replace("(", " ").replace(")", " ")
                         .split(), dtype=float)
        n = n_cells(case)
        return np.full(n, value[0]) if value.size == 1 \
            else np.tile(value, (n, 1))
    m = re.match(r"\s*nonuniform\s+List<(\w+)>\s*(\d+)\s*\(", rest)
    assert m, f"cannot parse the internalField of {path}"
    kind, n = m.group(1), int(m.group(2))
    assert kind in _NCOMP, f"{path}: unknown List<{kind}>"
    k = _NCOMP[kind]
    if n == 0:
        return np.empty((0,) if k == 1 else (0, k))
    body = rest[m.end():]
    # The list closes at the first ')' of a scalar list, or at the first
    # ')' that follows another ')' (only blanks between) for vectors.
    end = re.search(r"\)" if kind == "scalar" else r"\)\s*\)", body)
    assert end, f"{path}: unterminated internalField list"
    body = body[:end.end() - 1]
    values = np.array(body.replace("(", " ").replace(")", " ").split(),
                      dtype=float)
    assert values.size == n * k, (
        f"{path}: {values.size} numbers for {n} {kind} values")
    return values if k == 1 else values.reshape(n, k)


def cell_centres(case, time_name):
    """Cell centres (n, 3): field C of `postProcess -func writeCellCentres`
    (run when time_name/C is missing; it writes into the case)."""
    case = Path(case)
    if not (case / str(time_name) / "C").is_file():
        run(case, "postProcess", "-func", "writeCellCentres",
             "-time", str(time_name))
    return read_field(case, time_name, "C")


def time_names(case, field="alpha.air"):
    """Sorted names of the time directories of case holding field (plain
    or .gz); with field None, of every time directory."""
    case = Path(case)
    out = []
    for d in case.iterdir():
        try:
            float(d.name)
        except ValueError:
            continue
        if d.is_dir() and (field is None or (d / field).is_file()
                           or (d / (field + ".gz")).is_file()):
            out.append(d.name)
    return sorted(out, key=float)


def table(path):
    """Rows of a function object's .dat file (comments '#' skipped; 'nan'
    read as NaN): array (rows, columns)."""
    rows = [line.split() for line in read_text(path).splitlines()
            if line.strip() and not line.startswith("#")]
    assert rows, f"{path} holds no data"
    return np.array(rows, dtype=float)


def function_table(case, function, name):
    """Rows of case/postProcessing/function/<start>/name over all start
    times (restarts): each start's rows up to the next start."""
    base = Path(case) / "postProcessing" / function
    assert base.is_dir(), f"no {base}"
    starts = sorted((d for d in base.iterdir()
                     if d.is_dir() and (d / name).is_file()),
                    key=lambda d: float(d.name))
    assert starts, f"no {name} in {base}"
    parts = []
    for k, d in enumerate(starts):
        a = table(d / name)
        if k + 1 < len(starts):
            a = a[a[:, 0] < float(starts[k + 1].name) + 1e-9]
        parts.append(a)
    return np.concatenate(parts)


def entries(case, dictionary, keys):
    """{key: float} of foamDictionary -entry key -value on case/dictionary
    (with 15 digits: foamDictionary prints 6 by default; the value is the
    last word, after any warning).  A failing foamDictionary raises."""
    out = {}
    for k in keys:
        res = subprocess.run(
            ["foamDictionary", "-precision", "15", "-entry", k, "-value",
             str(dictionary)], cwd=case, capture_output=True, text=True,
            check=True)
        out[k] = float(res.stdout.split()[-1])
    return out


def times(case, function="profile"):
    """Sorted sampling times (floats, as directory names) of a sets object."""
    base = case / "postProcessing" / function
    assert base.is_dir(), f"no sampled profiles in {base}"
    return sorted((d.name for d in base.iterdir() if d.is_dir()), key=float)


def last_two(case, function="profile"):
    """Names of the last two sampling times."""
    t = times(case, function)
    assert len(t) >= 2, f"{case}: fewer than two sampled times {t}"
    return t[-2], t[-1]


def profiles(case, time_name, function="profile", set_name="centreline"):
    """Sampled fields at a time: {'z': ..., field: column, 'U': (n, 3)}."""
    folder = case / "postProcessing" / function / time_name
    files = sorted(folder.glob(f"{set_name}_*.xy"))
    assert files, f"no sampled sets in {folder}"
    out = {}
    for path in files:
        fields = path.stem[len(set_name) + 1:].split("_")
        data = errors.read_raw(path)
        out["z"] = data[:, 0]
        if fields == ["U"]:
            out["U"] = data[:, 1:4]
        else:
            assert data.shape[1] == len(fields) + 1, (
                f"{path}: {data.shape[1]} columns for fields {fields}")
            for k, name in enumerate(fields):
                out[name] = data[:, k + 1]
    return out


def grain_profiles(case, time_name, grains, h, function="profile"):
    """The grains of a sampled column at a time (0 <= z < h): {'z': z,
    'phi': (len(grains), n) fractions per unit grain volume (alpha.<name>
    over their sum), 'u': downslope velocity}."""
    prof = profiles(case, time_name, function)
    inside = prof["z"] < h
    alpha = np.array([prof["alpha." + g][inside] for g in grains])
    return {"z": prof["z"][inside], "phi": alpha / alpha.sum(axis=0),
            "u": prof["U"][inside, 0]}


def volumes(case, function="volumes"):
    """volIntegrate of the phase fractions: (times, {field: values})."""
    files = sorted((case / "postProcessing" / function).glob(
        "*/volFieldValue.dat"), key=lambda p: float(p.parent.name))
    assert files, f"no volume integrals in {case / 'postProcessing'}"
    header, rows = None, []
    for path in files:
        for line in path.read_text().splitlines():
            if line.startswith("# Time"):
                header = line[1:].split()
            elif line and not line.startswith("#"):
                rows.append([float(x) for x in line.split()])
    assert header and rows, f"empty volume integrals in {files}"
    cols = list(zip(*rows))
    names = [re.sub(r"^volIntegrate\((.*)\)$", r"\1", h) for h in header]
    return cols[0], {n: cols[k] for k, n in enumerate(names) if k > 0}


_SOLUTIONS = re.compile(r"^Pressure coupling: (\d+) pressure solutions")
_KRYLOV = re.compile(r"^Krylov coupling: \w+, (\d+) iterations \((\d+) of")


def log_cost(text, start=None, end=None):
    """Steps, CPU seconds and pressure solutions per step of a solver log's
    text (the master's, in a parallel run) over its steps with time in
    (start, end] (all steps by default): the steps' "Time =" lines, the
    last ExecutionTime of those steps less the one before them (None
    without any), the mean of the steps' "Pressure coupling: N pressure
    solutions" (None without any); with the Krylov coupling, also the
    mean of its iterations and of its inner solvers' iterations a step."""
    steps, solutions, last, before, now = 0, [], None, None, None
    krylov = []
    for line in text.splitlines():
        if line.startswith("Time = "):
            now = float(line.split()[2])
        inside = now is not None \
            and (start is None or now > start + 1e-9) \
            and (end is None or now <= end + 1e-9)
        if line.startswith("Time = ") and inside:
            steps += 1
        elif line.startswith("ExecutionTime = "):
            seconds = float(line.split()[2])
            if inside:
                last = seconds
            elif last is None:
                before = seconds
        elif inside:
            m = _SOLUTIONS.match(line)
            if m:
                solutions.append(int(m.group(1)))
            m = _KRYLOV.match(line)
            if m:
                krylov.append((int(m.group(1)), int(m.group(2))))
    cost = {"steps": steps,
            "cpu_seconds": None if last is None else last - (before or 0.0),
            "pressure_solutions_per_step":
                sum(solutions) / len(solutions) if solutions else None}
    if krylov:
        cost["krylov_iterations_per_step"] = \
            sum(k for k, _ in krylov) / len(krylov)
        cost["inner_iterations_per_step"] = \
            sum(i for _, i in krylov) / len(krylov)
    return cost

"""Readers of what OpenFOAM wrote: dictionary entries (foamDictionary) and
the output of the sets, volFieldValue and similar function objects in
postProcessing/.  Every reader fails (an exception) on a missing output,
never returns nothing."""
import re
import subprocess

import numpy as np

from .exact import errors


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

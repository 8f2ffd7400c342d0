"""Smoke tier: the tests take their cases from the repository, never from
the user's folders.

A clone of HEAD in a temporary directory (the real tutorials/ is never
written to) is dirtied the way a user's runs and edits dirty a case: in
every tutorial and every case of validation/cases a written time 25/,
processor0/, movingFrame/, postProcessing/, figures/, logs (log.blockMesh,
log.granularSegregationFoam, log.<application>) and an edited
system/controlDict.  committed_copy from the clone then holds exactly the
committed files, byte for byte and with their executable bits, and tests
of the suite run in the clone (the chute's short runs, its moving frame
and pictures, the well-posedness utility through case_copy and the
rotating box of validation/cases) pass, leaving the dirt where it was.
"""
import hashlib
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from conftest import PROJECT, committed_copy, run

pytestmark = pytest.mark.smoke

EDIT = "\n// the user's edit\nendTime         1e9;\n"
# What a user's run leaves in a case (with log.<application>)
DIRT = {"25/U": "a field of a user's run",
        "processor0/25/U": "a field of a parallel run",
        "movingFrame/25/U": "a field of the moving frame",
        "postProcessing/profile/25/centreline_U.xy": "0 0 0 0",
        "figures/fields_25.png": "a picture",
        "log.blockMesh": "a log",
        "log.granularSegregationFoam": "a log"}
DIRT_NAMES = {path.split("/")[0] for path in DIRT}
# Tests of the suite that copy a case and run it (seconds in all)
SUITE_TESTS = ["validation/chute/test_chute_smoke.py::test_inflow_profiles",
               "validation/chute/test_chute_smoke.py::test_moving_frame",
               "validation/chute/test_chute_smoke.py::test_pictures",
               "validation/test_unit.py::test_well_posedness_utility_table1",
               "validation/test_smoke_solver.py::test_rotating_box"]


def git(project, *args):
    """git -C project args; its standard output (assertion failure on a
    non-zero status)."""
    res = run(["git", "-C", str(project), *args], PROJECT)
    assert res.returncode == 0, f"git {' '.join(args)}: {res.stderr}"
    return res.stdout


def tracked(project, folder):
    """{path relative to folder: (mode, blob id)} of the files HEAD holds
    under folder."""
    out = {}
    for line in git(project, "ls-tree", "-r", "-z", "HEAD", "--",
                    f"{folder}/").split("\0"):
        if line:
            meta, path = line.split("\t", 1)
            mode, _, blob = meta.split()
            out[path[len(folder) + 1:]] = (mode, blob)
    return out


def case_folders(project):
    """The tutorials and the cases of validation/cases HEAD holds."""
    names = set()
    for top in ("tutorials", "validation/cases"):
        for path in tracked(project, top):
            if "/" in path:  # files such as tutorials/Alltest hold no case
                names.add(f"{top}/{path.split('/')[0]}")
    return sorted(names)


def dirty(case):
    """Leave in case what a user's runs and edits leave."""
    control = case / "system" / "controlDict"
    m = re.search(r"^application\s+(\w+);", control.read_text(), re.M)
    assert m, f"no application in {control}"
    for path, text in dict(DIRT, **{f"log.{m.group(1)}": "a log"}).items():
        (case / path).parent.mkdir(parents=True, exist_ok=True)
        (case / path).write_text(f"dirt: {text}\n")
    with open(control, "a") as out:
        out.write(EDIT)


def snapshot(folder):
    """{path: bytes (None for a folder)} of everything under folder."""
    return {str(p.relative_to(folder)): (None if p.is_dir()
                                         else p.read_bytes())
            for p in sorted(folder.rglob("*"))}


def blob_id(data):
    """git's object id of a blob with these bytes."""
    return hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()


def suite_code(folder, names):
    """shutil.copytree's ignore: of validation/, the code only (not its
    results, caches or cases)."""
    skip = {"results", "__pycache__", ".pytest_cache"}
    if Path(folder) == PROJECT / "validation":
        skip.add("cases")
    return [n for n in names if n in skip]


@pytest.fixture(scope="module")
def dirty_clone(tmp_path_factory):
    """A clone of PROJECT's HEAD with every case dirtied, holding the
    running suite's validation/ and python/ (the code under test, from
    PROJECT's work tree): (clone, case folders, snapshot of the dirty
    cases)."""
    clone = tmp_path_factory.mktemp("isolation") / "project"
    head = git(PROJECT, "rev-parse", "HEAD").strip()
    git(PROJECT, "clone", "-q", "--shared", "--no-checkout", str(PROJECT),
        str(clone))
    git(clone, "checkout", "-q", "--detach", head)
    shutil.copytree(PROJECT / "validation", clone / "validation",
                    dirs_exist_ok=True, ignore=suite_code)
    shutil.copytree(PROJECT / "python", clone / "python",
                    dirs_exist_ok=True, ignore=suite_code)
    folders = case_folders(clone)
    assert {"tutorials/chute", "tutorials/wellPosedness",
            "validation/cases/rotatingBox"} <= set(folders), folders
    for folder in folders:
        dirty(clone / folder)
    status = git(clone, "status", "--porcelain", "--ignored", "--",
                 "tutorials", "validation/cases")
    for folder in folders:
        assert f" {folder}/system/controlDict\n" in status, status
        assert f"!! {folder}/25/\n" in status, status
    return clone, folders, {f: snapshot(clone / f) for f in folders}


def test_copies_are_the_committed_cases(dirty_clone, tmp_path):
    """committed_copy of each dirty case: the files HEAD holds, each with
    its committed bytes and executable bit; none of the dirt, the
    dictionary unedited; the dirty case left as it was."""
    clone, folders, before = dirty_clone
    for folder in folders:
        copy = committed_copy(folder, tmp_path / folder, project=clone)
        files = {str(p.relative_to(copy)): p for p in copy.rglob("*")
                 if not p.is_dir()}
        dirt = sorted(n for n in os.listdir(copy)
                      if n in DIRT_NAMES or n.startswith("log."))
        assert not dirt, f"{folder}: the copy holds the user's {dirt}"
        assert EDIT not in (copy / "system" / "controlDict").read_text(), (
            f"{folder}: the copy holds the user's edit of controlDict")
        expected = tracked(clone, folder)
        assert sorted(files) == sorted(expected), (
            f"{folder}: files not in HEAD "
            f"{sorted(set(files) - set(expected))}, missing "
            f"{sorted(set(expected) - set(files))}")
        for name, (mode, blob) in expected.items():
            path = files[name]
            assert blob_id(path.read_bytes()) == blob, (
                f"{folder}/{name}: not the committed content")
            assert os.access(path, os.X_OK) == (mode == "100755"), (
                f"{folder}/{name}: mode {oct(path.stat().st_mode)}, "
                f"committed {mode}")
        assert snapshot(clone / folder) == before[folder], (
            f"{folder}: the copy changed the user's folder")


def test_suite_passes_beside_dirty_tutorials(dirty_clone, foam_env):
    """Tests of the suite that copy a case (the chute, the well-posedness
    tutorial, the rotating box) and run it pass in the dirty clone, and
    leave every case of it as it was."""
    clone, folders, before = dirty_clone
    env = dict(os.environ, GSF_PROJECT_DIR=str(clone))
    res = subprocess.run(
        ["/usr/bin/python3", "-m", "pytest", "-c", "validation/pytest.ini",
         "-p", "no:cacheprovider", "-q", *SUITE_TESTS],
        cwd=clone, env=env, capture_output=True, text=True, timeout=900)
    out = res.stdout + res.stderr
    assert res.returncode == 0, f"the suite failed in {clone}:\n{out[-4000:]}"
    assert f"{len(SUITE_TESTS)} passed" in out, out[-2000:]
    changed = [f for f in folders if snapshot(clone / f) != before[f]]
    assert not changed, f"the tests wrote into {changed}"

"""Shared helpers of the test suite.

A missing OpenFOAM environment, a program that did not run or a missing
output file is a failure here, never a skip.
"""
import io
import json
import os
import shutil
import subprocess
import tarfile
import time
from pathlib import Path, PurePosixPath

import pytest

import reference as reference_rule

PROJECT = Path(__file__).resolve().parent.parent


def run(cmd, cwd, timeout=600):
    """Run cmd (a list) in cwd; return the completed process (text output)."""
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True,
                          timeout=timeout)


@pytest.fixture(scope="session")
def foam_env():
    """The project's OpenFOAM environment: fails when it is not set up."""
    missing = [v for v in ("WM_PROJECT_DIR", "FOAM_USER_APPBIN",
                           "GSF_PROJECT_DIR") if not os.environ.get(v)]
    assert not missing, (
        f"OpenFOAM environment not sourced ({', '.join(missing)} unset): "
        "run ./Alltest, or etc/bootstrap and . etc/openfoam.env")
    assert Path(os.environ["GSF_PROJECT_DIR"]).resolve() == PROJECT, (
        "the sourced environment belongs to another checkout: "
        f"{os.environ['GSF_PROJECT_DIR']}")
    import granularfoam
    installed = Path(granularfoam.__file__).resolve().parent
    assert installed.parent.parent.parent.name == "platforms", (
        f"granularfoam imported from {installed}, not from a platforms/ "
        "folder (run ./Allwmake)")
    sources = PROJECT / "python" / "granularfoam"
    stale = [str(f.relative_to(sources)) for f in sources.rglob("*.py")
             if not (installed / f.relative_to(sources)).is_file()
             or (installed / f.relative_to(sources)).read_bytes()
             != f.read_bytes()]
    assert not stale, (f"granularfoam in {installed} differs from this "
                       f"checkout's python/ in {stale} (run ./Allwmake)")
    return os.environ


def executable(name):
    """Path of an executable on PATH; assertion failure if absent."""
    path = shutil.which(name)
    assert path, f"{name} not found on PATH: was ./Allwmake run?"
    return path


def committed_copy(path, dst, project=PROJECT):
    """Copy path (a folder or a file, relative to the root of the git
    checkout project) to dst as the checked-out commit (HEAD) holds it, by
    git archive, keeping the file modes (the executable Allrun scripts);
    return dst.

    The tests take every case this way, never from the work tree: a user's
    tutorial folder holds their runs (time directories, processor*,
    movingFrame/, postProcessing/, logs, figures) and their edits of the
    dictionaries, none of which is in HEAD; the index (staged changes) is
    not read either.  A change to a case is tested once committed.  A
    project that is not a git checkout, or a path not in HEAD, is an
    assertion failure."""
    path = PurePosixPath(path)
    res = subprocess.run(["git", "-C", str(project), "-c", "tar.umask=user",
                          "archive", "--format=tar", "HEAD", "--", str(path)],
                         capture_output=True)
    assert res.returncode == 0, (
        f"cannot copy {path} from HEAD of {project} (the tests take their "
        "cases from the git repository, so the project must be a git "
        "checkout with the path committed): "
        + res.stderr.decode(errors="replace").strip())
    dst = Path(dst)
    with tarfile.open(fileobj=io.BytesIO(res.stdout)) as tar:
        for member in tar:
            name = PurePosixPath(member.name)
            if name != path and path not in name.parents:
                continue                 # the folders above path
            target = dst.joinpath(*name.relative_to(path).parts)
            if member.isdir():
                target.mkdir(parents=True, exist_ok=True)
                continue
            target.parent.mkdir(parents=True, exist_ok=True)
            if member.issym():
                target.symlink_to(member.linkname)
            else:
                assert member.isfile(), f"{member.name}: not a file"
                target.write_bytes(tar.extractfile(member).read())
                target.chmod(member.mode)
    assert dst.exists(), f"{path} is not in HEAD of {project}"
    return dst


@pytest.fixture
def case_copy(tmp_path):
    """Copy a tutorial, as HEAD holds it, into a temporary directory;
    return the copy's path."""
    def copy(name):
        return committed_copy(f"tutorials/{name}", tmp_path / name)
    return copy


# ---------------------------------------------------------------------------
# Measured numbers and the validation status table
#
# A test states a measured number against its tolerance through the `check`
# fixture, which asserts it and records it; at the end of a session every
# test's outcome, time and checks are merged into STATUS (keyed by test, so
# a partial run updates only its own tests), from which
# `validation/status.py --doc` writes the status table into doc/validation.md
# (section Status).

STATUS = reference_rule.STATUS


# The tolerance and the regression guard of every checked number, by label
REFERENCE = reference_rule.REFERENCE


def reference(label):
    """{"tolerance", "guard", "measured"} of a checked number, from
    REFERENCE; a label missing from it is an assertion failure."""
    entries = json.loads(REFERENCE.read_text())["checks"]
    assert label in entries, (
        f"no entry '{label}' in {REFERENCE}: give it the paper's tolerance "
        "and a guard of about 3 x the measured value")
    return entries[label]


@pytest.fixture
def check(request):
    """check(label, measured, paper=None, percent=False): assert measured
    (a number, e.g. a relative L2 error) below its tolerance (the paper's)
    and below its regression guard (about 3 x the measured value), both from
    validation/reference.json, and record them, with the paper's figure or
    equation, for the status table (shown in % with percent).  An entry with
    "bound": "lower" is a number that must stay above its tolerance and
    above its guard (about a third of the measured value)."""
    def _check(label, measured, paper=None, percent=False):
        measured = float(measured)
        ref = reference(label)
        tolerance = float(ref["tolerance"])
        # An entry not measured yet holds no guard (test_reference.py fails
        # on it) until reference.py --update writes one
        guard = tolerance if ref["guard"] is None else float(ref["guard"])
        lower = reference_rule.is_lower(ref)
        inside = (lambda x, bound: x > bound) if lower else (
            lambda x, bound: x < bound)
        assert (guard >= tolerance) if lower else (guard <= tolerance), (
            label, ref)
        request.node.user_properties.append(
            ("check", {"label": label, "measured": measured,
                       "tolerance": tolerance, "guard": guard,
                       "paper": paper, "percent": percent, "lower": lower,
                       "passed": bool(inside(measured, guard))}))
        side = "below" if lower else "above"
        before = ("nothing" if ref["measured"] is None
                  else f"{ref['measured']:.4g}")
        assert inside(measured, tolerance), (
            f"{label}: measured {measured:.4g}, {side} the tolerance "
            f"{tolerance:.4g}")
        assert inside(measured, guard), (
            f"{label}: measured {measured:.4g}, {side} the regression guard "
            f"{guard:.4g} (from the {before} measured before)")
    return _check


_OUTCOMES = {}


def pytest_runtest_logreport(report):
    """Keep the outcome of every test: failed in any phase, else passed."""
    entry = _OUTCOMES.setdefault(report.nodeid, {"checks": []})
    if report.when == "setup":
        entry.update(outcome="passed", seconds=0.0)
    entry["seconds"] += report.duration
    if report.failed:
        entry["outcome"] = "failed"
    elif report.skipped:
        entry["outcome"] = "skipped"
    if report.when == "call":
        entry["checks"] = [v for k, v in report.user_properties
                           if k == "check"]


def pytest_collection_modifyitems(items):
    """The first line of each test's docstring, for the status table."""
    for item in items:
        doc = getattr(item.function, "__doc__", None) or ""
        _OUTCOMES.setdefault(item.nodeid, {
            "outcome": "not run", "seconds": 0.0, "checks": []})["doc"] = (
                doc.strip().splitlines()[0] if doc.strip() else "")


def pytest_sessionfinish(session):
    """Merge this session's outcomes into STATUS."""
    ran = {k: v for k, v in _OUTCOMES.items() if v["outcome"] != "not run"}
    if not ran:
        return
    commit = run(["git", "rev-parse", "--short=12", "HEAD"], PROJECT)
    dirty = run(["git", "status", "--porcelain", "--untracked-files=no"],
                PROJECT)
    stamp = {"commit": (commit.stdout.strip() if commit.returncode == 0
                        else "unknown")
             + ("+changes" if dirty.stdout.strip() else ""),
             "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    old = json.loads(STATUS.read_text()) if STATUS.is_file() else {}
    for nodeid, entry in ran.items():
        old[nodeid] = dict(entry, **stamp)
    STATUS.parent.mkdir(parents=True, exist_ok=True)
    STATUS.write_text(json.dumps(old, indent=1, sort_keys=True) + "\n")

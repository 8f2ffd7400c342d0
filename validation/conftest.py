"""Shared helpers of the test suite.

A missing OpenFOAM environment, a program that did not run or a missing
output file is a failure here, never a skip.
"""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

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
    return os.environ


def executable(name):
    """Path of an executable on PATH; assertion failure if absent."""
    path = shutil.which(name)
    assert path, f"{name} not found on PATH: was ./Allwmake run?"
    return path


@pytest.fixture
def case_copy(tmp_path):
    """Copy a tutorial into a temporary directory, return the copy's path."""
    def copy(name):
        src = PROJECT / "tutorials" / name
        assert src.is_dir(), f"no tutorial {name}"
        dst = tmp_path / name
        shutil.copytree(src, dst)
        return dst
    return copy

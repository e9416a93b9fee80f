"""Shared fixtures of the Python package's tests: where the source tree and the build are, and
how to run the `plumage` command beside a Python call (their results must agree bit for bit)."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("PLUMAGE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("PLUMAGE_BINARY_DIR", SOURCE_DIR / "build"))
PLUMAGE = BINARY_DIR / "bin" / "plumage"


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def configs():
    return SOURCE_DIR / "configs"


def run_plumage(*args, cwd=None, check=True):
    """Runs the command (quiet) and returns the CompletedProcess; raises with its stderr on failure."""
    result = subprocess.run([str(PLUMAGE), "-q", *map(str, args)], cwd=cwd, capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"plumage {' '.join(map(str, args))} exited {result.returncode}:\n{result.stderr}")
    return result


@pytest.fixture
def plumage_cli():
    return run_plumage

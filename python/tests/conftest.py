"""Fixtures of the Python module's tests: where the command, the examples and the shared data are.

ctest runs these with the interpreter the build found and PYTHONPATH=build/python; KONTUR_BIN
names the command (the tests compare the module with it), KONTUR_SHARED the shared data.
"""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT


@pytest.fixture(scope="session")
def kontur_bin() -> str:
    path = os.environ.get("KONTUR_BIN", str(ROOT / "build" / "bin" / "kontur"))
    if not os.path.exists(path):
        pytest.skip(f"the kontur command is not built ({path})")
    return path


@pytest.fixture(scope="session")
def shared() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("KONTUR_SHARED", str(ROOT.parent / "shared")))
    if not (path / "data").is_dir():
        pytest.skip(f"the shared data is not beside the checkout ({path})")
    return path


@pytest.fixture(scope="session")
def command(kontur_bin):
    """Runs the command; returns the CompletedProcess (text)."""

    def run(*args, check=True):
        p = subprocess.run([kontur_bin, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"kontur {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr}")
        return p

    return run

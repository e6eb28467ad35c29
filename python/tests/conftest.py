"""Shared fixtures: the repository's root (cases are read from it) and the command line
binary the Python results are compared with."""

import os
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def required() -> bool:
    """Whether a test that cannot run must fail instead of skipping (CI)."""
    return os.environ.get("CI") == "true"


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def cli() -> Path:
    """The `rockslide` binary: $ROCKSLIDE_BIN, the workspace's release build, or the PATH."""
    candidates = [os.environ.get("ROCKSLIDE_BIN"), REPO / "target" / "release" / "rockslide"]
    for c in candidates:
        if c and Path(c).is_file():
            return Path(c)
    found = shutil.which("rockslide")
    if found:
        return Path(found)
    message = "the rockslide binary is not built (cargo build --release)"
    if required():
        pytest.fail(message)
    pytest.skip(message)

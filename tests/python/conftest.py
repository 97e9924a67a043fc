"""Shared fixtures of the Python package's tests (tests/python, run by the
ctest entry python.pytest with PYTHONPATH=<build>/python)."""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
CHECKER = ROOT / "tests" / "independent" / "check_plan.py"


@pytest.fixture
def data():
    return DATA


@pytest.fixture
def cli():
    """The built `unstack` executable (ctest sets UNSTACK_TEST_CLI)."""
    path = os.environ.get("UNSTACK_TEST_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("UNSTACK_TEST_CLI not set: the CLI comparisons need the built tool")
    return path

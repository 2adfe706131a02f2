"""Shared set-up of the Python module's tests (CTest runs them: tests/CMakeLists.txt).

The module comes from the build tree (PYTHONPATH=build/python, set by CTest); NSBENCH_EXE is the
command line they compare with, NSBENCH_STUDY_EXE the study driver; examples/python/ is importable (the example integrator).
"""
import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "python"))

import nsbench  # noqa: E402
import symplectic_euler  # noqa: E402

if "py-symplectic-euler" not in {e["name"] for e in nsbench.integrators()}:
    symplectic_euler.register()


def program(variable, what):
    exe = os.environ.get(variable)
    if not exe:
        pytest.skip(f"{variable} ({what}) is not set")
    return exe


@pytest.fixture
def nsbench_exe():
    return program("NSBENCH_EXE", "the nsbench command line")


@pytest.fixture
def study_exe():
    return program("NSBENCH_STUDY_EXE", "nsbench-study")

"""Set-up of the Python module's tests: `import gearkit` from build/python (GEARKIT_BUILD),
the shipped cases, and the executable's outputs of the cases (GEARKIT_CASE_OUT, from the case
tests) to compare with.
(tests/python/run_tests.py starts pytest on the OpenBLAS kernels the executable uses.)
"""
import os
import sys

import pytest

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("GEARKIT_BUILD", os.path.join(SOURCE, "build"))
PYTHON = os.path.join(BUILD, "python")
sys.path.insert(0, PYTHON)

@pytest.fixture(scope="session")
def source_dir():
    return SOURCE


@pytest.fixture(scope="session")
def case_out():
    """The executable's results of the shipped cases (build/case-out, the case tests')."""
    return os.environ.get("GEARKIT_CASE_OUT", os.path.join(BUILD, "case-out"))

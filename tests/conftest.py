"""Test session set-up: one BLAS thread, as the ``mechsing`` command uses.

The tests run many tiny matrix operations; BLAS threads only add overhead there
and make timings erratic on a loaded machine.  Set before numpy is imported.
The session's fixtures shared by several test modules live here too.
"""

import os
from pathlib import Path

import pytest

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


@pytest.fixture(scope="session")
def scaled_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Where the scaled examples are written (tests/mechanisms.py ``scaled_file``), once a
    session."""
    return tmp_path_factory.mktemp("scaled")

"""Test session set-up: one BLAS thread, as the ``mechsing`` command uses.

The tests run many tiny matrix operations; BLAS threads only add overhead there
and make timings erratic on a loaded machine.  Set before numpy is imported.
"""

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

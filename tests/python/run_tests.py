#!/usr/bin/python3
"""Runs the Python module's tests (pytest) on the OpenBLAS kernels the gearkit executable uses.

The executable switches OpenBLAS to the kernels that suit the processor where OpenBLAS fell back
to generic ones (base/blas_kernels.h: it runs itself again with OPENBLAS_CORETYPE set); results
are bit for bit the executable's only on the same kernels, and OpenBLAS picks them when it
loads: so pytest runs in a process started with OPENBLAS_CORETYPE set the same way.

  run_tests.py BUILD_DIR [pytest arguments...]
"""
import os
import subprocess
import sys

build, args = sys.argv[1], sys.argv[2:]
env = dict(os.environ, GEARKIT_BUILD=build)
python = os.path.join(build, "python")
if "OPENBLAS_CORETYPE" not in env:
    fitting = subprocess.run(
        [sys.executable, "-c", "import gearkit._core as c; print(c.fitting_blas_kernels())"],
        env=dict(env, PYTHONPATH=python), capture_output=True, text=True, check=True).stdout.strip()
    if fitting:
        env["OPENBLAS_CORETYPE"] = fitting
sys.exit(subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider"] + args,
                        env=env).returncode)

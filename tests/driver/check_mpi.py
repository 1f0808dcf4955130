#!/usr/bin/python3
"""Compares the results of one scene run on one process and under mpirun (tests/CMakeLists.txt:
driver_mpi_np2): the fast mode's loaded TE and mesh stiffness, and the reference mode's, agree
to solver precision (the direct solver's ordering differs between the runs)."""
import os
import sys

import h5py
import numpy as np

one, many = (os.path.join(d, "results.h5") for d in sys.argv[1:3])
with h5py.File(one, "r") as a, h5py.File(many, "r") as b:
    for pair in a["stiffness"]:
        ga, gb = a["stiffness"][pair], b["stiffness"][pair]
        paths = ["transmission_error_loaded", "mesh_stiffness", "normal_force"]
        if "reference" in ga:
            paths += ["reference/" + p for p in ("transmission_error_loaded", "mesh_stiffness")]
        for p in paths:
            x, y = ga[p][()], gb[p][()]
            assert x.shape == y.shape and np.all(np.isfinite(x)) and np.all(x != 0), p
            assert np.allclose(x, y, rtol=1e-8, atol=0), (pair, p, x, y)
            print(f"{pair} {p}: max relative difference {np.max(np.abs(y / x - 1)):.1e}")
print("mpi: ok")

#!/usr/bin/python3
"""Compares the results of one scene run on one process and under mpirun (tests/CMakeLists.txt:
driver_mpi_np2): the fast mode's loaded TE and mesh stiffness, and the reference mode's, agree
to solver precision (the direct solver's ordering differs between the runs); the dynamics'
sweeps, whose blocks ran on different processes and were gathered, agree with the single
process's to what that difference in K_m carries; so do the micro-geometry map's variants, which
ran on different processes."""
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
    for pair in a["dynamics"]:
        for exc in a["dynamics"][pair]:
            if not isinstance(a["dynamics"][pair][exc], h5py.Group):
                continue
            for d in ("up", "down"):
                ga, gb = a["dynamics"][pair][exc][d], b["dynamics"][pair][exc][d]
                # every field of a sweep point crosses the gather (Newmark's steps and error
                # estimate, the status and divergence time)
                assert set(ga.keys()) == set(gb.keys()), (pair, d, set(ga) ^ set(gb))
                for p in ("speed", "dte_peak_to_peak", "dynamic_load_factor", "dte_spectrum",
                          "time_series/0/dte"):
                    x, y = ga[p][()], gb[p][()]
                    assert x.shape == y.shape and x.size > 0 and np.all(np.isfinite(x)), p
                    assert np.allclose(x, y, rtol=1e-6, atol=1e-6 * np.max(np.abs(x))), (pair, d, p)
                    print(f"{pair} {exc} {d} {p}: max difference "
                          f"{np.max(np.abs(y - x)) / np.max(np.abs(x)):.1e} of the largest")
    for pair in a["study"]:
        ga, gb = a["study"][pair], b["study"][pair]
        for p in ("te_peak_to_peak", "loaded_te", "mesh_stiffness", "unloaded_te", "max_pressure"):
            x, y = ga[p][()], gb[p][()]
            assert x.shape == y.shape and x.size > 0 and np.all(np.isfinite(x)), p
            assert np.allclose(x, y, rtol=1e-8, atol=1e-12 * np.max(np.abs(x))), (pair, p)
            print(f"study {pair} {p}: max difference "
                  f"{np.max(np.abs(y - x)) / np.max(np.abs(x)):.1e} of the largest")
        assert np.array_equal(ga["best_variant"][()], gb["best_variant"][()])
print("mpi: ok")

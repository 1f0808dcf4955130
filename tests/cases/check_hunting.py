#!/usr/bin/python3
"""Checks the hunting case: over the hunting cycle (3 pinion revolutions of the 16/24 pair) the
theoretical pair, whose only error is an eccentric pinion tooth, repeats every pinion revolution
(lines only at integer pinion orders, among them the sidebands of the mesh order), while the
measured pair's gear pitch errors put lines at gear orders (multiples of 16/24 = 2/3); the
picture exists."""
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    g = f["ste"]["spur"]
    order = g["shaft_order"][:]
    theory = g["shaft_order_spectrum"][:]
    measured = g["measured"]["shaft_order_spectrum"][:]
    assert g["transmission_error"].shape == (48 * 24,), g["transmission_error"].shape
    assert np.allclose(order[:4], [0, 1 / 3, 2 / 3, 1]), order[:4]
    integer = np.isclose(order, np.round(order))
    # eccentric pinion tooth: once-per-revolution lines of 0.1-1 um, nothing between them (the
    # touch-angle Newton's 1e-13 m is the floor)
    assert theory[~integer].max() < 1e-11, theory[~integer].max()
    for k in (1, 2, 15, 17):
        assert theory[np.isclose(order, k)][0] > 1e-8, (k, theory)
    # measured: gear order 1 (pinion order 2/3) carries the gear's cumulative pitch deviation
    gear_order_1 = measured[np.isclose(order, 2 / 3)][0]
    assert gear_order_1 > 1e-7, gear_order_1
path = os.path.join(out, "hunting.png")
with open(path, "rb") as fh:
    assert fh.read(8) == b"\x89PNG\r\n\x1a\n", path
assert os.path.getsize(path) > 20000, path
print("hunting case: spectra and picture OK")

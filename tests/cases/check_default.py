#!/usr/bin/python3
"""Checks the default case's output folder: results.h5 holds both pairs with their flank
grids and the pictures exist and are real PNG images of a sensible size."""
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    for pair in ("spur", "helical"):
        for member in ("pinion", "gear"):
            g = f["flanks"][pair][member]
            z = int(g["number_of_teeth"][()])
            pts = g["drive"]["points"]
            assert pts.shape == (z, 9, 29, 3), pts.shape  # the seed's 261-point grid
            assert np.all(np.isfinite(pts[:]))
            # Without the stored modifications (deviation along the normal) every flank point
            # lies between the form and the tip circle. The modified normal differs from the
            # nominal one by ~ |grad deviation| ~ 1e-3, so undoing 15 um leaves ~1e-8 m.
            nominal = pts[:] - g["drive"]["deviation"][:][..., None] * g["drive"]["normals"][:]
            r = np.hypot(nominal[..., 0], nominal[..., 1])
            assert r.min() > g["form_radius"][()] - 1e-7, (pair, member, r.min())
            assert r.max() < g["tip_radius"][()] + 1e-7, (pair, member, r.max())
for png in ("profiles.png", "topography.png"):
    path = os.path.join(out, png)
    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n", path
    assert os.path.getsize(path) > 20000, path
print("default case: results.h5 and pictures OK")

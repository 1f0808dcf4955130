#!/usr/bin/python3
"""Checks the published_pairs case's output folder: results.h5 holds both pairs with their flank
grids and measurements, the CMM files were exported, and the pictures exist and are real PNG
images of a sensible size."""
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
            # lies between the form and the tip circle. Undoing them along the modified normal
            # leaves |deviation| x (tilt of the normal); the tilt is d(delta)/ds, and near the
            # form circle ds = xi dL with xi ~ 0.11, so 8 C_alpha / L_alpha / xi ~ 1.5e-2 rad for
            # the pinion's 4 um profile crowning: 19 um x 1.5e-2 ~ 3e-7 m at most.
            nominal = pts[:] - g["drive"]["deviation"][:][..., None] * g["drive"]["normals"][:]
            r = np.hypot(nominal[..., 0], nominal[..., 1])
            assert r.min() > g["form_radius"][()] - 3e-7, (pair, member, r.min())
            assert r.max() < g["tip_radius"][()] + 3e-7, (pair, member, r.max())
    # synthesised spur measurement: all teeth, both sides, 261 points, deviations of a few um
    for member, z in (("pinion", 16), ("gear", 24)):
        g = f["measured"]["spur"][member]
        flanks = [n for n in g if n.startswith("tooth_")]
        assert len(flanks) == 2 * z, (member, len(flanks))
        dev = np.array([g[n]["deviation"][:] for n in flanks])
        assert dev.shape[1:] == (29, 9), dev.shape  # 29 profile x 9 face points
        # Per flank, the pitch error is a near-constant offset; what is left has the spread of
        # noise (1 um sd), roughness (0.3 um sd), waviness (0.5 um amplitude) and form error
        # (2 um peak, four random shapes): about 1.3 um.
        offsets = dev.mean(axis=(1, 2))
        rest = dev - offsets[:, None, None]
        assert 0.9e-6 < rest.std() < 1.5e-6, rest.std()
        assert offsets.std() > 1e-6, offsets.std()  # pitch errors of 3 um sd are there
    # unloaded TCA: 3 mesh cycles x 60 positions; the spur pinion's profile crowning gives
    # parabolic arcs (e_0 >= 0, minimum 0 where the contact passes the profile middle), the
    # crossed helical pair a sawtooth; every table has one row per position
    for pair in ("spur", "helical"):
        g = f["ste"][pair]
        te = g["transmission_error"][:]
        assert te.shape == (180,), te.shape
        assert g["contact_point"].shape[:2] == g["separation"].shape and g["separation"].shape[0] == 180
        assert g["peak_to_peak"][()] > 1e-6, (pair, g["peak_to_peak"][()])
    # the synthesised measured spur flanks (fast discrete-point mode) show the higher mesh
    # orders that the theoretical pair lacks (the seed's observation)
    theory, measured = f["ste"]["spur"]["harmonics"][:], f["ste"]["spur"]["measured"]["harmonics"][:]
    assert measured[4:].sum() > 3 * theory[4:].sum(), (theory, measured)
    spur = f["ste"]["spur"]["transmission_error"][:]
    assert spur.min() > -1e-12 and spur.min() < 1e-8, spur.min()
for name in ("spur_pinion", "spur_gear", "helical_pinion", "helical_gear"):
    assert os.path.getsize(os.path.join(out, "cmm", name + ".cmm")) > 1000, name
for png in ("profiles.png", "topography.png", "measured.png", "ste.png"):
    path = os.path.join(out, png)
    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n", path
    assert os.path.getsize(path) > 20000, path
print("default case: results.h5 and pictures OK")

#!/usr/bin/python3
"""Checks the seed spiral bevel case: the pair's cone geometry (reference-data.md section 1),
the classical transmission error synthesised to the seed's 3.72e-5 rad, the measured flanks'
higher mesh orders, and the pictures and harmonic table."""
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    fl = f["flanks"]["seed"]
    assert fl.attrs["type"] == "spiral bevel"
    assert abs(np.degrees(fl["pitch_angle_pinion"][()]) - 49.4846) < 5e-5
    assert abs(np.degrees(fl["pitch_angle_gear"][()]) - 40.5154) < 5e-5
    for member, z in (("pinion", 55), ("gear", 47)):
        pts = fl[member]["drive"]["points"]
        assert pts.shape == (z, 9, 29, 3), pts.shape
        assert np.all(np.isfinite(pts[:]))
    g = f["ste"]["seed"]
    pp = g["peak_to_peak"][()]
    assert abs(pp - 3.72e-5) < 0.02 * 3.72e-5, pp  # local synthesis hits the seed's amplitude
    assert g["transmission_error"].shape == (3 * 48,)
    lead = g["leading"][:]
    edges = g["edge_contact"][:][np.arange(len(lead)), lead]
    assert edges.sum() == 0, edges  # the bearing stays inside the flanks
    axes = g["contact_ellipse_axes"][:][np.arange(len(lead)), lead]
    assert np.all((axes[:, 0] > 2e-3) & (axes[:, 0] < 19e-3)), axes[:, 0]  # localised
    m = g["measured"]
    h, hm = g["harmonics"][:], m["harmonics"][:]
    assert hm[4:].sum() > 2 * h[4:].sum(), (h, hm)  # measured flanks: higher mesh orders
    assert m["peak_to_peak"][()] > pp
for name in ("ste.png", "contact_pattern.png", "measured.png"):
    path = os.path.join(out, name)
    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n", path
    assert os.path.getsize(path) > 20000, path
with open(os.path.join(out, "ste_harmonics.md")) as fh:
    table = fh.read()
assert "| 1x |" in table and "| 3x |" in table
print("seed spiral bevel case: geometry, TE amplitude, harmonics and pictures OK")

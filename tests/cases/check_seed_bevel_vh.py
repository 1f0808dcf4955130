#!/usr/bin/python3
"""Checks the seed_bevel_vh case, the V-H check of the seed's spiral bevel pair: the nominal
assembly's e_0 peak-to-peak is the 37.2 urad the pinion's modified roll was synthesised for
(within 3 %) and the least of the grid's single misalignments; the pattern centre at the design
torque walks monotonically along each axis (offset V toward the heel, pinion axial shift H
toward the toe: the bias a V-H chart shows) and stays on the flank; every grid point's tables
agree with its summaries; the picture."""
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    g = f["study"]["seed"]
    assert g.attrs.get("kind") in ("misalignments", b"misalignments")
    names = [n.strip() for n in str(g.attrs.get("parameters")).split(",")]
    assert names == ["offset", "pinion_axial_shift"], names
    shape = tuple(int(n) for n in g["shape"][()])
    grid = g["grid"][()]
    torques = g["torques"][()]
    m = int(np.argmin(np.abs(torques - g["design_torque"][()])))
    r = g["pitch_radius"][()]
    e0 = g["unloaded_te_peak_to_peak"][()]
    nominal = int(np.nonzero(~np.any(grid != 0, axis=1))[0][0])
    assert abs(e0[nominal] / 37.2e-6 - 1) < 0.03, e0[nominal]
    single = [k for k in range(len(grid)) if np.count_nonzero(grid[k]) == 1]
    assert single and all(e0[nominal] < e0[k] for k in single), e0
    # The pattern centre's face position [G] on the (V, H) grid: rises along V, falls along H.
    face = g["pattern_centre"][:, m, 1].reshape(shape)
    assert np.all(np.diff(face, axis=0) > 0), ("V moves the pattern toward the heel", face)
    assert np.all(np.diff(face, axis=1) < 0), ("H moves it toward the toe", face)
    pu, pf = g["pattern_profile_range"][()], g["pattern_face_range"][()]
    ext = g["pattern_extent"][()]
    assert np.all(ext[..., 0] >= pu[0] - 1e-9) and np.all(ext[..., 1] <= pu[1] + 1e-9)
    assert np.all(ext[..., 2] >= pf[0] - 1e-9) and np.all(ext[..., 3] <= pf[1] + 1e-9)
    eL = g["loaded_te"][()]
    assert np.allclose(g["te_peak_to_peak"][()], eL.max(axis=2) - eL.min(axis=2), rtol=1e-12)
    assert np.allclose(g["max_pressure"][()], g["pattern"][()].max(axis=(2, 3)), rtol=1e-12)
    assert np.all(np.isfinite(g["mesh_stiffness"][()])) and np.all(g["mesh_stiffness"][()] > 0)
    print("pattern centre along the face at %g N m [mm]:\n%s" % (torques[m], face * 1e3))
    print("e_0 p-p [um]:\n%s" % (e0.reshape(shape) * r * 1e6))
assert os.path.getsize(os.path.join(out, "vh_seed.png")) > 50000
print("seed_bevel_vh: ok")

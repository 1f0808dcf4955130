#!/usr/bin/python3
"""Checks the fzg_reference case: the reference mode at its positions against the fast mode at
the same positions (coarse on both sides: within 2 %), the reference torque balance, and the VTU
files (read by meshio, independently of deal.II): hexahedra, the displacement present and
finite, each member's largest displacement of the order of the loaded approach (the von Mises
stress is not checked)."""
import glob
import os
import sys

import h5py
import meshio
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    g = f["stiffness"]["fzg"]
    ref = g["reference"]
    pos = ref["position"][()]
    assert list(pos) == [0, 5], pos
    assert np.allclose(ref["pinion_angle"][()], g["pinion_angle"][()][pos], rtol=0, atol=1e-12)
    K_fast = g["mesh_stiffness"][()][:, pos]
    K_ref = ref["mesh_stiffness"][()]
    assert np.all(np.isfinite(K_ref)) and np.all(K_ref > 0), K_ref
    assert np.all(np.abs(K_fast / K_ref - 1) < 0.02), (K_fast, K_ref)
    torque = g["torque"][()]
    lever = g["lever"][()][:, pos]
    assert np.allclose(ref["normal_force"][()] * lever, torque[:, None], rtol=5e-3)
    de = ref["transmission_error_loaded"][()] - g["transmission_error_unloaded"][()][pos][None, :]
    assert np.all(de > 0), de
    rb = f["flanks"]["fzg"]["pinion"]["base_radius"][()]

files = sorted(glob.glob(os.path.join(out, "vtu", "fzg_position*_torque0_*.vtu")))
assert len(files) == 4, files
for name in files:
    m = meshio.read(name)
    assert "hexahedron" in m.cells_dict or "VTK_LAGRANGE_HEXAHEDRON" in str(m.cells), name
    keys = list(m.point_data.keys())
    disp = [k for k in keys if "displacement" in k.lower() or k.lower().startswith("u")]
    assert disp, (name, keys)
    u = np.asarray(m.point_data[disp[0]])
    assert np.all(np.isfinite(u)), name
    umax = np.linalg.norm(u.reshape(len(u), -1), axis=1).max()
    # the approach e_L - e_0 times the base radius is shared by both members: each moves by a
    # fraction of it at most (bores held)
    assert 1e-7 < umax < 2 * de.max() * rb, (name, umax, de.max() * rb)
print("fzg_reference: reference K_m", K_ref.ravel(), "fast", K_fast.ravel())

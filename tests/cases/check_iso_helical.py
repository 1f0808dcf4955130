#!/usr/bin/python3
"""Checks the iso_helical case (ISO/TR 6336-30 example, reference-data.md section 3): the
geometry's contact ratios against the example (eps_alpha 1.549) and the unloaded TCA
(pairs in contact average eps_alpha + eps_beta), ISO 6336-1 c'_th = 17.856 N/(mm um), the
torque balance with the helical lever r_b1 cos(beta_b), and the finite-element mesh stiffness
against ISO's theoretical mean stiffness c'_th (0.75 eps_alpha + 0.25) b (without the
standard's empirical C_M, C_B, cos beta, as the FE models theoretical solid gears): within the
15-20 % reference-data.md expects. With an overlap ratio near 1 the total contact line and
hence K_m barely change over the mesh cycle."""
import math
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    g = f["stiffness"]["iso"]
    p = f["flanks"]["iso"]["pinion"]
    b = p["face_width"][()]
    eps_a = g["transverse_contact_ratio"][()]
    eps_b = g["overlap_ratio"][()]
    assert abs(eps_a - 1.549) < 1e-3, eps_a
    assert abs(eps_b - b * math.sin(math.radians(15.8)) / (math.pi * 8e-3)) < 1e-9, eps_b
    n = g["pinion_angle"].shape[0]
    assert abs(g["mean_pairs_in_contact"][()] - (eps_a + eps_b)) <= 1.0 / n + 1e-9
    c_th = g["iso_c_th"][()]
    assert abs(c_th / (17.856e9 * b) - 1) < 1e-4, c_th

    torque = g["torque"][()]
    F = g["normal_force"][()]
    lever = g["lever"][()]
    lever_expected = p["base_radius"][()] * math.cos(p["base_helix_angle"][()])
    assert np.allclose(lever, lever_expected, rtol=1e-3), (lever.min(), lever_expected)
    assert np.allclose(F * lever, torque[:, None], rtol=1e-9), "torque balance"
    d = g["transmission_error_loaded"][()] - g["transmission_error_unloaded"][()][None, :]
    assert np.all(d > 0), "loaded TE lags the unloaded one"

    K = g["mesh_stiffness"][()]
    assert np.all(np.isfinite(K)) and np.all(K > 0)
    iso_mean = c_th * (0.75 * eps_a + 0.25)
    ratio = K.mean() / iso_mean
    assert abs(ratio - 1) < 0.2, (K.mean(), iso_mean)
    assert (K.max() - K.min()) / K.mean() < 0.1, (K.min(), K.max())
    print(f"K_m mean {K.mean() / 1e6:.0f} N/um ({(ratio - 1) * 100:+.1f} % against ISO "
          f"c'_th (0.75 eps_a + 0.25) b = {iso_mean / 1e6:.0f} N/um), over the cycle "
          f"{K.min() / 1e6:.0f}..{K.max() / 1e6:.0f} N/um; ISO c_gamma_alpha b "
          f"{g['iso_c_gamma_alpha'][()] / 1e6:.0f} N/um")
path = os.path.join(out, "stiffness.png")
assert os.path.getsize(path) > 10000, path
print("iso_helical: ok")

#!/usr/bin/python3
"""Checks the fzg_microgeometry case, the Harris map of the FZG C pair: every variant's contact
stayed inside its fixed zone; at every torque the loaded TE peak-to-peak falls to one least
relief and rises beyond it (the V of a Harris map); the least relief grows with the torque; at
the design torque the interpolated best relief agrees with the classical rule, the relief equal
to the mesh deflection F_bt / (b c_gamma) (ISO 6336-1's c_gamma, and the finite elements' own
K_m), within 15 %, and leaves less than a fifth of the unmodified pair's TE peak-to-peak; the
unmodified pair's mean K_m lies within 20 % of ISO 6336-1's c_gamma_alpha b; the picture."""
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    g = f["study"]["fzg"]
    torques = g["torques"][()]
    relief = g["axes"]["tip_relief"][()]
    pp = g["te_peak_to_peak"][()]  # [relief][torque]
    assert pp.shape == (relief.size, torques.size), pp.shape
    assert np.all(np.isfinite(pp)) and np.all(pp > 0)
    assert not np.any(g["zone_edge"][()]), "a contact reached the edge of its fixed zone"
    best = g["best_variant"][()]
    for m in range(torques.size):
        b = int(best[m])
        assert b == int(np.argmin(pp[:, m])), (m, b)
        assert np.all(np.diff(pp[: b + 1, m]) < 0), ("falls to the best relief", torques[m])
        assert np.all(np.diff(pp[b:, m]) > 0), ("rises beyond it", torques[m])
    assert np.all(np.diff(best) >= 0), ("the best relief grows with the torque", best)

    design = float(g["design_torque"][()])
    m = int(np.argmin(np.abs(torques - design)))
    assert torques[m] == design
    best_relief = float(g["best_relief_design"][()])
    iso = float(g["classical_relief_iso"][()])
    fe = float(g["mesh_deflection_design"][()])
    for rule, value in (("ISO 6336-1", iso), ("finite elements", fe)):
        assert abs(best_relief / value - 1) < 0.15, (rule, best_relief, value)
    unmodified = int(g["unmodified_variant"][()])
    assert relief[unmodified] == 0
    assert pp[best[m], m] < 0.2 * pp[unmodified, m], (pp[best[m], m], pp[unmodified, m])
    Km = g["stiffness_mean"][unmodified, m]
    assert abs(Km / g["iso_c_gamma_alpha"][()] - 1) < 0.2, Km
    r = g["pitch_radius"][()]
    print(f"best tip relief at {design:g} N m: {best_relief * 1e6:.1f} um (ISO F_bt/(b c_gamma) "
          f"{iso * 1e6:.1f} um, FE F_bt/K_m {fe * 1e6:.1f} um), TE p-p {pp[best[m], m] * r * 1e6:.2f}"
          f" um against {pp[unmodified, m] * r * 1e6:.2f} um unmodified")
assert os.path.getsize(os.path.join(out, "study_fzg.png")) > 50000
print("fzg_microgeometry: ok")

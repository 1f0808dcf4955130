#!/usr/bin/python3
"""Checks the seed002_power_loss case (seed 002's Figures 4 to 6, reference-data.md section 2):
the two-stage train with a crank-slider at its operating speed (input 167.5 rad/s, the others by
the exact ratios: 47.458 and 12.524 rad/s, not the seed's -73.5 rad/s) loses its power, only 1 %
friction torques left; perfect against a chipped tooth on gear A (input inertia 1.06e-3 against
1.04e-3 kg m^2), with c_max 10 N s/mm and with seed 001's damping reading (*_damper).

* kinematic initial speeds; no mesh touches at t = 0 (both start mid-backlash);
* the light input pinion is braked hardest: stage 1 touches first, on the coast flanks (the
  gear drives), then stage 2, coast only;
* the chipped pinion (2 % less inertia) touches a little earlier (the seed's statement);
* the output (gear D, shaft, crank, flywheel) is more than ten times heavier than the others;
* the damper contact's peaks are more than ten times the c_max = 10 N s/mm contact's;
* every energy balance within 1e-6.
"""
import os
import sys

import h5py

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    trains = f["train"]
    names = ["perfect", "chipped", "perfect_damper", "chipped_damper"]
    assert sorted(trains) == sorted(names), list(trains)
    first = {}
    for name in names:
        g = trains[name]
        assert g["energy_error"][()] < 1e-6, (name, g["energy_error"][()])
        w = g["initial_speed"][:]
        assert abs(w[1] - 167.5 * 17 / 60) < 1e-9 and abs(w[2] - 167.5 * 323 / 4320) < 1e-9, w
        J = g["inertia"][:]
        assert J[2] > 10 * max(J[0], J[1]), J
        assert abs(J[0] - (1.04e-3 if name.startswith("chipped") else 1.06e-3)) < 1e-15
        s1, s2 = g["meshes"]["stage1"], g["meshes"]["stage2"]
        assert 0 < s1["first_contact"][()] < s2["first_contact"][()], name
        for m in (s1, s2):
            assert m["drive_impacts"][()] == 0 and m["coast_impacts"][()] > 0, name
        first[name] = s1["first_contact"][()]
    assert first["chipped"] < first["perfect"] and first["chipped_damper"] < first["perfect_damper"]
    for name in ("perfect", "chipped"):
        for mesh in ("stage1", "stage2"):
            light = trains[name]["meshes"][mesh]["max_force"][()]
            damper = trains[name + "_damper"]["meshes"][mesh]["max_force"][()]
            assert damper > 10 * light, (name, mesh, light, damper)
for picture in ("train_perfect.png", "train_compare.png", "train_spectrogram.png"):
    path = os.path.join(out, picture)
    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n", path
    assert os.path.getsize(path) > 20000, path
print("seed002_power_loss: speeds, first contacts, flanks, inertias, energy balances OK")

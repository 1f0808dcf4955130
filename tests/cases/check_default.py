#!/usr/bin/python3
"""Checks the default case (the whole chain on the FZG C-type pair): every stage's results are
there and agree with what they can be checked against, and the report shows every picture."""
import os
import re
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    # flanks: the published centre distance (reference-data.md section 5)
    a = f["flanks/fzg/working_centre_distance"][()]
    assert abs(a - 91.5e-3) < 1e-5, a
    # unloaded TCA: three mesh cycles of 40 positions, theoretical and measured; the pitch
    # errors of the measured flanks (3 um sd) raise e_0 well above the theoretical 54 urad
    assert f["ste/fzg/transmission_error"].shape == (120,)
    assert f["ste/fzg/measured/peak_to_peak"][()] > 2 * f["ste/fzg/peak_to_peak"][()]
    # loaded contact: K_m against ISO 6336-1 method B (the standard's c_gamma_alpha b, an
    # empirical value: within its +-20 %), and a discretisation error estimate below 1 %
    st = f["stiffness/fzg"]
    km = st["mesh_stiffness"][0]
    iso = st["iso_c_gamma_alpha"][()]
    assert abs(km.mean() / iso - 1) < 0.2, (km.mean(), iso)
    est = np.abs(st["error_estimate/mesh_stiffness"][0]) / km
    assert 0 < est.mean() < 0.01, est.mean()
    # torque balance: F lambda = T at every position
    assert np.allclose(st["normal_force"][0] * st["lever"][0], 200, rtol=1e-6)
    # dynamics: the largest dynamic load factor of the theoretical up sweep sits where mesh
    # order 1 meets a mode that carries a large share of its energy in the mesh (within two
    # steps of the sweep); the load factor exceeds 1 there
    d = f["dynamics/fzg"]
    up = d["theoretical/up"]
    speed, dlf = up["speed"][()], up["dynamic_load_factor"][()]
    k = int(np.nanargmax(dlf))
    step = (speed.max() - speed.min()) / (len(speed) - 1)
    meshy = d["mode_mesh_energy"][()] > 0.2
    crossings = d["resonance_speed"][0][meshy]
    assert np.min(np.abs(crossings - speed[k])) < 2 * step, (speed[k], crossings)
    assert dlf[k] > 1.2, dlf[k]

# the report: one page, every picture of this run embedded once, the parameters as run
pngs = sorted(p for p in os.listdir(out) if p.endswith(".png"))
assert len(pngs) >= 9, pngs
with open(os.path.join(out, "report.html"), encoding="utf-8") as fh:
    page = fh.read()
assert page.count("data:image/png;base64,") == len(pngs), (page.count("data:image/png"), pngs)
for png in pngs:
    assert f"<b>{png}</b>" in page, png
assert "subsection Finite elements" in page and "local refinements" in page
assert re.search(r"K_m estimated discretisation error", page)
print(f"default case: K_m {km.mean() / 1e6:.1f} N/um (ISO c_gamma_alpha b {iso / 1e6:.1f}), "
      f"largest dynamic load factor {dlf[k]:.2f} at {speed[k]:.0f} rpm, {len(pngs)} pictures")

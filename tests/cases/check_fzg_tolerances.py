#!/usr/bin/python3
"""Checks the fzg_tolerances case, a tolerance Monte Carlo of the FZG C pair's relieved design
(ISO 1328-1 class 6 on both members, 200 samples over a pinion revolution at 200 N m): every
sample's contact stayed inside its fixed zone; the percentiles are ordered and those of the TE
peak-to-peak lie above the design's own (deviations add transmission error: the cumulative pitch
alone, F_p up to 28 um, exceeds the design's 1.5 um); the median has converged (the first half's
within 10 % of all samples'); the cumulative pitch deviations of the two members drive the TE
peak-to-peak most (the largest standardized regression coefficient, its interval clear of zero);
the deviations soften the mesh on average (the median K_m below the design's); the picture."""
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    g = f["study"]["fzg"]
    assert g.attrs.get("kind") == "tolerances", "a tolerance study"
    assert not np.any(g["zone_edge"][()]), "a contact reached the edge of its fixed zone"
    pp = g["te_peak_to_peak"][()][:, 0]
    assert pp.size == 200 and np.all(np.isfinite(pp)) and np.all(pp > 0)
    pct = g["percentiles/te_peak_to_peak"][0]
    assert np.all(np.diff(pct) > 0), pct
    nominal = g["nominal/te_peak_to_peak"][0]
    assert pct[0] > nominal, (pct, nominal)
    counts = g["convergence_samples"][()]
    conv = g["convergence/te_peak_to_peak"][0]
    half = int(np.argmin(np.abs(counts - counts[-1] / 2)))
    assert abs(conv[half, 1] / conv[-1, 1] - 1) < 0.1, conv[:, 1]
    names = g.attrs.get("features", "").split(",")
    sens = g["sensitivity/te_peak_to_peak"]
    c, low = sens["coefficient"][0], sens["low"][0]
    k = int(np.argmax(np.abs(c)))
    assert names[k] in ("pinion_cumulative_pitch", "gear_cumulative_pitch"), names[k]
    assert low[k] > 0, (names[k], c[k], low[k])
    assert g["percentiles/stiffness_mean"][0][1] < g["nominal/stiffness_mean"][0]
    r = g["pitch_radius"][()] * 1e6
    print(f"TE p-p {pct[0] * r:.2f} / {pct[1] * r:.2f} / {pct[2] * r:.2f} um (5 / 50 / 95 %), "
          f"the design alone {nominal * r:.2f} um; drives it most: {names[k]} (SRC {c[k]:+.2f})")
assert os.path.getsize(os.path.join(out, "tolerances_fzg.png")) > 50000
print("fzg_tolerances: ok")

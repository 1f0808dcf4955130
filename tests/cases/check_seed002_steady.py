#!/usr/bin/python3
"""Checks the seed002_steady case (seed 002's steady-state spectra, reference-data.md section 2):
the two-stage train 17/60 and 19/72 with a crank-slider, the input held at 167.5 rad/s (stage 1,
the seed's Figure 10a) or the output at 12.5237 rad/s (stage 2, Figures 10b and 11), 1 % of the
rated torques resisting on the other shafts; c_max 10 N s/mm (damper_input: 4000 N s/mm).

* kinematic frequencies: shafts 26.658 / 7.553 / 1.993 Hz, GMF1 453.19 Hz, GMF2 143.51 Hz;
* force spectra (4 s, 0.25 Hz bins): GMF1 and GMF2 with harmonics 2 to 4, each found within
  0.1 %; the crank-slider's second order (2 x 1.993 Hz: its inertia varies twice a turn) as
  sidebands around GMF1 harmonics; with the output held stage 1 rattles and, recorded without
  aliasing, keeps a floor below 0.01 N around the GMF1 lines (point samples folded the impacts
  back into a 0.1 N floor); perfect teeth on gear A give no sidebands at the input speed
  (+-26.66 Hz) around GMF2, a chipped tooth on A gives them around GMF1; the eccentric tooth on
  gear C the intermediate shaft's orders 7.553 Hz x 1..4 and sidebands +-7.553 Hz around GMF2,
  and a larger GMF1 line than the perfect train's (the seed: +50.4 %);
* seed 001's damping reading (the damper contact) rattles: a broadband floor far above the
  c_max = 10 N s/mm train's;
* every energy balance within 1e-6.
"""
import os
import sys

import h5py
import numpy as np

F_IN, F_I = 167.5 / (2 * np.pi), 167.5 * 17 / 60 / (2 * np.pi)
F_OUT = F_I * 19 / 72  # the total ratio 4320 / 323 = 13.3746 (the seed: 13.375)
GMF1, GMF2 = 17 * F_IN, 19 * F_I


def lines(g, mesh):
    t = g["meshes"][mesh]["spectrum"]["lines"]
    return {k: t[k][:] for k in ("expected", "frequency", "amplitude", "floor", "found", "harmonic",
                                  "sideband", "shaft")}


def line(t, harmonic, sideband=0, shaft=-1):
    k = np.nonzero((t["harmonic"] == harmonic) & (t["sideband"] == sideband) &
                   (t["shaft"] == shaft))[0]
    assert k.size == 1, (harmonic, sideband, shaft)
    return {key: v[k[0]] for key, v in t.items()}


def found_within(t, harmonic, sideband, shaft, frequency, tolerance=1e-3):
    x = line(t, harmonic, sideband, shaft)
    return bool(x["found"]) and abs(x["frequency"] / frequency - 1) < tolerance


out = sys.argv[1]
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    trains = f["train"]
    names = ["perfect_input", "damper_input", "perfect_output", "eccentric_output",
             "chipped_output"]
    assert sorted(trains) == sorted(names), list(trains)
    for name in names:
        g = trains[name]
        assert g["energy_error"][()] < 1e-6, (name, g["energy_error"][()])
        k = g["kinematics"]
        assert np.allclose(k["shaft_frequency"][:], [F_IN, F_I, F_OUT], rtol=1e-6), name
        assert np.allclose(k["mesh_frequency"][:], [GMF1, GMF2], rtol=1e-6), name
    assert abs(GMF1 - 453.19) < 0.01 and abs(GMF2 - 143.51) < 0.01

    stage1 = lines(trains["perfect_input"], "stage1")
    for h in (1, 2, 3, 4):
        assert found_within(stage1, h, 0, -1, h * GMF1), ("GMF1", h, line(stage1, h))
    crank = sum(found_within(stage1, h, s, 2, h * GMF1 + s * F_OUT) for h in (1, 2, 3, 4)
                for s in (-2, 2))
    assert crank >= 4, crank

    # with the output held stage 1 rattles (its impacts are broadband): recorded without
    # aliasing, the floor around the GMF1 lines stays below 0.01 N. Point samples folded the
    # impacts' content back: a floor of 0.1 N at 20 kHz (on which six of the eight +-1.993 Hz
    # sidebands stood four times above it: folded content, not found at 200 kHz either, where
    # the floor is 0.013 N)
    output_held = lines(trains["perfect_output"], "stage1")
    for h in (1, 2, 3, 4):
        floor = line(output_held, h)["floor"]
        assert floor < 0.01, ("stage 1 floor with the output held", h, floor)

    stage2 = lines(trains["perfect_output"], "stage2")
    for h in (1, 2, 3, 4):
        assert found_within(stage2, h, 0, -1, h * GMF2), ("GMF2", h, line(stage2, h))
    for h in (1, 2, 3, 4):
        for s in (-1, 1):
            assert not line(stage2, h, s, 0)["found"], ("+-26.66 Hz around GMF2", h, s)

    chipped = lines(trains["chipped_output"], "stage1")
    input_sidebands = sum(found_within(chipped, h, s, 0, h * GMF1 + s * F_IN)
                          for h in (1, 2, 3, 4) for s in (-2, -1, 1, 2))
    assert input_sidebands >= 6, input_sidebands

    eccentric = lines(trains["eccentric_output"], "stage2")
    for j in (1, 2, 3, 4):
        assert found_within(eccentric, 0, j, 1, j * F_I), ("7.553 Hz family", j)
    around = sum(found_within(eccentric, h, s, 1, h * GMF2 + s * F_I) for h in (1, 2, 3, 4)
                 for s in (-1, 1))
    assert around >= 7, around
    gmf1_eccentric = line(lines(trains["eccentric_output"], "stage1"), 1)["amplitude"]
    gmf1_perfect = line(lines(trains["perfect_output"], "stage1"), 1)["amplitude"]
    assert gmf1_eccentric > 1.2 * gmf1_perfect, (gmf1_eccentric, gmf1_perfect)

    damper = line(lines(trains["damper_input"], "stage1"), 1)["floor"]
    assert damper > 10 * line(stage1, 1)["floor"], (damper, line(stage1, 1)["floor"])
for picture in ("train_perfect_input.png", "train_eccentric_output.png", "train_compare.png",
                "train_spectrogram.png"):
    path = os.path.join(out, picture)
    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n", path
    assert os.path.getsize(path) > 20000, path
print("seed002_steady: GMF lines, sidebands, the eccentric tooth's family and energy balances OK")

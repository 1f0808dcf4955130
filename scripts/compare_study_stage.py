#!/usr/bin/env python3
"""One micro-geometry map variant against the stiffness stage of the same modified scene.

usage: compare_study_stage.py STUDY_RESULTS.h5 STAGE_RESULTS.h5 VARIANT [PAIR]
                              [FINE_RESULTS.h5 [LAYOUT_RESULTS.h5 ...]]

STUDY_RESULTS holds /study/<pair> of a map (kind = microgeometry map); STAGE_RESULTS the
/stiffness/<pair> of a scene with the variant's modifications written into its flanks and the
map's torques and positions (its compliance computed again: the compliance stage takes the
pair's macro-geometry, so it equals the map's). Prints per torque the TE peak-to-peak of both,
K_m's mean and its worst position, and the largest e_L difference; with FINE_RESULTS (the same
scene on finer contact cells, some of the torques) both against it; LAYOUT_RESULTS (the same
scene on other cell layouts, e.g. another `cells across`) against it as well: the stage's own
sensitivity to its cells, which the study's fixed zones are to be judged by. bench/README.md
quotes it.
"""
import sys

import h5py
import numpy as np


def peak_to_peak(x):
    return float(np.max(x) - np.min(x))


def compare(label, a, Ka, b, Kb):
    return (f"{label}: TE p-p {peak_to_peak(a) * 1e6:9.3f} against {peak_to_peak(b) * 1e6:9.3f} "
            f"urad ({(peak_to_peak(a) / peak_to_peak(b) - 1) * 100:+.3f} %), K_m mean "
            f"{(Ka.mean() / Kb.mean() - 1) * 100:+.4f} %, worst position "
            f"{np.max(np.abs(Ka / Kb - 1)) * 100:.3f} %, e_L worst {np.max(np.abs(a - b)) * 1e6:.2f} urad")


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    variant = int(argv[3])
    pair = argv[4] if len(argv) > 4 else "fzg"
    study = h5py.File(argv[1], "r")[f"study/{pair}"]
    stage = h5py.File(argv[2], "r")[f"stiffness/{pair}"]
    if not np.allclose(study["pinion_angle"][()], stage["pinion_angle"][()], atol=1e-12):
        sys.exit("the study's and the stage's positions differ: give the stage the study's "
                 "positions per mesh cycle and start angle")
    e0 = np.max(np.abs(study["unloaded_te"][variant] - stage["transmission_error_unloaded"][()]))
    print(f"e_0: largest difference {e0 * 1e6:.2e} urad")
    torques = list(study["torques"][()])
    for k, T in enumerate(stage["torque"][()]):
        m = torques.index(T)
        print(f"{T:6.0f} N m  " + compare(
            "study vs stage", study["loaded_te"][variant, m], study["mesh_stiffness"][variant, m],
            stage["transmission_error_loaded"][k], stage["mesh_stiffness"][k]))
    if len(argv) > 5:
        fine = h5py.File(argv[5], "r")[f"stiffness/{pair}"]
        # the stage and any further layouts of the same scene, each against the fine cells
        runs = [("stage", stage)] + [(path, h5py.File(path, "r")[f"stiffness/{pair}"])
                                     for path in argv[6:]]
        run_torques = [list(run["torque"][()]) for _, run in runs]
        for k, T in enumerate(fine["torque"][()]):
            f, Kf = fine["transmission_error_loaded"][k], fine["mesh_stiffness"][k]
            m = torques.index(T)
            print(f"{T:6.0f} N m  " + compare("study vs fine", study["loaded_te"][variant, m],
                                              study["mesh_stiffness"][variant, m], f, Kf))
            for (label, run), listed in zip(runs, run_torques):
                if T in listed:
                    o = listed.index(T)
                    print(f"{T:6.0f} N m  " + compare(f"{label} vs fine",
                                                      run["transmission_error_loaded"][o],
                                                      run["mesh_stiffness"][o], f, Kf))

if __name__ == "__main__":
    main(sys.argv)

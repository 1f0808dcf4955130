#!/usr/bin/env python3
"""The loaded contact across load and size (issue 36), through the whole chain (finite-element
compliance + half-space contact): a 20/31 spur pair, m 3 mm, b 15 mm, bores 30/45 mm,

  light load:  K_m and e_L - e_0 at pinion torques 1e-3 ... 3000 N m (one scene);
  similarity:  the pair scaled by s = 0.05 ... 10 (every length times s, torque 100 s^3 N m, the
               nominal tooth load kept): K_m / s, e_L - e_0 and the peak pressure stay.

usage: design_space_study.py GEARKIT OUTDIR   (writes OUTDIR/design_space.png and .txt)
Each scene runs the executable from an argument vector; about 40 s per scene on 2 cores."""
import os
import subprocess
import sys

import h5py
import numpy as np

from spur_study_scene import spur_study_scene



def run(gearkit, out, name, s, torques):
    text = spur_study_scene(scale=s, torques=torques, positions=4)
    scene = os.path.join(out, name + ".prm")
    with open(scene, "w") as f:
        f.write(text)
    subprocess.run([gearkit, "--output-root", out, scene], check=True,
                   stdout=subprocess.DEVNULL)
    with h5py.File(os.path.join(out, name, "results.h5"), "r") as f:
        g = f["stiffness/p"]
        e = g["transmission_error_loaded"][:] - g["transmission_error_unloaded"][:][None, :]
        return (g["torque"][:], g["mesh_stiffness"][:].mean(axis=1), e.mean(axis=1),
                g["peak_pressure"][:].max(axis=1), g["interior_peak_pressure"][:].max(axis=1),
                g["edge_load_share"][:].max(axis=1))


def main():
    gearkit, out = sys.argv[1], os.path.abspath(sys.argv[2])
    os.makedirs(out, exist_ok=True)
    lines = []
    torques = [1e-3, 1e-2, 1e-1, 1, 10, 100, 1000, 3000]
    T, K, e, p, pi_, edge = run(gearkit, out, "light", 1.0, torques)
    lines.append("light load: T [N m], K_m mean [N/um], e_L-e_0 mean [urad], peak, interior "
                 "peak [MPa], largest edge share")
    for row in zip(T, K / 1e6, e * 1e6, p / 1e6, pi_ / 1e6, edge):
        lines.append("  %-8g %8.2f %12.5g %9.1f %9.1f %6.3f" % row)
    scales = [0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0]
    sim = []
    for s in scales:
        r = run(gearkit, out, "scale_" + f"{s:g}".replace(".", "p"), s, [100 * s**3])
        sim.append([x[0] for x in r])
    lines.append("similarity: s, K_m/s [N/um], e_L-e_0 [urad], peak pressure [MPa]")
    for s, r in zip(scales, sim):
        lines.append("  %-5g %8.3f %10.4f %8.1f" % (s, r[1] / s / 1e6, r[2] * 1e6, r[3] / 1e6))
    with open(os.path.join(out, "design_space.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.4))
    ax[0].semilogx(T, K / 1e6, "o-")
    ax[0].set(xlabel="pinion torque [N m]", ylabel="K_m, mean over the cycle [N/µm]",
              title="Light to heavy load: K_m")
    ax[1].loglog(T, e * 1e6, "o-", label="e_L - e_0")
    ax[1].loglog(T, e[5] * 1e6 * np.asarray(T) / T[5], "--", label="∝ T (linear)")
    ax[1].set(xlabel="pinion torque [N m]", ylabel="e_L - e_0, mean [µrad]",
              title="Loaded TE against torque")
    ax[1].legend()
    k = np.array([r[1] / s for s, r in zip(scales, sim)])
    ax[2].semilogx(scales, k / k[scales.index(1.0)], "o-", label="K_m / s")
    ax[2].semilogx(scales, [r[2] / sim[scales.index(1.0)][2] for r in sim], "s--",
                   label="e_L - e_0")
    ax[2].semilogx(scales, [r[3] / sim[scales.index(1.0)][3] for r in sim], "^:",
                   label="peak pressure")
    ax[2].set(xlabel="scale s (m_n = 3 s mm)", ylabel="relative to s = 1",
              title="Geometric similarity, T = 100 s³ N m", ylim=(0.9, 1.1))
    ax[2].legend()
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "design_space.png"), dpi=110)


if __name__ == "__main__":
    main()

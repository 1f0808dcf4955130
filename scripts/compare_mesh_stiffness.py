#!/usr/bin/env python3
"""K_m over the mesh cycle from several results.h5 files on one picture, each with its error
estimate as a band where the file has one (stiffness/<pair>/error_estimate).

usage: compare_mesh_stiffness.py OUT.png PAIR LABEL=results.h5 [LABEL=results.h5 ...]
       [--torque T] [--from X --to Y]   (mesh cycles; default the whole cycle)
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("pair")
    ap.add_argument("runs", nargs="+", help="LABEL=results.h5")
    ap.add_argument("--from", dest="lo", type=float, default=None)
    ap.add_argument("--to", dest="hi", type=float, default=None)
    a = ap.parse_args()
    fig, axes = plt.subplots(1, 1, figsize=(10, 5.5))
    markers = "os^vDx+"
    for n, run in enumerate(a.runs):
        if "=" not in run:
            sys.exit(f"compare_mesh_stiffness.py: '{run}' is not LABEL=results.h5")
        label, path = run.split("=", 1)
        with h5py.File(path, "r") as f:
            g = f[f"stiffness/{a.pair}"]
            z1 = f[f"flanks/{a.pair}/pinion/number_of_teeth"][()]
            x = g["pinion_angle"][()] / (2 * np.pi / z1)
            x = x - np.floor(x[0])
            for k, t in enumerate(g["torque"][()]):
                km = g["mesh_stiffness"][k] * 1e-6
                line, = axes.plot(x, km, "-" + markers[n % len(markers)], ms=3.5, lw=1,
                                  label=f"{label}, {t:g} N m")
                if "error_estimate" in g:
                    e = g["error_estimate/mesh_stiffness"][k] * 1e-6
                    axes.fill_between(x, km - e, km + e, color=line.get_color(), alpha=0.18, lw=0)
    if a.lo is not None or a.hi is not None:
        axes.set_xlim(a.lo, a.hi)
    axes.set_xlabel("mesh cycles")
    axes.set_ylabel("K_m [N/um]")
    axes.set_title(f"{a.pair}: mesh stiffness (bands: estimated discretisation error)")
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Element studies of issue 36 on the spur pair 20/31 (m 3 mm, b 15 mm, bores 30 / 45 mm, 100 N m,
20 positions per mesh cycle): the mean mesh stiffness K_m as the finite elements change.

    scripts/element_study.py refinement [--sizes 2,1,0.5,0.25] [--runs N] [options]
    scripts/element_study.py locking [--degrees 1,2] [--poisson 0.3,0.45,0.49,0.499] [options]

refinement: one run per flank element size [m_n] (`Finite elements/<pair>/flank element size`;
the other flanks and fillets the same, far elements 1 m_n), with the elements the mesh really
has at the central tooth's loaded flank (along the profile, over the face) read from the
segment's gmsh file, the change to the previous size and the Richardson estimate of the error
left, |K(h) - K(2h)| / (2^p - 1) with the order p observed over the last three sizes that halve
(2 where it cannot be observed). locking: K_m for every degree and Poisson's ratio (flank size
--size), each degree against degree 2 at the same ratio.

Every run is a `gearkit` run of its own scene in --work (default /tmp/gearkit-element-study),
its cache cleared first; the time is the compliance stage's (both members, the `seconds` the
tables record), the median of --runs runs. Prints a Markdown table (bench/README.md, "Element
refinement study (issue 36)").
"""
import argparse
import contextlib
import glob
import io
import os
import shutil
import statistics
import subprocess
import sys

import h5py
import meshio
import numpy as np

from spur_study_scene import spur_study_scene



def run(args, name, size, degree, poisson, extra=""):
    """K_m mean [N/um], per position, dofs (pinion, gear) and the median compliance time [s]."""
    os.makedirs(args.work, exist_ok=True)
    scene = os.path.join(args.work, name + ".prm")
    with open(scene, "w") as f:
        f.write(spur_study_scene(finite_elements=f"    set flank element size = {size}\n"
                                                 f"    set degree             = {degree}\n"
                                                 f"    set Poisson's ratio    = {poisson}\n"
                                                 + extra))
    seconds = []
    for _ in range(args.runs):
        shutil.rmtree(os.path.join(args.work, "out", name, "cache"), ignore_errors=True)
        env = dict(os.environ, GEARKIT_PROGRESS="0")
        done = subprocess.run([args.gearkit, scene], cwd=args.work, env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if done.returncode != 0:
            sys.exit(f"element_study.py: {name} failed:\n{done.stdout}")
        with h5py.File(os.path.join(args.work, "out", name, "results.h5"), "r") as h5:
            seconds.append(sum(h5[f"compliance/p/{m}/seconds"][()] for m in ("pinion", "gear")))
            km = h5["stiffness/p/mesh_stiffness"][0] * 1e-6
            dofs = [int(h5[f"compliance/p/{m}/dofs"][()]) for m in ("pinion", "gear")]
            warnings = h5.attrs.get("warnings", [])
            warnings = warnings.splitlines() if isinstance(warnings, str) else list(warnings)
    return {"km": km, "mean": float(np.mean(km)), "dofs": dofs, "seconds": statistics.median(seconds),
            "mesh": loaded_flank_elements(args, name), "warnings": warnings}


def loaded_flank_elements(args, name):
    """Elements along the profile and over the face of the pinion's central tooth's drive flank
    (the segment's middle tooth) in the gmsh file the run left in its cache."""
    files = glob.glob(os.path.join(args.work, "out", name, "cache", "*", "*Pinion_segment.msh"))
    if not files:
        return None
    with contextlib.redirect_stdout(io.StringIO()):  # meshio's progress lines
        mesh = meshio.read(files[0])
    tags = {n: t for n, (t, dim) in mesh.field_data.items()}
    teeth = sorted(n for n in tags if n.endswith("_drive"))
    group = tags[teeth[len(teeth) // 2]]
    quads = [blk.data[phys == group] for blk, phys in zip(mesh.cells, mesh.cell_data["gmsh:physical"])
             if blk.type == "quad"]
    nodes = mesh.points[np.unique(np.concatenate(quads))]
    z = np.unique(np.round(nodes[:, 2] * 1e9))
    front = nodes[np.abs(nodes[:, 2] - nodes[:, 2].min()) < 1e-9]
    return len(front) - 1, len(z) - 1


def refinement(args):
    sizes = [float(s) for s in args.sizes.split(",")]
    rows = [(h, run(args, "refine_" + f"{h:g}".replace(".", "p"), h, 2, 0.3, args.extra))
            for h in sizes]
    print("| flank element size [m_n] | elements at the loaded flank (profile × face) | dofs "
          "(pinion / gear) | K_m mean [N/µm] | change | Richardson error estimate | "
          "compliance time [s] |")
    print("|---|---|---|---|---|---|---|")
    means = [r["mean"] for _, r in rows]
    for k, (h, r) in enumerate(rows):
        change = f"{means[k] - means[k - 1]:+.3f}" if k > 0 else "–"
        estimate = "–"
        if k > 0 and abs(sizes[k - 1] / h - 2) < 1e-9:
            p = 2.0
            if k > 1 and abs(sizes[k - 2] / sizes[k - 1] - 2) < 1e-9:
                d1, d2 = means[k - 1] - means[k - 2], means[k] - means[k - 1]
                if d1 * d2 > 0 and abs(d2) < abs(d1):
                    p = np.log2(d1 / d2)
            estimate = f"{abs(means[k] - means[k - 1]) / (2 ** p - 1):.3f} (p = {p:.2f})"
        mesh = "{} × {}".format(*r["mesh"]) if r["mesh"] else "?"
        print(f"| {h:g} | {mesh} | {r['dofs'][0]} / {r['dofs'][1]} | {r['mean']:.3f} | {change} | "
              f"{estimate} | {r['seconds']:.1f} |")


def locking(args):
    degrees = [int(d) for d in args.degrees.split(",")]
    ratios = [float(v) for v in args.poisson.split(",")]
    found = {}
    for nu in ratios:
        for d in degrees:
            name = f"lock_q{d}_nu{nu:g}".replace(".", "p")
            try:
                found[(d, nu)] = run(args, name, args.size, d, nu, args.extra)
            except SystemExit as refused:
                found[(d, nu)] = {"refused": str(refused).splitlines()[-1]}
    print("| Poisson's ratio | " + " | ".join(f"degree {d}: K_m [N/µm], time [s]" for d in degrees)
          + " | " + " | ".join(f"degree {d} / degree 2" for d in degrees if d != 2) + " |")
    print("|---" * (1 + len(degrees) + sum(d != 2 for d in degrees)) + "|")
    for nu in ratios:
        cells = []
        for d in degrees:
            r = found[(d, nu)]
            cells.append("refused" if "refused" in r else f"{r['mean']:.2f}, {r['seconds']:.1f}")
        for d in degrees:
            if d == 2:
                continue
            a, b = found[(d, nu)], found.get((2, nu), {})
            cells.append(f"{a['mean'] / b['mean']:.4f}" if "mean" in a and "mean" in b else "–")
        print(f"| {nu:g} | " + " | ".join(cells) + " |")
    for key, r in found.items():
        for w in r.get("warnings", []):
            print(f"degree {key[0]}, nu {key[1]:g}: warning: {w}")
        if "refused" in r:
            print(f"degree {key[0]}, nu {key[1]:g}: {r['refused']}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("study", choices=["refinement", "locking"])
    ap.add_argument("--gearkit", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                      "gearkit"))
    ap.add_argument("--work", default="/tmp/gearkit-element-study")
    ap.add_argument("--runs", type=int, default=1, help="runs per setting (median time)")
    ap.add_argument("--sizes", default="2,1,0.5,0.25", help="flank element sizes [m_n]")
    ap.add_argument("--size", type=float, default=0.25, help="locking: flank element size [m_n]")
    ap.add_argument("--degrees", default="1,2")
    ap.add_argument("--poisson", default="0.3,0.45,0.49,0.499")
    ap.add_argument("--set", dest="extra", action="append", default=[],
                    help="another Finite elements/<pair> parameter, 'name = value'")
    args = ap.parse_args()
    args.gearkit = os.path.abspath(args.gearkit)
    args.extra = "".join(f"    set {s}\n" for s in args.extra)
    (refinement if args.study == "refinement" else locking)(args)


if __name__ == "__main__":
    main()

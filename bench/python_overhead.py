#!/usr/bin/python3
"""The Python layer's overhead: the default case run by the executable and by
gearkit.run_scene, each from nothing (a fresh output root: every stage computed) in a process of
its own, wall time from start to exit, medians of N runs taken in turns; and the cost of one
call into the compiled module and of the Scene and Results accessors (timeit, median of 7).

  bench/python_overhead.py [BUILD_DIR] [N]      (default build, 3)

Run it alone on the machine (the figures are wall times). OPENBLAS_CORETYPE is set as the
executable sets it, so that both run the same kernels.
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time
import timeit

top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
build = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(top, "build")
n = int(sys.argv[2]) if len(sys.argv) > 2 else 3
python = os.path.join(build, "python")
scene = os.path.join(top, "cases", "default.prm")
env = dict(os.environ, PYTHONPATH=python, OPENBLAS_NUM_THREADS=os.environ.get(
    "OPENBLAS_NUM_THREADS", "1"))
if "OPENBLAS_CORETYPE" not in env:
    fitting = subprocess.run([sys.executable, "-c", "import gearkit._core as c; "
                              "print(c.fitting_blas_kernels())"], env=env, check=True,
                             capture_output=True, text=True).stdout.strip()
    if fitting:
        env["OPENBLAS_CORETYPE"] = fitting


def wall(command):
    with tempfile.TemporaryDirectory(prefix="gearkit-bench-") as root:
        start = time.perf_counter()
        subprocess.run(command(root), env=env, check=True, stdout=subprocess.DEVNULL)
        return time.perf_counter() - start


executable = lambda root: [os.path.join(build, "gearkit"), "--output-root", root, scene]
module = lambda root: [sys.executable, "-c", "import gearkit, sys; "
                       f"gearkit.run_scene({scene!r}, output_root=sys.argv[1])", root]
times = {"executable": [], "python": []}
for _ in range(n):
    times["executable"].append(wall(executable))
    times["python"].append(wall(module))
te, tp = statistics.median(times["executable"]), statistics.median(times["python"])
print(f"default case from nothing, median of {n}: executable {te:.2f} s, "
      f"gearkit.run_scene {tp:.2f} s, Python layer {100 * (tp - te) / te:+.2f} % "
      f"(all: executable {['%.2f' % t for t in times['executable']]}, "
      f"python {['%.2f' % t for t in times['python']]})")

sys.path.insert(0, python)
os.environ.update(env)
import gearkit  # noqa: E402

s = gearkit.Scene(scene)
with tempfile.TemporaryDirectory(prefix="gearkit-bench-") as root:
    r = gearkit.run_scene(scene, output_root=root)
    calls = {
        "_core.blas_kernels() (one call into the module)": lambda: gearkit._core.blas_kernels(),
        "Scene[path]": lambda: s["Loaded contact/fzg/torques"],
        "Scene.check() after a change (the driver reads the scene)":
            lambda: (s.set("Dynamics/fzg/speeds", 120), s.check()),
        "Results[path] (h5py read of K_m)": lambda: r["stiffness/fzg/mesh_stiffness"],
        "Results.dataset('stiffness/fzg') (xarray)": lambda: r.dataset("stiffness/fzg"),
    }
    for what, call in calls.items():
        number = 1000 if "blas" in what or "Scene[" in what else 20
        per = statistics.median(timeit.repeat(call, number=number, repeat=7)) / number
        print(f"{what}: {per * 1e6:.2f} us")

    # Library level on the run's cached compliance: the loaded contact at one torque (the
    # scene's positions), the compiled call alone and with the xarray Dataset built around it;
    # one flank point (Flanks.evaluate) as the smallest library call.
    loaded = s.loaded_pair("fzg", output_root=root)
    pinion = loaded.members[0]
    u = sum(pinion.domain(0, "drive")[:2]) / 2
    lib = {
        "LoadedPair.loaded_contact([150]) (xarray)": lambda: loaded.loaded_contact([150.0]),
        "_core loaded_contact([150]) (NumPy dict)":
            lambda: loaded._core.loaded_contact([150.0], 0, None, None),
        "Flanks.evaluate (one flank point)": lambda: pinion.evaluate(0, "drive", u, 0.0),
    }
    for what, call in lib.items():
        number = 1000 if "evaluate" in what else 1
        repeat = 7 if "evaluate" in what else 5
        per = statistics.median(timeit.repeat(call, number=number, repeat=repeat)) / number
        print(f"{what}: {per * 1e6:.2f} us" if per < 1e-2 else f"{what}: {per:.3f} s")

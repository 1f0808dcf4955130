#!/usr/bin/env python3
"""The gearkit executable where the disk or another run is in the way (CTest driver_failure_paths).

usage: check_failure_paths.py GEARKIT WORK_DIR

Each case runs the executable as a user would and asserts: it ends by itself (an exit status,
not a signal: no SIGSEGV in HDF5's exit handling), with status 1, a message naming the file and
the cause, and no temporary file left behind.
  * the disk full while a stage writes its cache file (the temporary is a link to /dev/full,
    whose writes fail with ENOSPC: a full disk without mounting one);
  * the disk full while results.h5 is written;
  * the output folder held by another process (its process id named).
"""
import fcntl
import os
import shutil
import subprocess
import sys

SCENE = """
subsection Scene
  set name    = small
  set outputs = flanks
  set pairs   = p1
end
subsection Flanks
  subsection p1
    set grid profile points = 3
    set grid face points    = 4
    subsection Pinion
      set number of teeth = 19
      set normal module   = 2
    end
    subsection Gear
      set number of teeth = 37
      set normal module   = 2
    end
  end
end
"""

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED:", what)


def run(gearkit, root, scene):
    p = subprocess.run([gearkit, "--output-root", root, scene], capture_output=True, text=True,
                       timeout=300, stdin=subprocess.DEVNULL)
    return p.returncode, p.stdout, p.stderr


def leftovers(folder):
    return [os.path.join(d, f) for d, _, files in os.walk(folder) for f in files
            if f.endswith(".tmp") or ".tmp." in f]


def main():
    gearkit, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    scene = os.path.join(work, "small.prm")
    with open(scene, "w") as f:
        f.write(SCENE)
    root = os.path.join(work, "out")
    code, out, err = run(gearkit, root, scene)
    check(code == 0, f"a clean run: exit {code}: {err}")
    cache = os.path.join(root, "small", "cache")
    flanks = [f for f in os.listdir(cache) if f.startswith("flanks-") and f.endswith(".h5")][0]
    results = os.path.join(root, "small", "results.h5")

    # 1. The disk full while the flanks stage writes its cache file.
    os.remove(os.path.join(cache, flanks))
    os.symlink("/dev/full", os.path.join(cache, flanks + ".tmp"))
    code, out, err = run(gearkit, root, scene)
    print("full disk, cache:", code, err.strip())
    check(code == 1, f"full disk at the cache: exit status {code} (negative: a signal)")
    check(flanks in err and "No space left on device" in err,
          f"full disk at the cache: the file and the cause named: {err}")
    check(not leftovers(root), f"full disk at the cache: left {leftovers(root)}")
    check(not os.path.exists(os.path.join(cache, flanks)), "full disk: a cache file under its name")

    # 2. The disk full while results.h5 is written.
    code, out, err = run(gearkit, root, scene)
    check(code == 0, f"a clean run again: exit {code}: {err}")
    os.remove(results)
    os.symlink("/dev/full", results + ".tmp")
    code, out, err = run(gearkit, root, scene)
    print("full disk, results:", code, err.strip())
    check(code == 1, f"full disk at results.h5: exit status {code} (negative: a signal)")
    check("results.h5" in err and "No space left on device" in err,
          f"full disk at results.h5: the file and the cause named: {err}")
    check(not leftovers(root), f"full disk at results.h5: left {leftovers(root)}")
    check(not os.path.exists(results), "full disk at results.h5: a results.h5 written")

    # 3. Another process holds the output folder.
    lock = os.path.join(root, "small", ".gearkit.lock")
    with open(lock, "a+") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        held.seek(0)
        held.truncate()
        held.write(f"{os.getpid()}\n")
        held.flush()
        code, out, err = run(gearkit, root, scene)
        print("folder held:", code, err.strip())
        check(code == 1, f"folder held: exit status {code}")
        check(f"in use by another gearkit run (process {os.getpid()})" in err,
              f"folder held: the other run's process named: {err}")
        check("stage " not in out, "folder held: a stage ran")
    code, out, err = run(gearkit, root, scene)
    check(code == 0, f"the folder free again: exit {code}: {err}")

    print(f"{3 - len(set(f.split(':')[0] for f in failures))} of 3 cases clear")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()

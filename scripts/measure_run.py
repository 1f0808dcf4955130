#!/usr/bin/env python3
"""Runs a command and reports its wall time and the peak of the memory its processes hold
together (the resident sets of the command and all its descendants, summed, sampled every
0.1 s): under mpirun the processes' sum, which /usr/bin/time's largest single process is not.

    scripts/measure_run.py [--runs N] -- COMMAND ...

Prints one line per run and, with several runs, the median; exits with the command's status
(the first failing run's). For the benchmark figures of bench/README.md.
"""
import os
import statistics
import subprocess
import sys
import time


def descendants(root):
    """The process ids under root (root included), from /proc."""
    children = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            children.setdefault(int(fields[1]), []).append(int(entry))
        except OSError:
            continue
    found, todo = [], [root]
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo.extend(children.get(pid, []))
    return found


def resident_bytes(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def measure(command):
    start = time.monotonic()
    process = subprocess.Popen(command)
    peak = 0
    while process.poll() is None:
        peak = max(peak, sum(resident_bytes(p) for p in descendants(process.pid)))
        time.sleep(0.1)
    return process.returncode, time.monotonic() - start, peak


def main(argv):
    runs = 1
    if argv[:1] == ["--runs"]:
        runs, argv = int(argv[1]), argv[2:]
    if argv[:1] == ["--"]:
        argv = argv[1:]
    if not argv or runs < 1:
        sys.exit(__doc__)
    times, peaks, status = [], [], 0
    for k in range(runs):
        code, seconds, peak = measure(argv)
        status = status or code
        times.append(seconds)
        peaks.append(peak)
        print(f"measure_run: run {k + 1}: {seconds:.1f} s, peak memory {peak / 2**30:.2f} GiB "
              f"(all processes), exit {code}", file=sys.stderr)
    if runs > 1:
        print(f"measure_run: median of {runs}: {statistics.median(times):.1f} s, "
              f"peak memory {max(peaks) / 2**30:.2f} GiB", file=sys.stderr)
    sys.exit(status)


if __name__ == "__main__":
    main(sys.argv[1:])

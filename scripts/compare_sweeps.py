#!/usr/bin/env python3
"""Compare the speed sweeps of two results.h5 files speed by speed.

usage: scripts/compare_sweeps.py TEST.h5 REFERENCE.h5 [--quantity dte_rms] [--limit 0.005]

For every pair, excitation and direction in both files: the relative difference of the quantity
(default the DTE RMS) at each speed, over the speeds where both runs reached a steady state
(period > 0, not diverged). Prints the worst speed per sweep, the speeds beyond --limit, and
exits 1 if any (or if no speed could be compared). Used to hold a fast sweep setting (e.g. Newmark steps from the accuracy) against
a tight-tolerance CVODE run of the same scene.
"""
import argparse
import sys

import h5py
import numpy as np


def sweeps(f):
    for pair, g in f["dynamics"].items():
        for excitation, e in g.items():
            if not isinstance(e, h5py.Group):
                continue
            for direction in ("up", "down"):
                if direction in e:
                    yield (pair, excitation, direction), e[direction]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("test")
    ap.add_argument("reference")
    ap.add_argument("--quantity", default="dte_rms")
    ap.add_argument("--limit", type=float, default=0.005)
    a = ap.parse_args()
    failed, compared = False, 0
    with h5py.File(a.test, "r") as t, h5py.File(a.reference, "r") as r:
        ref = dict(sweeps(r))
        for key, s in sweeps(t):
            if key not in ref:
                continue
            q, qr = s[a.quantity][:], ref[key][a.quantity][:]
            speed = s["speed"][:]
            if not np.allclose(speed, ref[key]["speed"][:]):
                sys.exit(f"{'/'.join(key)}: the speeds differ")
            steady = (s["period"][:] > 0) & (ref[key]["period"][:] > 0)
            steady &= np.isfinite(q) & np.isfinite(qr)
            err = np.abs(q - qr) / np.abs(qr)
            err[~steady] = np.nan
            compared += int(steady.sum())
            if not steady.any():
                print(f"{'/'.join(key)}: no speed steady in both")
                continue
            worst = int(np.nanargmax(err))
            beyond = [f"{speed[i]:.0f}" for i in np.flatnonzero(err > a.limit)]
            print(f"{'/'.join(key)}: {steady.sum()} of {len(q)} speeds steady in both; worst "
                  f"{err[worst]:.2e} at {speed[worst]:.0f} rpm; beyond {a.limit}: "
                  f"{', '.join(beyond) if beyond else 'none'}")
            failed |= bool(beyond)
    if compared == 0:
        print("no speed steady in both files: nothing compared")
    sys.exit(1 if failed or compared == 0 else 0)


if __name__ == "__main__":
    main()

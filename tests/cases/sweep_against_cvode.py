#!/usr/bin/env python3
"""The driver's default sweep against a tight CVODE sweep on a case's own scene (slow).

usage: sweep_against_cvode.py GEARKIT SCENE OUTPUT_ROOT FROM_RPM TO_RPM SPEEDS

Writes two variants of SCENE's Dynamics sections - the speed range cut to FROM..TO rpm in SPEEDS
speeds, theoretical flanks only; one as the scene has it (the default accuracy), one with
`integrator = cvode bdf` (relative tolerance 1e-8) - runs both, and asserts that the DTE RMS of
every speed settled in both agrees within 0.5 % (scripts/compare_sweeps.py). The seed spiral
bevel case's low speeds are where 64 fixed steps per mesh cycle were 13.6 % off.
"""
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
COMPARE = os.path.join(HERE, "..", "..", "scripts", "compare_sweeps.py")


def variant(text, start, stop, speeds, extra):
    subs = [(r"(set speed from\s*=\s*)\S+", rf"\g<1>{start}"),
            (r"(set speed to\s*=\s*)\S+", rf"\g<1>{stop}"),
            (r"(set speeds\s*=\s*)\S+", rf"\g<1>{speeds}"),
            (r"(set excitations\s*=\s*).*", r"\g<1>theoretical"),
            (r"(set time series speeds\s*=\s*).*", r"\g<1>")]
    for pattern, replacement in subs:
        text, n = re.subn(pattern, replacement, text)
        if n == 0:
            sys.exit(f"sweep_against_cvode: the scene has no '{pattern}' to change")
    if extra:
        text = re.sub(r"(set speeds\s*=.*\n)", r"\g<1>    " + extra + "\n", text)
    return text


def main():
    if len(sys.argv) != 7:
        sys.exit(__doc__)
    gearkit, scene, root, start, stop, speeds = sys.argv[1:]
    with open(scene) as f:
        text = f.read()
    os.makedirs(root, exist_ok=True)
    results = {}
    for name, extra in (("default", ""), ("cvode", "set integrator = cvode bdf")):
        path = os.path.join(root, f"sweep_{name}.prm")
        with open(path, "w") as f:
            f.write(variant(text, start, stop, speeds, extra))
        subprocess.run([gearkit, "--output-root", root, path], check=True)
        results[name] = os.path.join(root, f"sweep_{name}", "results.h5")
    subprocess.run([sys.executable, COMPARE, results["default"], results["cvode"],
                    "--quantity", "dte_rms", "--limit", "0.005"], check=True)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Every results name the scripts and the case checks read is one the results schema has.

The results schema (`gearkit --print-results json`, driver/results_schema.cc) names every group
and dataset once. The scripts (plot_results.py, report.py, compare_*.py) and the case checks
(tests/cases/check_*.py) index results.h5 by name, `g["mesh_stiffness"]`, `f["stiffness/fzg"]`;
each such literal - each level of a path, f-string fields left out - must be a dataset or a
literal group level of the schema, or a name that stands for one of its placeholders in a case
(a pair, train, mesh or body of a shipped case, as its results.h5 holds them; pinion, gear,
drive, coast, ...), or an attribute a results file carries. A name renamed or dropped in the
schema is caught here in every script and check that still reads it, whether or not a case runs
that code path. Keys of a script's own tables (not results) are listed below with the file.

  check_script_names.py GEARKIT SOURCE_DIR CASE_OUT_DIR
"""
import glob
import json
import os
import re
import subprocess
import sys

import h5py

gearkit, source, case_out = sys.argv[1], sys.argv[2], sys.argv[3]
schema = json.loads(subprocess.run([gearkit, "--print-results", "json"], check=True,
                                   capture_output=True, text=True).stdout)

known = set()
for entry in schema:
    known.add(entry["dataset"])
    known.update(level for level in entry["group"].split("/") if not level.startswith("<"))
# the placeholders' values and the attributes, as the cases' results files hold them
files = sorted(glob.glob(os.path.join(case_out, "*", "results.h5")))
if not files:
    sys.exit(f"no results.h5 under {case_out}: run the cases first")
for path in files:
    with h5py.File(path, "r") as f:
        known.update(f.attrs.keys())

        def visit(name, obj):
            known.update(name.split("/"))
            known.update(obj.attrs.keys())

        f.visititems(visit)
# pairs and trains of every shipped case (also those whose results are not at hand: slow cases)
for scene in glob.glob(os.path.join(source, "cases", "**", "*.prm"), recursive=True):
    for line in open(scene, encoding="utf-8"):
        m = re.match(r"\s*set\s+(pairs|trains)\s*=\s*(.*)", line)
        if m:
            known.update(n.strip() for n in m.group(2).split("#")[0].split(",") if n.strip())

# Keys of the scripts' own tables (dictionaries, JSON), not results names.
OWN_KEYS = {
    "check_hertz.py": {"3d", "both", "ds", "dt", "p", "s", "struct", "v", "xi"},
    "plot_results.py": {"color"},
}
checked = sorted(glob.glob(os.path.join(source, "scripts", "plot_results.py")) +
                 glob.glob(os.path.join(source, "scripts", "report.py")) +
                 glob.glob(os.path.join(source, "scripts", "compare_*.py")) +
                 [p for p in glob.glob(os.path.join(source, "tests", "cases", "check_*.py"))
                  if os.path.basename(p) not in ("check_results_schema.py",
                                                 "check_script_names.py")])
subscript = re.compile(r"\[\s*f?[\"']([^\"'\]\n]+)[\"']\s*\]")
unknown, names = [], 0
for path in checked:
    own = OWN_KEYS.get(os.path.basename(path), set())
    text = open(path, encoding="utf-8").read()
    for m in subscript.finditer(text):
        for level in m.group(1).split("/"):
            if "{" in level or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", level):
                continue  # an f-string's field, or not a name
            names += 1
            if level not in known and level not in own:
                line = text.count("\n", 0, m.start()) + 1
                unknown.append(f"{os.path.relpath(path, source)}:{line}: '{level}' "
                               f"(in [\"{m.group(1)}\"]) is in no results schema entry")
for u in unknown:
    print(u)
print(f"{len(checked)} scripts and checks, {names} names read, {len(unknown)} not in the schema")
sys.exit(1 if unknown else 0)

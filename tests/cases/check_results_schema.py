#!/usr/bin/python3
"""A case's results.h5 against the results schema (`gearkit --print-results json`): every
dataset's group (its names matched against the schema's group patterns, where <...> stands for a
name that varies) and name are in the schema, and its `units` and `description` attributes, its
rank and its type (integers or not) are those of its entry. A description's choice
"{first|second}" may be either. Prints how many entries the case's file hit.

  check_results_schema.py GEARKIT CASE_OUT_DIR
"""
import json
import os
import re
import subprocess
import sys

import h5py

gearkit, out = sys.argv[1], sys.argv[2]
schema = json.loads(subprocess.run([gearkit, "--print-results", "json"], check=True,
                                   capture_output=True, text=True).stdout)
problems = []

seen = set()
for e in schema:
    if (e["group"], e["dataset"]) in seen:
        problems.append(f"schema: {e['group']}/{e['dataset']} twice")
    seen.add((e["group"], e["dataset"]))


def group_regex(pattern):
    """A group pattern as a regular expression: <...> any text within one level."""
    return re.compile("/".join(
        "".join("[^/]+" if part.startswith("<") else re.escape(part)
                for part in re.split(r"(<[^>]*>)", level) if part)
        for level in pattern.split("/")))


def description_regex(text):
    """A description as a regular expression: its choice {a|b} either alternative."""
    parts = re.split(r"\{([^}]*)\}", text)
    return re.compile("".join(
        re.escape(p) if i % 2 == 0 else "(?:" + "|".join(map(re.escape, p.split("|"))) + ")"
        for i, p in enumerate(parts)))


def rank(shape):
    return 0 if shape.startswith("scalar") else shape.count(" x ") + 1


def integers(shape):
    return shape.endswith(", integer") or shape.endswith(", integers")


by_name = {}
for e in schema:
    by_name.setdefault(e["dataset"], []).append(
        (group_regex(e["group"]), description_regex(e["description"]), e))


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


hit, count = set(), 0
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    def visit(path, obj):
        global count
        if not isinstance(obj, h5py.Dataset):
            return
        count += 1
        group, _, name = path.rpartition("/")
        candidates = [(d, e) for g, d, e in by_name.get(name, []) if g.fullmatch(group)]
        if not candidates:
            problems.append(f"/{path}: no schema entry for {name!r} in a group like {group!r}")
            return
        units = text(obj.attrs.get("units", "<none>"))
        description = text(obj.attrs.get("description", "<none>"))
        fitting = [e for d, e in candidates
                   if e["units"] == units and d.fullmatch(description)]
        if not fitting:
            problems.append(f"/{path}: units {units!r}, description {description!r}; the schema "
                            "has " + "; ".join(f"{e['group']}: {e['units']!r}, "
                                               f"{e['description']!r}" for _, e in candidates))
            return
        e = fitting[0]
        if obj.ndim != rank(e["shape"]):
            problems.append(f"/{path}: {obj.ndim} dimensions, the schema's shape is "
                            f"{e['shape']!r}")
        if (obj.dtype.kind in "iu") != integers(e["shape"]):
            problems.append(f"/{path}: type {obj.dtype}, the schema's shape is {e['shape']!r}")
        hit.update((x["group"], x["dataset"]) for x in fitting)
    f.visititems(visit)

if count == 0:
    problems.append("results.h5 holds no datasets")
for p in problems:
    print("FAIL", p)
print(f"{out}: {count} datasets, {len(hit)} of the schema's {len(schema)} entries"
      + (f"; {len(problems)} problems" if problems else ", all as the schema says"))
sys.exit(1 if problems else 0)

#!/usr/bin/python3
"""The key-number table of a case's report.html against its results.h5 (issue 38): the gear data
of every pair (tooth counts, contact ratios), and per pair and torque the loaded transmission
error's peak-to-peak and mesh orders 1-3, recomputed here independently (a direct Fourier sum
over the positions of one mesh cycle), and the ISO comparison like for like (c_gamma_alpha b
against the mean K_m), the flank-interior pressure from positions without edge contact, the
dynamics' headline load factor from settled speeds alone, and the trains' impacts per side and
located largest force (counted from the contact table).

  check_report_keys.py CASE_OUT_DIR
"""
import html
import os
import re
import sys

import h5py
import numpy as np

out = sys.argv[1]
with open(os.path.join(out, "report.html"), encoding="utf-8") as fh:
    page = fh.read()
table = page[page.index('id="key"'):page.index('id="pictures"')]
rows, triples = {}, []
for row in re.findall(r"<tr>(.*?)</tr>", table, re.S):
    cells = [html.unescape(re.sub("<[^>]+>", "", c)).strip()
             for c in re.findall(r"<td>(.*?)</td>", row, re.S)]
    if len(cells) == 3:
        rows[cells[1]] = cells[2]
        triples.append(tuple(cells))


glance = []
if 'id="glance"' in page:
    for row in re.findall(r"<tr>(.*?)</tr>", page[page.index('id="glance"'):page.index('id="key"')],
                          re.S):
        cells = [html.unescape(re.sub("<[^>]+>", "", c)).strip()
                 for c in re.findall(r"<td>(.*?)</td>", row, re.S)]
        if cells:
            glance.append(cells)


def numbers(text):
    return [float(v) for v in re.findall(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?", text)]


def near(shown, exact, what):
    # the report shows four significant digits
    assert abs(shown - exact) <= 6e-4 * abs(exact) + 1e-9, (what, shown, exact)


checked = 0
with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    for pair in f.get("flanks", {}):
        g = f["flanks"][pair]
        for member in ("pinion", "gear"):
            if member in g and "number_of_teeth" in g[member]:
                z = int(g[member]["number_of_teeth"][()])
                assert rows[f"{pair}: {member}"].startswith(f"z {z}"), rows[f"{pair}: {member}"]
                checked += 1
        if "transverse_contact_ratio" in g:
            eps = g["transverse_contact_ratio"][()]
            row = rows[f"{pair}: pair: working centre distance and pressure angle, contact ratios"]
            assert f"ε_α {eps:.3f}" in row, row
            checked += 1
        # at the working centre distance (zero backlash by its definition) the backlash from the
        # tooth thicknesses vanishes: an exact check of the thickness arithmetic
        key = (f"{pair}: pair: normal backlash at the operating centre distance (from the tooth "
               "thicknesses)")
        if key in rows and abs(g["operating_centre_distance"][()]
                               - g["working_centre_distance"][()]) < 1e-12:
            assert numbers(rows[key])[0] == 0.0, rows[key]
            checked += 1
    for pair in f.get("stiffness", {}):
        s = f["stiffness"][pair]
        for t, torque in enumerate(s["torque"][()]):
            te = s["transmission_error_loaded"][t]
            n = te.size
            dft = [abs(np.sum(te * np.exp(-2j * np.pi * k * np.arange(n) / n))) * 2 / n
                   for k in (1, 2, 3)]
            key = (f"{pair}, {torque:g} N m: loaded transmission error e_L: peak-to-peak; "
                   "mesh orders 1, 2, 3")
            assert key in rows, (key, list(rows)[:20])
            text = rows[key]
            pp_shown = numbers(text.split("(")[0])[0]
            near(pp_shown, (te.max() - te.min()) * 1e6, key + " p-p [urad]")
            shown = numbers(text.split(";")[1])
            for k in range(3):
                near(shown[k], dft[k] * 1e6, f"{key} order {k + 1} [urad]")
            checked += 4
            # the glance table's row of this pair and torque: the same peak-to-peak
            at = [r for r in glance if len(r) == 8 and r[0] == pair and r[3] == f"{torque:g} N m"]
            assert len(at) == 1, (pair, torque, glance)
            near(numbers(at[0][4])[0], (te.max() - te.min()) * 1e6, "glance e_L p-p")
            checked += 1
            # the interior pressure's headline: from positions whose largest pressure is on
            # no flank-edge cell (a tip corner's singular value is never the headline)
            if "interior_peak_pressure" in s and np.any(s["peak_pressure"][t] <=
                                                        1.01 * s["interior_peak_pressure"][t]):
                interior, peak = s["interior_peak_pressure"][t], s["peak_pressure"][t]
                clean = peak <= 1.01 * interior
                key = (f"{pair}, {torque:g} N m: largest contact pressure in the flank interior "
                       "(Hertz's), positions without edge contact: largest, at; mean (min .. max)")
                k = int(np.argmax(np.where(clean, interior, -np.inf)))
                value = numbers(rows[key])
                near(value[0], interior[k] * 1e-6, key)
                assert value[1] == k and not np.any(interior[clean] > interior[k]), (key, value)
                assert np.all(peak[clean] <= 1.01 * interior[k]), key
                checked += 1
        if "iso_c_gamma_alpha" in s:
            key = f"{pair}: ISO 6336-1 c_γα b (mesh) against K_m mean"
            diff = (s["mesh_stiffness"][()].mean() / s["iso_c_gamma_alpha"][()] - 1) * 100
            assert f"K_m mean {diff:+.1f} %" in rows[key], (rows[key], diff)
            checked += 1
    # dynamics: the headline load factor from settled speeds only (status 0), never from a
    # speed whose motion did not repeat or diverged
    for pair in f.get("dynamics", {}):
        for ex, e in f["dynamics"][pair].items():
            if not isinstance(e, h5py.Group):
                continue
            for sweep in ("up", "down"):
                if sweep not in e or "status" not in e[sweep]:
                    continue
                sw = e[sweep]
                settled = sw["status"][()] == 0
                if not settled.any():
                    continue
                dlf, speed = sw["dynamic_load_factor"][()], sw["speed"][()]
                k = int(np.argmax(np.where(settled, dlf, -np.inf)))
                key = (f"{pair}, {ex} excitation: largest dynamic load factor, settled speeds "
                       f"({sweep} sweep)")
                assert rows[key] == f"{dlf[k]:.3f} at {speed[k]:.0f} rpm", (key, rows[key])
                checked += 1
                if sweep == "up":  # the glance's load factor: the largest settled of any excitation
                    shown = [numbers(r[7])[0] for r in glance if len(r) == 8 and r[0] == pair]
                    assert all(v >= round(dlf[k], 3) - 1e-9 for v in shown), (pair, shown, dlf[k])
    # trains: impacts per side counted from the contact table, the largest force located
    for name in f.get("train", {}):
        g = f["train"][name]
        for mesh in g.get("meshes", {}):
            m = g["meshes"][mesh]
            where = f"{name}, mesh {mesh}"
            c = m["contacts"]
            touch, side = c["touch"][()], c["side"][()]
            drive, coast = int(np.sum((touch > 0) & (side > 0))), int(np.sum((touch > 0) & (side < 0)))
            assert rows[f"{where}: impacts (drive / coast flanks)"] == \
                f"{drive + coast} ({drive} / {coast})", (where, drive, coast)
            peak = numbers(rows[f"{where}: largest force (located), at"])[0]
            largest = c["peak"][()].max() if c["peak"].size else 0.0
            near(peak, largest, where + " largest force [N]")
            checked += 2
    # the scene's notes, each in the key table under its area, after that area's rows
    notes = f.attrs.get("notes", "")
    notes = notes.decode() if isinstance(notes, bytes) else str(notes)
    for line in notes.splitlines():
        name, area, text = line.split("\t", 2)
        assert (area, f"{name}: note", text) in triples, (name, area, text)
        # after the last row of its area and name (or of its area)
        at = triples.index((area, f"{name}: note", text))
        assert triples[at - 1][0] == area, (name, area, triples[at - 1])
        checked += 1
assert checked > 0
print(f"{os.path.basename(out)}: {checked} key numbers of report.html agree with results.h5")

#!/usr/bin/python3
"""The page an engineer forwards: <scene folder>/report.html from a gearkit results.h5.

  report.py RESULTS.h5

Self-contained (styles inline, pictures embedded as data URIs): the scene's parameters as run,
each stage's key numbers with units and their accuracy figures (error estimates, reference
positions, checks), every picture drawn from these results (PNGs in the scene folder not older
than results.h5), the stages' times and cache files, versions and the machine. Written through a
temporary file and a rename. The driver runs it after every run (gearkit, ./run).
"""

import base64
import html
import inspect
import os
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_results  # noqa: E402  (captions: the docstrings of the functions that drew them)
import plot_study  # noqa: E402

CAPTIONS = {
    "profiles.png": plot_results.plot_profiles,
    "topography.png": plot_results.plot_topography,
    "measured.png": plot_results.plot_measured,
    "ste.png": plot_results.plot_ste,
    "contact_pattern.png": plot_results.plot_contact_pattern,
    "hunting.png": plot_results.plot_hunting,
    "stiffness.png": plot_results.plot_stiffness,
    "dynamics.png": plot_results.plot_dynamics,
    "dynamics_spectra.png": plot_results.plot_dynamics_spectra,
    "dynamics_time.png": plot_results.plot_dynamics_time,
    "train_compare.png": plot_results.plot_train_compare,
    "train_spectrogram.png": plot_results.plot_train_spectrograms,
    "deflection.png": plot_results.plot_deflection,
}
# Displayed units: SI inside, the engineer's units on the page.
DISPLAY = {"m": (1e6, "µm"), "rad": (1e6, "µrad"), "N/m": (1e-6, "N/µm"), "Pa": (1e-6, "MPa"),
           "m/N": (1e9, "µm/kN")}


def esc(text):
    return html.escape(str(text))


def shown(value, units):
    """A number in display units: 4 significant digits, whole numbers from 1e4 to 1e7."""
    scale, label = DISPLAY.get(units, (1.0, units))
    v = float(value) * scale
    text = f"{v:.4g}" if abs(v) < 1e4 else f"{v:.0f}" if abs(v) < 1e7 else f"{v:.4e}"
    return text, ("" if label == "1" else label)


# The pictures in the order of the work: geometry, unloaded TCA, loaded contact and the study's
# micro-geometry maps, dynamics, trains.
ORDER = ["profiles.png", "topography.png", "measured.png", "ste.png", "contact_pattern.png",
         "hunting.png", "stiffness.png", "study_", "tolerances_", "vh_", "deflection.png",
         "dynamics.png",
         "dynamics_spectra.png", "dynamics_time.png", "train_compare.png", "train_",
         "train_spectrogram.png"]


def workflow_order(png):
    if png in ORDER:
        return (ORDER.index(png), png)
    for prefix in ("train_", "study_", "tolerances_", "vh_"):
        if png.startswith(prefix):
            return (ORDER.index(prefix), png)
    return (len(ORDER), png)


def caption(png):
    f = CAPTIONS.get(png)
    if f is None and png.startswith("train_"):
        f = plot_results.plot_train
    if f is None and png.startswith("study_"):
        f = plot_study.plot_study
    if f is None and png.startswith("tolerances_"):
        f = plot_study.plot_tolerances
    if f is None and png.startswith("vh_"):
        f = plot_study.plot_misalignments
    doc = inspect.getdoc(f) if f else ""
    return " ".join(doc.split()) if doc else png


class Page:
    def __init__(self):
        self.parts = []

    def h(self, level, text, anchor=None):
        a = f' id="{anchor}"' if anchor else ""
        self.parts.append(f"<h{level}{a}>{esc(text)}</h{level}>")

    def p(self, text, cls=None):
        c = f' class="{cls}"' if cls else ""
        self.parts.append(f"<p{c}>{text}</p>")

    def table(self, header, rows, cls=None, alarm=()):
        """rows: lists of cells (HTML); those whose index is in alarm marked class="alarm"."""
        c = f' class="{cls}"' if cls else ""
        out = [f"<table{c}><tr>" + "".join(f"<th>{esc(x)}</th>" for x in header) + "</tr>"]
        for i, r in enumerate(rows):
            out.append(("<tr class=\"alarm\">" if i in alarm else "<tr>")
                       + "".join(f"<td>{x}</td>" for x in r) + "</tr>")
        out.append("</table>")
        self.parts.append("\n".join(out))

    def raw(self, text):
        self.parts.append(text)


def attr(group, name, default=""):
    v = group.attrs.get(name, default)
    return v.decode() if isinstance(v, bytes) else str(v)


def number(value, units):
    v, u = shown(value, units)
    return f"{v} {esc(u)}".strip()


def stats(values, units):
    """mean (min .. max) of an array in display units."""
    a = np.asarray(values, dtype=float)
    a = a[np.isfinite(a)]
    if a.size == 0:
        return "–"
    mean, u = shown(a.mean(), units)
    lo, _ = shown(a.min(), units)
    hi, _ = shown(a.max(), units)
    return f"{mean} ({lo} .. {hi}) {esc(u)}"


def gear_rows(name, g):
    """The pair's gear data as a drawing gives it, in mm and degrees: per member z, m_n, alpha_n,
    x, b, d_a, d_f, beta; the pair's working centre distance and pressure angle, eps_alpha and
    eps_beta."""
    rows = []

    def mm(v):
        return f"{v * 1e3:.4f} mm"

    def deg(v):
        return f"{np.degrees(v):.4f}°"

    for member in ("pinion", "gear"):
        if member not in g:
            continue
        m = g[member]
        parts = []
        for key, label, fmt in (("number_of_teeth", "z", lambda v: f"{int(v)}"),
                                ("normal_module", "m_n", mm),
                                ("normal_pressure_angle", "α_n", deg),
                                ("profile_shift", "x", lambda v: f"{v:.4f}"),
                                ("face_width", "b", mm),
                                ("tip_radius", "d_a", lambda v: mm(2 * v)),
                                ("root_radius", "d_f", lambda v: mm(2 * v)),
                                ("helix_angle", "β", deg),
                                ("pitch_angle", "δ", deg),
                                ("mean_pitch_radius", "d_m", lambda v: mm(2 * v)),
                                ("addendum", "h_am", mm),
                                ("dedendum", "h_fm", mm)):
            if key in m and m[key].shape == ():
                parts.append(f"{label} {fmt(m[key][()])}")
        if parts:
            rows.append([esc(name), member, ", ".join(parts)])
    parts = []
    for key, label, fmt in (("working_centre_distance", "a_w", mm),
                            ("working_pressure_angle", "α_wt", deg),
                            ("transverse_contact_ratio", "ε_α", lambda v: f"{v:.3f}"),
                            ("overlap_ratio", "ε_β", lambda v: f"{v:.3f}"),
                            ("shaft_angle", "Σ", deg),
                            ("mean_cone_distance", "R_m", mm),
                            ("mean_normal_module", "m_mn", mm),
                            ("mean_spiral_angle", "β_m", deg)):
        if key in g:
            parts.append(f"{label} {fmt(g[key][()])}")
    if parts:
        rows.append([esc(name), "pair: working centre distance and pressure angle, contact ratios"
                     if "working_centre_distance" in g else "pair: shaft angle, mean cone distance, "
                     "mean normal module and spiral angle", ", ".join(parts)])
    j = backlash(g)
    if j is not None:
        rows.append([esc(name), "pair: normal backlash at the operating centre distance "
                     "(from the tooth thicknesses)", f"{j * 1e3:.4f} mm"])
    return rows


def backlash(g):
    """Normal backlash of an involute pair at its operating centre distance a: the working
    circles' pitch less both transverse tooth thicknesses there (s(r) = 2 r (s_t / (2 r_ref) +
    inv alpha_t - inv alpha(r))), times cos alpha' cos beta_b. None where the data are missing
    (bevel pairs)."""
    need = ("base_radius", "tooth_thickness_reference", "reference_radius",
            "transverse_pressure_angle", "number_of_teeth", "base_helix_angle")
    if "operating_centre_distance" not in g or not all(
            m in g and all(k in g[m] for k in need) for m in ("pinion", "gear")):
        return None
    p, w = g["pinion"], g["gear"]
    a = g["operating_centre_distance"][()]
    cos_w = (p["base_radius"][()] + w["base_radius"][()]) / a
    if not 0 < cos_w < 1:
        return None

    def inv(x):
        return np.tan(x) - x
    alpha_w = np.arccos(cos_w)
    thickness = 0.0
    for m in (p, w):
        r_w = m["base_radius"][()] / cos_w
        thickness += 2 * r_w * (m["tooth_thickness_reference"][()] / (2 * m["reference_radius"][()])
                                + inv(m["transverse_pressure_angle"][()]) - inv(alpha_w))
    pitch = 2 * np.pi * p["base_radius"][()] / cos_w / p["number_of_teeth"][()]
    return (pitch - thickness) * cos_w * np.cos(p["base_helix_angle"][()])


def stiffness_rows(name, g, base_radius=None):
    """Key numbers of one pair's loaded contact: per torque K_m, e_L - e_0, pressure, with the
    error estimate and the reference positions where present."""
    rows = []
    torques = g["torque"][()]
    km = g["mesh_stiffness"][()]
    de = g["transmission_error_loaded"][()] - g["transmission_error_unloaded"][()][None, :]
    est = g["error_estimate"]["mesh_stiffness"][()] if "error_estimate" in g else None
    r_b, where = ((base_radius, "along the line of action") if not isinstance(base_radius, tuple)
                  else base_radius) if base_radius is not None else (0.0, "")
    for t, torque in enumerate(torques):
        label = f"{esc(name)}, {torque:g} N m"
        rows.append([label, "mesh stiffness K_m, mean (min .. max)", stats(km[t], "N/m")])
        rows.append([label, "e_L − e_0, mean (min .. max)", stats(de[t], "rad")])
        share = g["pair_force"][t] / np.maximum(g["normal_force"][t][:, None], 1e-300)
        carrying = np.sum(share > 0.01, axis=1)
        rows.append([label, "load sharing: tooth pairs carrying over 1 % of the load (min .. "
                     "max over the positions); the most loaded pair's share, least over the cycle",
                     f"{carrying.min()} .. {carrying.max()} pairs; {share.max(axis=1).min() * 100:.1f} %"])
        pp, orders = plot_results.te_harmonics(g["transmission_error_loaded"][t])
        along = f" ({pp * r_b * 1e6:.3f} µm {where})" if r_b else ""
        rows.append([label, "loaded transmission error e_L: peak-to-peak; mesh orders 1, 2, 3",
                     f"{number(pp, 'rad')}{along}; "
                     + ", ".join(number(a, "rad") for a in orders)])
        rows += pressure_rows(label, g, t)
        if est is not None:
            rel = np.abs(est[t]) / km[t] * 100
            rows.append([label, "K_m estimated discretisation error (mean, largest)",
                         f"{rel.mean():.2f} %, {rel.max():.2f} %"])
    # like for like: the single pair's c' against K_m where one pair carries (its least value
    # over the cycle), the mesh's c_gamma_alpha against K_m's mean
    for key, what, ours, which in (
            ("iso_c_th", "ISO 6336-1 c'_th b (one pair)", km.min(), "K_m least"),
            ("iso_c_prime", "ISO 6336-1 c' b (one pair)", km.min(), "K_m least"),
            ("iso_c_gamma_alpha", "ISO 6336-1 c_γα b (mesh)", km.mean(), "K_m mean")):
        if key in g:
            rows.append([esc(name), f"{what} against {which}",
                         f"{number(g[key][()], 'N/m')} ({which} {(ours / g[key][()] - 1) * 100:+.1f} %)"])
    if "reference" in g:
        r = g["reference"]
        pos = r["position"][()].astype(int)
        ref = r["mesh_stiffness"][()]
        for t, torque in enumerate(torques):
            diffs = ", ".join(f"{p}: {(km[t][p] / ref[t][i] - 1) * 100:+.2f} %"
                              for i, p in enumerate(pos))
            rows.append([f"{esc(name)}, {torque:g} N m",
                         "fast mode against the reference mode (finite elements alone), by position",
                         diffs])
    return rows


def cell_pressure_spread(g, t):
    """The loaded contact cells' pressure over all positions at torque t: median / 90th
    percentile (where no position's peak is free of an edge)."""
    cells = g["contact_cells"][t][..., 3]
    loaded = cells[cells > 0]
    return f"{number(np.median(loaded), 'Pa')} / {number(np.percentile(loaded, 90), 'Pa')}"


def pressure_rows(label, g, t):
    """The flank interior's largest contact pressure (Hertz's) from the positions whose largest
    pressure is on no flank edge; the edge-contact positions apart, with their (singular,
    mesh-dependent) pressure and the load share on edge cells."""
    rows = []
    edge = plot_results.edge_contact(g, t)
    if "interior_peak_pressure" in g and (~edge).any():
        interior = g["interior_peak_pressure"][t]
        k = int(np.argmax(np.where(edge, -np.inf, interior)))
        rows.append([label, "largest contact pressure in the flank interior (Hertz's), positions "
                     "without edge contact: largest, at; mean (min .. max)",
                     f"{number(interior[k], 'Pa')} at position {k}; "
                     f"{stats(interior[~edge], 'Pa')} over {int((~edge).sum())} of {edge.size}"])
    elif "interior_peak_pressure" in g:
        rows.append([label, "largest contact pressure in the flank interior: not separable "
                     "(every position's largest pressure is on a flank-edge cell); the loaded "
                     "cells' pressure over all positions, median / 90th percentile",
                     cell_pressure_spread(g, t)])
    if edge.any():
        where = ", ".join(f"{k}: {g['peak_pressure'][t][k] * 1e-6:.0f}"
                          for k in np.nonzero(edge)[0][:10])
        rows.append([label, "edge contact: positions whose largest pressure is on a flank-edge "
                     "cell (tip corner, start of the working flank, face end; singular: grows "
                     "with mesh refinement), not in the line above",
                     f"{int(edge.sum())} of {edge.size}, position: MPa {where}"
                     + (" …" if edge.sum() > 10 else "")])
    elif "interior_peak_pressure" not in g:
        rows.append([label, "largest contact pressure, flank-edge cells included (singular at "
                     "corners: grows with mesh refinement)", stats(g["peak_pressure"][t], "Pa")])
    if "edge_load_share" in g:
        share = g["edge_load_share"][t]
        k = int(np.argmax(share))
        if share[k] > 0:
            r_mm, z_mm = g["edge_position"][t, k] * 1e3
            rows.append([label, "edge load: largest share of the load on cells at a flank edge",
                         f"{share[k] * 100:.1f} % at position {k} (pinion point r {r_mm:.3f} mm, "
                         f"z {z_mm:.3f} mm)"])
    return rows


def sweep_valid(s):
    """Per speed of a sweep group: True where it has results (not diverged: `status` 2, or the
    older `diverged` flag)."""
    if "status" in s:
        return s["status"][()] != 2
    if "diverged" in s:
        return s["diverged"][()] == 0
    return np.ones(len(s["speed"]), dtype=bool)


def diverged_speeds(s):
    """The diverged speeds of a sweep group, with the time each ran until it diverged."""
    bad = ~sweep_valid(s)
    speed = s["speed"][()][bad]
    when = s["diverged_time"][()][bad] if "diverged_time" in s else np.zeros(len(speed))
    return ", ".join(f"{v:.0f} rpm (after {t * 1e3:.3g} ms)" for v, t in zip(speed, when))


def train_rows(name, g):
    """A gear train's headline numbers per mesh: impacts (drive/coast), first contact, the
    largest force as the integrator located it (not a sample), the deepest penetration, the GMF
    line where a spectrum was taken; the energy balance and the located contact changes."""
    rows = []
    label = esc(name)
    if "energy_error" in g:
        rows.append([label, "energy balance error",
                     f"{g['energy_error'][()]:.2e} of the largest term"])
    if "events" in g:
        rows.append([label, "contact changes located", f"{int(g['events'][()])}"])
    method = attr(g, "integrator")
    if method and "steps" in g:
        rows.append([label, "integrator (CVODE), steps",
                     f"{'BDF' if method == 'bdf' else 'Adams'}, {int(g['steps'][()])}"])
    for mesh in (g["meshes"] if "meshes" in g else []):
        m = g["meshes"][mesh]
        where = f"{label}, mesh {esc(mesh)}"
        rows.append([where, "impacts (drive / coast flanks)",
                     f"{int(m['impacts'][()])} ({int(m['drive_impacts'][()])} / "
                     f"{int(m['coast_impacts'][()])})"])
        first = m["first_contact"][()]
        rows.append([where, "first contact", "none" if first < 0 else f"{first * 1e3:.3f} ms"])
        rows.append([where, "largest force (located), at",
                     f"{number(m['max_force'][()], 'N')} at {m['max_force_time'][()] * 1e3:.4g} ms"])
        rows.append([where, "deepest penetration", number(m["max_penetration"][()], "m")])
        rows.append([where, "backlash along the line of action (the band S moves in)",
                     number(2 * m["band_half_width"][()], "m")])
        if "spectrum" not in m:
            rows.append([where, "force spectrum", "none: the speed does not hold over the "
                         "analysis interval (see the spectrogram)"])
            continue
        lines = m["spectrum"]["lines"]
        h, sb, found = lines["harmonic"][()], lines["sideband"][()], lines["found"][()]
        rows.append([where, "spectral lines found: GMF harmonics; their sidebands; shaft orders",
                     f"{int(np.sum(found[(h > 0) & (sb == 0)]))} of {int(np.sum((h > 0) & (sb == 0)))}; "
                     f"{int(np.sum(found[(h > 0) & (sb != 0)]))} of {int(np.sum((h > 0) & (sb != 0)))}; "
                     f"{int(np.sum(found[h == 0]))} of {int(np.sum(h == 0))}"])
        k = np.nonzero((h == 1) & (sb == 0))[0]
        if k.size:
            i = int(k[0])
            rows.append([where, "GMF line (1st harmonic)",
                         f"{lines['amplitude'][()][i]:.3g} N at {lines['frequency'][()][i]:.3f} Hz"
                         if found[i] else f"not found near {lines['expected'][()][i]:.3f} Hz"])
    return rows


def study_invalid(g):
    """The zone_edge results of a micro-geometry map as text ("tip relief 40 µm at 50, 100 N m;
    ..."; a tolerance study's as sample numbers), their count and the number of results;
    ("", 0, n) when every result is valid."""
    edge = g["zone_edge"][()] != 0
    torques = g["torques"][()]
    if plot_study.text(g.attrs.get("kind", "")) == plot_study.TOLERANCES:
        bad = np.nonzero(edge.any(axis=1))[0]
        listed = "samples " + ", ".join(str(v) for v in bad[:12]) + (" …" if bad.size > 12 else "")
        return listed, int(edge.sum()), edge.size
    where = [f"{plot_study.variant_label(g, v, 'µm')} at "
             + ", ".join(f"{t:g}" for t in torques[edge[v]]) + " N m"
             for v in np.nonzero(edge.any(axis=1))[0]]
    listed = "; ".join(where[:8]) + (" …" if len(where) > 8 else "")
    return listed, int(edge.sum()), edge.size


def misalignment_rows(name, g):
    """A misalignment (V-H) check's table: per grid point e_0 and e_L peak-to-peak, the pattern's
    centre and extent on the gear flank at the design torque (else the largest) and its
    edge-load share (alarm above 10 %: a tenth of the load on an edge)."""
    m, _ = plot_study.design_index(g)
    torque = g["torques"][m]
    e0 = plot_study.te_length(g, g["unloaded_te_peak_to_peak"][()])
    eL = plot_study.te_length(g, g["te_peak_to_peak"][:, m])
    centre = g["pattern_centre"][:, m] * 1e3
    extent = g["pattern_extent"][:, m] * 1e3
    edge = g["max_edge_share"][:, m]
    rows, alarm = [], []
    for k in range(len(e0)):
        if edge[k] > plot_study.EDGE_ALARM:
            alarm.append(len(rows))
        rows.append([name, esc(plot_study.point_label(g, k)), f"{torque:g} N m",
                     f"{e0[k]:.3g} / {eL[k]:.3g} µm",
                     f"({centre[k, 1]:+.2f}, {centre[k, 0]:+.2f}) mm",
                     f"{extent[k, 2]:+.1f} … {extent[k, 3]:+.1f} × {extent[k, 0]:+.1f} … "
                     f"{extent[k, 1]:+.1f} mm", f"{edge[k]:.1%}"])
    return rows, alarm


def tolerance_rows(name, g):
    """A tolerance Monte Carlo's table: per torque the percentiles of the loaded TE peak-to-peak
    (at the pitch circle) and of K_m's mean against the design without deviations, and the
    deviation that drives the TE peak-to-peak most (its standardized regression coefficient)."""
    rows = []
    levels = g["percentile_levels"][()]
    names = plot_study.text(g.attrs.get("features", "")).split(",")
    classes = plot_study.text(g.attrs.get("classes", "")).replace(",", " / ")
    for m, t in enumerate(g["torques"][()]):
        pp = plot_study.te_length(g, g["percentiles/te_peak_to_peak"][m])
        nominal = plot_study.te_length(g, g["nominal/te_peak_to_peak"][m])
        rows.append([name, f"{t:g} N m", f"TE p-p, classes {classes}: "
                     + " / ".join(f"{x:g} %" for x in levels),
                     " / ".join(f"{x:.3g}" for x in pp) + f" µm (design alone {nominal:.3g} µm)"])
        km = g["percentiles/stiffness_mean"][m] / 1e6
        rows.append([name, f"{t:g} N m", "K_m mean: " + " / ".join(f"{x:g} %" for x in levels),
                     " / ".join(f"{x:.4g}" for x in km)
                     + f" N/µm (design alone {g['nominal/stiffness_mean'][m] / 1e6:.4g})"])
        if "percentiles/max_interior_pressure" in g:
            p = g["percentiles/max_interior_pressure"][m] / 1e6
            rows.append([name, f"{t:g} N m", "largest flank-interior pressure (off the flanks' "
                         "edges): " + " / ".join(f"{x:g} %" for x in levels),
                         " / ".join(f"{x:.4g}" for x in p) + " MPa (design alone "
                         f"{g['nominal/max_interior_pressure'][m] / 1e6:.4g})"])
        if "sensitivity" in g:
            c = g["sensitivity/te_peak_to_peak/coefficient"][m]
            k = int(np.argmax(np.abs(c)))
            rows.append([name, f"{t:g} N m", "drives the TE p-p most",
                         f"{plot_study.feature_label(names[k])}: SRC {c[k]:+.2f} "
                         f"[{g['sensitivity/te_peak_to_peak/low'][m][k]:+.2f}, "
                         f"{g['sensitivity/te_peak_to_peak/high'][m][k]:+.2f}]"])
    return rows


def study_rows(name, g):
    """A micro-geometry map's table (pair, torque, what, value): per torque the best valid
    variant (its parameter values) and its loaded TE's peak-to-peak at the pitch circle, with the
    unmodified variant's; at the design torque the classical relief F / (b c_gamma) (ISO 6336-1),
    the unmodified pair's mesh deflection F / K_m and the best relief interpolated there; and
    the warning where a contact reached the edge of the fixed zone. Returns (rows, indices of
    the warning rows)."""
    rows, alarm = [], []
    label = esc(name)
    torques = g["torques"][()]
    pp = plot_study.te_length(g, g["te_peak_to_peak"][()])
    best = np.atleast_1d(g["best_variant"][()]).astype(int)
    edge = g["zone_edge"][()] != 0
    zero = plot_study.unmodified_variant(g)
    design = plot_study.scalar(g, "design_torque", 0.0)
    for m, torque in enumerate(torques):
        when = f"{torque:g} N m" + (" (design)" if np.isclose(torque, design) else "")
        v = best[m]
        if v < 0:
            rows.append([label, when, "best variant: none (no valid result)", "–"])
            continue
        valid = int((~edge[:, m]).sum())
        unmodified = ("" if zero is None or zero == v else
                      f" (unmodified: {pp[zero, m]:.4g} µm" + (", not valid" if edge[zero, m]
                                                              else "") + ")")
        interior = (f", flank-interior pressure {g['max_interior_pressure'][v, m] / 1e6:.4g} MPa"
                    if "max_interior_pressure" in g else "")
        rows.append([label, when,
                     f"best of {valid} valid variants: {esc(plot_study.variant_label(g, v, 'µm'))}",
                     f"TE p-p {pp[v, m]:.4g} µm at the pitch circle{unmodified}{interior}"])
    if design > 0:
        when = f"design {design:g} N m"
        single = len(plot_study.parameters(g)) == 1
        for key, what, missing in (
                ("classical_relief_iso", "classical relief F / (b c_γ) (ISO 6336-1 c_γ)",
                 "– (not in the results)"),
                ("mesh_deflection_design", "mesh deflection F / K_m of the unmodified pair",
                 "– (not in the results)"),
                ("best_relief_design", "best relief interpolated at the design torque (parabola "
                 "through the grid's best three)",
                 "– (a single relief axis only)" if not single else "– (not in the results)")):
            v = plot_study.scalar(g, key)
            rows.append([label, when, what, missing if v is None else number(v, "m")])
    listed, count, total = study_invalid(g)
    if count:
        alarm.append(len(rows))
        rows.append([label, "<b>WARNING</b>", f"<b>{esc(plot_study.INVALID)}</b>",
                     f"<b>{count} of {total} (variant, torque) results:</b> {esc(listed)}"])
    return rows, alarm


def dynamics_rows(name, g):
    rows = []
    for ex in g:
        e = g[ex]
        if not isinstance(e, h5py.Group) or "up" not in e:
            continue
        label = f"{esc(name)}, {esc(ex)} excitation"
        rows.append([label, "static mesh force", number(e["static_mesh_force"][()], "N")])
        if "stability" in e:
            st = e["stability"]
            grows = (st["unstable"][()] != 0) if "unstable" in st else st["spectral_radius"][()] > 1
            rows.append([label, "speeds where the mesh in contact is parametrically unstable "
                         "(Floquet: a disturbance grows)",
                         ", ".join(f"{v:.0f}" for v in st["speed"][()][grows][:12])
                         + (" …" if grows.sum() > 12 else "") + " rpm" if grows.any() else "none"])
        for sweep in ("up", "down"):
            if sweep not in e:
                continue
            s = e[sweep]
            speed = s["speed"][()]
            dlf = s["dynamic_load_factor"][()]
            # a diverged speed has no results (zeros): it enters no maximum, mean or count
            ok = sweep_valid(s)
            # headlines from the speeds whose motion settled (status 0); a speed that never
            # repeated (inside a parametric instability, chaotic rattle) is listed apart
            settled = ok & (s["status"][()] == 0) if "status" in s else ok
            if settled.any():
                k = int(np.argmax(np.where(settled, dlf, -np.inf)))
                rows.append([label, f"largest dynamic load factor, settled speeds ({sweep} sweep)",
                             f"{dlf[k]:.3f} at {speed[k]:.0f} rpm"])
                dte = s["dte_peak_to_peak"][()]
                j = int(np.argmax(np.where(settled, dte, -np.inf)))
                rows.append([label, f"DTE peak-to-peak, settled speeds ({sweep} sweep), mean "
                             "(min .. max); largest at",
                             f"{stats(dte[settled], 'm')}; {speed[j]:.0f} rpm"])
            unsettled = ok & ~settled
            if unsettled.any():
                listed = ", ".join(f"{v:.0f}" for v in speed[unsettled][:12])
                more = " …" if unsettled.sum() > 12 else ""
                worst = dlf[unsettled].max()
                rows.append([label, f"speeds whose motion did not settle ({sweep} sweep): not "
                             "in the headlines",
                             f"{int(unsettled.sum())} of {len(speed)}: {listed}{more} rpm "
                             f"(load factor there up to {worst:.3f})"])
            if not ok.all():
                rows.append([label, f"DIVERGED speeds ({sweep} sweep): no results there",
                             diverged_speeds(s)])
            if "contact_loss" in s:
                lost = int(np.count_nonzero(s["contact_loss"][()][ok]))
                rows.append([label, f"speeds with contact loss ({sweep} sweep)",
                             f"{lost} of {int(ok.sum())}"])
            if "error_estimate" in s and ok.any():
                worst = s["error_estimate"][()][ok].max()
                rows.append([label, f"estimated integration error of the DTE ({sweep} sweep), "
                             "largest over the speeds", f"{worst * 100:.2g} % of its RMS"])
    return rows


def glance_rows(f):
    """The headline of every pair (one row a torque) and of every train mesh: the numbers the
    key table below details, from the same rules (settled speeds, no edge positions)."""
    rows, trains = [], []
    for pair in f["flanks"] if "flanks" in f else []:
        fl = f["flanks"][pair]
        eps = (f"{fl['transverse_contact_ratio'][()]:.3f} / {fl['overlap_ratio'][()]:.3f}"
               if "transverse_contact_ratio" in fl and "overlap_ratio" in fl else "–")
        ste = f["ste"][pair] if "ste" in f and pair in f["ste"] else None
        e0 = number(plot_results.resolved(ste["peak_to_peak"][()], plot_results.ANGLE_FLOOR),
                    "rad") if ste is not None and "peak_to_peak" in ste else "–"
        dlf = "–"
        if "dynamics" in f and pair in f["dynamics"]:
            best = None
            for ex, e in f["dynamics"][pair].items():
                if isinstance(e, h5py.Group) and "up" in e:
                    s = e["up"]
                    ok = sweep_valid(s) & ((s["status"][()] == 0) if "status" in s else True)
                    if ok.any():
                        k = int(np.argmax(np.where(ok, s["dynamic_load_factor"][()], -np.inf)))
                        v = (s["dynamic_load_factor"][()][k], s["speed"][()][k], ex)
                        best = v if best is None or v[0] > best[0] else best
            if best is not None:
                dlf = f"{best[0]:.3f} at {best[1]:.0f} rpm ({esc(best[2])})"
        if not ("stiffness" in f and pair in f["stiffness"]):
            if ste is not None or dlf != "–":
                rows.append([esc(pair), eps, e0, "–", "–", "–", "–", dlf])
            continue
        g = f["stiffness"][pair]
        for t, torque in enumerate(g["torque"][()]):
            pp, orders = plot_results.te_harmonics(g["transmission_error_loaded"][t])
            edge = plot_results.edge_contact(g, t)
            pressure = "–"
            if "interior_peak_pressure" in g and (~edge).any():
                pressure = number(g["interior_peak_pressure"][t][~edge].max(), "Pa")
                if edge.any():
                    pressure += f" ({int(edge.sum())} edge positions apart)"
            elif "interior_peak_pressure" in g:
                pressure = ("every position on an edge; cells' median / 90th percentile "
                            + cell_pressure_spread(g, t))
            rows.append([esc(pair), eps, e0, f"{torque:g} N m",
                         f"{number(pp, 'rad')} ({', '.join(f'{a * 1e6:.3g}' for a in orders)})",
                         stats(g["mesh_stiffness"][t], "N/m"), pressure, dlf])
    for name in f["train"] if "train" in f else []:
        g = f["train"][name]
        for mesh in g["meshes"] if "meshes" in g else []:
            m = g["meshes"][mesh]
            first = m["first_contact"][()]
            line = "–"
            if "spectrum" in m:
                lines = m["spectrum"]["lines"]
                k = np.nonzero((lines["harmonic"][()] == 1) & (lines["sideband"][()] == 0))[0]
                if k.size and lines["found"][()][k[0]]:
                    line = (f"{lines['amplitude'][()][k[0]]:.3g} N at "
                            f"{lines['frequency'][()][k[0]]:.2f} Hz")
                elif k.size:
                    line = "not found"
            trains.append([f"{esc(name)}, {esc(mesh)}",
                           f"{int(m['impacts'][()])} ({int(m['drive_impacts'][()])} / "
                           f"{int(m['coast_impacts'][()])})",
                           "none" if first < 0 else f"{first * 1e3:.3f} ms",
                           number(m["max_force"][()], "N"), line])
    return rows, trains


def with_notes(rows, notes):
    """The key rows with the scene's notes (section Notes: `<name>\t<area>\t<text>` a line,
    root attribute `notes`) each set after the last row of its area and name: the caveat next
    to the number it qualifies."""
    for line in notes.splitlines():
        parts = line.split("\t", 2)
        if len(parts) != 3 or not parts[2].strip():
            continue
        name, area, text = parts
        row = [area, f"{esc(name)}: note", f'<span class="note">{esc(text)}</span>']
        at = [i for i, r in enumerate(rows) if r[0] == area and r[1].startswith(esc(name))]
        if not at:
            at = [i for i, r in enumerate(rows) if r[0] == area]
        rows.insert(at[-1] + 1 if at else len(rows), row)
    return rows


def scalar_rows(f):
    """Every scalar dataset of the results with its units and description."""
    rows = []

    def visit(path, obj):
        if isinstance(obj, h5py.Dataset) and obj.shape == () and obj.dtype.kind in "fiu":
            units = attr(obj, "units", "1")
            rows.append([esc(path), number(obj[()], units), esc(attr(obj, "description"))])
    f.visititems(visit)
    return rows


def checks(f):
    """Checks any reader can repeat: every floating-point dataset finite (no NaN, no infinity:
    results have none; a speed whose dynamics diverged says so in its sweep's `status`)."""
    bad, total = [], 0

    def visit(path, obj):
        nonlocal total
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
            total += 1
            if not np.all(np.isfinite(obj[()])):
                bad.append(path)
    f.visititems(visit)
    return total, bad


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    results = sys.argv[1]
    folder = os.path.dirname(os.path.abspath(results))
    page = Page()
    with h5py.File(results, "r") as f:
        scene = attr(f, "scene")
        made = os.path.getmtime(results)
        page.h(1, f"gearkit — {scene}")
        page.p(f"Scene file <code>{esc(attr(f, 'scene_file'))}</code>, run "
               f"{time.strftime('%Y-%m-%d %H:%M', time.localtime(made))}. "
               f"Results: <code>results.h5</code> beside this page (SI units; shown here in µm, "
               f"µrad, N/µm, MPa).", "meta")

        # 0. Warnings of the scene's plausibility checks, before anything else
        warnings = [w for w in attr(f, "warnings").splitlines() if w.strip()]
        # and the stages' own (a torque the loaded contact refused, a lost error estimate)
        for stage in ("stiffness",):
            for pair in (f[stage] if stage in f else []):
                if isinstance(f[stage][pair], h5py.Group):
                    warnings += [w for w in attr(f[stage][pair], "warnings").splitlines()
                                 if w.strip()]
        for pair in (f["study"] if "study" in f else []):
            g = f["study"][pair]
            if isinstance(g, h5py.Group) and "zone_edge" in g:
                listed, count, total = study_invalid(g)
                if count:
                    warnings.append(f"study {pair}: {plot_study.INVALID} ({count} of {total} "
                                    f"results: {listed})")
        if warnings:
            page.h(2, f"Warnings ({len(warnings)})", "warnings")
            page.raw('<div class="warnings"><ul>' + "".join(f"<li>{esc(w)}</li>" for w in warnings)
                     + "</ul></div>")

        # 1. Key numbers and their accuracy
        glance, train_glance = glance_rows(f)
        if glance:
            page.h(2, "At a glance", "glance")
            page.table(["pair", "ε_α / ε_β", "e_0 p-p", "torque", "e_L p-p (orders 1, 2, 3)",
                        "K_m mean (min .. max)", "flank-interior pressure",
                        "dynamic load factor (settled)"], glance, "glance")
        if train_glance:
            if not glance:
                page.h(2, "At a glance", "glance")
            page.table(["train, mesh", "impacts (drive / coast)", "first contact",
                        "largest force (located)", "GMF line"], train_glance, "glance")
        page.h(2, "Key numbers", "key")
        rows = []
        if "flanks" in f:
            for pair in f["flanks"]:
                rows += [["gear data", r[0] + ": " + r[1], r[2]]
                         for r in gear_rows(pair, f["flanks"][pair])]
        if "ste" in f:
            for pair in f["ste"]:
                g = f["ste"][pair]
                if "peak_to_peak" in g:
                    rows.append(["unloaded TCA", f"{esc(pair)} e_0 peak-to-peak (theoretical)",
                                 number(plot_results.resolved(g["peak_to_peak"][()],
                                                              plot_results.ANGLE_FLOOR), "rad")])
                if "measured" in g and "peak_to_peak" in g["measured"]:
                    rows.append(["unloaded TCA", f"{esc(pair)} e_0 peak-to-peak (measured flanks)",
                                 number(plot_results.resolved(g["measured"]["peak_to_peak"][()],
                                                              plot_results.ANGLE_FLOOR), "rad")])
                if "mean_pairs_in_contact" in g:
                    rows.append(["unloaded TCA", f"{esc(pair)} pairs touching without load, "
                                 "mean (rigid teeth touch one at a time; the contact ratio is ε_α)",
                                 f"{g['mean_pairs_in_contact'][()]:.3f}"])
        if "compliance" in f:
            for pair in f["compliance"]:
                for member in ("pinion", "gear"):
                    if member in f["compliance"][pair]:
                        m = f["compliance"][pair][member]
                        rows.append(["finite elements", f"{esc(pair)} {member}",
                                     f"{int(m['dofs'][()]):,} dofs, {int(m['hexahedra'][()]):,} "
                                     f"hexahedra, {m['seconds'][()]:.1f} s"])
        if "stiffness" in f:
            for pair in f["stiffness"]:
                # the TE as a length: along the line of action (involutes: r_b1), else at the
                # pinion's pitch radius where the unloaded TCA gives one (bevel pairs)
                r_b = (f["flanks"][pair]["pinion"]["base_radius"][()]
                       if "flanks" in f and pair in f["flanks"] and "pinion" in f["flanks"][pair]
                       and "base_radius" in f["flanks"][pair]["pinion"] else None)
                if r_b is None and "ste" in f and pair in f["ste"] and "pitch_radius" in f["ste"][pair]:
                    r_b = (f["ste"][pair]["pitch_radius"][()], "at the pinion's pitch radius")
                rows += [["loaded contact", r[0] + ": " + r[1], r[2]]
                         for r in stiffness_rows(pair, f["stiffness"][pair], r_b)]
                if "measured" in f["stiffness"][pair]:
                    rows += [["loaded contact", r[0] + ": " + r[1], r[2]]
                             for r in stiffness_rows(f"{pair} (measured flanks)",
                                                     f["stiffness"][pair]["measured"], r_b)]
        if "dynamics" in f:
            for pair in f["dynamics"]:
                rows += [["dynamics", r[0] + ": " + r[1], r[2]]
                         for r in dynamics_rows(pair, f["dynamics"][pair])]
        if "train" in f:
            for name in f["train"]:
                rows += [["gear train", r[0] + ": " + r[1], r[2]]
                         for r in train_rows(name, f["train"][name])]
        rows = with_notes(rows, attr(f, "notes"))
        total, bad = checks(f)
        rows.append(["checks", "finite values in every floating-point dataset",
                     f"{total - len(bad)} of {total} datasets"
                     + ("" if not bad else " — not: " + esc(", ".join(bad[:10])))])
        page.table(["stage", "what", "value"], rows, "key")

        # 1b. The studies: micro-geometry maps (the best design per torque), tolerance Monte
        # Carlo runs, misalignment (V-H) checks
        for kind, title, anchor, header, table_rows in (
                (plot_study.KIND, "Micro-geometry map", "study",
                 ["pair", "torque", "what", "value"], study_rows),
                (plot_study.TOLERANCES, "Tolerance Monte Carlo", "tolerances",
                 ["pair", "torque", "what", "value"],
                 lambda pair, g: (tolerance_rows(pair, g), [])),
                (plot_study.MISALIGNMENTS, "Misalignment (V-H) check", "misalignments",
                 ["pair", "assembly", "torque", "e0 / eL p-p", "pattern centre (face, profile)",
                  "pattern face × profile", "edge load (alarm > 10 %)"], misalignment_rows)):
            studies = [(pair, f["study"][pair]) for pair in (f["study"] if "study" in f else [])
                       if plot_study.text(f["study"][pair].attrs.get("kind", "")) == kind]
            if not studies:
                continue
            page.h(2, title, anchor)
            rows, alarm = [], []
            for pair, g in studies:
                r, a = table_rows(pair, g)
                alarm += [len(rows) + i for i in a]
                rows += r
            page.table(header, rows, anchor, alarm)

        # 2. Pictures
        pngs = sorted((p for p in os.listdir(folder)
                       if p.endswith(".png") and os.path.getmtime(os.path.join(folder, p)) >= made - 1),
                      key=workflow_order)
        page.h(2, "Pictures", "pictures")
        if not pngs:
            page.p("No pictures drawn from these results (run with <code>--plot</code>, as "
                   "<code>./run</code> does).")
        for png in pngs:
            with open(os.path.join(folder, png), "rb") as fh:
                data = base64.b64encode(fh.read()).decode()
            page.raw(f'<figure><img src="data:image/png;base64,{data}" alt="{esc(png)}">'
                     f"<figcaption><b>{esc(png)}</b>: {esc(caption(png))}</figcaption></figure>")

        # 3. Stages
        page.h(2, "Stages", "stages")
        stage_rows = []
        for line in attr(f, "stage_table").splitlines():
            name, how, seconds, cache = (line.split("\t") + ["", "", "", ""])[:4]
            stage_rows.append([esc(name), esc(how), f"{float(seconds or 0):.2f} s",
                               f"<code>cache/{esc(cache)}</code>"])
        page.table(["stage", "ran or reused", "time", "cache file (name-key)"], stage_rows)
        others = sorted(p for p in os.listdir(folder) if not p.endswith(".png")
                        and not p.startswith(".") and p not in ("report.html", "cache"))
        page.p("Other files beside this page: " + ", ".join(f"<code>{esc(o)}</code>" for o in others))

        # 4. Parameters, all scalars, versions
        page.h(2, "Scene parameters as run", "parameters")
        page.raw(f"<details><summary>{len(attr(f, 'scene_parameters').splitlines())} lines "
                 f"(defaults filled in)</summary><pre>{esc(attr(f, 'scene_parameters'))}</pre></details>")
        page.h(2, "Every scalar result", "scalars")
        page.raw("<details><summary>with units and descriptions</summary>")
        page.table(["dataset", "value", "description"], scalar_rows(f))
        page.raw("</details>")
        page.h(2, "Versions and machine", "versions")
        page.p(esc(attr(f, "versions")) + "<br>" + esc(attr(f, "machine")))

    style = """
body{font-family:system-ui,sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.6em} h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.5em 0} td,th{border:1px solid #ddd;padding:.25em .6em;
text-align:left;vertical-align:top} th{background:#f3f3f3} table.key td:first-child{color:#666}
figure{margin:1em 0} img{max-width:100%;border:1px solid #eee} figcaption{font-size:.9em;color:#444}
.note{color:#7a4b00;font-style:italic} tr.alarm td{background:#f8d7da;color:#842029;border-color:#d9534f} .warnings{background:#fff3cd;border:2px solid #d39e00;padding:.2em 1em;font-weight:600}
pre{background:#f7f7f7;padding:.6em;overflow:auto;font-size:.85em} .meta{color:#555}
"""
    # For the browser check (tests): how many pictures decoded, on the body once the page loaded.
    script = """<script>window.addEventListener('load',function(){var i=document.images,n=0;
for(var k=0;k<i.length;k++){if(i[k].complete&&i[k].naturalWidth>0)n++;}
document.body.setAttribute('data-images',n+'/'+i.length);});</script>"""
    text = (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>gearkit — {esc(scene)}</title><style>{style}</style>{script}</head><body>\n"
            + "\n".join(page.parts) + "\n</body></html>\n")
    out = os.path.join(folder, "report.html")
    tmp = out + ".tmp"
    try:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, out)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)  # nothing half-written: the page is there whole, or not at all
    print(f"report: {out}")


if __name__ == "__main__":
    main()

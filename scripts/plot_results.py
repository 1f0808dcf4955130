#!/usr/bin/python3
"""Pictures of a gearkit result file: one PNG per kind of result, next to results.h5.

usage: plot_results.py out/<scene>/results.h5

  profiles.png  transverse tooth profiles of every pair, in mesh at the working centre distance
  topography.png  modifications of tooth 0 (drive, coast) of every member, um over the flank
  measured.png    measured minus theoretical flank of the first measured tooth, um
  ste.png         unloaded static transmission error, harmonics, contact path
  hunting.png     STE over the hunting-tooth cycle and its spectrum in pinion shaft orders
  contact_pattern.png  contact ellipses on the gear flank over the analysed positions
  ste_harmonics.md     mesh-order harmonics at the pitch point, theoretical and measured
  stiffness.png   loaded against unloaded TE, mesh stiffness over the mesh cycle (with ISO
                  6336), load sharing and the contact pressure on the pinion flank
  study_<pair>.png  per micro-geometry map of the study stage: the Harris map (TE p-p over the
                  torque and the modification), K_m and the TE of the best (plot_study.py)
  train_<train>.png  per gear train: the relative displacement S of every mesh with its
                  backlash band, its force, its force spectrum with the GMF harmonics and the
                  sidebands found, the body speeds and the energy balance
  train_compare.png  every train of the scene over each other: S, forces and speeds
  train_spectrogram.png  the first mesh's force over time and frequency, per train
"""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
import numpy as np  # noqa: E402


def save(fig, path):
    """Write atomically: a reader never sees a half-written PNG."""
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=130)
    plt.close(fig)
    os.replace(tmp, path)
    print("picture:", path)


# Below these the numbers are the computation's round-off, shown as 0: transmission errors and
# angles 1e-10 rad (a 0.1 nm at a 1 m radius), lengths 1e-12 m.
ANGLE_FLOOR, LENGTH_FLOOR = 1e-10, 1e-12


def resolved(value, floor):
    """value with everything smaller than floor in magnitude set to 0."""
    a = np.asarray(value, dtype=float)
    return np.where(np.abs(a) < floor, 0.0, a)


def rotate(xy, angle):
    c, s = np.cos(angle), np.sin(angle)
    return xy @ np.array([[c, s], [-s, c]])


def is_bevel(pair_group):
    return pair_group.attrs.get("type", "involute") == "spiral bevel"


def flank_coordinates(flanks, name, member, u, v):
    """Flank parameters as lengths in mm: (face, profile). Involute: z and roll length r_b u;
    spiral bevel: A - A_m and the height h above the pitch cone."""
    m = flanks[name][member]
    if is_bevel(flanks[name]):
        return v * 1e3, u * 1e3
    return v * 1e3, m["base_radius"][()] * u * 1e3


def gear_flank_coordinates(flanks, name, points):
    """(face, profile) in mm of points given in the gear's own frame: spiral bevel: cone
    distance - A_m and height above the pitch cone (rotational projection); involute: z and
    roll length."""
    gear = flanks[name]["gear"]
    axial, radius = points[..., 2], np.hypot(points[..., 0], points[..., 1])
    if is_bevel(flanks[name]):
        gamma = gear["pitch_angle"][()]
        A = axial * np.cos(gamma) + radius * np.sin(gamma)
        h = -axial * np.sin(gamma) + radius * np.cos(gamma)
        return (A - flanks[name]["mean_cone_distance"][()]) * 1e3, h * 1e3
    rb = gear["base_radius"][()]
    return axial * 1e3, np.sqrt(np.maximum(radius**2 - rb**2, 0)) * 1e3


def plot_profiles(flanks, out_dir):
    """The transverse tooth profiles of every parallel-axis pair in mesh at its working centre
    distance: the whole pair (left) and the mesh region enlarged (right; dotted: base circles,
    dashed: reference circles), pinion blue, gear red."""
    pairs = [n for n in flanks if not is_bevel(flanks[n])]
    if not pairs:
        return
    fig, axes = plt.subplots(len(pairs), 2, figsize=(12, 5.2 * len(pairs)), squeeze=False)
    for row, name in zip(axes, pairs):
        pair = flanks[name]
        a = pair["working_centre_distance"][()]
        p, g = pair["pinion"], pair["gear"]
        z1, z2 = int(p["number_of_teeth"][()]), int(g["number_of_teeth"][()])
        # Pinion at the origin with tooth 0 on +x; gear at (a, 0) turned so that a tooth space
        # faces the pinion tooth.
        pin = p["transverse_outline"][:] * 1e3
        gea = rotate(g["transverse_outline"][:], np.pi + np.pi / z2) * 1e3 + [a * 1e3, 0]
        for ax, zoom in zip(row, (False, True)):
            for xy, member, colour in ((pin, p, "tab:blue"), (gea, g, "tab:red")):
                closed = np.vstack([xy, xy[:1]])
                # (a collection: Axes.fill's patch bounds its many-vertex outline in Python,
                # seconds for a gear of a hundred teeth)
                ax.add_collection(PolyCollection([closed], facecolors=colour, alpha=0.15,
                                                 linewidths=0))
                ax.plot(closed[:, 0], closed[:, 1], color=colour, lw=0.8)
            for member, centre, colour in ((p, 0.0, "tab:blue"), (g, a * 1e3, "tab:red")):
                t = np.linspace(0, 2 * np.pi, 400)
                for key, style in (("base_radius", ":"), ("reference_radius", "--")):
                    r = member[key][()] * 1e3
                    ax.plot(centre + r * np.cos(t), r * np.sin(t), style, color=colour, lw=0.6)
            for member, centre in ((p, 0.0), (g, a * 1e3)):
                r = member["bore_radius"][()] * 1e3
                if r > 0:
                    ax.add_patch(plt.Circle((centre, 0), r, color="white", ec="k", lw=0.6))
            ax.set_aspect("equal")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
            if zoom:
                r1 = p["reference_radius"][()] * 1e3
                m = p["normal_module"][()] * 1e3
                ax.set_xlim(r1 - 3.5 * m, r1 + 3.5 * m)
                ax.set_ylim(-4 * m, 4 * m)
                ax.set_title(f"{name}: mesh region (dotted: base circles, dashed: reference)")
            else:
                ax.set_title(
                    f"{name}: z {z1}/{z2}, m_n {p['normal_module'][()] * 1e3:g} mm, "
                    f"beta {np.degrees(abs(p['helix_angle'][()])):g} deg, a_w {a * 1e3:.3f} mm"
                )
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "profiles.png"))


def plot_topography(flanks, out_dir):
    """K-chart of every member whose flanks carry modifications or deviations: the profile trace
    (along the roll length, at mid-face) and the lead trace (along the face, at mid-profile) of
    the flank most teeth share, drive solid and coast dashed, and the traces of every tooth that
    differs from it (a proud or chipped tooth, a pitch error) through its largest difference;
    right: the map of the flank with the largest deviation, um along the normal."""
    rows = []
    for pn in flanks:
        if is_bevel(flanks[pn]):
            continue
        for mn in ("pinion", "gear"):
            if mn not in flanks[pn]:
                continue
            m = flanks[pn][mn]
            sides = {s: m[s]["deviation"][:] * 1e6 for s in ("drive", "coast") if s in m}
            if any(np.abs(d).max() > 1e-3 for d in sides.values()):  # 1 nm: round-off below
                rows.append((pn, mn, m, sides))
    if not rows:
        return
    fig, axes = plt.subplots(len(rows), 3, figsize=(13, 3.9 * len(rows)), squeeze=False,
                             layout="constrained")
    for (ax_p, ax_l, ax_m), (pn, mn, m, sides) in zip(axes, rows):
        rb = m["base_radius"][()]
        worst = None
        for (side, dev), style in zip(sides.items(), ("-", "--")):
            s = m[side]
            L = rb * s["roll_angle"][:] * 1e3
            z = s["z"][:] * 1e3
            common = np.median(dev, axis=0)  # the flank most teeth share
            i, j = dev.shape[1] // 2, dev.shape[2] // 2
            ax_p.plot(L, common[:, j], style, color="k", label=f"{side}, most teeth")
            ax_l.plot(z, common[i, :], style, color="k", label=f"{side}, most teeth")
            if worst is None or np.abs(common).max() > worst[0]:
                worst = (np.abs(common).max(), common, L, z, f"{side}, most teeth")
            differ = np.abs(dev - common).reshape(len(dev), -1).max(axis=1)
            for n, k in enumerate(np.nonzero(differ > 1e-3)[0][:6]):
                a, b = np.unravel_index(np.argmax(np.abs(dev[k] - common)), common.shape)
                c = TRAIN_COLOURS[n % len(TRAIN_COLOURS)]
                ax_p.plot(L, dev[k][:, b], style, color=c, lw=1.4, label=f"{side}, tooth {k}")
                ax_l.plot(z, dev[k][a, :], style, color=c, lw=1.4, label=f"{side}, tooth {k}")
                if np.abs(dev[k]).max() > worst[0]:
                    worst = (np.abs(dev[k]).max(), dev[k], L, z, f"{side}, tooth {k}")
        ax_p.set_xlabel("roll length L [mm] (root to tip)")
        ax_p.set_ylabel("deviation [um]")
        ax_p.set_title(f"{pn} {mn}: profile traces")
        ax_l.set_xlabel("face z [mm]")
        ax_l.set_title(f"{pn} {mn}: lead traces")
        for ax in (ax_p, ax_l):
            ax.grid(alpha=0.3)
        ax_l.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        _, dev, L, z, what = worst
        span = max(np.abs(dev).max(), 1e-3)
        im = ax_m.pcolormesh(z, L, dev, shading="gouraud", cmap="coolwarm", vmin=-span,
                             vmax=span)
        fig.colorbar(im, ax=ax_m, label="deviation [um]")
        ax_m.set_title(f"{mn} {what}")
        ax_m.set_xlabel("face z [mm]")
        ax_m.set_ylabel("roll length L [mm]")
    save(fig, os.path.join(out_dir, "topography.png"))


def plot_measured(measured, out_dir):
    """Measured minus theoretical flank (um), drive and coast of the first measured tooth of
    every member whose measurement deviates from its theoretical counterpart."""
    rows = []
    for pn in measured:
        for mn in ("pinion", "gear"):
            groups = measured[pn][mn] if mn in measured[pn] else {}
            names = [n for n in groups if n.startswith("tooth_") and "deviation" in groups[n]]
            if not names:
                continue
            tooth = min(int(n.split("_")[1]) for n in names)
            sides = [groups[f"tooth_{tooth}_{s}"] for s in ("drive", "coast")
                     if f"tooth_{tooth}_{s}" in groups]
            if max(np.abs(g["deviation"][:]).max() for g in sides) > 1e-9:
                rows.append((pn, mn, tooth, sides))
    if not rows:
        return
    fig, axes = plt.subplots(len(rows), 2, figsize=(9, 3.3 * len(rows)), squeeze=False)
    for row, (pn, mn, tooth, sides) in zip(axes, rows):
        for ax, g in zip(row, sides):
            dev = g["deviation"][:] * 1e6
            span = max(np.abs(dev).max(), 1.0)
            im = ax.imshow(dev, origin="lower", aspect="auto", cmap="coolwarm", vmin=-span,
                           vmax=span)
            fig.colorbar(im, ax=ax, label="measured - theory [um]")
            ax.set_title(f"{pn} {mn}, tooth {tooth}, {g.attrs['side']}")
            ax.set_xlabel("face point (-z to +z)")
            ax.set_ylabel("profile point (root to tip)")
    fig.suptitle("Measured flanks against theory")
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "measured.png"))


def plot_ste(ste, flanks, out_dir):
    """Unloaded static transmission error of every pair over its mesh cycles, its mesh-order
    harmonics, and the contact path on the pinion flank."""
    pairs = list(ste)
    fig, axes = plt.subplots(len(pairs), 3, figsize=(12.5, 3.8 * len(pairs)), squeeze=False,
                             gridspec_kw={"width_ratios": [2.2, 1, 1.2]})
    for row, name in zip(axes, pairs):
        g = ste[name]
        z1 = int(flanks[name]["pinion"]["number_of_teeth"][()])
        cycles = g["pinion_angle"][:] * z1 / (2 * np.pi)
        te = g["transmission_error"][:] * 1e6
        row[0].plot(cycles, te, ".-", ms=3, lw=0.8, label="theoretical flanks")
        measured = g["measured"] if "measured" in g else None
        if measured is not None:
            row[0].plot(cycles, measured["transmission_error"][:] * 1e6, ".-", ms=3, lw=0.8,
                        label="measured flanks (discrete-point)")
            row[0].legend(fontsize=8)
        row[0].set_xlabel("pinion angle [mesh cycles]")
        row[0].set_ylabel("e_0 [urad, pinion]")
        pp = resolved(g["peak_to_peak"][()], ANGLE_FLOOR) * 1e6
        row[0].set_title(f"{name}: unloaded STE, peak-to-peak {pp:.3g} urad"
                         + (" (conjugate flanks)" if pp == 0 else ""))
        row[0].grid(alpha=0.3)
        h = resolved(g["harmonics"][1:], LENGTH_FLOOR) * 1e6
        orders = np.arange(1, len(h) + 1)
        width = 0.4 if measured is not None else 0.8
        row[1].bar(orders - (width / 2 if measured is not None else 0), h, width,
                   label="theoretical")
        if measured is not None:
            row[1].bar(orders + width / 2, resolved(measured["harmonics"][1:], LENGTH_FLOOR) * 1e6, width,
                       label="measured")
            row[1].legend(fontsize=8)
        row[1].set_xlabel("mesh order")
        row[1].set_ylabel("amplitude at pitch point [um]")
        row[1].set_title("harmonics")
        lead = g["leading"][:]
        idx = np.arange(len(lead))
        face, profile = flank_coordinates(flanks, name, "pinion", g["pinion_u"][:][idx, lead],
                                          g["pinion_v"][:][idx, lead])
        sc = row[2].scatter(face, profile, c=cycles, s=10, cmap="viridis")
        fig.colorbar(sc, ax=row[2], label="mesh cycles")
        half_b = flanks[name]["pinion"]["face_width"][()] * 500
        row[2].set_xlim(-half_b * 1.05, half_b * 1.05)
        if is_bevel(flanks[name]):
            p = flanks[name]["pinion"]
            row[2].set_ylim(p["drive"]["form_height"][()] * 1e3, p["addendum"][()] * 1e3)
            row[2].set_xlabel("face: cone distance - A_m [mm] (toe to heel)")
            row[2].set_ylabel("height above the pitch cone [mm]")
        else:
            rb = flanks[name]["pinion"]["base_radius"][()]
            d = flanks[name]["pinion"]["drive"]["roll_angle"][:]
            row[2].set_ylim(rb * d[0] * 1e3, rb * d[-1] * 1e3)
            row[2].set_xlabel("face z [mm]")
            row[2].set_ylabel("pinion roll length L [mm]")
        row[2].set_title("contact path on the pinion flank (theory)")
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "ste.png"))


def plot_contact_pattern(ste, flanks, out_dir):
    """Contact pattern on the gear flank: the instantaneous contact ellipses (at the scene's
    elastic approach) of every touching pair over the analysed positions, theoretical and
    measured flanks side by side."""
    pairs = list(ste)
    sets = [(n, label, g) for n in pairs
            for label, g in (("theoretical", ste[n]), ("measured", ste[n].get("measured")))
            if g is not None]
    fig, axes = plt.subplots(1, len(sets), figsize=(6.5 * len(sets), 4.8), squeeze=False)
    t = np.linspace(0, 2 * np.pi, 60)
    clip_items = []
    for ax, (name, label, g) in zip(axes[0], sets):
        gear = flanks[name]["gear"]
        sep = g["separation"][:]
        tol = g["paper_tolerance"][()] if "paper_tolerance" in g else 1e-9
        touching = (g["pinion_tooth"][:] >= 0) & (sep <= tol)  # slots in use, in contact
        geo = g["contact_in_gear_frame"][:]
        half_b = gear["face_width"][()] * 500
        ellipses = []
        for i, k in zip(*np.nonzero(touching)):
            X, A, B = geo[i, k]
            pts = X + np.outer(np.cos(t), A) + np.outer(np.sin(t), B)
            ellipses.append(np.column_stack(gear_flank_coordinates(flanks, name, pts)))
        if ellipses:  # (collections: one patch a contact took seconds for a hunting cycle)
            clip_items.append(ax.add_collection(
                PolyCollection(ellipses, facecolors="tab:green", alpha=0.08, linewidths=0)))
            clip_items.append(ax.add_collection(
                LineCollection(ellipses, colors="tab:green", linewidths=0.3, alpha=0.5)))
        face, profile = gear_flank_coordinates(flanks, name, geo[touching][:, 0])
        ax.plot(face, profile, "k.", ms=2, label="contact points")
        if is_bevel(flanks[name]):
            lo, hi = gear["drive"]["form_height"][()] * 1e3, gear["addendum"][()] * 1e3
            ax.set_ylabel("height above the pitch cone [mm] (root to tip)")
            ax.set_xlabel("face: cone distance - A_m [mm] (toe to heel)")
        else:
            rb = gear["base_radius"][()]
            d = gear["drive"]["roll_angle"][:]
            lo, hi = rb * d[0] * 1e3, rb * d[-1] * 1e3
            ax.set_ylabel("gear roll length L [mm]")
            ax.set_xlabel("face z [mm]")
        outline = plt.Rectangle((-half_b, lo), 2 * half_b, hi - lo, fill=False, color="k",
                                lw=0.8)
        ax.add_patch(outline)
        for item in clip_items:  # the pattern ends at the flank's edges
            item.set_clip_path(outline)
        clip_items.clear()
        ax.set_xlim(-half_b * 1.08, half_b * 1.08)
        ax.set_ylim(lo - 0.08 * (hi - lo), hi + 0.08 * (hi - lo))
        delta = g["elastic_approach"][()] * 1e6
        ax.set_title(f"{name} ({label}): contact pattern on the gear flank, approach {delta:g} um",
                     fontsize=10)
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "contact_pattern.png"))


def write_harmonic_table(ste, out_dir):
    """The mesh-order harmonics of e_0 as displacement at the pitch point, theoretical and
    measured, in the seed paper's form (ste_harmonics.md)."""
    lines = []
    for name in ste:
        g = ste[name]
        m = g.get("measured")
        lines.append(f"## {name}\n")
        lines.append(f"pitch radius {g['pitch_radius'][()] * 1e3:.3f} mm; e_0 peak-to-peak "
                     f"{g['peak_to_peak'][()]:.4g} rad (theoretical)"
                     + (f", {m['peak_to_peak'][()]:.4g} rad (measured)" if m is not None else "")
                     + "\n")
        lines.append("| mesh order | theoretical [m] | measured [m] |")
        lines.append("|---|---|---|")
        h = g["harmonics"][:]
        hm = m["harmonics"][:] if m is not None else None
        for k in range(1, len(h)):
            lines.append(f"| {k}x | {h[k]:.3e} | " + (f"{hm[k]:.3e} |" if hm is not None else "- |"))
        lines.append("")
    path = os.path.join(out_dir, "ste_harmonics.md")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(path + ".tmp", path)
    print("table:", path)


def plot_hunting(ste, flanks, out_dir):
    """Pairs analysed over the hunting-tooth cycle: e_0 over pinion revolutions and its spectrum
    in pinion shaft orders (mesh orders at multiples of z1, per-tooth errors between them)."""
    pairs = [n for n in ste if "shaft_order_spectrum" in ste[n]]
    if not pairs:
        return
    fig, axes = plt.subplots(len(pairs), 2, figsize=(12, 4 * len(pairs)), squeeze=False,
                             gridspec_kw={"width_ratios": [1.3, 1]})
    for row, name in zip(axes, pairs):
        g = ste[name]
        z1 = int(flanks[name]["pinion"]["number_of_teeth"][()])
        revolutions = g["pinion_angle"][:] / (2 * np.pi)
        sets = [("theoretical flanks", g)]
        if "measured" in g and "shaft_order_spectrum" in g["measured"]:
            sets.append(("measured flanks", g["measured"]))
        for i, (label, h) in enumerate(sets):
            colour = f"C{i}"
            row[0].plot(revolutions, h["transmission_error_pitch"][:] * 1e6, lw=0.6, color=colour,
                        label=label)
            # the first two mesh orders, where the sidebands of per-tooth errors are readable
            shown = h["shaft_order"][:] <= 2 * z1 + 0.5
            spectrum = h["shaft_order_spectrum"][:][shown][1:] * 1e6
            orders = h["shaft_order"][:][shown][1:] + (0.08 * i - 0.04 if len(sets) > 1 else 0)
            markers, stems, _ = row[1].stem(orders, spectrum, label=label, linefmt=colour + "-",
                                            markerfmt=colour + ("o" if i == 0 else "s"),
                                            basefmt=" ")
            plt.setp(markers, markersize=3 if i == 0 else 2.5)
            plt.setp(stems, linewidth=0.8, alpha=0.8)
        row[0].set_xlabel("pinion revolutions")
        row[0].set_ylabel("e_0 at pitch point [um]")
        row[0].set_title(f"{name}: unloaded STE over the hunting cycle")
        row[0].legend(fontsize=8)
        row[0].grid(alpha=0.3)
        for m in (z1, 2 * z1):
            row[1].axvline(m, color="grey", ls="--", lw=0.6)
        row[1].set_yscale("log")
        row[1].set_ylim(bottom=1e-4)
        z2 = int(flanks[name]["gear"]["number_of_teeth"][()])
        row[1].set_xlabel(f"pinion shaft order (dashed: mesh orders; gear order 1 = {z1}/{z2})")
        row[1].set_ylabel("amplitude at pitch point [um]")
        row[1].set_title("spectrum over the hunting cycle")
        row[1].legend(fontsize=8)
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "hunting.png"))


def plot_stiffness(st, flanks, out_dir):
    """Per pair, in three rows: the loaded against the unloaded TE and the mesh stiffness K_m
    over the mesh cycle (with ISO 6336 and the error estimate); the load sharing between the
    teeth and the loaded TE's peak-to-peak and mesh orders 1-3 over the torque; the largest
    contact pressure on the pinion flank over all positions (colour capped at the flank
    interior's largest pressure where no edge carries the peak, else the cells' 90th
    percentile: cells above it, at a flank edge or tip corner where the pressure is singular,
    marked with crosses)."""
    pairs = list(st.keys())
    if not pairs:
        return
    fig = plt.figure(figsize=(12, 12.6 * len(pairs)), layout="constrained")
    grid = fig.add_gridspec(3 * len(pairs), 2)
    for p, name in enumerate(pairs):
        g = st[name]
        axes = [fig.add_subplot(grid[3 * p + r, c]) for r in (0, 1) for c in (0, 1)]
        axes.append(fig.add_subplot(grid[3 * p + 2, :]))
        phi = g["pinion_angle"][()]
        pin = flanks[name]["pinion"]
        z1 = pin["number_of_teeth"][()] if "number_of_teeth" in pin else None
        x = phi / (2 * np.pi / z1) if z1 else phi
        x_label = "mesh cycles" if z1 else "pinion angle [rad]"
        torques = g["torque"][()]
        colours = plt.cm.viridis(np.linspace(0, 0.85, len(torques)))
        variants = [(g, "-", "theory")] + ([(g["measured"], "--", "measured")] if "measured" in g else [])
        ax = axes[0]
        for grp, style, label in variants:
            e0 = grp["transmission_error_unloaded"][()] * 1e6
            ax.plot(x, e0, style, color="grey", label=f"e_0 {label}")
            for k, t in enumerate(torques):
                ax.plot(x, grp["transmission_error_loaded"][k] * 1e6, style, color=colours[k],
                        label=f"e_L {label}, {t:g} N m")
        if "error_estimate" in g:
            err = g["error_estimate"]["transmission_error_loaded"][()]
            for k in range(len(torques)):
                el = g["transmission_error_loaded"][k]
                ax.fill_between(x, (el - err[k]) * 1e6, (el + err[k]) * 1e6, color=colours[k],
                                alpha=0.25, lw=0)
        ax.set_xlabel(x_label)
        ax.set_ylabel("transmission error [urad, pinion]")
        ax.set_title(f"{name}: unloaded and loaded TE")
        legend_below(ax)
        ax = axes[1]
        for grp, style, label in variants:
            for k, t in enumerate(torques):
                ax.plot(x, grp["mesh_stiffness"][k] * 1e-6, style, color=colours[k],
                        label=f"{label}, {t:g} N m")
        if "error_estimate" in g:  # the discretisation error estimate as a band
            err = g["error_estimate"]["mesh_stiffness"][()]
            for k, t in enumerate(torques):
                km = g["mesh_stiffness"][k]
                ax.fill_between(x, (km - err[k]) * 1e-6, (km + err[k]) * 1e-6, color=colours[k],
                                alpha=0.25, lw=0,
                                label="estimated discretisation error" if k == 0 else None)
        if "reference" in g:  # reference mode at a few positions, as markers
            ref = g["reference"]
            xr = ref["pinion_angle"][()] / (2 * np.pi / z1) if z1 else ref["pinion_angle"][()]
            for k, t in enumerate(torques):
                ax.plot(xr, ref["mesh_stiffness"][k] * 1e-6, "s", ms=7, mfc="none",
                        color=colours[k], label=f"reference mode, {t:g} N m")
        for key, ls, what in (("iso_c_prime", ":", "ISO 6336 c' b (one pair)"),
                              ("iso_c_gamma_alpha", "-.", "ISO 6336 c_gamma_alpha b (mesh)")):
            if key in g:
                ax.axhline(g[key][()] * 1e-6, color="k", ls=ls, lw=1, label=what)
        if "transverse_contact_ratio" in g and "iso_c_th" in g:  # the theoretical mean
            mean = g["iso_c_th"][()] * (0.75 * g["transverse_contact_ratio"][()] + 0.25)
            ax.axhline(mean * 1e-6, color="grey", ls="--", lw=1,
                       label="ISO c'_th (0.75 eps_alpha + 0.25) b (theoretical)"
                       + (", virtual cylindrical gears" if "iso_basis" in g.attrs else ""))
        ax.set_xlabel(x_label)
        ax.set_ylabel("K_m [N/um]")
        ax.set_title("mesh stiffness K_m = F / (lambda (e_L - e_0))")
        legend_below(ax)
        ax = axes[2]
        k = len(torques) - 1
        share = g["pair_force"][k] / np.maximum(g["normal_force"][k][:, None], 1e-30)
        teeth = g["pinion_tooth"][()]
        for tooth in sorted(set(teeth[teeth >= 0].tolist())):
            y = np.where(teeth == tooth, share, 0).sum(axis=1)
            if y.max() > 0:
                ax.plot(x, y, "o-", ms=3, label=f"pinion tooth {tooth}")
        ax.set_ylim(-0.05, 1.05)
        ax.set_xlabel(x_label)
        ax.set_ylabel("share of the normal force")
        ax.set_title(f"load sharing at {torques[k]:g} N m")
        legend_below(ax, ncol=3)
        plot_te_orders(axes[3], g, torques, variants)
        ax = axes[4]
        cap = pressure_cap(g, k)
        im = pressure_map(ax, flanks, name, g["contact_cells"][k], cap)
        fig.colorbar(im, ax=ax, label="largest pressure [MPa]", extend="max")
        ax.set_xlabel("cone distance - A_m [mm]" if is_bevel(flanks[name]) else "face position [mm]")
        ax.set_ylabel("height above the pitch cone [mm]" if is_bevel(flanks[name]) else "roll length [mm]")
        ax.set_title(f"contact pressure on the pinion flank, {torques[k]:g} N m, all positions "
                     f"(colour capped at {cap * 1e-6:.0f} MPa; x: cells above it, up to "
                     f"{g['peak_pressure'][k].max() * 1e-6:.0f} MPa)")
    save(fig, os.path.join(out_dir, "stiffness.png"))


def legend_below(ax, ncol=2):
    """The legend under the axes, off the data (constrained layout makes room)."""
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=ncol,
              frameon=False)


def plot_te_orders(ax, g, torques, variants):
    """The loaded TE's peak-to-peak and its mesh orders 1-3 against the torque (te_harmonics:
    the same numbers as the report's key table); at a single torque as bars."""
    for v, (grp, style, label) in enumerate(variants):
        values = [te_harmonics(te) for te in grp["transmission_error_loaded"][()]]
        table = np.array([[pp] + list(orders) for pp, orders in values]) * 1e6
        if len(torques) == 1:
            width = 0.8 / len(variants)
            ax.bar(np.arange(4) + (v - (len(variants) - 1) / 2) * width, table[0], width,
                   color=["k", "C0", "C1", "C2"], alpha=1.0 if v == 0 else 0.45,
                   label=label)
            continue
        for n, what in enumerate(("peak-to-peak", "order 1", "order 2", "order 3")):
            ax.plot(torques, table[:, n], style + "o", color=["k", "C0", "C1", "C2"][n],
                    label=f"{what}, {label}")
    if len(torques) == 1:
        ax.set_xticks(range(4), ["peak-to-peak", "order 1", "order 2", "order 3"])
        ax.set_xlabel(f"at {torques[0]:g} N m" + (" (pale: measured flanks)"
                                                  if len(variants) > 1 else ""))
        ax.set_title("loaded TE: peak-to-peak and mesh orders 1-3")
    else:
        ax.set_xlabel("pinion torque [N m]")
        ax.set_title("loaded TE over the torque: peak-to-peak and mesh orders 1-3")
        legend_below(ax)
    ax.set_ylabel("loaded TE [urad]")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3, axis="y")


def te_harmonics(te):
    """Peak-to-peak and the amplitudes of mesh orders 1-3 of a transmission error sampled at
    uniform positions over one mesh cycle (the last position one step short of the cycle's end)."""
    te = np.asarray(te, dtype=float)
    spectrum = np.abs(np.fft.rfft(te - te.mean())) * 2 / te.size
    # below the computation's resolution (rounding of the TE's mean): zero, not 1e-20
    floor = 1e-12 * max(np.abs(te).max(), 1e-300)
    return te.max() - te.min(), [spectrum[k] if k < spectrum.size and spectrum[k] > floor
                                 else 0.0 for k in (1, 2, 3)]


def edge_contact(g, k):
    """Per position at torque k: True where the largest contact pressure sits on a flank-edge
    cell (a tip corner, the start of the working flank, a face end: singular, growing with
    mesh refinement) - there the interior's peak stands next to the singularity too. Neither is
    a headline; the report lists these positions apart."""
    if "interior_peak_pressure" not in g:
        return np.zeros(g["peak_pressure"].shape[1], dtype=bool)
    return g["peak_pressure"][k] > 1.01 * g["interior_peak_pressure"][k]


def pressure_cap(g, k):
    """The colour scale's top for torque k: the flank interior's largest pressure at the
    positions without edge contact (Hertz's), else (every position touches an edge: unmodified
    helical flanks) the loaded cells' 90th percentile - across a Hertz band the pressure
    exceeds 0.995 of its peak on a tenth of the width, so the interior's peaks reach the top
    while the singular edge cells, a few percent of all, are marked above it."""
    if "interior_peak_pressure" in g:
        clean = g["interior_peak_pressure"][k][~edge_contact(g, k)]
        if clean.size and clean.max() > 0:
            return clean.max()
    cells = g["contact_cells"][k][..., 3]
    loaded = cells[cells > 0]
    return np.percentile(loaded, 90) if loaded.size else 1.0


def pressure_map(ax, flanks, name, cells, cap, nx=500, ny=300):
    """The largest pressure over all positions on a raster of the pinion flank: the cells of each
    position and tooth pair are triangulated (Delaunay on their centres, triangles much longer
    than the cells dropped) and interpolated linearly. A scatter of the cell centres would alias
    into stripes where the contact lines run obliquely (helical gears). Colours end at `cap`
    [Pa]; the cells above it are marked with crosses."""
    pieces = []
    for c in cells:  # (cells, 4) per position: tooth, u, v, pressure
        c = c[c[:, 0] >= 0]
        for tooth in np.unique(c[:, 0]):
            t = c[c[:, 0] == tooth]
            if len(t) >= 4 and np.any(t[:, 3] > 0):
                face, profile = flank_coordinates(flanks, name, "pinion", t[:, 1], t[:, 2])
                pieces.append((face, profile, t[:, 3]))
    if not pieces:
        return ax.imshow(np.zeros((2, 2)), cmap="inferno")
    f_all = np.concatenate([p[0] for p in pieces])
    r_all = np.concatenate([p[1] for p in pieces])
    X, Y = np.meshgrid(np.linspace(f_all.min(), f_all.max(), nx),
                       np.linspace(r_all.min(), r_all.max(), ny))
    P = np.zeros_like(X)
    skipped = 0
    for face, profile, p in pieces:
        # cells that coincide on the flank (the zone folded at an edge) would make the
        # triangulation invalid: keep the first of each
        _, keep = np.unique(np.round(np.stack([face, profile], axis=1), 6), axis=0,
                            return_index=True)
        face, profile, p = face[keep], profile[keep], p[keep]
        # triangulated in coordinates scaled to the zone's extent (the cells are far longer
        # along the contact line than across it: slivers otherwise)
        sf, sp = max(np.ptp(face), 1e-9), max(np.ptp(profile), 1e-9)
        # a tiny fixed jitter: the cell centres form regular grids, whose cocircular points give
        # qhull degenerate triangles
        jitter = np.random.default_rng(0).uniform(-1e-7, 1e-7, size=(2, len(face)))
        face, profile = face / sf + jitter[0], profile / sp + jitter[1]
        try:
            tri = mtri.Triangulation(face, profile)
            xy = np.stack([face[tri.triangles], profile[tri.triangles]], axis=-1)
            longest = np.max(np.linalg.norm(xy - np.roll(xy, 1, axis=1), axis=-1), axis=1)
            flat = mtri.TriAnalyzer(tri).get_flat_tri_mask(0.01, rescale=True)
            tri.set_mask((longest > 3 * np.median(longest)) | flat)
            P = np.fmax(P, mtri.LinearTriInterpolator(tri, p)(X / sf, Y / sp).filled(0))
        except (RuntimeError, ValueError):  # degenerate (collinear) cell centres
            skipped += 1
    if skipped:
        print(f"pressure map: {skipped} of {len(pieces)} contact zones could not be drawn")
    above = [(f[p > cap], r[p > cap]) for f, r, p in pieces]
    face = np.concatenate([a[0] for a in above])
    if face.size:
        ax.plot(face, np.concatenate([a[1] for a in above]), "x", color="tab:cyan", ms=5,
                mew=1.2, label="cells above the colour scale")
    return ax.imshow(np.ma.masked_less_equal(P, 0) * 1e-6, origin="lower", aspect="auto",
                     cmap="inferno", interpolation="nearest", vmin=0, vmax=cap * 1e-6,
                     extent=(X.min(), X.max(), Y.min(), Y.max()))


EXCITATION_COLOURS = {"theoretical": "tab:blue", "measured": "tab:orange"}


def diverged(sweep):
    """Per speed of a sweep group: True where the response diverged (`status` 2: no results,
    its datasets hold 0 there)."""
    if "status" in sweep:
        return sweep["status"][:] == 2
    return np.zeros(len(sweep["speed"]), dtype=bool)


def valid(sweep, name):
    """A sweep dataset with its diverged speeds blanked (NaN: matplotlib leaves a gap)."""
    a = sweep[name][:].astype(float)
    a[diverged(sweep)] = np.nan
    return a


def plot_dynamics(dyn, flanks, out_dir):
    """Per pair: DTE peak-to-peak, DTE RMS and the dynamic load factor against the pinion speed,
    swept up and down (jumps show as the two curves part) for each excitation (theoretical and
    measured flanks: the seed's comparison), the Campbell diagram: the linear modes with
    enough mesh strain energy against the first three mesh orders, and the integrator's share:
    Newmark's estimated DTE error and its steps per mesh cycle at each speed."""
    pairs = list(dyn.keys())
    fig, grid = plt.subplots(3 * len(pairs), 2, figsize=(12, 12 * len(pairs)), squeeze=False,
                             layout="constrained")
    for p, name in enumerate(pairs):
        row = grid[3 * p:3 * p + 3].ravel()  # five panels and the legend's slot
        g = dyn[name]
        labels = [k for k in ("theoretical", "measured") if k in g]
        for label in labels:
            for direction, style in (("up", "-"), ("down", "--")):
                d = g[label][direction]
                rpm = d["speed"][:]
                kw = dict(lw=1.2, color=EXCITATION_COLOURS[label], label=f"{label}, {direction}")
                row[0].plot(rpm, valid(d, "dte_peak_to_peak") * 1e6, style, **kw)
                row[1].plot(rpm, valid(d, "dte_rms") * 1e6, style, **kw)
                row[2].plot(rpm, valid(d, "dynamic_load_factor"), style, **kw)
                if "status" in d and np.any(d["status"][:] == 1):  # motion never repeated
                    uns = d["status"][:] == 1
                    row[2].plot(rpm[uns], d["dynamic_load_factor"][:][uns], "o", mfc="none",
                                ms=5, color=kw["color"],
                                label=f"{label}, {direction}: did not settle (not a headline)")
                # diverged speeds (no results): crosses on the speed axis
                bad = diverged(d)
                for ax in row[:3]:
                    if bad.any():
                        ax.plot(rpm[bad], np.zeros(bad.sum()), "x", color="tab:red", ms=8,
                                mew=2, clip_on=False,
                                label=f"{label}, {direction}: diverged (no result)")
        # speeds where the mesh in contact is parametrically unstable (Floquet): shaded
        for label in labels:
            if "stability" not in g[label]:
                continue
            st = g[label]["stability"]
            rpm, radius = st["speed"][:], st["spectral_radius"][:]
            step = rpm[1] - rpm[0] if len(rpm) > 1 else 1
            grows = st["unstable"][:] != 0 if "unstable" in st else radius > 1
            for i in np.nonzero(grows)[0]:
                for ax in row[:3]:
                    ax.axvspan(rpm[i] - step / 2, rpm[i] + step / 2, color=EXCITATION_COLOURS[label],
                               alpha=0.15, lw=0)
        row[0].set_xlabel("pinion speed [rpm]")
        row[0].set_ylabel("DTE peak-to-peak [um]")
        row[0].set_title(f"{name}: dynamic transmission error, peak-to-peak")
        row[1].set_xlabel("pinion speed [rpm]")
        row[1].set_ylabel("DTE RMS [um]")
        row[1].set_title("RMS of the dynamic transmission error")
        row[2].set_xlabel("pinion speed [rpm]")
        row[2].set_ylabel("max F_m / static F_m")
        static = g[labels[0]]["static_mesh_force"][()]
        row[2].set_title(f"dynamic load factor (static mesh force {static:.0f} N)")
        # one legend for the three sweep panels, in the sixth slot
        handles, names = row[2].get_legend_handles_labels()
        if any(g[label].get("stability") is not None for label in labels):
            handles.append(plt.Rectangle((0, 0), 1, 1, color="0.5", alpha=0.3))
            names.append("shaded: parametrically unstable (Floquet)")
        row[5].axis("off")
        row[5].legend(handles, names, loc="center", fontsize=10, frameon=False,
                      title=f"{name}: sweeps (up solid, down dashed)")
        ax = row[3]
        f_modes, energy = g["mode_frequency"][:], g["mode_mesh_energy"][:]
        rpm = g[labels[0]]["up"]["speed"][:]
        n_max = rpm.max()
        z = g["pinion_teeth"][()]
        top = 1.3 * f_modes.max()
        for order in (1, 2, 3):
            n_end = min(n_max, top * 60 / (order * z))  # where the order leaves the plot
            ax.plot([0, n_end], [0, order * z * n_end / 60], "k-", lw=0.8)
            ax.text(n_end, order * z * n_end / 60, f" {order}x", fontsize=9, va="top")
        for f_mode, e in zip(f_modes, energy):
            if e > 0.05:
                ax.axhline(f_mode, color="tab:red", lw=0.8 + 3 * e)
                ax.text(0, f_mode, f" {f_mode:.0f} Hz ({100 * e:.0f} % in the mesh)", fontsize=9,
                        va="bottom")
        ax.set_xlim(0, n_max * 1.08)
        ax.set_ylim(0, top)
        ax.set_xlabel("pinion speed [rpm]")
        ax.set_ylabel("frequency [Hz]")
        ax.set_title("Campbell: modes (red; width: mesh energy), orders")
        ax = row[4]
        steps_ax = None
        for label in labels:
            for direction, style in (("up", "-"), ("down", "--")):
                d = g[label][direction]
                if "error_estimate" not in d:
                    continue
                kw = dict(lw=1.2, color=EXCITATION_COLOURS[label], label=f"{label}, {direction}")
                ax.plot(d["speed"][:], valid(d, "error_estimate") * 100, style, **kw)
                steps_ax = steps_ax or ax.twinx()
                steps_ax.plot(d["speed"][:], d["steps_per_cycle"][:], ":", lw=1,
                              color=EXCITATION_COLOURS[label])
        if steps_ax is None:
            ax.text(0.5, 0.5, "CVODE: error held by its tolerances", ha="center",
                    transform=ax.transAxes)
        else:
            ax.set_yscale("log")
            steps_ax.set_yscale("log")
            steps_ax.set_ylabel("Newmark steps per mesh cycle (dotted)")
        ax.set_xlabel("pinion speed [rpm]")
        ax.set_ylabel("estimated DTE error [% of its RMS]")
        ax.set_title("integrator: Newmark's estimated error (dynamics/newmark_error.h)")
    save(fig, os.path.join(out_dir, "dynamics.png"))
    plot_dynamics_spectra(dyn, out_dir)
    plot_dynamics_time(dyn, out_dir)


def plot_dynamics_spectra(dyn, out_dir):
    """Per pair and excitation: the DTE amplitude of mesh orders 1-4 against the speed (up sweep;
    one curve an order, logarithmic scale: resonances are the peaks where an order meets a
    mode), and the largest of the orders between them (grey: measured flanks repeat over several
    mesh cycles and excite those too)."""
    rows = [(name, label) for name in dyn for label in ("theoretical", "measured")
            if label in dyn[name]]
    fig, axes = plt.subplots(len(rows), 1, figsize=(12, 4.2 * len(rows)), squeeze=False)
    for ax, (name, label) in zip(axes[:, 0], rows):
        d = dyn[name][label]["up"]
        rpm, order = d["speed"][:], d["spectrum_order"][:]
        a = d["dte_spectrum"][:] * 1e6
        a[diverged(d)] = np.nan  # no results there: gaps
        whole = np.abs(order - np.round(order)) < 1e-6
        for k in (1, 2, 3, 4):
            j = np.nonzero(whole & (np.round(order) == k))[0]
            if j.size:
                ax.plot(rpm, a[:, j[0]], lw=1.4, label=f"order {k}")
        between = np.nonzero(~whole & (order > 0))[0]
        if between.size:
            ax.plot(rpm, np.nanmax(a[:, between], axis=1), color="0.6", lw=0.9,
                    label="largest order between")
        ax.set_yscale("log")
        top = np.nanmax(a[:, order > 0]) if np.isfinite(a[:, order > 0]).any() else 1.0
        ax.set_ylim(top * 1e-4, top * 2)  # below 1e-4 of the largest line: round-off, not signal
        ax.set_xlabel("pinion speed [rpm]")
        ax.set_ylabel("DTE amplitude [um]")
        cycles = dyn[name][label]["excitation_cycles"][()]
        ax.set_title(f"{name}, {label} flanks: DTE by mesh order, swept up (excitation period "
                     f"{cycles:.0f} mesh cycle{'s' if cycles > 1 else ''})")
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "dynamics_spectra.png"))


def plot_dynamics_time(dyn, out_dir):
    """Per pair: the recorded DTE (and the excitation E_t, dotted; both about their means) and
    the mesh force over the first 9 recorded mesh cycles at the speeds kept (the up sweep),
    theoretical and measured flanks together."""
    pairs = [n for n in dyn if any("time_series" in dyn[n][l]["up"]
                                   for l in ("theoretical", "measured") if l in dyn[n])]
    if not pairs:
        return
    speeds = {n: sorted({dyn[n][l]["up"]["time_series"][k]["speed"][()]
                         for l in ("theoretical", "measured") if l in dyn[n]
                         for k in dyn[n][l]["up"].get("time_series", {})}) for n in pairs}
    rows = [(n, v) for n in pairs for v in speeds[n]]
    fig, axes = plt.subplots(len(rows), 2, figsize=(12, 3.2 * len(rows)), squeeze=False)
    for (ax_d, ax_f), (name, rpm) in zip(axes, rows):
        z = dyn[name]["pinion_teeth"][()]
        for label in ("theoretical", "measured"):
            if label not in dyn[name] or "time_series" not in dyn[name][label]["up"]:
                continue
            for s in dyn[name][label]["up"]["time_series"].values():
                if s["speed"][()] != rpm:
                    continue
                cycles = s["time"][:] * rpm / 60 * z
                k = cycles <= 9
                dte, et = s["dte"][:][k], s["transmission_error"][:][k]
                c = EXCITATION_COLOURS[label]
                ax_d.plot(cycles[k], (dte - dte.mean()) * 1e6, color=c, lw=1,
                          label=f"{label}: delta_D")
                ax_d.plot(cycles[k], (et - et.mean()) * 1e6, ":", color=c, lw=1,
                          label=f"{label}: E_t")
                ax_f.plot(cycles[k], s["mesh_force"][:][k], color=c, lw=1, label=label)
        ax_d.set_xlabel("mesh cycles")
        ax_d.set_ylabel("about the mean [um]")
        ax_d.set_title(f"{name} at {rpm:.0f} rpm: dynamic TE and its excitation")
        ax_d.legend(fontsize=7, ncol=2)
        ax_f.set_xlabel("mesh cycles")
        ax_f.set_ylabel("F_m [N]")
        ax_f.set_title(f"{name} at {rpm:.0f} rpm: mesh force")
        ax_f.legend(fontsize=7)
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "dynamics_time.png"))


TRAIN_COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]


def names_of(group, attribute):
    return [s.strip() for s in group.attrs[attribute].split(",")]


def time_axis(t):
    """Times in ms for runs up to a second, else in s."""
    return (t * 1e3, "time [ms]") if t[-1] <= 1.0 else (t, "time [s]")


def plot_trains(trains, out_dir):
    for name in trains:
        plot_train(name, trains[name], out_dir)
    plot_train_compare(trains, out_dir)
    plot_train_spectrograms(trains, out_dir)


def plot_train(name, g, out_dir):
    """One gear train: per mesh S(t) with the backlash band (the seeds' Figures 3, 6, 7), the
    normal force (drive +, coast -; crosses: every contact's peak as the integrator located it,
    on a symmetric log scale where they stand far above the samples), the impacts counted over
    time (rattle shows as a climbing count), the spectrum of the force magnitude over the
    analysis interval with the GMF harmonics (red: a line found there, grey: none) and the
    sidebands found (triangles) where the train runs steadily; the body speeds and the energy
    balance."""
    meshes = names_of(g, "meshes")
    bodies = names_of(g, "bodies")
    t, t_label = time_axis(g["time"][:])
    n = 2 * len(meshes) + 2  # two rows of two panels a mesh; speeds and energy; the numbers
    fig, grid = plt.subplots(n, 2, figsize=(12, 3.7 * (n - 1) + 2.2), squeeze=False,
                             layout="constrained", height_ratios=[1] * (n - 1) + [0.55])
    for i, mesh in enumerate(meshes):
        row = grid[2 * i:2 * i + 2].ravel()
        m = g["meshes"][mesh]
        half = m["band_half_width"][()]
        row[0].plot(t, m["relative"][:] * 1e6, lw=0.8)
        for s, label in ((1, "drive contact"), (-1, "coast contact")):
            row[0].axhline(s * half * 1e6, color="k", ls="--", lw=0.8)
            row[0].text(t[-1], s * half * 1e6, " " + label, fontsize=7, va="center")
        row[0].set_xlabel(t_label)
        row[0].set_ylabel("S [um]")
        row[0].set_title(f"{name} {mesh}: S along the line of action\n(band +-{half * 1e6:.1f} um)",
                         fontsize=9)
        scale = t[-1] / g["time"][-1] if g["time"][-1] > 0 else 1.0  # seconds to the axis' unit
        force = m["force"][:]
        filtered = "anti_alias" in g and g["anti_alias"][()] > 0
        row[1].plot(t, force, lw=0.7, color="tab:red",
                    label="samples, low-passed without aliasing (ring about short impacts)"
                    if filtered else "samples (point values)")
        if "contacts" in m and m["contacts"]["peak"].size:
            # the located peak of every contact (the integrator's, not the samples')
            c = m["contacts"]
            peaks = c["side"][:] * c["peak"][:]
            row[1].plot(c["peak_time"][:] * scale, peaks, "x", color="k", ms=4,
                        label="located contact peaks")
            largest = max(np.abs(force).max(), 1e-300)
            if np.abs(peaks).max() > 20 * largest:  # spikes far above the samples: both visible
                row[1].set_yscale("symlog", linthresh=largest)
            legend_below(row[1], ncol=1)
        first = m["first_contact"][()]
        row[1].set_xlabel(t_label)
        row[1].set_ylabel("normal force [N]")
        row[1].set_title(f"force (drive +, coast -): {m['impacts'][()]:.0f} impacts "
                         f"({m['drive_impacts'][()]:.0f} drive, {m['coast_impacts'][()]:.0f} "
                         f"coast)\nfirst {first * 1e3:.3f} ms, peak {m['max_force'][()]:.0f} N",
                         fontsize=9)
        touches = m["contacts"]["touch"][:] if "contacts" in m else np.zeros(0)
        sides = m["contacts"]["side"][:] if "contacts" in m else np.zeros(0)
        for sign, label, colour in ((1, "drive", "tab:red"), (-1, "coast", "tab:blue")):
            at = np.sort(touches[(sides == sign) & (touches > 0)]) * scale
            row[2].step(np.concatenate(([0.0], at, [t[-1]])),
                        np.concatenate(([0], np.arange(1, at.size + 1), [at.size])),
                        where="post", color=colour, label=f"{label} flanks: {at.size}")
        row[2].set_xlabel(t_label)
        row[2].set_ylabel("impacts so far")
        row[2].set_title(f"{name} {mesh}: impacts over time\n(a contact at the start is none)",
                         fontsize=9)
        row[2].legend(fontsize=7, loc="upper left")
        if "spectrum" not in m:
            row[3].axis("off")
            row[3].text(0.02, 0.5, "no force spectrum: the speed does\nnot hold over the analysis "
                        "interval\n(a run-up, coast-down or transient);\nsee the spectrogram",
                        transform=row[3].transAxes, fontsize=10, va="center")
            continue
        row = row[1:]  # the spectrum in the last column
        sp = m["spectrum"]
        a = sp["amplitude"][:]
        f = np.arange(a.size) * sp["resolution"][()]
        gmf = m["gmf"][()]
        lines = sp["lines"]
        harmonics = lines["harmonic"][:]
        top = min(f[-1], (harmonics.max() + 0.6) * gmf) if harmonics.size else f[-1]
        k = f <= top
        row[2].plot(f[k], a[k], lw=0.7, color="tab:blue")
        expected, found = lines["expected"][:], lines["found"][:]
        freq, amp, side = lines["frequency"][:], lines["amplitude"][:], lines["sideband"][:]
        for e, ok, h, s in zip(expected, found, harmonics, side):
            if h > 0 and s == 0:
                row[2].axvline(e, color="tab:red" if ok else "0.6", ls="-" if ok else ":",
                               lw=0.8)
        sb = (side != 0) & (found == 1) & (harmonics > 0)
        row[2].plot(freq[sb], amp[sb], "v", color="tab:green", ms=4, label="sidebands found")
        shaft = (harmonics == 0) & (found == 1)
        row[2].plot(freq[shaft], amp[shaft], "s", color="tab:purple", ms=4,
                    label="shaft orders found")
        row[2].set_xlim(0, top)
        row[2].set_xlabel("frequency [Hz]")
        row[2].set_ylabel("amplitude of |force| [N]")
        row[2].set_title(f"force spectrum from {sp['start'][()]:.3g} s: GMF {gmf:.2f} Hz\n"
                         "(harmonics red: found, grey: not)", fontsize=9)
        row[2].legend(fontsize=7, loc="upper right")
    last = list(grid[-2]) + list(grid[-1])
    speed = g["speed"][:]
    for i, body in enumerate(bodies):
        last[0].plot(t, speed[i], lw=0.9, label=body)
    last[0].set_xlabel(t_label)
    last[0].set_ylabel("speed [rad/s]")
    last[0].set_title(f"{name}: body speeds")
    # (placed, not "best": that scans every point of the long time series, seconds a picture)
    last[0].legend(fontsize=7, loc="center right")
    work, kin, pot, dis = (g[k][:] for k in ("work", "kinetic", "potential", "dissipated"))
    last[1].plot(t, work, label="work of the torques")
    last[1].plot(t, kin - kin[0], label="kinetic energy change")
    last[1].plot(t, pot - pot[0], label="stored (contacts)")
    last[1].plot(t, dis, label="dissipated")
    last[1].plot(t, work - (kin - kin[0]) - (pot - pot[0]) - dis, "k:", label="balance residual")
    last[1].set_xlabel(t_label)
    last[1].set_ylabel("energy [J]")
    last[1].set_title(f"energy balance (error {g['energy_error'][()]:.2g} of the largest term)")
    last[1].legend(fontsize=7, loc="upper left")
    kin_f = g["kinematics"]
    method = g.attrs.get("integrator", "")
    method = method.decode() if isinstance(method, bytes) else str(method)
    method = f" ({method.upper() if method == 'bdf' else method.capitalize()})" if method else ""
    text = [f"{g['steps'][()]:.0f} CVODE{method} steps, {g['events'][()]:.0f} events, "
            f"{g['seconds'][()]:.2f} s", "kinematic frequencies [Hz]:"]
    for body, fr in zip(bodies, kin_f["shaft_frequency"][:]):
        text.append(f"  {body}: {fr:.4f}")
    for mesh, fr in zip(meshes, kin_f["mesh_frequency"][:]):
        text.append(f"  GMF {mesh}: {fr:.3f}")
    for body, j in zip(bodies, g["inertia"][:]):
        text.append(f"  J {body}: {j:.4g} kg m^2")
    last[2].axis("off")
    last[3].axis("off")
    half = (len(text) + 1) // 2  # the numbers in two columns under the speeds and the energy
    for ax, part in ((last[2], text[:half]), (last[3], text[half:])):
        ax.text(0.02, 0.98, "\n".join(part), va="top", family="monospace", fontsize=9,
                transform=ax.transAxes)
    save(fig, os.path.join(out_dir, f"train_{name}.png"))


def plot_train_compare(trains, out_dir):
    """The trains of the scene over each other (perfect against defective gears): S and the
    force of every mesh and the speed of every body (the seeds' comparisons). Trains whose names
    end in the same _<suffix> (e.g. perfect_light, chipped_light) share a column; the others
    share the first. The perfect train is drawn first and in grey, the others over it, the
    largest force swing first; a speed that holds to round-off is drawn flat, not magnified
    into noise."""
    groups = {}
    for name in trains:
        groups.setdefault(name.split("_", 1)[1] if "_" in name else "", []).append(name)
    first = trains[next(iter(trains))]
    meshes, bodies = names_of(first, "meshes"), names_of(first, "bodies")
    rows = len(meshes) * 2 + len(bodies)
    fig, axes = plt.subplots(rows, len(groups), figsize=(12, 2.3 * rows + 0.8), squeeze=False,
                             layout="constrained", sharex="col")
    for column, (suffix, names) in zip(axes.T, groups.items()):
        # the reference first, then the others from the largest force swing to the smallest:
        # no defect's curve hides under a larger one
        def swing(n):
            return np.ptp(trains[n]["meshes"][meshes[0]]["force"][:]) if meshes[0] in \
                trains[n]["meshes"] else 0.0
        names = sorted(names, key=lambda n: (not n.startswith("perfect"), -swing(n)))
        for n, name in enumerate(names):
            g = trains[name]
            reference = name.startswith("perfect")
            c = "0.55" if reference else TRAIN_COLOURS[n % len(TRAIN_COLOURS)]
            kw = dict(lw=1.4 if reference else 0.8, color=c, label=name)
            t, t_label = time_axis(g["time"][:])
            for i, mesh in enumerate(meshes):
                if mesh not in g["meshes"]:
                    continue
                m = g["meshes"][mesh]
                column[2 * i].plot(t, m["relative"][:] * 1e6, **kw)
                if n == 0:
                    half = m["band_half_width"][()] * 1e6
                    for s in (1, -1):
                        column[2 * i].axhline(s * half, color="k", ls="--", lw=0.7)
                column[2 * i].set_ylabel(f"S {mesh} [um]")
                column[2 * i + 1].plot(t, m["force"][:], **kw)
                column[2 * i + 1].set_ylabel(f"force {mesh} [N]")
            for j, body in enumerate(names_of(g, "bodies")):
                if j < len(bodies):
                    column[2 * len(meshes) + j].plot(t, g["speed"][j], **kw)
                    column[2 * len(meshes) + j].set_ylabel(f"{body} [rad/s]")
        for ax in column:
            ax.ticklabel_format(axis="y", useOffset=False)
            lo, hi = ax.get_ylim()
            middle = 0.5 * (lo + hi)
            if hi - lo < 1e-6 * abs(middle):  # a held speed: round-off, not signal
                ax.set_ylim(middle * (1 - 1e-4), middle * (1 + 1e-4))
        column[-1].set_xlabel(t_label)
        column[0].set_title("S per mesh (dashed: the backlash band), forces, speeds",
                            fontsize=10)
        column[0].legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.12),
                         ncol=len(names), frameon=False)
    save(fig, os.path.join(out_dir, "train_compare.png"))


def plot_train_spectrograms(trains, out_dir):
    """Per train: the spectrogram of the first mesh's force magnitude (time on x, frequency on y,
    colour: log10 amplitude), with its GMF from the kinematics at the end of the run."""
    names = [n for n in trains if "spectrogram" in trains[n]]
    if not names:
        return
    fig, axes = plt.subplots(len(names), 1, figsize=(12, 3.6 * len(names)), squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        s = trains[name]["spectrogram"]
        t, f, a = s["time"][:], s["frequency"][:], s["amplitude"][:]
        top = a.max()
        image = ax.pcolormesh(t, f, np.log10(np.maximum(a.T, top * 1e-4)), shading="nearest",
                              cmap="viridis")
        fig.colorbar(image, ax=ax, label="log10 amplitude [N]")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("frequency [Hz]")
        df = f[1] - f[0] if f.size > 1 else 0.0  # the window's resolution: 1 / its length
        ax.set_title(f"{name}: spectrogram of the {s.attrs['mesh']} force magnitude "
                     f"(windows of {1e3 / df if df else 0:.0f} ms: {df:.0f} Hz resolution, "
                     f"{(t[1] - t[0]) * 1e3 if t.size > 1 else 0:.0f} ms steps)")
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "train_spectrogram.png"))


def plot_deflection(dyn, ste, flanks, out_dir):
    """System deflection: e_0 and the contact path on the gear flank as assembled and in the
    position the static load deflects the pair to, per pair and excitation."""
    rows = [(name, label, dyn[name][label]["deflection"]) for name in dyn
            for label in ("theoretical", "measured")
            if label in dyn[name] and "deflection" in dyn[name][label]]
    if not rows:
        return
    fig, axes = plt.subplots(len(rows), 2, figsize=(13, 4.2 * len(rows)), squeeze=False)
    for (left, right), (name, label, d) in zip(axes, rows):
        aligned = ste[name] if label == "theoretical" else ste[name]["measured"]
        moved = d["tca"]
        z1 = int(flanks[name]["pinion"]["number_of_teeth"][()])
        shift = resolved(d["transmission_error_mean_shift"][()], ANGLE_FLOOR) * 1e6
        for g, what in ((aligned, "as assembled"), (moved, "deflected")):
            cycles = g["pinion_angle"][:] * z1 / (2 * np.pi)
            te = g["transmission_error"][:] * 1e6
            left.plot(cycles, te - te.mean(), ".-", ms=3, lw=0.8,
                      label=f"{what}: p-p {resolved(g['peak_to_peak'][()], ANGLE_FLOOR) * 1e6:.3g} urad")
        left.set_xlabel("pinion angle [mesh cycles]")
        left.set_ylabel("e_0 - mean [urad]")
        left.set_title(f"{name} ({label}): e_0, mean moved by {shift:.4g} urad", fontsize=10)
        left.legend(fontsize=8)
        left.grid(alpha=0.3)
        for g, what, style in ((aligned, "as assembled", "k."), (moved, "deflected", "r.")):
            lead = np.maximum(g["leading"][:], 0)
            points = g["contact_in_gear_frame"][:][np.arange(len(lead)), lead, 0]
            face, profile = gear_flank_coordinates(flanks, name, points)
            right.plot(face, profile, style, ms=3, label=what)
        def um(key):
            return f"{resolved(d[key][()], LENGTH_FLOOR) * 1e6:+.3g} um"

        def mrad(key):
            return f"{resolved(d[key][()], ANGLE_FLOOR) * 1e3:+.3g} mrad"
        if "centre_distance" in ste[name]:
            text = (f"a {um('centre_distance_error')}, offset {um('offset')}, crossing "
                    f"{mrad('crossing_angle')}, inclination {mrad('intersecting_angle')}")
        else:
            text = (f"dE {um('offset')}, dP {um('pinion_axial_shift')}, dG "
                    f"{um('gear_axial_shift')}, dgamma {mrad('intersecting_angle')}")
        right.set_title(f"contact path on the gear flank\ndeflection: {text}", fontsize=9)
        right.set_xlabel("face [mm]" if not is_bevel(flanks[name])
                         else "face: cone distance - A_m [mm] (toe to heel)")
        right.set_ylabel("gear roll length L [mm]" if not is_bevel(flanks[name])
                         else "height above the pitch cone [mm]")
        half_b = flanks[name]["gear"]["face_width"][()] * 500  # the flank's extent, not round-off
        right.set_xlim(-half_b * 1.05, half_b * 1.05)
        right.legend(fontsize=8)
        right.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, os.path.join(out_dir, "deflection.png"))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    path = sys.argv[1]
    out_dir = os.path.dirname(os.path.abspath(path))
    with h5py.File(path, "r") as f:
        if "flanks" in f:
            plot_profiles(f["flanks"], out_dir)
            plot_topography(f["flanks"], out_dir)
        if "measured" in f:
            plot_measured(f["measured"], out_dir)
        if "ste" in f:
            plot_ste(f["ste"], f["flanks"], out_dir)
            plot_hunting(f["ste"], f["flanks"], out_dir)
            plot_contact_pattern(f["ste"], f["flanks"], out_dir)
            write_harmonic_table(f["ste"], out_dir)
        if "stiffness" in f:
            plot_stiffness(f["stiffness"], f["flanks"], out_dir)
        if "dynamics" in f:
            plot_dynamics(f["dynamics"], f["flanks"], out_dir)
            plot_deflection(f["dynamics"], f["ste"], f["flanks"], out_dir)
        if "train" in f:
            plot_trains(f["train"], out_dir)
        if "study" in f:
            from plot_study import plot_study  # imports save from here: not at the top
            plot_study(f["study"], out_dir)


if __name__ == "__main__":
    main()

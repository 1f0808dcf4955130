#!/usr/bin/python3
"""Pictures of the study stage: the micro-geometry design map ("Harris map") of a gear pair, the
tolerance Monte Carlo and the misalignment (V-H) check.

usage: plot_study.py out/<scene>/results.h5

  study_<pair>.png  per pair of /study: the loaded TE's peak-to-peak over the torque for every
                    amount of the grid's first modification (curves and filled contours), the
                    mesh stiffness of a few variants and the loaded TE over the mesh cycle of the
                    unmodified and the best variant at the design torque
  tolerances_<pair>.png  the tolerance Monte Carlo (plot_tolerances)
  vh_<pair>.png     the misalignment (V-H) check: the contact pattern per grid point and the
                    V-H chart (plot_misalignments)

plot_results.py draws them too (its main() calls plot_study when results.h5 has /study); the
helpers below (variant labels, the TE as a length) are the report's as well (report.py).
"""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_results import legend_below, save  # noqa: E402  (the same atomic writes)

KIND = "microgeometry map"
TOLERANCES = "tolerances"
MISALIGNMENTS = "misalignments"
EDGE_ALARM = 0.1  # a tenth of the load on a flank edge: the misalignment check's alarm
INVALID = "the fixed contact zone was too narrow for some variants: their results are not valid"


def text(value):
    """An HDF5 string (bytes or str) as str."""
    return value.decode() if isinstance(value, bytes) else str(value)


def parameters(g):
    """The grid's axis names, first axis first (the stage writes them comma-separated)."""
    names = [text(n) for n in np.atleast_1d(g.attrs.get("parameters", []))]
    return [p.strip() for n in names for p in n.split(",") if p.strip()]


def is_length(name):
    return name.endswith("_length")


def unit(name):
    """(scale from metres, label) of a parameter: lengths in mm, amounts in um."""
    return (1e3, "mm") if is_length(name) else (1e6, "um")


def pretty(name):
    return name.replace("_", " ")


def value_text(name, value, micro="um"):
    """A parameter's value in its display unit: 'tip relief 15 um', 'tip relief length 2.5 mm'."""
    scale, label = unit(name)
    label = micro if label == "um" else label
    return f"{pretty(name)} {value * scale:.4g} {label}"


def variant_label(g, v, micro="um"):
    """A variant by its parameter values; 'unmodified' for the one without modifications."""
    row = g["grid"][int(v)]
    if unmodified_variant(g) == int(v):
        return "unmodified"
    return ", ".join(value_text(n, x, micro) for n, x in zip(parameters(g), row))


def te_length(g, rad):
    """A TE in pinion radians as a displacement at the pitch circle [um]."""
    return np.asarray(rad, dtype=float) * scalar(g, "pitch_radius") * 1e6


def scalar(g, name, default=None):
    """A scalar of the study group: an attribute (design_torque, pitch_radius) or a dataset
    (the optional classical_relief_iso, mesh_deflection_design, best_relief_design)."""
    if name in g:
        return float(g[name][()])
    if name in g.attrs:
        return float(g.attrs[name])
    return default


def design_index(g):
    """(index of the torque nearest the design torque, design torque): with no design torque
    (0) the largest torque's."""
    torques = g["torques"][()]
    design = scalar(g, "design_torque", 0.0)
    if design > 0:
        return int(np.argmin(np.abs(torques - design))), design
    return int(np.argmax(torques)), 0.0


def unmodified_variant(g):
    """The variant without modifications on either member (the stage's `unmodified_variant`,
    which also knows the modifications outside the grid; else every parameter 0), else None."""
    if "unmodified_variant" in g:
        v = int(g["unmodified_variant"][()])
        return v if v >= 0 else None
    zero = np.nonzero(~np.any(g["grid"][()] != 0, axis=1))[0]
    return int(zero[0]) if zero.size else None


def first_axis_slice(g):
    """The variants along the first axis with every other axis at its first value: (indices,
    the first axis' values [m], the other axes' text for titles)."""
    shape = [int(n) for n in np.atleast_1d(g["shape"][()])]
    names = parameters(g)
    stride = int(np.prod(shape[1:])) if len(shape) > 1 else 1
    index = np.arange(shape[0]) * stride
    others = ", ".join(value_text(n, g["axes"][n][0]) for n in names[1:])
    return index, g["axes"][names[0]][()], others


def parabola_minimum(x, y):
    """The abscissa of the vertex of the parabola through three points (x, y); None where
    they are on a line or the vertex is a maximum."""
    a = np.polyfit(x, y, 2)
    if a[0] <= 0:
        return None
    return -a[1] / (2 * a[0])


def best_path(pp, valid, index, values):
    """The first axis' value minimising TE p-p per torque along the slice: the grid's best,
    refined by the parabola through it and its two valid neighbours where it has both."""
    out = np.full(pp.shape[1], np.nan)
    for m in range(pp.shape[1]):
        ok = valid[index, m]
        if not ok.any():
            continue
        y = np.where(ok, pp[index, m], np.inf)
        k = int(np.argmin(y))
        out[m] = values[k]
        if 0 < k < len(values) - 1 and ok[k - 1] and ok[k + 1]:
            v = parabola_minimum(values[k - 1:k + 2], y[k - 1:k + 2])
            if v is not None and values[k - 1] <= v <= values[k + 1]:
                out[m] = v
    return out


def plot_study(study, out_dir):
    """Per pair, the micro-geometry design map ("Harris map"): top left, the loaded TE's
    peak-to-peak (at the pitch circle) over the torque, a curve per amount of the grid's first
    modification (other modifications at their first value), the lowest of all variants as a
    black line with stars; top right, the same as filled contours over (amount, torque) with the
    best amount per torque (dotted), the design torque (dashed) and on it the classical relief
    F / (b c_gamma) of ISO 6336-1, the unmodified pair's mesh deflection and the interpolated best
    relief; bottom left, the mean mesh stiffness (band: its range over the mesh cycle) of the
    unmodified variant, the best at the design torque and the largest; bottom right, their loaded
    TE over the mesh cycle at the design torque (dashed: unloaded). Results whose contact reached
    the edge of the fixed cell zone are not valid: crossed out (red x), hatched in the contours."""
    for name in study:
        g = study[name]
        if isinstance(g, h5py.Group) and text(g.attrs.get("kind", "")) == KIND:
            plot_study_pair(name, g, out_dir)
        elif isinstance(g, h5py.Group) and text(g.attrs.get("kind", "")) == TOLERANCES:
            plot_tolerances(name, g, out_dir)
        elif isinstance(g, h5py.Group) and text(g.attrs.get("kind", "")) == MISALIGNMENTS:
            plot_misalignments(name, g, out_dir)


def misalignment_text(name, value):
    """A misalignment by its value in the display unit: 'offset +0.2 mm', 'intersecting angle
    -1 mrad'."""
    if "angle" in name:
        return f"{pretty(name)} {value * 1e3:+.3g} mrad"
    return f"{pretty(name)} {value * 1e3:+.3g} mm"


def point_label(g, k):
    """Grid point k of a misalignment check by its values ('nominal' where all are 0)."""
    row = np.atleast_1d(g["grid"][int(k)])
    if not np.any(row):
        return "nominal"
    return ", ".join(misalignment_text(n, x) for n, x in zip(parameters(g), row))


def panel_layout(g):
    """(rows, columns) of a misalignment check's panels: the last axis across, the others
    (first slowest) down."""
    shape = [int(n) for n in np.atleast_1d(g["shape"][()])] or [1]
    return int(np.prod(shape[:-1])), shape[-1]


def plot_misalignments(name, g, out_dir):
    """vh_<name>.png of a misalignment (V-H) check: one panel per grid point (the last axis
    across, the others down), each the gear flank (profile up, face toe to heel across) with
    the loaded contact pattern at the lightest torque (the largest pressure over the mesh
    cycle: a marking-compound print; the colours stop at the 98th percentile, edge-contact
    peaks beyond it are clipped), the outline of the pattern at the design torque (else the
    largest; cyan), the unloaded contact path (black dots) and the pattern's centre at the
    design torque (cyan cross), titled with e_0, e_L peak-to-peak and the edge-load share (red
    above a tenth of the load); on
    the right the V-H chart proper: every grid point's pattern centre at the design torque on
    one flank outline, joined along each axis, and e_0, e_L peak-to-peak per grid point."""
    m, torque = design_index(g)
    light = int(np.argmin(g["torques"][()]))
    rows, cols = panel_layout(g)
    pattern = g["pattern"][:, light] / 1e6  # MPa
    loaded = g["pattern"][:, m] > 0
    pu, pf = g["pattern_profile_range"][()] * 1e3, g["pattern_face_range"][()] * 1e3
    path = g["contact_path"][()] * 1e3
    centre = g["pattern_centre"][:, m] * 1e3
    e0 = te_length(g, g["unloaded_te_peak_to_peak"][()])
    eL = te_length(g, g["te_peak_to_peak"][:, m])
    edge = g["max_edge_share"][:, m]
    lit = pattern[pattern > 0]
    vmax = float(np.percentile(lit, 98)) if lit.size else 1.0
    nu, nf = pattern.shape[1:]
    fu = pu[0] + (np.arange(nu) + 0.5) * (pu[1] - pu[0]) / nu
    ff = pf[0] + (np.arange(nf) + 0.5) * (pf[1] - pf[0]) / nf
    fig = plt.figure(figsize=(3.3 * cols + 6, 2.4 * rows + 1.4))
    grid = fig.add_gridspec(rows, cols + 2, width_ratios=[1] * cols + [0.06, 1.6])
    image = None
    for k in range(rows * cols):
        ax = fig.add_subplot(grid[k // cols, k % cols])
        image = ax.imshow(pattern[k], origin="lower", aspect="auto", cmap="magma_r", vmin=0,
                          vmax=vmax, extent=(pf[0], pf[1], pu[0], pu[1]))
        if loaded[k].any() and not loaded[k].all():
            ax.contour(ff, fu, loaded[k].astype(float), levels=[0.5], colors="tab:cyan",
                       linewidths=1)
        ax.plot(path[k, :, 1], path[k, :, 0], "k.", ms=1.5)
        ax.plot(*centre[k, ::-1], "x", color="tab:cyan", ms=8, mew=2)
        ax.set_xlim(pf), ax.set_ylim(pu)
        ax.set_title(f"{point_label(g, k)}\ne0 {e0[k]:.2f} um; at {g['torques'][m]:.4g} N m: "
                     f"eL {eL[k]:.2f} um, edge {edge[k]:.0%}", fontsize=8,
                     color="firebrick" if edge[k] > EDGE_ALARM else "k")
        ax.tick_params(labelsize=7)
        if k // cols == rows - 1:
            ax.set_xlabel("face [mm] (toe to heel)", fontsize=8)
        if k % cols == 0:
            ax.set_ylabel("profile [mm] (root to tip)", fontsize=8)
    bar = fig.colorbar(image, cax=fig.add_subplot(grid[:, cols]), extend="max")
    bar.set_label(f"largest pressure over the mesh cycle at {g['torques'][light]:.4g} N m [MPa]")
    top = max(1, (rows + 1) // 2)
    chart = fig.add_subplot(grid[:top, cols + 1])
    chart.add_patch(plt.Rectangle((pf[0], pu[0]), pf[1] - pf[0], pu[1] - pu[0], fill=False,
                                  color="k", lw=0.8))
    shape = [int(n) for n in np.atleast_1d(g["shape"][()])] or [1]
    index = np.arange(int(np.prod(shape))).reshape(shape)
    for axis, axis_name in enumerate(parameters(g)):
        for j, line in enumerate(np.moveaxis(index, axis, -1).reshape(-1, shape[axis])):
            chart.plot(centre[line, 1], centre[line, 0], "-", lw=0.8, color=f"C{axis}",
                       label=f"along {pretty(axis_name)}" if j == 0 else None)
    chart.plot(centre[:, 1], centre[:, 0], "k.", ms=4)
    nominal = [k for k in range(len(centre)) if point_label(g, k) == "nominal"]
    if nominal:
        chart.plot(*centre[nominal[0], ::-1], "o", mfc="none", mec="k", ms=9, label="nominal")
    chart.set_xlim(pf), chart.set_ylim(pu)
    chart.set_title(f"V-H chart: pattern centres at {g['torques'][m]:.4g} N m", fontsize=9)
    chart.set_xlabel("face [mm] (toe to heel)", fontsize=8)
    chart.set_ylabel("profile [mm]", fontsize=8)
    chart.legend(fontsize=7, loc="best")
    if rows > 1:
        bars = fig.add_subplot(grid[top:, cols + 1])
        x = np.arange(len(e0))
        bars.bar(x - 0.2, e0, 0.4, label="e0 p-p (unloaded)", color="tab:gray")
        bars.bar(x + 0.2, eL, 0.4, label=f"eL p-p at {g['torques'][m]:.4g} N m",
                 color="tab:blue")
        bars.set_xticks(x)
        bars.set_xlabel("grid point (the panels in reading order)", fontsize=8)
        bars.set_ylabel("TE peak-to-peak at the pitch cone [um]", fontsize=8)
        bars.legend(fontsize=7)
    fig.suptitle(f"{name}: misalignment (V-H) check - contact pattern on the gear flank at "
                 f"{g['torques'][light]:.4g} N m, cyan: outline and centre at "
                 f"{g['torques'][m]:.4g} N m" + (" (design torque)" if torque > 0 else ""))
    fig.tight_layout()
    save(fig, os.path.join(out_dir, f"vh_{name}.png"))


def feature_label(name):
    """pinion_cumulative_pitch -> "pinion F_p"."""
    member, _, what = name.partition("_")
    short = {"cumulative_pitch": "F_p", "runout": "runout e", "profile_slope_rms": "f_Hα rms",
             "profile_form_rms": "f_fα rms", "helix_slope_rms": "f_Hβ rms",
             "helix_form_rms": "f_fβ rms"}
    return f"{member} {short.get(what, what)}"


def plot_tolerances(name, g, out_dir):
    """tolerances_<name>.png of a tolerance Monte Carlo: per torque (the design torque, else the
    largest) the distribution of the samples' loaded TE peak-to-peak at the pitch circle
    (histogram and empirical CDF, the 5/50/95 % percentiles, the design without deviations);
    their K_m mean likewise; the percentiles' convergence with the sample count; and which
    deviation drives the TE peak-to-peak: standardized regression coefficients with their 95 %
    bootstrap intervals. Samples whose contact reached the edge of a fixed zone are left out of
    the histograms and counted in the title."""
    torques = g["torques"][()]
    at, design = design_index(g)
    valid = g["zone_edge"][()][:, at] == 0
    pp = te_length(g, g["te_peak_to_peak"][()][:, at])
    km = g["stiffness_mean"][()][:, at] / 1e6
    levels = g["percentile_levels"][()]
    fig, ax = plt.subplots(2, 2, figsize=(13.5, 10))
    classes = text(g.attrs.get("classes", "")).replace(",", " / ")
    fig.suptitle(f"{name}: tolerance Monte Carlo at {torques[at]:g} N m, ISO 1328-1 classes "
                 f"{classes} ({text(g.attrs.get('distribution', ''))}), {valid.sum()} samples"
                 + ("" if valid.all() else f" ({(~valid).sum()} invalid, left out)"))
    for a, x, nominal, label in ((ax[0, 0], pp, te_length(g, g["nominal/te_peak_to_peak"][at]),
                                  "loaded TE peak-to-peak [um at the pitch circle]"),
                                 (ax[0, 1], km, g["nominal/stiffness_mean"][at] / 1e6,
                                  "mean mesh stiffness K_m [N/um]")):
        x = x[valid]
        a.hist(x, bins=max(8, int(np.sqrt(x.size))), color="#9ecae1", edgecolor="#3182bd",
               density=True, label="samples")
        b = a.twinx()
        b.plot(np.sort(x), np.arange(1, x.size + 1) / x.size, color="#08519c", label="CDF")
        b.set_ylim(0, 1.02)
        b.set_ylabel("cumulative share")
        for level, style in zip(levels, (":", "--", ":")):
            v = np.percentile(x, level)
            a.axvline(v, color="#08519c", linestyle=style)
            a.annotate(f"{level:g} %: {v:.3g}", (v, a.get_ylim()[1] * 0.95), rotation=90,
                       ha="right", va="top", fontsize=8)
        a.axvline(nominal, color="#d62728", linewidth=2, label=f"design alone: {nominal:.3g}")
        a.set_xlabel(label)
        a.set_ylabel("density")
        a.legend(loc="center right", fontsize=8)
        a.grid(alpha=0.3)
    counts = g["convergence_samples"][()]
    conv = te_length(g, g["convergence/te_peak_to_peak"][()][at])
    c = ax[1, 0]
    for j, level in enumerate(levels):
        c.plot(counts, conv[:, j], marker="o", label=f"{level:g} %")
    c.set_xscale("log")
    c.set_xlabel("samples (the first n)")
    c.set_ylabel("TE peak-to-peak percentile [um]")
    c.set_title("convergence of the percentiles with the sample count")
    c.legend(fontsize=8)
    c.grid(alpha=0.3, which="both")
    names = [feature_label(n) for n in text(g.attrs.get("features", "")).split(",")]
    sens = g["sensitivity/te_peak_to_peak"]
    coef, low, high = sens["coefficient"][at], sens["low"][at], sens["high"][at]
    y = np.arange(len(names))
    d = ax[1, 1]
    d.barh(y, coef, xerr=[coef - low, high - coef], color=np.where(coef >= 0, "#fb6a4a", "#6baed6"),
           capsize=3)
    d.set_yticks(y, names, fontsize=8)
    d.invert_yaxis()
    d.axvline(0, color="k", linewidth=0.8)
    d.set_xlabel("standardized regression coefficient (95 % bootstrap interval)")
    d.set_title(f"what drives the TE peak-to-peak (linear model R² = {sens['r2'][at]:.2f})")
    d.grid(alpha=0.3, axis="x")
    fig.tight_layout()
    save(fig, os.path.join(out_dir, f"tolerances_{name}.png"))


def plot_study_pair(name, g, out_dir):
    """study_<name>.png of one micro-geometry map (plot_study says what it shows)."""
    names = parameters(g)
    first = names[0]
    scale, amount_unit = unit(first)
    torques = g["torques"][()]
    pp = te_length(g, g["te_peak_to_peak"][()])
    valid = g["zone_edge"][()] == 0
    best = np.atleast_1d(g["best_variant"][()]).astype(int)
    index, values, others = first_axis_slice(g)
    design = scalar(g, "design_torque", 0.0)
    at, _ = design_index(g)
    members = text(g.attrs.get("members", "both"))
    on = {"both": "both members", "pinion": "the pinion", "gear": "the gear"}.get(members, members)

    fig = plt.figure(figsize=(13.5, 10.5), layout="constrained")
    axes = fig.subplots(2, 2)
    plural = "s" if len(torques) > 1 else ""
    fig.suptitle(f"{name}: micro-geometry map of {', '.join(map(pretty, names))} on {on} "
                 f"({len(g['grid'])} variants, {len(torques)} torque{plural})", fontsize=13)
    sliced = f"\n(curves: {others}; black: the best of all variants)" if others else ""

    # Harris map as curves
    ax = axes[0, 0]
    # the amount's colour: viridis without its palest yellow
    cmap = ListedColormap(plt.cm.viridis(np.linspace(0, 0.9, 256)))
    norm = plt.Normalize(values.min() * scale, max(values.max(), values.min() + 1e-300) * scale)
    colours = cmap(norm(values * scale))
    for k, (v, c) in enumerate(zip(index, colours)):
        y = np.ma.masked_where(~valid[v], pp[v])
        label = f"{values[k] * scale:.4g} {amount_unit}" if len(index) <= 12 else None
        ax.plot(torques, y, "o-", color=c, ms=3.5, lw=1.2, label=label)
    bad = [(torques[m], pp[v, m]) for v in index for m in range(len(torques)) if not valid[v, m]]
    if bad:
        ax.plot(*zip(*bad), "x", color="red", ms=9, mew=2, label="zone edge: not valid")
    ok = best >= 0
    if ok.any():
        ax.plot(torques[ok], pp[best[ok], np.nonzero(ok)[0]], "*-", color="k", lw=2.2, ms=10,
                alpha=0.55, zorder=1, label="best of all variants")
    if design > 0:
        ax.axvline(design, ls="--", color="grey", lw=1.2, label=f"design {design:g} N m")
    if len(index) > 12:  # too many for the legend
        fig.colorbar(plt.cm.ScalarMappable(cmap=cmap, norm=norm), ax=ax,
                     label=f"{pretty(first)} [{amount_unit}]")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False,
              ncol=4, title=pretty(first) if len(index) <= 12 else None, title_fontsize=8)
    ax.set_xlabel("pinion torque [N m]")
    ax.set_ylabel("TE peak-to-peak [um at the pitch circle]")
    ax.set_title(f"Harris map: loaded TE peak-to-peak over the torque{sliced}", fontsize=10)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)

    # Harris map as filled contours over (amount, torque)
    ax = axes[0, 1]
    x = values * scale
    z = pp[index].T  # [M][n0]
    if len(x) >= 2 and len(torques) >= 2:
        filled = ax.contourf(x, torques, np.ma.masked_where(~valid[index].T, z),
                             levels=MaxNLocator(14).tick_values(0, z[valid[index].T].max()
                                                                if valid[index].any() else 1),
                             cmap="viridis")
        lines = ax.contour(x, torques, np.ma.masked_where(~valid[index].T, z),
                           levels=filled.levels[::2], colors="white", linewidths=0.6, alpha=0.8)
        ax.clabel(lines, fontsize=7, fmt="%.3g")
        fig.colorbar(filled, ax=ax, label="TE peak-to-peak [um at the pitch circle]")
        if not valid[index].all():
            ax.contourf(x, torques, (~valid[index].T).astype(float), levels=[0.5, 1.5],
                        colors="none", hatches=["xx"])
        xx, yy = np.meshgrid(x, torques)
        ax.plot(xx.ravel(), yy.ravel(), ".", color="k", ms=2, alpha=0.35)
        if not valid[index].all():  # (an empty unclipped line would spoil the layout)
            ax.plot(xx[~valid[index].T], yy[~valid[index].T], "x", color="red", ms=9, mew=2,
                    clip_on=False, zorder=4, label="zone edge: not valid")
        path = best_path(pp, valid, index, values)
        ax.plot(path * scale, torques, ":o", color="white", mec="k", ms=4, lw=2,
                label=f"best {pretty(first)} per torque")
        ax.set_ylabel("pinion torque [N m]")
        ax.set_xlabel(f"{pretty(first)} [{amount_unit}]")
    else:  # one torque or one amount: no area to fill, the values along the first axis
        for m, t in enumerate(torques):
            ax.plot(x, np.ma.masked_where(~valid[index, m], pp[index, m]), "o-", ms=4,
                    label=f"{t:g} N m")
            bad = ~valid[index, m]
            if bad.any():
                ax.plot(x[bad], pp[index, m][bad], "x", color="red", ms=9, mew=2,
                        label="zone edge: not valid" if m == 0 or not (~valid[index, :m]).any()
                        else None)
        ax.set_xlabel(f"{pretty(first)} [{amount_unit}]")
        ax.set_ylabel("TE peak-to-peak [um at the pitch circle]")
        ax.set_ylim(bottom=0)
    if design > 0 and len(torques) >= 2 and len(x) >= 2:
        ax.axhline(design, ls="--", color="k", lw=1.2, label=f"design torque {design:g} N m")
        if not is_length(first):
            for key, marker, what in (
                    ("classical_relief_iso", "D", "F / (b c_gamma), ISO 6336-1"),
                    ("mesh_deflection_design", "s", "F / K_m, unmodified"),
                    ("best_relief_design", "*", "best relief, interpolated")):
                v = scalar(g, key)
                if v is not None:
                    ax.plot(v * scale, design, marker, color="orange" if marker != "*" else "red",
                            mec="k", ms=12 if marker == "*" else 8, zorder=5, clip_on=False,
                            label=f"{what}: {v * scale:.3g} {amount_unit}")
    ax.set_title(f"Harris map: TE peak-to-peak over {pretty(first)} and torque"
                 + (f"\n({others})" if others else ""),
                 fontsize=10)
    legend_below(ax)

    # mesh stiffness of a few variants
    ax = axes[1, 0]
    picks = []
    for v, what in ((unmodified_variant(g), None), (best[at] if best[at] >= 0 else None,
                    f"best at {torques[at]:g} N m"), (len(g["grid"]) - 1, "largest")):
        if v is not None and all(v != p for p, _ in picks):
            picks.append((int(v), what))
    km, band = g["stiffness_mean"][()] * 1e-6, g["stiffness_range"][()] * 1e-6
    for c, (v, what) in enumerate(picks):
        label = variant_label(g, v) + (f" ({what})" if what else "")
        colour = f"C{c}"
        ax.fill_between(torques, km[v] - band[v] / 2, km[v] + band[v] / 2, color=colour, alpha=0.15)
        ax.plot(torques, np.ma.masked_where(~valid[v], km[v]), "o-", color=colour, ms=3.5,
                label=label)
        if not valid[v].all():
            ax.plot(torques[~valid[v]], km[v][~valid[v]], "x", color="red", ms=9, mew=2)
    if design > 0:
        ax.axvline(design, ls="--", color="grey", lw=1.2)
    ax.set_xlabel("pinion torque [N m]")
    ax.set_ylabel("mesh stiffness K_m [N/um]")
    ax.set_title("mean mesh stiffness over the torque (band: its range over the mesh cycle)",
                 fontsize=10)
    ax.grid(alpha=0.3)
    legend_below(ax, ncol=1)

    # loaded TE over the mesh cycle at the design torque
    ax = axes[1, 1]
    phi = g["pinion_angle"][()]
    n = len(phi)
    # the positions divide one mesh cycle evenly (the last one step short of its end)
    cycles = (phi - phi[0]) / ((phi[1] - phi[0]) * n) if n > 1 else np.zeros(n)
    for c, (v, what) in enumerate(picks[:2]):
        colour = f"C{c}"
        label = variant_label(g, v) + ("" if valid[v, at] else " - NOT VALID (zone edge)")
        loaded = te_length(g, g["loaded_te"][v, at])
        ax.plot(cycles, loaded, "o", ms=2.5, color=colour, ls="-" if valid[v, at] else ":",
                label=f"{label}: loaded, p-p {pp[v, at]:.3g} um")
        ax.plot(cycles, te_length(g, g["unloaded_te"][v]), "--", color=colour, lw=1,
                label=f"{label}: unloaded")
    ax.set_xlabel("pinion angle [mesh cycles]")
    ax.set_ylabel("TE [um at the pitch circle]")
    ax.set_title(f"TE over the mesh cycle at {torques[at]:g} N m"
                 + ((" (design torque)" if np.isclose(torques[at], design)
                     else " (the design torque's nearest)") if design > 0
                    else " (largest torque: no design torque)"),
                 fontsize=10)
    ax.grid(alpha=0.3)
    legend_below(ax, ncol=1)

    if not valid.all():
        count = int((~valid).sum())
        shown = list(index) + [v for v, _ in picks]
        drawn = ("red x, hatched" if not valid[shown].all() else
                 "none of them among the variants drawn")
        fig.supxlabel(f"WARNING: {INVALID}\n({count} of {valid.size} variant-torque results; "
                      f"{drawn})", color="firebrick", fontweight="bold", fontsize=11)
    save(fig, os.path.join(out_dir, f"study_{name}.png"))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    path = sys.argv[1]
    with h5py.File(path, "r") as f:
        if "study" in f:
            plot_study(f["study"], os.path.dirname(os.path.abspath(path)))


if __name__ == "__main__":
    main()

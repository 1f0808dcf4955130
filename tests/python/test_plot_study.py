"""The study stage's pictures and report section (scripts/plot_study.py, scripts/report.py) on a
synthetic micro-geometry map written to the schema of /study/<pair>: a Harris map whose TE
peak-to-peak is V-shaped in the relief, least where the relief equals the mesh deflection
F / (b c_gamma) at that torque, with one variant's contact at the edge of the fixed zone. Needs
neither the build nor the gearkit module: the scripts are imported by path."""
import html
import os
import re
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import SOURCE

SCRIPTS = os.path.join(SOURCE, "scripts")
sys.path.insert(0, SCRIPTS)
import plot_study  # noqa: E402
import report  # noqa: E402

PITCH_RADIUS, BASE_RADIUS = 0.05, 0.047  # m
FACE_WIDTH, C_GAMMA = 0.02, 2.0e10  # m, N/m^2 (20 N/(mm um))
SLOPE, FLOOR = 0.6, 0.3e-6  # TE p-p at the pitch circle = SLOPE |deflection - relief| + FLOOR [m]
TORQUES = np.arange(50.0, 501.0, 50.0)  # N m
RELIEFS = np.arange(0.0, 40.1e-6, 5e-6)  # m


def deflection(torque):
    """The mesh deflection F / (b c_gamma) [m] (F = T / r_b)."""
    return torque / BASE_RADIUS / (FACE_WIDTH * C_GAMMA)


def te_pp(torque, relief, crowning=0.0):
    """The fake Harris map: TE peak-to-peak at the pitch circle [m]."""
    return SLOPE * abs(deflection(torque) - relief) + FLOOR + 0.3 * crowning


def write_study(path, axes, design_torque=300.0, zone_edge=((-1, 0), (-1, 1)), pair="pair",
                torques=TORQUES):
    """A results file with /study/<pair> to the schema: axes {name: values [m]} (first axis
    slowest) at the torques [N m]; zone_edge: (variant, torque index) results flagged invalid."""
    names = list(axes)
    shape = [len(axes[n]) for n in names]
    grid = np.array(np.meshgrid(*[axes[n] for n in names], indexing="ij")).reshape(len(names), -1).T
    G, M, N, H = len(grid), len(torques), 32, 4
    phi0, step = 0.1, 2 * np.pi / 25 / N  # 25 pinion teeth: N positions over one mesh cycle
    phi = phi0 + step * np.arange(N)
    x = np.arange(N) / N

    def amount(row, name):
        return row[names.index(name)] if name in names else 0.0

    pp = np.zeros((G, M))
    loaded, unloaded = np.zeros((G, M, N)), np.zeros((G, N))
    k_mean, k_range = np.zeros((G, M)), np.zeros((G, M))
    for v, row in enumerate(grid):
        relief, crowning = amount(row, "tip_relief"), amount(row, "lead_crowning")
        # the relief's material taken off at engagement and exit, about a quarter of the cycle
        unloaded[v] = -relief * np.clip((np.abs(2 * x - 1) - 0.6) / 0.4, 0, 1) / PITCH_RADIUS
        for m, torque in enumerate(torques):
            pp[v, m] = te_pp(torque, relief, crowning)
            k_mean[v, m] = FACE_WIDTH * C_GAMMA * (1 - 0.3 * relief / (relief + deflection(torque)))
            k_range[v, m] = 0.35 * k_mean[v, m]
            mean = torque / BASE_RADIUS / k_mean[v, m]
            loaded[v, m] = (mean + pp[v, m] / 2 * np.cos(2 * np.pi * x)) / PITCH_RADIUS
    pp_rad = pp / PITCH_RADIUS
    stiffness = k_mean[:, :, None] * (1 + 0.175 * np.cos(2 * np.pi * x))
    spectrum = np.abs(np.fft.rfft(loaded - loaded.mean(axis=2, keepdims=True))) * 2 / N
    edge = np.zeros((G, M), dtype=np.int8)
    for v, m in zone_edge:
        edge[v, m] = 1
    best = np.array([int(np.argmin(np.where(edge[:, m] == 0, pp_rad[:, m], np.inf)))
                     for m in range(M)])
    with h5py.File(path, "w") as f:
        f.attrs["scene"] = "synthetic"
        g = f.create_group(f"study/{pair}")
        g.attrs["kind"] = "microgeometry map"
        g.attrs["parameters"] = ",".join(names)  # as the stage writes them
        g.attrs["members"] = "both"
        g["design_torque"] = float(design_torque)  # datasets, as the stage writes them
        g["pitch_radius"] = PITCH_RADIUS
        g["torques"] = np.asarray(torques, dtype=float)
        g["shape"] = np.array(shape, dtype=np.int64)
        for n in names:
            g[f"axes/{n}"] = axes[n]
        g["grid"] = grid
        g["te_peak_to_peak"] = pp_rad
        g["unloaded_te_peak_to_peak"] = np.ptp(unloaded, axis=1)
        g["te_harmonics"] = spectrum[:, :, 1:H + 1]
        g["stiffness_mean"] = k_mean
        g["stiffness_range"] = k_range
        g["max_pressure"] = 1.2e9 * np.sqrt(torques / np.max(torques)) * np.ones((G, 1))
        g["max_edge_share"] = np.zeros((G, M))
        g["zone_edge"] = edge
        g["pinion_angle"] = phi
        g["unloaded_te"] = unloaded
        g["loaded_te"] = loaded
        g["mesh_stiffness"] = stiffness
        g["best_variant"] = best
        if design_torque > 0:
            g["mesh_deflection_design"] = deflection(design_torque) / 0.95
            g["classical_relief_iso"] = deflection(design_torque)
            if names == ["tip_relief"]:
                values = np.array([te_pp(design_torque, r) for r in RELIEFS])
                k = int(np.clip(np.argmin(values), 1, len(values) - 2))
                a = np.polyfit(RELIEFS[k - 1:k + 2], values[k - 1:k + 2], 2)
                g["best_relief_design"] = -a[1] / (2 * a[0])
    return path


def is_png(path):
    """(width, height) from a PNG's header; fails unless the file is a PNG."""
    with open(path, "rb") as fh:
        head = fh.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", path
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def picture(folder, pair="pair"):
    path = os.path.join(folder, f"study_{pair}.png")
    assert os.path.exists(path) and not os.path.exists(path + ".tmp.png")
    width, height = is_png(path)
    assert 1000 < width < 3000 and 800 < height < 3000, (width, height)
    assert os.path.getsize(path) > 50_000  # four panels drawn, not an empty canvas
    return path


def table_rows(page, anchor="study"):
    """The cells (text) of each row of the table after the heading with the anchor."""
    start = page.index(f'id="{anchor}"')
    table = page[start:page.index("</table>", start)]
    rows = [[html.unescape(re.sub("<[^>]+>", "", c)).strip()
             for c in re.findall(r"<td>(.*?)</td>", row, re.S)]
            for row in re.findall(r"<tr[^>]*>(.*?)</tr>", table, re.S)]
    return [r for r in rows if r]  # not the header


def test_one_axis_map_picture_and_report(tmp_path):
    results = write_study(str(tmp_path / "results.h5"), {"tip_relief": RELIEFS})
    with h5py.File(results, "r") as f:
        plot_study.plot_study(f["study"], str(tmp_path))
    picture(str(tmp_path))
    # the report as the driver runs it: the picture, its caption, the table
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "report.py"), results], check=True,
                   capture_output=True)
    with open(tmp_path / "report.html", encoding="utf-8") as fh:
        page = fh.read()
    assert 'alt="study_pair.png"' in page and "Harris map" in page
    rows = table_rows(page)
    # the best variant at the design torque: the grid's relief nearest the deflection there
    design = 300.0
    relief = RELIEFS[np.argmin(np.abs(RELIEFS - deflection(design)))]
    row = next(r for r in rows if r[1] == f"{design:g} N m (design)")
    assert f"tip relief {relief * 1e6:.4g} µm" in row[2], row
    shown = float(re.search(r"TE p-p ([\d.]+) µm", row[3]).group(1))
    assert abs(shown - te_pp(design, relief) * 1e6) < 1e-3 * te_pp(design, relief) * 1e6, row
    unmodified = float(re.search(r"unmodified: ([\d.]+) µm", row[3]).group(1))
    assert abs(unmodified - te_pp(design, 0.0) * 1e6) < 1e-3 * te_pp(design, 0.0) * 1e6
    # a torque per row, and the design torque's classical and interpolated relief
    assert sum(r[1].endswith("N m") or r[1].endswith("(design)") for r in rows) >= len(TORQUES)
    classical = next(r for r in rows if r[2].startswith("classical relief"))
    assert classical[3] == f"{deflection(design) * 1e6:.4g} µm", classical
    interpolated = next(r for r in rows if r[2].startswith("best relief interpolated"))
    assert abs(float(interpolated[3].split()[0]) - deflection(design) * 1e6) < 1.0, interpolated
    # the flagged variant: the warning row, marked, and in the page's warnings
    warning = next(r for r in rows if r[1] == "WARNING")
    assert plot_study.INVALID in warning[2]
    assert "2 of 90" in warning[3] and "tip relief 40 µm at 50, 100 N m" in warning[3], warning
    assert '<tr class="alarm">' in page and 'id="warnings"' in page
    # where the zone edge was reached, that variant is not the best
    assert all("40 µm" not in r[2] for r in rows if r[1] in ("50 N m", "100 N m"))


def test_report_rows_directly(tmp_path):
    results = write_study(str(tmp_path / "results.h5"), {"tip_relief": RELIEFS},
                          zone_edge=())
    with h5py.File(results, "r") as f:
        rows, alarm = report.study_rows("pair", f["study"]["pair"])
    assert alarm == [] and all(r[1] != "<b>WARNING</b>" for r in rows)
    assert len(rows) == len(TORQUES) + 3


def test_two_axis_grid(tmp_path):
    results = write_study(str(tmp_path / "results.h5"),
                          {"tip_relief": RELIEFS[::2], "lead_crowning": np.array([0, 5e-6, 10e-6])},
                          zone_edge=((7, 9),))
    with h5py.File(results, "r") as f:
        g = f["study"]["pair"]
        index, values, others = plot_study.first_axis_slice(g)
        assert list(index) == [0, 3, 6, 9, 12] and others == "lead crowning 0 um"
        plot_study.plot_study(f["study"], str(tmp_path))
        rows, alarm = report.study_rows("pair", g)
    picture(str(tmp_path))
    assert len(alarm) == 1
    best = next(r for r in rows if r[1] == "300 N m (design)")
    assert "tip relief 20 µm, lead crowning 0 µm" in best[2], best
    assert any(r[3].startswith("– (a single relief axis only)") for r in rows)


def test_without_design_torque(tmp_path):
    results = write_study(str(tmp_path / "results.h5"), {"tip_relief": RELIEFS}, design_torque=0.0)
    with h5py.File(results, "r") as f:
        plot_study.plot_study(f["study"], str(tmp_path))
        rows, _ = report.study_rows("pair", f["study"]["pair"])
        assert plot_study.design_index(f["study"]["pair"]) == (len(TORQUES) - 1, 0.0)
    picture(str(tmp_path))
    assert not any("design" in r[1] for r in rows)


def test_one_torque_and_a_length_axis(tmp_path):
    """No area for contours (one torque): the map along the axis instead; a length in mm."""
    results = write_study(str(tmp_path / "results.h5"),
                          {"tip_relief_length": np.array([1e-3, 2e-3, 3e-3])}, zone_edge=(),
                          torques=np.array([300.0]))
    with h5py.File(results, "r") as f:
        plot_study.plot_study(f["study"], str(tmp_path))
        rows, _ = report.study_rows("pair", f["study"]["pair"])
    picture(str(tmp_path))
    assert "tip relief length 1 mm" in rows[0][2], rows[0]


@pytest.mark.parametrize("name, value, shown", [("tip_relief", 12.5e-6, "tip relief 12.5 um"),
                                                ("tip_relief_length", 2.5e-3,
                                                 "tip relief length 2.5 mm")])
def test_units(name, value, shown):
    assert plot_study.value_text(name, value) == shown


def test_plot_results_draws_the_study(tmp_path):
    results = write_study(str(tmp_path / "results.h5"), {"tip_relief": RELIEFS})
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "plot_results.py"), results],
                   check=True, capture_output=True)
    picture(str(tmp_path))


def write_tolerances(path, samples=60, pair="pair", zone_edge=(3,)):
    """A synthetic tolerance Monte Carlo to the schema of /study/<pair> (kind tolerances): the
    TE peak-to-peak of each sample = the design's + 0.8 x its pinion cumulative pitch, K_m 2 %
    below the design's; sample `zone_edge` flagged."""
    rng = np.random.default_rng(5)
    F = 12
    features = rng.uniform(0, 1, (samples, F)) * 1e-5
    design_pp = 1.5e-6 / PITCH_RADIUS  # rad
    pp = design_pp + 0.8 * features[:, 0] / PITCH_RADIUS + 1e-8 * rng.normal(size=samples)
    km = 2e8 * (0.98 + 0.005 * rng.normal(size=samples))
    edge = np.zeros((samples, 1), dtype=np.int32)
    for k in zone_edge:
        edge[k, 0] = 1
    levels = np.array([5.0, 50.0, 95.0])
    counts = np.array([25.0, 50.0, float(samples)])
    names = ["pinion_cumulative_pitch", "pinion_runout", "pinion_profile_slope_rms",
             "pinion_profile_form_rms", "pinion_helix_slope_rms", "pinion_helix_form_rms",
             "gear_cumulative_pitch", "gear_runout", "gear_profile_slope_rms",
             "gear_profile_form_rms", "gear_helix_slope_rms", "gear_helix_form_rms"]
    coef = np.zeros((1, F))
    coef[0, 0] = 0.99
    with h5py.File(path, "w") as f:
        g = f.create_group(f"study/{pair}")
        g.attrs["kind"] = "tolerances"
        g.attrs["classes"] = "6,6"
        g.attrs["distribution"] = "normal"
        g.attrs["features"] = ",".join(names)
        g["torques"] = np.array([200.0])
        g["design_torque"] = 200.0
        g["pitch_radius"] = PITCH_RADIUS
        g["features"] = features
        g["zone_edge"] = edge
        g["percentile_levels"] = levels
        g["convergence_samples"] = counts
        outputs = {"te_peak_to_peak": pp, "stiffness_mean": km, "stiffness_range": 0.3 * km,
                   "max_pressure": np.full(samples, 1.2e9), "max_edge_share": np.zeros(samples)}
        nominal = {"te_peak_to_peak": design_pp, "stiffness_mean": 2e8, "stiffness_range": 6e7,
                   "max_pressure": 1.1e9, "max_edge_share": 0.0}
        for name, x in outputs.items():
            g[name] = x[:, None]
            g[f"nominal/{name}"] = np.array([nominal[name]])
            g[f"percentiles/{name}"] = np.percentile(x, levels)[None, :]
            g[f"convergence/{name}"] = np.array(
                [[np.percentile(x[:int(n)], levels) for n in counts]])
        for name in ("te_peak_to_peak", "stiffness_range"):
            s = g.create_group(f"sensitivity/{name}")
            s["coefficient"], s["low"], s["high"] = coef, coef - 0.05, coef + 0.05
            s["r2"] = np.array([0.98])
    return path, pp


def test_tolerance_picture_and_report(tmp_path):
    results, pp = write_tolerances(str(tmp_path / "results.h5"))
    with h5py.File(results, "r") as f:
        plot_study.plot_study(f["study"], str(tmp_path))
    path = os.path.join(str(tmp_path), "tolerances_pair.png")
    width, height = is_png(path)
    assert 1000 < width < 3000 and 800 < height < 3000 and os.path.getsize(path) > 50_000
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "report.py"), results], check=True,
                   capture_output=True)
    with open(tmp_path / "report.html", encoding="utf-8") as fh:
        page = fh.read()
    assert 'alt="tolerances_pair.png"' in page
    rows = table_rows(page, "tolerances")
    te = next(r for r in rows if r[2].startswith("TE p-p"))
    expected = " / ".join(f"{x:.3g}" for x in np.percentile(pp, [5, 50, 95]) * PITCH_RADIUS * 1e6)
    assert te[3].startswith(expected) and "design alone 1.5 µm" in te[3], te
    drives = next(r for r in rows if r[2] == "drives the TE p-p most")
    assert drives[3].startswith("pinion F_p: SRC +0.99"), drives
    # the flagged sample is in the page's warnings
    assert 'id="warnings"' in page and "samples 3" in page


def write_misalignments(path, pair="pair"):
    """A misalignment check to the schema: a 3 x 2 grid over offset [m] and pinion axial shift
    [m] at 20 and 200 N m whose pattern (a 16 x 40 raster of the gear flank) is a blob whose
    centre moves along the face with the offset (+10 mm per mm) and along the profile with the
    shift; grid point 4 carries 20 % of its load on an edge. Returns the path and the centres."""
    offsets, shifts = np.array([-0.2e-3, 0.0, 0.2e-3]), np.array([0.0, 0.2e-3])
    grid = np.array([(o, s) for o in offsets for s in shifts])
    G, M, U, V, T, N = len(grid), 2, 16, 40, 12, 8
    pu, pf = np.array([-2e-3, 2e-3]), np.array([-9e-3, 9e-3])
    u = pu[0] + (np.arange(U) + 0.5) * (pu[1] - pu[0]) / U
    v = pf[0] + (np.arange(V) + 0.5) * (pf[1] - pf[0]) / V
    pattern = np.zeros((G, M, U, V))
    centre = np.zeros((G, M, 2))
    for k, (o, s) in enumerate(grid):
        c = np.array([5 * s, 10 * o])  # (profile, face) [m]
        for m in range(M):
            blob = np.exp(-((u[:, None] - c[0]) / 1e-3) ** 2 - ((v[None, :] - c[1]) / 3e-3) ** 2)
            pattern[k, m] = np.where(blob > 0.05, (m + 1) * 1e9 * blob, 0.0)
            centre[k, m] = c
    with h5py.File(path, "w") as f:
        g = f.create_group(f"study/{pair}")
        g.attrs["kind"] = "misalignments"
        g.attrs["parameters"] = "offset,pinion_axial_shift"
        g["axes/offset"], g["axes/pinion_axial_shift"] = offsets, shifts
        g["shape"], g["grid"] = np.array([3, 2]), grid
        g["torques"], g["design_torque"] = np.array([20.0, 200.0]), 200.0
        g["pitch_radius"] = PITCH_RADIUS
        g["pattern"], g["pattern_centre"] = pattern, centre
        g["pattern_extent"] = np.concatenate([centre - 1e-3, centre + 1e-3], axis=2)[..., [0, 2, 1, 3]]
        g["pattern_profile_range"], g["pattern_face_range"] = pu, pf
        g["contact_path"] = np.zeros((G, T, 2))
        g["unloaded_te_peak_to_peak"] = 1e-5 * (1 + np.abs(grid).sum(axis=1) / 1e-4)
        g["te_peak_to_peak"] = np.full((G, M), 2e-5)
        edge = np.zeros((G, M))
        edge[4] = 0.2
        g["max_edge_share"] = edge
        g["max_pressure"] = pattern.max(axis=(2, 3))
    return path, centre


def test_misalignment_picture_and_report(tmp_path):
    results, centre = write_misalignments(str(tmp_path / "results.h5"))
    with h5py.File(results, "r") as f:
        plot_study.plot_study(f["study"], str(tmp_path))
    width, height = is_png(os.path.join(str(tmp_path), "vh_pair.png"))
    assert 1000 < width < 3500 and 500 < height < 3000
    assert os.path.getsize(os.path.join(str(tmp_path), "vh_pair.png")) > 50_000
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "report.py"), results], check=True,
                   capture_output=True)
    with open(tmp_path / "report.html", encoding="utf-8") as fh:
        page = fh.read()
    assert 'alt="vh_pair.png"' in page
    rows = table_rows(page, "misalignments")
    assert len(rows) == 6
    # grid point 2 is the nominal one (offset 0, shift 0); rows in grid order, at 200 N m
    assert rows[2][1] == "nominal" and rows[5][1] == "offset +0.2 mm, pinion axial shift +0.2 mm"
    assert rows[0][2] == "200 N m"
    profile, face = centre[5, 1] * 1e3
    assert rows[5][4] == f"({face:+.2f}, {profile:+.2f}) mm", rows[5]
    assert rows[4][6] == "20.0%"
    assert re.search(r'<tr class="alarm">(?:(?!</tr>).)*offset \+0\.2 mm, pinion axial shift \+0 mm',
                     page, re.S)

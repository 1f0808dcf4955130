#!/usr/bin/python3
"""The Hertz check of the flank-interior pressure on the default pair: at every mesh position
where one tooth pair carries the load, the finite elements' interior peak pressure against
Hertz's line contact at the same place, from the FE's own line load there.

  check_hertz.py CASE_OUT_DIR

What results.h5 gives (stiffness/<pair>/contact_cells, [torque][position][cell][4]): per cell
the pinion tooth (-1: unused slot), the pinion flank parameters u (roll angle xi: radius
r_b sqrt(1 + xi^2), roll length L = r_b xi = the curvature radius rho1) and v (axial position
z), and the pressure [Pa] = the cell's force / (ds dt). The cell sizes are not stored. Each pair
gets cells_along columns (along the contact line: the face) of cells_across cells (across it:
the profile), uniform in the pair's tangent plane and centred on its unloaded contact point
(contact_cells.cc); the face-end columns are the flank-edge cells, which interior_peak_pressure
leaves out (loaded_contact.cc). Here ds is recovered exactly from the cells' u (the tangent-plane
coordinate of the pinion involute's point at each u), dt from their v.

Checked, per single-pair position (one pinion tooth carries >= 99 % of F, by the cells and by
pair_force) of the theoretical flanks:
  1. load balance: sum of p ds dt over the cells = normal_force within 1e-3 (the ds
     reconstruction is exact to (b_H / rho)^2 ~ 1e-4; this also proves the areas right);
  2. interior_peak_pressure is the largest pressure off the face-end columns; the contact of
     its column lies inside the zone (not in its outermost rows) and on the smooth flank
     (roll lengths between the start of active profile and the start of the tip relief);
  3. Hertz: w = sum of p ds over the peak's column (the FE's line load at that face
     coordinate), 1/R' = 1/rho1 + 1/rho2 + k_Ca with rho1 = sqrt(r^2 - r_b1^2) at the column's
     contact point, rho2 = a_w sin(alpha_wt) - rho1, k_Ca the pinion's profile crowning
     8 C_a / L_a^2 (r_b1 / rho1)^2 (parabolic over the active roll length L_a,
     modifications.cc, turned from roll length to arc length), E* = E / (2 (1 - nu^2)) from the
     scene; p0 = sqrt(w E* / (pi R')), b_H = sqrt(4 w R' / (pi E*));
  4. the contact half-width from the FE's pressure, 2 sqrt(second moment), each cell counted
     as uniform over its width (+ ds^2 / 12), against b_H, while ds < b_H / 2.

The tolerance, from the discretisation, not from the result (all computed here, per position):
  a. Cells: the FE's pressure is piecewise constant on cells of width ds, collocated at the
     cells' centres. The exact Hertz semi-ellipse averaged over the peak cell, the mean of
     p0 sqrt(1 - x^2 / b_H^2) over [x_c - ds / 2, x_c + ds / 2], lies below p0 by a factor that
     depends on where the cell sits against the centre (0.992-0.998 at ds / b_H = 0.215), and
     the collocation solution of the same discrete problem (2D: uniform strips of width ds
     on the half-space, log kernel, Hertz's gap, the FE's w) lies within a band about p0; both
     are computed for this position's ds / b_H over every offset of the grid against the Hertz
     centre, and their union is the band [r_lo, r_hi] (at ds / b_H = 0.215: 0.992 to 1.002).
     The same collocation model gives the band of the half-width estimate.
  b. The structural compliance tables (compliance/<pair>/<member>, without the local half-space
     part) are read bilinearly between their profile grid points (flank_compliance.cc), so the
     members' structural deflection across the contact is piecewise linear with a kink at each
     grid node, and a contact centred on a node is squeezed (here up to +0.9 % on the peak).
     Its size is computed: the tables read as the FE reads them at the column's cells, loaded by
     the FE's cell forces, added to the gap of the collocation model; |change of the model's
     peak| widens the band (likewise for the width).
  c. 3D: the column is not an infinite uniform strip (the load falls towards the face ends
     under the lead crowning; columns of finite length dt): the half-space displacement of all
     the FE's cells (Love's rectangles) minus the column's own 2D strips, added to the gap the
     same way; |change| widens the band (here 0.04 %).
  d. 0.5 %, a margin for what these models leave out: the involute gap's cubic term (< 0.01 %
     here), the gear side of b read on first-order gear points, the contact solver's own
     tolerance. A judgement, not a computation: ten times the 3D term and fifty times the cubic
     one.
The check passes if FE / p0 lies in [r_lo - b - c - d, r_hi + b + c + d]; the column "rest"
shows what the models leave (FE against the collocation model with b and c in its gap: within
+-0.1 % when the tolerance was set). A wrong E (factor 2: p0 41 % high), the pressure of a
face-end column instead of the interior peak (27-33 % below p0 here), or the whole normal force
spread evenly over the face (the old 1346 MPa estimate: p0 8-10 % low) lie far outside, and the
script proves that: each such mistake must fail at every position checked, else it exits
non-zero too. A 3 % error in the pressures or 8 % in E fails the check as well (tried on
altered copies of results.h5).
"""
import math
import os
import sys

import h5py
import numpy as np

out = sys.argv[1]


def scene_parameters(text):
    """The scene text as run -> {('Subsection', ..., 'name'): 'value'}."""
    values, path = {}, []
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("subsection "):
            path.append(line[len("subsection "):].strip())
        elif line == "end":
            path.pop()
        elif line.startswith("set "):
            key, _, value = line[4:].partition("=")
            values[tuple(path) + (key.strip(),)] = value.strip()
    return values


# ---------------------------------------------------------------------------------------------
# The 2D collocation model of the FE's cells across a contact line, in Hertz units: lengths in
# b_H, pressure in p0, so that E* = 2, R' = 1, the gap X^2 / 2 and the line load pi / 2.
def strip_log_integral(x, ds):
    """Integral of ln|x - x'| over |x'| <= ds / 2."""
    def f(u):
        au = np.abs(u)
        return np.where(au > 0, u * np.log(np.where(au > 0, au, 1.0)), 0.0) - u
    return f(x + ds / 2) - f(x - ds / 2)


def collocation(x, ds, gap):
    """Pressures on strips of width ds centred at x (a uniform grid) pressed by w = pi / 2 against
    the gap (E* = 2): contact where the deformed gap closes, p >= 0 (active set)."""
    n = len(x)
    K = -(1 / math.pi) * strip_log_integral(x[:, None] - x[None, :], ds)  # 2 / (pi E*) = 1 / pi
    active = gap <= np.min(gap) + 0.6  # start from about Hertz's width
    for _ in range(200):
        idx = np.flatnonzero(active)
        m = len(idx)
        A = np.zeros((m + 1, m + 1))
        A[:m, :m], A[:m, m], A[m, :m] = K[np.ix_(idx, idx)], -1.0, ds
        sol = np.linalg.solve(A, np.concatenate([-gap[idx], [math.pi / 2]]))
        p = np.zeros(n)
        p[idx] = sol[:m]
        opened = gap + K @ p - sol[m]
        drop, add = active & (p < 0), ~active & (opened < -1e-12)
        if not drop.any() and not add.any():
            return p
        active[drop], active[add] = False, True
    raise RuntimeError("collocation model: active set did not settle")


def half_width(x, ds, p):
    """2 sqrt(second moment) of a piecewise-constant pressure (each cell uniform)."""
    f = p * ds
    xc = np.sum(f * x) / np.sum(f)
    return 2 * math.sqrt(np.sum(f * ((x - xc) ** 2 + ds ** 2 / 12)) / np.sum(f))


def semi_ellipse_mean(lo, hi):
    """Mean of sqrt(1 - X^2) over [lo, hi] (0 outside |X| <= 1)."""
    def F(u):
        u = min(max(u, -1.0), 1.0)
        return 0.5 * (u * math.sqrt(1 - u * u) + math.asin(u))
    return (F(hi) - F(lo)) / (hi - lo)


def cell_band(dsn):
    """Over every offset of a grid of width dsn (in b_H) against the Hertz centre: the range of
    the collocation peak / p0, of the exact cell average of the peak cell / p0, and of the
    collocation half-width estimate / b_H."""
    peaks, averages, widths = [], [], []
    n = 2 * int(math.ceil(1.5 / dsn)) + 1
    for e in np.linspace(0.0, 0.5, 11):  # symmetric: offsets in [-ds/2, 0] alike
        x = (np.arange(n) - (n - 1) / 2 + e) * dsn
        p = collocation(x, dsn, x ** 2 / 2)
        i = int(np.argmax(p))
        peaks.append(p[i])
        averages.append(semi_ellipse_mean(x[i] - dsn / 2, x[i] + dsn / 2))
        widths.append(half_width(x, dsn, p))
    lo, hi = min(min(peaks), min(averages)), max(max(peaks), max(averages))
    return lo, hi, min(averages), max(averages), min(widths), max(widths)


def love_rectangle(x, y, a, b):
    """Integral of 1 / r over the rectangle |x'| <= a, |y'| <= b seen from (x, y)."""
    def F(X, Y):
        with np.errstate(divide="ignore", invalid="ignore"):
            t1 = np.where(X != 0, X * np.arcsinh(Y / np.where(X != 0, np.abs(X), 1)), 0.0)
            t2 = np.where(Y != 0, Y * np.arcsinh(X / np.where(Y != 0, np.abs(Y), 1)), 0.0)
        return t1 + t2
    return F(x + a, y + b) - F(x + a, y - b) - F(x - a, y + b) + F(x - a, y - b)


# ---------------------------------------------------------------------------------------------
class Table:
    """A member's structural compliance table, read bilinearly as flank_compliance.cc reads it,
    on the cyclic tooth (load and response on the same tooth: offset 0)."""

    def __init__(self, f, pair, member, n_u, graded):
        g = f["flanks"][pair][member]
        rb = g["base_radius"][()]
        xf = math.sqrt(max(g["form_radius"][()] ** 2 / rb ** 2 - 1, 0.0))
        xt = math.sqrt(g["tip_radius"][()] ** 2 / rb ** 2 - 1)
        b = g["face_width"][()]
        margin = 0.02  # FlankGridSpec::margin
        self.u = (xf + margin * (xt - xf), xt - margin * (xt - xf))
        self.v = (-b / 2 + margin * b, b / 2 - margin * b)
        c = f["compliance"][pair][member]
        cyclic = int(c["cyclic_tooth"][()])
        assert cyclic >= 0, f"{member}: the structural term is written for a cyclic tooth's table"
        H = c["compliance"][()]  # H[load k, response j] = S(j, k)
        per_tooth = H.shape[0]
        self.n_u, self.n_v = n_u, per_tooth // n_u
        assert self.n_u * self.n_v == per_tooth, (n_u, H.shape)
        t = list(c["grid_teeth"][()]).index(cyclic)
        self.S = H[:, t * per_tooth:(t + 1) * per_tooth]  # [load node, response node]

        def nodes(n):
            k = np.arange(n)
            x = (1 - np.cos(math.pi * k / (n - 1))) / 2 if graded else k / (n - 1)
            x[-1] = 1
            return x
        self.nu, self.nv = nodes(self.n_u), nodes(self.n_v)

    def weights(self, u, v):
        W = np.zeros((len(u), self.n_u * self.n_v))
        for k, (uu, vv) in enumerate(zip(u, v)):
            fu = min(max((uu - self.u[0]) / (self.u[1] - self.u[0]), 0.0), 1.0)
            fv = min(max((vv - self.v[0]) / (self.v[1] - self.v[0]), 0.0), 1.0)
            iu = min(max(int(np.searchsorted(self.nu, fu, "right")) - 1, 0), self.n_u - 2)
            iv = min(max(int(np.searchsorted(self.nv, fv, "right")) - 1, 0), self.n_v - 2)
            a = (fu - self.nu[iu]) / (self.nu[iu + 1] - self.nu[iu])
            c = (fv - self.nv[iv]) / (self.nv[iv + 1] - self.nv[iv])
            for da, wa in ((0, 1 - a), (1, a)):
                for dc, wc in ((0, 1 - c), (1, c)):
                    W[k, (iu + da) * self.n_v + iv + dc] += wa * wc
        return W

    def deflection(self, load_u, load_v, forces, resp_u, resp_v):
        """Approach at the response points under the forces at the load points [m]."""
        return self.weights(resp_u, resp_v) @ (self.S.T @ (self.weights(load_u, load_v).T @ forces))


# ---------------------------------------------------------------------------------------------
class Pair:
    """What the check needs of a pair: geometry, material, modifications, cells, tables."""

    def __init__(self, f, name):
        scene = scene_parameters(f.attrs["scene_parameters"])
        fe, lc = ("Finite elements", name), ("Loaded contact", name)
        mods = ("Flanks", name, "Pinion", "Drive flank modifications")
        fl = f["flanks"][name]
        assert fl["pinion"]["base_helix_angle"][()] == 0, "written for spur pairs"
        interp = scene[lc + ("table interpolation",)]
        assert interp == "bilinear", f"the structural term is written for bilinear tables: {interp}"
        self.name = name
        self.E = float(scene[fe + ("Young's modulus",)]) * 1e9
        self.nu = float(scene[fe + ("Poisson's ratio",)])
        self.Es = self.E / (2 * (1 - self.nu ** 2))
        self.rb1, self.rb2 = fl["pinion"]["base_radius"][()], fl["gear"]["base_radius"][()]
        self.line = (fl["operating_centre_distance"][()] *
                     math.sin(fl["operating_pressure_angle"][()]))  # rho1 + rho2
        self.face = fl["pinion"]["face_width"][()]
        self.L_sap = math.sqrt(fl["pinion"]["active_profile_start_radius"][()] ** 2 - self.rb1 ** 2)
        self.L_tip = math.sqrt(fl["pinion"]["tip_radius"][()] ** 2 - self.rb1 ** 2)
        self.C_a = float(scene[mods + ("profile crowning",)]) * 1e-6
        relief = float(scene[mods + ("tip relief",)]) != 0
        self.L_smooth = self.L_tip - relief * float(scene[mods + ("tip relief length",)]) * 1e-3
        self.eps_alpha = fl["transverse_contact_ratio"][()]
        self.across = int(scene[lc + ("cells across",)])
        self.along = int(scene[lc + ("cells along",)])
        n_u = int(scene[fe + ("profile grid points",)])
        graded = scene[fe + ("load grid",)] == "graded"
        self.tables = (Table(f, name, "pinion", n_u, graded), Table(f, name, "gear", n_u, graded))

    def curvature(self, rho1):
        """1/R': both involutes and the pinion's profile crowning, parabolic in the roll length
        over the active profile (8 C_a / L_a^2 per roll length^2, modifications.cc), per arc
        length^2 (d L / d arc = r_b1 / rho1)."""
        crowning = 8 * self.C_a / (self.L_tip - self.L_sap) ** 2 * (self.rb1 / rho1) ** 2
        return 1 / rho1 + 1 / (self.line - rho1) + crowning

    def hertz(self, w, rho1, Es=None):
        """Hertz's line contact under the line load w: p0, b_H."""
        Es = Es or self.Es
        R = 1 / self.curvature(rho1)
        return math.sqrt(w * Es / (math.pi * R)), math.sqrt(4 * w * R / (math.pi * Es))

    def grid(self, cells):
        """One tooth's cells as the regular grid [along][across] of (xi, v, p), with each cell's
        tangent-plane coordinate s across the line (exact, from the pinion involute), ds per
        column and dt; None if the cells are not that grid (cut columns)."""
        if len(cells) != self.along * self.across:
            return None
        g = cells.reshape(self.along, self.across, 4)
        xi, v, p = g[:, :, 1], g[:, :, 2], g[:, :, 3]
        xi0 = xi[:, self.across // 2:self.across // 2 + 1]  # the middle row: the contact line

        def point(x):
            return self.rb1 * np.stack([np.cos(x) + x * np.sin(x), np.sin(x) - x * np.cos(x)], -1)
        d = point(xi) - point(xi0)
        T0 = np.stack([np.cos(xi0), np.sin(xi0)], -1)
        N0 = np.stack([np.sin(xi0), -np.cos(xi0)], -1)
        N = np.stack([np.sin(xi), -np.cos(xi)], -1)
        # the flank point is the projection of the tangent-plane point along its normal
        h = -np.sum(d * N0, -1) / np.sum(N * N0, -1)
        sc = np.sum(d * T0, -1) + h * np.sum(N * T0, -1)
        ds = (sc[:, -1] - sc[:, 0]) / (self.across - 1)
        dt = (v[-1, 0] - v[0, 0]) / (self.along - 1)
        if (np.abs(np.diff(sc, axis=1) / ds[:, None] - 1).max() > 1e-3 or
                np.abs(np.diff(v[:, 0]) / dt - 1).max() > 1e-3):
            return None
        return dict(xi=xi, v=v, p=p, s=sc, ds=ds, dt=dt)


def gap_terms(pair, g, i, rho1):
    """The structural tables' and the 3D half-space part of the gap across column i [m]."""
    xi, v, p, sc, ds, dt = g["xi"], g["v"], g["p"], g["s"], g["ds"], g["dt"]
    rho2 = pair.line - rho1
    xi2 = rho2 / pair.rb2 - sc / rho2  # the gear's points, to first order across the line
    forces = (p * ds[:, None] * dt).ravel()
    pinion, gear = pair.tables
    structural = (pinion.deflection(xi.ravel(), v.ravel(), forces, xi[i], v[i]) +
                  gear.deflection(xi2.ravel(), v.ravel(), forces, xi2[i], v[i]))
    X = sc[i][:, None] - sc.ravel()[None, :]
    Y = v[i, 0] - v.ravel()[None, :] + 0 * X
    A = np.repeat(ds, pair.across)[None, :] / 2 + 0 * X
    love = (love_rectangle(X, Y, A, dt / 2) * p.ravel()[None, :]).sum(1) / (math.pi * pair.Es)
    strips = -(2 / (math.pi * pair.Es)) * (
        strip_log_integral(sc[i][:, None] - sc[i][None, :], ds[i]) * p[i][None, :]).sum(1)
    return structural, love - strips


REST = 0.005  # d. in the docstring
failures = []
checked = 0


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg)


def check_position(pair, s, m, n, mistakes):
    """Checks one position where one pair carries the load: the band of the cells alone
    (r_lo, r_hi, and that of the cell average alone), else None."""
    global checked
    F = s["normal_force"][m, n]
    if not F > 0 or s["pair_force"][m, n].max() < 0.99 * F:
        return None
    tag = f"{pair.name} torque {s['torque'][m]:g} position {n}"
    cells = s["contact_cells"][m, n]
    cells = cells[cells[:, 0] >= 0]
    grids = {t: pair.grid(cells[cells[:, 0] == t]) for t in np.unique(cells[:, 0])}
    force = {t: None if g is None else float(np.sum(g["p"] * g["ds"][:, None] * g["dt"]))
             for t, g in grids.items()}
    carrying = [t for t, x in force.items() if x is not None and x >= 0.99 * F]
    if len(carrying) != 1 or any(x is None for x in force.values()):
        fail(f"{tag}: pair_force has one pair carry F, the cells disagree or their grid is not "
             f"the regular one (force per pinion tooth {force})")
        return None
    g = grids[carrying[0]]
    xi, v, p, sc, ds = g["xi"], g["v"], g["p"], g["s"], g["ds"]
    balance = sum(force.values()) / F - 1
    if not abs(balance) <= 1e-3:
        fail(f"{tag}: load balance: the cells carry {sum(force.values()):.2f} N, F {F:.2f} N")

    # the interior peak: off the face-end columns (the flank-edge cells)
    i, j = np.unravel_index(int(np.argmax(p[1:-1])), p[1:-1].shape)
    i += 1
    p_fe = p[i, j]
    if abs(p_fe / s["interior_peak_pressure"][m, n] - 1) > 1e-9:
        fail(f"{tag}: interior_peak_pressure {s['interior_peak_pressure'][m, n] / 1e6:.1f} MPa "
             f"is not the largest pressure off the face ends ({p_fe / 1e6:.1f} MPa)")
    loaded = p[i] > 0
    L = pair.rb1 * xi[i][loaded]
    if loaded[0] or loaded[-1]:
        fail(f"{tag}: the contact of the peak's column reaches the zone's edge")
    if L.min() < pair.L_sap or L.max() > pair.L_smooth:
        fail(f"{tag}: the contact of the peak's column leaves the smooth flank (roll lengths "
             f"{L.min() * 1e3:.2f}-{L.max() * 1e3:.2f} mm)")

    # Hertz at the peak's column, from the FE's line load there
    w = np.sum(p[i] * ds[i])
    rho1 = pair.rb1 * xi[i, pair.across // 2]
    p0, bH = pair.hertz(w, rho1)
    ratio = p_fe / p0
    b_fe = half_width(sc[i], ds[i], p[i])

    # a. the cells; b., c. the structural and 3D parts of the gap, on the FE's own grid
    dsn = ds[i] / bH
    r_lo, r_hi, avg_lo, avg_hi, q_lo, q_hi = cell_band(dsn)
    xn = sc[i] / bH
    scale = 1 / (pair.curvature(rho1) * bH ** 2)  # gap [m] -> model units b_H^2 / R'
    structural, three_d = gap_terms(pair, g, i, rho1)
    base = collocation(xn, dsn, xn ** 2 / 2)
    models = {k: collocation(xn, dsn, xn ** 2 / 2 + extra * scale)
              for k, extra in (("struct", structural), ("3d", three_d),
                               ("both", structural + three_d))}
    d = {k: q.max() / base.max() - 1 for k, q in models.items()}
    dq = {k: half_width(xn, dsn, q) / half_width(xn, dsn, base) - 1 for k, q in models.items()}
    if abs(d["struct"]) > 0.02:
        fail(f"{tag}: the structural tables alone move the peak by {d['struct'] * 100:+.2f} %: "
             "too much for a Hertz check")
    widen = abs(d["struct"]) + abs(d["3d"]) + REST
    lo, hi = r_lo - widen, r_hi + widen
    ok = lo <= ratio <= hi
    # what the models leave (the FE against the collocation model with both gap terms)
    rest = p_fe / (models["both"].max() * p0) - 1
    print(f"  {n:3d} {v[i, 0] * 1e3:6.2f} {rho1 * 1e3:5.2f} {(pair.line - rho1) * 1e3:5.2f} "
          f"{w / 1e3:6.1f} {p_fe / 1e6:7.1f} {p0 / 1e6:7.1f} {(ratio - 1) * 100:+6.2f}  "
          f"[{(lo - 1) * 100:+.2f}, {(hi - 1) * 100:+.2f}]  {d['struct'] * 100:+.2f} "
          f"{d['3d'] * 100:+.2f} {rest * 100:+.2f}  {b_fe * 1e6:5.1f} {bH * 1e6:5.1f} "
          f"{dsn:5.3f} {balance:+.0e}  {'ok' if ok else 'FAIL'}")
    if not ok:
        fail(f"{tag}: FE interior peak {p_fe / 1e6:.1f} MPa against Hertz {p0 / 1e6:.1f} MPa: "
             f"{(ratio - 1) * 100:+.2f} % outside [{(lo - 1) * 100:+.2f}, {(hi - 1) * 100:+.2f}] %")
    if dsn < 0.5:  # the half-width: only where the cells resolve it
        widen_q = abs(dq["struct"]) + abs(dq["3d"]) + REST
        q = b_fe / bH
        if not q_lo - widen_q <= q <= q_hi + widen_q:
            fail(f"{tag}: contact half-width {b_fe * 1e6:.1f} um against Hertz {bH * 1e6:.1f} um: "
                 f"{(q - 1) * 100:+.2f} % outside [{(q_lo - widen_q - 1) * 100:+.2f}, "
                 f"{(q_hi + widen_q - 1) * 100:+.2f}] %")
    checked += 1

    # the mistakes the check must catch: (FE value, Hertz reference) as each would have them
    face_end = max(p[0].max(), p[-1].max())
    for what, fe_value, reference in (
            ("E doubled", p_fe, pair.hertz(w, rho1, 2 * pair.Es)[0]),
            ("face-end column", face_end, p0),
            ("F spread over the face", p_fe, pair.hertz(F / pair.face, rho1)[0])):
        mistakes.setdefault(what, []).append((fe_value / reference,
                                              not lo <= fe_value / reference <= hi))
    return (r_lo, r_hi, avg_lo, avg_hi)


with h5py.File(os.path.join(out, "results.h5"), "r") as f:
    names = [p for p in f.get("stiffness", {}) if "contact_cells" in f["stiffness"][p]]
    assert names, "no loaded contact in " + out
    for name in names:
        pair, s = Pair(f, name), f["stiffness"][name]
        print(f"{name}: E {pair.E / 1e9:g} GPa, nu {pair.nu:g}, E* {pair.Es / 1e9:.2f} GPa; "
              f"profile crowning {pair.C_a * 1e6:g} um over roll lengths "
              f"{pair.L_sap * 1e3:.2f}-{pair.L_tip * 1e3:.2f} mm; smooth flank to "
              f"{pair.L_smooth * 1e3:.2f} mm")
        print("  pos  z[mm] rho1  rho2  w[N/mm] FE[MPa] p0[MPa] FE/p0-1 window [%]      "
              "struct 3D    rest   b_FE  b_H[um] ds/b_H balance")
        mistakes, band, before = {}, None, checked
        for m in range(s["contact_cells"].shape[0]):
            for n in range(s["contact_cells"].shape[1]):
                band = check_position(pair, s, m, n, mistakes) or band
        for what, results in mistakes.items():
            ratios = [r for r, _ in results]
            missed = sum(not c for _, c in results)
            print(f"  mistake '{what}': FE/p0-1 {(min(ratios) - 1) * 100:+.1f} to "
                  f"{(max(ratios) - 1) * 100:+.1f} %, caught at {len(results) - missed} of "
                  f"{len(results)} positions")
            if missed:
                fail(f"{name}: the check cannot tell '{what}' from the FE at {missed} positions")
        if band:
            r_lo, r_hi, avg_lo, avg_hi = band
            print(f"  cells alone (last position): collocation and cell average "
                  f"{(r_lo - 1) * 100:+.2f} to {(r_hi - 1) * 100:+.2f} %, the exact cell average "
                  f"of the semi-ellipse alone {(avg_lo - 1) * 100:+.2f} to "
                  f"{(avg_hi - 1) * 100:+.2f} %")
        # one pair carries the load over (2 - eps_alpha) of the cycle: at least half as many
        # positions must have been checked
        positions = s["contact_cells"].shape[0] * s["contact_cells"].shape[1]
        if checked - before < (2 - pair.eps_alpha) * positions / 2:
            fail(f"{name}: only {checked - before} single-pair positions of {positions} checked")

if failures or checked == 0:
    print(f"{os.path.basename(out)}: {len(failures)} failure(s)")
    sys.exit(1)
print(f"{os.path.basename(out)}: the FE interior peak pressure agrees with Hertz at {checked} "
      "single-pair positions")

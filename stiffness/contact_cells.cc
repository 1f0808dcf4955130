#include "stiffness/contact_cells.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>

namespace gearkit
{
namespace
{
struct Projection
{
  double u, v;
  Vec3   position, normal; ///< global
};

/// The pinion flank point nearest to a global target (Gauss-Newton from (u, v)); empty if it
/// lies off the flank's domain or the flank cannot be evaluated there.
std::optional<Projection>
project(const Flank &flank, const Assembly &assembly, double phi, const Vec3 &target, double u,
        double v)
{
  const FlankDomain d = flank.domain();
  try
    {
      // Gauss-Newton on the foot point; one that has not settled (a target far off the flank,
      // beyond a fold near the base circle, sends it back and forth) is no projection: taken
      // as it stood, it put cells on flank points other cells already held.
      double last = HUGE_VAL; // the last step, in fractions of the domain
      for (int it = 0; it < 20 && last >= 1e-13; ++it)
        {
          const FlankPoint            p = flank.evaluate(u, v);
          Eigen::Matrix<double, 3, 2> J;
          J.col(0)        = assembly.pinion_vector_to_global(p.d_du, phi);
          J.col(1)        = assembly.pinion_vector_to_global(p.d_dv, phi);
          const Vec3 r    = target - assembly.pinion_to_global(p.position, phi);
          const Vec2 step = (J.transpose() * J).ldlt().solve(J.transpose() * r);
          u += step.x(), v += step.y();
          last = std::max(std::abs(step.x()) / (d.u_max - d.u_min),
                          std::abs(step.y()) / (d.v_max - d.v_min));
        }
      if (!(last < 1e-9) || !(u >= d.u_min && u <= d.u_max && v >= d.v_min && v <= d.v_max) ||
          !flank.contains(u, v))
        return std::nullopt;
      const FlankPoint p = flank.evaluate(u, v);
      return Projection{u, v, assembly.pinion_to_global(p.position, phi),
                        assembly.pinion_vector_to_global(p.normal, phi)};
    }
  catch (const InputError &)
    {
      return std::nullopt;
    }
}

/// One pair's contact zone as it is laid out: the pair, its flanks, and the zone's frame in the
/// common tangent plane (n the pinion normal, e_t along the contact line, e_s = n x e_t across
/// it) with the relative curvature across the line that sets the band.
struct PairZone
{
  const UnloadedTca        &tca;
  const Assembly           &assembly;
  const TcaPosition        &position;
  const ContactCellOptions &o;
  const PairContact        &c;
  const Flank              &flank;
  double                    sign, phi;
  Vec3                      n, e_t, e_s;
  double                    k_max;

  PairZone(const UnloadedTca &tca, const TcaPosition &position, const ContactCellOptions &o,
           const PairContact &c)
      : tca(tca)
      , assembly(tca.assembly_data())
      , position(position)
      , o(o)
      , c(c)
      , flank(tca.pinion_flanks().flank(c.pinion_tooth, tca.options_data().side))
      , sign(tca.options_data().side == FlankSide::drive ? 1.0 : -1.0)
      , phi(position.pinion_angle)
      , n(c.normal_pinion)
  {
    e_t = c.major_direction - c.major_direction.dot(n) * n;
    if (e_t.norm() < 1e-9)
      e_t = assembly.pinion_vector_to_global(flank.evaluate(c.u1, c.v1).d_dv, phi);
    e_t   = (e_t - e_t.dot(n) * n).normalized();
    e_s   = n.cross(e_t);
    k_max = std::max(c.curvature_max, 1e-9);
  }

  /// The unloaded gap at a pinion flank point (false off either flank).
  bool
  gap_at(const Vec3 &target, double s_cell, double t_cell, ContactCell &cell) const
  {
    const auto p = project(flank, assembly, phi, target, c.u1, c.v1);
    double     psi;
    if (!p ||
        !tca.touch_angle(c.gear_tooth, p->position, position.gear_angle, psi, cell.u2, cell.v2))
      return false;
    cell.s = s_cell, cell.t = t_cell;
    cell.u1 = p->u, cell.v1 = p->v;
    cell.position = p->position, cell.normal = p->normal;
    const Vec3 r = p->position - assembly.gear_centre();
    cell.gap     = std::max(0.0, sign * (position.gear_angle - psi) *
                                     std::abs(assembly.gear_axis().cross(r).dot(p->normal)));
    return true;
  }
};

/// Optionally the gap at the zone's scale: a quadratic fitted to gaps sampled on two rings
/// about the contact point. Where its principal directions or largest curvature disagree with
/// the local ones (measured flanks: the curvature at a point carries the measurement's noise,
/// and the contact line can turn by tens of degrees), the fit sets the zone.
void
fit_zone_to_gaps(PairZone &z)
{
  const PairContact                       &c   = z.c;
  const double                             rho = std::sqrt(2 * z.o.gap_band / z.k_max);
  std::vector<Eigen::Matrix<double, 6, 1>> rows;
  std::vector<double>                      gaps;
  for (double r : {rho / 2, rho})
    for (int a = 0; a < 12; ++a)
      {
        const double s_ = r * std::cos(pi * a / 6), t_ = r * std::sin(pi * a / 6);
        ContactCell  probe;
        if (z.gap_at(c.position + s_ * z.e_s + t_ * z.e_t, s_, t_, probe))
          {
            rows.emplace_back();
            rows.back() << 1, s_, t_, s_ * s_ / 2, s_ * t_, t_ * t_ / 2;
            gaps.push_back(probe.gap);
          }
      }
  if (rows.size() >= 12)
    {
      Eigen::MatrixXd A(rows.size(), 6);
      Eigen::VectorXd g(rows.size());
      for (std::size_t i = 0; i < rows.size(); ++i)
        A.row(Eigen::Index(i)) = rows[i].transpose(), g[Eigen::Index(i)] = gaps[i];
      const Eigen::VectorXd q = A.colPivHouseholderQr().solve(g);
      Eigen::Matrix2d       H;
      H << q[3], q[4], q[4], q[5];
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(H);
      const double                                         k_fit = eig.eigenvalues()[1];
      const Vec2 along = eig.eigenvectors().col(0); // least curvature, in (s, t)
      if (k_fit > 0 && (std::abs(along.y()) < std::cos(5 * pi / 180) || k_fit < z.k_max / 2))
        {
          z.e_t   = (along.x() * z.e_s + along.y() * z.e_t).normalized();
          z.e_s   = z.n.cross(z.e_t);
          z.k_max = k_fit;
        }
    }
}

/// The band's half width across the line. Across the line the gap opens as k_max s^2 / 2 near
/// the contact point; where the gap opens more slowly (measured flanks: the local curvature
/// carries the measurement's noise and waviness), the band is widened until the gap at its
/// edges reaches the band.
double
band_width(const PairZone &z, double span)
{
  const ContactCellOptions &o      = z.o;
  double                    w_band = std::sqrt(2 * o.gap_band / z.k_max);
  for (int it = 0; it < 8 && w_band < span / 2; ++it)
    {
      double opening = HUGE_VAL;
      for (double side : {-1.0, 1.0})
        {
          ContactCell probe;
          if (z.gap_at(z.c.position + side * w_band * z.e_s, side * w_band, 0, probe))
            opening = std::min(opening, probe.gap - z.c.separation);
        }
      if (opening == HUGE_VAL || opening >= o.gap_band / 2)
        break;
      w_band *= std::min(4.0, std::sqrt(o.gap_band / std::max(opening, 1e-6 * o.gap_band)));
    }
  return w_band;
}

/// The zone's extent along the line [t0, t1], and whether each end is the band's (the gap on
/// the line opening beyond it) rather than the flank's edge.
struct Extent
{
  double t0 = 0, t1 = 0;
  bool   band_end[2] = {false, false};
  /// How far the columns crowd towards each end (0 ... 1): 1 where the line reaches a flank's
  /// edge with the gap there inside the contact (below a quarter of the band, where the
  /// contact's edge sits: a line contact's pressure peaks at the edge), falling linearly to 0 as
  /// that gap opens to the band (the contact stops short of the edge) - and so continuous as
  /// the end passes from the flank's edge to the band's.
  double grading[2] = {0, 0};
};

Extent
extent_along(const PairZone &z, double span, double w)
{
  const PairContact        &c = z.c;
  const ContactCellOptions &o = z.o;
  // Extent along the line: where the projection leaves the flank (bisection both ways). For a
  // contact point on an edge of a flank, where the columns leave it: a column is on the
  // flank where any point of it across the band is (the straight line through a point on an
  // edge that curves - a crowned pinion's tip - leaves the flank near the point, while the
  // columns beside it still meet the edge), so the farthest of nine lines parallel to the
  // contact line across the band. Each line's last point on the flank is bracketed from a
  // scan at eighths of the flank's span (its domain is convex along a line), then bisected.
  auto on_pinion = [&](double s_, double t_) {
    return bool(
        project(z.flank, z.assembly, z.phi, c.position + s_ * z.e_s + t_ * z.e_t, c.u1, c.v1));
  };
  auto exit = [&](double s_, double direction, int scan) {
    double in = 0, out = span;
    for (int k = scan; k >= 0; --k)
      if (on_pinion(s_, direction * span * k / scan))
        {
          if (k == scan)
            return span;
          in = span * k / scan, out = span * (k + 1) / scan;
          break;
        }
      else if (k == 0)
        return -1.0; // the line misses the flank
    for (int it = 0; it < 40; ++it)
      {
        const double mid                            = (in + out) / 2;
        (on_pinion(s_, direction * mid) ? in : out) = mid;
      }
    return in;
  };
  auto reach = [&](double direction) {
    if (!c.edge)
      return std::max(0.0, exit(0, direction, 1));
    double farthest = 0;
    for (const double s_ : {0.0, -w / 4, w / 4, -w / 2, w / 2, -3 * w / 4, 3 * w / 4, -w, w})
      farthest = std::max(farthest, exit(s_, direction, 8));
    return farthest;
  };
  Extent x;
  double t0 = -reach(-1), t1 = reach(+1);
  // Along the line the zone ends at the flank's edges, or where the gap on the line opens
  // beyond twice the band (crowning: a point contact): there its end column is a zone edge.
  auto across      = [&](int j) { return (j % 2 ? 1 : -1) * ((j + 1) / 2) * w / 8; };
  auto gap_on_line = [&](double t_) {
    // on the line, else (a contact on an edge: the line just off the flank) from the
    // column's points on both flanks, less the opening across, k_max s^2 / 2 (at most an
    // underestimate: the zone grows rather than shrinks)
    ContactCell probe;
    double      least = HUGE_VAL;
    for (int j = 0; j <= (c.edge ? 16 : 0) && !(j == 1 && least < HUGE_VAL); ++j)
      if (z.gap_at(c.position + across(j) * z.e_s + t_ * z.e_t, across(j), t_, probe))
        least = std::min(least, probe.gap - z.k_max * across(j) * across(j) / 2);
    return least == HUGE_VAL ? -HUGE_VAL : least - c.separation;
  };
  auto within_band = [&](double t_) { return gap_on_line(t_) <= 2 * o.gap_band; };
  // The gap at an end of the line, for the columns' grading: where the end's point falls just
  // off the other flank (the line's end found on the pinion's flank, to rounding), a little
  // inside it - by fractions of the extent, so alike at every scale.
  auto gap_at_end = [&](double t_) {
    double g = -HUGE_VAL;
    for (const double back : {0.0, 1e-9, 1e-6, 1e-4, 1e-3, 1e-2})
      if ((g = gap_on_line(t_ * (1 - back))) > -HUGE_VAL)
        break;
    return g;
  };
  for (int e = 0; e < 2; ++e)
    {
      double &end = e == 0 ? t0 : t1;
      if (within_band(end))
        {
          if (o.along_grading > 0)
            x.grading[e] =
                std::clamp((o.gap_band - gap_at_end(end)) / (0.75 * o.gap_band), 0.0, 1.0);
          continue;
        }
      double in = 0, out = end;
      for (int it = 0; it < 40 && std::abs(out - in) > 1e-9 * (t1 - t0); ++it)
        {
          const double mid              = (in + out) / 2;
          (within_band(mid) ? in : out) = mid;
        }
      end = out, x.band_end[e] = true;
    }
  x.t0 = t0, x.t1 = t1;
  return x;
}

/// The edge j (0 ... cells_along) between columns along the line, graded towards the ends by
/// the extent's weights: a blend of uniform spacing, cosine spacing (both ends graded) and a
/// quarter cosine (one end), each weighted by the ends' gradings - a convex combination of
/// increasing maps of [0, 1] onto itself, and continuous in the weights.
double
along_edge(const Extent &x, const ContactCellOptions &o, int j)
{
  const double xi = double(j) / o.cells_along, q = pi / 2 * xi;
  const double a0 = o.along_grading * x.grading[0], a1 = o.along_grading * x.grading[1];
  const double both = (1 - std::cos(pi * xi)) / 2, to0 = 1 - std::cos(q), to1 = std::sin(q);
  const double f =
      a0 * a1 * both + a0 * (1 - a1) * to0 + (1 - a0) * a1 * to1 + (1 - a0) * (1 - a1) * xi;
  return x.t0 + (x.t1 - x.t0) * f;
}

/// The cells of column i (of the pair k) on both flanks, appended to `cells`: dt and ds the
/// cells' sizes along and across, w the band's half width (w_band: before the flank's span
/// cut it).
void
add_column(const PairZone &z, std::size_t k, int i, const Extent &extent, double ds, double w,
           double w_band, std::vector<ContactCell> &cells)
{
  const PairContact        &c        = z.c;
  const ContactCellOptions &o        = z.o;
  const auto               &band_end = extent.band_end;
  const double              ta = along_edge(extent, o, i), tb = along_edge(extent, o, i + 1);
  const double              t_cell = (ta + tb) / 2, dt = tb - ta;
  // The column's part on both flanks, [s_lo, s_hi] within the band: where an edge of
  // either flank (a tip) crosses the band, the column's cells share the part on the
  // flanks - cells kept or dropped whole by their centres would gain or lose a row in
  // steps as the contact line moves towards the edge, and a contact at a tip's corner
  // (half its band off the flank) would lose half its resolution across.
  ContactCell probe;
  auto        on = [&](double s_) {
    return z.gap_at(c.position + s_ * z.e_s + t_cell * z.e_t, s_, t_cell, probe);
  };
  // a point of the column on both flanks: the contact line, else (a contact point on
  // an edge, where rounding can put the line just off) the nearest of the band's grid
  double s_in  = 0;
  bool   found = on(s_in);
  for (int j = 1; j < o.cells_across && !found; ++j)
    s_in = (j % 2 ? 1 : -1) * ((j + 1) / 2) * ds, found = on(s_in);
  if (!found)
    return;
  double       s_lo = -w, s_hi = w;
  const double tol = 1e-4 * ds;
  for (double side : {-1.0, 1.0})
    {
      if (on(side * w))
        continue;
      double in = s_in, out = side * w;
      while (std::abs(out - in) > tol)
        {
          const double mid     = (in + out) / 2;
          (on(mid) ? in : out) = mid;
        }
      (side < 0 ? s_lo : s_hi) = in;
    }
  if (!(s_hi - s_lo > 1e-3 * ds))
    return; // the column only grazes the flanks
  // Cut columns grade their cells towards the cut (half way to sine spacing, blended in
  // as the cut reaches the contact line: the cell at the edge about half the others),
  // where the pressure of a contact at a tip's corner peaks.
  const bool   cut  = s_lo > -w || s_hi < w;
  const double lo   = cut ? s_lo : -w;
  const double span = cut ? s_hi - s_lo : 2 * w;
  const double g_hi = std::min(1.0, (w - s_hi) / w), g_lo = std::min(1.0, (w + s_lo) / w);
  auto         edge = [&](int j) {
    const double x = double(j) / o.cells_across, q = pi / 2 * x;
    return lo + span * (x + (g_hi * (std::sin(q) - x) + g_lo * (1 - std::cos(q) - x)) / 2);
  };
  for (int j = 0; j < o.cells_across; ++j)
    {
      const double a = cut ? edge(j) : -w + j * ds, b = cut ? edge(j + 1) : -w + (j + 1) * ds,
                   s_cell = cut ? (a + b) / 2 : -w + (j + 0.5) * ds, size = cut ? b - a : ds;
      ContactCell cell;
      cell.pair = int(k), cell.pinion_tooth = c.pinion_tooth, cell.gear_tooth = c.gear_tooth;
      cell.column = i, cell.dt = dt, cell.ds = size;
      cell.zone_edge = (w == w_band && (a <= -w + tol || b >= w - tol)) ||
                       (i == 0 && band_end[0]) || (i == o.cells_along - 1 && band_end[1]);
      cell.flank_edge = (i == 0 && !band_end[0]) || (i == o.cells_along - 1 && !band_end[1]) ||
                        (cut && ((s_lo > -w && a <= s_lo + tol) || (s_hi < w && b >= s_hi - tol)));
      if (!z.gap_at(c.position + s_cell * z.e_s + t_cell * z.e_t, s_cell, t_cell, cell))
        continue;
      cell.table_u1 = cell.u1, cell.table_v1 = cell.v1;
      cell.table_u2 = cell.u2, cell.table_v2 = cell.v2;
      cell.lever = pinion_lever(cell.position, cell.normal);
      cells.push_back(cell);
    }
}
} // namespace

std::vector<ContactCell>
contact_cells(const UnloadedTca &tca, const TcaPosition &position, const ContactCellOptions &o)
{
  if (!(o.cells_across >= 1 && o.cells_along >= 1 && o.gap_band > 0))
    throw InputError("contact cells: cells across and along must be >= 1 and the gap band > 0");
  std::vector<ContactCell> cells;
  for (std::size_t k = 0; k < position.pairs.size(); ++k)
    {
      const PairContact &c = position.pairs[k];
      if (!c.found || c.separation > std::max(o.gap_band, o.pair_gap))
        continue;
      PairZone z(tca, position, o, c);
      if (o.zone_from_gaps)
        fit_zone_to_gaps(z);
      const FlankDomain d    = z.flank.domain();
      const double      span = (z.flank.evaluate(d.u_max, d.v_max).position -
                           z.flank.evaluate(d.u_min, d.v_min).position)
                              .norm();
      const double w_band = band_width(z, span);
      const double w      = std::min(w_band, span / 2);
      const Extent x      = extent_along(z, span, w);
      const double ds     = 2 * w / o.cells_across;
      if (!(x.t1 - x.t0 > 0))
        continue; // the contact sits on a corner of the flank: no extent along the line
      for (int i = 0; i < o.cells_along; ++i)
        add_column(z, k, i, x, ds, w, w_band, cells);
    }
  return cells;
}
} // namespace gearkit

#include "dynamics/train_system.h"

#include "base/types.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace gearkit
{
namespace
{
/// IMPACT's damping coefficient STEP(d, 0, 0, d_max, c_max) at penetration d > 0, and its
/// derivative by d.
std::pair<double, double>
impact_damping(const ImpactLaw &law, double d)
{
  if (!(d < law.depth))
    return {law.damping, 0.0};
  const double x = d / law.depth;
  return {law.damping * x * x * (3 - 2 * x), law.damping * 6 * x * (1 - x) / law.depth};
}

/// IMPACT's force from its elastic part K d^e (given: the caller has it).
double
damped_impact_force(const ImpactLaw &law, double d, double d_rate, double elastic)
{
  if (!(d > 0))
    return 0;
  return std::max(0.0, elastic + impact_damping(law, d).first * d_rate);
}
} // namespace

double
impact_force(const ImpactLaw &law, double d, double d_rate)
{
  return damped_impact_force(law, d, d_rate, law.stiffness * std::pow(d, law.exponent));
}

double
impact_energy(const ImpactLaw &law, double d)
{
  return d > 0 ? law.stiffness * std::pow(d, law.exponent + 1) / (law.exponent + 1) : 0.0;
}

double
impact_stiffness_si(double stiffness, double exponent, double length_unit)
{
  return stiffness / std::pow(length_unit, exponent);
}

namespace
{
/// The cubic through values y0, y1 with slopes m0, m1 (by the local coordinate u in [0, 1]) in
/// powers of u.
std::array<double, 4>
hermite_coefficients(double y0, double y1, double m0, double m1)
{
  return {y0, m0, 3 * (y1 - y0) - 2 * m0 - m1, 2 * (y0 - y1) + m0 + m1};
}

/// The Hermite cubic of samples y on interval i in powers of its local coordinate u in [0, 1]
/// (slopes by central differences, one-sided at the ends; per sample step).
std::array<double, 4>
hermite_cubic(const std::vector<double> &y, std::size_t i)
{
  const std::size_t n = y.size();
  auto              m = [&](std::size_t j) {
    if (j == 0)
      return y[1] - y[0];
    if (j == n - 1)
      return y[n - 1] - y[n - 2];
    return (y[j + 1] - y[j - 1]) / 2;
  };
  return hermite_coefficients(y[i], y[i + 1], m(i), m(i + 1));
}
} // namespace

namespace train_internal
{
namespace
{
/// Pairing k's gap psi_touch - psi [rad] at local pinion angle `local` (its curve's offset
/// there): its penetration is s arm gap.
double
pairing_gap(const ToothPairTables &t, int k, double local, double offset, double psi)
{
  const double ratio = double(t.pinion_teeth) / t.gear_teeth;
  return 2 * pi * k / t.gear_teeth + ratio * local + offset - psi;
}

/// A point of a curve between kinks: local angle, offset, arm.
struct CurveNode
{
  double x, offset, arm;
};

/// The Hermite piece from a to b with slopes m (by the local angle) in powers of its local
/// coordinate u = (x - a.x) / (b.x - a.x).
std::array<double, 8>
hermite_piece(const CurveNode &a, const CurveNode &b, const double ma[2], const double mb[2])
{
  const double                w = b.x - a.x;
  const std::array<double, 4> o = hermite_coefficients(a.offset, b.offset, w * ma[0], w * mb[0]);
  const std::array<double, 4> r = hermite_coefficients(a.arm, b.arm, w * ma[1], w * mb[1]);
  return {o[0], o[1], o[2], o[3], r[0], r[1], r[2], r[3]};
}

/// The slopes (offset, arm) at x of the parabola through the three points of `f` (a smooth
/// segment's nodes, ordered) nearest x; a secant for two, zero for one.
void
parabola_slopes(const std::vector<CurveNode> &f, double x, double m[2])
{
  m[0] = m[1] = 0;
  if (f.size() < 2)
    return;
  if (f.size() == 2)
    {
      m[0] = (f[1].offset - f[0].offset) / (f[1].x - f[0].x);
      m[1] = (f[1].arm - f[0].arm) / (f[1].x - f[0].x);
      return;
    }
  const auto pos = std::lower_bound(f.begin(), f.end(), x,
                                    [](const CurveNode &n, double v) { return n.x < v; }) -
                   f.begin();
  const auto       i  = std::size_t(std::clamp<long>(long(pos) - 1, 0, long(f.size()) - 3));
  const CurveNode &p0 = f[i], &p1 = f[i + 1], &p2 = f[i + 2];
  for (int k = 0; k < 2; ++k)
    {
      auto         y   = [k](const CurveNode &n) { return k == 0 ? n.offset : n.arm; };
      const double d01 = (y(p1) - y(p0)) / (p1.x - p0.x), d12 = (y(p2) - y(p1)) / (p2.x - p1.x);
      const double d012 = (d12 - d01) / (p2.x - p0.x);
      m[k]              = d01 + d012 * ((x - p0.x) + (x - p1.x));
    }
}
} // namespace

CurveCubics::CurveCubics(const ToothPairCurve &c)
    : start(c.start)
    , step(c.step)
    , inverse_step(1 / c.step)
    , intervals(c.offset.size() >= 2 ? int(c.offset.size()) - 1 : 0)
{
  intervals_.assign(std::size_t(intervals), {0, HUGE_VAL});
  // the knots by interval: strictly inside one (it is split there), or on a sample (within
  // rounding: the sample is the kink)
  std::vector<const CurveKnot *> knot_in(std::size_t(intervals), nullptr),
      knot_on(std::size_t(intervals + 1), nullptr);
  for (const CurveKnot &k : c.knots)
    {
      const double s = (k.at - start) / step;
      const int    j = int(std::lround(s));
      if (std::abs(s - j) < 1e-9 && j >= 0 && j <= intervals)
        knot_on[std::size_t(j)] = &k;
      else if (const int i = int(std::floor(s)); i >= 0 && i < intervals)
        knot_in[std::size_t(i)] = &k;
    }
  auto none = [](const std::vector<const CurveKnot *> &v) {
    return std::none_of(v.begin(), v.end(), [](const CurveKnot *k) { return k; });
  };
  if (none(knot_in) && none(knot_on))
    {
      // no kink: the samples' Hermite cubics on the uniform grid (slopes by central
      // differences, one-sided at the ends; per sample step)
      for (int i = 0; i < intervals; ++i)
        {
          const std::array<double, 4> o = hermite_cubic(c.offset, std::size_t(i));
          const std::array<double, 4> a = hermite_cubic(c.arm, std::size_t(i));
          pieces.push_back(
              {{o[0], o[1], o[2], o[3], a[0], a[1], a[2], a[3]}, start + i * step, 1 / step});
          intervals_[std::size_t(i)].first = i;
        }
      return;
    }
  // smooth segments between the kinks, each interpolated on its own: slopes from the parabola
  // through the three nearest nodes of its segment (samples closer to a kink than a hundredth
  // of a step left out of the slopes: their differences would be rounding)
  std::vector<std::vector<CurveNode>> segments(1);
  for (int i = 0; i <= intervals; ++i)
    {
      const double x = start + i * step;
      if (const CurveKnot *k = knot_on[std::size_t(i)]; k && i > 0 && i < intervals)
        {
          segments.back().push_back({x, k->offset[0], k->arm[0]});
          segments.push_back({{x, k->offset[1], k->arm[1]}});
        }
      else
        segments.back().push_back({x, c.offset[std::size_t(i)], c.arm[std::size_t(i)]});
      if (i < intervals && knot_in[std::size_t(i)])
        {
          const CurveKnot &k = *knot_in[std::size_t(i)];
          segments.back().push_back({k.at, k.offset[0], k.arm[0]});
          segments.push_back({{k.at, k.offset[1], k.arm[1]}});
        }
    }
  const double near = step / 100;
  for (std::size_t s = 0; s < segments.size(); ++s)
    {
      const std::vector<CurveNode> &nodes = segments[s];
      std::vector<CurveNode>        fit;
      for (std::size_t j = 0; j < nodes.size(); ++j)
        {
          const bool end = j == 0 || j + 1 == nodes.size();
          if (end || ((s == 0 || nodes[j].x - nodes.front().x > near) &&
                      (s + 1 == segments.size() || nodes.back().x - nodes[j].x > near)))
            fit.push_back(nodes[j]);
        }
      for (std::size_t j = 0; j + 1 < nodes.size(); ++j)
        {
          double ma[2], mb[2];
          parabola_slopes(fit, nodes[j].x, ma);
          parabola_slopes(fit, nodes[j + 1].x, mb);
          const double w = nodes[j + 1].x - nodes[j].x;
          pieces.push_back({hermite_piece(nodes[j], nodes[j + 1], ma, mb), nodes[j].x, 1 / w});
        }
    }
  // each interval's first piece, and where a kink splits it
  std::size_t piece = 0;
  for (int i = 0; i < intervals; ++i)
    {
      intervals_[std::size_t(i)].first = int(piece);
      if (const CurveKnot *k = knot_in[std::size_t(i)])
        intervals_[std::size_t(i)].cut = k->at, piece += 2;
      else
        piece += 1;
    }
}

void
CurveCubics::slopes(const CurvePoint &p, double &offset_slope, double &arm_slope) const
{
  const double u = p.u, *c = p.a;
  offset_slope = ((3 * c[3] * u + 2 * c[2]) * u + c[1]) * p.inverse_width;
  arm_slope    = ((3 * c[7] * u + 2 * c[6]) * u + c[5]) * p.inverse_width;
}

void
CurveCubics::curvatures(const CurvePoint &p, double &offset_curvature, double &arm_curvature) const
{
  const double u = p.u, *c = p.a;
  offset_curvature = (6 * c[3] * u + 2 * c[2]) * (p.inverse_width * p.inverse_width);
  arm_curvature    = (6 * c[7] * u + 2 * c[6]) * (p.inverse_width * p.inverse_width);
}
} // namespace train_internal

namespace
{
/// The curve's offset at x; false outside the samples.
bool
interpolate_offset(const ToothPairCurve &c, double x, double &value)
{
  train_internal::CurvePoint p;
  if (!train_internal::CurveCubics(c).at(x, p))
    return false;
  value = p.offset;
  return true;
}
} // namespace

std::pair<double, double>
band_edges(const ToothPairTables &t)
{
  // the most common class of a member; -1 when none is more common than every other
  auto nominal = [](const std::vector<int> &classes, int count) {
    std::vector<int> n(std::size_t(std::max(count, 0)), 0);
    for (int c : classes)
      if (c >= 0 && c < count)
        ++n[std::size_t(c)];
    int best = -1, most = 0, ties = 0;
    for (int c = 0; c < count; ++c)
      if (n[std::size_t(c)] > most)
        best = c, most = n[std::size_t(c)], ties = 0;
      else if (n[std::size_t(c)] == most)
        ++ties;
    return ties > 0 ? -1 : best;
  };
  const int             p = nominal(t.pinion_class, t.pinion_classes);
  const int             g = nominal(t.gear_class, t.gear_classes);
  const ToothPairCurve *d = &t.curve(drive_side, 0, mod(-1, t.gear_teeth));
  const ToothPairCurve *c = &t.curve(coast_side, 0, 0);
  if (p >= 0 && g >= 0 &&
      !t.curves[drive_side][std::size_t(p * t.gear_classes + g)].offset.empty() &&
      !t.curves[coast_side][std::size_t(p * t.gear_classes + g)].offset.empty())
    {
      d = &t.curves[drive_side][std::size_t(p * t.gear_classes + g)];
      c = &t.curves[coast_side][std::size_t(p * t.gear_classes + g)];
    }
  double v[2] = {0, 0};
  if (!interpolate_offset(*d, 0.0, v[0]) || !interpolate_offset(*c, 0.0, v[1]))
    require_value(false, "Train mesh", "tooth pair curves at the pitch point", 0,
                  "curves that cover the pairing's centre (local angle 0)");
  return {v[0], v[1]};
}

double
band_centre(const ToothPairTables &t)
{
  const auto [drive, coast] = band_edges(t);
  return (drive + coast) / 2;
}

namespace
{

/// A finite-element mesh stiffness at pinion angle phi and its derivative by phi (periodic over
/// the mesh cycle, linear between the samples).
std::pair<double, double>
mesh_stiffness_at(const TrainMesh &m, double phi)
{
  const std::vector<double> &K    = m.mesh_stiffness;
  const int                  n    = int(K.size());
  const double               step = 2 * pi / m.teeth.pinion_teeth / n;
  const double               s    = (phi - m.mesh_stiffness_start) / step;
  const double               f    = std::floor(s);
  const int                  i    = mod(int(std::fmod(f, double(n))), n);
  const double               u    = s - f;
  const double               a = K[std::size_t(i)], b = K[std::size_t((i + 1) % n)];
  return {a + u * (b - a), (b - a) / step};
}
} // namespace

namespace train_internal
{
TrainSystem::TrainSystem(const TrainModel &m, const TrainRunOptions &o)
    : model(m)
    , options(o)
{
  n = int(model.bodies.size());
  for (const TrainMesh &mesh : model.meshes)
    {
      centre.push_back(band_centre(mesh.teeth));
      std::array<std::vector<CurveCubics>, 2> &tables = cubics.emplace_back();
      std::vector<Kink>                       &kinks  = kink_list.emplace_back();
      const double                             pitch  = 2 * pi / mesh.teeth.pinion_teeth;
      for (int side = 0; side < 2; ++side)
        for (const ToothPairCurve &c : mesh.teeth.curves[std::size_t(side)])
          {
            tables[std::size_t(side)].emplace_back(c);
            for (const CurveKnot &k : c.knots)
              {
                const double phase = k.at - pitch * std::floor(k.at / pitch);
                if (std::none_of(kinks.begin(), kinks.end(), [&](const Kink &o) {
                      return o.side == side &&
                             std::abs(std::remainder(o.at - phase, pitch)) < 1e-9 * pitch;
                    }))
                  kinks.push_back({side, phase, std::cos(mesh.teeth.pinion_teeth * phase / 2),
                                   std::sin(mesh.teeth.pinion_teeth * phase / 2)});
              }
          }
      // the local pinion angles any curve has samples at
      std::pair<double, double> span{HUGE_VAL, -HUGE_VAL};
      for (const auto &side : mesh.teeth.curves)
        for (const ToothPairCurve &c : side)
          if (c.offset.size() >= 2)
            span = {std::min(span.first, c.start),
                    std::max(span.second, c.start + double(c.offset.size() - 1) * c.step)};
      sampled.push_back(span);
    }
}

const CurveCubics &
TrainSystem::curve(int index, int side, int k) const
{
  const ToothPairTables &t = model.meshes[std::size_t(index)].teeth;
  const int              i = mod(-k, t.pinion_teeth);
  const int              j = mod(side == drive_side ? k - 1 : k, t.gear_teeth);
  return cubics[std::size_t(index)][std::size_t(side)][std::size_t(
      t.pinion_class[std::size_t(i)] * t.gear_classes + t.gear_class[std::size_t(j)])];
}

namespace
{
/// The deepest touching pair of a mesh's side (a finite-element K_m acts on it alone): its
/// approach d, d's derivatives by the pinion and gear angles, its rate and d'' less the angles'
/// accelerations' part.
struct DeepestPair
{
  double d = 0, dd_dphi = 0, dd_dpsi = 0, rate = 0, curvature = 0;
};

/// One touching pair's IMPACT force (approach d > 0, its rate and derivatives as DeepestPair's)
/// added to the mesh's torques and force; with `outputs` its energy and the rates that locate
/// the force's peaks as well.
void
add_impact_pair(const ImpactLaw &law, int side, double d, double d_rate, double dd_dphi,
                double dd_dpsi, double curvature, bool outputs, MeshEval &e)
{
  const double elastic = law.stiffness * std::pow(d, law.exponent);
  const double F       = damped_impact_force(law, d, d_rate, elastic);
  e.torque_driver -= F * dd_dphi;
  e.torque_driven -= F * dd_dpsi;
  e.force[side] += F;
  e.dissipation_rate += (F - elastic) * d_rate;
  if (!outputs)
    return;
  e.energy += elastic * d / (law.exponent + 1); // impact_energy
  e.penetration_rate += elastic / d * d_rate;
  e.penetration_weight += elastic / d;
  if (F > 0)
    {
      const auto [c_d, dc_dd] = impact_damping(law, d);
      e.rate_fixed[side] +=
          law.exponent * elastic / d * d_rate + dc_dd * d_rate * d_rate + c_d * curvature;
      e.rate_driver[side] += c_d * dd_dphi;
      e.rate_driven[side] += c_d * dd_dpsi;
    }
}

/// The finite-element mesh stiffness's force on each side's deepest pair (linear in its
/// approach, K_m at the pinion angle phi) added to the mesh's torques, force and energy.
void
add_stiffness_forces(const TrainMesh &m, double phi, double w_p, const DeepestPair (&deepest)[2],
                     MeshEval &e)
{
  const auto [K, dK_dphi] = mesh_stiffness_at(m, phi);
  const ImpactLaw linear{K, 1.0, m.law.damping, m.law.depth};
  for (int side = 0; side < 2; ++side)
    {
      const DeepestPair &p = deepest[side];
      if (!(p.d > 0))
        continue;
      const double F = impact_force(linear, p.d, p.rate);
      e.torque_driver -= F * p.dd_dphi;
      e.torque_driven -= F * p.dd_dpsi;
      e.force[side] += F;
      e.energy += K * p.d * p.d / 2;
      e.dissipation_rate += (F - K * p.d) * p.rate;
      e.parametric_power += dK_dphi * w_p * p.d * p.d / 2;
      e.penetration_rate += K * p.rate;
      e.penetration_weight += K;
      if (F > 0)
        {
          const auto [c, dc_dd] = impact_damping(linear, p.d);
          e.rate_fixed[side] +=
              dK_dphi * w_p * p.d + K * p.rate + dc_dd * p.rate * p.rate + c * p.curvature;
          e.rate_driver[side] += c * p.dd_dphi;
          e.rate_driven[side] += c * p.dd_dpsi;
        }
    }
}
} // namespace

MeshEval
TrainSystem::mesh(int index, const double *theta, const double *omega, MeshDetail detail) const
{
  const TrainMesh       &m   = model.meshes[index];
  const ToothPairTables &t   = m.teeth;
  const double           phi = theta[m.driver] + m.pinion_angle_0;
  const double           psi = theta[m.driven] + m.gear_angle_0;
  const double           w_p = omega[m.driver], w_g = omega[m.driven];
  const double           ratio   = double(t.pinion_teeth) / t.gear_teeth;
  const bool             outputs = detail != MeshDetail::forces;
  MeshEval               e;
  const int              k0 = int(std::lround(phi * t.pinion_teeth / (2 * pi)));
  const bool             fe = !m.mesh_stiffness.empty();
  DeepestPair            deepest[2]; // of each side (finite-element K_m)
  /// the deepest pairing of each side, for its rate (MeshDetail::deepest_rates)
  struct Nearest
  {
    const CurveCubics *curve = nullptr;
    CurvePoint         p;
    double             gap = 0, rate = 0;
    bool               has_rate = false;
  } nearest[2];
  // the pairings within reach whose local angle phi - 2 pi k / z1 some curve samples
  const double per_tooth = t.pinion_teeth / (2 * pi);
  const auto [lo, hi]    = sampled[std::size_t(index)];
  const int k_first =
      std::max(k0 - options.pairings_each_side, int(std::ceil((phi - hi) * per_tooth - 1e-9)));
  const int k_last =
      std::min(k0 + options.pairings_each_side, int(std::floor((phi - lo) * per_tooth + 1e-9)));
  for (int k = k_first; k <= k_last; ++k)
    {
      const double phi_k = phi - 2 * pi * k / t.pinion_teeth;
      for (int side = 0; side < 2; ++side)
        {
          const CurveCubics &c = curve(index, side, k);
          CurvePoint         p;
          if (!c.at(phi_k, p))
            continue;
          // d = s arm(phi_k) (psi_touch(phi_k) - psi); the derivatives only where it touches
          const double gap            = pairing_gap(t, k, phi_k, p.offset, psi);
          const double s              = side == drive_side ? 1.0 : -1.0;
          const double d              = s * p.arm * gap;
          bool         deepest_so_far = false;
          if (outputs)
            {
              double &p1 = e.max_penetration[side], &p2 = e.next_penetration[side][0],
                     &p3 = e.next_penetration[side][1];
              if ((deepest_so_far = d > p1))
                {
                  p3 = p2, p2 = p1, p1 = d;
                  if (detail == MeshDetail::deepest_rates)
                    nearest[side] = {&c, p, gap, 0, false};
                }
              else if (d > p2)
                p3 = p2, p2 = d;
              else
                p3 = std::max(p3, d);
            }
          if (!(d > 0))
            continue;
          double o_slope, arm_slope;
          c.slopes(p, o_slope, arm_slope);
          const double dd_dphi = s * (arm_slope * gap + p.arm * (ratio + o_slope));
          const double dd_dpsi = -s * p.arm;
          const double d_rate  = dd_dphi * w_p + dd_dpsi * w_g;
          if (detail == MeshDetail::deepest_rates && deepest_so_far)
            nearest[side].rate = d_rate, nearest[side].has_rate = true;
          // d'' = d_phi phi'' + d_psi psi'' + curvature, curvature = d_phiphi phi'^2 +
          // 2 d_phipsi phi' psi'
          double curvature = 0;
          if (outputs)
            {
              double o_curvature, arm_curvature;
              c.curvatures(p, o_curvature, arm_curvature);
              curvature = s *
                              (arm_curvature * gap + 2 * arm_slope * (ratio + o_slope) +
                               p.arm * o_curvature) *
                              w_p * w_p -
                          2 * s * arm_slope * w_p * w_g;
            }
          ++e.pairs;
          if (fe)
            {
              if (d > deepest[side].d)
                deepest[side] = {d, dd_dphi, dd_dpsi, d_rate, curvature};
              continue;
            }
          add_impact_pair(m.law, side, d, d_rate, dd_dphi, dd_dpsi, curvature, outputs, e);
        }
    }
  for (int side = 0; detail == MeshDetail::deepest_rates && side < 2; ++side)
    {
      const Nearest &q = nearest[side];
      if (!q.curve || q.has_rate)
        {
          e.deepest_rate[side] = q.rate;
          continue;
        }
      double       o_slope, arm_slope;
      const double s = side == drive_side ? 1.0 : -1.0;
      q.curve->slopes(q.p, o_slope, arm_slope);
      e.deepest_rate[side] =
          s * (arm_slope * q.gap + q.p.arm * (ratio + o_slope)) * w_p - s * q.p.arm * w_g;
    }
  if (fe)
    add_stiffness_forces(m, phi, w_p, deepest, e);
  return e;
}

void
TrainSystem::kink_roots(int index, const double *theta, double *g) const
{
  const TrainMesh &m = model.meshes[std::size_t(index)];
  const double     a = m.teeth.pinion_teeth * (theta[m.driver] + m.pinion_angle_0) / 2;
  const double     s = std::sin(a), c = std::cos(a);
  for (const Kink &k : kink_list[std::size_t(index)])
    *g++ = s * k.cosine - c * k.sine; // sin(a - z1 at / 2)
}

bool
TrainSystem::kink_touches(int index, int k, const double *theta) const
{
  const TrainMesh       &m     = model.meshes[std::size_t(index)];
  const ToothPairTables &t     = m.teeth;
  const Kink            &kink  = kink_list[std::size_t(index)][std::size_t(k)];
  const double           pitch = 2 * pi / t.pinion_teeth;
  const double           phi   = theta[m.driver] + m.pinion_angle_0;
  const double           psi   = theta[m.driven] + m.gear_angle_0;
  // the pairing at the kink (its local angle phi - pitch k nearest the kink's phase), its
  // penetration there (continuous through the kink)
  const int          pairing = int(std::lround((phi - kink.at) / pitch));
  const CurveCubics &c       = curve(index, kink.side, pairing);
  CurvePoint         p;
  const double       local = phi - pitch * pairing;
  if (!c.at(local, p))
    return false;
  const double gap = pairing_gap(t, pairing, local, p.offset, psi);
  return (kink.side == drive_side ? 1.0 : -1.0) * p.arm * gap > 0;
}

double
TrainSystem::relative(int index, const double *theta) const
{
  const TrainMesh &m     = model.meshes[index];
  const double     ratio = double(m.teeth.pinion_teeth) / m.teeth.gear_teeth;
  const double     phi = theta[m.driver] + m.pinion_angle_0, psi = theta[m.driven] + m.gear_angle_0;
  return m.gear_base_radius * (ratio * phi + centre[index] - psi);
}

void
TrainSystem::evaluate(double t, const double *theta, const double *omega, double *alpha,
                      double &power, double &dissipation, std::vector<MeshEval> *evaluated,
                      bool deepest_rates) const
{
  double              fixed[16] = {};
  std::vector<double> more(n > 16 ? std::size_t(n) : 0, 0.0);
  double *const       Q = n > 16 ? more.data() : fixed;
  dissipation           = 0;
  double parametric     = 0;
  if (evaluated)
    evaluated->resize(model.meshes.size());
  for (int i = 0; i < int(model.meshes.size()); ++i)
    {
      const MeshEval e = mesh(i, theta, omega,
                              !evaluated      ? MeshDetail::forces
                              : deepest_rates ? MeshDetail::deepest_rates
                                              : MeshDetail::outputs);
      if (evaluated)
        (*evaluated)[std::size_t(i)] = e;
      Q[model.meshes[i].driver] += e.torque_driver;
      Q[model.meshes[i].driven] += e.torque_driven;
      dissipation += e.dissipation_rate;
      parametric += e.parametric_power;
    }
  for (const TrainShaft &s : model.shafts)
    {
      const double dw = omega[s.b] - omega[s.a];
      const double T  = s.stiffness * (theta[s.b] - theta[s.a]) + s.damping * dw;
      Q[s.a] += T;
      Q[s.b] -= T;
      dissipation += s.damping * dw * dw;
    }
  power = parametric;
  for (int i = 0; i < n; ++i)
    {
      const TrainBody &b = model.bodies[i];
      double           J = b.inertia, dJ = 0, external = 0;
      if (b.has_crank)
        {
          const auto [Jc, dJc] = b.crank.inertia(theta[i] + b.crank.crank_angle_0);
          J += Jc, dJ = dJc;
          external -=
              b.crank.piston_force * b.crank.piston(theta[i] + b.crank.crank_angle_0).second;
        }
      if (b.constant_speed)
        {
          alpha[i] = 0; // held by the torque that balances the rest
          power += (dJ * omega[i] * omega[i] / 2 - Q[i]) * omega[i];
          continue;
        }
      external += b.torque(t, omega[i]);
      power += external * omega[i];
      alpha[i] = (external + Q[i] - dJ * omega[i] * omega[i] / 2) / J;
    }
}

double
TrainSystem::kinetic(const double *theta, const double *omega) const
{
  double E = 0;
  for (int i = 0; i < n; ++i)
    {
      const TrainBody &b = model.bodies[i];
      double           J = b.inertia;
      if (b.has_crank)
        J += b.crank.inertia(theta[i] + b.crank.crank_angle_0).first;
      E += J * omega[i] * omega[i] / 2;
    }
  return E;
}

double
TrainSystem::potential(const double *theta, const double *omega) const
{
  double V = 0;
  for (int i = 0; i < int(model.meshes.size()); ++i)
    V += mesh(i, theta, omega).energy;
  for (const TrainShaft &s : model.shafts)
    V += s.stiffness * std::pow(theta[s.b] - theta[s.a], 2) / 2;
  return V;
}
} // namespace train_internal
} // namespace gearkit

#include "geometry/flank_distance.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gearkit
{
FlankFoot
flank_foot(const MemberFlanks &member, int tooth, FlankSide side, const Vec3 &x)
{
  const Flank      &flank = member.flank(tooth, side);
  const FlankDomain d     = flank.domain();
  auto [u, v]             = member.guess(tooth, side, x.head<2>().norm(), x.z());
  FlankPoint p            = flank.evaluate(u, v);
  bool       edge         = false;
  // Gauss-Newton on (x - r(u, v)) . r_u = (x - r(u, v)) . r_v = 0: quadratic near the foot on
  // these smooth surfaces; 30 steps are far more than the ~5 a micrometre needs.
  for (int it = 0; it < 30; ++it)
    {
      Eigen::Matrix2d J;
      J << p.d_du.dot(p.d_du), p.d_du.dot(p.d_dv), p.d_dv.dot(p.d_du), p.d_dv.dot(p.d_dv);
      const Vec3            r = x - p.position;
      const Eigen::Vector2d g(p.d_du.dot(r), p.d_dv.dot(r));
      const Eigen::Vector2d step = J.ldlt().solve(g);
      const double          un   = std::clamp(u + step(0), d.u_min, d.u_max);
      const double          vn   = std::clamp(v + step(1), d.v_min, d.v_max);
      edge                       = un != u + step(0) || vn != v + step(1);
      const bool converged       = std::abs(un - u) <= 1e-12 * (d.u_max - d.u_min) &&
                             std::abs(vn - v) <= 1e-12 * (d.v_max - d.v_min);
      u = un, v = vn;
      p = flank.evaluate(u, v);
      if (converged)
        break;
    }
  FlankFoot f;
  f.u = u, f.v = v, f.position = p.position, f.normal = p.normal, f.on_edge = edge;
  const Vec3   r      = x - p.position;
  const double normal = r.dot(p.normal);
  f.signed_distance   = edge ? std::copysign(r.norm(), normal) : normal;
  return f;
}

namespace
{
std::string
str(double x)
{
  std::ostringstream s;
  s << x;
  return s.str();
}

double
median(std::vector<double> v)
{
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}
} // namespace

void
check_measurement(const MeasuredMember &measured, const MemberFlanks &nominal, double tolerance,
                  const std::string &source, const std::string &tolerance_parameter)
{
  // 1. Units: the radii of the measured points against the nominal flanks' radii. A factor
  //    of 1000 or 25.4 between them is a unit mistake, not a measurement.
  std::vector<double> measured_radii, nominal_radii;
  for (const MeasuredFlank &f : measured.flanks)
    {
      for (const Vec3 &x : f.points)
        measured_radii.push_back(x.head<2>().norm());
      if (!nominal.has(f.tooth, f.side))
        continue;
      const FlankDomain d = nominal.flank(f.tooth, f.side).domain();
      for (const double u : {d.u_min, 0.5 * (d.u_min + d.u_max), d.u_max})
        nominal_radii.push_back(nominal.flank(f.tooth, f.side)
                                    .evaluate(u, 0.5 * (d.v_min + d.v_max))
                                    .position.head<2>()
                                    .norm());
    }
  if (measured_radii.empty() || nominal_radii.empty())
    return;
  const double r_measured = median(measured_radii);
  const double r_nominal  = median(nominal_radii);
  for (const auto &[factor, what] : {std::pair{1e-3, "metres written as millimetres"},
                                     {1e3, "millimetres written as metres"},
                                     {1 / 25.4, "inches written as millimetres"},
                                     {25.4, "millimetres written as inches"}})
    if (std::abs(r_measured / factor / r_nominal - 1) < 0.2)
      throw InputError(source + ": the points' median radius is " + str(r_measured * 1e3) +
                       " mm where the member's flanks lie at " + str(r_nominal * 1e3) +
                       " mm: the coordinates look like " + what +
                       "; expected the units the header states");

  // 2. Every point near its flank, and on the side its block names.
  for (const MeasuredFlank &f : measured.flanks)
    {
      const std::string flank =
          source + ": tooth " + std::to_string(f.tooth) + " " + to_string(f.side) + " flank";
      const FlankSide other = f.side == FlankSide::drive ? FlankSide::coast : FlankSide::drive;
      std::size_t     far = 0, nearer_other = 0, against = 0, worst = 0;
      double          worst_distance = 0;
      for (std::size_t k = 0; k < f.points.size(); ++k)
        {
          const FlankFoot foot = flank_foot(nominal, f.tooth, f.side, f.points[k]);
          const double    dist = std::abs(foot.signed_distance);
          if (dist > tolerance)
            {
              ++far;
              if (nominal.has(f.tooth, other) &&
                  std::abs(flank_foot(nominal, f.tooth, other, f.points[k]).signed_distance) <=
                      tolerance)
                ++nearer_other;
            }
          if (!f.normals.empty() && f.normals[k].dot(foot.normal) < 0)
            ++against;
          if (dist > worst_distance)
            worst_distance = dist, worst = k;
        }
      if (far > 0 && nearer_other == far)
        throw InputError(flank + ": its points lie on the tooth's " + to_string(other) +
                         " flank, not on its " + to_string(f.side) +
                         " flank; are the drive and coast labels swapped? (side: the drive flank's "
                         "outward normal points in +theta, docs/cmm-format.md)");
      if (against > f.points.size() / 2)
        throw InputError(flank + ": " + std::to_string(against) + " of " +
                         std::to_string(f.points.size()) +
                         " probe normals point into the tooth (against the nominal flank's "
                         "outward normal); expected outward normals on the named side");
      if (far > 0)
        throw InputError(flank + ", point " + std::to_string(worst) + " (profile " +
                         std::to_string(worst / std::size_t(std::max(f.n_face, 1))) + ", face " +
                         std::to_string(worst % std::size_t(std::max(f.n_face, 1))) + ") lies " +
                         str(worst_distance * 1e6) + " um from the nominal flank (" +
                         std::to_string(far) + " points beyond the tolerance); allowed: within " +
                         str(tolerance * 1e6) + " um (" + tolerance_parameter + ")");
    }
}
} // namespace gearkit

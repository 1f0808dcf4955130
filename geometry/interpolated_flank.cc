#include "interpolated_flank.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gearkit
{
namespace
{
// A cubic B-spline through equally spaced values (unit spacing) with 4th-order one-sided
// end derivatives: Boost 1.74's own end-derivative estimate is wrong at the right end (errors of
// 1e-2 on sin(0.3 x) at 9 points, against 1e-5 with these).
boost::math::interpolators::cardinal_cubic_b_spline<double>
spline_through(const std::vector<double> &y)
{
  const std::size_t n    = y.size();
  const double      left = (-25 * y[0] + 48 * y[1] - 36 * y[2] + 16 * y[3] - 3 * y[4]) / 12;
  const double      right =
      (25 * y[n - 1] - 48 * y[n - 2] + 36 * y[n - 3] - 16 * y[n - 4] + 3 * y[n - 5]) / 12;
  return {y.data(), n, 0.0, 1.0, left, right};
}
} // namespace

InterpolatedFlank::InterpolatedFlank(const MeasuredFlank &f)
    : n_profile(f.n_profile)
    , n_face(f.n_face)
{
  if (n_profile < 5 || n_face < 5)
    throw InputError("interpolating the measured flank of tooth " + std::to_string(f.tooth) + " " +
                     to_string(f.side) + ": grid " + std::to_string(n_profile) + " x " +
                     std::to_string(n_face) + " is too small; expected at least 5 x 5 points");
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < n_profile; ++i)
      {
        std::vector<double> row(n_face);
        for (int j = 0; j < n_face; ++j)
          row[j] = f.points[std::size_t(i) * n_face + j][c];
        rows[c].push_back(spline_through(row));
      }
  // Outward: drive flanks face +theta, coast flanks -theta (types.h).
  const FlankPoint centre = evaluate(0.5 * (n_profile - 1), 0.5 * (n_face - 1));
  const Vec3       e_theta(-centre.position.y(), centre.position.x(), 0);
  if ((f.side == FlankSide::drive ? 1 : -1) * centre.normal.dot(e_theta) < 0)
    orientation = -1;
}

FlankDomain
InterpolatedFlank::domain() const
{
  return {0, double(n_profile - 1), 0, double(n_face - 1)};
}

FlankPoint
InterpolatedFlank::evaluate(double u, double v) const
{
  // Outside the grid (Newton iterates may step there) the surface continues linearly from its
  // edge, so the interpolant is C1 everywhere and never read out of range.
  FlankPoint p;
  if (!std::isfinite(u) || !std::isfinite(v))
    {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      p.position = p.normal = p.d_du = p.d_dv = Vec3::Constant(nan);
      return p;
    }
  const double uc = std::clamp(u, 0.0, double(n_profile - 1));
  const double vc = std::clamp(v, 0.0, double(n_face - 1));
  // Along the face within each profile row (precomputed splines), then across the rows through
  // those values (and through their face derivatives for d/dv).
  std::vector<double> value(n_profile), slope(n_profile);
  for (int c = 0; c < 3; ++c)
    {
      for (int i = 0; i < n_profile; ++i)
        {
          value[i] = rows[c][i](vc);
          slope[i] = rows[c][i].prime(vc);
        }
      const Spline across       = spline_through(value);
      const Spline across_slope = spline_through(slope);
      p.position[c]             = across(uc);
      p.d_du[c]                 = across.prime(uc);
      p.d_dv[c]                 = across_slope(uc);
    }
  p.position += p.d_du * (u - uc) + p.d_dv * (v - vc);
  p.normal = orientation * p.d_dv.cross(p.d_du).normalized();
  return p;
}
} // namespace gearkit

#include "geometry/interpolated_flank.h"

#include <Eigen/Geometry>
#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>

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

// Cubic Hermite basis on [0, 1] and its derivative: weights of p0, p1, p0', p1'.
Eigen::Vector4d
hermite(double t)
{
  const double t2 = t * t, t3 = t2 * t;
  return {2 * t3 - 3 * t2 + 1, -2 * t3 + 3 * t2, t3 - 2 * t2 + t, t3 - t2};
}

Eigen::Vector4d
hermite_slope(double t)
{
  const double t2 = t * t;
  return {6 * t2 - 6 * t, -6 * t2 + 6 * t, 3 * t2 - 4 * t + 1, 3 * t2 - 2 * t};
}
} // namespace

InterpolatedFlank::InterpolatedFlank(const MeasuredFlank &f)
    : n_profile(f.n_profile)
    , n_face(f.n_face)
    , nodes(std::size_t(f.n_profile) * f.n_face)
{
  if (n_profile < 5 || n_face < 5)
    throw InputError("interpolating the measured flank of tooth " + std::to_string(f.tooth) + " " +
                     to_string(f.side) + ": grid " + std::to_string(n_profile) + " x " +
                     std::to_string(n_face) + " is too small; expected at least 5 x 5 points");
  auto at = [this](int i, int j) -> std::array<Vec3, 4> & {
    return nodes[std::size_t(i) * n_face + j];
  };
  for (int c = 0; c < 3; ++c)
    {
      // d/dv along each profile row; then d/du and d2/dudv along each face column.
      for (int i = 0; i < n_profile; ++i)
        {
          std::vector<double> row(n_face);
          for (int j = 0; j < n_face; ++j)
            row[j] = f.points[std::size_t(i) * n_face + j][c];
          const auto s = spline_through(row);
          for (int j = 0; j < n_face; ++j)
            {
              at(i, j)[0][c] = row[j];
              at(i, j)[2][c] = s.prime(j);
            }
        }
      for (int j = 0; j < n_face; ++j)
        {
          std::vector<double> value(n_profile), slope(n_profile);
          for (int i = 0; i < n_profile; ++i)
            {
              value[i] = at(i, j)[0][c];
              slope[i] = at(i, j)[2][c];
            }
          const auto sv = spline_through(value), ss = spline_through(slope);
          for (int i = 0; i < n_profile; ++i)
            {
              at(i, j)[1][c] = sv.prime(i);
              at(i, j)[3][c] = ss.prime(i);
            }
        }
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
  FlankPoint p;
  if (!std::isfinite(u) || !std::isfinite(v))
    {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      p.position = p.normal = p.d_du = p.d_dv = Vec3::Constant(nan);
      return p;
    }
  const double uc = std::clamp(u, 0.0, double(n_profile - 1));
  const double vc = std::clamp(v, 0.0, double(n_face - 1));
  const int    i = std::min(int(uc), n_profile - 2), j = std::min(int(vc), n_face - 2);
  const double s = uc - i, t = vc - j;
  // Bicubic Hermite patch: P(s, t) = sum over corners a, b of the value, d/du, d/dv and d2/dudv
  // weighted by the Hermite basis in s and t (unit cell).
  const Eigen::Vector4d hs = hermite(s), ht = hermite(t), ds = hermite_slope(s),
                        dt = hermite_slope(t);
  p.position.setZero();
  p.d_du.setZero();
  p.d_dv.setZero();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      {
        const std::array<Vec3, 4> &n = nodes[std::size_t(i + a) * n_face + j + b];
        // basis indices: value at corner a -> a, slope at corner a -> 2 + a
        const double w[4][2] = {
            {hs[a], ht[b]}, {hs[2 + a], ht[b]}, {hs[a], ht[2 + b]}, {hs[2 + a], ht[2 + b]}};
        const double wu[4][2] = {
            {ds[a], ht[b]}, {ds[2 + a], ht[b]}, {ds[a], ht[2 + b]}, {ds[2 + a], ht[2 + b]}};
        const double wv[4][2] = {
            {hs[a], dt[b]}, {hs[2 + a], dt[b]}, {hs[a], dt[2 + b]}, {hs[2 + a], dt[2 + b]}};
        for (int k = 0; k < 4; ++k)
          {
            p.position += w[k][0] * w[k][1] * n[k];
            p.d_du += wu[k][0] * wu[k][1] * n[k];
            p.d_dv += wv[k][0] * wv[k][1] * n[k];
          }
      }
  // Beyond the grid the surface continues linearly from its edge (C1).
  p.position += p.d_du * (u - uc) + p.d_dv * (v - vc);
  p.normal = orientation * p.d_dv.cross(p.d_du).normalized();
  return p;
}
} // namespace gearkit

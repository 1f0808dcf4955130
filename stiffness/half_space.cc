#include "stiffness/half_space.h"

#include <cmath>
#include <tuple>
#include <unsupported/Eigen/AutoDiff>

namespace gearkit
{
namespace
{
/// X asinh(Y / |X|) + Y asinh(X / |Y|): the corner term of the integral of 1/r over a rectangle
/// (each product tends to 0 with its factor).
double
corner(double X, double Y)
{
  double f = 0;
  if (X != 0)
    f += X * std::asinh(Y / std::abs(X));
  if (Y != 0)
    f += Y * std::asinh(X / std::abs(Y));
  return f;
}

/// The quintic step from 1 at a to 0 at b (second derivatives continuous) at a < x < b: its
/// value and first and second derivatives in x. With s = (x - a) / w and t = (b - x) / w, the
/// value 1 - s^3 (10 - 15 s + 6 s^2) is written t^3 (10 - 15 t + 6 t^2): near b it is then
/// tiny and positive to its last digits, not 1 less almost 1 (rounding noise of either sign).
std::tuple<double, double, double>
quintic_step(double x, double a, double b)
{
  const double w = b - a, s = (x - a) / w, t = (b - x) / w;
  return {t * t * t * (10 - 15 * t + 6 * t * t), -30 * s * s * t * t / w,
          -60 * s * t * (t - s) / (w * w)};
}
} // namespace

double
contact_modulus(const Material &a, const Material &b)
{
  return 1 / ((1 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
              (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

double
rectangle_displacement(double x, double y, double a, double b, double force, double modulus)
{
  // u = p / (pi E*) * integral over the rectangle of dA / r, p = F / (4 a b).
  const double integral =
      corner(x + a, y + b) - corner(x + a, y - b) - corner(x - a, y + b) + corner(x - a, y - b);
  return force / (4 * a * b) / (pi * modulus) * integral;
}

double
point_load_displacement(double r, double z, double force, const Material &m)
{
  const double rho = std::sqrt(r * r + z * z);
  const double nu  = m.poisson_ratio;
  return force * (1 + nu) / (2 * pi * m.youngs_modulus) *
         (2 * (1 - nu) / rho + z * z / (rho * rho * rho));
}

DisplacementField
point_force_field(const Vec3 &x, const Vec3 &origin, const Vec3 &direction, double force,
                  const Material &m)
{
  // a right-handed frame (e1, e2, e3 = direction); the local field differentiated exactly
  const Vec3      e3 = direction.normalized();
  const Vec3      e1 = e3.unitOrthogonal(), e2 = e3.cross(e1);
  Eigen::Matrix3d R;
  R.col(0) = e1, R.col(1) = e2, R.col(2) = e3;
  const Vec3 local = R.transpose() * (x - origin);

  using Scalar = Eigen::AutoDiffScalar<Eigen::Vector3d>;
  const Scalar X(local.x(), 3, 0), Y(local.y(), 3, 1), Z(local.z(), 3, 2);
  const double nu  = m.poisson_ratio;
  const double C   = force * (1 + nu) / (2 * pi * m.youngs_modulus); // F / (4 pi G)
  const Scalar rho = sqrt(X * X + Y * Y + Z * Z);
  const Scalar a   = Z / (rho * rho * rho) - (1 - 2 * nu) / (rho * (rho + Z)); // u_r / (C r)
  const Scalar ux = C * X * a, uy = C * Y * a;
  const Scalar uz = C * (Z * Z / (rho * rho * rho) + 2 * (1 - nu) / rho);

  Eigen::Matrix3d g;
  g.row(0) = ux.derivatives().transpose();
  g.row(1) = uy.derivatives().transpose();
  g.row(2) = uz.derivatives().transpose();
  DisplacementField out;
  out.u        = R * Vec3(ux.value(), uy.value(), uz.value());
  out.gradient = R * g * R.transpose();
  return out;
}

Cutoff
radial_cutoff(const Vec3 &x, const Vec3 &centre, double inner, double outer)
{
  Cutoff       c;
  const Vec3   d = x - centre;
  const double r = d.norm();
  if (r <= inner)
    {
      c.value = 1;
      return c;
    }
  if (r >= outer)
    return c;
  const auto [value, d1, d2] = quintic_step(r, inner, outer); // chi, d chi / dr, d2 chi / dr2
  c.value                    = value;
  const Vec3 e               = d / r;
  c.gradient                 = d1 * e;
  c.hessian = d2 * e * e.transpose() + d1 / r * (Eigen::Matrix3d::Identity() - e * e.transpose());
  return c;
}

Cutoff
elevation_cutoff(const Vec3 &x, const Vec3 &centre, const Vec3 &direction, double from, double to)
{
  Cutoff       c;
  const Vec3   y = x - centre;
  const double r = y.norm();
  if (r == 0)
    {
      c.value = 1;
      return c;
    }
  // t = sin(elevation) = -(y . d) / r
  const double yd = y.dot(direction), t = -yd / r, lo = std::sin(from), w = std::sin(to) - lo;
  if (t <= lo)
    {
      c.value = 1;
      return c;
    }
  if (t >= lo + w)
    return c;
  const auto [value, d1, d2] = quintic_step(t, lo, lo + w); // psi, d psi / dt, d2 psi / dt2
  c.value                    = value;
  const double          r3   = r * r * r;
  const Vec3            gt   = -direction / r + yd * y / r3;
  const Eigen::Matrix3d ht =
      (direction * y.transpose() + y * direction.transpose()) / r3 +
      yd * (Eigen::Matrix3d::Identity() / r3 - 3 * y * y.transpose() / (r3 * r * r));
  c.gradient = d1 * gt;
  c.hessian  = d2 * gt * gt.transpose() + d1 * ht;
  return c;
}

Cutoff
operator*(const Cutoff &a, const Cutoff &b)
{
  Cutoff c;
  c.value    = a.value * b.value;
  c.gradient = a.value * b.gradient + b.value * a.gradient;
  c.hessian  = a.value * b.hessian + b.value * a.hessian + a.gradient * b.gradient.transpose() +
              b.gradient * a.gradient.transpose();
  return c;
}

Cutoff
near_field_cutoff(const Vec3 &x, const Vec3 &centre, const Vec3 &direction, double inner,
                  double outer)
{
  const Cutoff radial = radial_cutoff(x, centre, inner, outer);
  if (radial.value == 0)
    return radial;
  return radial * elevation_cutoff(x, centre, direction, pi / 6, pi / 3);
}

Lame
lame(const Material &m)
{
  const double E = m.youngs_modulus, nu = m.poisson_ratio;
  return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
}

Eigen::Matrix3d
stress(const Eigen::Matrix3d &g, const Material &m)
{
  const auto [lambda, mu] = lame(m);
  return lambda * g.trace() * Eigen::Matrix3d::Identity() + mu * (g + g.transpose());
}

NearField
cut_off_near_field(const DisplacementField &f, const Cutoff &chi, const Vec3 &normal,
                   const Material &m)
{
  const auto [lambda, mu] = lame(m);
  const Vec3 &a           = chi.gradient;
  const auto &G           = f.gradient;
  const auto &H           = chi.hessian;
  NearField   out;
  out.u = chi.value * f.u;
  // grad(chi u) = chi grad u + u (grad chi)^T
  out.traction = stress(chi.value * G + f.u * a.transpose(), m) * normal;
  // div sigma(chi u) with div sigma(u) = 0: sigma(u) grad chi + lambda (H u + G^T a)
  // + mu (H u + a tr G + G a + u tr H)
  out.body = stress(G, m) * a + lambda * (H * f.u + G.transpose() * a) +
             mu * (H * f.u + a * G.trace() + G * a + f.u * H.trace());
  return out;
}
} // namespace gearkit

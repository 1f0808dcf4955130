#include "stiffness/half_space.h"

#include <cmath>

namespace gearkit
{
namespace
{
constexpr double pi = 3.14159265358979323846;

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
} // namespace gearkit

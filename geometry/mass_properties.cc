#include "geometry/mass_properties.h"

namespace gearkit
{
AreaMoments &
AreaMoments::operator-=(const AreaMoments &o)
{
  area -= o.area;
  first_x -= o.first_x;
  first_y -= o.first_y;
  second_xx -= o.second_xx;
  second_yy -= o.second_yy;
  return *this;
}

AreaMoments
polygon_moments(const std::vector<Vec2> &p)
{
  // Green's theorem over each edge (x_i, y_i) -> (x_j, y_j) with c = x_i y_j - x_j y_i.
  AreaMoments       m;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    {
      const Vec2  &a = p[i];
      const Vec2  &b = p[(i + 1) % n];
      const double c = a.x() * b.y() - b.x() * a.y();
      m.area += c / 2;
      m.first_x += c * (a.x() + b.x()) / 6;
      m.first_y += c * (a.y() + b.y()) / 6;
      m.second_xx += c * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) / 12;
      m.second_yy += c * (a.y() * a.y() + a.y() * b.y() + b.y() * b.y()) / 12;
    }
  return m;
}

AreaMoments
disc_moments(double r)
{
  AreaMoments m;
  m.area      = pi * r * r;
  m.second_xx = m.second_yy = pi * r * r * r * r / 4;
  return m;
}

MassProperties
prism_mass_properties(const AreaMoments &s, double b, double rho)
{
  MassProperties p;
  p.volume        = s.area * b;
  p.mass          = rho * p.volume;
  p.polar_inertia = rho * b * s.polar();
  // About a diameter: rho (b int y^2 dA + A int z^2 dz) with int z^2 dz = b^3 / 12.
  p.diametral_inertia = rho * b * 0.5 * s.polar() + p.mass * b * b / 12;
  return p;
}
} // namespace gearkit

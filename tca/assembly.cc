#include "assembly.h"

#include <cmath>

namespace gearkit
{
namespace
{
Eigen::Matrix3d
rot_z(double a)
{
  return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
}
} // namespace

Assembly::Assembly(double a, int z2, const Misalignment &m)
    : centre(a + m.centre_distance_error, 0, 0)
    , orientation((Eigen::AngleAxisd(m.intersecting_angle, Vec3::UnitY()) *
                   Eigen::AngleAxisd(m.crossing_angle, Vec3::UnitX()))
                      .toRotationMatrix())
    , phase(pi + pi / z2)
    , pinion_shift(m.pinion_axial_shift)
    , gear_shift(m.gear_axial_shift)
{
}

Vec3
Assembly::pinion_to_global(const Vec3 &x, double phi) const
{
  return rot_z(phi) * (x + Vec3(0, 0, pinion_shift));
}

Vec3
Assembly::pinion_vector_to_global(const Vec3 &v, double phi) const
{
  return rot_z(phi) * v;
}

Vec3
Assembly::gear_to_global(const Vec3 &x, double psi) const
{
  // The gear turns clockwise (about -z of its frame) as psi grows.
  return centre + orientation * (rot_z(phase - psi) * x + Vec3(0, 0, gear_shift));
}

Vec3
Assembly::gear_vector_to_global(const Vec3 &v, double psi) const
{
  return orientation * (rot_z(phase - psi) * v);
}

Vec3
Assembly::global_to_gear_unrotated(const Vec3 &X) const
{
  return rot_z(-phase) * (orientation.transpose() * (X - centre) - Vec3(0, 0, gear_shift));
}
} // namespace gearkit

namespace gearkit
{
Vec3
Assembly::global_to_gear_unrotated_vector(const Vec3 &v) const
{
  return rot_z(-phase) * (orientation.transpose() * v);
}
} // namespace gearkit

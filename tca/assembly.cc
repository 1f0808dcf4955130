#include "tca/assembly.h"

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

Assembly::Assembly(const Vec3 &c, const Eigen::Matrix3d &frame, double ph, const Misalignment &m)
    : centre(c + Vec3(m.centre_distance_error, m.offset, 0))
    , orientation((Eigen::AngleAxisd(m.intersecting_angle, Vec3::UnitY()) *
                   Eigen::AngleAxisd(m.crossing_angle, Vec3::UnitX()))
                      .toRotationMatrix() *
                  frame)
    , phase(ph)
    , pinion_shift(m.pinion_axial_shift)
    , gear_shift(m.gear_axial_shift)
{
}

Assembly::Assembly(double a, int z2, const Misalignment &m)
    : Assembly(Vec3(a, 0, 0), Eigen::Matrix3d::Identity(), pi + pi / z2, m)
{
}

Assembly
Assembly::bevel(double shaft_angle, double gamma_1, int z2, const Misalignment &m)
{
  // Gear frame: z along the gear axis, x from the axis toward the common pitch element.
  const Vec3      element(std::sin(gamma_1), 0, std::cos(gamma_1));
  const Vec3      axis(std::sin(shaft_angle), 0, std::cos(shaft_angle));
  const Vec3      x = (element - element.dot(axis) * axis).normalized();
  Eigen::Matrix3d frame;
  frame.col(0) = x;
  frame.col(1) = axis.cross(x);
  frame.col(2) = axis;
  return Assembly(Vec3::Zero(), frame, pi / z2, m);
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

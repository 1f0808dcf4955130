#include "tca/assembly.h"

#include <array>
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
Assembly::tilted(double crossing, double intersecting) const
{
  Assembly a = *this;
  a.orientation =
      (Eigen::AngleAxisd(intersecting, Vec3::UnitY()) * Eigen::AngleAxisd(crossing, Vec3::UnitX()))
          .toRotationMatrix() *
      orientation;
  return a;
}

double
operating_centre_distance(double a, const Misalignment &m)
{
  return std::hypot(a + m.centre_distance_error, m.offset);
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

namespace gearkit
{
Misalignment
misalignment_after(const Assembly &assembly, const Misalignment &m, const RigidMotion &motion,
                   RigidMotion *taken)
{
  // Six unknowns, each moving the gear relative to the pinion by a rigid motion (T; W) per
  // unit: misalignment changes and turns of the members about their own axes; the motion is
  // their sum. The gear frame turns about its origin C by Ry(intersecting) Rx(crossing), so a
  // change of the crossing angle turns it about Ry(intersecting) e_x.
  using Column = Eigen::Matrix<double, 6, 1>;
  const Vec3 C = assembly.gear_centre(), a = assembly.gear_axis(), z = Vec3::UnitZ();
  const auto turn = [](const Vec3 &w, const Vec3 &pivot) {
    Column c;
    c << -w.cross(pivot), w;
    return c;
  };
  const auto shift = [](const Vec3 &t) {
    Column c;
    c << t, Vec3::Zero();
    return c;
  };
  const Vec3 crossing_axis = Eigen::AngleAxisd(m.intersecting_angle, Vec3::UnitY()) * Vec3::UnitX();
  Misalignment                               out = m;
  std::array<std::pair<Column, double *>, 6> unknowns; // (motion per unit, entry; none: a turn)
  if (a.cross(z).norm() < 0.1) // parallel axes (bevel shaft angles are far larger)
    unknowns = {{{shift(Vec3::UnitX()), &out.centre_distance_error},
                 {shift(Vec3::UnitY()), &out.offset},
                 {turn(crossing_axis, C), &out.crossing_angle},
                 {turn(Vec3::UnitY(), C), &out.intersecting_angle},
                 {shift(a), &out.gear_axial_shift},
                 {turn(a, C), nullptr}}}; // (the pinion's turn: the gear's and an offset)
  else
    unknowns = {{{shift(Vec3::UnitY()), &out.offset},
                 {turn(Vec3::UnitY(), C), &out.intersecting_angle},
                 {shift(a), &out.gear_axial_shift},
                 {shift(-z), &out.pinion_axial_shift},
                 {turn(a, C), nullptr},
                 {turn(z, Vec3::Zero()), nullptr}}};
  Eigen::Matrix<double, 6, 6> A;
  for (int j = 0; j < 6; ++j)
    A.col(j) = unknowns[std::size_t(j)].first;
  Column u;
  u << motion.translation, motion.rotation;
  const Column x    = A.fullPivLu().solve(u);
  Column       part = Column::Zero();
  for (int j = 0; j < 6; ++j)
    if (double *entry = unknowns[std::size_t(j)].second)
      *entry += x[j], part += x[j] * A.col(j);
  if (taken)
    taken->translation = part.head<3>(), taken->rotation = part.tail<3>();
  return out;
}
} // namespace gearkit

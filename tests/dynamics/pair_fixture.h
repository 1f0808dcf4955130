// A spiral-bevel-like pair for the dynamics tests: pinion axis Z, gear axis Y, the mesh at a
// point ahead of both axes, steel bodies of a few kilograms on two radial bearings each, motor
// and load on torsional shafts. Constant tables unless a transmission-error harmonic is given.
#pragma once

#include "dynamics/pair_model.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <complex>

namespace gearkit::test_data
{
inline PairModelParameters
bevel_like_parameters(double half_backlash = 0, double damping = 1)
{
  PairModelParameters p;
  p.motor_inertia = 0.05, p.load_inertia = 0.1;
  p.pinion_teeth       = 55;
  p.half_backlash      = half_backlash;
  p.mesh_damping_ratio = 0.05 * damping;
  auto body            = [&](double m, double ia, double it, Vec3 axis) {
    BodyParameters b;
    b.mass = m, b.axial_inertia = ia, b.transverse_inertia = it, b.axis = axis;
    b.bearings        = {{-0.04, 5e8, 500 * damping}, {0.05, 4e8, 400 * damping}};
    b.axial_stiffness = 3e8, b.axial_damping = 300 * damping;
    return b;
  };
  p.pinion      = body(2.0, 4e-3, 3e-3, Vec3::UnitZ());
  p.gear        = body(2.5, 5e-3, 4e-3, Vec3::UnitY());
  p.motor_shaft = {2e4, 2 * damping}, p.load_shaft = {3e4, 3 * damping};
  return p;
}

/// n samples of a mesh with constant geometry, K_m and E_t = amplitude sin(2 pi phase).
inline MeshCycleSamples
bevel_like_tables(int n = 1, double km = 3e8, double amplitude = 0)
{
  const Vec3       P(0.075, 0, 0.06), pinion_centre(0, 0, 0), gear_centre(0, 0.09, 0);
  const Vec3       normal = Vec3(0.3, 0.9, -0.3).normalized();
  MeshCycleSamples s;
  for (int i = 0; i < n; ++i)
    {
      s.transmission_error.push_back(amplitude * std::sin(2 * pi * i / n));
      s.mesh_stiffness.push_back(km);
      s.normal_pinion.push_back(normal);
      s.normal_gear.push_back(normal);
      s.arm_pinion.push_back((P - pinion_centre).cross(normal));
      s.arm_gear.push_back((P - gear_centre).cross(normal));
    }
  return s;
}
/// Steady response of delta_D to E_t = E sin(w t) of a linear model (constant mesh, no
/// backlash): delta_D - delta_static = Re D sin(w t) + Im D cos(w t), from
/// (K + K_m g g^T - w^2 M + i w (C + c_m g g^T)) Q = g (K_m + i w c_m) E, D = g . Q.
inline std::complex<double>
frequency_response(const PairModel &model, double w, double E)
{
  using Complex            = std::complex<double>;
  const MeshState        m = model.mesh().mean();
  const PairVector       g = PairModel::mesh_gradient(m);
  const Eigen::MatrixXcd A =
      (model.stiffness() + m.km * g * g.transpose() - w * w * model.mass()).cast<Complex>() +
      Complex(0, w) * (model.damping() + model.mesh_damping() * g * g.transpose()).cast<Complex>();
  const Eigen::VectorXcd rhs = g.cast<Complex>() * Complex(m.km, w * model.mesh_damping()) * E;
  return g.cast<Complex>().dot(A.partialPivLu().solve(rhs));
}
} // namespace gearkit::test_data

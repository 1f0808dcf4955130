// The 14-DOF pair model: static equilibrium against the moment arms, energy conservation of the
// undamped model, a linear forced response against the frequency-domain solution, modes, and
// bad input refused.
#include "dynamics/integrators.h"
#include "dynamics/modes.h"
#include "tests/dynamics/pair_fixture.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <complex>

using namespace gearkit;

namespace
{
/// Energy of the undamped model with constant tables and no backlash, constant torques.
double
energy(const PairModel &model, const PairVector &q, const PairVector &v, double TE, double TL)
{
  const MeshState  m = model.mesh().at(0);
  const PairVector g = PairModel::mesh_gradient(m);
  const double     x = g.dot(q) - m.et;
  return 0.5 * v.dot(model.mass() * v) + 0.5 * q.dot(model.stiffness() * q) + 0.5 * m.km * x * x -
         TE * q[dof::motor] + TL * q[dof::load];
}
} // namespace

TEST(PairModel, StaticEquilibriumBalancesTheTorquesThroughTheMomentArms)
{
  const PairModel model(test_data::bevel_like_parameters(), test_data::bevel_like_tables());
  const MeshState m = model.mesh().mean();
  for (double TL : {50.0, 200.0})
    {
      const StaticEquilibrium s = model.static_equilibrium(TL);
      // moments about each body's own axis: T_E = lambda_pz F_m, T_L = lambda_gy F_m
      EXPECT_NEAR(TL / s.motor_torque, m.lg.y() / m.lp.z(), 1e-12);
      EXPECT_NEAR(s.motor_torque, m.lp.z() * s.mesh_force, 1e-9 * s.motor_torque);
      EXPECT_NEAR(s.mesh_force, m.km * s.deflection, 1e-9 * s.mesh_force);
      EXPECT_GT(s.mesh_force, 0);
      // the static state is a rest state of the dynamic model
      const PairVector a = model.acceleration(0, s.q, PairVector::Zero(), 100, s.motor_torque, TL);
      EXPECT_LT(a.norm(), 1e-6);
    }
  // backlash: the same force, the deflection measured beyond the clearance
  const PairModel loose(test_data::bevel_like_parameters(20e-6), test_data::bevel_like_tables());
  const StaticEquilibrium a = model.static_equilibrium(100), b = loose.static_equilibrium(100);
  EXPECT_NEAR(b.mesh_force / a.mesh_force, 1, 1e-12);
  EXPECT_THROW(model.static_equilibrium(-100), InputError);
}

TEST(PairModel, UndampedConstantStiffnessConservesEnergy)
{
  const PairModel model(test_data::bevel_like_parameters(0, 0), test_data::bevel_like_tables());
  const double    TL           = 150;
  const StaticEquilibrium s    = model.static_equilibrium(TL);
  PairVector              v0   = PairVector::Zero();
  v0[dof::pinion_rotation + 2] = 0.02, v0[dof::gear] = 0.01, v0[dof::load] = -0.01;
  RunOptions o;
  o.omega        = 2 * pi * 1000 / 60;
  o.motor_torque = s.motor_torque, o.load_torque = TL;
  o.samples_per_cycle = 1;
  const double E0     = energy(model, s.q, v0, o.motor_torque, TL);
  const double Ev     = 0.5 * v0.dot(model.mass() * v0); // the vibration's energy
  // Newmark (trapezoidal): exact for the linear model, 10^4 mesh cycles
  o.method = Integrator::newmark, o.mesh_cycles = 1e4, o.steps_per_cycle = 64;
  const Trajectory n     = simulate(model, s.q, v0, o);
  double           worst = 0;
  for (std::size_t k = 0; k < n.t.size(); ++k)
    worst = std::max(worst, std::abs(energy(model, n.q[k], n.v[k], o.motor_torque, TL) - E0));
  EXPECT_LT(worst / Ev, 1e-8) << "Newmark";
  // CVODE (Adams, tight tolerances) is not symplectic: its energy drifts with the tolerance
  // times the time, about 2e-7 of the vibration's energy over 10^3 mesh cycles at 1e-12
  o.method = Integrator::cvode_adams, o.mesh_cycles = 1e3;
  o.relative_tolerance = 1e-12, o.absolute_tolerance = 1e-10;
  const Trajectory c = simulate(model, s.q, v0, o);
  worst              = 0;
  for (std::size_t k = 0; k < c.t.size(); ++k)
    worst = std::max(worst, std::abs(energy(model, c.q[k], c.v[k], o.motor_torque, TL) - E0));
  EXPECT_LT(worst / Ev, 1e-6) << "CVODE Adams";
}

TEST(PairModel, LinearForcedResponseMatchesTheFrequencyDomain)
{
  // constant stiffness, no backlash, E_t = E1 sin(omega_m t): the steady state of the damped
  // model against (K + K_m g g^T - w^2 M + i w (C + c_m g g^T)) Q = g (K_m + i w c_m) E1
  const double            E1 = 5e-6;
  const PairModel         model(test_data::bevel_like_parameters(),
                                test_data::bevel_like_tables(16, 3e8, E1));
  const double            TL = 100;
  const StaticEquilibrium s  = model.static_equilibrium(TL);
  RunOptions              o;
  o.omega        = 2 * pi * 3000 / 60; // mesh frequency 2750 Hz
  o.motor_torque = s.motor_torque, o.load_torque = TL;
  o.mesh_cycles = 400, o.samples_per_cycle = 32;
  const double w = model.parameters().pinion_teeth * o.omega;

  const PairVector g = PairModel::mesh_gradient(model.mesh().mean());
  const auto       D = test_data::frequency_response(model, w, E1);

  for (Integrator method : {Integrator::cvode_bdf, Integrator::newmark})
    {
      o.method           = method;
      o.steps_per_cycle  = 256;
      const Trajectory r = simulate(model, s.q, PairVector::Zero(), o);
      // project the last 50 cycles on sin and cos of the mesh frequency
      double            a = 0, b = 0;
      const std::size_t n = 50 * 32, first = r.t.size() - n;
      const double      delta_s = g.dot(s.q);
      for (std::size_t k = first; k < r.t.size(); ++k)
        {
          a += 2.0 / n * (r.dte[k] - delta_s) * std::sin(w * r.t[k]);
          b += 2.0 / n * (r.dte[k] - delta_s) * std::cos(w * r.t[k]);
        }
      EXPECT_NEAR(a, D.real(), 2e-3 * std::abs(D)) << int(method);
      EXPECT_NEAR(b, D.imag(), 2e-3 * std::abs(D)) << int(method);
    }
}

TEST(PairModel, ModesHaveTheRigidRotationAndPositiveFrequencies)
{
  const PairModel model(test_data::bevel_like_parameters(), test_data::bevel_like_tables());
  const PairModes modes = linear_modes(model);
  ASSERT_EQ(modes.frequency.size(), 14u);
  EXPECT_LT(modes.frequency[0], 1e-3); // the whole train turning
  for (int i = 1; i < 14; ++i)
    EXPECT_GT(modes.frequency[i], 1.0);
  // a free vibration started in mode k oscillates at its frequency (CVODE, undamped)
  const PairModel undamped(test_data::bevel_like_parameters(0, 0), test_data::bevel_like_tables());
  const PairModes u = linear_modes(undamped);
  int             k = 1;
  while (u.mesh_energy[k] < 0.3)
    ++k; // a mode that strains the mesh
  const StaticEquilibrium s  = undamped.static_equilibrium(100);
  const PairVector        q0 = s.q + 1e-7 * u.shapes.col(k) / u.shapes.col(k).cwiseAbs().maxCoeff();
  RunOptions              o;
  o.omega = 2 * pi * 500 / 60, o.motor_torque = s.motor_torque, o.load_torque = 100;
  o.mesh_cycles = 20, o.samples_per_cycle = 64, o.relative_tolerance = 1e-11;
  o.method = Integrator::cvode_adams; // BDF damps and detunes a mode over hundreds of periods
  const Trajectory r = simulate(undamped, q0, PairVector::Zero(), o);
  // delta(t) - delta_s = d0 cos(w_k t)
  const PairVector g  = PairModel::mesh_gradient(undamped.mesh().mean());
  const double     d0 = g.dot(q0 - s.q), wk = 2 * pi * u.frequency[k];
  double           worst = 0;
  for (std::size_t i = 0; i < r.t.size(); ++i)
    worst = std::max(worst, std::abs(r.dte[i] - g.dot(s.q) - d0 * std::cos(wk * r.t[i])));
  EXPECT_LT(worst, 1e-4 * std::abs(d0)) << "mode " << k << " at " << u.frequency[k] << " Hz";
}

TEST(PairModel, BadInputIsRefused)
{
  auto p        = test_data::bevel_like_parameters();
  p.pinion.mass = 0;
  EXPECT_THROW(PairModel(p, test_data::bevel_like_tables()), InputError);
  p           = test_data::bevel_like_parameters();
  p.gear.axis = Vec3(0, 2, 0);
  EXPECT_THROW(PairModel(p, test_data::bevel_like_tables()), InputError);
  auto t              = test_data::bevel_like_tables(4);
  t.mesh_stiffness[2] = -1;
  EXPECT_THROW(PairModel(test_data::bevel_like_parameters(), t), InputError);
  t = test_data::bevel_like_tables(4);
  t.normal_gear.pop_back();
  EXPECT_THROW(PairModel(test_data::bevel_like_parameters(), t), InputError);
  const PairModel model(test_data::bevel_like_parameters(), test_data::bevel_like_tables());
  RunOptions      o; // no speed
  EXPECT_THROW(simulate(model, PairVector::Zero(), PairVector::Zero(), o), InputError);
}

TEST(PairModel, PlacedInTheAssemblyTheGearTurnsAgainstItsFrameAxis)
{
  PairModelParameters p;
  p.gear.bearings             = {{0.1, 1e8, 0}, {0.16, 1e8, 0}};
  const PairModelParameters q = placed_in_assembly(p, 12, Vec3::UnitZ(), Vec3::UnitY());
  EXPECT_EQ(q.pinion_teeth, 12);
  EXPECT_EQ(q.pinion.axis, Vec3::UnitZ());
  EXPECT_EQ(q.gear.axis, -Vec3::UnitY()); // driven sense
  // 100 mm along the gear frame's +y is 100 mm along the model's -y axis
  EXPECT_EQ(q.gear.bearings[0].position, -0.1);
  EXPECT_EQ(q.gear.bearings[1].position, -0.16);
}

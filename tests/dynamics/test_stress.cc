// Stress: zero and very large backlash, near-zero and very large support-to-mesh stiffness
// ratios, high speed with many impacts: finite results from both integrators (or a clear
// InputError naming CVODE's failure), never a silent NaN.
#include "dynamics/sweep.h"
#include "tests/dynamics/pair_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

namespace
{
MeshCycleSamples
rough_tables(double et_amplitude)
{
  MeshCycleSamples t = test_data::bevel_like_tables(24, 3e8, et_amplitude);
  for (int i = 0; i < 24; ++i)
    t.mesh_stiffness[i] *= 1 - 0.2 * std::cos(2 * pi * i / 24);
  return t;
}

/// Sweeps a few speeds with both integrators; every figure finite.
std::vector<SweepPoint>
run(const PairModelParameters &p, const MeshCycleSamples &t, std::vector<double> rpm,
    Integrator method)
{
  const PairModel         model(p, t);
  const MeshState         m = model.mesh().mean();
  const double            F = 3000;
  const StaticEquilibrium s = model.static_equilibrium(F * m.lg.y());
  SweepOptions            o;
  o.motor_torque = F * m.lp.z(), o.load_torque = F * m.lg.y();
  o.settle_cycles = 30, o.record_cycles = 10;
  o.run.method = method, o.run.steps_per_cycle = 64;
  for (double r : rpm)
    o.speeds.push_back(r * 2 * pi / 60);
  PairVector q = s.q, v = PairVector::Zero();
  const auto points = sweep(model, q, v, o);
  for (const SweepPoint &pt : points)
    {
      EXPECT_TRUE(std::isfinite(pt.dte_pp) && std::isfinite(pt.max_force) &&
                  std::isfinite(pt.load_factor))
          << "at " << pt.speed * 60 / (2 * pi) << " rpm";
      EXPECT_GE(pt.max_force, 0);
    }
  EXPECT_TRUE(q.allFinite() && v.allFinite());
  return points;
}
} // namespace

TEST(PairDynamicsStress, ZeroAndVeryLargeBacklash)
{
  for (Integrator method : {Integrator::cvode_bdf, Integrator::newmark})
    {
      // no backlash: the mesh never opens, both flanks act as one spring
      const auto tight =
          run(test_data::bevel_like_parameters(0), rough_tables(20e-6), {3000, 9000}, method);
      for (const auto &p : tight)
        EXPECT_EQ(p.contact_loss, 0);
      // 1 mm half backlash and an excitation larger than the static deflection: the teeth fly
      // apart and meet again on the drive side (free flight between impacts)
      const auto loose = run(test_data::bevel_like_parameters(1e-3), rough_tables(40e-6),
                             {3000, 9000, 12000}, method);
      double     lost  = 0;
      for (const auto &p : loose)
        lost = std::max(lost, p.contact_loss);
      EXPECT_GT(lost, 0) << "no contact loss with a 40 um excitation on 10 um of deflection";
    }
}

TEST(PairDynamicsStress, ExtremeSupportStiffnessRatiosAndManyImpacts)
{
  for (double ratio : {1e-5, 1e4}) // bearing stiffness over the mesh stiffness
    {
      auto p = test_data::bevel_like_parameters(10e-6);
      for (BodyParameters *b : {&p.pinion, &p.gear})
        {
          for (RadialBearing &r : b->bearings)
            r.stiffness = ratio * 3e8;
          b->axial_stiffness = ratio * 3e8;
        }
      run(p, rough_tables(5e-6), {2000, 8000}, Integrator::newmark);
      try
        {
          run(p, rough_tables(5e-6), {2000, 8000}, Integrator::cvode_bdf);
        }
      catch (const InputError &e) // a stiff failure is reported, not hidden
        {
          EXPECT_NE(std::string(e.what()).find("CVODE"), std::string::npos) << e.what();
        }
    }
  // high speed, excitation three times the static deflection: impacts on both flanks
  const auto  points = run(test_data::bevel_like_parameters(10e-6), rough_tables(30e-6),
                           {11000, 12000}, Integrator::cvode_bdf);
  std::size_t events = 0;
  for (const auto &p : points)
    events += p.events;
  EXPECT_GT(events, 10u);
}

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

/// Sweeps a few speeds with both integrators at a static mesh force F; every figure finite.
std::vector<SweepPoint>
run(const PairModelParameters &p, const MeshCycleSamples &t, std::vector<double> rpm,
    Integrator method, double F = 3000)
{
  const PairModel         model(p, t);
  const MeshState         m = model.mesh().mean();
  const StaticEquilibrium s = model.static_equilibrium(F * m.lg.y());
  SweepOptions            o;
  // a tight steady check and fixed Newmark steps, as this test was written for
  o.steady_tolerance = 1e-6, o.accuracy = 0;
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

TEST(PairDynamicsStress, ZeroBacklashIsTheLinearLimit)
{
  // Without backlash both flanks act as one spring: the model is linear, so twice the load with
  // twice the transmission error gives twice every response, although the excitation (30 um on
  // 10 um of static deflection) would part the teeth with backlash; and a backlash shrinking to
  // nothing tends to it (no threshold at zero): delta_D's peak-to-peak moves in proportion to
  // b (4.3 to 4.7 times the band 2 b here, the same from b = 100 nm to 1 nm within 1 %).
  const std::vector<double> rpm = {3000, 9000};
  for (Integrator method : {Integrator::cvode_bdf, Integrator::newmark})
    {
      const auto   p   = test_data::bevel_like_parameters(0);
      const auto   one = run(p, rough_tables(30e-6), rpm, method, 3000);
      const auto   two = run(p, rough_tables(60e-6), rpm, method, 6000);
      const double tol = method == Integrator::newmark ? 1e-9 : 1e-6;
      for (std::size_t i = 0; i < rpm.size(); ++i)
        {
          SCOPED_TRACE(std::to_string(rpm[i]) + " rpm, " +
                       (method == Integrator::newmark ? "Newmark" : "CVODE"));
          EXPECT_NEAR(two[i].dte_pp / one[i].dte_pp, 2, 2 * tol);
          EXPECT_NEAR(two[i].max_force / one[i].max_force, 2, 2 * tol);
          EXPECT_NEAR(two[i].relative_rms / one[i].relative_rms, 2, 2 * tol);
          EXPECT_EQ(one[i].contact_loss, 0);
        }
      double last = HUGE_VAL;
      for (const double b : {1e-7, 1e-8, 1e-9})
        {
          const auto loose =
              run(test_data::bevel_like_parameters(b), rough_tables(30e-6), rpm, method, 3000);
          double worst = 0; // the largest change of the peak-to-peak over the band 2 b
          for (std::size_t i = 0; i < rpm.size(); ++i)
            worst = std::max(worst, std::abs(loose[i].dte_pp - one[i].dte_pp) / (2 * b));
          EXPECT_LT(worst, 10) << "half backlash " << b << " m";
          if (last < HUGE_VAL)
            {
              EXPECT_NEAR(worst / last, 1, 0.05) << "half backlash " << b << " m";
            }
          last = worst;
        }
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

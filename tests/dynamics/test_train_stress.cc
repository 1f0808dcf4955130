// Stress tests of the gear-train impact model: a contact 1000 times stiffer, no backlash and a
// millimetre of it, 20 000 rpm, a missing tooth. Each ends with finite results or a clear
// InputError - never a hang (the step budget) and never a NaN.
#include "dynamics/train.h"
#include "tests/dynamics/train_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;
using namespace gearkit::test_data;

namespace
{
/// Seed 002's first stage (17/60, m 4 mm) with ideal flanks: pinion A 1.06e-3 kg m^2, the
/// gear side 0.05 kg m^2, 0.05 mm backlash, the seed's IMPACT law, 1 % resistive torque.
TrainModel
stage_one(double stiffness_factor = 1, double backlash = 0.05e-3)
{
  const double r_bp = 0.034 * std::cos(20 * pi / 180), r_bg = r_bp * 60 / 17;
  ImpactLaw    law{stiffness_factor * impact_stiffness_si(2e7, 2.2, 1e-3), 2.2,
                impact_stiffness_si(2e7 * 2e-4, 1.0, 1e-3), 1e-10};
  TrainModel   m = two_body_model(1.06e-3, 0.05, 17, 60, r_bp, backlash / r_bg, law, 1.6);
  m.bodies[0].initial_speed   = 167.5;
  m.bodies[1].initial_speed   = 167.5 * 17 / 60;
  m.bodies[0].torque.constant = 1.49;
  m.bodies[1].torque.constant = -1.49 * 60 / 17;
  return m;
}

void
expect_finite(const TrainResult &r)
{
  for (const auto &w : r.speed)
    for (double v : w)
      ASSERT_TRUE(std::isfinite(v));
  for (const MeshSeries &m : r.meshes)
    for (double f : m.force)
      {
        ASSERT_TRUE(std::isfinite(f));
        ASSERT_LT(std::abs(f), 1e9);
      }
}

/// Runs; a failure must be an InputError that says what to change.
void
run_or_refuse(const TrainModel &m, const TrainRunOptions &o, const char *expect_in_message)
{
  try
    {
      const TrainResult r = simulate_train(m, o);
      expect_finite(r);
      EXPECT_LT(r.energy_error, 1e-6);
      std::printf("ran: %zu steps, %zu impacts, max force %g N, energy error %g\n", r.steps,
                  r.meshes[0].impacts, r.meshes[0].max_force, r.energy_error);
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find(expect_in_message), std::string::npos) << e.what();
      std::printf("refused: %s\n", e.what());
    }
}
} // namespace

TEST(TrainStress, ContactThousandTimesStiffer)
{
  TrainRunOptions o;
  o.duration = 0.02;
  run_or_refuse(stage_one(1000), o, "gear train");
  // a step budget too small for it: refused with the reason, not a hang
  o.max_steps = 50;
  try
    {
      simulate_train(stage_one(1000), o);
      FAIL() << "expected the step budget to run out";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("integrator steps"), std::string::npos) << e.what();
    }
}

TEST(TrainStress, NoBacklashAndAMillimetre)
{
  TrainRunOptions o;
  o.duration = 0.02;
  for (double b : {0.0, 1e-3})
    {
      const TrainResult r = simulate_train(stage_one(1, b), o);
      expect_finite(r);
      EXPECT_LT(r.energy_error, 1e-6) << "backlash " << b;
      // S stays within the band, up to the penetrations
      for (double s : r.meshes[0].relative)
        EXPECT_LT(std::abs(s), b / 2 + 50e-6);
    }
}

TEST(TrainStress, TwentyThousandRpm)
{
  TrainModel m              = stage_one();
  m.bodies[0].initial_speed = 20000 * 2 * pi / 60;
  m.bodies[1].initial_speed = m.bodies[0].initial_speed * 17 / 60;
  TrainRunOptions o;
  o.duration = 0.01;
  run_or_refuse(m, o, "gear train");
}

TEST(TrainStress, MissingTooth)
{
  // pinion tooth 5 gone: its class pair never touches; the mesh runs on the others and loses
  // contact once a pinion revolution, touching again with an impact. At 0.9 N m on the pinion
  // (stage_one's 1.49 N m lets the pinion follow the receding flank of the pair before the gap:
  // no separation once the integrator resolves it; an earlier version saw one at the output
  // times only) - against 0.6 N m, where it separates at every tooth.
  TrainModel m                = stage_one();
  m.bodies[0].torque.constant = 0.9;
  m.bodies[1].torque.constant = -0.9 * 60 / 17;
  auto &t                     = m.meshes[0].teeth;
  t.pinion_class              = std::vector<int>(17, 0);
  t.pinion_class[5]           = 1;
  t.pinion_classes            = 2;
  for (auto &side : t.curves)
    side.push_back(ToothPairCurve{}); // class pair (1, 0): never touches

  TrainRunOptions o;
  o.duration          = 0.1; // 2.7 pinion revolutions
  const TrainResult r = simulate_train(m, o);
  expect_finite(r);
  EXPECT_LT(r.energy_error, 1e-6);
  ASSERT_GE(r.meshes[0].drive_impacts, 2u);
  ASSERT_LE(r.meshes[0].drive_impacts, 8u); // not at every tooth (45 mesh cycles)
  // the contacts that begin after a separation at the gap follow each other by one revolution
  const std::vector<TrainImpact> &c = r.meshes[0].contacts;
  std::vector<double>             long_ones;
  for (const TrainImpact &x : c)
    if (x.separation < 0 || x.separation - x.touch > 5e-3)
      long_ones.push_back(x.touch);
  ASSERT_GE(long_ones.size(), 3u);
  EXPECT_NEAR(long_ones[2] - long_ones[1], 2 * pi / 167.5, 0.02 * 2 * pi / 167.5);
}

TEST(TrainStress, BriefContactsInsideOneStepAreFound)
{
  // Both bodies held at the kinematic speed (the motion is exact; free flight lets the steps
  // grow to their bound of 1/16 of a mesh period) and a bump on the drive flank of every tooth
  // pair: a raised cosine of half-width a quarter pitch rising 2 % above the half backlash, so
  // each tooth pass touches for 0.045 of a mesh period - inside one step, not at its ends. Every
  // pass is a contact, at the times the bump's geometry gives, whichever way the output is
  // sampled. (Without the midpoint check 2 of the 15 are found: those a step happens to end in.)
  const int       z   = 20;
  const double    r_b = 0.05, beta = 1e-3, pitch = 2 * pi / z, sigma = pitch / 4, w = 100;
  const double    rise = 1.02 * beta / 2;
  ImpactLaw       law{1e3, 1.0, 0, 0};
  TrainModel      m = two_body_model(1e-3, 1e-3, z, z, r_b, beta, law);
  ToothPairCurve &c = m.meshes[0].teeth.curves[drive_side][0];
  for (std::size_t i = 0; i < c.offset.size(); ++i)
    {
      const double x = c.start + double(i) * c.step;
      if (std::abs(x) < sigma)
        c.offset[i] += rise * std::pow(std::cos(pi * x / (2 * sigma)), 2);
    }
  for (TrainBody &b : m.bodies)
    b.constant_speed = true, b.initial_speed = w;
  const double x0 = -0.7 * pitch; // the first pass through the bump at 0.7 pitch
  // ratio 1, both in the middle of the backlash (the ideal flanks' band is centred on 0)
  m.bodies[0].initial_angle = m.bodies[1].initial_angle = x0;
  // the contact: rise cos^2(pi x / 2 sigma) > beta / 2, |x| < x_c
  const double x_c    = 2 * sigma / pi * std::acos(std::sqrt(beta / 2 / rise));
  const int    passes = 15;
  for (const double rate : {1e3, 2e5})
    {
      TrainRunOptions o;
      o.duration          = (passes * pitch - x0 - pitch / 2) / w;
      o.sample_rate       = rate;
      const TrainResult r = simulate_train(m, o);
      SCOPED_TRACE("output at " + std::to_string(rate) + " Hz");
      EXPECT_GT(r.steps, std::size_t(16 * passes)); // the step bound, not the contacts, sets them
      ASSERT_EQ(r.meshes[0].drive_impacts, std::size_t(passes));
      EXPECT_EQ(r.meshes[0].coast_impacts, 0u);
      for (std::size_t j = 0; j < r.meshes[0].contacts.size(); ++j)
        {
          const TrainImpact &k      = r.meshes[0].contacts[j];
          const double       centre = (double(j) * pitch - x0) / w;
          // the curve is a Hermite interpolant of 16 samples per half-width: its window within
          // 2 % of the exact bump's
          EXPECT_NEAR(k.touch, centre - x_c / w, 0.02 * x_c / w) << "pass " << j;
          EXPECT_NEAR(k.separation, centre + x_c / w, 0.02 * x_c / w) << "pass " << j;
        }
    }
}

// Divergence of the pair dynamics (issue 36): without damping and backlash nothing limits the
// principal parametric resonance of a varying K_m, and the response grows by the Floquet
// multiplier every mesh cycle. The integrators stop at the first step (Newmark) or sample
// (CVODE) past the bound or at a state that is not finite, with every sample finite; a sweep
// flags those speeds (zero results, the time), leaves every other speed as it would be without
// them, and a damped sweep is bit for bit what it is without a bound.
#include "dynamics/modes.h"
#include "dynamics/sweep.h"
#include "tests/dynamics/pair_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

using namespace gearkit;

namespace
{
/// The fixture pair with K_m varying by +-30 % over the mesh cycle, a speed-controlled motor,
/// no backlash; damping scaled by `damping` (0: none anywhere).
PairModel
pumped_pair(double damping)
{
  PairModelParameters p    = test_data::bevel_like_parameters(0, damping);
  p.speed_controlled_motor = true;
  MeshCycleSamples tables  = test_data::bevel_like_tables(64);
  for (int i = 0; i < 64; ++i)
    tables.mesh_stiffness[std::size_t(i)] *= 1 + 0.3 * std::cos(2 * pi * i / 64);
  return PairModel(p, tables);
}

/// The mode with the most mesh strain energy [Hz].
double
mesh_mode(const PairModel &model)
{
  const PairModes modes = linear_modes(model);
  const auto k = std::size_t(std::max_element(modes.mesh_energy.begin(), modes.mesh_energy.end()) -
                             modes.mesh_energy.begin());
  return modes.frequency[k];
}

/// Pinion speed [rad/s] of a mesh frequency [Hz] (55 pinion teeth).
double
speed_of(double mesh_frequency)
{
  return 2 * pi * mesh_frequency / 55;
}

RunOptions
newmark_run(const PairModel &model, double omega)
{
  RunOptions r;
  r.omega = omega, r.load_torque = 100;
  r.motor_torque    = model.static_equilibrium(100).motor_torque;
  r.method          = Integrator::newmark;
  r.steps_per_cycle = 128;
  return r;
}

/// |delta_D - E_t| of every sample within the bound and every state finite.
void
expect_finite_within(const Trajectory &t, double bound)
{
  for (std::size_t k = 0; k < t.t.size(); ++k)
    {
      ASSERT_TRUE(t.q[k].allFinite() && t.v[k].allFinite() && std::isfinite(t.force[k])) << k;
      ASSERT_LE(std::abs(t.relative[k]), bound) << k;
    }
}

void
expect_same_point(const SweepPoint &a, const SweepPoint &b)
{
  EXPECT_EQ(a.speed, b.speed);
  EXPECT_EQ(a.dte_pp, b.dte_pp);
  EXPECT_EQ(a.dte_rms, b.dte_rms);
  EXPECT_EQ(a.relative_pp, b.relative_pp);
  EXPECT_EQ(a.relative_rms, b.relative_rms);
  EXPECT_EQ(a.max_force, b.max_force);
  EXPECT_EQ(a.load_factor, b.load_factor);
  EXPECT_EQ(a.contact_loss, b.contact_loss);
  EXPECT_EQ(a.events, b.events);
  EXPECT_EQ(a.settled_cycles, b.settled_cycles);
  EXPECT_EQ(a.steps_per_cycle, b.steps_per_cycle);
  EXPECT_TRUE(a.error_estimate == b.error_estimate ||
              (std::isnan(a.error_estimate) && std::isnan(b.error_estimate)));
  EXPECT_EQ(a.period, b.period);
  EXPECT_EQ(a.diverged, b.diverged);
  EXPECT_EQ(a.diverged_time, b.diverged_time);
  EXPECT_EQ(a.spectrum, b.spectrum);
}
} // namespace

TEST(Divergence, IntegratorsStopAtTheFirstStepOrSamplePastTheBound)
{
  const PairModel model = pumped_pair(0);
  const double    f     = mesh_mode(model);
  // at twice the mesh mode's frequency (the principal parametric resonance) the motion grows
  RunOptions   r  = newmark_run(model, speed_of(2 * f));
  const double mu = std::abs(floquet_multipliers(model, r).front());
  ASSERT_GT(mu, 1.1) << f << " Hz";
  const PairVector q0 = model.static_equilibrium(100).q, v0 = PairVector::Zero();

  // Newmark without a bound, every step a sample: the first step past the bound B is where the
  // bounded run stops, and every sample before it is the same to the bit
  r.mesh_cycles         = 200;
  r.samples_per_cycle   = r.steps_per_cycle;
  const Trajectory free = simulate(model, q0, v0, r);
  ASSERT_FALSE(free.diverged);
  const double B     = 1e3 * std::abs(free.relative.front());
  const auto   first = std::size_t(std::find_if(free.relative.begin(), free.relative.end(),
                                                [&](double x) { return std::abs(x) > B; }) -
                                   free.relative.begin());
  ASSERT_LT(first, free.relative.size()) << "grows past 1000 times the static deflection";
  r.divergence_bound      = B;
  const Trajectory capped = simulate(model, q0, v0, r);
  EXPECT_TRUE(capped.diverged);
  EXPECT_EQ(capped.diverged_at, free.t[first]);
  ASSERT_EQ(capped.t.size(), first);
  for (std::size_t k = 0; k < first; ++k)
    ASSERT_TRUE(capped.t[k] == free.t[k] && capped.q[k] == free.q[k] &&
                capped.relative[k] == free.relative[k])
        << k;
  EXPECT_EQ(capped.steps, first - 1);
  expect_finite_within(capped, B);

  // CVODE: the same at its samples (the bound checked there and at events only)
  RunOptions c         = r;
  c.method             = Integrator::cvode_bdf;
  c.samples_per_cycle  = 8;
  c.divergence_bound   = std::numeric_limits<double>::infinity();
  const Trajectory cf  = simulate(model, q0, v0, c);
  const auto       cfk = std::size_t(std::find_if(cf.relative.begin(), cf.relative.end(),
                                                  [&](double x) { return std::abs(x) > B; }) -
                                     cf.relative.begin());
  ASSERT_LT(cfk, cf.relative.size());
  c.divergence_bound     = B;
  const Trajectory cvode = simulate(model, q0, v0, c);
  EXPECT_TRUE(cvode.diverged);
  EXPECT_EQ(cvode.diverged_at, cf.t[cfk]);
  ASSERT_EQ(cvode.t.size(), cfk);
  EXPECT_EQ(cvode.q.back(), cf.q[cfk - 1]);
  expect_finite_within(cvode, B);

  // the growth is the Floquet multiplier's: log(B / |x_0|) / log(mu) mesh cycles, within a
  // factor of 1.5 (the start projects on every Floquet mode, and the amplitude beats within
  // a cycle)
  const double cycles   = free.t[first] * 55 * r.omega / (2 * pi);
  const double expected = std::log(1e3) / std::log(mu);
  EXPECT_GT(cycles, expected / 1.5) << mu;
  EXPECT_LT(cycles, expected * 1.5) << mu;
}

TEST(Divergence, WithoutABoundTheRunEndsOnItsLastFiniteState)
{
  // the same resonance run until the numbers overflow: the run stops before the first state
  // that is not finite, and says so (before, the samples went on as inf and NaN)
  const PairModel model = pumped_pair(0);
  RunOptions      r     = newmark_run(model, speed_of(2 * mesh_mode(model)));
  const double    mu    = std::abs(floquet_multipliers(model, r).front());
  r.steps_per_cycle = 64, r.samples_per_cycle = 64;
  // twice the cycles to grow from a micrometre past the largest double
  r.mesh_cycles =
      std::ceil(2 * (std::log(std::numeric_limits<double>::max()) - std::log(1e-6)) / std::log(mu));
  const Trajectory t = simulate(model, model.static_equilibrium(100).q, PairVector::Zero(), r);
  EXPECT_TRUE(t.diverged);
  EXPECT_LT(t.diverged_at, r.mesh_cycles * 2 * pi / (55 * r.omega));
  expect_finite_within(t, std::numeric_limits<double>::max());
  EXPECT_GT(std::abs(t.relative.back()), 1e200) << "it ran until the numbers gave out";
}

TEST(Divergence, UndampedSweepFlagsTheFloquetUnstableSpeedsAndLeavesTheOthers)
{
  const PairModel model = pumped_pair(0);
  const double    f     = mesh_mode(model);
  SweepOptions    o;
  // a tight steady check and fixed Newmark steps, as this test was written for
  o.steady_tolerance = 1e-6, o.accuracy = 0;
  o.load_torque = 100, o.motor_torque = model.static_equilibrium(100).motor_torque;
  o.settle_cycles = 400, o.record_cycles = 10;
  o.run.method = Integrator::newmark, o.run.steps_per_cycle = 128;
  // mesh frequencies below, in and above the principal parametric resonance at 2 f
  for (double x : {1.5, 1.9, 2.0, 2.1, 2.6, 3.2})
    o.speeds.push_back(speed_of(x * f));
  std::vector<double> radius;
  for (double w : o.speeds)
    radius.push_back(std::abs(floquet_multipliers(model, newmark_run(model, w)).front()));
  const PairVector s0 = model.static_equilibrium(100).q;
  PairVector       q = s0, v = PairVector::Zero();
  const auto       swept = sweep(model, q, v, o);
  ASSERT_EQ(swept.size(), o.speeds.size());
  int unstable = 0, stable = 0;
  for (std::size_t i = 0; i < swept.size(); ++i)
    {
      const SweepPoint &p = swept[i];
      SCOPED_TRACE("mesh frequency " + std::to_string(o.speeds[i] * 55 / (2 * pi) / f) +
                   " f, spectral radius " + std::to_string(radius[i]));
      // every result finite, whatever happened
      for (double x : {p.dte_pp, p.dte_rms, p.relative_pp, p.relative_rms, p.max_force,
                       p.load_factor, p.contact_loss, p.error_estimate, p.diverged_time})
        EXPECT_TRUE(std::isfinite(x));
      for (double a : p.spectrum)
        ASSERT_TRUE(std::isfinite(a));
      EXPECT_EQ(p.spectrum.size(), swept.front().spectrum.size());
      std::cout << "mesh frequency " << o.speeds[i] * 55 / (2 * pi) / f << " f: radius "
                << radius[i] << (p.diverged ? ", diverged after " : ", DTE p-p ")
                << (p.diverged ? p.diverged_time * 55 * o.speeds[i] / (2 * pi) : p.dte_pp)
                << (p.diverged ? " mesh cycles" : " m") << "\n";
      if (parametrically_unstable(radius[i]))
        {
          ++unstable;
          ASSERT_GT(radius[i], 1.01); // no speed on the band's edge: it diverges in time
          EXPECT_TRUE(p.diverged);
          EXPECT_EQ(p.period, 0);
          EXPECT_TRUE(p.dte_pp == 0 && p.dte_rms == 0 && p.max_force == 0 && p.load_factor == 0 &&
                      p.relative_pp == 0 && p.error_estimate == 0);
          EXPECT_TRUE(
              std::all_of(p.spectrum.begin(), p.spectrum.end(), [](double a) { return a == 0; }));
          EXPECT_TRUE(p.series_time.empty());
          // within the cycles a growth by the multiplier needs to cross the bound from the
          // start's transient (a few times smaller than the static deflection and more)
          const double cycles = p.diverged_time * 55 * o.speeds[i] / (2 * pi);
          EXPECT_GT(cycles, std::log(1e3) / std::log(radius[i]) / 1.5);
          EXPECT_LT(cycles, std::log(1e5) / std::log(radius[i]));
        }
      else
        {
          ++stable;
          // undamped and stable: the multipliers on the unit circle, to rounding
          EXPECT_NEAR(radius[i], 1, 1e-11);
          EXPECT_FALSE(p.diverged);
          EXPECT_EQ(p.diverged_time, 0);
          EXPECT_GT(p.dte_pp, 0);
          EXPECT_GT(p.load_factor, 1);
        }
    }
  EXPECT_GE(unstable, 2);
  EXPECT_GE(stable, 3);

  // the stable speeds are what sweeps without the unstable ones give: the one before the band
  // on its own from the static equilibrium, those after it from there too (a diverged speed
  // hands the next one the static equilibrium), to the bit
  auto alone = [&](std::vector<double> speeds) {
    SweepOptions s = o;
    s.speeds       = std::move(speeds);
    PairVector a = s0, b = PairVector::Zero();
    return sweep(model, a, b, s);
  };
  const auto before = alone({o.speeds[0]});
  expect_same_point(swept[0], before[0]);
  std::size_t last = 0; // the last diverged speed
  for (std::size_t i = 0; i < swept.size(); ++i)
    if (swept[i].diverged)
      last = i;
  ASSERT_GT(last, 0u);
  ASSERT_LT(last + 1, swept.size());
  const auto after = alone(std::vector<double>(o.speeds.begin() + long(last) + 1, o.speeds.end()));
  for (std::size_t k = 0; k < after.size(); ++k)
    expect_same_point(swept[last + 1 + k], after[k]);

  // CVODE flags the resonance the same way
  SweepOptions c = o;
  c.speeds       = {speed_of(2 * f)};
  c.run.method   = Integrator::cvode_adams;
  q = s0, v = PairVector::Zero();
  const auto cv = sweep(model, q, v, c);
  EXPECT_TRUE(cv[0].diverged);
  EXPECT_GT(cv[0].diverged_time, 0);
  EXPECT_EQ(cv[0].dte_pp, 0);
}

TEST(Divergence, DampedSweepIsBitForBitTheSameWithoutABound)
{
  // the divergence checks change no arithmetic: a damped sweep through the same speeds (with
  // backlash, contact loss and Newmark's step refinement from the accuracy) is to the bit what
  // it is with no bound but the finite numbers, and nothing diverges
  PairModelParameters p    = test_data::bevel_like_parameters(20e-6, 1);
  p.speed_controlled_motor = true;
  MeshCycleSamples tables  = test_data::bevel_like_tables(64, 3e8, 2e-6);
  for (int i = 0; i < 64; ++i)
    tables.mesh_stiffness[std::size_t(i)] *= 1 + 0.3 * std::cos(2 * pi * i / 64);
  const PairModel model(p, tables);
  const double    f = mesh_mode(model);
  SweepOptions    o;
  // a tight steady check, as this test was written for
  o.steady_tolerance = 1e-6;
  o.load_torque = 100, o.motor_torque = model.static_equilibrium(100).motor_torque;
  o.settle_cycles = 300, o.record_cycles = 10;
  o.run.method = Integrator::newmark, o.run.steps_per_cycle = 64;
  o.accuracy = 0.005;
  for (double x : {0.5, 1.0, 1.5, 2.0, 2.5})
    o.speeds.push_back(speed_of(x * f));
  for (Integrator method : {Integrator::newmark, Integrator::cvode_bdf})
    {
      SweepOptions bounded = o, unbounded = o;
      bounded.run.method = unbounded.run.method = method;
      unbounded.divergence_factor               = std::numeric_limits<double>::infinity();
      PairVector qa = model.static_equilibrium(100).q, va = PairVector::Zero();
      PairVector qb = qa, vb = va;
      const auto a = sweep(model, qa, va, bounded);
      const auto b = sweep(model, qb, vb, unbounded);
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < a.size(); ++i)
        {
          EXPECT_FALSE(a[i].diverged);
          expect_same_point(a[i], b[i]);
        }
      EXPECT_EQ(qa, qb);
      EXPECT_EQ(va, vb);
    }
}

TEST(Divergence, ATorqueDrivenTrainsRigidRotationIsNoParametricInstability)
{
  // damped, the motor driven by a torque: the train's free rotation gives the double multiplier
  // 1 (angle and speed), computed to about the square root of the rounding; only the principal
  // parametric resonance counts as unstable
  PairModelParameters p      = test_data::bevel_like_parameters();
  MeshCycleSamples    tables = test_data::bevel_like_tables(64);
  for (int i = 0; i < 64; ++i)
    tables.mesh_stiffness[std::size_t(i)] *= 1 + 0.3 * std::cos(2 * pi * i / 64);
  const PairModel model(p, tables);
  ASSERT_FALSE(model.parameters().speed_controlled_motor);
  const double f = mesh_mode(model);
  for (double x : {0.3, 0.7, 1.0, 1.3, 1.6, 2.0, 2.5, 3.1, 3.7})
    {
      const double radius =
          std::abs(floquet_multipliers(model, newmark_run(model, speed_of(x * f))).front());
      std::cout << "torque-driven, mesh frequency " << x << " f: radius - 1 = " << radius - 1
                << "\n";
      EXPECT_EQ(parametrically_unstable(radius), x == 2.0) << x << " f: " << radius - 1;
      if (x != 2.0)
        {
          EXPECT_NEAR(radius, 1, 1e-7) << x << " f";
        }
    }
}

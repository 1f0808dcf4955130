// The Kahraman & Singh (1991) benchmark (reference-data.md section 8): the 14-DOF model reduced
// to pure torsion (supports held, no motor and load DOFs, mesh damping always on) against the
// nondimensional single-DOF oscillator with clearance integrated independently (Boost.Odeint,
// Dormand-Prince), swept up and down in the mesh frequency with continuation.
#include "dynamics/sweep.h"
#include "tests/dynamics/pair_fixture.h"

#include <boost/numeric/odeint.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

using namespace gearkit;

namespace
{
constexpr double zeta = 0.05, Fm = 0.1; // the benchmark's
constexpr double Fe[3] = {0.01, 0.004, 0.002}, kj[3] = {0.2, 0.1, 0.05};

/// x'' + 2 zeta x' + k(tau) f(x) = Fm + sum_j Fe_j (j Omega)^2 cos(j Omega tau), b = 1.
struct KahramanSingh
{
  double Omega;
  double damping = zeta, variation = 1; ///< zeta, and a factor on the k_j
  void
  operator()(const std::array<double, 2> &y, std::array<double, 2> &dy, double tau) const
  {
    double k = 1, F = Fm;
    for (int j = 1; j <= 3; ++j)
      {
        k -= variation * kj[j - 1] * std::cos(j * Omega * tau);
        F += Fe[j - 1] * j * j * Omega * Omega * std::cos(j * Omega * tau);
      }
    const double x = y[0], f = x >= 1 ? x - 1 : x <= -1 ? x + 1 : 0;
    dy[0] = y[1];
    dy[1] = F - 2 * damping * y[1] - k * f;
  }
};

/// RMS (32 samples a period, as the sweep records) and peak-to-peak of x over `record` periods
/// after `settle`, continuing from y. The peak-to-peak of the continuous solution: x at 4096
/// points a period, each local extreme refined by the parabola through it and its neighbours
/// (its error ~ (2 pi / 4096)^3 of the amplitude: below 1e-8).
std::pair<double, double>
oscillator(double Omega, std::array<double, 2> &y, int settle, int record)
{
  using namespace boost::numeric::odeint;
  auto stepper       = make_dense_output(1e-11, 1e-11, runge_kutta_dopri5<std::array<double, 2>>());
  const double T     = 2 * pi / Omega;
  const int    dense = 4096;
  integrate_const(stepper, KahramanSingh{Omega}, y, 0.0, settle * T, T);
  std::vector<double> x;
  integrate_const(stepper, KahramanSingh{Omega}, y, 0.0, record * T, T / dense,
                  [&](const std::array<double, 2> &s, double) { x.push_back(s[0]); });
  double      mean = 0, rms = 0;
  std::size_t samples = 0;
  for (std::size_t i = 0; i + 1 < x.size(); i += dense / 32, ++samples)
    mean += x[i];
  mean /= double(samples);
  for (std::size_t i = 0; i + 1 < x.size(); i += dense / 32)
    rms += (x[i] - mean) * (x[i] - mean) / double(samples);
  double lo = std::min(x.front(), x.back()), hi = std::max(x.front(), x.back());
  for (std::size_t i = 1; i + 1 < x.size(); ++i)
    if ((x[i] - x[i - 1]) * (x[i + 1] - x[i]) <= 0) // a local extreme: the parabola's vertex
      {
        const double c = x[i + 1] - 2 * x[i] + x[i - 1], b = (x[i + 1] - x[i - 1]) / 2;
        const double v = c != 0 ? x[i] - b * b / (2 * c) : x[i];
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
  return {std::sqrt(rms), hi - lo};
}

/// The 14-DOF model reduced to the oscillator (physical parameters chosen freely; the
/// nondimensional groups are the benchmark's): supports held, no motor and load DOFs (torques
/// straight on pinion and gear), one mesh cycle per pinion turn, mesh damping always on; its
/// damping ratio and a factor on the stiffness variation given. `options` carry the torques
/// that balance the mean mesh force F = Fm k b (T_E = F lambda_pz, T_L = F lambda_gy).
/// Omega = from, from + step, ... to `to` (inclusive within rounding), reversed when down.
std::vector<double>
omegas(double from, double to, double step, bool up = true)
{
  std::vector<double> W;
  for (double x = from; x <= to + 1e-3 * step; x += step)
    W.push_back(x);
  if (!up)
    std::reverse(W.begin(), W.end());
  return W;
}

struct Reduction
{
  static constexpr double b = 10e-6, kbar = 1e8;
  PairModel               model;
  double                  wn = 0; ///< [rad/s]
  SweepOptions            options;

  /// Pinion speeds [rad/s] of the frequency ratios W (pinion speed = mesh frequency, z = 1).
  std::vector<double>
  speeds(const std::vector<double> &W) const
  {
    std::vector<double> w;
    for (double x : W)
      w.push_back(x * wn);
    return w;
  }

  Reduction(double damping, double variation)
      : model(parameters(damping), tables(variation))
  {
    wn                = std::sqrt(kbar / model.mesh_mass());
    const MeshState m = model.mesh().mean();
    const double    F = Fm * kbar * b;
    // a tight steady check and fixed Newmark steps, as this test was written for
    options.steady_tolerance = 1e-6, options.accuracy = 0;
    options.motor_torque = F * m.lp.z();
    options.load_torque  = F * m.lg.y();
  }

  static PairModelParameters
  parameters(double damping)
  {
    PairModelParameters p = test_data::bevel_like_parameters(b);
    p.motor_inertia = p.load_inertia = 0;
    p.torsion_only                   = true;
    p.mesh_damping_in_contact_only   = false;
    p.mesh_damping_ratio             = damping;
    p.pinion_teeth                   = 1;
    return p;
  }

  static MeshCycleSamples
  tables(double variation)
  {
    MeshCycleSamples t = test_data::bevel_like_tables(32, kbar);
    for (int i = 0; i < 32; ++i)
      {
        const double phase = double(i) / 32;
        double       k = 1, e = 0;
        for (int j = 1; j <= 3; ++j)
          {
            k -= variation * kj[j - 1] * std::cos(2 * pi * j * phase);
            e += Fe[j - 1] * b * std::cos(2 * pi * j * phase);
          }
        t.mesh_stiffness[i] = kbar * k, t.transmission_error[i] = e;
      }
    return t;
  }
};
} // namespace

TEST(KahramanSingh, TorsionalReductionMatchesTheOscillatorUpAndDown)
{
  // physical parameters chosen freely; the nondimensional groups are the benchmark's
  const Reduction  ks(zeta, 1);
  const PairModel &model = ks.model;
  const double     b     = Reduction::b;
  SweepOptions     o     = ks.options;
  o.settle_cycles = 150, o.record_cycles = 30;
  o.run.method = Integrator::cvode_bdf, o.run.samples_per_cycle = 32;
  o.run.relative_tolerance = 1e-9, o.run.absolute_tolerance = 1e-9;
  const std::vector<double> Omegas = omegas(0.6, 1.4, 0.05);

  std::vector<double> up_rms, down_rms, newmark_rms;
  double              worst_pp = 0;
  for (bool up : {true, false})
    {
      const std::vector<double> W = omegas(0.6, 1.4, 0.05, up);
      o.speeds                    = ks.speeds(W);
      const StaticEquilibrium s   = model.static_equilibrium(o.load_torque);
      PairVector              q = s.q, v = PairVector::Zero();
      const auto              points = sweep(model, q, v, o);
      std::array<double, 2>   y{1 + Fm, 0}; // the oscillator's static state
      for (std::size_t i = 0; i < W.size(); ++i)
        {
          const auto [rms, pp]   = oscillator(W[i], y, o.settle_cycles, o.record_cycles);
          const double model_rms = points[i].relative_rms / b, model_pp = points[i].relative_pp / b;
          EXPECT_NEAR(model_rms, rms, 0.01 * rms + 1e-4)
              << (up ? "up" : "down") << " Omega " << W[i];
          // the peak-to-peak of the continuous solutions (the sweep's located inside its steps)
          EXPECT_NEAR(model_pp, pp, 0.005 * pp) << (up ? "up" : "down") << " Omega " << W[i];
          worst_pp = std::max(worst_pp, std::abs(model_pp / pp - 1));
          (up ? up_rms : down_rms).push_back(rms);
          // the Poincare section found the periodic motion before the fixed settling ended
          EXPECT_EQ(points[i].period, 1) << (up ? "up" : "down") << " Omega " << W[i];
          EXPECT_LT(points[i].settled_cycles, o.settle_cycles);
        }
    }
  std::printf("CVODE BDF 1e-9: peak-to-peak within %.2e of the continuous reference\n", worst_pp);
  // the fixed-step path of the sweeps, up: within 2 % with 128 steps per mesh cycle (RMS and
  // the peak-to-peak located inside its steps)
  {
    SweepOptions n = o;
    n.run.method = Integrator::newmark, n.run.steps_per_cycle = 128;
    n.speeds                = ks.speeds(Omegas);
    PairVector            q = model.static_equilibrium(o.load_torque).q, v = PairVector::Zero();
    const auto            points = sweep(model, q, v, n);
    std::array<double, 2> y{1 + Fm, 0};
    double                worst = 0;
    for (std::size_t i = 0; i < Omegas.size(); ++i)
      {
        EXPECT_NEAR(points[i].relative_rms / b, up_rms[i], 0.02 * up_rms[i])
            << "Newmark, Omega " << Omegas[i];
        const double pp = oscillator(Omegas[i], y, o.settle_cycles, o.record_cycles).second;
        EXPECT_NEAR(points[i].relative_pp / b, pp, 0.02 * pp) << "Newmark, Omega " << Omegas[i];
        worst = std::max(worst, std::abs(points[i].relative_pp / b / pp - 1));
      }
    std::printf("Newmark 128 steps: peak-to-peak within %.2e of the continuous reference\n", worst);
  }
  std::reverse(down_rms.begin(), down_rms.end());
  // hysteresis: near Omega = 1 the two sweeps sit on different branches
  double widest = 0;
  for (std::size_t i = 0; i < Omegas.size(); ++i)
    widest = std::max(widest, std::abs(up_rms[i] - down_rms[i]));
  EXPECT_GT(widest, 0.05) << "no jump between the up and down sweeps";
  for (std::size_t i = 0; i < Omegas.size(); ++i)
    std::printf("Omega %.2f  rms up %.4f  down %.4f\n", Omegas[i], up_rms[i], down_rms[i]);
}

namespace
{
/// The period (1 to 6 excitation periods) of the oscillator's motion after settling 1000 periods
/// from y (continued), by its Poincare points over the following 24 periods: the smallest p with
/// every point within 1e-7 (position, speed) of the one p periods earlier; 0 when none.
int
oscillator_period(const KahramanSingh &oscillator, std::array<double, 2> &y)
{
  const double Omega = oscillator.Omega;
  using namespace boost::numeric::odeint;
  auto stepper   = make_dense_output(1e-12, 1e-12, runge_kutta_dopri5<std::array<double, 2>>());
  const double T = 2 * pi / Omega;
  integrate_const(stepper, oscillator, y, 0.0, 1000 * T, T);
  std::vector<std::array<double, 2>> points;
  integrate_const(stepper, oscillator, y, 0.0, 24 * T, T,
                  [&](const std::array<double, 2> &s, double) { points.push_back(s); });
  for (int p = 1; p <= 6; ++p)
    {
      double worst = 0;
      for (std::size_t k = std::size_t(p); k < points.size(); ++k)
        worst = std::max({worst, std::abs(points[k][0] - points[k - std::size_t(p)][0]),
                          std::abs(points[k][1] - points[k - std::size_t(p)][1])});
      if (worst < 1e-7)
        return p;
    }
  return 0;
}

/// The torsional reduction of the 14-DOF model as the oscillator with damping ratio `damping`
/// and the stiffness variation scaled by `variation`, swept with the defaults (BDF 1e-8, settle
/// at most 200 cycles, steady tolerance 1e-6 - 1e-5 by the integrator's) over the Omegas up:
/// per speed the sweep's period label and the oscillator's, settled 1000 periods along the
/// same continuation. Returns the speeds the sweep found not steady though the oscillator is
/// periodic.
std::vector<double>
check_period_labels(const std::vector<double> &Omegas, double damping, double variation)
{
  const Reduction  ks(damping, variation);
  const PairModel &model  = ks.model;
  SweepOptions     o      = ks.options;
  o.speeds                = ks.speeds(Omegas);
  PairVector            q = model.static_equilibrium(o.load_torque).q, v = PairVector::Zero();
  const auto            points = sweep(model, q, v, o);
  std::array<double, 2> y{1 + Fm, 0};
  std::vector<double>   unsettled;
  int                   most = 0;
  for (std::size_t i = 0; i < Omegas.size(); ++i)
    {
      const int expected = oscillator_period({Omegas[i], damping, variation}, y);
      most               = std::max(most, points[i].settled_cycles);
      if (points[i].period == 0 && expected != 0)
        {
          unsettled.push_back(Omegas[i]);
          EXPECT_EQ(points[i].settled_cycles, o.settle_cycles) << "Omega " << Omegas[i];
          continue;
        }
      EXPECT_EQ(points[i].period, expected <= 4 ? expected : 0)
          << "Omega " << Omegas[i] << ", settled " << points[i].settled_cycles << " cycles";
    }
  std::printf("period labels: %zu speeds, all right but %zu not steady; longest settling %d "
              "cycles\n",
              Omegas.size(), unsettled.size(), most);
  return unsettled;
}
} // namespace

TEST(KahramanSingh, PeriodLabelsOfTheSweepMatchALongIndependentIntegration)
{
  // the benchmark over Omega 0.3 - 2.0: period 1 everywhere but a weak period 2 (Poincare
  // points 3e-6 to 3e-5 b apart) just past a period doubling near Omega = 2, where the
  // transient decays by 0.4 % a cycle (critical slowing down: more than 1000 cycles to the
  // tolerance, beyond the fivefold extension of the settling): "not steady" is allowed there
  // only. Before the three-period confirmation, the integrator-scaled tolerance, the still
  // period-1 mismatch asked of a subharmonic and the extension, 27 of the 86 labels were
  // wrong (transients taken for period 2 or 3, period-1 motions never found steady at 1e-8).
  const std::vector<double> unsettled = check_period_labels(omegas(0.3, 2.0, 0.02), zeta, 1);
  EXPECT_LE(unsettled.size(), 2u);
  for (double W : unsettled)
    EXPECT_GE(W, 1.95) << "not steady within the settling at Omega " << W;
}

TEST(KahramanSingh, SubharmonicsOfAStrongerVariationAreFound)
{
  // twice the stiffness variation, zeta 0.02: period 4 over Omega 1.84 - 1.94, period 2 over
  // 1.98 - 2.18 (Poincare points 0.03 b apart), period 1 around them; the sweep's labels
  // against the oscillator's at every speed
  const std::vector<double> unsettled = check_period_labels(omegas(1.8, 2.3, 0.02), 0.02, 2);
  EXPECT_LE(unsettled.size(), 2u);
}

TEST(KahramanSingh, NewmarkStepsFromTheAccuracyHoldHalfAPercentUpAndDown)
{
  // Newmark with its steps per mesh cycle from the accuracy wanted (0.5 % of the DTE RMS): at
  // every speed of Omega 0.3 - 2.0, up and down, against the oscillator integrated alone; 64
  // steps a cycle for contrast (8 % off near Omega 0.3, where the mode sits at 3.3 mesh orders)
  const Reduction  ks(zeta, 1);
  const PairModel &model = ks.model;
  const double     b     = Reduction::b;
  SweepOptions     o     = ks.options;
  o.settle_cycles = 400, o.record_cycles = 30, o.steady_tolerance = 0;
  o.run.method = Integrator::newmark, o.run.steps_per_cycle = 64;
  double              worst = 0, worst_64 = 0;
  std::map<long, int> steps; // at 100 Omega
  // the down sweeps go on from where the up sweeps end (the oscillator's too)
  std::array<double, 2> y{1 + Fm, 0};
  PairVector            q[2], v[2];
  for (int a = 0; a < 2; ++a)
    q[a] = model.static_equilibrium(o.load_torque).q, v[a] = PairVector::Zero();
  for (bool up : {true, false})
    {
      const std::vector<double> W = omegas(0.3, 2.0, 0.05, up);
      o.speeds                    = ks.speeds(W);
      std::vector<double> reference;
      for (double w : W)
        reference.push_back(oscillator(w, y, o.settle_cycles, o.record_cycles).first);
      for (int a = 0; a < 2; ++a)
        {
          const double accuracy = a == 0 ? 0.005 : 0.0;
          SweepOptions s        = o;
          s.accuracy            = accuracy;
          const auto points     = sweep(model, q[a], v[a], s);
          for (std::size_t i = 0; i < W.size(); ++i)
            {
              const double error = std::abs(points[i].relative_rms / b / reference[i] - 1);
              (accuracy > 0 ? worst : worst_64) = std::max(accuracy > 0 ? worst : worst_64, error);
              if (accuracy > 0)
                {
                  EXPECT_LT(error, accuracy)
                      << (up ? "up" : "down") << " Omega " << W[i] << ": "
                      << points[i].steps_per_cycle << " steps a cycle, error estimated "
                      << points[i].error_estimate;
                  steps[std::lround(100 * W[i])] = points[i].steps_per_cycle;
                }
            }
        }
    }
  std::printf("Newmark from the accuracy 0.5 %%: worst RMS error %.2e (64 steps a cycle: %.2e); "
              "steps a cycle at Omega 0.3 / 1 / 2 (down): %d / %d / %d\n",
              worst, worst_64, steps[30], steps[100], steps[200]);
  EXPECT_GT(worst_64, 0.02); // the contrast: the fixed count is far off somewhere
}

// Mesh tables over several mesh cycles (measured flanks), makima interpolation, the sweep's DTE
// spectrum against the frequency-domain solution (one and three mesh cycles per excitation
// period), time series kept, and sweeps in parallel and in blocks against one sequential sweep.
#include "dynamics/modes.h"
#include "dynamics/sweep.h"
#include "tests/dynamics/pair_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace gearkit;

namespace
{
/// Tables of the fixture with E_t = sum of amplitude[k] sin(2 pi (k + 1) phase / cycles).
MeshCycleSamples
tables(int n, int cycles, const std::vector<double> &amplitude,
       MeshInterpolation how = MeshInterpolation::trigonometric)
{
  MeshCycleSamples s = test_data::bevel_like_tables(n);
  s.cycles = cycles, s.interpolation = how;
  for (int i = 0; i < n; ++i)
    {
      double e = 0;
      for (std::size_t k = 0; k < amplitude.size(); ++k)
        e += amplitude[k] * std::sin(2 * pi * double(k + 1) * i / n);
      s.transmission_error[std::size_t(i)] = e;
    }
  return s;
}
} // namespace

TEST(MeshCycle, ResamplesPeriodicTablesAndBalancesTheTorque)
{
  // A trigonometric polynomial of degree 3 given at 8 phases is resampled exactly (8 > 2 * 3)
  // at 20 others; K_m (1 - v cos 2 pi phase) at its samples is the formula.
  std::vector<double> k;
  auto                f = [](double x) {
    return 300e6 + 20e6 * std::cos(2 * pi * x) - 7e6 * std::sin(6 * pi * x);
  };
  for (int i = 0; i < 8; ++i)
    k.push_back(f(i / 8.0));
  const std::vector<double> r = resample_periodic(k, 20);
  ASSERT_EQ(r.size(), 20u);
  for (int i = 0; i < 20; ++i)
    EXPECT_NEAR(r[i], f(i / 20.0), 1e-6) << i; // 1e-15 relative of 3e8 N/m
  const std::vector<double> v = varying_mesh_stiffness(300e6, 0.1, 4);
  EXPECT_DOUBLE_EQ(v[0], 270e6);
  EXPECT_NEAR(v[1], 300e6, 1e-6);
  EXPECT_DOUBLE_EQ(v[2], 330e6);

  // The load torque through constant arms: T_L = T_E (lambda_g . a_g) / (lambda_p . a_p).
  MeshCycleSamples s;
  s.transmission_error = {0};
  s.mesh_stiffness     = {3e8};
  s.normal_pinion = s.normal_gear = {Vec3(0, 1, 0)};
  s.arm_pinion                    = {Vec3(0, 0, 0.03)};
  s.arm_gear                      = {Vec3(0, 0, 0.075)};
  const MeshCycle mesh(s);
  EXPECT_DOUBLE_EQ(balancing_load_torque(mesh, 100, Vec3::UnitZ(), Vec3::UnitZ()), 250);
}

TEST(MeshCycle, TablesOverSeveralCyclesAndMakima)
{
  // a step over 3 mesh cycles (as a pitch error makes in measured e_0): both interpolants are
  // exact at the samples and periodic over 3 cycles; makima stays within the samples' range,
  // the trigonometric interpolant rings past it (Gibbs)
  const int        n = 24;
  MeshCycleSamples s = test_data::bevel_like_tables(n);
  s.cycles           = 3;
  for (int i = 0; i < n; ++i)
    s.transmission_error[std::size_t(i)] = i < 12 ? 0.0 : 2e-6;
  double overshoot[2] = {0, 0};
  for (MeshInterpolation how : {MeshInterpolation::trigonometric, MeshInterpolation::makima})
    {
      s.interpolation = how;
      const MeshCycle c(s);
      EXPECT_EQ(c.cycles(), 3);
      for (int i = 0; i < n; ++i)
        {
          const double phase = 3.0 * i / n;
          EXPECT_NEAR(c.at(phase).et, s.transmission_error[std::size_t(i)], 1e-15);
          EXPECT_NEAR(c.at(phase + 3).et, s.transmission_error[std::size_t(i)], 1e-15);
          EXPECT_NEAR(c.at(phase - 6).et, s.transmission_error[std::size_t(i)], 1e-15);
        }
      for (double phase = 0; phase < 3; phase += 1e-3)
        overshoot[int(how)] =
            std::max({overshoot[int(how)], c.at(phase).et - 2e-6, -c.at(phase).et});
    }
  EXPECT_LT(overshoot[1], 1e-18) << "makima";
  EXPECT_GT(overshoot[0], 1e-7) << "trigonometric";

  // makima on a smooth table: value and slope (per mesh cycle) of a sine over 3 cycles, the
  // slope continuous across the wrap
  s = tables(96, 3, {2e-6}, MeshInterpolation::makima);
  const MeshCycle c(s);
  for (double phase : {0.0, 0.37, 1.5, 2.99})
    {
      const double x = 2 * pi * phase / 3;
      EXPECT_NEAR(c.at(phase).et, 2e-6 * std::sin(x), 2e-6 * 1e-4) << phase;
      EXPECT_NEAR(c.at(phase).det, 2e-6 * 2 * pi / 3 * std::cos(x), 2e-6 * 2e-3) << phase;
    }
  EXPECT_NEAR(c.at(-1e-9).det, c.at(1e-9).det, 1e-12);

  s.cycles = 0;
  EXPECT_THROW(MeshCycle{s}, InputError);
  s = tables(3, 1, {1e-6}, MeshInterpolation::makima);
  EXPECT_THROW(MeshCycle{s}, InputError);
}

TEST(Sweep, SpectrumMatchesTheFrequencyDomainOverOneAndThreeMeshCycles)
{
  // linear model (no backlash, constant K_m); E_t with mesh orders 1 and 2 over one mesh cycle,
  // and with orders 1/3 and 2/3 over three: the spectrum of delta_D at those orders against the
  // frequency-domain amplitudes, nothing between them; the motion repeats after 1 and 3 cycles
  const double E1 = 4e-6, E2 = 1.5e-6;
  for (int cycles : {1, 3})
    {
      const PairModel model(test_data::bevel_like_parameters(),
                            tables(32 * cycles, cycles, {E1, E2}));
      const double    TL = 100;
      const auto      s  = model.static_equilibrium(TL);
      SweepOptions    o;
      // a tight steady check and fixed Newmark steps, as this test was written for
      o.steady_tolerance = 1e-6, o.accuracy = 0;
      o.motor_torque = s.motor_torque, o.load_torque = TL;
      o.speeds        = {2 * pi * 2000 / 60, 2 * pi * 3000 / 60};
      o.settle_cycles = 3000, o.record_cycles = 31; // rounded up to whole periods
      o.run.method            = Integrator::newmark;
      o.run.steps_per_cycle   = 256;
      o.run.samples_per_cycle = 32;
      o.series_speeds         = {2 * pi * 2900 / 60};
      PairVector q = s.q, v = PairVector::Zero();
      const auto points = sweep(model, q, v, o);
      ASSERT_EQ(points.size(), 2u);
      for (const SweepPoint &p : points)
        {
          const int R = p.record_cycles;
          EXPECT_EQ(R % cycles, 0);
          EXPECT_GE(R, 31);
          EXPECT_EQ(p.period, cycles) << p.speed << " rad/s, settled " << p.settled_cycles;
          ASSERT_EQ(p.spectrum.size(), std::size_t(10 * R + 1));
          const double w = model.parameters().pinion_teeth * p.speed / cycles; // order 1/cycles
          for (int k : {1, 2})
            {
              const double exact =
                  std::abs(test_data::frequency_response(model, k * w, k == 1 ? E1 : E2));
              EXPECT_NEAR(p.spectrum[std::size_t(k * R / cycles)], exact, 3e-3 * exact)
                  << cycles << " cycles, order " << k << "/" << cycles;
            }
          for (std::size_t j = 1; j < p.spectrum.size(); ++j)
            if (int(j) != R / cycles && int(j) != 2 * R / cycles)
              {
                EXPECT_LT(p.spectrum[j], 1e-3 * p.spectrum[std::size_t(R / cycles)]) << j;
              }
        }
      // the time series at the speed nearest 2900 rpm: 3000 rpm, R cycles of samples
      EXPECT_TRUE(points[0].series_time.empty());
      const SweepPoint &p = points[1];
      ASSERT_EQ(p.series_time.size(), std::size_t(32 * p.record_cycles + 1));
      // peak-to-peak: the samples' is within the continuous solution's, which is the exact
      // steady response's (sum of the two orders, their amplitudes and phases from the
      // frequency domain) to Newmark's error
      const double pp = *std::max_element(p.series_dte.begin(), p.series_dte.end()) -
                        *std::min_element(p.series_dte.begin(), p.series_dte.end());
      const double               w  = model.parameters().pinion_teeth * p.speed / cycles;
      const std::complex<double> D1 = test_data::frequency_response(model, w, E1),
                                 D2 = test_data::frequency_response(model, 2 * w, E2);
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (int i = 0; i < 100000; ++i)
        {
          const double x = 2 * pi * i / 100000;
          const double d = D1.real() * std::sin(x) + D1.imag() * std::cos(x) +
                           D2.real() * std::sin(2 * x) + D2.imag() * std::cos(2 * x);
          lo = std::min(lo, d), hi = std::max(hi, d);
        }
      EXPECT_LE(pp, p.dte_pp);
      EXPECT_NEAR(p.dte_pp, hi - lo, 3e-3 * (hi - lo)) << cycles << " cycles";
      std::printf("%d cycles: DTE peak-to-peak %.4e (located), %.4e (exact), %.4e (samples)\n",
                  cycles, p.dte_pp, hi - lo, pp);
      EXPECT_NEAR(p.series_transmission_error[5], model.mesh().at(5.0 / 32).et, 1e-15);
    }
}

TEST(Sweep, ThreadsAndBlocksReproduceTheSequentialSweep)
{
  // backlash and a time-varying mesh (contact loss near resonance): the sequential up sweep
  // against the same on two threads (identical) and in 3 blocks with 4 warm-up speeds each
  // (the continuation regained: the same steady states)
  MeshCycleSamples t = tables(32, 1, {8e-6});
  for (int i = 0; i < 32; ++i)
    t.mesh_stiffness[std::size_t(i)] = 3e8 * (1 - 0.2 * std::cos(2 * pi * i / 32));
  const PairModel model(test_data::bevel_like_parameters(10e-6), t);
  const auto      s = model.static_equilibrium(60);
  SweepOptions    o;
  // a tight steady check and fixed Newmark steps, as this test was written for
  o.steady_tolerance = 1e-6, o.accuracy = 0;
  o.motor_torque = s.motor_torque, o.load_torque = 60;
  for (int i = 0; i < 18; ++i)
    o.speeds.push_back(2 * pi * (500 + 400.0 * i) / 60);
  o.settle_cycles = 400, o.record_cycles = 20;
  o.run.method = Integrator::newmark, o.run.steps_per_cycle = 64, o.run.samples_per_cycle = 32;
  SweepOptions down = o;
  std::reverse(down.speeds.begin(), down.speeds.end());

  PairVector q = s.q, v = PairVector::Zero();
  const auto up = sweep(model, q, v, o);
  q = s.q, v = PairVector::Zero();
  const auto back = sweep(model, q, v, down);

  const auto both = run_sweeps(
      {{&model, s.q, PairVector::Zero(), o}, {&model, s.q, PairVector::Zero(), down}}, 2);
  ASSERT_EQ(both.size(), 2u);
  for (std::size_t i = 0; i < up.size(); ++i)
    {
      EXPECT_EQ(both[0][i].dte_pp, up[i].dte_pp);
      EXPECT_EQ(both[1][i].dte_pp, back[i].dte_pp);
    }

  const auto pieces = split_sweep(o, 3, 4);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].warmup_speeds, 0);
  EXPECT_EQ(pieces[1].warmup_speeds, 4);
  std::vector<SweepTask> tasks;
  for (const SweepOptions &b : pieces)
    tasks.push_back({&model, s.q, PairVector::Zero(), b});
  std::vector<SweepPoint> joined;
  for (const auto &r : run_sweeps(tasks, 2))
    joined.insert(joined.end(), r.begin(), r.end());
  ASSERT_EQ(joined.size(), up.size());
  bool lost = false;
  for (std::size_t i = 0; i < up.size(); ++i)
    {
      EXPECT_EQ(joined[i].speed, up[i].speed);
      EXPECT_NEAR(joined[i].dte_pp, up[i].dte_pp, 1e-4 * up[i].dte_pp) << i;
      lost = lost || up[i].contact_loss > 0;
    }
  EXPECT_TRUE(lost) << "the case should lose contact somewhere";

  // an error in one task comes back
  SweepTask bad{&model, s.q, PairVector::Zero(), o};
  bad.options.record_cycles = 0;
  EXPECT_THROW(run_sweeps({tasks[0], bad}, 2), InputError);
  EXPECT_THROW(split_sweep(o, 0, 1), InputError);
}

TEST(Floquet, ConstantMeshMatchesTheStateMatrixAndVaryingStiffnessResonatesParametrically)
{
  // constant tables: the multipliers are exp(lambda T) of the state matrix's eigenvalues (T one
  // mesh period), the largest modulus to 1e-6 (a speed-controlled motor: no rigid rotation,
  // whose multiplier would be 1)
  PairModelParameters held    = test_data::bevel_like_parameters();
  held.speed_controlled_motor = true;
  const PairModel model(held, test_data::bevel_like_tables());
  RunOptions      o;
  o.omega = 2 * pi * 3000 / 60, o.load_torque = 100;
  o.motor_torque = model.static_equilibrium(100).motor_torque;
  o.method = Integrator::cvode_bdf, o.relative_tolerance = 1e-11, o.absolute_tolerance = 1e-11;
  const auto mu = floquet_multipliers(model, o);

  std::vector<int> index;
  for (int i = 0; i < pair_dofs; ++i)
    if (model.active()[i] > 0)
      index.push_back(i);
  const int        n = int(index.size());
  const MeshState  m = model.mesh().mean();
  const PairVector g = PairModel::mesh_gradient(m);
  const PairMatrix K = model.stiffness() + m.km * g * g.transpose();
  const PairMatrix C = model.damping() + model.mesh_damping() * g * g.transpose();
  Eigen::MatrixXd  A = Eigen::MatrixXd::Zero(2 * n, 2 * n), Mr(n, n), Kr(n, n), Cr(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      Mr(a, b) = model.mass()(index[a], index[b]), Kr(a, b) = K(index[a], index[b]),
            Cr(a, b) = C(index[a], index[b]);
  A.topRightCorner(n, n)    = Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n)  = -Mr.ldlt().solve(Kr);
  A.bottomRightCorner(n, n) = -Mr.ldlt().solve(Cr);
  const double T            = 2 * pi / (model.parameters().pinion_teeth * o.omega);
  double       largest      = 0;
  const Eigen::EigenSolver<Eigen::MatrixXd> state(A, false);
  for (const auto &lambda : state.eigenvalues())
    largest = std::max(largest, std::exp(lambda.real() * T));
  ASSERT_EQ(int(mu.size()), 2 * n);
  EXPECT_NEAR(std::abs(mu.front()), largest, 1e-6);
  EXPECT_LT(std::abs(mu.front()), 1);

  // K_m varying by +-30 % over the mesh cycle: at a mesh frequency of twice the mesh mode's
  // (the principal parametric resonance) a multiplier leaves the unit circle; at 1.3 times it,
  // or without the variation, none does
  MeshCycleSamples varying = test_data::bevel_like_tables(64);
  for (int i = 0; i < 64; ++i)
    varying.mesh_stiffness[std::size_t(i)] *= 1 + 0.3 * std::cos(2 * pi * i / 64);
  const PairModel   pumped(held, varying);
  const PairModes   modes = linear_modes(pumped);
  const std::size_t k =
      std::size_t(std::max_element(modes.mesh_energy.begin(), modes.mesh_energy.end()) -
                  modes.mesh_energy.begin());
  const double f      = modes.frequency[k]; // the mesh mode [Hz]
  auto         radius = [&](const PairModel &mdl, double mesh_frequency) {
    RunOptions r = o;
    r.method = Integrator::newmark, r.steps_per_cycle = 512;
    r.omega = 2 * pi * mesh_frequency / mdl.parameters().pinion_teeth;
    return std::abs(floquet_multipliers(mdl, r).front());
  };
  EXPECT_GT(radius(pumped, 2 * f), 1.01) << f << " Hz";
  EXPECT_LT(radius(pumped, 1.3 * f), 1) << f << " Hz";
  EXPECT_LT(radius(model, 2 * f), 1) << f << " Hz";

  // swept there without backlash (nothing limits the growth): the point is flagged diverged
  // with zero results, and the next speed starts afresh from the static equilibrium
  PairModelParameters tight = held;
  tight.half_backlash       = 0;
  const PairModel lin(tight, varying);
  SweepOptions    sw;
  // a tight steady check and fixed Newmark steps, as this test was written for
  sw.steady_tolerance = 1e-6, sw.accuracy = 0;
  sw.load_torque = 100, sw.motor_torque = lin.static_equilibrium(100).motor_torque;
  sw.speeds        = {2 * pi * 2 * f / 55, 2 * pi * 1.3 * f / 55};
  sw.settle_cycles = 3000, sw.record_cycles = 10;
  sw.run.method = Integrator::newmark, sw.run.steps_per_cycle = 128;
  PairVector q = lin.static_equilibrium(100).q, v = PairVector::Zero();
  const auto points = sweep(lin, q, v, sw);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_TRUE(points[0].diverged);
  EXPECT_GT(points[0].diverged_time, 0);
  EXPECT_TRUE(points[0].dte_pp == 0 && points[0].load_factor == 0);
  EXPECT_EQ(points[0].spectrum.size(), points[1].spectrum.size());
  EXPECT_FALSE(points[1].diverged);
  EXPECT_GT(points[1].period, 0);
  EXPECT_TRUE(std::isfinite(points[1].dte_pp) && points[1].load_factor < 2);
}

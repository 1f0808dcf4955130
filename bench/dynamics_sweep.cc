// Pair dynamics: run time against accuracy for the integrators (DTE peak-to-peak against a
// tight CVODE reference at a few speeds), and the 1000-speed up-and-down sweep
// (200 settling and 50 recorded mesh cycles per speed; the two directions on two threads).
// The model: the tests' spiral-bevel-like pair (14 DOF, bearings with spans, shafts), half
// backlash 10 um, K_m 300 N/um with 10 % and 5 % first and second mesh-order variation, E_t of
// 4 and 1.5 um in the first two orders, 3000 N static mesh force.
#include "bench/timing.h"
#include "dynamics/newmark_error.h"
#include "dynamics/sweep.h"
#include "tests/dynamics/pair_fixture.h"

#include <cstdio>

using namespace gearkit;

namespace
{
MeshCycleSamples
tables()
{
  MeshCycleSamples t = test_data::bevel_like_tables(48, 3e8);
  for (int i = 0; i < 48; ++i)
    {
      const double f          = 2 * pi * i / 48;
      t.mesh_stiffness[i]     = 3e8 * (1 - 0.1 * std::cos(f) - 0.05 * std::cos(2 * f));
      t.transmission_error[i] = 4e-6 * std::sin(f) + 1.5e-6 * std::sin(2 * f + 0.3);
    }
  return t;
}

double
rpm(double r)
{
  return r * 2 * pi / 60;
}
} // namespace

int
main(int argc, char **argv)
{
  const bool              quick = argc > 1 && std::string(argv[1]) == "--quick";
  const PairModel         model(test_data::bevel_like_parameters(10e-6), tables());
  const MeshState         m0 = model.mesh().mean();
  const double            F = 3000, TL = F * m0.lg.y(), TE = F * m0.lp.z();
  const StaticEquilibrium s = model.static_equilibrium(TL);
  std::printf("static mesh force %.1f N, deflection %.2f um; mesh mass %.3f kg\n", s.mesh_force,
              s.deflection * 1e6, model.mesh_mass());

  // 1. time against error
  const std::vector<double> speeds{rpm(2000), rpm(5000), rpm(8000)};
  auto                      dte_pp = [&](RunOptions r, double omega, double accuracy = 0) {
    r.omega = omega, r.motor_torque = TE, r.load_torque = TL;
    SweepOptions o;
    o.speeds = {omega}, o.motor_torque = TE, o.load_torque = TL;
    o.settle_cycles = 200, o.record_cycles = 50, o.run = r, o.accuracy = accuracy;
    o.steady_tolerance = 0; // the same 200 cycles for every integrator
    PairVector q = s.q, v = PairVector::Zero();
    return sweep(model, q, v, o).front().dte_pp;
  };
  RunOptions reference;
  reference.method = Integrator::cvode_bdf, reference.samples_per_cycle = 64;
  reference.relative_tolerance = 1e-11, reference.absolute_tolerance = 1e-11;
  std::vector<double> ref;
  for (double w : speeds)
    ref.push_back(dte_pp(reference, w));
  std::printf("reference DTE p-p [um]: %.5f %.5f %.5f\n", ref[0] * 1e6, ref[1] * 1e6, ref[2] * 1e6);
  std::printf(
      "| integrator | setting | time per speed (250 mesh cycles) | worst DTE p-p error |\n");
  std::printf("|---|---|---|---|\n");
  auto row = [&](const char *name, const std::string &setting, RunOptions r, double accuracy = 0) {
    double       worst = 0;
    const double t     = bench::median_seconds(
        [&] {
          worst = 0;
          for (std::size_t k = 0; k < speeds.size(); ++k)
            worst = std::max(worst, std::abs(dte_pp(r, speeds[k], accuracy) / ref[k] - 1));
        },
        3);
    std::printf("| %s | %s | %.3f s | %.2e |\n", name, setting.c_str(), t / speeds.size(), worst);
  };
  for (int n : {16, 32, 64, 128, 256})
    {
      RunOptions r;
      r.method = Integrator::newmark, r.steps_per_cycle = n, r.samples_per_cycle = std::min(n, 64);
      row("Newmark", std::to_string(n) + " steps / mesh cycle", r);
    }
  for (double accuracy : {0.02, 0.005, 0.001})
    {
      RunOptions r;
      r.method = Integrator::newmark, r.steps_per_cycle = 32, r.samples_per_cycle = 32;
      const NewmarkError e(model, TL);
      char               setting[96];
      std::snprintf(setting, sizeof setting, "accuracy %g (%d / %d / %d steps)", accuracy,
                    e.steps(speeds[0], accuracy / 2, 32, 32),
                    e.steps(speeds[1], accuracy / 2, 32, 32),
                    e.steps(speeds[2], accuracy / 2, 32, 32));
      row("Newmark", setting, r, accuracy);
    }
  for (Integrator method : {Integrator::cvode_bdf, Integrator::cvode_adams})
    for (double tol : {1e-4, 1e-6, 1e-8})
      {
        RunOptions r;
        r.method = method, r.samples_per_cycle = 64;
        r.relative_tolerance = r.absolute_tolerance = tol;
        char setting[32];
        std::snprintf(setting, sizeof setting, "tolerance %.0e", tol);
        row(method == Integrator::cvode_bdf ? "CVODE BDF" : "CVODE Adams", setting, r);
      }

  // 2. the 1000-speed sweep, up and down at once
  const int    n_speeds = quick ? 100 : 1000;
  SweepOptions o;
  o.motor_torque = TE, o.load_torque = TL;
  o.settle_cycles = 200, o.record_cycles = 50;
  o.run.method = Integrator::newmark, o.run.steps_per_cycle = 32, o.run.samples_per_cycle = 32;
  for (int i = 0; i < n_speeds; ++i)
    o.speeds.push_back(rpm(100 + 11900.0 * i / (n_speeds - 1)));
  for (const auto &[tolerance, accuracy] : {std::pair{0.0, 0.0}, {1e-4, 0.0}, {1e-4, 0.005}})
    {
      o.steady_tolerance = tolerance;
      o.accuracy         = accuracy;
      SweepOptions down  = o;
      std::reverse(down.speeds.begin(), down.speeds.end());
      std::vector<SweepPoint> up_points, down_points;
      const double            t = bench::median_seconds(
          [&] {
            const auto r = run_sweeps(
                           {{&model, s.q, PairVector::Zero(), o}, {&model, s.q, PairVector::Zero(), down}}, 2);
            up_points = r[0], down_points = r[1];
          },
          1);
      double worst_dlf = 0, settled = 0;
      for (const auto &p : up_points)
        worst_dlf = std::max(worst_dlf, p.load_factor), settled += p.settled_cycles;
      std::printf("%d speeds 100-12000 rpm up and down (two threads), %s + 50 mesh cycles each, "
                  "Newmark %s: %.1f s; mean settling %.0f cycles; largest dynamic load factor "
                  "%.2f\n",
                  n_speeds, tolerance > 0 ? "settled to 1e-4 (at most 200)" : "200",
                  accuracy > 0 ? "steps from the accuracy 0.005" : "32 steps / cycle", t,
                  settled / double(up_points.size()), worst_dlf);
      if (tolerance == 0 || accuracy > 0)
        continue;
      // the up sweep again in blocks that start 3 speeds early (as the driver shares a sweep
      // among threads or MPI processes): the continuation regained?
      for (int blocks : {2, 4, 8})
        {
          std::vector<SweepTask> tasks;
          for (const SweepOptions &b : split_sweep(o, blocks, 3))
            tasks.push_back({&model, s.q, PairVector::Zero(), b});
          std::vector<SweepPoint> joined;
          const double            tb = bench::median_seconds(
              [&] {
                joined.clear();
                for (const auto &r : run_sweeps(tasks, 2))
                  joined.insert(joined.end(), r.begin(), r.end());
              },
              1);
          double worst = 0;
          int    off   = 0;
          for (std::size_t i = 0; i < joined.size(); ++i)
            {
              const double e =
                  std::abs(joined[i].dte_pp - up_points[i].dte_pp) / up_points[i].dte_pp;
              worst = std::max(worst, e);
              off += e > 1e-2;
            }
          std::printf("  up sweep in %d blocks (3 warm-up speeds each) on two threads: %.1f s; "
                      "DTE p-p against the continuous sweep: %d of %zu speeds off by more than "
                      "1 %%, worst %.2e\n",
                      blocks, tb, off, joined.size(), worst);
        }
    }
  return 0;
}

// Gear-train impact dynamics: run time against error for the integrator settings on seed 002's
// 3 s start-up (the case cases/seed002_startup: T = 149.123 N m (1 - exp(-t / 100 ms)) on the
// input shaft, no load but the crank-slider), errors against a tight-tolerance run; and a steady
// stage-1 case swept over 200 input speeds.
//
// The train (as the case): stage 1 z 17/60 m 4 mm, stage 2 z 19/72 m 5 mm, 20 deg, face widths
// 20 / 25 mm, backlash 0.05 / 0.08 mm by the centre distances, IMPACT 2e7 N/mm^2.2, e 2.2,
// c_max 10 N s/mm over 1e-7 mm, curves 200 um beyond the conjugate touch; inertias: input
// 1.06e-3 kg m^2, intermediate gears B + C + 0.002, output gear D + 20.45 with the crank-slider
// (r 100 mm, l 350 mm, rod 6 kg, 0.08 kg m^2 at 120 mm, piston 10 kg).
//
// The unloaded run-up accelerates for the whole 3 s, the meshes rattle from about 0.5 s on, and
// which tooth hits when is chaotic: the largest force of the whole run differs by O(1) between
// any two tolerances (two tight references included), so it measures nothing. The errors
// reported are those of well-posed quantities: the largest force in the first 0.1 s and 0.5 s
// (first contact and run-up under the torque ramp), the speeds at 3 s (what the torque's work
// gives), the energy balance.
#include "bench/timing.h"
#include "dynamics/train.h"
#include "tca/tooth_pairs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace gearkit;

namespace
{
constexpr double mm = 1e-3;

struct Stage
{
  TrainMesh mesh;
  double    pinion_inertia = 0, gear_inertia = 0;
};

Stage
stage(const std::string &name, int driver, int z1, int z2, double module, double face,
      double backlash)
{
  InvoluteGearData p, g;
  p.teeth = z1, g.teeth = z2;
  p.normal_module = g.normal_module = module;
  p.face_width = g.face_width = face;
  auto [pinion, gear]         = create_pair(p, g);
  ToothPairOptions o;
  o.recess = 200e-6;
  Stage s;
  auto &m  = s.mesh;
  m.name   = name;
  m.driver = driver, m.driven = driver + 1;
  m.teeth              = tooth_pair_tables(std::make_shared<InvoluteMemberFlanks>(pinion),
                                           std::make_shared<InvoluteMemberFlanks>(gear),
                                           centre_distance_for_backlash(*pinion, *gear, backlash), {}, o);
  m.law                = ImpactLaw{impact_stiffness_si(2e7, 2.2, mm), 2.2, 10 / mm, 1e-7 * mm};
  m.pinion_base_radius = pinion->base_radius;
  m.gear_base_radius   = gear->base_radius;
  m.gear_angle_0       = band_centre(m.teeth);
  s.pinion_inertia     = pinion->mass_properties().polar_inertia;
  s.gear_inertia       = gear->mass_properties().polar_inertia;
  return s;
}

TrainModel
seed002()
{
  const Stage a = stage("stage 1", 0, 17, 60, 4 * mm, 20 * mm, 0.05 * mm);
  const Stage b = stage("stage 2", 1, 19, 72, 5 * mm, 25 * mm, 0.08 * mm);
  TrainModel  m;
  m.bodies.resize(3);
  m.bodies[0].name = "input", m.bodies[0].inertia = 1.06e-3;
  m.bodies[1].name = "intermediate", m.bodies[1].inertia = a.gear_inertia + b.pinion_inertia + 2e-3;
  m.bodies[2].name = "output", m.bodies[2].inertia = b.gear_inertia + 20.45;
  CrankSlider &k        = m.bodies[2].crank;
  m.bodies[2].has_crank = true;
  k.crank_radius = 100 * mm, k.rod_length = 350 * mm, k.rod_centre = 120 * mm;
  k.rod_mass = 6, k.rod_inertia = 0.08, k.piston_mass = 10;
  m.meshes = {a.mesh, b.mesh};
  return m;
}

/// Largest |force| of a mesh at the samples up to time `until`.
double
peak(const TrainResult &r, int mesh, double until)
{
  double f = 0;
  for (std::size_t i = 0; i < r.t.size() && r.t[i] <= until + 1e-12; ++i)
    f = std::max(f, std::abs(r.meshes[std::size_t(mesh)].force[i]));
  return f;
}

struct Errors
{
  double peak_01 = 0, peak_05 = 0, peak_all = 0, speed = 0;
};

/// Relative errors of r against the reference (the larger of the two stages').
Errors
errors(const TrainResult &r, const TrainResult &ref)
{
  Errors e;
  for (int m = 0; m < 2; ++m)
    {
      auto rel   = [](double a, double b) { return std::abs(a / b - 1); };
      e.peak_01  = std::max(e.peak_01, rel(peak(r, m, 0.1), peak(ref, m, 0.1)));
      e.peak_05  = std::max(e.peak_05, rel(peak(r, m, 0.5), peak(ref, m, 0.5)));
      e.peak_all = std::max(e.peak_all, rel(r.meshes[std::size_t(m)].max_force,
                                            ref.meshes[std::size_t(m)].max_force));
    }
  for (int b = 0; b < 3; ++b)
    e.speed = std::max(
        e.speed, std::abs(r.speed[std::size_t(b)].back() / ref.speed[std::size_t(b)].back() - 1));
  return e;
}
} // namespace

int
main(int argc, char **argv)
{
  // --quick: 0.6 s, 10 speeds; --setting METHOD RTOL ATOL [METHOD RTOL ATOL ...] (METHOD bdf,
  // adams or auto): those
  // settings alone (one run each), no sweep
  const bool quick   = argc > 1 && std::string(argv[1]) == "--quick";
  const bool setting = argc >= 5 && (argc - 2) % 3 == 0 && std::string(argv[1]) == "--setting";
  setvbuf(stdout, nullptr, _IOLBF, 0);
  // 0. the tooth pair tables of both stages (both sides, from the involute flanks)
  TrainModel   base;
  const double t_tables = bench::median_seconds([&] { base = seed002(); }, quick ? 1 : 3);
  std::printf("tooth pair tables of both stages, drive and coast: %.2f s\n", t_tables);

  // 1. start-up: time against error
  TrainModel startup                     = base;
  startup.bodies[0].torque.step          = 149.123;
  startup.bodies[0].torque.time_constant = 0.1;
  TrainRunOptions reference;
  reference.duration           = quick ? 0.6 : 3.0;
  reference.sample_rate        = 20e3;
  reference.method             = TrainIntegrator::adams;
  reference.relative_tolerance = 1e-12, reference.absolute_tolerance = 1e-13;
  TrainResult  ref, bdf_ref;
  const double t_ref = bench::median_seconds([&] { ref = simulate_train(startup, reference); }, 1);
  TrainRunOptions second = reference;
  second.method          = TrainIntegrator::bdf;
  const double t_second =
      bench::median_seconds([&] { bdf_ref = simulate_train(startup, second); }, 1);
  std::printf("first contact stage 1 at %.2f ms, stage 2 at %.2f ms; impacts %zu / %zu\n",
              1e3 * ref.meshes[0].first_contact, 1e3 * ref.meshes[1].first_contact,
              ref.meshes[0].impacts, ref.meshes[1].impacts);
  std::printf("start-up %.1f s, reference (adams, rtol 1e-12, atol 1e-13 m): %.1f s, %zu steps, "
              "peak forces 0.1 s %.0f / %.0f N, 0.5 s %.0f / %.0f N, all %.0f / %.0f N, energy "
              "error %.1e, final speeds %.3f / %.3f / %.3f rad/s\n",
              reference.duration, t_ref, ref.steps, peak(ref, 0, 0.1), peak(ref, 1, 0.1),
              peak(ref, 0, 0.5), peak(ref, 1, 0.5), ref.meshes[0].max_force,
              ref.meshes[1].max_force, ref.energy_error, ref.speed[0].back(), ref.speed[1].back(),
              ref.speed[2].back());
  const Errors s = errors(bdf_ref, ref);
  std::printf("second reference (bdf, same tolerances): %.1f s, %zu steps; against the first: "
              "peak 0.1 s %.1e, 0.5 s %.1e, whole run %.1e, final speeds %.1e\n",
              t_second, bdf_ref.steps, s.peak_01, s.peak_05, s.peak_all, s.speed);
  std::printf("%-6s %8s %8s %9s %9s %10s %10s %10s %10s %9s\n", "method", "rtol", "atol[m]",
              "time[s]", "steps", "peak 0.1s", "peak 0.5s", "peak all", "speeds", "energy");
  struct Setting
  {
    TrainIntegrator method;
    double          rtol, atol;
  };
  std::vector<Setting> settings;
  if (setting)
    for (int a = 2; a + 2 < argc; a += 3)
      settings.push_back({std::string(argv[a]) == "adams"  ? TrainIntegrator::adams
                          : std::string(argv[a]) == "auto" ? TrainIntegrator::automatic
                                                           : TrainIntegrator::bdf,
                          std::stod(argv[a + 1]), std::stod(argv[a + 2])});
  else
    for (TrainIntegrator method : {TrainIntegrator::bdf, TrainIntegrator::adams})
      for (double rtol : {1e-6, 1e-8, 1e-10})
        for (double atol : {1e-10, 1e-12})
          settings.push_back({method, rtol, atol});
  for (const Setting &c : settings)
    {
      TrainRunOptions o    = reference;
      o.method             = c.method;
      o.relative_tolerance = c.rtol, o.absolute_tolerance = c.atol;
      TrainResult  r;
      const double t =
          bench::median_seconds([&] { r = simulate_train(startup, o); }, quick || setting ? 1 : 3);
      const Errors e = errors(r, ref);
      std::printf("%-6s %8.0e %8.0e %9.2f %9zu %10.1e %10.1e %10.1e %10.1e %9.1e\n",
                  r.method == TrainIntegrator::adams ? "adams" : "bdf", c.rtol, c.atol, t, r.steps,
                  e.peak_01, e.peak_05, e.peak_all, e.speed, r.energy_error);
    }

  if (setting)
    return 0;

  // 2. steady stage 1 over 200 input speeds (0.1 s each, from the kinematic speeds, 1 %
  // resistive torque on the intermediate and output shafts), the default tolerances
  const int    speeds  = quick ? 10 : 200;
  TrainModel   steady  = base;
  std::size_t  steps   = 0;
  const double t_sweep = bench::median_seconds(
      [&] {
        for (int i = 0; i < speeds; ++i)
          {
            const double              w = 20 + 180.0 * i / (speeds - 1);
            const std::vector<double> k = train_speeds(steady, 0, w);
            for (int b = 0; b < 3; ++b)
              steady.bodies[std::size_t(b)].initial_speed = k[std::size_t(b)];
            steady.bodies[0].constant_speed  = true;
            steady.bodies[1].torque.constant = -0.01 * 149.123 * 60 / 17;
            steady.bodies[2].torque.constant = -0.01 * 149.123 * 60 / 17 * 72 / 19;
            TrainRunOptions o;
            o.duration = 0.1;
            steps += simulate_train(steady, o).steps;
          }
      },
      1);
  std::printf("steady sweep: %d input speeds 20-200 rad/s, 0.1 s each: %.1f s (%zu steps)\n",
              speeds, t_sweep, steps);
}

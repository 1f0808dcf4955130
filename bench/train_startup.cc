// Gear-train impact dynamics: run time against error for the integrator settings on seed 002's
// 3 s start-up (T = 149.123 N m (1 - exp(-t / 100 ms)) on the input shaft), error = the peak
// mesh forces of both stages and the final speeds against a tight-tolerance run; and a steady
// stage-1 case swept over 200 input speeds.
//
// The train: stage 1 z 17/60 m 4 mm, stage 2 z 19/72 m 5 mm, 20 deg, face widths 20 / 25 mm,
// backlash 0.05 / 0.08 mm by the centre distances, IMPACT 2e7 N/mm^2.2, e 2.2, damping 2e-4 K
// per mm over 1e-7 mm; inertias: input 1.06e-3 kg m^2, intermediate 2.0e-2, output (gear D,
// crank, flywheel) 40 kg m^2: the seed's run-up passes the rated input speed 167.5 rad/s at
// about 350 ms, which asks for 0.225 kg m^2 referred to the input shaft.
#include "bench/timing.h"
#include "dynamics/train.h"
#include "tca/tooth_pairs.h"

#include <cstdio>
#include <string>

using namespace gearkit;

namespace
{
TrainMesh
stage(const std::string &name, int driver, int z1, int z2, double module, double face,
      double backlash)
{
  InvoluteGearData p, g;
  p.teeth = z1, g.teeth = z2;
  p.normal_module = g.normal_module = module;
  p.face_width = g.face_width = face;
  auto [pinion, gear]         = create_pair(p, g);
  const double a0             = working_centre_distance(*pinion, *gear);
  const double alpha          = working_pressure_angle(*pinion, *gear);
  const double a              = a0 + backlash / (2 * std::tan(alpha)); // circumferential backlash
  TrainMesh    m;
  m.name   = name;
  m.driver = driver, m.driven = driver + 1;
  m.teeth              = tooth_pair_tables(std::make_shared<InvoluteMemberFlanks>(pinion),
                                           std::make_shared<InvoluteMemberFlanks>(gear), a);
  m.law                = ImpactLaw{impact_stiffness_si(2e7, 2.2, 1e-3), 2.2,
                    impact_stiffness_si(2e7 * 2e-4, 1.0, 1e-3), 1e-10};
  m.pinion_base_radius = pinion->base_radius;
  m.gear_base_radius   = gear->base_radius;
  m.gear_angle_0       = band_centre(m.teeth);
  return m;
}

TrainModel
seed002()
{
  TrainModel m;
  m.bodies.resize(3);
  m.bodies[0].name = "input", m.bodies[0].inertia = 1.06e-3;
  m.bodies[1].name = "intermediate", m.bodies[1].inertia = 2.0e-2;
  m.bodies[2].name = "output", m.bodies[2].inertia = 40;
  m.meshes = {stage("stage 1", 0, 17, 60, 4e-3, 20e-3, 0.05e-3),
              stage("stage 2", 1, 19, 72, 5e-3, 25e-3, 0.08e-3)};
  return m;
}
} // namespace

int
main(int argc, char **argv)
{
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  // 0. the tooth pair tables of both stages (both sides, from the involute flanks)
  TrainModel   base;
  const double t_tables = bench::median_seconds([&] { base = seed002(); }, quick ? 1 : 3);
  std::printf("tooth pair tables of both stages, drive and coast: %.2f s\n", t_tables);
  // 1. start-up: time against peak-force error
  TrainModel startup                     = base;
  startup.bodies[0].torque.step          = 149.123;
  startup.bodies[0].torque.time_constant = 0.1;
  TrainRunOptions reference;
  reference.duration           = quick ? 0.3 : 3.0;
  reference.sample_rate        = 20e3;
  reference.relative_tolerance = 1e-12, reference.absolute_tolerance = 1e-13;
  TrainResult  ref;
  const double t_ref = bench::median_seconds([&] { ref = simulate_train(startup, reference); }, 1);
  for (int m = 0; m < 2; ++m)
    {
      const auto &f = ref.meshes[m].force;
      std::size_t k = 0;
      for (std::size_t i = 0; i < f.size(); ++i)
        if (std::abs(f[i]) > std::abs(f[k]))
          k = i;
      std::printf("stage %d: largest sampled force %.0f N at %.2f ms (input %.1f rad/s), "
                  "%zu impacts\n",
                  m + 1, f[k], 1e3 * ref.t[k], ref.speed[0][k], ref.meshes[m].impacts);
    }
  std::printf("first contact stage 1 at %.2f ms, stage 2 at %.2f ms\n",
              1e3 * ref.meshes[0].first_contact, 1e3 * ref.meshes[1].first_contact);
  std::printf(
      "start-up %.1f s, reference (adams, rtol 1e-12, atol 1e-13 m): %.1f s, %zu steps, "
      "peak forces %.1f / %.1f N, energy error %.1e, final speeds %.3f / %.3f / %.3f rad/s\n",
      reference.duration, t_ref, ref.steps, ref.meshes[0].max_force, ref.meshes[1].max_force,
      ref.energy_error, ref.speed[0].back(), ref.speed[1].back(), ref.speed[2].back());
  std::printf("%-6s %8s %8s %10s %10s %12s %12s %10s\n", "method", "rtol", "atol[m]", "time[s]",
              "steps", "peak err 1", "peak err 2", "energy");
  for (TrainIntegrator method : {TrainIntegrator::adams, TrainIntegrator::bdf})
    for (double rtol : {1e-6, 1e-8, 1e-10})
      for (double atol : {1e-9, 1e-10, 1e-11})
        {
          TrainRunOptions o    = reference;
          o.method             = method;
          o.relative_tolerance = rtol, o.absolute_tolerance = atol;
          TrainResult  r;
          const double t =
              bench::median_seconds([&] { r = simulate_train(startup, o); }, quick ? 1 : 3);
          std::printf("%-6s %8.0e %8.0e %10.2f %10zu %12.2e %12.2e %10.1e\n",
                      method == TrainIntegrator::adams ? "adams" : "bdf", rtol, atol, t, r.steps,
                      std::abs(r.meshes[0].max_force / ref.meshes[0].max_force - 1),
                      std::abs(r.meshes[1].max_force / ref.meshes[1].max_force - 1),
                      r.energy_error);
        }

  // 2. steady stage 1 over 200 input speeds (0.1 s each, from the kinematic speeds, 1 %
  // resistive torque on the intermediate and output shafts)
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
              steady.bodies[b].initial_speed = k[b];
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

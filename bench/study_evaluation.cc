// One study evaluation on one compliance: a scene's pair (its finite-element compliance from
// the driver's cache, computed once), the mesh cycle study built on the pair without
// modifications, and the median time of one variant's evaluation (N positions, one torque) on
// 1 and 2 threads, the set-up time, the zone sizes, and the variant against the standalone
// loaded contact of its modified flanks (zones fitted to each load, the same compliance).
// usage: bench_study_evaluation SCENE [pair] [positions = 40] [torque = 200 N m]
//          [output root = /tmp/gearkit-bench-study]
#include "base/blas_kernels.h"
#include "bench/timing.h"
#include "driver/driver.h"
#include "driver/pair_contact.h"
#include "study/mesh_cycle_study.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>

using namespace gearkit;

namespace
{
std::shared_ptr<const InvoluteMemberFlanks>
without_modifications(const MemberFlanks &m)
{
  InvoluteGearData d    = involute(m).data();
  d.drive_modifications = d.coast_modifications = {};
  return std::make_shared<const InvoluteMemberFlanks>(InvoluteGear::create(d));
}
} // namespace

int
main(int argc, char **argv)
{
  gearkit::use_fitting_blas_kernels(argv); // before MPI: may run the program again
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2)
    {
      std::fprintf(stderr, "usage: %s SCENE [pair] [positions] [torque] [output root]\n", argv[0]);
      return 2;
    }
  try
    {
      const Scene         scene     = read_scene(argv[1]);
      const std::string   pair_name = argc > 2 ? argv[2] : scene.pairs.front().name;
      const int           positions = argc > 3 ? std::atoi(argv[3]) : 40;
      const double        torque    = argc > 4 ? std::atof(argv[4]) : 200;
      const std::string   root      = argc > 5 ? argv[5] : "/tmp/gearkit-bench-study";
      const StageUpstream up(scene, std::vector<std::string>{"flanks", "compliance"}, root,
                             std::cerr);
      const PairScene    &pair = scene.pair(pair_name);
      const LoadedPair lp  = loaded_pair(scene, pair, up.upstream().at("flanks")->group(pair_name),
                                         up.upstream().at("compliance")->group(pair_name));
      const auto       bp  = without_modifications(*lp.members.pinion);
      const auto       bg  = without_modifications(*lp.members.gear);
      const TcaOptions tca = lp.theory->options_data();

      MeshCycleStudyOptions o;
      o.positions = positions, o.torques = {torque};
      const auto           t0 = std::chrono::steady_clock::now();
      const MeshCycleStudy study(bp, bg, lp.members.assembly, tca, lp.options, lp.pinion_compliance,
                                 lp.gear_compliance, o);
      const double         setup =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::size_t cells = 0, most = 0;
      for (int i = 0; i < positions; ++i)
        cells += study.zone(0, std::size_t(i)).cells().size(),
            most = std::max(most, study.zone(0, std::size_t(i)).cells().size());

      const auto working = [&](const MemberFlanks &m) {
        const InvoluteGearData &d = involute(m).data();
        return tca.side == FlankSide::drive ? d.drive_modifications : d.coast_modifications;
      };
      // The scene's modifications, or where it has none a classical design: 15 um linear tip
      // relief over 3 mm of roll length on both members, 5 um lead crowning on the pinion.
      PairVariant v{working(*lp.members.pinion), working(*lp.members.gear)};
      if (!v.pinion.any() && !v.gear.any())
        {
          for (ToothModifications *m : {&v.pinion, &v.gear})
            m->tip_relief = 15e-6, m->tip_relief_length = 3e-3;
          v.pinion.lead_crowning = 5e-6;
        }
      {
        const auto [mp, mg] = study.members(v);
        const UnloadedTca own(mp, mg, lp.members.assembly, tca);
        const double      t_tca      = bench::median_seconds([&] {
          for (int i = 0; i < positions; ++i)
            own.at(study.zone(0, std::size_t(i)).position().pinion_angle);
        });
        const double      t_solve    = bench::median_seconds([&] {
          for (int i = 0; i < positions; ++i)
            {
              const FixedZone                 &z = study.zone(0, std::size_t(i));
              const MeshCycleStudy::Deviations d = study.deviations(0, std::size_t(i), 0, v);
              z.solve(d.added, torque, z.position().transmission_error, &d.pinion_slope);
            }
        });
        int               iterations = 0, active = 0;
        for (int i = 0; i < positions; ++i)
          {
            const FixedZone                 &z = study.zone(0, std::size_t(i));
            const MeshCycleStudy::Deviations d = study.deviations(0, std::size_t(i), 0, v);
            const LoadedPosition             p =
                z.solve(d.added, torque, z.position().transmission_error, &d.pinion_slope);
            iterations += p.iterations, active += p.active_cells;
          }
        std::printf("  parts on 1 thread: the variant's whole TCA %.4f s (the evaluation searches "
                    "each pair from its first touch in the cells instead), contact solves %.4f s "
                    "(%.1f iterations, %.0f active cells per position)\n",
                    t_tca, t_solve, double(iterations) / positions, double(active) / positions);
      }
      VariantCycle r;
      if (const char *repeat = std::getenv("GEARKIT_BENCH_REPEAT")) // for a profiler
        for (int k = 0; k < std::atoi(repeat); ++k)
          r = study.evaluate(v, 1);
      const double one = bench::median_seconds([&] { r = study.evaluate(v, 1); }, 5);
      const double two = bench::median_seconds([&] { r = study.evaluate(v, 2); }, 5);

      // The standalone loaded contact of the variant's flanks on the same compliance.
      const auto [vp, vg] = study.members(v);
      const UnloadedTca      variant(vp, vg, lp.members.assembly, tca);
      const MeshCycleContact c  = loaded_contact_cycle(variant, positions, {torque}, lp.options,
                                                       lp.pinion_compliance, lp.gear_compliance);
      double                 dK = 0, dE = 0, lo = HUGE_VAL, hi = -HUGE_VAL;
      for (int i = 0; i < positions; ++i)
        {
          dK = std::max(dK, std::abs(r.mesh_stiffness[i] / c.mesh_stiffness[i] - 1));
          dE = std::max(dE, std::abs(r.loaded_te[i] - c.loaded_te[i]));
          lo = std::min(lo, c.loaded_te[i]), hi = std::max(hi, c.loaded_te[i]);
        }
      double Km = 0;
      for (const double k : c.mesh_stiffness)
        Km += k / positions;
      std::printf("study evaluation: %s pair %s, %d positions, %g N m\n", argv[1],
                  pair_name.c_str(), positions, torque);
      std::printf("  set-up (zones, compliance matrices): %.2f s; cells per zone mean %.0f, "
                  "most %zu\n",
                  setup, double(cells) / positions, most);
      std::printf("  one evaluation: %.4f s on 1 thread, %.4f s on 2 (median of 5)\n", one, two);
      std::printf("  variant: tip relief %g/%g um over %g/%g mm, lead crowning %g/%g um\n",
                  v.pinion.tip_relief * 1e6, v.gear.tip_relief * 1e6,
                  v.pinion.tip_relief_length * 1e3, v.gear.tip_relief_length * 1e3,
                  v.pinion.lead_crowning * 1e6, v.gear.lead_crowning * 1e6);
      std::printf("  TE p-p study %.4f urad, standalone %.4f urad (%+.3f %%)\n",
                  r.te_peak_to_peak[0] * 1e6, (hi - lo) * 1e6,
                  100 * (r.te_peak_to_peak[0] / (hi - lo) - 1));
      std::printf("  K_m mean study %.5g, standalone %.5g N/m (%+.3f %%); worst position: "
                  "K_m %.3f %%, e_L %.3g urad\n",
                  r.stiffness_mean[0], Km, 100 * (r.stiffness_mean[0] / Km - 1), 100 * dK,
                  dE * 1e6);
      std::printf("  zone edge reached: %s\n", r.zone_edge[0] ? "yes" : "no");
      if (std::getenv("GEARKIT_BENCH_TABLE"))
        for (int i = 0; i < positions; ++i)
          std::printf("  %2d e0 %9.3f %9.3f  eL %9.3f %9.3f urad  K %.4g %.4g\n", i,
                      r.unloaded_te[i] * 1e6, c.unloaded_te[i] * 1e6, r.loaded_te[i] * 1e6,
                      c.loaded_te[i] * 1e6, r.mesh_stiffness[i], c.mesh_stiffness[i]);
    }
  catch (const std::exception &e)
    {
      std::fprintf(stderr, "bench_study_evaluation: %s\n", e.what());
      return 1;
    }
  return 0;
}

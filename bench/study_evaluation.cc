// One study evaluation on one compliance: a scene's pair (its finite-element compliance from
// the driver's cache, computed once), the mesh cycle study built on the pair without
// modifications, and the median time of one variant's evaluation (N positions, one torque) on
// 1 and 2 threads, the set-up time, the zone sizes, and the variant against the standalone
// loaded contact of its modified flanks (zones fitted to each load, the same compliance).
// usage: bench_study_evaluation SCENE [pair] [positions = 40] [torque = 200 N m]
//          [output root = /tmp/gearkit-bench-study]
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
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2)
    {
      std::fprintf(stderr, "usage: %s SCENE [pair] [positions] [torque] [output root]\n", argv[0]);
      return 2;
    }
  try
    {
      const Scene       scene     = read_scene(argv[1]);
      const std::string pair_name = argc > 2 ? argv[2] : scene.pairs.front().name;
      const int         positions = argc > 3 ? std::atoi(argv[3]) : 40;
      const double      torque    = argc > 4 ? std::atof(argv[4]) : 200;
      const std::string root      = argc > 5 ? argv[5] : "/tmp/gearkit-bench-study";
      const StageUpstream up(scene, std::vector<std::string>{"flanks", "compliance"}, root,
                             std::cerr);
      const PairScene &pair = scene.pair(pair_name);
      const LoadedPair lp   = loaded_pair(scene, pair, up.upstream().at("flanks")->group(pair_name),
                                          up.upstream().at("compliance")->group(pair_name));
      const auto       bp   = without_modifications(*lp.members.pinion);
      const auto       bg   = without_modifications(*lp.members.gear);
      const TcaOptions tca  = lp.theory->options_data();

      MeshCycleStudyOptions o;
      o.positions = positions, o.torques = {torque};
      const auto t0 = std::chrono::steady_clock::now();
      const MeshCycleStudy study(bp, bg, lp.members.assembly, tca, lp.options,
                                 lp.pinion_compliance, lp.gear_compliance, o);
      const double setup =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::size_t cells = 0, most = 0;
      for (int i = 0; i < positions; ++i)
        cells += study.zone(0, std::size_t(i)).cells().size(),
            most = std::max(most, study.zone(0, std::size_t(i)).cells().size());

      const auto working = [&](const MemberFlanks &m) {
        const InvoluteGearData &d = involute(m).data();
        return tca.side == FlankSide::drive ? d.drive_modifications : d.coast_modifications;
      };
      const PairVariant v{working(*lp.members.pinion), working(*lp.members.gear)}; // the scene's
      VariantCycle r;
      const double one = bench::median_seconds([&] { r = study.evaluate(v, 1); }, 5);
      const double two = bench::median_seconds([&] { r = study.evaluate(v, 2); }, 5);

      // The standalone loaded contact of the scene's own (modified) flanks.
      const MeshCycleContact c = loaded_contact_cycle(*lp.theory, positions, {torque}, lp.options,
                                                      lp.pinion_compliance, lp.gear_compliance);
      double dK = 0, dE = 0, lo = HUGE_VAL, hi = -HUGE_VAL;
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
      std::printf("  TE p-p study %.4f urad, standalone %.4f urad (%+.3f %%)\n",
                  r.te_peak_to_peak[0] * 1e6, (hi - lo) * 1e6,
                  100 * (r.te_peak_to_peak[0] / (hi - lo) - 1));
      std::printf("  K_m mean study %.5g, standalone %.5g N/m (%+.3f %%); worst position: "
                  "K_m %.3f %%, e_L %.3g urad\n",
                  r.stiffness_mean[0], Km, 100 * (r.stiffness_mean[0] / Km - 1), 100 * dK,
                  dE * 1e6);
      std::printf("  zone edge reached: %s\n", r.zone_edge[0] ? "yes" : "no");
    }
  catch (const std::exception &e)
    {
      std::fprintf(stderr, "bench_study_evaluation: %s\n", e.what());
      return 1;
    }
  return 0;
}

// Run time against error of the unloaded contact analysis of the seed's spiral bevel pair
// (55/47, m 3 mm, 35 deg, 19 mm face; pinion with 2 mm cutter-radius mismatch and the modified
// roll synthesised for a 3.72e-5 rad parabolic TE), one mesh cycle at 200 positions: classical
// TCA on the generated flanks (reference), the fast discrete-point mode on virtual-CMM grids,
// and (with --paper) the seed's point-cloud method at 20 positions.
#include "bench/timing.h"
#include "tca/bevel_synthesis.h"
#include "tca/paper_mode.h"

#include <cmath>
#include <cstdio>
#include <string>

using namespace gearkit;
using bench::median_seconds;

int
main(int argc, char **argv)
{
  const bool      paper = argc > 1 && std::string(argv[1]) == "--paper";
  BevelPairDesign d;
  d.pinion_teeth = 55, d.gear_teeth = 47, d.module = 3e-3, d.face_width = 19e-3;
  d.pinion_hand = Hand::right;
  PinionMismatch start;
  start.cutter_radius = 2e-3;
  PinionMismatch m;
  const double   t_synthesis =
      median_seconds([&] { m = synthesise_modified_roll(d, start, 3.72e-5); }, 1);
  const double          t_build = median_seconds([&] { bevel_pair_flanks(d, m); });
  const BevelPairFlanks f       = bevel_pair_flanks(d, m);
  std::printf("seed spiral bevel pair: 2C = %.6g; synthesis %.2f s; generating both members "
              "(102 flanks) %.3f s\n",
              m.modified_roll_2c, t_synthesis, t_build);

  TcaOptions o;
  o.positions_per_mesh = 200;
  TcaResult    reference;
  const double t_ref =
      median_seconds([&] { reference = UnloadedTca(f.pinion, f.gear, f.assembly, o).run(); });
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &q : reference.positions)
    lo = std::min(lo, q.transmission_error), hi = std::max(hi, q.transmission_error);
  std::printf("one mesh cycle, 200 positions; e_0 peak-to-peak %.4g urad\n", (hi - lo) * 1e6);
  std::printf("%-36s %10s %14s %12s\n", "method", "time [s]", "max error [rad]", "% of p-p");
  std::printf("%-36s %10.3f %14s %12s\n", "classical TCA (generated flanks)", t_ref, "reference",
              "-");
  auto measure = [](const BevelMemberFlanks &member, int np, int nf) {
    return std::make_shared<MeasuredMemberFlanks>(
        virtual_cmm("m", member.teeth(), [&](int k, FlankSide side) {
          return sample_flank(member.flank(k, side), np, nf);
        }));
  };
  for (auto [np, nf] : {std::pair{5, 15}, {9, 29}, {17, 57}, {33, 113}})
    {
      const auto   mp = measure(*f.pinion, np, nf), mg = measure(*f.gear, np, nf);
      TcaResult    r;
      const double t = median_seconds([&] { r = UnloadedTca(mp, mg, f.assembly, o).run(); });
      double       e = 0;
      for (std::size_t i = 0; i < r.positions.size(); ++i)
        e = std::max(e, std::abs(r.positions[i].transmission_error -
                                 reference.positions[i].transmission_error));
      char name[64];
      std::snprintf(name, sizeof name, "fast discrete-point, %d x %d pts", np, nf);
      std::printf("%-36s %10.3f %14.2e %12.4f\n", name, t, e, 100 * e / (hi - lo));
    }
  if (!paper)
    return 0;
  const auto mp = measure(*f.pinion, 9, 29), mg = measure(*f.gear, 9, 29);
  for (double spacing : {200e-6, 100e-6})
    {
      PaperModeOptions po;
      po.spacing            = spacing;
      po.positions_per_mesh = 20;
      PaperModeResult r;
      const double    t = median_seconds([&] { r = paper_mode_ste(*mp, *mg, f.assembly, po); }, 1);
      double          e = 0;
      for (std::size_t i = 0; i < r.seed_ste.size(); ++i)
        e = std::max(e, std::abs(r.seed_ste[i] - (reference.positions[10 * i].transmission_error -
                                                  reference.positions[0].transmission_error)));
      char name[64];
      std::snprintf(name, sizeof name, "paper mode, %.0f um, 20 positions", spacing * 1e6);
      std::printf("%-36s %10.3f %14.2e %12.4f   (E = %.3g um, %zu points)\n", name, t, e,
                  100 * e / (hi - lo), r.tolerance * 1e6, r.points);
    }
}

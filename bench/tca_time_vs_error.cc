// Run time against error of the unloaded contact analysis, one mesh cycle at 200 positions of
// the FZG C-type pair (pinion with profile and lead crowning): classical TCA on the exact flanks
// (the reference) and the fast discrete-point mode on flanks interpolated from virtual-CMM grids.
// Prints a table; each time is the median of 5 runs.
#include "bench/timing.h"
#include "tca/paper_mode.h"
#include "tca/unloaded_tca.h"
#include "tests/fzg_c_pair.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

using namespace gearkit;
using bench::median_seconds;

namespace
{
// Largest |e_0 difference| between two runs over the same positions.
double
max_difference(const TcaResult &r, const TcaResult &reference)
{
  double e = 0;
  for (std::size_t i = 0; i < r.positions.size(); ++i)
    e = std::max(
        e, std::abs(r.positions[i].transmission_error - reference.positions[i].transmission_error));
  return e;
}

/// The study for one pair: classical reference, coarser search grids, fast discrete-point mode
/// over grid sizes (profile x face points), optionally paper mode.
void
study(const char *title, const InvoluteGearData &pp, const InvoluteGearData &gp,
      const std::vector<std::pair<int, int>> &grids, bool paper)
{
  const auto   pinion = InvoluteGear::create(pp);
  const auto   gear   = InvoluteGear::create(gp);
  const double a      = working_centre_distance(*pinion, *gear);
  TcaOptions   o;
  o.positions_per_mesh = 200;

  TcaResult    reference;
  const auto   classical = [&] { reference = UnloadedTca(pinion, gear, a, {}, o).run(); };
  const double t_ref     = median_seconds(classical);
  double       lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &q : reference.positions)
    lo = std::min(lo, q.transmission_error), hi = std::max(hi, q.transmission_error);
  std::printf("\n%s\none mesh cycle, 200 positions; e_0 peak-to-peak %.4g urad\n", title,
              (hi - lo) * 1e6);
  std::printf("%-34s %10s %14s %12s\n", "method", "time [s]", "max error [rad]", "% of p-p");
  std::printf("%-34s %10.3f %14s %12s\n", "classical TCA (exact flanks)", t_ref, "reference", "-");

  // The same exact flanks with a coarser search grid: the error the search itself adds.
  for (auto [nu, nv] : {std::pair{9, 5}, {5, 3}})
    {
      TcaOptions c      = o;
      c.profile_samples = nu, c.face_samples = nv;
      TcaResult    r;
      const double t = median_seconds([&] { r = UnloadedTca(pinion, gear, a, {}, c).run(); });
      const double e = max_difference(r, reference);
      char         name[64];
      std::snprintf(name, sizeof name, "classical, search grid %d x %d", nu, nv);
      std::printf("%-34s %10.3f %14.2e %12.4f\n", name, t, e, 100 * e / (hi - lo));
    }

  for (auto [np, nf] : grids)
    {
      const auto   mp = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*pinion, "p", np, nf));
      const auto   mg = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*gear, "g", np, nf));
      TcaResult    r;
      const double t = median_seconds([&] { r = UnloadedTca(mp, mg, a, {}, o).run(); });
      const double e = max_difference(r, reference);
      char         name[64];
      std::snprintf(name, sizeof name, "fast discrete-point, %d x %d pts", np, nf);
      std::printf("%-34s %10.3f %14.2e %12.4f\n", name, t, e, 100 * e / (hi - lo));
    }

  // The seed's literal method: minutes per mesh cycle, so only on request, at 20 positions (one
  // run each), against the same reference at those positions.
  if (!paper)
    return;
  const auto mp = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*pinion, "p", 9, 29));
  const auto mg = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*gear, "g", 9, 29));
  for (double spacing : {200e-6, 100e-6, 50e-6})
    {
      PaperModeOptions po;
      po.spacing            = spacing;
      po.rotation_step      = 1e-6;
      po.positions_per_mesh = 20;
      PaperModeResult r;
      const double    t = median_seconds([&] { r = paper_mode_ste(*mp, *mg, a, {}, po); }, 1);
      double          e = 0;
      for (std::size_t i = 0; i < r.seed_ste.size(); ++i)
        e = std::max(e, std::abs(r.seed_ste[i] - (reference.positions[10 * i].transmission_error -
                                                  reference.positions[0].transmission_error)));
      char name[64];
      std::snprintf(name, sizeof name, "paper mode, %.0f um, 20 positions", spacing * 1e6);
      std::printf("%-34s %10.3f %14.2e %12.4f   (E = %.3g um)\n", name, t, e, 100 * e / (hi - lo),
                  r.tolerance * 1e6);
    }
}
} // namespace

int
main(int argc, char **argv)
{
  const bool paper                       = argc > 1 && std::string(argv[1]) == "--paper";
  auto [p, g]                            = test_data::fzg_c_pair();
  p.drive_modifications.profile_crowning = 4e-6;
  p.drive_modifications.lead_crowning    = 5e-6;
  study("FZG C, pinion with 4 um profile and 5 um lead crowning", p, g,
        {{9, 29}, {29, 9}, {17, 29}, {33, 57}, {65, 113}}, paper);
  p.drive_modifications.tip_relief        = 10e-6;
  p.drive_modifications.tip_relief_length = 2e-3;
  study("the same with a 10 um / 2 mm linear tip relief", p, g,
        {{9, 29}, {29, 9}, {33, 29}, {65, 113}}, false);
}

// Fast discrete-point STE: the same contact analysis on flanks interpolated from 9 x 29 measured
// points (a virtual CMM of the theoretical flanks), against classical TCA on the exact flanks.
#include "../fzg_c_pair.h"
#include "unloaded_tca.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

namespace
{
// FZG C-type pair; pinion with profile and lead crowning, and optionally a 2 mm linear tip
// relief.
std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
modified_pair(bool tip_relief)
{
  auto [p, g]                            = test_data::fzg_c_pair();
  p.drive_modifications.profile_crowning = 4e-6;
  p.drive_modifications.lead_crowning    = 5e-6;
  if (tip_relief)
    {
      p.drive_modifications.tip_relief        = 10e-6;
      p.drive_modifications.tip_relief_length = 2e-3;
    }
  return {InvoluteGear::create(p), InvoluteGear::create(g)};
}

// Largest |e_discrete - e_classical| over one mesh cycle and the classical peak-to-peak.
std::pair<double, double>
discrete_against_classical(bool tip_relief, int n_profile, int n_face)
{
  const auto [p, g] = modified_pair(tip_relief);
  const double a    = working_centre_distance(*p, *g);
  TcaOptions   o;
  o.positions_per_mesh  = 25;
  const TcaResult exact = UnloadedTca(p, g, a, {}, o).run();
  const auto      mp =
      std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*p, "pinion", n_profile, n_face));
  const auto mg =
      std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*g, "gear", n_profile, n_face));
  const TcaResult discrete = UnloadedTca(mp, mg, a, {}, o).run();
  double          lo = HUGE_VAL, hi = -HUGE_VAL, worst = 0;
  for (std::size_t i = 0; i < exact.positions.size(); ++i)
    {
      const double e = exact.positions[i].transmission_error;
      lo             = std::min(lo, e);
      hi             = std::max(hi, e);
      worst          = std::max(worst, std::abs(discrete.positions[i].transmission_error - e));
    }
  return {worst, hi - lo};
}
} // namespace

TEST(DiscretePointFast, MatchesClassicalTcaFromSeedSizedGrids)
{
  // Smooth modifications from the seed's 9 x 29 = 261 points per flank: within 1 % of the
  // peak-to-peak (measured 0.33 %), and 4th-order convergence of the interpolation (17 x 29
  // brings it down ~30x).
  const auto [worst, pp] = discrete_against_classical(false, 9, 29);
  EXPECT_GT(pp, 30e-6);
  EXPECT_LT(worst, 0.01 * pp) << worst << " of " << pp;
  const auto [finer, _] = discrete_against_classical(false, 17, 29);
  EXPECT_LT(finer, worst / 10);
}

TEST(DiscretePointFast, TipReliefNeedsAProfileGridThatResolvesIt)
{
  // A 2 mm linear tip relief is shorter than the 9-point grid's profile spacing (~2.6 mm): the
  // spline cannot represent it (17 % of the peak-to-peak measured). 33 profile points (spacing
  // ~0.6 mm) resolve it to well within 1 % (measured 0.06 %).
  const auto [coarse, pp] = discrete_against_classical(true, 9, 29);
  EXPECT_GT(coarse, 0.05 * pp);
  const auto [fine, _] = discrete_against_classical(true, 33, 29);
  EXPECT_LT(fine, 0.01 * pp) << fine << " of " << pp;
}

// The seed's literal discrete-point method (paper mode) against classical TCA: its error is set by
// the contact tolerance E and shrinks with the point spacing.
#include "../fzg_c_pair.h"
#include "paper_mode.h"
#include "unloaded_tca.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

TEST(PaperMode, ErrorShrinksWithSpacingAndStaysWithinTolerance)
{
  auto [p, g]                            = test_data::fzg_c_pair();
  p.drive_modifications.profile_crowning = 4e-6;
  const auto   P = InvoluteGear::create(p), G = InvoluteGear::create(g);
  const double a = working_centre_distance(*P, *G);
  TcaOptions   o;
  o.positions_per_mesh  = 4;
  const TcaResult exact = UnloadedTca(P, G, a, {}, o).run();
  const auto      mp    = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*P, "pinion", 9, 29));
  const auto      mg    = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*G, "gear", 9, 29));

  auto worst = [&](double spacing, double &tolerance) {
    PaperModeOptions po;
    po.spacing              = spacing;
    po.rotation_step        = 1e-6;
    po.positions_per_mesh   = 4;
    const PaperModeResult r = paper_mode_ste(*mp, *mg, a, {}, po);
    tolerance               = r.tolerance;
    double w                = 0;
    for (std::size_t i = 0; i < r.pinion_angle.size(); ++i)
      w = std::max(w, std::abs(r.transmission_error[i] - (exact.positions[i].transmission_error -
                                                          exact.positions[0].transmission_error)));
    return w;
  };
  double       E_coarse, E_fine;
  const double coarse = worst(300e-6, E_coarse), fine = worst(150e-6, E_fine);
  // E >= sqrt((a/2)^2 + (b/2)^2 + l^2): about 0.71 x spacing here.
  EXPECT_GT(E_coarse, 0.7 * 300e-6);
  EXPECT_LT(E_coarse, 0.8 * 300e-6);
  // The contact is declared up to E early on either flank: the error is bounded by
  // 2 E / r_b2 in gear angle, i.e. 2 E / r_b2 * z2 / z1 in pinion radians ...
  EXPECT_LT(coarse, 2 * E_coarse / G->base_radius * 24 / 16);
  // ... and halving the spacing reduces it.
  EXPECT_LT(fine, coarse);
}

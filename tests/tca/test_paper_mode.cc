// The seed's literal discrete-point method (paper mode) against classical TCA: its error is set by
// the contact tolerance E and shrinks with the point spacing.
#include "tca/paper_mode.h"
#include "tca/unloaded_tca.h"
#include "tests/fzg_c_pair.h"

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
    for (std::size_t i = 0; i < r.seed_ste.size(); ++i)
      w = std::max(w, std::abs(r.seed_ste[i] - (exact.positions[i].transmission_error -
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

TEST(PaperMode, GivesTheContactTablesOfClassicalTca)
{
  // Same tables as classical TCA, at the method's resolution: the cloud points closest to each
  // other lie up to about a spacing apart along the flanks, so their normals are off by up to
  // ~ 2E / rho (rho: involute radius of curvature there); moment arms about the axes (r_b for
  // involutes) and separations (within 2E) agree.
  auto [p, g]                            = test_data::fzg_c_pair();
  p.drive_modifications.profile_crowning = 4e-6;
  const auto   P = InvoluteGear::create(p), G = InvoluteGear::create(g);
  const double a = working_centre_distance(*P, *G);
  TcaOptions   o;
  o.positions_per_mesh   = 5;
  const TcaResult  exact = UnloadedTca(P, G, a, {}, o).run();
  const auto       mp    = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*P, "pinion", 9, 29));
  const auto       mg    = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*G, "gear", 9, 29));
  PaperModeOptions po;
  po.spacing              = 200e-6;
  po.positions_per_mesh   = 5;
  int calls               = 0;
  po.on_position          = [&] { ++calls; };
  const PaperModeResult r = paper_mode_ste(*mp, *mg, a, {}, po);
  ASSERT_EQ(r.tca.positions.size(), exact.positions.size());
  EXPECT_EQ(calls, 5);
  const double E = r.tolerance;
  for (std::size_t i = 0; i < exact.positions.size(); ++i)
    {
      const TcaPosition &x = exact.positions[i], &q = r.tca.positions[i];
      EXPECT_NEAR(q.transmission_error, x.transmission_error, 2 * E / G->base_radius * 24 / 16);
      EXPECT_GE(q.touching, 1);
      EXPECT_LE(q.pairs[q.leading].separation, E);
      const PairContact &lx      = x.pairs[x.leading];
      bool               matched = false;
      for (const PairContact &d : q.pairs)
        {
          if (d.pinion_tooth != lx.pinion_tooth)
            continue;
          matched = true;
          // Smallest radius of curvature of the two involutes at the contact.
          const double rho =
              std::min(std::sqrt(lx.position.head<2>().squaredNorm() - std::pow(P->base_radius, 2)),
                       std::sqrt((lx.position - Vec3(a, 0, 0)).head<2>().squaredNorm() -
                                 std::pow(G->base_radius, 2)));
          EXPECT_LT(std::acos(std::min(1.0, d.normal_pinion.dot(lx.normal_pinion))), 2 * E / rho);
          EXPECT_LT(std::acos(std::min(1.0, d.normal_gear.dot(lx.normal_gear))), 2 * E / rho);
          EXPECT_NEAR(d.lambda_pinion.z(), lx.lambda_pinion.z(), 1e-3 * P->base_radius) << i;
          EXPECT_NEAR(d.lambda_gear.z(), lx.lambda_gear.z(), 1e-3 * G->base_radius) << i;
        }
      EXPECT_TRUE(matched) << i;
      for (const PairContact &c : x.pairs)
        for (const PairContact &d : q.pairs)
          if (c.pinion_tooth == d.pinion_tooth && c.separation < 1e-3)
            {
              EXPECT_NEAR(d.separation, c.separation, 2 * E) << i;
            }
    }
}

TEST(PaperMode, ToleranceBelowTheGridBoundIsRefused)
{
  // E must cover half the point spacing in both directions and the arc of one rotation step;
  // a larger E is used as given (contact declared earlier: the error grows with it).
  auto [p, g]        = test_data::fzg_c_pair();
  const auto       P = InvoluteGear::create(p), G = InvoluteGear::create(g);
  const double     a  = working_centre_distance(*P, *G);
  const auto       mp = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*P, "pinion"));
  const auto       mg = std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*G, "gear"));
  PaperModeOptions po;
  po.spacing            = 300e-6;
  po.positions_per_mesh = 2;
  po.mesh_cycles        = 1;
  po.tolerance          = 100e-6;
  try
    {
      paper_mode_ste(*mp, *mg, a, {}, po);
      FAIL() << "E = 100 um below the bound for 300 um spacing was accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("tolerance E = 100 um"), std::string::npos) << e.what();
    }
  po.tolerance             = 0;
  const PaperModeResult r0 = paper_mode_ste(*mp, *mg, a, {}, po);
  po.tolerance             = 2 * r0.tolerance;
  const PaperModeResult r2 = paper_mode_ste(*mp, *mg, a, {}, po);
  EXPECT_DOUBLE_EQ(r2.tolerance, 2 * r0.tolerance);
  // a larger E declares contact earlier: the gear is found further ahead (e_0 lower)
  EXPECT_LT(r2.tca.positions[0].transmission_error, r0.tca.positions[0].transmission_error);
}

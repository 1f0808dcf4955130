// First guesses of member flanks: the nanoflann query against brute force over the same samples
// (random queries, fixed seed), and measured members standing in for unmeasured teeth.
#include "geometry/member_flanks.h"

#include <gtest/gtest.h>

#include <functional>
#include <random>

using namespace gearkit;

TEST(MemberFlanks, NearestSampleMatchesBruteForce)
{
  InvoluteGearData d;
  d.teeth                = 21;
  d.normal_module        = 3e-3;
  d.helix_angle          = 0.3;
  const auto           g = InvoluteGear::create(d);
  InvoluteMemberFlanks m(g);
  // The 9 x 9 sample grid MemberFlanks builds, recomputed here.
  const InvoluteFlank                f   = g->flank(4, FlankSide::coast);
  const FlankDomain                  dom = f.domain();
  std::vector<std::array<double, 4>> samples; // r, z, u, v
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      {
        const double u = dom.u_min + (dom.u_max - dom.u_min) * i / 8;
        const double v = dom.v_min + (dom.v_max - dom.v_min) * j / 8;
        const Vec3   p = f.evaluate(u, v).position;
        samples.push_back({p.head<2>().norm(), p.z(), u, v});
      }
  std::mt19937_64                        rng(42);
  std::uniform_real_distribution<double> r(g->root_radius, g->tip_radius), z(-0.012, 0.012);
  for (int q = 0; q < 500; ++q)
    {
      const double qr = r(rng), qz = z(rng);
      double       best = HUGE_VAL, bu = 0, bv = 0;
      for (const auto &s : samples)
        {
          const double d2 = (s[0] - qr) * (s[0] - qr) + (s[1] - qz) * (s[1] - qz);
          if (d2 < best)
            best = d2, bu = s[2], bv = s[3];
        }
      const auto [u, v] = m.guess(4, FlankSide::coast, qr, qz);
      EXPECT_EQ(u, bu);
      EXPECT_EQ(v, bv);
    }
}

TEST(MemberFlanks, UnmeasuredTeethTakeTheNearestMeasuredFlankTurnedIntoPlace)
{
  InvoluteGearData d;
  d.teeth                = 12;
  d.normal_module        = 2e-3;
  const auto           g = InvoluteGear::create(d);
  MeasuredMemberFlanks m(virtual_cmm(*g, "gear", 9, 11, 0, {3}, false));
  EXPECT_TRUE(m.has(7, FlankSide::drive));
  EXPECT_FALSE(m.has(7, FlankSide::coast)); // no coast flank measured at all
  // tooth 7 is tooth 3 turned by 4 pitches: it lies on the exact flank of tooth 7
  const Vec3 p  = m.flank(7, FlankSide::drive).evaluate(4, 5).position;
  const auto e  = g->flank(7, FlankSide::drive);
  const auto dm = e.domain();
  EXPECT_LT(
      (e.evaluate(0.5 * (dm.u_min + dm.u_max), 0.5 * (dm.v_min + dm.v_max)).position - p).norm(),
      1e-12);
}

TEST(MemberFlanks, ToothClassesOfInvoluteAndMeasuredMembers)
{
  // Nominal teeth share class 0; an eccentric or chipped tooth has its own; any pitch deviation
  // or runout makes every tooth its own class; the numbering is dense.
  InvoluteGearData d;
  d.teeth         = 9;
  d.normal_module = 2e-3;
  {
    InvoluteMemberFlanks m(InvoluteGear::create(d));
    for (int k = 0; k < 9; ++k)
      EXPECT_EQ(m.flank_class(k), 0);
  }
  InvoluteGearData e = d;
  e.eccentric_teeth  = {{4, FlankSide::coast, 3e-6}, {6, FlankSide::drive, 0}};
  e.chipped_teeth    = {{2, 10e-3, 0.5}}; // r = 9 mm, r_a = 11 mm
  InvoluteMemberFlanks m(InvoluteGear::create(e));
  for (int k = 0; k < 9; ++k)
    EXPECT_EQ(m.flank_class(k), k == 2 ? 1 : k == 4 ? 2 : 0) << k; // a zero offset is nominal
  for (auto change : std::vector<std::function<void(InvoluteGearData &)>>{
           [](InvoluteGearData &x) {
             x.single_pitch_deviations = {1e-6, -1e-6, 0, 0, 0, 0, 0, 0, 0};
           },
           [](InvoluteGearData &x) { x.runout.eccentricity = 5e-6; }})
    {
      InvoluteGearData x = d;
      change(x);
      InvoluteMemberFlanks each(InvoluteGear::create(x));
      for (int k = 0; k < 9; ++k)
        EXPECT_EQ(each.flank_class(k), k);
    }
  EXPECT_THROW(m.flank_class(9), InputError);

  // Measured: teeth standing in by one measured tooth's flanks share its class.
  const auto           g = InvoluteGear::create(d);
  MeasuredMemberFlanks one(virtual_cmm(*g, "gear", 9, 5, 0, {3}));
  for (int k = 0; k < 9; ++k)
    EXPECT_EQ(one.flank_class(k), 0);
  MeasuredMemberFlanks two(virtual_cmm(*g, "gear", 9, 5, 0, {1, 5}));
  // nearest measured tooth (ties to the lower index): 0-3 from tooth 1, 4-7 from 5, 8 from 1
  for (int k = 0; k < 9; ++k)
    EXPECT_EQ(two.flank_class(k), k >= 4 && k <= 7 ? 1 : 0) << k;
}

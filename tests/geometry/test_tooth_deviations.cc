// Per-tooth deviations of an involute gear (tolerance samples): a tooth's own deviations add to
// its side's modifications along the normal, the other teeth and the other side keep theirs,
// such a tooth is a flank class of its own, and a list of the wrong length is refused.
#include "geometry/member_flanks.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

using namespace gearkit;

TEST(ToothDeviations, AddToTheSidesModificationsOnTheirToothAlone)
{
  auto [pd, gd]                        = test_data::fzg_c_pair();
  pd.drive_modifications.lead_crowning = 5e-6;
  const auto       plain               = InvoluteGear::create(pd);
  InvoluteGearData d                   = pd;
  d.drive_tooth_deviations.resize(16);
  d.drive_tooth_deviations[3].profile_slope = 4e-6;
  d.drive_tooth_deviations[3].helix_slope   = -3e-6;
  const auto               gear             = InvoluteGear::create(d);
  const ModificationFrame &frame            = gear->modification_frame();
  const double             u = 0.4, z = 3e-3;
  for (const int k : {2, 3})
    {
      const FlankPoint a    = plain->flank(k, FlankSide::drive).evaluate(u, z);
      const FlankPoint b    = gear->flank(k, FlankSide::drive).evaluate(u, z);
      const double expected = k == 3 ? evaluate_modifications(d.drive_tooth_deviations[3], frame,
                                                              gear->base_radius * u, z)
                                           .value
                                     : 0.0;
      EXPECT_NEAR((b.position - a.position).dot(a.normal), expected, 1e-12) << k;
      EXPECT_NEAR((b.position - a.position).norm(), std::abs(expected), 1e-12) << k;
    }
  EXPECT_NE(
      evaluate_modifications(d.drive_tooth_deviations[3], frame, gear->base_radius * u, z).value,
      0.0);
  const FlankPoint coast_a = plain->flank(3, FlankSide::coast).evaluate(u, z);
  const FlankPoint coast_b = gear->flank(3, FlankSide::coast).evaluate(u, z);
  EXPECT_EQ(coast_a.position, coast_b.position);
  const InvoluteMemberFlanks member(gear);
  EXPECT_EQ(member.flank_class(2), 0);
  EXPECT_EQ(member.flank_class(3), 1);
  d.drive_tooth_deviations.resize(15);
  EXPECT_THROW(InvoluteGear::create(d), InputError);
  d.drive_tooth_deviations.resize(16);
  d.drive_tooth_deviations[0].tip_relief = 5e-6; // a relief without its length
  EXPECT_THROW(InvoluteGear::create(d), InputError);
}

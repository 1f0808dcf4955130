// Unloaded TCA of face-milled spiral bevel pairs (reference-data.md section 7): the crown-gear
// test (both members cut by complementary flanks of one plane generating gear: conjugate, line
// contact, zero transmission error) on the seed pair's blank (section 1).
#include "bevel_gear.h"
#include "unloaded_tca.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

namespace
{
BevelPairDesign
seed_design()
{
  BevelPairDesign d; // seed Table 1: 55/47, m 3 mm (taken as outer transverse), 35 deg, 19 mm
  d.pinion_teeth = 55, d.gear_teeth = 47, d.module = 3e-3, d.face_width = 19e-3;
  d.pinion_hand = Hand::right;
  return d;
}

struct BevelPair
{
  std::shared_ptr<const BevelMemberFlanks> pinion, gear;
  Assembly                                 assembly;
};

BevelPair
make(const BevelPairDesign &d, const Misalignment &m = {})
{
  const auto [pc, gc] = conjugate_cuts(d);
  return {std::make_shared<BevelMemberFlanks>(pc), std::make_shared<BevelMemberFlanks>(gc),
          Assembly::bevel(d.shaft_angle, bevel_geometry(d).pitch_angle_pinion, d.gear_teeth, m)};
}
} // namespace

TEST(BevelTca, CrownGearTestGivesZeroTransmissionError)
{
  const BevelPair s = make(seed_design());
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      TcaOptions o;
      o.positions_per_mesh = 12;
      o.side               = side;
      const TcaResult r    = UnloadedTca(s.pinion, s.gear, s.assembly, o).run();
      for (const TcaPosition &p : r.positions)
        {
          EXPECT_LT(std::abs(p.transmission_error), 1e-9) << to_string(side) << p.pinion_angle;
          // torque ratio of a conjugate pair: lambda_g . a_g / lambda_p . z = z2 / z1
          const PairContact &c = p.pairs[p.leading];
          EXPECT_NEAR(std::abs(c.lambda_gear.dot(s.assembly.gear_axis()) / c.lambda_pinion.z()),
                      47.0 / 55, 1e-6);
          EXPECT_NEAR((c.normal_pinion + c.normal_gear).norm(), 0, 1e-9);
        }
      EXPECT_GT(r.mean_pairs_in_contact, 1.2);
    }
}

// The foot of a point on a flank against points built at a known normal distance, and the
// plausibility checks of a measurement (units, swapped sides, a point off the flank) on a
// perfect virtual CMM and its deliberate corruptions.
#include "geometry/flank_distance.h"

#include <gtest/gtest.h>

#include <random>

using namespace gearkit;

namespace
{
std::shared_ptr<const InvoluteGear>
helical_gear()
{
  InvoluteGearData d;
  d.name                                  = "gear";
  d.teeth                                 = 21;
  d.normal_module                         = 3e-3;
  d.helix_angle                           = 0.3;
  d.profile_shift                         = 0.2;
  d.drive_modifications.tip_relief        = 20e-6;
  d.drive_modifications.tip_relief_length = 2e-3;
  d.drive_modifications.lead_crowning     = 10e-6;
  return InvoluteGear::create(d);
}
} // namespace

TEST(FlankDistance, FootOfPointsAtKnownNormalDistance)
{
  // x = r(u, v) + delta n(u, v) has its foot at (u, v) and distance delta exactly (the normal
  // line through a surface point meets the surface there perpendicularly); Gauss-Newton from the
  // coarse guess converges to rounding: 1e-12 m on distances of up to 0.5 mm.
  const InvoluteMemberFlanks             m(helical_gear());
  std::mt19937_64                        rng(7);
  std::uniform_real_distribution<double> unit(0.05, 0.95), delta(-500e-6, 500e-6);
  for (int q = 0; q < 200; ++q)
    {
      const int         tooth = q % 21;
      const FlankSide   side  = q % 2 ? FlankSide::drive : FlankSide::coast;
      const Flank      &f     = m.flank(tooth, side);
      const FlankDomain d     = f.domain();
      const double      u     = d.u_min + unit(rng) * (d.u_max - d.u_min);
      const double      v     = d.v_min + unit(rng) * (d.v_max - d.v_min);
      const double      s     = delta(rng);
      const FlankPoint  p     = f.evaluate(u, v);
      const FlankFoot   foot  = flank_foot(m, tooth, side, p.position + s * p.normal);
      EXPECT_FALSE(foot.on_edge);
      EXPECT_NEAR(foot.signed_distance, s, 1e-12) << q;
      EXPECT_LT((foot.position - p.position).norm(), 1e-9) << q;
    }
}

TEST(FlankDistance, MeasurementChecksCatchUnitsSidesAndStrayPoints)
{
  const InvoluteMemberFlanks m(helical_gear());
  MeasuredMember             measured = virtual_cmm(m, "gear", 7, 5, 0.05, {0, 4});
  EXPECT_NO_THROW(check_measurement(measured, m, 1e-6, "gear.cmm", "tolerance"));

  auto message = [&](const MeasuredMember &bad) {
    try
      {
        check_measurement(bad, m, 100e-6, "gear.cmm", "Measured flanks/p/nominal tolerance");
      }
    catch (const InputError &e)
      {
        return std::string(e.what());
      }
    return std::string("accepted");
  };
  MeasuredMember metres = measured; // metres written in a millimetre file
  for (MeasuredFlank &f : metres.flanks)
    for (Vec3 &x : f.points)
      x *= 1e-3;
  EXPECT_NE(message(metres).find("metres written as millimetres"), std::string::npos)
      << message(metres);
  MeasuredMember inches = measured; // millimetres in a file that says inches
  for (MeasuredFlank &f : inches.flanks)
    for (Vec3 &x : f.points)
      x *= 25.4;
  EXPECT_NE(message(inches).find("millimetres written as inches"), std::string::npos)
      << message(inches);

  MeasuredMember swapped = measured;
  for (MeasuredFlank &f : swapped.flanks)
    f.side = f.side == FlankSide::drive ? FlankSide::coast : FlankSide::drive;
  EXPECT_NE(message(swapped).find("labels swapped"), std::string::npos) << message(swapped);

  MeasuredMember inward = measured; // probe normals reversed
  for (MeasuredFlank &f : inward.flanks)
    for (Vec3 &n : f.normals)
      n = -n;
  EXPECT_NE(message(inward).find("probe normals point into the tooth"), std::string::npos)
      << message(inward);

  MeasuredMember stray = measured; // one point 150 um off, another 50 um: only the first counts
  MeasuredFlank &f     = stray.flanks[1];
  f.points[12] += 150e-6 * f.normals[12];
  f.points[20] -= 50e-6 * f.normals[20];
  const std::string text = message(stray);
  EXPECT_NE(text.find("point 12 (profile 2, face 2) lies 150"), std::string::npos) << text;
  EXPECT_NE(text.find("(1 points beyond"), std::string::npos) << text;
  EXPECT_NE(text.find("Measured flanks/p/nominal tolerance"), std::string::npos) << text;
}

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

// Equality of modifications (a study reuses its own modifications' values at the cells for the
// variants that keep them): every field takes part.
TEST(ToothDeviations, ModificationsAreEqualOnlyWithEveryFieldEqual)
{
  ToothModifications a;
  a.tip_relief        = 20e-6;
  a.tip_relief_length = 4e-3;
  EXPECT_TRUE(a == a);
  const std::vector<double ToothModifications::*> fields = {
      &ToothModifications::tip_relief,         &ToothModifications::tip_relief_length,
      &ToothModifications::root_relief,        &ToothModifications::root_relief_length,
      &ToothModifications::lead_crowning,      &ToothModifications::end_relief,
      &ToothModifications::end_relief_length,  &ToothModifications::profile_crowning,
      &ToothModifications::profile_slope,      &ToothModifications::helix_slope,
      &ToothModifications::waviness_amplitude, &ToothModifications::waviness_wavelength,
      &ToothModifications::waviness_phase};
  for (const auto f : fields)
    {
      ToothModifications b = a;
      b.*f += 1e-9;
      EXPECT_TRUE(a != b);
      EXPECT_FALSE(a == b);
    }
  ToothModifications b = a;
  b.tip_relief_shape   = ReliefShape::parabolic;
  EXPECT_TRUE(a != b);
  b                   = a;
  b.root_relief_shape = ReliefShape::parabolic;
  EXPECT_TRUE(a != b);
}

// A waviness from the sines of its phase and of the point's phase (a study's teeth evaluated
// at fixed cells) equals the waviness evaluated directly, at any phase.
TEST(ToothDeviations, WavinessFromTheAngleSumEqualsTheDirectOne)
{
  ModificationFrame  f{0.004, 0.022, 0.014, 0.0045};
  ToothModifications m;
  m.waviness_amplitude  = 3e-6;
  m.waviness_wavelength = profile_form_wavelength(f);
  for (const double phase : {0.0, 0.7, pi, -2.1})
    for (const double L : {0.004, 0.0091, 0.0133, 0.0217})
      {
        m.waviness_phase        = phase;
        const NormalDeviation d = evaluate_modifications(m, f, L, 0.001);
        const double          a = 2 * pi / m.waviness_wavelength * (L - f.roll_length_form);
        const NormalDeviation w =
            waviness_term(m.waviness_amplitude, m.waviness_wavelength, std::sin(phase),
                          std::cos(phase), std::sin(a), std::cos(a));
        EXPECT_NEAR(w.value, d.value, 1e-15 * m.waviness_amplitude) << phase << " " << L;
        const double k = 2 * pi / m.waviness_wavelength;
        EXPECT_NEAR(w.d_dL, d.d_dL, 1e-14 * k * m.waviness_amplitude) << phase << " " << L;
        EXPECT_NEAR(d.value, m.waviness_amplitude * std::sin(a + phase), 1e-15 * 3e-6);
      }
}

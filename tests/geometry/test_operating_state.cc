// What is defined on the active profile or the path of contact, taken at the centre distance the
// pair runs at (issue 35): the start of active profile, the ISO 1328-1 profile evaluation range
// and the f_Halpha acting over it, the transverse contact ratio. Every expectation is computed
// here from the line-of-action geometry alone (radii from z, m and alpha_n; no InvoluteGear
// member), at an operating centre distance a != a_w.
#include "base/units.h"
#include "geometry/involute_gear.h"
#include "geometry/modifications.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;
using units::deg;

namespace
{

// The pair: 29/41 teeth, m 3 mm, alpha 20 deg, spur, no profile shift: a_w = 105 mm.
constexpr int    z1 = 29, z2 = 41;
constexpr double m_n = 3e-3, alpha = 20 * deg;

InvoluteGearData
member(const char *name, int z)
{
  InvoluteGearData d;
  d.name                  = name;
  d.teeth                 = z;
  d.normal_module         = m_n;
  d.normal_pressure_angle = alpha;
  d.face_width            = 20e-3;
  return d;
}

// The closed-form line-of-action geometry of an unshifted spur pair with h_aP* = 1.
struct LineOfAction
{
  double rb1, rb2, ra1, ra2, a, alpha_wt, p_bt;

  explicit LineOfAction(double a_)
      : rb1(z1 * m_n / 2 * std::cos(alpha))
      , rb2(z2 * m_n / 2 * std::cos(alpha))
      , ra1(z1 * m_n / 2 + m_n)
      , ra2(z2 * m_n / 2 + m_n)
      , a(a_)
      , alpha_wt(std::acos((rb1 + rb2) / a_))
      , p_bt(pi * m_n * std::cos(alpha))
  {
  }
  // roll length of a member's tip (distance from its base tangent point to the tip circle)
  static double
  tip_roll(double ra, double rb)
  {
    return std::sqrt(ra * ra - rb * rb);
  }
  // L_A of the gear: the pinion's tip circle on the line of action
  double
  gear_start_roll() const
  {
    return a * std::sin(alpha_wt) - tip_roll(ra1, rb1);
  }
  double
  pinion_start_roll() const
  {
    return a * std::sin(alpha_wt) - tip_roll(ra2, rb2);
  }
  double
  transverse_contact_ratio() const
  {
    return (tip_roll(ra1, rb1) + tip_roll(ra2, rb2) - a * std::sin(alpha_wt)) / p_bt;
  }
};
} // namespace

TEST(OperatingState, StartOfActiveProfileFollowsTheCentreDistance)
{
  const double a_w = 105e-3, a = 105.15e-3;
  const auto [p, g] = create_pair(member("pinion", z1), member("gear", z2), a);
  const LineOfAction l(a), l_w(a_w);
  // the radii the closed form starts from are the members' (1e-15 m: rounding of the same
  // formulas written twice)
  ASSERT_NEAR(p->base_radius, l.rb1, 1e-15);
  ASSERT_NEAR(g->tip_radius, l.ra2, 1e-15);
  ASSERT_NEAR(working_centre_distance(*p, *g), a_w, 1e-15);
  // r_SAP = sqrt(r_b^2 + L_A^2), L_A = a sin(alpha_wt) - sqrt(r_a,mate^2 - r_b,mate^2); 1e-13 m:
  // a few roundings of quantities of 0.1 m
  EXPECT_NEAR(g->data().active_profile_start_radius, std::hypot(l.rb2, l.gear_start_roll()), 1e-13);
  EXPECT_NEAR(p->data().active_profile_start_radius, std::hypot(l.rb1, l.pinion_start_roll()),
              1e-13);
  EXPECT_NEAR(g->modification_frame().roll_length_active_start, l.gear_start_roll(), 1e-13);
  EXPECT_NEAR(p->modification_frame().roll_length_active_start, l.pinion_start_roll(), 1e-13);
  // the numbers: opened by 0.15 mm the gear's start lies 0.15 mm / sin(alpha_wt) =
  // 0.44 mm of roll length higher than at a_w (to first order in the opening)
  const auto [p_w, g_w] = create_pair(member("pinion", z1), member("gear", z2));
  const double shift    = g->modification_frame().roll_length_active_start -
                       g_w->modification_frame().roll_length_active_start;
  EXPECT_NEAR(shift, l.gear_start_roll() - l_w.gear_start_roll(), 1e-13);
  EXPECT_NEAR(shift, 0.15e-3 / std::sin(l_w.alpha_wt), 0.005e-3);
  EXPECT_NEAR(shift, 0.44e-3, 0.005e-3);
  // the same through the default (zero-backlash) centre distance: the design mesh
  EXPECT_NEAR(g_w->modification_frame().roll_length_active_start, l_w.gear_start_roll(), 1e-13);
}

TEST(OperatingState, ProfileEvaluationRangeAndSlopeAtTheOperatingCentreDistance)
{
  const double     a                   = 105.15e-3;
  InvoluteGearData dg                  = member("gear", z2);
  dg.drive_modifications.profile_slope = -6e-6;
  const auto [p, g]                    = create_pair(member("pinion", z1), dg, a);
  const LineOfAction l(a);
  // ISO 1328-1: from the start of active profile L_A over 92 % of the active length to the tip
  const double L_A = l.gear_start_roll(), L_E = LineOfAction::tip_roll(l.ra2, l.rb2);
  const auto [L0, L1] = profile_evaluation_range(g->modification_frame());
  EXPECT_NEAR(L0, L_A, 1e-13);
  EXPECT_NEAR(L1, L_A + 0.92 * (L_E - L_A), 1e-13);
  // f_Halpha is the rise of the mean profile line over exactly that range
  const ToothModifications &m    = g->data().drive_modifications;
  const ModificationFrame  &f    = g->modification_frame();
  const double              rise = evaluate_modifications(m, f, L_A + 0.92 * (L_E - L_A), 0).value -
                      evaluate_modifications(m, f, L_A, 0).value;
  EXPECT_NEAR(rise, -6e-6, 1e-15);
  // slope -6 um / L_alpha: the range taken at a_w is 0.44 mm longer, a slope about 3 % off
  const auto [p_w, g_w] = create_pair(member("pinion", z1), dg);
  const auto [W0, W1]   = profile_evaluation_range(g_w->modification_frame());
  EXPECT_NEAR(evaluate_modifications(m, f, L_E, 0).d_dL, -6e-6 / (0.92 * (L_E - L_A)), 1e-15);
  const double slope_ratio = (W1 - W0) / (L1 - L0);
  EXPECT_GT(slope_ratio - 1, 0.025);
  EXPECT_LT(slope_ratio - 1, 0.035);
}

// C_alpha is removed at both ends of the active profile (the start of active profile at the
// operating centre distance, and the tip), none in its middle - as its help text says; before
// issue 35 the crown spanned the whole involute (form circle to tip), so that less than C_alpha
// was removed at the start of active profile and some in the middle of the active profile.
TEST(OperatingState, ProfileCrowningOverTheActiveProfileAtTheOperatingCentreDistance)
{
  const double     a                      = 105.15e-3;
  InvoluteGearData dg                     = member("gear", z2);
  dg.drive_modifications.profile_crowning = 5e-6;
  const auto [p, g]                       = create_pair(member("pinion", z1), dg, a);
  const LineOfAction        l(a);
  const double              L_A = l.gear_start_roll(), L_E = LineOfAction::tip_roll(l.ra2, l.rb2);
  const ToothModifications &m = g->data().drive_modifications;
  const ModificationFrame  &f = g->modification_frame();
  EXPECT_NEAR(evaluate_modifications(m, f, L_A, 0).value, -5e-6, 1e-15);
  EXPECT_NEAR(evaluate_modifications(m, f, L_E, 0).value, -5e-6, 1e-15);
  EXPECT_NEAR(evaluate_modifications(m, f, 0.5 * (L_A + L_E), 0).value, 0, 1e-15);
  // a quarter of the way: (1/2)^2 of C_alpha; the slope there by the parabola's derivative
  const double L_q = L_A + 0.25 * (L_E - L_A);
  EXPECT_NEAR(evaluate_modifications(m, f, L_q, 0).value, -1.25e-6, 1e-15);
  EXPECT_NEAR(evaluate_modifications(m, f, L_q, 0).d_dL, 2 * 5e-6 / (L_E - L_A), 1e-12);
  // at the zero-backlash centre distance the active profile starts 0.44 mm lower
  const auto [p_w, g_w] = create_pair(member("pinion", z1), dg);
  EXPECT_NEAR(evaluate_modifications(m, g_w->modification_frame(), l.gear_start_roll(), 0).value,
              -5e-6 * std::pow((l.gear_start_roll() -
                                0.5 * (LineOfAction(105e-3).gear_start_roll() + L_E)) /
                                   (0.5 * (L_E - LineOfAction(105e-3).gear_start_roll())),
                               2),
              1e-15);
}

TEST(OperatingState, TransverseContactRatioAtTheOperatingCentreDistance)
{
  const auto [p, g] = create_pair(member("pinion", z1), member("gear", z2));
  for (double a : {105e-3, 105.15e-3, 105.6e-3})
    {
      const LineOfAction l(a);
      // 1e-12: differences of roll lengths of ~0.02 m divided by the pitch, a few roundings
      EXPECT_NEAR(contact_ratios(*p, *g, a).transverse, l.transverse_contact_ratio(), 1e-12)
          << "a " << a;
      // the path of contact is the stretch between the two starts of active profile
      const auto [pa, ga] = create_pair(member("pinion", z1), member("gear", z2), a);
      const double path =
          LineOfAction::tip_roll(l.ra1, l.rb1) - pa->modification_frame().roll_length_active_start;
      EXPECT_NEAR(path / l.p_bt, l.transverse_contact_ratio(), 1e-12) << "a " << a;
    }
  // opening the centre distance shortens the path of contact by da / sin(alpha_wt) ... to first
  // order; 0.15 mm here: 0.44 mm of the 14.5 mm path
  EXPECT_LT(contact_ratios(*p, *g, 105.15e-3).transverse,
            contact_ratios(*p, *g, 105e-3).transverse - 0.04);
}

TEST(OperatingState, ATipThatReachesBelowTheInvoluteStartsTheRangeAtTheFormCircle)
{
  // 12 teeth against 80 at a_w: the gear's tip circle crosses the line of action below the
  // pinion's form circle (the pinion is undercut); opened far enough it crosses above it.
  InvoluteGearData dp = member("pinion", 12), dg = member("gear", 80);
  const auto [p, g] = create_pair(dp, dg);
  EXPECT_EQ(p->data().active_profile_start_radius, p->form_radius);
  const double a    = working_centre_distance(*p, *g) + 1.5e-3;
  const auto [q, h] = create_pair(dp, dg, a);
  const double rb   = q->base_radius + h->base_radius;
  const double L_A  = std::sqrt(a * a - rb * rb) -
                     std::sqrt(h->tip_radius * h->tip_radius - h->base_radius * h->base_radius);
  ASSERT_GT(L_A, q->base_radius * q->roll_angle_form);
  EXPECT_NEAR(q->data().active_profile_start_radius, std::hypot(q->base_radius, L_A), 1e-13);
}

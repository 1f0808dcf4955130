// Unloaded TCA of involute pairs against the exact relations of reference-data.md section 6.
#include "base/units.h"
#include "tca/unloaded_tca.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;
using units::deg;

namespace
{

std::pair<InvoluteGearData, InvoluteGearData>
c_pair(double helix = 0)
{
  return test_data::fzg_c_pair(helix);
}

struct TcaPair
{
  std::shared_ptr<const InvoluteGear> pinion, gear;
  double                              a_w;
};

TcaPair
make_tca_pair(const std::pair<InvoluteGearData, InvoluteGearData> &d)
{
  // assembled as a pair: each member's start of active profile from the other
  auto [p, g] = create_pair(d.first, d.second);
  return {p, g, working_centre_distance(*p, *g)};
}

double
peak_to_peak(const TcaResult &r)
{
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &p : r.positions)
    lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
  return hi - lo;
}
} // namespace

TEST(UnloadedTca, PerfectInvolutesHaveZeroTransmissionError)
{
  for (double beta : {0.0, 15 * deg})
    {
      const TcaPair s = make_tca_pair(c_pair(beta));
      TcaOptions    o;
      o.positions_per_mesh = 24;
      const auto r         = UnloadedTca(s.pinion, s.gear, s.a_w, {}, o).run();
      for (const TcaPosition &p : r.positions)
        EXPECT_LT(std::abs(p.transmission_error), 1e-9)
            << "beta " << beta << " phi " << p.pinion_angle;
    }
}

TEST(UnloadedTca, ShiftedCentreDistanceGivesConstantErrorOfHalfTheBacklash)
{
  // At a' = a_w + 0.1 mm the involutes stay conjugate (TE constant); the pinion takes up half the
  // circumferential backlash j on the operating pitch circle: e = j / (2 r'_1) with
  // j = p' - s_1(r'_1) - s_2(r'_2), cos(alpha') = (r_b1 + r_b2) / a'.
  const TcaPair s  = make_tca_pair(c_pair());
  const double  a  = s.a_w + 0.1e-3;
  const double  ca = (s.pinion->base_radius + s.gear->base_radius) / a;
  const double  r1 = s.pinion->base_radius / ca, r2 = s.gear->base_radius / ca;
  const double  j = 2 * pi * r1 / 16 - s.pinion->tooth_thickness(r1) - s.gear->tooth_thickness(r2);
  TcaOptions    o;
  o.positions_per_mesh = 12;
  const auto r         = UnloadedTca(s.pinion, s.gear, a, {}, o).run();
  EXPECT_LT(peak_to_peak(r), 1e-9);
  EXPECT_NEAR(r.positions[0].transmission_error, j / (2 * r1), 1e-9);
}

TEST(UnloadedTca, ContactRatioOfPerfectSpurPair)
{
  // eps_alpha = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a_w sin(alpha_w)) / p_bt; counting
  // touching pairs at N positions per cycle resolves it to 1/N.
  const TcaPair s = make_tca_pair(c_pair());
  const auto   &p = *s.pinion, &g = *s.gear;
  const double  aw  = working_pressure_angle(p, g);
  const double  eps = (std::sqrt(p.tip_radius * p.tip_radius - p.base_radius * p.base_radius) +
                      std::sqrt(g.tip_radius * g.tip_radius - g.base_radius * g.base_radius) -
                      s.a_w * std::sin(aw)) /
                     p.transverse_base_pitch;
  EXPECT_NEAR(contact_ratios(p, g, s.a_w).transverse, eps, 1e-12);
  EXPECT_EQ(contact_ratios(p, g, s.a_w).overlap, 0);
  TcaOptions o;
  o.positions_per_mesh = 200;
  const auto r         = UnloadedTca(s.pinion, s.gear, s.a_w, {}, o).run();
  EXPECT_NEAR(r.mean_pairs_in_contact, eps, 1.0 / 200);
  EXPECT_GT(eps, 1.3);
  EXPECT_THROW(contact_ratios(p, g, p.base_radius + g.base_radius), InputError);
}

TEST(UnloadedTca, TotalContactRatioOfPerfectHelicalPair)
{
  // Helical: the pairs in contact average eps_gamma = eps_alpha + eps_beta, and at a larger
  // centre distance eps_alpha drops as the formula says.
  const TcaPair s = make_tca_pair(c_pair(15 * deg));
  for (double da : {0.0, 0.3e-3})
    {
      const ContactRatios c = contact_ratios(*s.pinion, *s.gear, s.a_w + da);
      EXPECT_NEAR(c.overlap, 14e-3 * std::sin(15 * deg) / (pi * 4.5e-3), 1e-12);
      TcaOptions o;
      o.positions_per_mesh = 200;
      const auto r         = UnloadedTca(s.pinion, s.gear, s.a_w + da, {}, o).run();
      EXPECT_NEAR(r.mean_pairs_in_contact, c.transverse + c.overlap, 1.0 / 200) << da;
    }
}

TEST(UnloadedTca, TorqueRatioEqualsToothRatio)
{
  // T2 / T1 = (lambda_g . a_g) / (lambda_p . e_z) = z2 / z1 at every contact of perfect involutes.
  const TcaPair s = make_tca_pair(c_pair(12 * deg));
  UnloadedTca   tca(s.pinion, s.gear, s.a_w);
  for (double phi : {0.0, 0.07, 0.21})
    {
      const TcaPosition  p = tca.at(phi);
      const PairContact &c = p.pairs[p.leading];
      EXPECT_NEAR(std::abs(c.lambda_gear.z() / c.lambda_pinion.z()), 24.0 / 16, 1e-9);
      EXPECT_NEAR((c.normal_pinion + c.normal_gear).norm(), 0, 1e-9); // opposite normals
    }
}

TEST(UnloadedTca, EccentricToothStepsByEOverBaseRadius)
{
  // Pinion tooth 0 moved 4.5 um along its drive normal: while it carries the load the TE drops
  // by e / r_b1 (the gear runs ahead), elsewhere it is zero.
  auto d                  = c_pair();
  d.first.eccentric_teeth = {{0, FlankSide::drive, 4.5e-6}};
  const TcaPair s         = make_tca_pair(d);
  UnloadedTca   tca(s.pinion, s.gear, s.a_w);
  EXPECT_NEAR(tca.at(0).transmission_error, -4.5e-6 / s.pinion->base_radius, 1e-9);
  EXPECT_NEAR(tca.at(-3 * 2 * pi / 16).transmission_error, 0, 1e-9); // tooth 0 far from mesh
}

TEST(UnloadedTca, LeadCrowningAloneLeavesSpurErrorZero)
{
  auto d                                     = c_pair();
  d.first.drive_modifications.lead_crowning  = 10e-6;
  d.second.drive_modifications.lead_crowning = 5e-6;
  const TcaPair s                            = make_tca_pair(d);
  TcaOptions    o;
  o.positions_per_mesh = 10;
  const auto r         = UnloadedTca(s.pinion, s.gear, s.a_w, {}, o).run();
  for (const TcaPosition &p : r.positions)
    {
      EXPECT_LT(std::abs(p.transmission_error), 1e-9);
      EXPECT_NEAR(p.pairs[p.leading].v1, 0, 1e-6); // contact in the middle of the face
    }
}

TEST(UnloadedTca, ProfileSlopeGivesTheExpectedRamp)
{
  // delta = f_Ha (L - L_mid) / L_alpha on every pinion tooth, L_alpha the ISO 1328-1 profile
  // evaluation range: 92 % of the active length from the start of active profile L_A (the gear's
  // tip circle on the line of action, L_A = a sin(alpha_wt) - sqrt(r_a2^2 - r_b2^2)) to the tip
  // L_E. While one pair leads, its contact rolls along the line of action by r_b1 dphi, so to
  // first order dTE/dphi = -f_Ha / L_alpha. The slope also tilts the normal by f_Ha / L_alpha
  // (~4.5e-4 here), which moves the contact: the relative departure from the first-order ramp
  // must be of that order and halve with f_Ha.
  auto departure = [](double f_Ha) {
    auto d                                    = c_pair();
    d.first.drive_modifications.profile_slope = f_Ha;
    const TcaPair       s                     = make_tca_pair(d);
    const InvoluteGear &p = *s.pinion, &g = *s.gear;
    const double        cos_alpha = (p.base_radius + g.base_radius) / s.a_w;
    const double        L_A       = s.a_w * std::sqrt(1 - cos_alpha * cos_alpha) -
                       std::sqrt(g.tip_radius * g.tip_radius - g.base_radius * g.base_radius);
    const double L_alpha = 0.92 * (p.base_radius * p.roll_angle_tip - L_A);
    UnloadedTca  tca(s.pinion, s.gear, s.a_w);
    const double h  = 1e-3;
    const auto   p0 = tca.at(0.0), p1 = tca.at(h);
    EXPECT_EQ(p0.pairs[p0.leading].pinion_tooth, p1.pairs[p1.leading].pinion_tooth);
    const double first_order = -f_Ha / L_alpha;
    return std::pair((p1.transmission_error - p0.transmission_error) / h / first_order - 1,
                     f_Ha / L_alpha);
  };
  const auto [big, tilt] = departure(8e-6);
  const auto [small, _]  = departure(4e-6);
  EXPECT_LT(std::abs(big), 3 * tilt);
  EXPECT_NEAR(big / small, 2, 0.1);
}

TEST(UnloadedTca, CrossedAxesGiveLinearErrorWithJumps)
{
  // A helical pair with a 0.5 mrad crossing misalignment: the contact runs to the face edge and
  // the TE is piecewise linear in phi, jumping where the next pair takes over.
  const TcaPair s = make_tca_pair(c_pair(15 * deg));
  Misalignment  m;
  m.crossing_angle = 0.5e-3;
  TcaOptions o;
  o.positions_per_mesh = 40;
  o.mesh_cycles        = 2;
  const auto r         = UnloadedTca(s.pinion, s.gear, s.a_w, m, o).run();
  EXPECT_GT(peak_to_peak(r), 1e-6);
  EXPECT_FALSE(r.transfers.empty());
  // Where the contact sits on a face end (not on a tip or root edge) of one pair, TE is linear.
  const FlankDomain d1          = s.pinion->flank(0, FlankSide::drive).domain();
  const FlankDomain d2          = s.gear->flank(0, FlankSide::drive).domain();
  auto              on_face_end = [&](const TcaPosition &p) {
    const PairContact &c  = p.pairs[p.leading];
    auto               in = [](double x, double lo, double hi) {
      return x > lo + 1e-6 * (hi - lo) && x < hi - 1e-6 * (hi - lo);
    };
    return in(c.u1, d1.u_min, d1.u_max) && in(c.u2, d2.u_min, d2.u_max) &&
           (!in(c.v1, d1.v_min, d1.v_max) || !in(c.v2, d2.v_min, d2.v_max));
  };
  int linear_checks = 0;
  for (std::size_t i = 2; i < r.positions.size(); ++i)
    {
      const auto &a = r.positions[i - 2], &b = r.positions[i - 1], &c = r.positions[i];
      const int   t = a.pairs[a.leading].pinion_tooth;
      if (b.pairs[b.leading].pinion_tooth != t || c.pairs[c.leading].pinion_tooth != t ||
          !on_face_end(a) || !on_face_end(b) || !on_face_end(c))
        continue;
      // Second against first difference: linear to a few times the misalignment angle (0.5
      // mrad): the edge contact's TE is linear in phi to first order in the misalignment; the
      // measured ratio is <= 7e-4.
      const double second = a.transmission_error - 2 * b.transmission_error + c.transmission_error;
      EXPECT_LT(std::abs(second), 2e-3 * std::abs(c.transmission_error - a.transmission_error))
          << i;
      ++linear_checks;
    }
  EXPECT_GT(linear_checks, 20);
  // and it jumps where the next pair takes over: far off the line through the previous steps
  for (int i : r.transfers)
    if (i >= 2)
      {
        const double extrapolated =
            2 * r.positions[i - 1].transmission_error - r.positions[i - 2].transmission_error;
        EXPECT_GT(std::abs(r.positions[i].transmission_error - extrapolated), 1e-7) << i;
      }
}

TEST(UnloadedTca, FlanksThatDoNotMeshAreRefused)
{
  const TcaPair s = make_tca_pair(c_pair());
  EXPECT_THROW(UnloadedTca(s.pinion, s.gear, s.a_w + 20e-3).at(0), InputError); // apart
  Misalignment off;
  off.gear_axial_shift = 20e-3; // faces do not overlap
  EXPECT_THROW(UnloadedTca(s.pinion, s.gear, s.a_w, off).at(0), InputError);
  auto same_hand        = c_pair(15 * deg);
  same_hand.second.hand = Hand::right;
  EXPECT_THROW(UnloadedTca(InvoluteGear::create(same_hand.first),
                           InvoluteGear::create(same_hand.second), s.a_w),
               InputError);
}

TEST(UnloadedTca, ProfileCrowningGivesParabolicArcs)
{
  // C_alpha on the pinion: the leading pair is the one nearer the middle of the active
  // profile, and e_0 = -delta(L)/r_b1 = C_alpha (2 (L - L_mid) / L_alpha)^2 / r_b1 at its
  // contact roll length L, L_alpha the active profile from the start of active profile L_A in
  // mesh to the tip, to first order (the normal tilts by <= 4 C_alpha / L_alpha ~ 1e-3:
  // tolerance 1 %). L_A from the line of action: the gear's tip circle crosses it there.
  auto d                                       = c_pair();
  d.first.drive_modifications.profile_crowning = 4e-6;
  const TcaPair s                              = make_tca_pair(d);
  const double  rb = s.pinion->base_radius, Lt = rb * s.pinion->roll_angle_tip;
  const double  rb2 = s.gear->base_radius, ra2 = s.gear->tip_radius;
  const double  Lf =
      std::sqrt(s.a_w * s.a_w - (rb + rb2) * (rb + rb2)) - std::sqrt(ra2 * ra2 - rb2 * rb2); // L_A
  ASSERT_GT(Lf, rb * s.pinion->roll_angle_form);
  TcaOptions o;
  o.positions_per_mesh = 30;
  const auto r         = UnloadedTca(s.pinion, s.gear, s.a_w, {}, o).run();
  double     largest   = 0;
  for (const TcaPosition &p : r.positions)
    {
      const double L        = rb * p.pairs[p.leading].u1;
      const double x        = 2 * (L - 0.5 * (Lf + Lt)) / (Lt - Lf);
      const double expected = 4e-6 * x * x / rb;
      EXPECT_NEAR(p.transmission_error, expected, 0.01 * expected + 1e-12) << p.pinion_angle;
      largest = std::max(largest, p.transmission_error);
    }
  // the transfer lies half a base pitch either side of the middle: the arcs peak near there
  const double x_transfer = s.pinion->transverse_base_pitch / (Lt - Lf);
  EXPECT_LT(largest, 1.01 * 4e-6 * x_transfer * x_transfer / rb);
  EXPECT_GT(largest, 0.8 * 4e-6 * x_transfer * x_transfer / rb);
}

TEST(UnloadedTca, CoastFlanksCloseTheBacklashFromTheOtherSide)
{
  // On the coast flanks the same exact relations hold with the signs turned: zero TE at zero
  // backlash; at a' = a_w + 0.1 mm the drive and coast errors lie the whole backlash j / r'_1
  // apart, symmetrically; a 4.5 um proud coast flank holds the gear back by e / r_b1.
  const TcaPair s = make_tca_pair(c_pair(10 * deg));
  TcaOptions    o;
  o.positions_per_mesh = 12;
  o.side               = FlankSide::coast;
  for (const TcaPosition &p : UnloadedTca(s.pinion, s.gear, s.a_w, {}, o).run().positions)
    EXPECT_LT(std::abs(p.transmission_error), 1e-9) << p.pinion_angle;

  const double a  = s.a_w + 0.1e-3;
  const double ca = (s.pinion->base_radius + s.gear->base_radius) / a;
  const double r1 = s.pinion->base_radius / ca, r2 = s.gear->base_radius / ca;
  const double j = 2 * pi * r1 / 16 - s.pinion->tooth_thickness(r1) - s.gear->tooth_thickness(r2);
  const TcaResult coast = UnloadedTca(s.pinion, s.gear, a, {}, o).run();
  o.side                = FlankSide::drive;
  const TcaResult drive = UnloadedTca(s.pinion, s.gear, a, {}, o).run();
  EXPECT_LT(peak_to_peak(coast), 1e-9);
  EXPECT_NEAR(drive.positions[0].transmission_error - coast.positions[0].transmission_error, j / r1,
              1e-9);
  EXPECT_NEAR(coast.positions[0].transmission_error, -j / (2 * r1), 1e-9);

  auto d                  = c_pair();
  d.first.eccentric_teeth = {{0, FlankSide::coast, 4.5e-6}};
  const TcaPair e         = make_tca_pair(d);
  TcaOptions    oc;
  oc.side = FlankSide::coast;
  UnloadedTca tca(e.pinion, e.gear, e.a_w, {}, oc);
  EXPECT_NEAR(tca.at(0).transmission_error, 4.5e-6 / e.pinion->base_radius, 1e-9);
  EXPECT_NEAR(tca.at(-3 * 2 * pi / 16).transmission_error, 0, 1e-9);
  // the drive side does not see it
  EXPECT_NEAR(UnloadedTca(e.pinion, e.gear, e.a_w).at(0).transmission_error, 0, 1e-9);
}

TEST(UnloadedTca, RelativeCurvaturesOfACrownedSpurPair)
{
  // Spur pair, pinion with 5 um lead crowning: at the contact in the face middle the relative
  // curvature is 1/rho_1 + 1/rho_2 across (involute radii of curvature = roll lengths) and
  // 8 C_beta / b^2 along the face; the contact ellipse at approach delta has the semi-axes
  // sqrt(2 delta / k).
  auto d                                    = c_pair();
  d.first.drive_modifications.lead_crowning = 5e-6;
  const TcaPair s                           = make_tca_pair(d);
  UnloadedTca   tca(s.pinion, s.gear, s.a_w);
  for (double phi : {0.0, 0.05, -0.1})
    {
      const TcaPosition  p = tca.at(phi);
      const PairContact &c = p.pairs[p.leading];
      ASSERT_NEAR(c.v1, 0, 1e-9);
      const double rho1 =
          std::sqrt(c.position.head<2>().squaredNorm() - std::pow(s.pinion->base_radius, 2));
      const double rho2 = std::sqrt((c.position - Vec3(s.a_w, 0, 0)).head<2>().squaredNorm() -
                                    std::pow(s.gear->base_radius, 2));
      const double lead = 8 * 5e-6 / std::pow(14e-3, 2);
      EXPECT_NEAR(c.curvature_min, lead, 1e-6 * lead) << phi;
      EXPECT_NEAR(c.curvature_max, 1 / rho1 + 1 / rho2, 1e-7 * (1 / rho1 + 1 / rho2)) << phi;
      EXPECT_NEAR(std::abs(c.major_direction.z()), 1, 1e-9);
      const auto [a, b] = contact_ellipse(c, 6.32e-6);
      EXPECT_NEAR(a, std::sqrt(2 * 6.32e-6 / lead), 1e-9);
      EXPECT_NEAR(b, std::sqrt(2 * 6.32e-6 / (1 / rho1 + 1 / rho2)), 1e-9);
    }
}

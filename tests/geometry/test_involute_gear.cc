// Involute gear geometry against exact values (ISO 21771 formulas, generation kinematics, and
// independent integrations). Tolerances: 1e-12 relative where both sides are closed-form double
// arithmetic of a few dozen operations; looser ones are justified where they appear.
#include "base/units.h"
#include "geometry/involute_gear.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;
using units::deg;

namespace
{

InvoluteGearData
spur(int z = 20, double x = 0)
{
  InvoluteGearData d;
  d.name                  = "spur";
  d.teeth                 = z;
  d.normal_module         = 5e-3;
  d.normal_pressure_angle = 20 * deg;
  d.profile_shift         = x;
  d.face_width            = 30e-3;
  return d;
}

InvoluteGearData
helical(Hand hand = Hand::right)
{
  InvoluteGearData d;
  d.name                  = "helical";
  d.teeth                 = 30;
  d.normal_module         = 2e-3;
  d.normal_pressure_angle = 20 * deg;
  d.helix_angle           = 20 * deg;
  d.hand                  = hand;
  d.profile_shift         = 0.25;
  d.face_width            = 25e-3;
  return d;
}

double
polar_angle(const Vec2 &p)
{
  return std::atan2(p.y(), p.x());
}
} // namespace

TEST(InvoluteGear, DiametersOfTextbookSpurGear)
{
  // z 20, m 5, alpha 20 deg, x 0.2: d = 100, d_b = 100 cos 20 deg = 93.96926208 mm,
  // d_a = d + 2 (1 + x) m = 112 mm, d_f = d - 2 (1.25 - x) m = 89.5 mm.
  const auto g = InvoluteGear::create(spur(20, 0.2));
  EXPECT_NEAR(2 * g->reference_radius, 100e-3, 1e-15);
  EXPECT_NEAR(2 * g->base_radius, 93.96926207859083e-3, 1e-15);
  EXPECT_NEAR(2 * g->tip_radius, 112e-3, 1e-15);
  EXPECT_NEAR(2 * g->root_radius, 89.5e-3, 1e-15);
  // s = m (pi/2 + 2 x tan alpha) = 8.58182 mm
  EXPECT_NEAR(g->tooth_thickness_reference, 5e-3 * (pi / 2 + 0.4 * std::tan(20 * deg)), 1e-15);
}

TEST(InvoluteGear, HelicalTransverseQuantities)
{
  // m_n 2, z 30, beta 20 deg: d = 60 / cos 20 deg = 63.85066634 mm,
  // alpha_t = atan(tan 20 / cos 20) = 21.17283219 deg, tan beta_b = tan beta cos alpha_t.
  const auto g = InvoluteGear::create(helical());
  EXPECT_NEAR(2 * g->reference_radius, 63.85066634855473e-3, 1e-14);
  EXPECT_NEAR(g->transverse_pressure_angle / deg, 21.17283218516298, 1e-11);
  EXPECT_NEAR(std::tan(g->base_helix_angle),
              std::tan(20 * deg) * std::cos(g->transverse_pressure_angle), 1e-15);
  EXPECT_NEAR(g->lead, 2 * pi * g->reference_radius / std::tan(20 * deg), 1e-15);
}

TEST(InvoluteGear, ToothThicknessOfRackGeneratedProfileMatchesIso21771)
{
  // The straight rack flank, rolled through the generation kinematics, must produce a profile
  // whose arc thickness at every radius is s_yt = d_y (s_t/d + inv alpha_t - inv alpha_yt).
  for (const auto &data : {spur(20, 0.2), spur(31, -0.3), helical()})
    {
      const auto g        = InvoluteGear::create(data);
      const auto [h0, h1] = g->rack_flank_height_range();
      for (int i = 0; i <= 20; ++i)
        {
          const Vec2   p = g->rack_generated_flank_point(h0 + (h1 - h0) * i / 20.0);
          const double r = p.norm();
          EXPECT_NEAR(2 * r * polar_angle(p), g->tooth_thickness(r), 1e-12 * r) << data.name;
        }
      // and the ends of that range are the tip and form circles
      EXPECT_NEAR(g->rack_generated_flank_point(h0).norm(), g->tip_radius, 1e-12 * g->tip_radius);
      EXPECT_NEAR(g->rack_generated_flank_point(h1).norm(), g->form_radius, 1e-12 * g->tip_radius);
    }
}

TEST(InvoluteGear, FlankEqualsRackGeneratedInvolute)
{
  const auto g        = InvoluteGear::create(helical());
  const auto f        = g->flank(0, FlankSide::drive);
  const auto [h0, h1] = g->rack_flank_height_range();
  for (int i = 0; i <= 10; ++i)
    {
      Vec2         n_rack;
      const Vec2   p  = g->rack_generated_flank_point(h0 + (h1 - h0) * i / 10.0, &n_rack);
      const double xi = g->roll_angle(p.norm());
      const auto   q  = f.evaluate(xi, 0);
      EXPECT_NEAR((q.position.head<2>() - p).norm(), 0, 1e-12 * g->tip_radius);
      // the transverse part of the 3D normal has the direction of the generated normal
      EXPECT_NEAR((q.normal.head<2>().normalized() - n_rack).norm(), 0, 1e-12);
    }
}

TEST(InvoluteGear, NormalsOrthogonalToTangentsWithAllModifications)
{
  InvoluteGearData    d = helical(Hand::left);
  ToothModifications &m = d.drive_modifications;
  m.tip_relief = 20e-6, m.tip_relief_length = 1.5e-3, m.tip_relief_shape = ReliefShape::parabolic;
  m.root_relief = 10e-6, m.root_relief_length = 1e-3;
  m.lead_crowning = 8e-6, m.end_relief = 5e-6, m.end_relief_length = 3e-3;
  m.profile_crowning = 3e-6, m.profile_slope = 4e-6, m.helix_slope = -6e-6;
  m.waviness_amplitude = 1e-6, m.waviness_wavelength = 0.4e-3;
  d.coast_modifications = m;
  d.eccentric_teeth     = {{3, FlankSide::coast, 4.5e-6}};
  const auto g          = InvoluteGear::create(d);
  for (int tooth : {0, 3})
    for (FlankSide side : {FlankSide::drive, FlankSide::coast})
      {
        const auto        f   = g->flank(tooth, side);
        const FlankDomain dom = f.domain();
        for (int i = 0; i <= 12; ++i)
          for (int j = 0; j <= 12; ++j)
            {
              const double u = dom.u_min + (dom.u_max - dom.u_min) * i / 12;
              const double v = dom.v_min + (dom.v_max - dom.v_min) * j / 12;
              const auto   p = f.evaluate(u, v);
              EXPECT_NEAR(p.normal.norm(), 1, 1e-14);
              EXPECT_LT(std::abs(p.normal.dot(p.d_du.normalized())), 1e-12);
              EXPECT_LT(std::abs(p.normal.dot(p.d_dv.normalized())), 1e-12);
              // outward: drive flanks face +theta, coast flanks -theta
              const Vec3 e_theta(-p.position.y(), p.position.x(), 0);
              EXPECT_GT((side == FlankSide::drive ? 1 : -1) * p.normal.dot(e_theta), 0);
            }
      }
}

TEST(InvoluteGear, DerivativesMatchFiniteDifferencesOfModifiedSurface)
{
  // d_du and d_dv of the modified surface are analytic; central differences (h = 1e-6 of the
  // range, error ~ h^2 |r'''| ~ 1e-12 relative) must agree.
  InvoluteGearData d                        = helical();
  d.drive_modifications.lead_crowning       = 10e-6;
  d.drive_modifications.waviness_amplitude  = 2e-6;
  d.drive_modifications.waviness_wavelength = 0.5e-3;
  d.drive_modifications.profile_slope       = 5e-6;
  const auto        g                       = InvoluteGear::create(d);
  const auto        f                       = g->flank(2, FlankSide::drive);
  const FlankDomain dom                     = f.domain();
  const double      u = 0.6 * dom.u_min + 0.4 * dom.u_max, v = 0.3 * dom.v_max;
  const double      hu = 1e-6 * (dom.u_max - dom.u_min), hv = 1e-6 * (dom.v_max - dom.v_min);
  const auto        p = f.evaluate(u, v);
  const Vec3 fd_u = (f.evaluate(u + hu, v).position - f.evaluate(u - hu, v).position) / (2 * hu);
  const Vec3 fd_v = (f.evaluate(u, v + hv).position - f.evaluate(u, v - hv).position) / (2 * hv);
  EXPECT_LT((fd_u - p.d_du).norm(), 1e-7 * p.d_du.norm());
  EXPECT_LT((fd_v - p.d_dv).norm(), 1e-7 * p.d_dv.norm());
}

TEST(InvoluteGear, NormalIsTangentToBaseCylinder)
{
  // Involute helicoid: every normal line touches the base cylinder (lies in a plane of action),
  // so its distance to the axis is r_b.
  for (Hand hand : {Hand::right, Hand::left})
    {
      const auto g = InvoluteGear::create(helical(hand));
      for (FlankSide side : {FlankSide::drive, FlankSide::coast})
        {
          const auto        f   = g->flank(7, side);
          const FlankDomain dom = f.domain();
          for (int i = 0; i <= 8; ++i)
            {
              const auto   p = f.evaluate(dom.u_min + (dom.u_max - dom.u_min) * i / 8, 0.01);
              const Vec3  &P = p.position, &n = p.normal;
              const double dist = std::abs(P.x() * n.y() - P.y() * n.x()) / n.head<2>().norm();
              EXPECT_NEAR(dist, g->base_radius, 1e-12 * g->base_radius);
            }
        }
    }
}

TEST(InvoluteGear, HelixLeadAndHand)
{
  // Along the face at fixed radius the flank turns by 2 pi dz / p_z, counter-clockwise for a
  // right hand, clockwise for a left hand.
  for (Hand hand : {Hand::right, Hand::left})
    {
      const auto   g  = InvoluteGear::create(helical(hand));
      const auto   f  = g->flank(0, FlankSide::drive);
      const double xi = g->roll_angle(g->reference_radius);
      const double z0 = -0.01, z1 = 0.012;
      const auto   p0 = f.evaluate(xi, z0), p1 = f.evaluate(xi, z1);
      const double turn = std::atan2(p1.position.y(), p1.position.x()) -
                          std::atan2(p0.position.y(), p0.position.x());
      EXPECT_NEAR(turn, (hand == Hand::right ? 1 : -1) * 2 * pi * (z1 - z0) / g->lead, 1e-13);
    }
}

TEST(InvoluteGear, FilletJoinsInvoluteWithContinuousTangent)
{
  for (const auto &data : {spur(20, 0.2), spur(40, 0), helical()})
    {
      const auto g = InvoluteGear::create(data);
      Vec2       n_fillet;
      const Vec2 q = g->fillet_point(1.0, &n_fillet);
      const auto f = g->flank(0, FlankSide::drive).evaluate(g->roll_angle_form, 0);
      EXPECT_NEAR((q - f.position.head<2>()).norm(), 0, 1e-12 * g->tip_radius) << data.name;
      EXPECT_NEAR((n_fillet - f.normal.head<2>().normalized()).norm(), 0, 1e-12) << data.name;
      // the fillet starts on the root circle with a radial-free (circumferential) normal... its
      // normal there points outward along the radius
      Vec2       n_root;
      const Vec2 r0 = g->fillet_point(0.0, &n_root);
      EXPECT_NEAR(r0.norm(), g->root_radius, 1e-12 * g->root_radius);
      EXPECT_NEAR(n_root.dot(r0.normalized()), 1, 1e-12);
      // and it climbs monotonically from the root to the form circle
      double r_prev = 0;
      for (int i = 0; i <= 50; ++i)
        {
          const double r = g->fillet_point(i / 50.0).norm();
          EXPECT_GE(r, r_prev - 1e-15);
          r_prev = r;
        }
    }
}

TEST(InvoluteGear, UndercutLimit)
{
  // Rack with h_fP* - rho*(1 - sin alpha) = 1.25 - 0.38 (1 - sin 20 deg) = 0.99997: the limit
  // tooth count without shift is 2 * 0.99997 / sin^2(20 deg) = 17.1.
  EXPECT_TRUE(InvoluteGear::create(spur(17, 0))->checks().undercut);
  EXPECT_FALSE(InvoluteGear::create(spur(18, 0))->checks().undercut);
  EXPECT_FALSE(InvoluteGear::create(spur(12, 0.35))->checks().undercut);
  EXPECT_TRUE(InvoluteGear::create(spur(12, 0.25))->checks().undercut);
}

TEST(InvoluteGear, UndercutFilletMeetsInvoluteAboveBaseCircle)
{
  // z 10 without shift is deeply undercut: the trochoid of the cutter tip rounding crosses the
  // involute above the base circle; there the profile has a corner (position continuous, normal
  // not), and below it the fillet lies inside the involute's extension.
  const auto g = InvoluteGear::create(spur(10, 0));
  ASSERT_TRUE(g->checks().undercut);
  EXPECT_GT(g->form_radius, g->base_radius * (1 + 1e-6));
  const Vec2 q = g->fillet_point(1.0);
  const auto f = g->flank(0, FlankSide::drive).evaluate(g->roll_angle_form, 0);
  EXPECT_NEAR((q - f.position.head<2>()).norm(), 0, 1e-9 * g->tip_radius);
  const Vec2   below = g->fillet_point(0.95);
  const double r     = below.norm();
  if (r > g->base_radius)
    {
      EXPECT_LT(polar_angle(below), g->tooth_thickness(r) / (2 * r));
    }
}

TEST(InvoluteGear, PointedToothIsRejected)
{
  InvoluteGearData d = spur(10, 1.2);
  try
    {
      InvoluteGear::create(d);
      FAIL() << "a pointed tooth must be rejected";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("pointed"), std::string::npos) << e.what();
    }
  // a nearly pointed tooth is accepted with a warning
  const auto g = InvoluteGear::create(spur(12, 0.7));
  EXPECT_LT(g->checks().tip_thickness_normal, 0.2 * 5e-3);
  EXPECT_FALSE(g->checks().warnings.empty());
}

TEST(InvoluteGear, InvalidDataNamesTheParameter)
{
  auto expect_error = [](InvoluteGearData d, const std::string &what) {
    try
      {
        InvoluteGear::create(d);
        ADD_FAILURE() << "accepted bad " << what;
      }
    catch (const InputError &e)
      {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      }
  };
  InvoluteGearData d = spur();
  d.teeth            = 2;
  expect_error(d, "number of teeth");
  d               = spur();
  d.normal_module = -1;
  expect_error(d, "normal module");
  d            = spur();
  d.face_width = 0;
  expect_error(d, "face width");
  d               = spur();
  d.bore_diameter = 0.2;
  expect_error(d, "bore diameter");
  d                         = spur();
  d.single_pitch_deviations = std::vector<double>(20, 1e-6);
  expect_error(d, "sum of single pitch deviations");
  d               = spur();
  d.chipped_teeth = {{25, 0.05, 1}};
  expect_error(d, "chipped tooth index");
  d                                       = spur();
  d.drive_modifications.tip_relief        = 1e-5;
  d.drive_modifications.tip_relief_length = 1.0;
  expect_error(d, "tip relief length");
}

TEST(InvoluteGear, TipReliefAmountsAlongNormal)
{
  // Linear tip relief Ca over La: zero at L_tip - La, -Ca at the tip, measured along the normal.
  InvoluteGearData d                      = spur(25);
  d.drive_modifications.tip_relief        = 15e-6;
  d.drive_modifications.tip_relief_length = 2e-3;
  const auto   g                          = InvoluteGear::create(d);
  const auto   f                          = g->flank(4, FlankSide::drive);
  const double rb                         = g->base_radius;
  auto         dev                        = [&](double xi) {
    const auto p = f.evaluate(xi, 0), q = f.nominal(xi, 0);
    return (p.position - q.position).dot(q.normal);
  };
  EXPECT_NEAR(dev(g->roll_angle_tip), -15e-6, 1e-15);
  EXPECT_NEAR(dev(g->roll_angle_tip - 1e-3 / rb), -7.5e-6, 1e-15);
  EXPECT_NEAR(dev(g->roll_angle_tip - 2e-3 / rb), 0, 1e-15);
  EXPECT_EQ(dev(g->roll_angle_form), 0);
  // the coast side is untouched
  const auto c = g->flank(4, FlankSide::coast);
  EXPECT_EQ(
      (c.evaluate(g->roll_angle_tip, 0).position - c.nominal(g->roll_angle_tip, 0).position).norm(),
      0);
}

TEST(InvoluteGear, EccentricToothMovesAlongNormal)
{
  InvoluteGearData d = helical();
  d.eccentric_teeth  = {{5, FlankSide::drive, 4.5e-6}};
  const auto g       = InvoluteGear::create(d);
  const auto moved = g->flank(5, FlankSide::drive), other = g->flank(6, FlankSide::drive);
  const auto p = moved.evaluate(0.4, 0.003), q = moved.nominal(0.4, 0.003);
  // positions are ~3e-2 m: one rounding of a coordinate is ~4e-18 m
  EXPECT_NEAR(((p.position - q.position) - 4.5e-6 * q.normal).norm(), 0, 2e-17);
  EXPECT_EQ((other.evaluate(0.4, 0.003).position - other.nominal(0.4, 0.003).position).norm(), 0);
}

TEST(InvoluteGear, PitchDeviationsAndRunoutAreRigidMotions)
{
  InvoluteGearData d           = spur(6 * 4);
  d.single_pitch_deviations    = std::vector<double>(24, 0);
  d.single_pitch_deviations[3] = 6e-6;  // tooth 3 and all after it advance by 6 um ...
  d.single_pitch_deviations[4] = -6e-6; // ... until tooth 4 takes it back
  d.runout                     = {20e-6, 30 * deg};
  const auto g                 = InvoluteGear::create(d);
  const auto ref               = InvoluteGear::create(spur(24));
  const Vec3 t(20e-6 * std::cos(30 * deg), 20e-6 * std::sin(30 * deg), 0);
  for (int k : {2, 3, 4})
    {
      const double xi   = 0.5;
      const Vec3   p    = g->flank(k, FlankSide::drive).evaluate(xi, 0).position - t;
      const Vec3   q    = ref->flank(k, FlankSide::drive).evaluate(xi, 0).position;
      const double turn = std::atan2(p.y(), p.x()) - std::atan2(q.y(), q.x());
      EXPECT_NEAR(turn, k == 3 ? 6e-6 / g->reference_radius : 0, 1e-15);
      EXPECT_NEAR(p.norm(), q.norm(), 1e-15);
    }
}

namespace
{
// Independent integration of a tooth's area and polar moment above the root circle:
// int 2 psi(r) r^n dr with psi the half angular thickness; psi from the fillet curve (sampled
// finely, trapezoid) below the form circle and from the ISO thickness formula (composite
// Simpson) above it.
std::pair<double, double>
tooth_area_and_polar(const InvoluteGear &g, double r_from)
{
  double area = 0, polar = 0;
  auto   add = [&](double r0, double psi0, double r1, double psi1) {
    area += (psi0 * r0 + psi1 * r1) * (r1 - r0);
    polar += (psi0 * r0 * r0 * r0 + psi1 * r1 * r1 * r1) * (r1 - r0);
  };
  const int n_fillet = 20000;
  for (int i = 0; i < n_fillet; ++i)
    {
      Vec2 a = g.fillet_point(double(i) / n_fillet), b = g.fillet_point(double(i + 1) / n_fillet);
      if (b.norm() <= r_from)
        continue;
      add(std::max(a.norm(), r_from), polar_angle(a), b.norm(), polar_angle(b));
    }
  const double r0 = std::max(g.form_radius, r_from), r1 = g.tip_radius;
  const int    n  = 2000;
  double       sa = 0, sp = 0;
  for (int i = 0; i <= n; ++i)
    {
      const double r = r0 + (r1 - r0) * i / n, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
      sa += w * g.tooth_thickness(r);
      sp += w * g.tooth_thickness(r) * r * r;
    }
  area += sa * (r1 - r0) / (3 * n);
  polar += sp * (r1 - r0) / (3 * n);
  return {area, polar};
}
} // namespace

TEST(MassProperties, CylinderBlankIsExact)
{
  // A disc polygon with N vertices: area error pi r^2 (1 - sin(2 pi/N) N / (2 pi)) ~ 2.6e-6 at
  // N = 2000; the prism formulas themselves are exact.
  const double      r = 0.05, b = 0.02, rho = 7850;
  std::vector<Vec2> circle;
  for (int i = 0; i < 2000; ++i)
    circle.emplace_back(r * std::cos(2 * pi * i / 2000), r * std::sin(2 * pi * i / 2000));
  const MassProperties p = prism_mass_properties(polygon_moments(circle), b, rho);
  const double         m = rho * pi * r * r * b;
  EXPECT_NEAR(p.mass / m, 1, 1e-5);
  EXPECT_NEAR(p.polar_inertia / (m * r * r / 2), 1, 1e-5);
  EXPECT_NEAR(p.diametral_inertia / (m * (3 * r * r + b * b) / 12), 1, 1e-5);
  // and exactly for the analytic disc
  const MassProperties q = prism_mass_properties(disc_moments(r), b, rho);
  EXPECT_DOUBLE_EQ(q.mass, m);
  EXPECT_DOUBLE_EQ(q.polar_inertia, m * r * r / 2);
}

TEST(MassProperties, GearBodyAgainstStripIntegration)
{
  // Polygon (Green's theorem) against radial strip integration; both converge as h^2, the
  // remaining difference is ~1e-6 relative at these resolutions.
  InvoluteGearData d            = helical();
  d.bore_diameter               = 20e-3;
  const auto g                  = InvoluteGear::create(d);
  const auto [A_tooth, J_tooth] = tooth_area_and_polar(*g, g->root_radius);
  const double         rf = g->root_radius, rbore = d.bore_diameter / 2;
  const double         area  = pi * (rf * rf - rbore * rbore) + d.teeth * A_tooth;
  const double         polar = pi / 2 * (std::pow(rf, 4) - std::pow(rbore, 4)) + d.teeth * J_tooth;
  const MassProperties p     = g->mass_properties();
  EXPECT_NEAR(p.mass / (d.density * d.face_width * area), 1, 2e-6);
  EXPECT_NEAR(p.polar_inertia / (d.density * d.face_width * polar), 1, 2e-6);
  // between the root and tip cylinders
  EXPECT_GT(p.mass, d.density * d.face_width * pi * (rf * rf - rbore * rbore));
  EXPECT_LT(p.mass, d.density * d.face_width * pi * (std::pow(g->tip_radius, 2) - rbore * rbore));
}

TEST(MassProperties, ChippedToothRemovesItsVolume)
{
  InvoluteGearData d          = spur(17);
  d.normal_module             = 4e-3;
  const auto   whole          = InvoluteGear::create(d);
  const double r_chip         = 0.5 * (whole->form_radius + whole->tip_radius);
  d.chipped_teeth             = {{0, r_chip, 0.5}};
  const auto chipped          = InvoluteGear::create(d);
  const auto [A, J]           = tooth_area_and_polar(*whole, r_chip);
  const double         length = 0.5 * d.face_width;
  const MassProperties a = whole->mass_properties(), b = chipped->mass_properties();
  EXPECT_NEAR((a.mass - b.mass) / (d.density * length * A), 1, 1e-5);
  EXPECT_NEAR((a.polar_inertia - b.polar_inertia) / (d.density * length * J), 1, 1e-5);
  // the chipped region is excluded from the flank, the rest is not
  const auto f = chipped->flank(0, FlankSide::drive);
  EXPECT_FALSE(f.contains(whole->roll_angle_tip, -0.01));
  EXPECT_TRUE(f.contains(whole->roll_angle_tip, +0.01));
  EXPECT_TRUE(f.contains(whole->roll_angle_form, -0.01));
  // a chip over the whole face leaves no material above its radius, face ends included
  d.chipped_teeth    = {{0, r_chip, 1.0}};
  const auto through = InvoluteGear::create(d)->flank(0, FlankSide::coast);
  EXPECT_FALSE(through.contains(whole->roll_angle_tip, d.face_width / 2));
  EXPECT_FALSE(through.contains(whole->roll_angle_tip, -d.face_width / 2));
  EXPECT_TRUE(through.contains(whole->roll_angle_form, d.face_width / 2));
}

TEST(InvoluteGear, NormalDerivativesOfSpurFlank)
{
  // Drive flank of a spur gear: n = e_theta(theta_b - xi), so dn/dxi = e_r(theta_b - xi) (unit
  // length, the involute's curvature times its arc-length rate) and dn/dz = 0. Central
  // differences with h = 1e-5 of the range: error ~ h^2 ~ 1e-10.
  const auto        g = InvoluteGear::create(spur(27, 0.1));
  const auto        f = g->flank(0, FlankSide::drive);
  const FlankDomain d = f.domain();
  for (double t : {0.1, 0.5, 0.9})
    {
      const double u        = d.u_min + t * (d.u_max - d.u_min);
      const auto [n_u, n_v] = f.normal_derivatives(u, 0.003);
      const Vec3   q        = f.evaluate(u, 0.003).position;
      const double a = std::atan2(q.y(), q.x()) - std::atan(g->roll_angle(q.head<2>().norm()));
      EXPECT_NEAR((n_u - Vec3(std::cos(a), std::sin(a), 0)).norm(), 0, 1e-8);
      EXPECT_LT(n_v.norm(), 1e-8);
    }
}

namespace
{
// The deviation of a flank from its nominal surface at (xi, z): the modified point minus the
// nominal one along the nominal normal (the modifications are superposed along it).
double
deviation(const InvoluteFlank &f, double xi, double z)
{
  const FlankPoint n = f.nominal(xi, z);
  return (f.evaluate(xi, z).position - n.position).dot(n.normal);
}
} // namespace

TEST(InvoluteModifications, ProfileSlopeIsTheDifferenceOverTheIsoEvaluationRange)
{
  // ISO 1328-1: f_Halpha is the difference of the mean profile line between the ends of the
  // profile evaluation range L_alpha, from the start of active profile A (where the mate's tip
  // circle crosses the line of action) over 92 % of the active length A..E toward the tip E.
  // FZG C pair at its zero-backlash centre distance, both members with f_Halpha = -6 um; the
  // ends computed here from the radii: L_A = a sin(alpha_wt) - sqrt(r_a,mate^2 - r_b,mate^2),
  // L_E = sqrt(r_a^2 - r_b^2). The deviation is the difference of points ~0.05 m from the axis
  // (rounding ~1e-17 m): 1e-12 m is a wide margin, and 6e-6 (1 - 0.92 L_AE / L_FE) > 1e-7 m
  // separates the former range (form circle to tip).
  auto [dp, dg]                        = test_data::fzg_c_pair();
  dp.drive_modifications.profile_slope = -6e-6;
  dp.coast_modifications.profile_slope = -6e-6;
  dg.drive_modifications.profile_slope = -6e-6;
  const auto [p, g]                    = create_pair(dp, dg);
  const double a                       = working_centre_distance(*p, *g);
  const double sin_alpha = std::sqrt(1 - std::pow((p->base_radius + g->base_radius) / a, 2));
  auto         path      = [](const InvoluteGear &m) {
    return std::sqrt(m.tip_radius * m.tip_radius - m.base_radius * m.base_radius);
  };
  for (const auto &[member, mate] : {std::pair{p, g}, std::pair{g, p}})
    {
      const double rb     = member->base_radius;
      const double L_A    = a * sin_alpha - path(*mate);
      const double L_E    = path(*member);
      const double L_end  = L_A + 0.92 * (L_E - L_A);
      const double L_form = rb * member->roll_angle_form;
      ASSERT_GT(L_A, L_form + 1e-4); // the active profile starts well above the form circle
      EXPECT_GT(6e-6 * (1 - 0.92 * (L_E - L_A) / (L_E - L_form)), 1e-7);
      for (FlankSide side : {FlankSide::drive, FlankSide::coast})
        {
          const auto &mods = side == FlankSide::drive ? member->data().drive_modifications
                                                      : member->data().coast_modifications;
          if (mods.profile_slope == 0)
            continue;
          const InvoluteFlank f = member->flank(3, side);
          for (double z : {-5e-3, 0.0, 4e-3})
            {
              EXPECT_NEAR(deviation(f, L_end / rb, z) - deviation(f, L_A / rb, z), -6e-6, 1e-12)
                  << member->data().name << " " << to_string(side) << " z " << z;
              // the mean profile line goes on linearly to the tip: -6 um / 0.92 over A..E
              EXPECT_NEAR(deviation(f, L_E / rb, z) - deviation(f, L_A / rb, z), -6e-6 / 0.92,
                          1e-12);
            }
        }
    }
  // A gear on its own (no mate): the form circle stands in for the start of active profile.
  const auto   alone  = InvoluteGear::create(dp);
  const double rb     = alone->base_radius;
  const double L_form = rb * alone->roll_angle_form, L_E = path(*alone);
  const auto   f = alone->flank(0, FlankSide::drive);
  EXPECT_NEAR(deviation(f, (L_form + 0.92 * (L_E - L_form)) / rb, 0) - deviation(f, L_form / rb, 0),
              -6e-6, 1e-12);
}

TEST(InvoluteModifications, HelixSlopeIsTheDifferenceOverTheIsoEvaluationRange)
{
  // ISO 1328-1: f_Hbeta over the helix evaluation range L_beta, the face width less at each end
  // the smaller of 5 % of b and one module: b 25 mm, m_n 2 mm leaves 1.25 mm (5 %) at each end,
  // b 60 mm leaves 2 mm (the module). Tolerance as for the profile slope.
  for (const auto &[b, end] : {std::pair{25e-3, 1.25e-3}, std::pair{60e-3, 2e-3}})
    {
      InvoluteGearData d                  = helical();
      d.face_width                        = b;
      d.drive_modifications.helix_slope   = -6e-6;
      d.drive_modifications.lead_crowning = 4e-6; // symmetric: cancels in the difference
      const auto          g               = InvoluteGear::create(d);
      const InvoluteFlank f               = g->flank(5, FlankSide::drive);
      const double        z0 = -b / 2 + end, z1 = b / 2 - end;
      for (double xi : {0.3 * g->roll_angle_form + 0.7 * g->roll_angle_tip,
                        0.8 * g->roll_angle_form + 0.2 * g->roll_angle_tip})
        {
          EXPECT_NEAR(deviation(f, xi, z1) - deviation(f, xi, z0), -6e-6, 1e-12) << b;
          // linear beyond the range: -6 um b / L_beta over the whole face
          EXPECT_NEAR(deviation(f, xi, b / 2) - deviation(f, xi, -b / 2), -6e-6 * b / (z1 - z0),
                      1e-12)
              << b;
        }
    }
}

TEST(InvoluteModifications, OnlyTheProfileShapesReferToTheActiveProfile)
{
  // Only the slope deviations and the profile crowning refer to the active profile (its start
  // in mesh with the mate): every other modification is the same with and without the mate
  // (bit for bit), and each has its closed-form value (rounding of point differences ~1e-17 m;
  // 1e-13 m) at the places that define it.
  auto [dp, dg]         = test_data::fzg_c_pair();
  ToothModifications &m = dp.drive_modifications;
  m.tip_relief = 20e-6, m.tip_relief_length = 1.5e-3;
  m.root_relief = 10e-6, m.root_relief_length = 1e-3, m.root_relief_shape = ReliefShape::parabolic;
  const auto   alone = InvoluteGear::create(dp);
  const auto   mated = create_pair(dp, dg).first;
  const double rb = alone->base_radius, b = dp.face_width;
  const double L_F = rb * alone->roll_angle_form, L_E = rb * alone->roll_angle_tip;
  auto         dev = [&](const InvoluteGear &gear, double L, double z) {
    return deviation(gear.flank(2, FlankSide::drive), L / rb, z);
  };
  for (int i = 0; i <= 10; ++i)
    for (double z : {-b / 2, -b / 5, 0.0, b / 3, b / 2})
      {
        const double L = L_F + (L_E - L_F) * i / 10;
        EXPECT_EQ(dev(*alone, L, z), dev(*mated, L, z)) << i << " " << z;
      }
  for (const InvoluteGear *gear : {alone.get(), mated.get()})
    {
      EXPECT_NEAR(dev(*gear, L_E, 0), -20e-6, 1e-13);           // C_a at the tip
      EXPECT_NEAR(dev(*gear, L_E - 0.75e-3, 0), -10e-6, 1e-13); // linear: half way
      EXPECT_NEAR(dev(*gear, L_F, 0), -10e-6, 1e-13);           // C_f at the form circle
      EXPECT_NEAR(dev(*gear, L_F + 0.5e-3, 0), -2.5e-6, 1e-13); // parabolic: a quarter
      EXPECT_NEAR(dev(*gear, 0.5 * (L_F + L_E), 0), 0, 1e-13);  // untouched in between
    }

  // The face and profile shapes, on a gear of their own.
  dp.drive_modifications = {};
  ToothModifications &n  = dp.drive_modifications;
  n.lead_crowning = 8e-6, n.end_relief = 5e-6, n.end_relief_length = 3e-3;
  n.profile_crowning   = 3e-6;
  n.waviness_amplitude = 1e-6, n.waviness_wavelength = 0.4e-3, n.waviness_phase = 30 * deg;
  const auto alone2 = InvoluteGear::create(dp);
  const auto mated2 = create_pair(dp, dg).first;
  auto wave = [&](double L) { return 1e-6 * std::sin(2 * pi * (L - L_F) / 0.4e-3 + 30 * deg); };
  for (const InvoluteGear *gear : {alone2.get(), mated2.get()})
    {
      // C_alpha at both ends of the active profile: from the start of active profile in mesh
      // (the form circle on a gear alone) to the tip; its vertex in the middle
      const double L_S =
          gear == alone2.get() ? L_F : gear->modification_frame().roll_length_active_start;
      const double L_mid = 0.5 * (L_S + L_E);
      EXPECT_NEAR(dev(*gear, L_mid, 0), wave(L_mid), 1e-13);
      EXPECT_NEAR(dev(*gear, L_mid, b / 2), wave(L_mid) - 8e-6 - 5e-6, 1e-13); // C_beta + C_I
      EXPECT_NEAR(dev(*gear, L_mid, -b / 4), wave(L_mid) - 2e-6, 1e-13);       // C_beta / 4
      EXPECT_NEAR(dev(*gear, L_mid, b / 2 - 1.5e-3),
                  wave(L_mid) - 8e-6 * std::pow(1 - 3e-3 / b, 2) - 2.5e-6, 1e-13);
      EXPECT_NEAR(dev(*gear, L_S, 0), -3e-6 + wave(L_S), 1e-13);
      EXPECT_NEAR(dev(*gear, L_E, 0), -3e-6 + wave(L_E), 1e-13);
    }
  // the FZG C pinion's active profile starts above its form circle: the two crowns differ
  EXPECT_GT(mated2->modification_frame().roll_length_active_start, L_F + 1e-3);
}

// Backlash by the centre distance (seed 001, reference-data.md §2): j_t on the operating pitch
// circles from the tooth thicknesses there (ISO 21771 s_yt, an independent route: p' - s_1(r'_1)
// - s_2(r'_2)) against circumferential_backlash, and centre_distance_for_backlash as its
// inverse. Seed 001: P_d 10 /in, 20 deg, 23/31 teeth, B 0.004 in: a = 2.700 in + B / (2 tan 20
// deg) = 2.7055 in to first order, 2.70544 in exactly (the seed's 2.705 in). The
// profile-shifted FZG C pair checks the zero-backlash working pressure angle's part.
TEST(InvoluteGear, BacklashByTheCentreDistance)
{
  const double     inch = 25.4e-3;
  InvoluteGearData dp, dg;
  dp.teeth = 23, dg.teeth = 31;
  dp.normal_module = dg.normal_module = inch / 10;
  dp.face_width = dg.face_width = 0.5 * inch;
  const auto [p, g]             = create_pair(dp, dg);
  const auto [fp, fg] = create_pair(test_data::fzg_c_pair().first, test_data::fzg_c_pair().second);
  auto thickness_backlash = [](const InvoluteGear &a, const InvoluteGear &b, double c) {
    const double alpha = std::acos((a.base_radius + b.base_radius) / c);
    const double r1 = a.base_radius / std::cos(alpha), r2 = b.base_radius / std::cos(alpha);
    return 2 * pi * r1 / a.teeth() - a.tooth_thickness(r1) - b.tooth_thickness(r2);
  };
  for (const auto &[a, b] : {std::pair{p, g}, std::pair{fp, fg}})
    {
      const double a_w = working_centre_distance(*a, *b);
      EXPECT_NEAR(circumferential_backlash(*a, *b, a_w), 0, 1e-15);
      // roundings of the thicknesses' involute functions near 1e-16 m
      for (double da : {1e-6, 0.127e-3, 1e-3})
        EXPECT_NEAR(circumferential_backlash(*a, *b, a_w + da),
                    thickness_backlash(*a, *b, a_w + da), 1e-13)
            << da;
      for (double j : {0.0, 1e-6, 0.1016e-3, 0.5e-3})
        EXPECT_NEAR(circumferential_backlash(*a, *b, centre_distance_for_backlash(*a, *b, j)), j,
                    1e-15)
            << j;
      EXPECT_THROW(circumferential_backlash(*a, *b, a_w - 1e-6), InputError);
      EXPECT_THROW(centre_distance_for_backlash(*a, *b, -1e-6), InputError);
    }
  EXPECT_NEAR(working_centre_distance(*p, *g), 2.7 * inch, 1e-12);
  // Exactly, j_t = 2 da tan(alpha_w) + da^2 / (a sin(alpha_w) cos(alpha_w)) + O(da^3): the
  // first-order a (2.705495 in) is 5.2e-5 in too wide; with the second-order term the
  // remainder, ~(da / a) x that term, is below 1e-5 in.
  const double s = std::sin(20 * deg), c = std::cos(20 * deg), da1 = 0.004 / (2 * s / c);
  EXPECT_NEAR(centre_distance_for_backlash(*p, *g, 0.004 * inch) / inch,
              2.7 + da1 - da1 * da1 / (2.7 * s * c) / (2 * s / c), 1e-5);
  EXPECT_NEAR(centre_distance_for_backlash(*p, *g, 0.004 * inch) / inch, 2.70544, 1e-5);
  // the seed's 2.705 in (the exact 2.70544 in rounded): 0.00367 in of backlash (an independent
  // evaluation of 2 a (inv alpha' - inv 20 deg) gave 0.0036717650919)
  EXPECT_NEAR(circumferential_backlash(*p, *g, 2.705 * inch) / inch, 0.0036717650919, 1e-12);
}

TEST(InvoluteGear, APairMeshesOnlyWithTheSameModulePressureAndHelixAngleAndOppositeHands)
{
  // One rule for the scene and the unloaded TCA (external_pair_mismatch): empty where the pair
  // can mesh, else the first reason, naming the values where they differ.
  EXPECT_EQ(external_pair_mismatch(spur(20), spur(40)), "");
  EXPECT_EQ(external_pair_mismatch(helical(Hand::right), helical(Hand::left)), "");
  InvoluteGearData other = spur(40);
  other.normal_module    = 6e-3;
  EXPECT_EQ(external_pair_mismatch(spur(20), other),
            "must have the same normal module (5 and 6 mm)");
  other                       = spur(40);
  other.normal_pressure_angle = 25 * deg;
  EXPECT_EQ(external_pair_mismatch(spur(20), other), "must have the same normal pressure angle");
  EXPECT_EQ(external_pair_mismatch(helical(Hand::right), spur(40))
                .rfind("must have the same normal module", 0),
            0u);
  other             = helical(Hand::left);
  other.helix_angle = 15 * deg;
  EXPECT_EQ(external_pair_mismatch(helical(Hand::right), other),
            "must have the same helix angle (external parallel-axis pair)");
  EXPECT_EQ(external_pair_mismatch(helical(Hand::left), helical(Hand::left)),
            "must have opposite hands (external helical pair); both are left");
}

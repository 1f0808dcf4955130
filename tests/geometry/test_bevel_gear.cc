// Spiral bevel blanks, nominal machine settings (reference-data.md section 7) and face-milled
// flanks generated on the cradle: the equation of meshing, envelope tangency, formate flanks on
// the cutter cone, hand of spiral.
#include "base/units.h"
#include "geometry/bevel_gear.h"
#include "tests/seed_bevel_pair.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;
using units::deg;

namespace
{
}

TEST(BevelGear, NominalSettingsWorkedExample)
{
  // reference-data.md section 7: N 12/36, m_et 6 mm, F 25.4 mm, beta_m 35 deg, r_c 76.2 mm.
  BevelPairDesign         d; // the defaults are this example
  const BevelPairGeometry g = bevel_geometry(d);
  EXPECT_NEAR(g.pitch_angle_pinion / deg, 18.4349, 5e-5);
  EXPECT_NEAR(g.pitch_angle_gear / deg, 71.5651, 5e-5);
  EXPECT_NEAR(g.outer_cone_distance * 1e3, 113.842, 5e-4);
  EXPECT_NEAR(g.mean_cone_distance * 1e3, 101.142, 5e-4);
  const NominalSettings n = nominal_settings(d);
  EXPECT_NEAR(n.radial_setting * 1e3, 84.823, 5e-4);
  EXPECT_NEAR(n.cradle_angle / deg, 47.381, 5e-4);
  EXPECT_NEAR(n.ratio_of_roll_pinion, 3.16228, 5e-6);
  EXPECT_NEAR(n.ratio_of_roll_gear, 1.05409, 5e-6);
}

TEST(BevelGear, SeedPairPitchAngles)
{
  // reference-data.md section 1 (derived): 55/47 teeth at 90 deg.
  BevelPairDesign d;
  d.pinion_teeth = 55, d.gear_teeth = 47, d.module = 3e-3, d.face_width = 19e-3;
  const BevelPairGeometry g = bevel_geometry(d);
  EXPECT_NEAR(g.pitch_angle_pinion / deg, 49.4846, 5e-5);
  EXPECT_NEAR(g.pitch_angle_gear / deg, 40.5154, 5e-5);
  d.face_width = 200e-3;
  EXPECT_THROW(bevel_geometry(d), InputError);
}

TEST(BevelGear, VirtualCylindricalGearsOfA90DegreePair)
{
  // Sigma = 90 deg: cos(delta_1) = z2 / sqrt(z1^2 + z2^2), so z_v1 = z1 sqrt(z1^2 + z2^2) / z2
  // exactly (ISO 10300-1); r_v = z_v m_mn / (2 cos beta_m); eps_beta = b sin beta_m / (pi m_mn).
  BevelPairDesign               d; // 12/36, beta_m 35 deg
  const VirtualCylindricalGears v = virtual_cylindrical_gears(d);
  const double                  c = std::hypot(12.0, 36.0);
  EXPECT_NEAR(v.z1, 12 * c / 36, 1e-12);
  EXPECT_NEAR(v.z2, 36 * c / 12, 1e-12);
  const double m = bevel_geometry(d).mean_normal_module;
  EXPECT_NEAR(v.r1, v.z1 * m / (2 * std::cos(d.mean_spiral_angle)), 1e-15);
  EXPECT_NEAR(v.overlap_ratio, d.face_width * std::sin(d.mean_spiral_angle) / (pi * m), 1e-12);
  // addenda as cut: h_a1 + h_a2 = the working depth 2 m_mn; a contact ratio of a real pair
  EXPECT_NEAR(v.addendum1 + v.addendum2, 2 * m, 1e-15);
  EXPECT_GT(v.transverse_contact_ratio, 1.0);
  EXPECT_LT(v.transverse_contact_ratio, 2.0);
}

TEST(GeneratedFlank, PointsSolveTheEquationOfMeshingAndTouchTheBlade)
{
  const auto [pinion, gear] = conjugate_cuts(BevelPairDesign{});
  for (const BevelMemberCut &cut : {pinion, gear})
    for (bool outside : {true, false})
      {
        const GeneratedFlank f(cut.blank, outside ? cut.outside_blade : cut.inside_blade,
                               outside ? cut.outside_machine : cut.inside_machine);
        const FlankDomain    d = f.domain();
        for (int i = 0; i < 9; ++i)
          for (int j = 0; j < 29; ++j)
            {
              const double u = d.u_min + (d.u_max - d.u_min) * i / 8;
              const double v = d.v_min + (d.v_max - d.v_min) * j / 28;
              const auto   g = f.generation(u, v);
              EXPECT_LT(std::abs(g.meshing_residual), 1e-13);
              const FlankPoint p = f.evaluate(u, v);
              // the rotational projection of the point is the requested (A, h)
              const Vec2 target = cut.blank.axial_plane(cut.blank.mean_cone_distance + v, u);
              EXPECT_NEAR(p.position.z(), target.x(), 1e-13);
              EXPECT_NEAR(p.position.head<2>().norm(), target.y(), 1e-13);
              // envelope: the surface's own tangent plane is the blade's (its normal)
              EXPECT_NEAR(std::abs(p.d_du.cross(p.d_dv).normalized().dot(p.normal)), 1, 1e-12);
              EXPECT_NEAR(p.normal.norm(), 1, 1e-14);
            }
      }
}

TEST(GeneratedFlank, DerivativesMatchFiniteDifferences)
{
  const auto [pinion, gear] = conjugate_cuts(BevelPairDesign{});
  const GeneratedFlank f(pinion.blank, pinion.outside_blade, pinion.outside_machine);
  const double         h = 1e-6;
  for (auto [u, v] : {std::pair{0.0, 0.0}, {2e-3, -8e-3}, {-1.5e-3, 10e-3}}) // inside the domain
    {
      const FlankPoint p = f.evaluate(u, v);
      const Vec3 fdu = (f.evaluate(u + h, v).position - f.evaluate(u - h, v).position) / (2 * h);
      const Vec3 fdv = (f.evaluate(u, v + h).position - f.evaluate(u, v - h).position) / (2 * h);
      EXPECT_LT((p.d_du - fdu).norm(), 1e-8 * p.d_du.norm()) << u << " " << v;
      EXPECT_LT((p.d_dv - fdv).norm(), 1e-8 * p.d_dv.norm()) << u << " " << v;
    }
}

TEST(GeneratedFlank, FormateFlankIsTheCutterCone)
{
  // Without roll the flank is the blade's cone, placed on the blank: back in the machine frame
  // every point lies at the blade's radius from the cutter axis for its height.
  const auto [pinion, gear] = conjugate_cuts(BevelPairDesign{});
  MachineSettings m         = gear.outside_machine;
  m.generated               = false;
  const Blade          b    = gear.outside_blade;
  const GeneratedFlank f(gear.blank, b, m);
  const double         gm = m.root_angle;
  Eigen::Matrix3d      to_blank;
  to_blank.row(0) = Vec3(std::sin(gm), 0, -std::cos(gm));
  to_blank.row(1) = Vec3(0, 1, 0);
  to_blank.row(2) = Vec3(std::cos(gm), 0, std::sin(gm));
  const Vec3        centre(m.radial_setting * std::cos(m.cradle_angle),
                           m.radial_setting * std::sin(m.cradle_angle), 0);
  const FlankDomain d = f.domain();
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j)
      {
        const double u  = d.u_min + (d.u_max - d.u_min) * i / 4;
        const double v  = d.v_min + (d.v_max - d.v_min) * j / 4;
        const Vec3   x  = to_blank.transpose() * f.evaluate(u, v).position; // apex at origin
        const double r  = (x - centre).head<2>().norm();
        const double rc = b.pitch_radius - b.slope * x.z() * std::tan(b.angle);
        EXPECT_NEAR(r, rc, 1e-12) << u << " " << v;
        EXPECT_EQ(f.generation(u, v).psi_c, 0.0);
      }
}

TEST(BevelMemberFlanks, HandOfSpiralAndToothPlacement)
{
  // Right hand: looking at the face of the gear (along +z from the apex side) the teeth turn
  // clockwise from toe to heel, i.e. the polar angle about +z grows along the face.
  for (Hand hand : {Hand::right, Hand::left})
    {
      BevelPairDesign d;
      d.pinion_hand       = hand;
      const auto [pc, gc] = conjugate_cuts(d);
      const BevelMemberFlanks p(pc), g(gc);
      auto                    turn = [](const BevelMemberFlanks &m) {
        const GeneratedFlank &f = m.tooth_flank(FlankSide::drive);
        const Vec3 toe = f.evaluate(0, -0.01).position, heel = f.evaluate(0, 0.01).position;
        return std::atan2(heel.y(), heel.x()) - std::atan2(toe.y(), toe.x());
      };
      EXPECT_GT(hand == Hand::right ? turn(p) : -turn(p), 0.05);
      EXPECT_GT(hand == Hand::right ? -turn(g) : turn(g), 0.02); // the gear has the other hand
      // tooth 0 centred on +x at the mean point; drive faces +theta
      for (const BevelMemberFlanks *m : {&p, &g})
        {
          const Vec3 pd = m->tooth_flank(FlankSide::drive).evaluate(0, 0).position;
          const Vec3 pc = m->tooth_flank(FlankSide::coast).evaluate(0, 0).position;
          EXPECT_NEAR(std::atan2(pd.y(), pd.x()), -std::atan2(pc.y(), pc.x()), 1e-12);
          EXPECT_GT(std::atan2(pd.y(), pd.x()), 0);
          const FlankPoint n = m->flank(3, FlankSide::drive).evaluate(0, 0);
          EXPECT_GT(n.normal.dot(Vec3(-n.position.y(), n.position.x(), 0)), 0);
        }
      // tooth thicknesses at the mean point (arc on the pitch cone, normal section) add up to
      // the normal pitch: pinion 0.5 of it by default
      const double Rm    = pc.blank.mean_cone_distance * std::sin(pc.blank.pitch_angle);
      const Vec3   pd    = p.tooth_flank(FlankSide::drive).evaluate(0, 0).position;
      const double arc_p = 2 * std::atan2(pd.y(), pd.x()) * Rm;
      const double m_mn  = bevel_geometry(d).mean_normal_module;
      EXPECT_NEAR(arc_p * std::cos(d.mean_spiral_angle), 0.5 * pi * m_mn, 1e-3 * m_mn);
    }
}

TEST(GeneratedFlank, EdgeRadiusShortensTheWorkingFlank)
{
  // The rounded blade tip cuts the fillet: the working flank (the domain) ends higher up, where
  // the straight blade meets the rounding, s = (h_f - r_e (1 - sin a)) / cos a.
  BevelPairDesign d;
  d.pinion_teeth = 55, d.gear_teeth = 47, d.module = 3e-3, d.face_width = 19e-3;
  auto [pinion, gear] = conjugate_cuts(d);
  const GeneratedFlank sharp(gear.blank, gear.outside_blade, gear.outside_machine);
  gear.outside_blade.edge_radius = 0.6e-3;
  const GeneratedFlank round(gear.blank, gear.outside_blade, gear.outside_machine);
  EXPECT_GT(round.domain().u_min, sharp.domain().u_min + 0.1e-3);
  const Blade &b = gear.outside_blade;
  const double s_end =
      (gear.blank.dedendum - b.edge_radius * (1 - std::sin(b.angle))) / std::cos(b.angle);
  // at the domain's lower edge (2 % of the depth above the limit) the blade point is just short
  // of the rounding everywhere along the face
  for (double v : {-9e-3, 0.0, 9e-3})
    {
      const double s = round.generation(round.domain().u_min, v).s;
      EXPECT_LT(s, s_end) << v;
      EXPECT_GT(s, s_end - 0.15 * (gear.blank.addendum + gear.blank.dedendum)) << v;
    }
  gear.outside_blade.edge_radius = gear.blank.dedendum;
  EXPECT_THROW(GeneratedFlank(gear.blank, gear.outside_blade, gear.outside_machine), InputError);
}

TEST(GeneratedFlank, RootFilletFromTheEdgeRadius)
{
  // The blade below the working flank and its tip rounding generate the fillet: continuous with
  // the flank at its lower edge (t = 0), on the equation of meshing throughout, going down
  // monotonically and ending on the root cone (h = -h_f) with the root cone's normal (t = 1).
  BevelPairDesign d;
  d.pinion_teeth = 55, d.gear_teeth = 47, d.module = 3e-3, d.face_width = 19e-3;
  auto [pinion, gear] = conjugate_cuts(d);
  for (BevelMemberCut *cut : {&pinion, &gear})
    for (bool outside : {true, false})
      {
        Blade &b                 = outside ? cut->outside_blade : cut->inside_blade;
        b.edge_radius            = 0.6e-3;
        const MachineSettings &m = outside ? cut->outside_machine : cut->inside_machine;
        const GeneratedFlank   f(cut->blank, b, m);
        const BevelBlank      &k  = cut->blank;
        const double           sg = std::sin(k.pitch_angle), cg = std::cos(k.pitch_angle);
        for (double v : {-9e-3, 0.0, 9e-3})
          {
            const FlankPoint edge = f.evaluate(f.domain().u_min, v);
            const auto       f0   = f.fillet_point(0, v);
            EXPECT_LT((f0.position - edge.position).norm(), 1e-10);
            EXPECT_LT((f0.normal - edge.normal).norm(), 1e-8);
            double h_prev = HUGE_VAL;
            for (int i = 0; i <= 10; ++i)
              {
                const auto p = f.fillet_point(i / 10.0, v);
                EXPECT_LT(std::abs(p.meshing_residual), 1e-12) << i << " " << v;
                EXPECT_LT(p.height, h_prev + 1e-12) << i << " " << v;
                h_prev = p.height;
              }
            const auto f1 = f.fillet_point(1, v);
            EXPECT_NEAR(f1.height, -k.dedendum, 1e-9) << v;
            // root-cone normal in the axial plane: (-sin g, cos g) (out of the material)
            const Vec3 radial = Vec3(f1.position.x(), f1.position.y(), 0).normalized();
            const Vec3 n_root = -sg * Vec3::UnitZ() + cg * radial;
            EXPECT_NEAR(f1.normal.dot(n_root), 1, 1e-8) << v;
            // the cone distance is the one asked for
            const double A =
                f1.position.z() * cg + Vec2(f1.position.x(), f1.position.y()).norm() * sg;
            EXPECT_NEAR(A, k.mean_cone_distance + v, 1e-10);
          }
      }
  BevelMemberCut       sharp = conjugate_cuts(d).second;
  const GeneratedFlank f(sharp.blank, sharp.outside_blade, sharp.outside_machine);
  EXPECT_THROW(f.fillet_point(0.5, 0), InputError);
}

TEST(BevelMismatch, CutterRadiusChangeKeepsTheMeanPoint)
{
  // A pinion cutter radius change pivots each blade about the blade line that generates the
  // flank's mean point (A_m, middle of the working depth): there the changed flank must give
  // the conjugate point and normal. Newton puts both flanks' points on the axial-plane target
  // to 1e-15 A_m, so 1e-9 m (and 1e-9 in the unit normal) is rounding with a wide margin; a
  // pivot 1 mm along the face off the mean point (the former fault) misses it by 3e-7 to 1e-6 m
  // and tilts the normal by 4e-4 to 1.5e-3. Away from the mean point the flank must differ (the
  // mismatch is not a no-op): at the face ends the pinion loses material against the conjugate
  // flank.
  const BevelPairDesign seed          = test_data::seed_bevel_design();
  BevelPairDesign       long_addendum = seed; // unequal addenda: the mean point off the pitch cone
  long_addendum.pinion_addendum       = 1.2;
  for (const BevelPairDesign &d : {seed, long_addendum})
    for (double c2 : {0.0, -0.03}) // the modified roll, expanded about the mean point, keeps it too
      {
        PinionMismatch m;
        m.cutter_radius            = 2e-3;
        m.modified_roll_2c         = c2;
        const BevelMemberCut conj  = conjugate_cuts(d).first;
        const BevelMemberCut moved = mismatched_cuts(d, m).first;
        const double h_mid = 0.5 * (conj.blank.addendum - conjugate_cuts(d).second.blank.addendum);
        EXPECT_NEAR(h_mid, (d.pinion_addendum - 1) * bevel_geometry(d).mean_normal_module, 1e-15);
        for (bool outside : {true, false})
          {
            const GeneratedFlank f0(conj.blank, outside ? conj.outside_blade : conj.inside_blade,
                                    outside ? conj.outside_machine : conj.inside_machine);
            const GeneratedFlank f1(moved.blank, outside ? moved.outside_blade : moved.inside_blade,
                                    outside ? moved.outside_machine : moved.inside_machine);
            const FlankPoint     p0 = f0.evaluate(h_mid, 0), p1 = f1.evaluate(h_mid, 0);
            EXPECT_LT((p1.position - p0.position).norm(), 1e-9) << outside << " 2C " << c2;
            EXPECT_LT((p1.normal - p0.normal).norm(), 1e-9) << outside << " 2C " << c2;
            if (c2 == 0)
              for (double v : {-8e-3, 8e-3})
                {
                  const FlankPoint q0 = f0.evaluate(h_mid, v), q1 = f1.evaluate(h_mid, v);
                  EXPECT_LT((q1.position - q0.position).dot(q0.normal), -1e-6) << outside << v;
                }
          }
      }
}

TEST(BevelCutterReach, TheLeastCutterRadiusIsWhereTheGenerationFails)
{
  // A head cutter too small for the spiral angle and face width: its tooth trace turns back
  // before the heel (or toe), and the equation of meshing has no solution at the top of the
  // tooth there ("no solution at h = 2.24 mm, A - A_m = 9.5 mm" for the seed pair with a 25 mm
  // cutter and its 2 mm pinion mismatch: h_a1 at the heel). cutter_reach finds that corner from
  // the traces alone; the least radius it gives must be where generating both members starts
  // to succeed: 1e-5 below it the generation fails, 1e-5 above it succeeds, for spiral angles
  // from 0.5 to 50 deg, pinions of 10 to 55 teeth and mismatches of 0 to 4 mm.
  struct Case
  {
    int    z1, z2;
    double module, face_width, spiral_deg, change;
  };
  for (const Case c : {Case{55, 47, 3e-3, 19e-3, 35, 0}, Case{55, 47, 3e-3, 19e-3, 35, 2e-3},
                       Case{12, 36, 6e-3, 25.4e-3, 50, 0}, Case{12, 36, 6e-3, 25.4e-3, 35, 4e-3},
                       Case{10, 41, 5e-3, 30e-3, 0.5, 0}})
    {
      BevelPairDesign d   = test_data::seed_bevel_design();
      d.pinion_teeth      = c.z1;
      d.gear_teeth        = c.z2;
      d.module            = c.module;
      d.face_width        = c.face_width;
      d.mean_spiral_angle = c.spiral_deg * deg;
      PinionMismatch m;
      m.cutter_radius    = c.change;
      const double least = least_cutter_radius(d, m);
      const double Am    = bevel_geometry(d).mean_cone_distance;
      ASSERT_GT(least, 0.1 * Am) << c.z1 << " " << c.spiral_deg;
      ASSERT_LT(least, 0.6 * Am) << c.z1 << " " << c.spiral_deg;
      auto generates = [&](double r) {
        d.cutter_radius = r;
        try
          {
            const auto [pinion, gear] = mismatched_cuts(d, m);
            BevelMemberFlanks{pinion};
            BevelMemberFlanks{gear};
            return true;
          }
        catch (const InputError &e)
          {
            EXPECT_NE(std::string(e.what()).find("equation of meshing has no solution"),
                      std::string::npos)
                << e.what();
            return false;
          }
      };
      EXPECT_FALSE(generates(least * (1 - 1e-5))) << c.z1 << " " << c.spiral_deg << " " << least;
      EXPECT_TRUE(generates(least * (1 + 1e-5))) << c.z1 << " " << c.spiral_deg << " " << least;
      d.cutter_radius = least * (1 - 1e-5);
      EXPECT_FALSE(cutter_reach(d, m).generated());
      d.cutter_radius = least * (1 + 1e-5);
      EXPECT_TRUE(cutter_reach(d, m).generated());
    }
  // the seed pair's 25 mm cutter with its 2 mm mismatch: the pinion's convex flank (inside
  // blade, smallest at the top of the tooth) misses the heel
  BevelPairDesign d = test_data::seed_bevel_design();
  d.cutter_radius   = 25e-3;
  PinionMismatch m;
  m.cutter_radius     = 2e-3;
  const CutterReach r = cutter_reach(d, m);
  EXPECT_FALSE(r.generated());
  EXPECT_EQ(r.member, "pinion");
  EXPECT_EQ(r.flank, "convex");
  EXPECT_TRUE(r.heel);
  EXPECT_NEAR(r.cone_distance, bevel_geometry(d).outer_cone_distance, 1e-12);
  EXPECT_GT(r.sin_spiral, 1);
  EXPECT_LT(r.sin_spiral, 1.01);
  // the nominal pair reaches with margin (sin beta 0.76 at the heel for 76.2 mm)
  EXPECT_LT(cutter_reach(test_data::seed_bevel_design()).sin_spiral, 0.8);
}

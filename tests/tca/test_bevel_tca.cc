// Unloaded TCA of face-milled spiral bevel pairs (reference-data.md section 7): the crown-gear
// test (both members cut by complementary flanks of one plane generating gear: conjugate, line
// contact, zero transmission error) on the seed pair's blank (section 1).
#include "tca/bevel_synthesis.h"
#include "tca/paper_mode.h"

#include <Eigen/QR>
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

BevelPairFlanks
make(const BevelPairDesign &d, const Misalignment &m = {})
{
  return bevel_pair_flanks(d, {}, m);
}
} // namespace

TEST(BevelTca, CrownGearTestGivesZeroTransmissionError)
{
  const BevelPairFlanks s = make(seed_design());
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

TEST(BevelTca, CutterRadiusMismatchLocalisesTheContact)
{
  // A 2 mm larger pinion cutter radius (blades kept through the mean point): point contact,
  // one pair at a time over most of the cycle, inside the flanks, and (straight blades, no
  // modified roll) a constant transmission error.
  PinionMismatch m;
  m.cutter_radius = 2e-3;
  const auto f    = bevel_pair_flanks(seed_design(), m);
  TcaOptions o;
  o.positions_per_mesh = 24;
  for (FlankSide side : {FlankSide::drive, FlankSide::coast}) // concave and convex pinion flank
    {
      o.side             = side;
      const TcaResult r  = UnloadedTca(f.pinion, f.gear, f.assembly, o).run();
      double          lo = HUGE_VAL, hi = -HUGE_VAL;
      for (const TcaPosition &p : r.positions)
        {
          EXPECT_FALSE(p.pairs[p.leading].edge) << to_string(side) << p.pinion_angle;
          lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
        }
      EXPECT_LT(hi - lo, 1e-10) << to_string(side);
      EXPECT_LT(r.mean_pairs_in_contact, 1.5) << to_string(side);
    }
  o.side = FlankSide::drive;
  // the contact in the crown-gear test is a line: almost three pairs at once
  const BevelPairFlanks c = bevel_pair_flanks(seed_design());
  EXPECT_GT(UnloadedTca(c.pinion, c.gear, c.assembly, o).run().mean_pairs_in_contact, 2.5);
}

TEST(BevelTca, CutterRadiusMismatchCentresTheBearingOnTheMeanPoint)
{
  // With a cutter radius change alone the pinion flank keeps the conjugate mean point and
  // normal (the blades pivot about the line that generates it), so where that point lies on
  // the pitch element (the pitch cones' line of contact, Assembly::bevel: polar angle 0) it
  // touches the gear with zero TE, and the bearing's centre is there: (h, A - A_m) = (0, 0) on
  // the pinion, and the contact point is the mean point. The contact search ends at a flat
  // maximum of the touch angle, accepted to 1e-14 rad; near it the angle falls as
  // k_min d^2 / (2 |lambda_g . a_g|) over a distance d along the ellipse's major axis, so the
  // position is resolved to d = sqrt(2e-14 |lambda_g . a_g| / k_min) (~7e-8 m here). The former
  // pivot put the contact 1.08 mm toward the heel and 0.29 mm up the profile.
  PinionMismatch m;
  m.cutter_radius = 2e-3;
  const auto f    = bevel_pair_flanks(seed_design(), m);
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      const Vec3   mean = f.pinion->tooth_flank(side).evaluate(0, 0).position; // h_mid = 0
      const double phi  = -std::atan2(mean.y(), mean.x());
      TcaOptions   o;
      o.side                 = side;
      const TcaPosition  p   = UnloadedTca(f.pinion, f.gear, f.assembly, o).at(phi);
      const PairContact &c   = p.pairs[p.leading];
      const double       arm = std::abs(c.lambda_gear.dot(f.assembly.gear_axis()));
      const double       tol = std::sqrt(2e-14 * arm / c.curvature_min);
      ASSERT_EQ(c.pinion_tooth, 0) << to_string(side);
      EXPECT_FALSE(c.edge) << to_string(side);
      EXPECT_LT(tol, 1e-6) << to_string(side);
      EXPECT_NEAR(c.v1, 0, tol) << to_string(side);
      EXPECT_NEAR(c.u1, 0, tol) << to_string(side);
      EXPECT_LT((c.position - f.assembly.pinion_to_global(mean, phi)).norm(), tol)
          << to_string(side);
      // touching as the conjugate pair does there: no transmission error, to the touch-angle
      // Newton's 1e-13 m over the arm (z2/z1 1e-13 m / |lambda_g . a_g| ~ 1.3e-12 rad)
      EXPECT_NEAR(p.transmission_error, 0, 2 * 1e-13 / arm) << to_string(side);
    }
}

TEST(BevelTca, NearlyStraightCutterFindsTheMeanPointContactInBoundedWork)
{
  // A 5 m head cutter on the seed pair at m_et 6 mm (A_m 207.5 mm: r_c / A_m = 24, within what
  // a scene allows), its pinion blades 2 mm larger: the bearing is localised by a difference of
  // lengthwise curvatures of 1/4998 - 1/5002 per mm, about 1e-4 of the profile's, so the touch
  // angle's maximum lies on a ridge along the contact line. The pattern search crawled along it
  // (about 21000 flank samples per tooth pair and 3 s per position, an unloaded TCA of 150
  // positions for minutes; the 5000 mm cutter ran for more than 300 s); with the Newton
  // step on the ridge it takes a few thousand. The contact is the conjugate mean point where that
  // lies on the pitch element (as in CutterRadiusMismatchCentresTheBearingOnTheMeanPoint, to
  // the flat maximum's resolution), and the TE is constant over the cycle.
  BevelPairDesign d = seed_design();
  d.module          = 6e-3;
  d.cutter_radius   = 5;
  ASSERT_NEAR(d.cutter_radius / bevel_geometry(d).mean_cone_distance, 24.1, 0.1);
  PinionMismatch m;
  m.cutter_radius = 2e-3;
  const auto f    = bevel_pair_flanks(d, m);
  TcaOptions o;
  o.most_samples       = 6000; // the seed pair's own searches take up to 2000
  o.positions_per_mesh = 4;
  const UnloadedTca  tca(f.pinion, f.gear, f.assembly, o);
  const Vec3         mean = f.pinion->tooth_flank(FlankSide::drive).evaluate(0, 0).position;
  const double       phi  = -std::atan2(mean.y(), mean.x());
  const TcaPosition  p    = tca.at(phi);
  const PairContact &c    = p.pairs[p.leading];
  const double       arm  = std::abs(c.lambda_gear.dot(f.assembly.gear_axis()));
  const double       tol  = std::sqrt(2e-14 * arm / c.curvature_min);
  ASSERT_EQ(c.pinion_tooth, 0);
  EXPECT_FALSE(c.edge);
  EXPECT_LT(c.curvature_min, 1e-3 * c.curvature_max); // nearly line contact
  EXPECT_LT(tol, 1e-5);
  EXPECT_NEAR(c.u1, 0, tol);
  EXPECT_NEAR(c.v1, 0, tol);
  EXPECT_NEAR(p.transmission_error, 0, 2 * 1e-13 / arm);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &q : tca.run().positions)
    {
      EXPECT_FALSE(q.pairs[q.leading].edge) << q.pinion_angle;
      lo = std::min(lo, q.transmission_error), hi = std::max(hi, q.transmission_error);
    }
  EXPECT_LT(hi - lo, 1e-10);
  // the bound on the search's work: a clear refusal, not a search without end
  o.most_samples = 100;
  try
    {
      UnloadedTca(f.pinion, f.gear, f.assembly, o).at(phi);
      ADD_FAILURE() << "no error beyond the most samples";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("took more than 100 flank samples without converging"),
                std::string::npos)
          << e.what();
    }
}

TEST(BevelTca, ACutterJustLargeEnoughStillGivesTheConjugatePair)
{
  // A cutter 0.1 % above the least radius that reaches the whole face (cutter_reach): both
  // members are generated, and the crown-gear test holds (line contact, zero TE). Beyond the
  // flanks, near the heel's top corner, the generated surface ends (the trace turns back), and
  // the touch-angle Newton, whose steps leave the domain, met it as "the equation of meshing
  // has no solution" thrown through the whole TCA (the seed pair with a 25 mm cutter failed so
  // at its first position); such a start is no touch.
  BevelPairDesign d = seed_design();
  d.cutter_radius   = 1.001 * least_cutter_radius(d);
  ASSERT_NEAR(d.cutter_radius, 23.39e-3, 0.01e-3);
  const BevelPairFlanks f = make(d);
  TcaOptions            o;
  o.positions_per_mesh = 6;
  const TcaResult r    = UnloadedTca(f.pinion, f.gear, f.assembly, o).run();
  double          lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &p : r.positions)
    lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
  EXPECT_LT(hi - lo, 1e-11);
  EXPECT_GT(r.mean_pairs_in_contact, 2.5);
}

TEST(BevelTca, ModifiedRollGivesTheRequestedParabolicTransmissionError)
{
  // Local synthesis: the seed's classical TE amplitude 3.72e-5 rad (reference-data.md section 1)
  // from the modified roll 2C with the 2 mm cutter radius mismatch. The amplitude is met within
  // 2 % (the secant stops at 0.1 %), and each pair's TE is a parabola: a least-squares parabola
  // through the positions of one pair leaves < 2 % of the amplitude.
  PinionMismatch m;
  m.cutter_radius             = 2e-3;
  const double         target = 3.72e-5;
  const PinionMismatch s      = synthesise_modified_roll(seed_design(), m, target);
  EXPECT_NE(s.modified_roll_2c, 0);
  const auto f = bevel_pair_flanks(seed_design(), s);
  TcaOptions o;
  o.positions_per_mesh = 48;
  const TcaResult r    = UnloadedTca(f.pinion, f.gear, f.assembly, o).run();
  double          lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &p : r.positions)
    lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
  EXPECT_NEAR(hi - lo, target, 0.02 * target);
  // the positions where the pair leading at mid-cycle leads
  const TcaPosition &mid   = r.positions[r.positions.size() / 2];
  const int          tooth = mid.pairs[mid.leading].pinion_tooth;
  Eigen::MatrixXd    A(0, 3);
  Eigen::VectorXd    b(0);
  for (const TcaPosition &p : r.positions)
    if (p.pairs[p.leading].pinion_tooth == tooth)
      {
        A.conservativeResize(A.rows() + 1, 3);
        b.conservativeResize(b.rows() + 1);
        A.row(A.rows() - 1) << 1, p.pinion_angle, p.pinion_angle * p.pinion_angle;
        b[b.rows() - 1] = p.transmission_error;
      }
  ASSERT_GT(A.rows(), 20);
  const Eigen::VectorXd fit = A.colPivHouseholderQr().solve(b);
  EXPECT_LT((A * fit - b).cwiseAbs().maxCoeff(), 0.02 * target);
  EXPECT_GT(std::abs(fit[2]), 0); // curved
}

namespace
{
// The seed pair with the 2 mm cutter-radius mismatch and the modified roll synthesised for the
// seed's 3.72e-5 rad (computed once).
const PinionMismatch &
seed_mismatch()
{
  static const PinionMismatch m = [] {
    PinionMismatch start;
    start.cutter_radius = 2e-3;
    return synthesise_modified_roll(seed_design(), start, 3.72e-5);
  }();
  return m;
}
} // namespace

TEST(BevelDiscretePoint, SeedPairFrom261PointFlanksWithinOnePercent)
{
  // The seed's discrete-point model was 6 % off its classical TCA (reference-data.md section 1).
  // The fast mode on 9 x 29 = 261 points per flank (profile x face, a virtual CMM of every
  // tooth) reproduces the classical e_0 within 1 % of its peak-to-peak; paper mode on the same
  // points within its resolution E (over the smallest moment arm about the gear axis).
  const BevelPairFlanks f = bevel_pair_flanks(seed_design(), seed_mismatch());
  TcaOptions            o;
  o.positions_per_mesh    = 24;
  const TcaResult exact   = UnloadedTca(f.pinion, f.gear, f.assembly, o).run();
  auto            measure = [](const BevelMemberFlanks &m, const std::string &name) {
    return std::make_shared<MeasuredMemberFlanks>(
        virtual_cmm(name, m.teeth(),
                               [&](int k, FlankSide side) { return sample_flank(m.flank(k, side), 9, 29); }));
  };
  const auto      mp       = measure(*f.pinion, "pinion");
  const auto      mg       = measure(*f.gear, "gear");
  const TcaResult discrete = UnloadedTca(mp, mg, f.assembly, o).run();
  double          lo = HUGE_VAL, hi = -HUGE_VAL, worst = 0, arm = HUGE_VAL;
  for (std::size_t i = 0; i < exact.positions.size(); ++i)
    {
      const TcaPosition &x = exact.positions[i];
      lo                   = std::min(lo, x.transmission_error);
      hi                   = std::max(hi, x.transmission_error);
      worst                = std::max(worst,
                                      std::abs(discrete.positions[i].transmission_error - x.transmission_error));
      arm = std::min(arm, std::abs(x.pairs[x.leading].lambda_gear.dot(f.assembly.gear_axis())));
    }
  EXPECT_NEAR(hi - lo, 3.72e-5, 0.02 * 3.72e-5);
  EXPECT_LT(worst, 0.01 * (hi - lo)) << worst;

  PaperModeOptions po;
  po.spacing                    = 200e-6;
  po.positions_per_mesh         = 4;
  const PaperModeResult r       = paper_mode_ste(*mp, *mg, f.assembly, po);
  const double          z_ratio = 47.0 / 55;
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(r.tca.positions[i].transmission_error, exact.positions[6 * i].transmission_error,
                2 * r.tolerance / arm / z_ratio)
        << i;
}

namespace
{
struct Bearing
{
  double peak_to_peak = 0, mean_error = 0, mean_face = 0; // [rad], [rad], mean v of the contact [m]
  int    edges = 0;
};

Bearing
bearing(const BevelPairDesign &d, const PinionMismatch &m, const Misalignment &mis)
{
  const BevelPairFlanks f = bevel_pair_flanks(d, m, mis);
  TcaOptions            o;
  o.positions_per_mesh = 12;
  const TcaResult r    = UnloadedTca(f.pinion, f.gear, f.assembly, o).run();
  Bearing         b;
  double          lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &p : r.positions)
    {
      lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
      b.mean_error += p.transmission_error / r.positions.size();
      b.mean_face += p.pairs[p.leading].v1 / r.positions.size();
      b.edges += p.pairs[p.leading].edge;
    }
  b.peak_to_peak = hi - lo;
  return b;
}
} // namespace

TEST(BevelTca, MisalignmentsShiftTheBearingAndThePredesignedParabolaAbsorbsThem)
{
  // Litvin's argument for the parabolic TE: misalignments add a linear function and a shift,
  // which the parabola absorbs (the peak-to-peak stays near the design instead of jumping), while
  // the bearing moves along the face (toward toe or heel, opposite ways for opposite signs) and
  // the backlash changes (mean e_0).
  const Bearing aligned = bearing(seed_design(), seed_mismatch(), {});
  EXPECT_EQ(aligned.edges, 0);
  std::vector<std::pair<const char *, Misalignment>> cases(4);
  cases[0].first = "offset dE", cases[0].second.offset = 50e-6;
  cases[1].first = "pinion axial dA1", cases[1].second.pinion_axial_shift = 50e-6;
  cases[2].first = "gear axial dA2", cases[2].second.gear_axial_shift = 50e-6;
  cases[3].first = "shaft angle dgamma", cases[3].second.intersecting_angle = 0.3e-3;
  for (const auto &[name, plus] : cases)
    {
      Misalignment minus;
      minus.offset             = -plus.offset;
      minus.pinion_axial_shift = -plus.pinion_axial_shift;
      minus.gear_axial_shift   = -plus.gear_axial_shift;
      minus.intersecting_angle = -plus.intersecting_angle;
      const Bearing p          = bearing(seed_design(), seed_mismatch(), plus);
      const Bearing m          = bearing(seed_design(), seed_mismatch(), minus);
      for (const Bearing *b : {&p, &m})
        {
          EXPECT_GT(b->peak_to_peak, 0.8 * aligned.peak_to_peak) << name;
          EXPECT_LT(b->peak_to_peak, 1.3 * aligned.peak_to_peak) << name;
        }
      EXPECT_LT((p.mean_face - aligned.mean_face) * (m.mean_face - aligned.mean_face), 0) << name;
      EXPECT_GT(std::abs(p.mean_face - m.mean_face), 0.4e-3) << name;
      EXPECT_LT((p.mean_error - aligned.mean_error) * (m.mean_error - aligned.mean_error), 0)
          << name;
    }
}

TEST(BevelTca, StressSpiralAnglesToothCountsAndLargeMisalignments)
{
  // Conjugate flanks stay conjugate from straight-ish (0 deg, a zerol-like cut) to 45 deg spiral
  // and down to 6 pinion teeth (the undercut root region is left out of the working flank);
  // misalignments that push the contact off the flank give edge contact, reported, and ones that
  // part the flanks a clear error rather than a wrong table.
  for (double beta : {0.0, 45.0})
    {
      BevelPairDesign d   = seed_design();
      d.mean_spiral_angle = beta * pi / 180;
      EXPECT_LT(bearing(d, {}, {}).peak_to_peak, 1e-11) << beta;
    }
  for (int z1 : {6, 9})
    {
      BevelPairDesign d = seed_design();
      d.pinion_teeth = z1, d.gear_teeth = 3 * z1, d.module = 6e-3;
      d.face_width = 0.25 * bevel_geometry(d).outer_cone_distance;
      EXPECT_LT(bearing(d, {}, {}).peak_to_peak, 1e-10) << z1;
    }
  Misalignment far;
  far.offset      = 0.5e-3;
  const Bearing b = bearing(seed_design(), seed_mismatch(), far);
  EXPECT_EQ(b.edges, 12);
  Misalignment apart;
  apart.intersecting_angle = 0.05;
  EXPECT_THROW(bearing(seed_design(), seed_mismatch(), apart), InputError);
}

TEST(BevelTca, ContactEllipse)
{
  // Line contact in the crown-gear test (the relative curvature vanishes along the line); the
  // cutter-radius mismatch gives a finite ellipse at Litvin's usual approach of 6.32 um, its
  // major axis along the face, shorter than the face width.
  TcaOptions o;
  o.positions_per_mesh     = 3;
  const BevelPairFlanks cf = bevel_pair_flanks(seed_design());
  for (const TcaPosition &p : UnloadedTca(cf.pinion, cf.gear, cf.assembly, o).run().positions)
    {
      const PairContact &c = p.pairs[p.leading];
      EXPECT_LT(std::abs(c.curvature_min), 1e-6 * c.curvature_max);
    }
  const BevelPairFlanks mf = bevel_pair_flanks(seed_design(), seed_mismatch());
  for (const TcaPosition &p : UnloadedTca(mf.pinion, mf.gear, mf.assembly, o).run().positions)
    {
      const PairContact &c = p.pairs[p.leading];
      const auto [a, b]    = contact_ellipse(c, 6.32e-6);
      EXPECT_GT(a, 2e-3);
      EXPECT_LT(a, 19e-3 / 2);
      EXPECT_GT(a, 5 * b);
      // along the face: mostly along the pitch element direction of the pinion (r, z) plane
      const Vec3 radial = Vec3(c.position.x(), c.position.y(), 0).normalized();
      const Vec3 element =
          (radial * std::sin(bevel_geometry(seed_design()).pitch_angle_pinion) +
           Vec3::UnitZ() * std::cos(bevel_geometry(seed_design()).pitch_angle_pinion))
              .normalized();
      EXPECT_GT(std::abs(c.major_direction.dot(element)), 0.5);
    }
}

TEST(BevelTca, ParabolicBladeNarrowsTheBearing)
{
  // Profile crowning from parabolic pinion blades adds relative curvature across the profile:
  // the contact ellipse's minor axis shrinks; curvature only adds, so the major axis does not
  // grow (it shrinks too, the ellipse being inclined to the profile direction).
  PinionMismatch m = seed_mismatch();
  TcaOptions     o;
  o.positions_per_mesh = 2;
  auto axes            = [&](double curvature) {
    m.blade_curvature   = curvature;
    const auto        f = bevel_pair_flanks(seed_design(), m);
    const TcaPosition p = UnloadedTca(f.pinion, f.gear, f.assembly, o).at(0);
    return contact_ellipse(p.pairs[p.leading], 6.32e-6);
  };
  const auto [a0, b0] = axes(0);
  const auto [a1, b1] = axes(20);
  EXPECT_LT(b1, 0.9 * b0);
  EXPECT_LE(a1, a0 * (1 + 1e-9));
  EXPECT_GT(a1, 1e-3); // still a localised, elongated bearing
  EXPECT_GT(a1, 3 * b1);
}

TEST(BevelTca, FormateGearWithConjugatePinion)
{
  // The gear formate cut (no roll: its flanks are the cutter cones), the pinion generated by
  // the gear itself on a tilted-cutter machine: conjugate, so line contact and zero TE.
  const auto [pc, gc] = formate_cuts(seed_design());
  EXPECT_FALSE(gc.outside_machine.generated);
  EXPECT_GT(pc.outside_machine.tilt, 0.5); // 90 deg - gamma_2 = 49.5 deg
  const auto     P = std::make_shared<BevelMemberFlanks>(pc);
  const auto     G = std::make_shared<BevelMemberFlanks>(gc);
  const Assembly a = Assembly::bevel(pi / 2, bevel_geometry(seed_design()).pitch_angle_pinion, 47);
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      TcaOptions o;
      o.positions_per_mesh = 8;
      o.side               = side;
      const TcaResult r    = UnloadedTca(P, G, a, o).run();
      for (const TcaPosition &p : r.positions)
        EXPECT_LT(std::abs(p.transmission_error), 1e-9) << to_string(side) << p.pinion_angle;
      EXPECT_GT(r.mean_pairs_in_contact, 2) << to_string(side);
    }
}

// Tooth pair contact curves (tca/tooth_pairs.h) against the exact relations of involute pairs:
// zero offset over the path of contact, the backlash from the involute functions, the eccentric
// tooth's e / r_b2, the chip that shortens the path, pitch deviations; and the convention of
// base/tooth_pairs.h against UnloadedTca itself (pairings, local angles, interpenetration).
#include "base/units.h"
#include "tca/tooth_pairs.h"
#include "tca/unloaded_tca.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gearkit;
using units::deg;

namespace
{

/// The 23/31 spur pair of the impact-model seed: m 2.54 mm, 20 deg, b 12.7 mm, no shift.
std::pair<InvoluteGearData, InvoluteGearData>
seed_pair(double helix = 0)
{
  InvoluteGearData p;
  p.name                  = "pinion";
  p.teeth                 = 23;
  p.normal_module         = 2.54e-3;
  p.normal_pressure_angle = 20 * deg;
  p.face_width            = 12.7e-3;
  p.helix_angle           = helix;
  p.hand                  = Hand::right;
  InvoluteGearData g      = p;
  g.name                  = "gear";
  g.teeth                 = 31;
  g.hand                  = Hand::left;
  return {p, g};
}

struct Members
{
  std::shared_ptr<const InvoluteGear>         pinion, gear;
  std::shared_ptr<const InvoluteMemberFlanks> pinion_flanks, gear_flanks;
  double                                      a_w = 0; ///< zero-backlash centre distance
};

Members
make(const std::pair<InvoluteGearData, InvoluteGearData> &d)
{
  Members m;
  std::tie(m.pinion, m.gear) = create_pair(d.first, d.second);
  m.pinion_flanks            = std::make_shared<InvoluteMemberFlanks>(m.pinion);
  m.gear_flanks              = std::make_shared<InvoluteMemberFlanks>(m.gear);
  m.a_w                      = working_centre_distance(*m.pinion, *m.gear);
  return m;
}

double
sign(int side)
{
  return side == drive_side ? 1.0 : -1.0;
}

/// Indices of the samples whose offset lies within tol of value; checks they are contiguous.
std::vector<int>
near(const ToothPairCurve &c, double value, double tol)
{
  std::vector<int> i;
  for (int j = 0; j < int(c.offset.size()); ++j)
    if (std::abs(c.offset[j] - value) < tol)
      i.push_back(j);
  EXPECT_FALSE(i.empty());
  if (!i.empty())
    {
      EXPECT_EQ(i.back() - i.front() + 1, int(i.size())) << "not one stretch";
    }
  return i;
}

/// The curve's own conjugate value: its most advanced offset.
double
lead(const ToothPairCurve &c, int side)
{
  double best = -HUGE_VAL;
  for (double o : c.offset)
    best = std::max(best, sign(side) * o);
  return sign(side) * best;
}

/// Both ends stand off from the most advanced touch by at least the recess (the pair leaves
/// mesh before a curve ends), the samples before them by a good part of it, and the offset
/// falls behind towards them.
void
expect_ends_recessed(const ToothPairCurve &c, int side, double recess)
{
  ASSERT_GE(c.offset.size(), 3u);
  const double s = sign(side), top = lead(c, side);
  EXPECT_GT(c.arm.front() * s * (top - c.offset.front()), recess);
  EXPECT_GT(c.arm.back() * s * (top - c.offset.back()), recess);
  EXPECT_LT(s * c.offset[0], s * c.offset[1]);
  EXPECT_LT(s * c.offset.back(), s * c.offset[c.offset.size() - 2]);
  // continuously: no jump from touching to apart (a search that lost the edge contact)
  EXPECT_GT(c.arm[1] * s * (top - c.offset[1]), 0.2 * recess);
  EXPECT_GT(c.arm[c.arm.size() - 2] * s * (top - c.offset[c.offset.size() - 2]), 0.2 * recess);
}

/// Linear interpolation of a curve at local pinion angle x (inside its samples).
double
offset_at(const ToothPairCurve &c, double x)
{
  const double t = (x - c.start) / c.step;
  const int    i = std::clamp(int(std::floor(t)), 0, int(c.offset.size()) - 2);
  return c.offset[i] + (t - i) * (c.offset[i + 1] - c.offset[i]);
}

/// The linear interpolation's error bound at x: h^2 / 8 max|offset''|, from the curve's second
/// differences around x (twice, for safety); plus the search's precision: rounding, and at an
/// edge contact (no tangency to pin it) 1e-4 of how far the touch has receded (sub-nm here).
double
interpolation_tolerance(const ToothPairCurve &c, double x, int side)
{
  const double t  = (x - c.start) / c.step;
  const int    i  = std::clamp(int(std::floor(t)), 1, int(c.offset.size()) - 3);
  double       d2 = 0;
  for (int j = i; j <= i + 1; ++j)
    d2 = std::max(d2, std::abs(c.offset[j - 1] - 2 * c.offset[j] + c.offset[j + 1]));
  const double search = 1e-11 + 1e-4 * std::abs(offset_at(c, x) - lead(c, side));
  return (std::abs(t - std::round(t)) < 1e-6 ? 0 : d2 / 8 * 2) + search;
}

/// Operating pitch radii and circumferential backlash on them at centre distance a (exact, by
/// the involute functions: j = p' - s_1(r'_1) - s_2(r'_2)).
struct Backlash
{
  double r1, r2, j;
};
Backlash
backlash(const Members &m, double a)
{
  const double ca = (m.pinion->base_radius + m.gear->base_radius) / a;
  Backlash     b;
  b.r1 = m.pinion->base_radius / ca;
  b.r2 = m.gear->base_radius / ca;
  b.j  = 2 * pi * b.r1 / m.pinion->teeth() - m.pinion->tooth_thickness(b.r1) -
        m.gear->tooth_thickness(b.r2);
  return b;
}
} // namespace

TEST(ToothPairs, PerfectInvolutesAtZeroBacklashTouchConjugatelyOverThePathOfContact)
{
  // Every tooth nominal: one class per member. Over the path of contact the offset is zero on
  // both sides and the arm the gear's base radius (times cos(beta_b): the normal leans along the
  // axis by the base helix angle); the zero stretch spans eps_gamma mesh cycles
  // (eps_alpha for spur, + eps_beta for helical) to within one sample.
  for (double beta : {0.0, 15 * deg})
    {
      const Members         m = make(seed_pair(beta));
      ToothPairOptions      o;
      const ToothPairTables t   = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w, {}, o);
      const ContactRatios   eps = contact_ratios(*m.pinion, *m.gear, m.a_w);
      EXPECT_EQ(t.pinion_teeth, 23);
      EXPECT_EQ(t.gear_teeth, 31);
      EXPECT_EQ(t.pinion_classes, 1);
      EXPECT_EQ(t.gear_classes, 1);
      EXPECT_EQ(t.pinion_class, std::vector<int>(23, 0));
      EXPECT_EQ(t.gear_class, std::vector<int>(31, 0));
      for (int side : {drive_side, coast_side})
        {
          ASSERT_EQ(t.curves[side].size(), 1u);
          const ToothPairCurve &c = t.curves[side][0];
          EXPECT_DOUBLE_EQ(c.step, 2 * pi / 23 / o.samples_per_mesh);
          EXPECT_NEAR(std::remainder(c.start, c.step), 0, 1e-12); // on the grid through 0
          const std::vector<int> zero   = near(c, 0, 1e-10);
          const double           extent = zero.size() * c.step / (2 * pi / 23); // mesh cycles
          EXPECT_NEAR(extent, eps.transverse + eps.overlap, 1.0 / o.samples_per_mesh)
              << "beta " << beta << " side " << side;
          for (int i : zero)
            EXPECT_NEAR(c.arm[i] / (m.gear->base_radius * std::cos(m.gear->base_helix_angle)), 1,
                        1e-9)
                << i;
          EXPECT_NEAR(lead(c, side), 0, 1e-10);
          expect_ends_recessed(c, side, o.recess);
        }
    }
}

TEST(ToothPairs, CentreDistanceOpensTheBacklashBetweenDriveAndCoast)
{
  // At a = a_w + da the involutes stay conjugate; drive and coast offsets lie the angular
  // backlash j / r'_2 apart, symmetrically about zero (both members symmetric about the line of
  // centres at zero rotation): drive -j / (2 r'_2), coast +j / (2 r'_2), with the exact
  // circumferential backlash j on the operating pitch circles. Along the line of action that is
  // j_bn = j cos(alpha'_wt) = r_b2 (offset_coast - offset_drive), ~ 2 da sin(alpha'_wt).
  for (double beta : {0.0, 15 * deg})
    for (double da : {0.05e-3, 0.3e-3})
      {
        const Members         m     = make(seed_pair(beta));
        const double          a     = m.a_w + da;
        const Backlash        b     = backlash(m, a);
        const ToothPairTables t     = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, a);
        const double          drive = lead(t.curves[drive_side][0], drive_side);
        const double          coast = lead(t.curves[coast_side][0], coast_side);
        EXPECT_NEAR(drive, -b.j / (2 * b.r2), 1e-10) << beta << " " << da;
        EXPECT_NEAR(coast, b.j / (2 * b.r2), 1e-10) << beta << " " << da;
        const double alpha = std::acos((m.pinion->base_radius + m.gear->base_radius) / a);
        EXPECT_NEAR(m.gear->base_radius * (coast - drive), 2 * da * std::sin(alpha),
                    0.02 * 2 * da * std::sin(alpha)); // the small-da approximation
        // conjugate over the (shorter) path of contact
        const ContactRatios eps = contact_ratios(*m.pinion, *m.gear, a);
        for (int side : {drive_side, coast_side})
          {
            const ToothPairCurve &c = t.curves[side][0];
            const double          v = side == drive_side ? drive : coast;
            EXPECT_NEAR(near(c, v, 1e-10).size() * c.step / (2 * pi / 23),
                        eps.transverse + eps.overlap, 1.0 / 64);
            expect_ends_recessed(c, side, 100e-6);
          }
      }
}

TEST(ToothPairs, EccentricToothShiftsItsClassCurveByEOverTheGearBaseRadius)
{
  // Pinion tooth 0's drive flank 4.5 um proud (more material): the gear touches it earlier by
  // e / r_b1 of pinion rotation, i.e. (z1 / z2) e / r_b1 = e / r_b2 of gear rotation: its drive
  // offset is the nominal + e / r_b2. A proud coast flank (tooth 7) holds the gear back on the
  // coast side: - e / r_b2. The other side of each is nominal. On the gear likewise.
  auto         d          = seed_pair();
  const double e          = 4.5e-6;
  d.first.eccentric_teeth = {{0, FlankSide::drive, e}, {7, FlankSide::coast, e}};
  const Members         m = make(d);
  const double          a = m.a_w + 0.1e-3;
  const ToothPairTables t = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, a);
  ASSERT_EQ(t.pinion_classes, 3);
  EXPECT_EQ(t.pinion_class[0], 1);
  EXPECT_EQ(t.pinion_class[7], 2);
  EXPECT_EQ(t.pinion_class[1], 0);
  const double rb2 = m.gear->base_radius;
  for (int side : {drive_side, coast_side})
    {
      const ToothPairCurve &nominal = t.curve(side, 1, 0);
      const double          v0      = lead(nominal, side);
      for (int tooth : {0, 7})
        {
          const ToothPairCurve &c     = t.curve(side, tooth, 0);
          const double          shift = (tooth == 0 && side == drive_side)   ? e / rb2
                                        : (tooth == 7 && side == coast_side) ? -e / rb2
                                                                             : 0.0;
          EXPECT_NEAR(lead(c, side) - v0, shift, 1e-10) << side << " " << tooth;
          // sample by sample over the stretch where both are conjugate
          int common = 0;
          for (int i = 0; i < int(c.offset.size()); ++i)
            {
              const int j = int(std::lround((c.start - nominal.start) / c.step)) + i;
              if (j < 0 || j >= int(nominal.offset.size()) ||
                  std::abs(c.offset[i] - v0 - shift) > 1e-10 ||
                  std::abs(nominal.offset[j] - v0) > 1e-10)
                continue;
              ++common;
              EXPECT_NEAR(c.arm[i], nominal.arm[j], 1e-11 * rb2);
            }
          EXPECT_GT(common, 64); // over a mesh cycle
          expect_ends_recessed(c, side, 100e-6);
        }
    }

  // A proud drive flank on the gear (tooth 3) sits further back against the gear's turning:
  // the gear must turn e / r_b2 further to meet the pinion, the same sign as the pinion's.
  auto g                   = seed_pair();
  g.second.eccentric_teeth = {{3, FlankSide::drive, e}};
  const Members         n  = make(g);
  const ToothPairTables u  = tooth_pair_tables(n.pinion_flanks, n.gear_flanks, a);
  EXPECT_NEAR(lead(u.curve(drive_side, 0, 3), drive_side) -
                  lead(u.curve(drive_side, 0, 4), drive_side),
              e / rb2, 1e-10);
  EXPECT_NEAR(lead(u.curve(coast_side, 0, 3), coast_side) -
                  lead(u.curve(coast_side, 0, 4), coast_side),
              0, 1e-10);
}

TEST(ToothPairs, ChippedGearToothShortensItsContactToTheChipRadius)
{
  // Gear tooth 4 chipped above r_c over the whole face: its flanks end at r_c, so its contact
  // on the line of action starts at the roll length sqrt(r_c^2 - r_b2^2) from the gear's base
  // tangent point instead of its tip's: the conjugate stretch is shorter by
  // (sqrt(r_a2^2 - r_b2^2) - sqrt(r_c^2 - r_b2^2)) / r_b1 of pinion rotation, on the side where
  // the gear's tip engages (approach: lower local angles on the drive side, higher on the
  // coast side), and the other end stays. Beyond the chip the pair still touches by the chip's
  // edge, receding until it leaves mesh.
  auto         d          = seed_pair();
  const double r_c        = 0.5 * 31 * 2.54e-3 + 1.0e-3; // 1.54 mm below the tip circle
  d.second.chipped_teeth  = {{4, r_c, 1.0}};
  const Members         m = make(d);
  const double          a = m.a_w + 0.1e-3;
  const ToothPairTables t = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, a);
  ASSERT_EQ(t.gear_classes, 2);
  EXPECT_EQ(t.gear_class[4], 1);
  const double rb1 = m.pinion->base_radius, rb2 = m.gear->base_radius, ra2 = m.gear->tip_radius;
  const double shorter =
      (std::sqrt(ra2 * ra2 - rb2 * rb2) - std::sqrt(r_c * r_c - rb2 * rb2)) / rb1;
  EXPECT_GT(shorter, 0.3 * 2 * pi / 23);
  for (int side : {drive_side, coast_side})
    {
      const ToothPairCurve &nominal = t.curve(side, 0, 0), &chipped = t.curve(side, 0, 4);
      const double          v = lead(nominal, side);
      EXPECT_NEAR(lead(chipped, side), v, 1e-10);
      const std::vector<int> n = near(nominal, v, 1e-10), c = near(chipped, v, 1e-10);
      const double           n0 = nominal.start + n.front() * nominal.step,
                   n1           = nominal.start + n.back() * nominal.step;
      const double c0           = chipped.start + c.front() * chipped.step,
                   c1           = chipped.start + c.back() * chipped.step;
      EXPECT_NEAR((n1 - n0) - (c1 - c0), shorter, 1.01 * chipped.step) << side;
      if (side == drive_side)
        {
          EXPECT_NEAR(c0 - n0, shorter, 1.01 * chipped.step);
          EXPECT_NEAR(c1, n1, 1e-12);
        }
      else
        {
          EXPECT_NEAR(n1 - c1, shorter, 1.01 * chipped.step);
          EXPECT_NEAR(c0, n0, 1e-12);
        }
      // the chip's edge keeps the pair touching beyond the conjugate stretch
      EXPECT_GE(side == drive_side ? c.front() : int(chipped.offset.size()) - 1 - c.back(), 3);
      expect_ends_recessed(chipped, side, 100e-6);
    }
}

TEST(ToothPairs, PitchDeviationsMoveEveryToothItsOwnWay)
{
  // Single pitch deviations on the pinion: every pinion tooth its own class; tooth k, turned
  // ahead by its cumulative deviation F_k along the reference circle, F_k / r_1, meets the gear
  // earlier on the drive side and later on the coast side by the same gear rotation
  // (z1 / z2) F_k / r_1 = F_k / r_2: both offsets grow by F_k / r_2.
  auto d         = seed_pair();
  d.first.teeth  = 13;
  d.second.teeth = 17;
  d.first.single_pitch_deviations.assign(13, 0);
  d.first.single_pitch_deviations[3]  = 3e-6;
  d.first.single_pitch_deviations[9]  = -5e-6;
  d.first.single_pitch_deviations[11] = 2e-6;
  const Members         m             = make(d);
  const ToothPairTables t = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w + 0.1e-3);
  ASSERT_EQ(t.pinion_classes, 13);
  ASSERT_EQ(t.gear_classes, 1);
  const double r2 = m.gear->reference_radius, r1 = m.pinion->reference_radius;
  EXPECT_NEAR(r1 / r2, 13.0 / 17, 1e-15);
  const double drive0 = lead(t.curve(drive_side, 0, 0), drive_side);
  const double coast0 = lead(t.curve(coast_side, 0, 0), coast_side);
  double       F      = 0;
  for (int k = 0; k < 13; ++k)
    {
      F += k > 0 ? d.first.single_pitch_deviations[k] : 0;
      EXPECT_NEAR(lead(t.curve(drive_side, k, 0), drive_side) - drive0, F / r2, 1e-10) << k;
      EXPECT_NEAR(lead(t.curve(coast_side, k, 0), coast_side) - coast0, F / r2, 1e-10) << k;
    }
}

namespace
{
void
check_convention(double helix)
{
  // base/tooth_pairs.h: pairing k has pinion tooth mod(-k, z1) and gear tooth mod(k - 1, z2)
  // (drive) or mod(k, z2) (coast), touching at psi_touch = 2 pi k / z2 + (z1 / z2) phi_k +
  // offset(phi_k), phi_k = phi - 2 pi k / z1; outside its curve it does not touch (or stands
  // off by more than the recess); and the separation UnloadedTca::at reports for a pair is
  // arm (psi - psi_touch) on the drive side, arm (psi_touch - psi) on the coast side. With
  // backlash, profile crowning (curved offsets), an eccentric pinion tooth and a chipped gear
  // tooth over part of the face, at random pairings and angles.
  auto d                                       = seed_pair(helix);
  d.first.drive_modifications.profile_crowning = 6e-6;
  d.first.coast_modifications.profile_crowning = 6e-6;
  d.first.eccentric_teeth                      = {{5, FlankSide::drive, 3e-6}};
  d.second.chipped_teeth  = {{9, InvoluteGear::create(d.second)->tip_radius - 1.3e-3, 0.6}};
  const Members         m = make(d);
  const double          a = m.a_w + 0.08e-3;
  ToothPairOptions      o;
  const ToothPairTables t = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, a, {}, o);
  EXPECT_EQ(t.pinion_classes, 2);
  EXPECT_EQ(t.gear_classes, 2);
  for (int side : {drive_side, coast_side})
    for (const ToothPairCurve &c : t.curves[side])
      expect_ends_recessed(c, side, o.recess);
  const int    z1 = 23, z2 = 31;
  const double mesh = 2 * pi / z1;
  auto         mod  = [](int x, int n) { return ((x % n) + n) % n; };

  std::mt19937_64                        rng(7);
  std::uniform_int_distribution<int>     pairing(-800, 800);
  std::uniform_real_distribution<double> local(-1.6 * mesh, 1.6 * mesh);
  int                                    inside = 0, outside = 0, on_grid = 0, separations = 0;
  for (int side : {drive_side, coast_side})
    {
      TcaOptions to;
      to.side = side == drive_side ? FlankSide::drive : FlankSide::coast;
      // a finer search grid than the curves' own (their search follows the contact from sample
      // to sample; one from a coarse grid alone can miss an edge contact's sliver of a region)
      to.profile_samples  = 33;
      to.face_samples     = 9;
      to.robust_search    = true; // as the curves' search
      const double      s = sign(side);
      const UnloadedTca tca(m.pinion_flanks, m.gear_flanks, a, {}, to);
      for (int trial = 0; trial < 300; ++trial)
        {
          // a third of the trials on the grid of the curve (exact), the rest anywhere
          const int k = trial < 20 ? (trial % 2 ? 5 * z1 - 5 : 9 + 1 - (side == coast_side))
                                   : pairing(rng); // the first: the defect teeth
          double    x = local(rng);
          if (trial % 3 == 0)
            x = std::round(x / (mesh / o.samples_per_mesh)) * (mesh / o.samples_per_mesh);
          const double      phi = x + 2 * pi * k / z1;
          const PairContact c   = tca.pair(k, phi);
          EXPECT_EQ(c.pinion_tooth, mod(-k, z1));
          EXPECT_EQ(c.gear_tooth, mod(side == drive_side ? k - 1 : k, z2));
          const ToothPairCurve &curve = t.curve(side, mod(-k, z1), c.gear_tooth);
          const double          end   = curve.start + (curve.offset.size() - 1) * curve.step;
          if (x < curve.start || x > end)
            {
              ++outside;
              if (c.found) // it stands off by more than the recess
                {
                  const Vec3   r = c.position - tca.assembly_data().gear_centre();
                  const double arm =
                      std::abs(tca.assembly_data().gear_axis().cross(r).dot(c.normal_gear));
                  const double predicted =
                      2 * pi * k / z2 + (double(z1) / z2) * x + lead(curve, side);
                  EXPECT_GT(arm * s * (predicted - c.touch_angle), 0.5 * o.recess)
                      << side << " " << k << " " << x;
                }
              continue;
            }
          ++inside;
          ASSERT_TRUE(c.found) << side << " " << k << " " << x;
          const double predicted = 2 * pi * k / z2 + (double(z1) / z2) * x + offset_at(curve, x);
          const double ti        = (x - curve.start) / curve.step;
          const bool   grid      = std::abs(ti - std::round(ti)) < 1e-6;
          on_grid += grid;
          EXPECT_NEAR(c.touch_angle, predicted, interpolation_tolerance(curve, x, side))
              << side << " " << k << " " << x;
        }

      // The separation of UnloadedTca::at against the curves: the gear sits at the leading
      // pair's touch angle; every other pair stands off by s arm (psi - psi_touch).
      for (double phi :
           {0.013, 0.41, -1.7, 2.9, 0.2, 0.77, -0.35, 1.3, 0.05, -0.11, 0.61, -0.83, 1.9, 2.2})
        {
          const TcaPosition p = tca.at(phi);
          for (const PairContact &c : p.pairs)
            {
              const int k0 = int(std::lround(phi * z1 / (2 * pi)));
              const int k =
                  -c.pinion_tooth + z1 * int(std::lround(double(k0 + c.pinion_tooth) / z1));
              const double          x     = phi - 2 * pi * k / z1;
              const ToothPairCurve &curve = t.curve(side, c.pinion_tooth, c.gear_tooth);
              if (x < curve.start || x > curve.start + (curve.offset.size() - 1) * curve.step ||
                  (c.normal_pinion + c.normal_gear).norm() > 1e-6) // edge: another normal
                continue;
              ++separations;
              const int    i = int(std::lround((x - curve.start) / curve.step));
              const double psi_touch =
                  2 * pi * k / z2 + (double(z1) / z2) * x + offset_at(curve, x);
              EXPECT_NEAR(c.touch_angle, psi_touch, interpolation_tolerance(curve, x, side));
              // d = -separation: the arm from the nearest sample, within its variation along
              // the curve
              EXPECT_NEAR(c.separation, s * curve.arm[i] * (p.gear_angle - c.touch_angle),
                          1e-3 * std::abs(c.separation) + 1e-15);
            }
        }
    }
  EXPECT_GT(inside, 200);
  EXPECT_GT(outside, 50);
  EXPECT_GT(on_grid, 50);
  EXPECT_GT(separations, 8);
}
} // namespace

TEST(ToothPairs, PairingsFollowTheConventionOfUnloadedTcaSpur) { check_convention(0); }

TEST(ToothPairs, PairingsFollowTheConventionOfUnloadedTcaHelical) { check_convention(15 * deg); }

TEST(ToothPairs, FlanksThatNeverMeetAreRefused)
{
  const Members m = make(seed_pair());
  EXPECT_THROW(tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w + 20e-3), InputError);
  Misalignment off;
  off.gear_axial_shift = 20e-3; // the faces do not overlap
  EXPECT_THROW(tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w, off), InputError);
  ToothPairOptions bad;
  bad.samples_per_mesh = 0;
  EXPECT_THROW(tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w, {}, bad), InputError);
  bad        = {};
  bad.recess = 0;
  EXPECT_THROW(tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w, {}, bad), InputError);
}

TEST(ToothPairs, AToothGoneToTheRootNeverTouches)
{
  // a wholly chipped gear tooth (gone to the root over the face) never meets the pinion: its
  // class pair's curves are empty on both sides (a pairing with it never touches), the nominal
  // teeth's curves are those of the perfect pair
  auto d                        = seed_pair();
  d.second.chipped_teeth        = {{3, 0.5 * 31 * 2.54e-3 - 1.25 * 2.54e-3, 1.0}};
  const Members         gone    = make(d);
  const Members         perfect = make(seed_pair());
  const double          a       = gone.a_w + 0.1e-3;
  const ToothPairTables t       = tooth_pair_tables(gone.pinion_flanks, gone.gear_flanks, a);
  const ToothPairTables p       = tooth_pair_tables(perfect.pinion_flanks, perfect.gear_flanks, a);
  ASSERT_EQ(t.gear_classes, 2);
  ASSERT_EQ(t.pinion_classes, 1);
  const int missing = t.gear_class[3], nominal = 1 - missing;
  for (int side : {drive_side, coast_side})
    {
      EXPECT_TRUE(t.curves[side][std::size_t(missing)].offset.empty());
      EXPECT_TRUE(t.curve(side, 0, 3).offset.empty());
      const ToothPairCurve &c = t.curves[side][std::size_t(nominal)];
      ASSERT_EQ(c.offset.size(), p.curves[side][0].offset.size());
      for (std::size_t i = 0; i < c.offset.size(); ++i)
        EXPECT_NEAR(c.offset[i], p.curves[side][0].offset[i], 1e-12);
    }
}

TEST(ToothPairs, ClassPairsThatNeverMateHaveNoSamples)
{
  // 20 / 40 teeth: pinion tooth i = mod(-k, 20) meets gear tooth j = mod(k - 1, 40) on the
  // drive side, so i + j = -1 (mod 20), and j = mod(k, 40) on the coast side, i + j = 0 (mod
  // 20). An eccentric pinion tooth 0 and a chipped gear tooth 20 never mate on the drive side,
  // and their class pair's drive curve is empty; on the coast side they do.
  auto d                  = seed_pair();
  d.first.teeth           = 20;
  d.second.teeth          = 40;
  d.first.eccentric_teeth = {{0, FlankSide::drive, 2e-6}};
  d.second.chipped_teeth  = {{20, 0.5 * 40 * 2.54e-3 + 1.5e-3, 0.5}};
  const Members         m = make(d);
  const ToothPairTables t = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w + 0.1e-3);
  EXPECT_TRUE(t.curve(drive_side, 0, 20).offset.empty());
  EXPECT_GT(t.curve(drive_side, 0, 20).step, 0);
  EXPECT_FALSE(t.curve(coast_side, 0, 20).offset.empty());
  EXPECT_FALSE(t.curve(drive_side, 0, 19).offset.empty());
  EXPECT_FALSE(t.curve(drive_side, 1, 20).offset.empty());
}

TEST(ToothPairs, A17To60PairWithAChippedAndAnEccentricToothRecedesOnEveryCurve)
{
  // m 4 mm, 17 / 60 teeth, 0.1 mm backlash opening, a chipped gear tooth and an eccentric pinion
  // tooth: 2 x 2 class pairs on both sides.
  InvoluteGearData p;
  p.name                  = "pinion";
  p.teeth                 = 17;
  p.normal_module         = 4e-3;
  p.normal_pressure_angle = 20 * deg;
  p.profile_shift         = 0.3;
  p.face_width            = 20e-3;
  InvoluteGearData g      = p;
  g.name                  = "gear";
  g.teeth                 = 60;
  g.profile_shift         = 0;
  g.hand                  = Hand::left;
  p.eccentric_teeth       = {{0, FlankSide::drive, 4.5e-6}};
  g.chipped_teeth         = {{11, 0.5 * 60 * 4e-3 + 2e-3, 0.5}};
  const Members m         = make({p, g});
  // (Its run time is measured by bench/train_startup, not here.)
  const auto t = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w + 0.1e-3);
  for (int side : {drive_side, coast_side})
    {
      EXPECT_EQ(t.curves[side].size(), 4u);
      for (const ToothPairCurve &c : t.curves[side])
        expect_ends_recessed(c, side, 100e-6);
    }
}

TEST(ToothPairs, MeasuredFlanks)
{
  // Any member flanks: a pinion measured on one tooth (both sides; every tooth stands in by it,
  // one class) against the involute gear gives the involute's curves to the interpolation's
  // accuracy; a member measured on its drive flanks only cannot give coast curves.
  const Members m = make(seed_pair());
  const double  a = m.a_w + 0.1e-3;
  const auto    measured =
      std::make_shared<MeasuredMemberFlanks>(virtual_cmm(*m.pinion, "pinion", 29, 9, 0, {0}));
  const ToothPairTables t = tooth_pair_tables(measured, m.gear_flanks, a);
  const ToothPairTables e = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, a);
  EXPECT_EQ(t.pinion_classes, 1);
  for (int side : {drive_side, coast_side})
    {
      EXPECT_NEAR(lead(t.curves[side][0], side), lead(e.curves[side][0], side), 1e-9); // 9e-11
      expect_ends_recessed(t.curves[side][0], side, 100e-6);
    }
  const auto drive_only = std::make_shared<MeasuredMemberFlanks>(
      virtual_cmm(*m.pinion, "pinion", 29, 9, 0, {0}, false));
  EXPECT_THROW(tooth_pair_tables(drive_only, m.gear_flanks, a), InputError);
}

TEST(ToothPairs, KinksSitWhereThePathOfContactEnds)
{
  // Each perfect pairing touches flank to flank over the path of contact and at a tip edge
  // beyond it: two kinks per curve, eps_gamma mesh cycles apart (eps_alpha + eps_beta). The
  // edge test looks 1e-6 of the profile's parameter range either side of the contact point, so
  // the kinks sit within a few 1e-6 of a cycle of the exact ends (the samples alone: 1/64).
  // The offset is continuous through a kink (zero on the path's side), the arm nearly so (the
  // normal switches from the gear's to the pinion's, which agree where the edge starts).
  for (double beta : {0.0, 15 * deg})
    {
      const Members         m     = make(seed_pair(beta));
      const ToothPairTables t     = tooth_pair_tables(m.pinion_flanks, m.gear_flanks, m.a_w);
      const ContactRatios   eps   = contact_ratios(*m.pinion, *m.gear, m.a_w);
      const double          cycle = 2 * pi / 23;
      for (int side : {drive_side, coast_side})
        {
          const ToothPairCurve &c = t.curves[side][0];
          ASSERT_EQ(c.knots.size(), 2u) << "beta " << beta << " side " << side;
          const CurveKnot &a = c.knots[0], &b = c.knots[1];
          EXPECT_NEAR((b.at - a.at) / cycle, eps.transverse + eps.overlap, 1e-5)
              << "beta " << beta << " side " << side;
          for (const CurveKnot &k : c.knots)
            {
              EXPECT_NEAR(k.offset[0], k.offset[1], 1e-12);
              EXPECT_NEAR(k.offset[0], 0, 1e-12);
              EXPECT_NEAR(k.arm[0] / k.arm[1], 1, 1e-6);
            }
          // strictly between two samples, in order
          EXPECT_GT(a.at, c.start);
          EXPECT_LT(b.at, c.start + double(c.offset.size() - 1) * c.step);
        }
    }
}

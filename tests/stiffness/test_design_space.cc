// The loaded contact across the design space (issue 36), on the half-space contact of the cells
// with rigid members (the finite-element part is linear and scales on its own; the driver's
// tests take it through the whole chain): exact laws of contact mechanics and similarity, over
// modules 0.1 to 30 mm, ratios, helix and pressure angles and loads from 1e-3 N m (scaled) to
// several times a nominal tooth load.
//  * geometric similarity: every length times s, the torque times s^3 (pressure kept): K_m
//    times s, e_L - e_0 and the pressures the same, to rounding (no absolute length anywhere);
//  * Young's modulus: K_m in proportion to E* at any load;
//  * light load, line contact: the contact's compliance grows by ln(10) / (pi E* L) per decade
//    of load as the 2D Hertz strip says (L the contact line's length); point contact (lead
//    crowning): the approach grows as the load^(2/3);
//  * Hertz: the interior peak pressure of a line contact 2 q / (pi a) for its line load q;
//  * invariance to one pitch of start angle, to swapping a 1:1 pair's members (the contact at
//    the same flank points carries the same load whichever member drives) and to a centre
//    distance off the working one by rounding (either side of zero backlash).
#include "stiffness/loaded_contact.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace gearkit;

namespace
{
struct Design
{
  int    z1 = 20, z2 = 31;
  double module = 3e-3, helix = 0, pressure_angle = 20 * pi / 180, face = 15e-3;
  double crowning      = 0; ///< lead crowning of the pinion [m]
  double gear_crowning = 0; ///< lead crowning of the gear [m]
  double centre_offset = 0; ///< centre distance minus the working one [m]
};

struct Pair
{
  std::unique_ptr<UnloadedTca> tca;
  double                       base_radius = 0;
  explicit Pair(const Design &d, double scale = 1)
  {
    InvoluteGearData p;
    p.name = "pinion", p.teeth = d.z1, p.normal_module = d.module * scale;
    p.normal_pressure_angle = d.pressure_angle, p.helix_angle = d.helix;
    p.face_width = d.face * scale, p.hand = Hand::right;
    p.drive_modifications.lead_crowning = d.crowning * scale;
    InvoluteGearData g                  = p;
    g.name = "gear", g.teeth = d.z2, g.hand = Hand::left;
    g.drive_modifications               = {};
    g.drive_modifications.lead_crowning = d.gear_crowning * scale;
    const auto pinion = InvoluteGear::create(p), gear = InvoluteGear::create(g);
    tca = std::make_unique<UnloadedTca>(
        pinion, gear, working_centre_distance(*pinion, *gear) + d.centre_offset * scale);
    base_radius = pinion->base_radius;
  }
  /// A position with one pair touching, near the middle of single contact where there is one.
  TcaPosition
  single(double phi_fraction = 0.5) const
  {
    const double step = 2 * pi / tca->pinion_flanks().teeth();
    for (int k = 0; k < 40; ++k)
      {
        const TcaPosition p = tca->at(step * std::fmod(phi_fraction + k / 40.0, 1.0));
        if (p.touching == 1)
          return p;
      }
    return tca->at(step * phi_fraction);
  }
};

const StructuralCompliance rigid = [](const ContactCell &, const ContactCell &) { return 0.0; };

LoadedContactOptions
options(double E = 206e9)
{
  LoadedContactOptions o;
  o.pinion_material = o.gear_material = {E, 0.3};
  o.cells.gap_band                    = 0; // from the load
  return o;
}

double
peak_pressure(const LoadedPosition &r, bool interior)
{
  double p = 0;
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    if (!interior || !r.cells[i].flank_edge)
      p = std::max(p, r.force[Eigen::Index(i)] / (r.cells[i].ds * r.cells[i].dt));
  return p;
}
} // namespace

TEST(DesignSpace, GeometricSimilarityFromModule0p1To30mm)
{
  // T at the nominal tooth load F_t / (b m_n) = 100 MPa of the 3 mm pair, and 1e-5 of it.
  for (const Design &d : {Design{}, Design{17, 17, 3e-3, 30 * pi / 180, 20 * pi / 180, 15e-3},
                          Design{12, 61, 3e-3, 0, 25 * pi / 180, 15e-3, 8e-6},
                          Design{25, 40, 3e-3, 15 * pi / 180, 14.5 * pi / 180, 20e-3, 5e-6}})
    {
      const Pair   base(d);
      const double T0 = 100e6 * d.face * d.module * d.z1 * d.module / 2;
      for (const double load : {1.0, 1e-5})
        {
          const TcaPosition    p0 = base.single();
          const LoadedPosition r0 =
              loaded_contact(*base.tca, p0, load * T0, options(), rigid, rigid);
          for (const double module : {0.1e-3, 0.3e-3, 1e-3, 10e-3, 30e-3})
            {
              const double         s = module / d.module;
              const Pair           scaled(d, s);
              const TcaPosition    p = scaled.single();
              const LoadedPosition r =
                  loaded_contact(*scaled.tca, p, load * T0 * s * s * s, options(), rigid, rigid);
              SCOPED_TRACE("z " + std::to_string(d.z1) + "/" + std::to_string(d.z2) + ", m " +
                           std::to_string(module * 1e3) + " mm, load " + std::to_string(load));
              // To rounding where no flank edge cuts the zone; where one does (the crowned
              // helical pair's second pair meets at the tip), the zone's extent along the line
              // and the columns' cut are found by bisection on the scaled geometry: 2e-5 then
              // (0.2 % before the zone along an edge contact was taken from lines across the
              // band: one line's exit jumped with the rounding of the edge point), and the
              // pressure beside the edge (singular there) is no measure.
              const bool edge = d.helix > 0 && d.crowning > 0;
              EXPECT_NEAR(r.mesh_stiffness / (s * r0.mesh_stiffness), 1, edge ? 2e-5 : 1e-5);
              EXPECT_NEAR((r.eL - r.e0) / (r0.eL - r0.e0), 1, edge ? 2e-5 : 1e-5);
              if (!edge)
                {
                  EXPECT_NEAR(peak_pressure(r, false) / peak_pressure(r0, false), 1, 1e-5);
                }
            }
        }
    }
}

TEST(DesignSpace, MeshStiffnessInProportionToTheContactModulus)
{
  const Pair        pair(Design{});
  const TcaPosition p = pair.tca->at(0.1);
  for (const double T : {1e-3, 1.0, 300.0})
    {
      const LoadedPosition a = loaded_contact(*pair.tca, p, T, options(206e9), rigid, rigid);
      const LoadedPosition b = loaded_contact(*pair.tca, p, T * 0.5, options(103e9), rigid, rigid);
      // half the modulus at half the load: the same contact, half the stiffness
      EXPECT_NEAR(b.mesh_stiffness / a.mesh_stiffness, 0.5, 1e-9);
      EXPECT_NEAR((b.eL - b.e0) / (a.eL - a.e0), 1, 1e-9);
    }
}

TEST(DesignSpace, LightLoadLineContactFollowsTheHertzStripsLogarithm)
{
  // A spur line contact on the half-space: per decade of load the compliance 1/K falls by
  // ln(10) / (pi E* L) (the 2D approach 2 q / (pi E*) (ln(..) - ln a) with a ~ sqrt(q)), from
  // 1e-3 N m (scaled) on, to within 1 % (the face ends and the curvature's change across the
  // wider contact add a little as the load grows).
  for (const double module : {0.3e-3, 3e-3})
    {
      const Design      d{20, 31, module, 0, 20 * pi / 180, 5 * module};
      const Pair        pair(d);
      const TcaPosition p     = pair.single();
      const double      Estar = 206e9 / (2 * (1 - 0.09));
      const double      law   = std::log(10.0) / (pi * Estar * d.face);
      const double      T1    = 1e-3 * std::pow(module / 3e-3, 3);
      double            last  = 0;
      for (int decade = 0; decade <= 4; ++decade)
        {
          const LoadedPosition r =
              loaded_contact(*pair.tca, p, T1 * std::pow(10.0, decade), options(), rigid, rigid);
          if (decade > 0)
            {
              EXPECT_NEAR((last - 1 / r.mesh_stiffness) / law, 1, 0.01)
                  << "m " << module * 1e3 << " mm, decade " << decade;
            }
          last = 1 / r.mesh_stiffness;
          EXPECT_LT(r.edge_force, 0.2 * r.normal_force);
        }
    }
}

TEST(DesignSpace, LightLoadPointContactApproachGrowsAsTheLoadToTwoThirds)
{
  // Lead crowning of 10 um on a 3 mm spur pair: at light loads an elliptical Hertz contact in
  // the middle of the face, approach ~ F^(2/3), K_m ~ F^(1/3); the zone follows the ellipse along
  // the line as well as across.
  const Pair        pair(Design{20, 31, 3e-3, 0, 20 * pi / 180, 15e-3, 10e-6});
  const TcaPosition p             = pair.single();
  double            last_approach = 0;
  for (int decade = 0; decade <= 3; ++decade)
    {
      const LoadedPosition r =
          loaded_contact(*pair.tca, p, 1e-3 * std::pow(10.0, decade), options(), rigid, rigid);
      const double approach = std::abs(r.eL - r.e0);
      if (decade > 0)
        {
          EXPECT_NEAR(approach / last_approach, std::pow(10.0, 2.0 / 3),
                      0.03 * std::pow(10.0, 2.0 / 3))
              << "decade " << decade;
        }
      last_approach = approach;
      EXPECT_EQ(r.edge_force, 0);
      EXPECT_FALSE(r.zone_edge_reached);
    }
}

TEST(DesignSpace, InteriorPressureIsHertzsAndEdgeContactIsReported)
{
  // The 3 mm spur pair at 100 MPa nominal to 15 times that: the pressure in the middle of the
  // face is Hertz's for the line load there; at a position where the pinion's tip meets the
  // gear's flank the load reaches the tip's edge, and is reported there.
  const Design      d;
  const Pair        pair(d);
  const double      T0    = 100e6 * d.face * d.module * d.z1 * d.module / 2;
  const TcaPosition p     = pair.single();
  const double      Estar = 206e9 / (2 * (1 - 0.09));
  for (const double factor : {0.01, 1.0, 15.0})
    {
      const LoadedPosition r = loaded_contact(*pair.tca, p, factor * T0, options(), rigid, rigid);
      const PairContact   &c = p.pairs[std::size_t(p.leading)];
      double               q = 0, peak = 0, z_mid = HUGE_VAL;
      for (const ContactCell &cell : r.cells)
        if (std::abs(cell.position.z()) < std::abs(z_mid))
          z_mid = cell.position.z();
      for (std::size_t i = 0; i < r.cells.size(); ++i)
        if (r.cells[i].pair == p.leading && !r.cells[i].flank_edge &&
            std::abs(r.cells[i].position.z() - z_mid) < r.cells[i].dt / 4)
          {
            q += r.force[Eigen::Index(i)] / r.cells[i].dt;
            peak = std::max(peak, r.force[Eigen::Index(i)] / (r.cells[i].ds * r.cells[i].dt));
          }
      const double R = 1 / c.curvature_max;
      const double a = std::sqrt(4 * q * R / (pi * Estar));
      EXPECT_NEAR(peak / (2 * q / (pi * a)), 1, 0.04) << "load factor " << factor;
    }
  // the tip: the first position of the cycle where a pair meets near the pinion's tip
  const double step = 2 * pi / d.z1;
  double       best = 0;
  TcaPosition  tip;
  for (int k = 0; k < 40; ++k)
    {
      const TcaPosition q = pair.tca->at(step * k / 40);
      for (const PairContact &c : q.pairs)
        if (c.found && c.separation < 1e-9 && c.position.head<2>().norm() > best)
          best = c.position.head<2>().norm(), tip = q;
    }
  const LoadedPosition r = loaded_contact(*pair.tca, tip, 15 * T0, options(), rigid, rigid);
  EXPECT_GT(r.edge_force, 0.02 * r.normal_force);
  ASSERT_GE(r.edge_cell, 0);
  // the most loaded edge cell, the first of those equal to rounding (the face ends of a spur
  // pair mirror each other: which one wins must not depend on the machine's BLAS)
  double edge_peak = 0;
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    if (r.cells[i].flank_edge)
      edge_peak = std::max(edge_peak, r.force[Eigen::Index(i)]);
  EXPECT_GE(r.force[r.edge_cell], edge_peak * (1 - 1e-8));
  for (int i = 0; i < r.edge_cell; ++i)
    if (r.cells[std::size_t(i)].flank_edge)
      {
        EXPECT_LT(r.force[i], edge_peak * (1 - 1e-8)) << "cell " << i;
      }
  EXPECT_GT(peak_pressure(r, false), peak_pressure(r, true));
  EXPECT_NEAR(r.normal_force * r.lever, 15 * T0, 1e-9 * 15 * T0);
}

TEST(DesignSpace, OnePitchOfStartAngleChangesNothing)
{
  const Pair   pair(Design{25, 40, 3e-3, 15 * pi / 180, 20 * pi / 180, 20e-3});
  const double step = 2 * pi / 25;
  for (const double T : {1e-3, 50.0, 500.0})
    {
      const LoadedPosition a =
          loaded_contact(*pair.tca, pair.tca->at(0.3 * step), T, options(), rigid, rigid);
      const LoadedPosition b =
          loaded_contact(*pair.tca, pair.tca->at(1.3 * step), T, options(), rigid, rigid);
      EXPECT_NEAR(b.mesh_stiffness / a.mesh_stiffness, 1, 2e-6);
      EXPECT_NEAR((b.eL - b.e0) / (a.eL - a.e0), 1, 2e-6);
    }
}

namespace
{
/// Distance of a contact point from the gear's axis (parallel axes: the z direction) with the
/// gear turned to psi.
double
gear_radius(const UnloadedTca &tca, const Vec3 &point, double psi)
{
  return (point - tca.assembly_data().gear_to_global(Vec3::Zero(), psi)).head<2>().norm();
}

/// The pinion angle at which some tooth pair of `tca` touches at distance r from the gear's
/// axis, by bisection on each pairing's own contact (the radius on the driven member falls as
/// the pinion turns); NaN if none does within one pitch of phi0.
double
angle_at_gear_radius(const UnloadedTca &tca, double r, double phi0)
{
  const double pitch  = 2 * pi / tca.pinion_flanks().teeth();
  auto         radius = [&](int k, double phi) {
    const PairContact c = tca.pair(k, phi);
    return c.found && !c.edge ? gear_radius(tca, c.position, c.touch_angle) - r : NAN;
  };
  for (int k = -2; k <= 2; ++k)
    for (int i = 0; i < 100; ++i)
      {
        double a = phi0 + pitch * i / 100, b = phi0 + pitch * (i + 1) / 100;
        if (!(radius(k, a) > 0 && radius(k, b) <= 0))
          continue;
        for (int n = 0; n < 60; ++n)
          {
            const double m             = (a + b) / 2;
            (radius(k, m) > 0 ? a : b) = m;
          }
        return (a + b) / 2;
      }
  return NAN;
}
} // namespace

TEST(DesignSpace, SwappingTheMembersOfAOneToOnePairChangesNothingUnderLoad)
{
  // A 25/25 spur pair, member A crowned (8 um) and stiff (206 GPa), member B plain and soft
  // (110 GPa). Driving with A or with B, the contact at the same flank points (the same radius
  // on A; on B it follows, the pair being 1:1 and symmetric about the pitch point) carries the
  // same load: the same K_m and e_L - e_0 over the whole mesh cycle, single and double contact,
  // at light and heavy load. The contact runs the other way along A's flank when B drives, so
  // the positions are found by the radius on A, not the angle. The cells lie on the driver's
  // flank, so the two discretise the contact on different members: 1e-5 at light load, within
  // 1.3e-4 at 2.4 times the nominal load. Where a tip's corner carries load the corner contact
  // is resolved on the cornered flank when the pinion's tip meets and on the smooth one when
  // the gear's does: 0.9 % at 2.4 times nominal where a pair joins at a tip (measured across
  // 17, 24 and 48 cells across: a model difference, not a resolution one). (Before the zone's
  // columns were followed along a crowned pinion's tip, the straight line through its corner
  // left the flank 0.5 mm from the point and the joining pair there carried 466 N instead of
  // 2486 N: 11 %.)
  Design a_drives{25, 25, 3e-3, 0, 20 * pi / 180, 15e-3, 8e-6};
  Design b_drives = a_drives;
  std::swap(b_drives.crowning, b_drives.gear_crowning);
  const Pair           A(a_drives), B(b_drives);
  LoadedContactOptions oa = options(), ob = options();
  oa.pinion_material = ob.gear_material = {206e9, 0.3};
  oa.gear_material = ob.pinion_material = {110e9, 0.3};
  const double pitch                    = 2 * pi / 25;
  int          doubles = 0, corners = 0;
  for (const double f : {0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95})
    {
      const TcaPosition  p   = A.tca->at(f * pitch);
      const PairContact &c   = p.pairs[std::size_t(p.leading)];
      const double       r   = c.position.head<2>().norm(); // on A, the pinion here
      const double       phi = angle_at_gear_radius(*B.tca, r, 0);
      ASSERT_TRUE(std::isfinite(phi)) << "no contact at r = " << r * 1e3 << " mm on A";
      const TcaPosition q = B.tca->at(phi);
      ASSERT_EQ(q.touching, p.touching) << "fraction " << f;
      doubles += p.touching == 2;
      for (const double T : {1e-2, 100.0, 600.0})
        {
          const LoadedPosition la     = loaded_contact(*A.tca, p, T, oa, rigid, rigid);
          const LoadedPosition lb     = loaded_contact(*B.tca, q, T, ob, rigid, rigid);
          const bool           corner = la.edge_force > 0 || lb.edge_force > 0;
          const double         tol    = corner ? 1.2e-2 : T < 1 ? 2e-5 : 3e-4;
          EXPECT_NEAR(lb.mesh_stiffness / la.mesh_stiffness, 1, tol)
              << "fraction " << f << ", " << T << " N m";
          EXPECT_NEAR((lb.eL - lb.e0) / (la.eL - la.e0), 1, tol)
              << "fraction " << f << ", " << T << " N m";
          corners += corner;
        }
    }
  EXPECT_GE(doubles, 2); // double contact was among the positions
  EXPECT_GE(corners, 3); // and loaded tip corners
}

TEST(DesignSpace, ACentreDistanceOffByRoundingEitherSideOfZeroBacklashChangesNothing)
{
  // At the working centre distance the coast flanks touch too (zero backlash); 1e-12 m closer
  // they interfere by that much, 1e-12 m further they are apart: no threshold may act there.
  for (const Design &d : {Design{}, Design{25, 40, 3e-3, 15 * pi / 180, 20 * pi / 180, 20e-3}})
    {
      const Pair base(d);
      for (const double offset : {-1e-12, 1e-12})
        {
          Design moved        = d;
          moved.centre_offset = offset;
          const Pair pair(moved);
          for (const double f : {0.1, 0.5, 0.9})
            for (const double T : {1e-3, 100.0})
              {
                const double         phi = f * 2 * pi / d.z1;
                const LoadedPosition a =
                    loaded_contact(*base.tca, base.tca->at(phi), T, options(), rigid, rigid);
                const LoadedPosition b =
                    loaded_contact(*pair.tca, pair.tca->at(phi), T, options(), rigid, rigid);
                EXPECT_NEAR(b.mesh_stiffness / a.mesh_stiffness, 1, 1e-6)
                    << "offset " << offset << ", fraction " << f << ", " << T << " N m";
                EXPECT_NEAR((b.eL - b.e0) / (a.eL - a.e0), 1, 1e-6)
                    << "offset " << offset << ", fraction " << f << ", " << T << " N m";
              }
        }
    }
}

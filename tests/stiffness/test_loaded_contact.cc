// Loaded contact on the cells of a spur pair: the torque balance, the Hertz strip at the pitch
// point, a structural compliance that adds exactly T (c_p + c_g) / lambda^2 to the loaded TE, load
// sharing by two pairs, and zero load.
#include "stiffness/loaded_contact.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

using namespace gearkit;

namespace
{
struct SpurPair
{
  std::shared_ptr<const InvoluteGear> pinion, gear;
  double                              a, alpha;
  std::unique_ptr<UnloadedTca>        tca;
  SpurPair()
  {
    const auto [pd, gd] = test_data::fzg_c_pair();
    pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
    a     = working_centre_distance(*pinion, *gear);
    alpha = working_pressure_angle(*pinion, *gear);
    tca   = std::make_unique<UnloadedTca>(pinion, gear, a);
  }
  /// A position with `pairs` touching pairs, the single one nearest the pitch point.
  TcaPosition
  position(int pairs) const
  {
    TcaPosition  best;
    double       best_distance = HUGE_VAL;
    const double rho_pitch =
        a * pinion->teeth() / (pinion->teeth() + gear->teeth()) * std::sin(alpha);
    for (int k = 0; k < 40; ++k)
      {
        const TcaPosition p = tca->at(2 * pi / pinion->teeth() * k / 40);
        if (p.touching != pairs)
          continue;
        const Vec3   x   = p.pairs[p.leading].position;
        const double rho = std::sqrt(x.head<2>().squaredNorm() - std::pow(pinion->base_radius, 2));
        if (std::abs(rho - rho_pitch) < best_distance)
          best = p, best_distance = std::abs(rho - rho_pitch);
      }
    return best;
  }
};

const StructuralCompliance rigid = [](const ContactCell &, const ContactCell &) { return 0.0; };
} // namespace

TEST(LoadedContact, HertzStripAndTorqueBalanceAtThePitchPoint)
{
  const SpurPair    s;
  const TcaPosition pos = s.position(1);
  ASSERT_EQ(pos.touching, 1);
  LoadedContactOptions o;
  o.pinion_material = o.gear_material = {206e9, 0.3};
  o.cells.cells_across                = 20;
  const double         T = 5912 * s.pinion->base_radius; // F_bt of FZG C14 on the line of action
  const LoadedPosition r = loaded_contact(*s.tca, pos, T, o, rigid, rigid);
  EXPECT_NEAR(r.lever, s.pinion->base_radius, 1e-9);
  EXPECT_NEAR(r.normal_force, 5912, 1e-6);
  EXPECT_GT(r.eL, r.e0);
  // Middle strip: Hertzian for its own load per length (see the half-space tests).
  const PairContact &c = pos.pairs[pos.leading];
  const double       rho1 =
      std::sqrt(c.position.head<2>().squaredNorm() - std::pow(s.pinion->base_radius, 2));
  const double R  = 1 / (1 / rho1 + 1 / (s.a * std::sin(s.alpha) - rho1));
  const double Es = contact_modulus(o.pinion_material, o.gear_material);
  double       q = 0, peak = 0, z_mid = HUGE_VAL; // the strip nearest the middle of the face
  for (const ContactCell &c : r.cells)
    if (std::abs(c.position.z()) < std::abs(z_mid))
      z_mid = c.position.z();
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    if (r.cells[i].pair == pos.leading &&
        std::abs(r.cells[i].position.z() - z_mid) < r.cells[i].dt / 4)
      {
        q += r.force[i] / r.cells[i].dt;
        peak = std::max(peak, r.force[i] / (r.cells[i].ds * r.cells[i].dt));
      }
  const double a_q = std::sqrt(4 * q * R / (pi * Es));
  EXPECT_NEAR(peak / (2 * q / (pi * a_q)), 1, 0.03);
  EXPECT_NEAR(q / (5912 / 14e-3), 1, 0.12); // the square ends take more than the mean
}

TEST(LoadedContact, StructuralComplianceAddsExactly)
{
  // A member compliance c on every pair of cells of the same tooth shifts all cells' approach by
  // c F: the forces stay, and e_L grows by T (c_p + c_g) / lambda^2.
  const SpurPair             s;
  const TcaPosition          pos = s.position(1);
  LoadedContactOptions       o;
  const double               T  = 200;
  const double               cp = 3e-10, cg = 5e-10;
  const StructuralCompliance pinion = [&](const ContactCell &a, const ContactCell &b) {
    return a.pinion_tooth == b.pinion_tooth ? cp : 0.0;
  };
  const StructuralCompliance gear = [&](const ContactCell &a, const ContactCell &b) {
    return a.gear_tooth == b.gear_tooth ? cg : 0.0;
  };
  const LoadedPosition hs = loaded_contact(*s.tca, pos, T, o, rigid, rigid);
  const LoadedPosition st = loaded_contact(*s.tca, pos, T, o, pinion, gear);
  const double         lb = s.pinion->base_radius;
  EXPECT_NEAR((st.eL - st.e0) - (hs.eL - hs.e0), T * (cp + cg) / (lb * lb),
              1e-9 * T * (cp + cg) / (lb * lb));
  EXPECT_NEAR((st.force - hs.force).norm(), 0, 1e-9 * hs.force.norm());
  // and K_m is the series spring: 1/K = 1/K_hs + (c_p + c_g)
  EXPECT_NEAR(1 / st.mesh_stiffness, 1 / hs.mesh_stiffness + cp + cg, 1e-9 / st.mesh_stiffness);
}

TEST(LoadedContact, TwoPairsShareTheLoadAndZeroLoadGivesTheUnloadedTE)
{
  const SpurPair    s;
  const TcaPosition pos = s.position(2);
  ASSERT_EQ(pos.touching, 2);
  LoadedContactOptions o;
  const double         T = 300;
  // Springs on every tooth pair much softer than the contact: the pairs share the load in
  // inverse proportion to their springs plus the contact's own compliance h (from the rigid
  // pairs: h = 2 delta / F each). At 1e-7 m/N the approach (0.4 mm) stays below the third
  // pair's separation (2 mm), which joins under springs ten times softer.
  const LoadedPosition hs = loaded_contact(*s.tca, pos, T, o, rigid, rigid);
  const double         h  = 2 * (hs.eL - hs.e0) * hs.lever / hs.normal_force;
  for (double ratio : {1.0, 3.0})
    {
      const StructuralCompliance spring = [&](const ContactCell &a, const ContactCell &b) {
        return a.pair == b.pair ? (a.pair == pos.leading ? 1e-7 : ratio * 1e-7) : 0.0;
      };
      const LoadedPosition r = loaded_contact(*s.tca, pos, T, o, spring, rigid);
      ASSERT_EQ(r.pair_force.size(), pos.pairs.size());
      double other = 0;
      for (std::size_t k = 0; k < pos.pairs.size(); ++k)
        if (int(k) != pos.leading)
          other += r.pair_force[k];
      EXPECT_NEAR(r.pair_force[pos.leading] / other, (ratio * 1e-7 + h) / (1e-7 + h),
                  0.005 * ratio);
      EXPECT_NEAR(r.normal_force * r.lever, T, 1e-9 * T);
    }
  const StructuralCompliance spring = [](const ContactCell &a, const ContactCell &b) {
    return a.pair == b.pair ? 1e-7 : 0.0;
  };
  const LoadedPosition zero = loaded_contact(*s.tca, pos, 0, o, spring, rigid);
  EXPECT_NEAR(zero.eL, pos.transmission_error, 1e-12);
  EXPECT_EQ(zero.normal_force, 0);
  EXPECT_THROW(loaded_contact(*s.tca, pos, -1, o, spring, rigid), InputError);
}

TEST(LoadedContact, VeryHighLoadSpreadsToTheTipOrIsRefusedWhenTheZoneIsTooNarrow)
{
  const SpurPair s;
  // The position where a pair touches nearest the tip of the pinion (end of the path).
  TcaPosition tip;
  int         tip_pair = 0;
  double      rho_max  = 0;
  for (int k = 0; k < 40; ++k)
    {
      const TcaPosition p = s.tca->at(2 * pi / s.pinion->teeth() * k / 40);
      for (std::size_t j = 0; j < p.pairs.size(); ++j)
        {
          const Vec3   x = p.pairs[j].position;
          const double rho =
              std::sqrt(x.head<2>().squaredNorm() - std::pow(s.pinion->base_radius, 2));
          if (p.pairs[j].found && p.pairs[j].separation < 1e-9 && rho > rho_max)
            tip = p, tip_pair = int(j), rho_max = rho;
        }
    }
  LoadedContactOptions o;
  const double         T = 20 * 5912 * s.pinion->base_radius; // twenty times FZG C14
  // Zones started far too narrow (0.1 um) or wide enough (10 um; not fitted to the load) are
  // widened until the contact fits, onto the tip edge of the pinion flank; the fitted zone
  // from 0.1 um gives the same balanced contact.
  o.cells.gap_band = 10e-6, o.cells.cells_across = 9, o.cells.cells_along = 6;
  o.adapt_band           = false;
  const LoadedPosition r = loaded_contact(*s.tca, tip, T, o, rigid, rigid);
  EXPECT_GT(r.gap_band, 10e-6);
  EXPECT_FALSE(r.zone_edge_reached);
  EXPECT_NEAR(r.normal_force * r.lever, T, 1e-9 * T);
  o.cells.gap_band = 0.1e-6, o.cells.cells_across = 17, o.adapt_band = true;
  const LoadedPosition fitted = loaded_contact(*s.tca, tip, T, o, rigid, rigid);
  EXPECT_FALSE(fitted.zone_edge_reached);
  EXPECT_GT(fitted.zones, 2);
  EXPECT_NEAR(fitted.normal_force * fitted.lever, T, 1e-9 * T);
  EXPECT_NEAR(fitted.mesh_stiffness / r.mesh_stiffness, 1, 0.02);
  EXPECT_GT(fitted.edge_force, 0.05 * fitted.normal_force); // on the tip edge
  const FlankDomain d =
      s.tca->pinion_flanks().flank(tip.pairs[tip_pair].pinion_tooth, FlankSide::drive).domain();
  double u_loaded = -HUGE_VAL, u_all = -HUGE_VAL;
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    if (r.cells[i].pair == tip_pair)
      {
        u_all = std::max(u_all, r.cells[i].u1);
        if (r.force[Eigen::Index(i)] > 0)
          u_loaded = std::max(u_loaded, r.cells[i].u1);
      }
  EXPECT_EQ(u_loaded, u_all); // the last cell row before the tip carries load
  EXPECT_GT(u_all, d.u_max - 0.05 * (d.u_max - d.u_min));
}

TEST(LoadedContact, MisalignedPairLoadsOneEndOfTheFace)
{
  // A crossing misalignment (deviation of parallelism, f_Sigma_beta) of 2 mrad tilts the gear
  // flank by ~26 um over the face, far beyond the pinion's 5 um lead crowning: point contact at
  // one face end. Under the FZG C14 load the contact spreads from that end: balanced,
  // the load's centre on that side, peak pressure above the aligned pair's, a softer mesh; a
  // negligible misalignment gives the aligned answer.
  const SpurPair s;
  const auto     loaded = [&](double crossing, int *end_side) {
    Misalignment m;
    m.crossing_angle = crossing;
    const UnloadedTca tca(s.pinion, s.gear, s.a, m);
    const TcaPosition pos = tca.at(s.position(1).pinion_angle);
    if (end_side)
      *end_side = pos.pairs[pos.leading].position.z() > 0 ? 1 : -1;
    LoadedContactOptions o;
    o.pinion_material = o.gear_material = {206e9, 0.3};
    const double T                      = 5912 * s.pinion->base_radius;
    // a tooth compliance (both members) of the order of the FE's: the contact can spread
    const StructuralCompliance tooth = [](const ContactCell &a, const ContactCell &b) {
      return a.pair == b.pair ? 4e-10 * std::exp(-std::abs(a.position.z() - b.position.z()) / 5e-3)
                                  : 0.0;
    };
    return loaded_contact(tca, pos, T, o, tooth, tooth);
  };
  const LoadedPosition aligned = loaded(0, nullptr);
  const LoadedPosition tiny    = loaded(1e-9, nullptr);
  EXPECT_NEAR(tiny.mesh_stiffness / aligned.mesh_stiffness, 1, 1e-3);
  int                  side = 0;
  const LoadedPosition r    = loaded(2e-3, &side);
  EXPECT_NEAR(r.normal_force * r.lever, r.torque, 1e-9 * r.torque);
  double z_centre = 0, z_min = HUGE_VAL, z_max = -HUGE_VAL, peak = 0, peak_aligned = 0;
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    if (r.force[Eigen::Index(i)] > 0)
      {
        const ContactCell &c = r.cells[i];
        z_centre += c.position.z() * r.force[Eigen::Index(i)] / r.normal_force;
        z_min = std::min(z_min, c.position.z()), z_max = std::max(z_max, c.position.z());
        peak = std::max(peak, r.force[Eigen::Index(i)] / (c.ds * c.dt));
      }
  for (std::size_t i = 0; i < aligned.cells.size(); ++i)
    peak_aligned = std::max(peak_aligned, aligned.force[Eigen::Index(i)] /
                                              (aligned.cells[i].ds * aligned.cells[i].dt));
  const double b = 14e-3;
  EXPECT_GT(side * z_centre, b / 8) << z_centre;
  EXPECT_LT(z_max - z_min, 0.9 * b); // the far end stands off
  EXPECT_GT(peak, 1.3 * peak_aligned);
  EXPECT_LT(r.mesh_stiffness, 0.9 * aligned.mesh_stiffness);
}

// A mesh cycle shared among the processes (every size-th torque and position on each, gathered
// on all; stiffness_mpi_np2 runs it on two) equals the one of this process alone, entry by
// entry; a position refused on one process is refused on all.
TEST(LoadedContact, MeshCycleSharedAmongProcessesEqualsOneProcessAlone)
{
  const SpurPair             s;
  const StructuralCompliance spring = [](const ContactCell &a, const ContactCell &b) {
    return a.pair == b.pair ? 2e-11 : 0.0;
  };
  LoadedContactOptions alone;
  alone.threads               = 1;
  LoadedContactOptions shared = alone;
  shared.communicator         = MPI_COMM_WORLD;
  const MeshCycleContact a    = loaded_contact_cycle(*s.tca, 7, {150, 300}, alone, spring, rigid);
  const MeshCycleContact b    = loaded_contact_cycle(*s.tca, 7, {150, 300}, shared, spring, rigid);
  EXPECT_EQ(a.slots, b.slots);
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.loaded_te, b.loaded_te);
  EXPECT_EQ(a.mesh_stiffness, b.mesh_stiffness);
  EXPECT_EQ(a.normal_force, b.normal_force);
  EXPECT_EQ(a.lever, b.lever);
  EXPECT_EQ(a.pair_force, b.pair_force);
  EXPECT_EQ(a.peak_pressure, b.peak_pressure);
  EXPECT_EQ(a.cell_pressure, b.cell_pressure);
  EXPECT_EQ(a.mesh_stiffness.size(), 14u);
  for (std::size_t i = 0; i < 7; ++i)
    EXPECT_GT(a.mesh_stiffness[i], 0); // no empty entry
  // a negative torque is refused, on every process
  EXPECT_THROW(loaded_contact_cycle(*s.tca, 1, {150, 300, -1}, shared, spring, rigid), InputError);
  // A torque that fails at some position is marked alone, on every process: segments covering
  // pinion teeth 15, 0 and 1 only, and a load so large (springs of 1e-9 m/N, an approach of mm)
  // that pairs beyond them come into contact.
  LoadedContactOptions few        = shared;
  few.covered                     = [](int p, int) { return (p + 1) % 16 <= 2; };
  const StructuralCompliance soft = [](const ContactCell &a, const ContactCell &b) {
    return a.pair == b.pair ? 1e-9 : 0.0;
  };
  const MeshCycleContact f = loaded_contact_cycle(*s.tca, 7, {150, 3e5}, few, soft, rigid);
  ASSERT_EQ(f.torque_failure.size(), 2u);
  EXPECT_EQ(f.torque_failure[0], "");
  EXPECT_NE(f.torque_failure[1].find("do not cover them"), std::string::npos)
      << f.torque_failure[1];
  const MeshCycleContact kept = select_torques(f, {0});
  EXPECT_EQ(kept.torques, 1u);
  const MeshCycleContact g = loaded_contact_cycle(*s.tca, 7, {150}, few, soft, rigid);
  EXPECT_EQ(kept.mesh_stiffness, g.mesh_stiffness);
  EXPECT_EQ(kept.loaded_te, g.loaded_te);
  EXPECT_EQ(kept.peak_pressure, g.peak_pressure); // (the cell tables pad to the most cells)
}

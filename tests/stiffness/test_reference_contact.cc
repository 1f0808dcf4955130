// Reference mode (finite elements alone on meshes graded to the contact lines) on the FZG C spur
// pair at the single-pair position nearest the pitch point, at the FZG C14 normal force: the
// torque balance, the Hertz strip in the middle of the face (reference-data.md section 5: the
// finite elements give the contact pressure themselves here), the fast mode on the same
// segments, several torques from one factorisation, zero load and bad input.
#include "stiffness/member_compliance.h"
#include "stiffness/reference_contact.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace gearkit;

namespace
{
struct Pitch
{
  std::shared_ptr<const InvoluteGear> pinion, gear;
  std::unique_ptr<UnloadedTca>        tca;
  TcaPosition                         position;
  double                              R = 0; ///< relative radius of curvature at the contact
  Pitch()
  {
    const auto [pd, gd] = test_data::fzg_c_pair();
    pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
    const double a         = working_centre_distance(*pinion, *gear);
    const double alpha     = working_pressure_angle(*pinion, *gear);
    tca                    = std::make_unique<UnloadedTca>(pinion, gear, a);
    const double rho_pitch = pinion->base_radius * std::tan(alpha);
    double       best      = HUGE_VAL;
    for (int k = 0; k < 40; ++k)
      {
        const TcaPosition p = tca->at(2 * pi / pinion->teeth() * k / 40);
        const Vec3        x = p.pairs[p.leading].position;
        const double rho = std::sqrt(x.head<2>().squaredNorm() - std::pow(pinion->base_radius, 2));
        if (p.touching == 1 && std::abs(rho - rho_pitch) < best)
          best = std::abs(rho - rho_pitch), position = p, R = rho;
      }
    R = 1 / (1 / R + 1 / (a * std::sin(alpha) - R));
  }
};

std::string
work_directory(const std::string &name)
{
  const auto dir = std::filesystem::temp_directory_path() / ("gearkit-test-" + name);
  std::filesystem::create_directories(dir);
  return dir.string();
}

/// The fast mode (FE tables of the members on the reference's segments, default meshes, and
/// the half-space between the cells) at the same position, torque and cells.
LoadedPosition
fast_mode(const InvoluteGear &pinion, const InvoluteGear &gear, const UnloadedTca &tca,
          const TcaPosition &position, double torque, const ReferenceContactOptions &o,
          const ReferenceContactInfo &info, const Material &material)
{
  auto table = [&](const InvoluteGear &g, const MemberFlanks &f, const SegmentChoice &seg) {
    MemberComplianceOptions mo;
    mo.mesh.teeth = seg.teeth, mo.mesh.central_tooth = seg.central;
    mo.material = material, mo.work_directory = o.work_directory;
    return involute_member_compliance(g, f, mo);
  };
  const FlankCompliance cp = table(pinion, tca.pinion_flanks(), info.pinion_segment);
  const FlankCompliance cg = table(gear, tca.gear_flanks(), info.gear_segment);
  LoadedContactOptions  lo = o.cells;
  lo.covered               = [&](int p, int g) { return cp.covers(p) && cg.covers(g); };
  return loaded_contact(tca, position, torque, lo, table_compliance(cp, true),
                        table_compliance(cg, false));
}
} // namespace

TEST(ReferenceContact, HertzStripTorqueBalanceAndTheFastMode)
{
  const Pitch s;
  ASSERT_EQ(s.position.touching, 1);
  const Material          steel{206e9, 0.3};
  ReferenceContactOptions o;
  o.cells.pinion_material = o.cells.gear_material = steel;
  o.cells.cells.cells_across = 21, o.cells.cells.cells_along = 4;
  o.cells.cells.gap_band = 8e-6;
  o.min_segment_teeth    = 1;
  o.elements_per_cell    = 1;
  o.far_size             = 2 * s.pinion->data().normal_module;
  o.work_directory       = work_directory("reference");
  const double F = 5912, T = F * s.pinion->base_radius; // FZG C14: F_bt on the line of action
  ReferenceContactInfo              info;
  const std::vector<LoadedPosition> r =
      reference_contact(*s.pinion, *s.gear, *s.tca, s.position, {0, T / 2, T}, o, &info);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(info.pinion_segment.teeth, 1);
  EXPECT_EQ(r[0].normal_force, 0);
  EXPECT_EQ(r[0].eL, s.position.transmission_error);
  for (const LoadedPosition &p : {r[1], r[2]})
    {
      EXPECT_NEAR(p.normal_force * p.lever, p.torque, 1e-9 * p.torque);
      EXPECT_NEAR(p.lever, s.pinion->base_radius, 1e-6 * p.lever);
      EXPECT_GE(p.force.minCoeff(), 0);
    }
  // Hertz contact stiffens with load; the tooth bending does not: K_m rises, by little.
  EXPECT_GT(r[2].mesh_stiffness, r[1].mesh_stiffness);
  EXPECT_LT(r[2].mesh_stiffness, 1.1 * r[1].mesh_stiffness);

  // The middle strips: Hertzian for their own load per length q (peak 2 q / (pi a(q))).
  const double Es = contact_modulus(steel, steel);
  double       q = 0, peak = 0, along = 0, s_min = HUGE_VAL, s_max = -HUGE_VAL;
  for (std::size_t i = 0; i < r[2].cells.size(); ++i)
    {
      const ContactCell &c = r[2].cells[i];
      if (std::abs(c.position.z()) < c.dt)
        {
          q += r[2].force[i], along = std::max(along, std::abs(c.position.z()) + c.dt / 2);
          peak = std::max(peak, r[2].force[i] / (c.ds * c.dt));
          if (r[2].force[i] > 0)
            s_min = std::min(s_min, c.s - c.ds / 2), s_max = std::max(s_max, c.s + c.ds / 2);
        }
    }
  q /= 2 * along;
  const double a = std::sqrt(4 * q * s.R / (pi * Es));
  EXPECT_NEAR(peak / (2 * q / (pi * a)), 1, 0.03);
  const double ds = r[2].cells.front().ds;
  EXPECT_NEAR(s_max - s_min, 2 * a, ds); // the contact width, to within a cell
  std::printf("reference mode, FZG C14 at the pitch point: p0 %.0f MPa (Hertz for q: %.0f MPa), "
              "width %.0f um (2a %.0f um), %zu dofs, %.1f s\n",
              peak * 1e-6, 2 * q / (pi * a) * 1e-6, (s_max - s_min) * 1e6, 2 * a * 1e6, info.dofs,
              info.mesh_seconds + info.solve_seconds + info.contact_seconds);

  // The fast mode on the same segments (FE tables + half-space) within a few per cent.
  const LoadedPosition fast = fast_mode(*s.pinion, *s.gear, *s.tca, s.position, T, o, info, steel);
  std::printf("K_m fast / reference %.4f\n", fast.mesh_stiffness / r[2].mesh_stiffness);
  EXPECT_NEAR(fast.mesh_stiffness / r[2].mesh_stiffness, 1, 0.06);
}

TEST(ReferenceContact, BadInputIsRefused)
{
  const Pitch             s;
  ReferenceContactOptions o;
  o.work_directory = work_directory("reference-bad");
  EXPECT_THROW(reference_contact(*s.pinion, *s.gear, *s.tca, s.position, {-1.0}, o), InputError);
  o.elements_per_cell = 0;
  EXPECT_THROW(reference_contact(*s.pinion, *s.gear, *s.tca, s.position, {1.0}, o), InputError);
  o.elements_per_cell = 1;
  o.work_directory    = "/nonexistent/gearkit";
  EXPECT_THROW(reference_contact(*s.pinion, *s.gear, *s.tca, s.position, {1.0}, o), InputError);
}

TEST(ReferenceContact, RefinedAboutTheCellsAsOnTheGradedSection)
{
  // The same spur position two ways: gmsh grading the transverse section to the contact lines
  // (the spur default), and deal.II refining a segment at the flank size about the contact
  // cells (the way of helical and bevel pairs). Independent meshes of the same problem.
  const Pitch             s;
  ReferenceContactOptions o;
  o.cells.cells.cells_across = 11, o.cells.cells.cells_along = 4;
  o.cells.cells.gap_band = 8e-6;
  o.min_segment_teeth    = 1;
  o.elements_per_cell    = 0.5;
  o.far_size             = 2 * s.pinion->data().normal_module;
  o.work_directory       = work_directory("reference-local");
  const double         T = 5912 * s.pinion->base_radius;
  ReferenceContactInfo graded_info, local_info;
  const double         graded =
      reference_contact(*s.pinion, *s.gear, *s.tca, s.position, {T}, o, &graded_info)
          .front()
          .mesh_stiffness;
  o.local_refinement = true;
  const LoadedPosition local =
      reference_contact(*s.pinion, *s.gear, *s.tca, s.position, {T}, o, &local_info).front();
  std::printf("reference K_m graded %.2f N/um (%zu dofs), refined about the cells %.2f N/um "
              "(%zu dofs, %u refinements)\n",
              graded * 1e-6, graded_info.dofs, local.mesh_stiffness * 1e-6, local_info.dofs,
              local_info.local_refinements);
  EXPECT_EQ(graded_info.local_refinements, 0u);
  EXPECT_GE(local_info.local_refinements, 2u);
  EXPECT_NEAR(local.normal_force * local.lever, T, 1e-9 * T);
  EXPECT_NEAR(local.mesh_stiffness / graded, 1, 0.02);
}

TEST(ReferenceContact, HelicalTorqueBalanceAndTheFastMode)
{
  // FZG C with a 15 degree helix: inclined contact lines, so the segments are refined about the
  // contact cells by deal.II. Torque balance, compressive cell forces, and the fast mode on the
  // same segments (FE tables + half-space) within a few per cent.
  const auto [pd, gd]        = test_data::fzg_c_pair(15 * pi / 180);
  const auto              hp = InvoluteGear::create(pd), hg = InvoluteGear::create(gd);
  const UnloadedTca       tca(hp, hg, working_centre_distance(*hp, *hg));
  const TcaPosition       position = tca.at(0);
  ReferenceContactOptions o;
  o.cells.cells.cells_across = 11, o.cells.cells.cells_along = 8;
  o.cells.cells.gap_band = 8e-6;
  o.min_segment_teeth    = 1;
  o.elements_per_cell    = 0.25; // 0.5: 686k dofs, 8 GB, fast / reference 0.994
  o.far_size             = 2 * hp->data().normal_module;
  o.work_directory       = work_directory("reference-helical");
  const double         T = 200;
  ReferenceContactInfo info;
  const LoadedPosition r = reference_contact(*hp, *hg, tca, position, {T}, o, &info).front();
  EXPECT_GE(info.local_refinements, 2u);
  EXPECT_NEAR(r.normal_force * r.lever, T, 1e-9 * T);
  EXPECT_GE(r.force.minCoeff(), 0);
  EXPECT_GT(r.force.maxCoeff(), 0);

  const LoadedPosition fast = fast_mode(*hp, *hg, tca, position, T, o, info, Material{});
  std::printf("helical FZG C, reference K_m %.2f N/um (%zu dofs, %u refinements, %.0f s), fast / "
              "reference %.4f\n",
              r.mesh_stiffness * 1e-6, info.dofs, info.local_refinements,
              info.mesh_seconds + info.solve_seconds + info.contact_seconds,
              fast.mesh_stiffness / r.mesh_stiffness);
  EXPECT_NEAR(fast.mesh_stiffness / r.mesh_stiffness, 1, 0.06);
}

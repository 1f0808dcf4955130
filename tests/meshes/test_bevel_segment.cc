// Spiral bevel tooth segments: all hexahedra, positive Jacobians at every corner, the mesh volume
// against the segment volume integrated from the exact surfaces, every physical group present,
// flank groups whose area is the working flank's (integrated from the flank parametrisation)
// and whose nodes lie on the flank, and bad options refused.
#include "meshes/bevel_segment.h"
#include "tests/meshes/read_mesh.h"
#include "tests/seed_bevel_pair.h"
#include "tests/temp_directory_test.h"

#include <cstdlib>

using namespace gearkit;

namespace
{
class BevelSegmentMesh : public test_data::TempDirectoryTest
{
};

/// Area of a flank from its parametrisation (Gauss-Legendre, 4 x 4 points on 12 x 12 panels).
double
flank_area(const Flank &f)
{
  const FlankDomain d    = f.domain();
  const double      x[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  const int         n    = 24;
  const double      du = (d.u_max - d.u_min) / n, dv = (d.v_max - d.v_min) / n;
  double            area = 0;
  const double      e    = 1e-7;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (double a : x)
        for (double b : x)
          {
            const double u = d.u_min + (i + a) * du, v = d.v_min + (j + b) * dv;
            const Vec3   xu =
                (f.evaluate(u + e, v).position - f.evaluate(u - e, v).position) / (2 * e);
            const Vec3 xv =
                (f.evaluate(u, v + e).position - f.evaluate(u, v - e).position) / (2 * e);
            area += xu.cross(xv).norm() * du * dv / 4;
          }
  return area;
}
} // namespace

TEST_F(BevelSegmentMesh, HexahedraVolumeGroupsAndFlanks)
{
  // Sample meshes for scripts/check_mesh.py as in tooth segments (the seed pair's pinion and
  // gear, three teeth each).
  const char       *env             = std::getenv("GEARKIT_MESH_CHECK_DIR");
  const std::string out             = env ? env : dir.string();
  const auto        design          = test_data::seed_bevel_design();
  const double      module          = bevel_geometry(design).mean_normal_module;
  const auto [pinion_cut, gear_cut] = conjugate_cuts(design);
  for (const bool is_pinion : {true, false})
    {
      const BevelMemberFlanks member(is_pinion ? pinion_cut : gear_cut);
      SegmentMeshOptions      o;
      o.teeth         = 3;
      o.central_tooth = is_pinion ? 0 : 46; // the gear's segment wraps around tooth 0
      const std::string path =
          out + (is_pinion ? "/seed_bevel_pinion.msh" : "/seed_bevel_gear.msh");
      const SegmentMeshInfo info = write_bevel_segment_mesh(member, module, o, path);
      EXPECT_EQ(info.member_teeth,
                (is_pinion ? std::vector<int>{54, 0, 1} : std::vector<int>{45, 46, 0}));

      test_data::MeshFile m = test_data::read(path);
      EXPECT_TRUE(m.other_element_types.empty());
      EXPECT_EQ(m.hexahedra.size(), info.hexahedra);
      const auto [volume, min_j] = test_data::volume_and_min_jacobian(m);
      EXPECT_GT(min_j, 0);
      // The exact volume converged in its samples, the mesh's within its chordal error.
      const double exact = bevel_segment_volume(member, o, module, 192);
      EXPECT_NEAR(info.analytic_volume / exact - 1, 0, 1e-5);
      EXPECT_NEAR(volume / exact - 1, 0, 2e-3) << "mesh " << volume << " exact " << exact;

      for (int id : {boundary::bore, boundary::cut_start, boundary::cut_end, boundary::end_front,
                     boundary::end_back, boundary::free})
        EXPECT_FALSE(m.group_nodes[id].empty()) << boundary::name(id);
      // Flank groups: nodes on the turned flank, the quads' area that of the working flank.
      for (int i = 0; i < 3; ++i)
        for (FlankSide side : {FlankSide::drive, FlankSide::coast})
          {
            const int   id    = boundary::flank(i, side);
            const auto &nodes = m.group_nodes[id];
            ASSERT_FALSE(nodes.empty()) << boundary::name(id);
            const Flank &f     = member.flank(info.member_teeth[i], side);
            double       worst = 0;
            for (std::size_t k = 0; k < nodes.size(); k += 7)
              {
                const Vec3 x = m.nodes.at(nodes[k]);
                // (u, v) from the rotational projection: u = h, v = A - A_m
                const BevelBlank &b  = member.tooth_flank(side).blank_data();
                const double      ax = x.z(), r = std::hypot(x.x(), x.y());
                const double      A = ax * std::cos(b.pitch_angle) + r * std::sin(b.pitch_angle);
                const double      h = -ax * std::sin(b.pitch_angle) + r * std::cos(b.pitch_angle);
                worst =
                    std::max(worst, (f.evaluate(h, A - b.mean_cone_distance).position - x).norm());
              }
            EXPECT_LT(worst, 1e-9) << boundary::name(id);
            if (i == 1)
              {
                double area = 0;
                for (const auto &q : m.group_quads[id])
                  {
                    const Vec3 a = m.nodes.at(q[0]), b = m.nodes.at(q[1]), c = m.nodes.at(q[2]),
                               d = m.nodes.at(q[3]);
                    area += 0.5 * ((c - a).cross(d - b)).norm();
                  }
                EXPECT_NEAR(area / flank_area(f) - 1, 0, 2e-3) << boundary::name(id);
              }
          }
    }
}

TEST_F(BevelSegmentMesh, BadOptionsAreRejected)
{
  const auto              design = test_data::seed_bevel_design();
  const BevelMemberFlanks member(conjugate_cuts(design).first);
  const std::string       path = (dir / "bad.msh").string();
  SegmentMeshOptions      o;
  o.teeth = 2;
  EXPECT_THROW(write_bevel_segment_mesh(member, 2e-3, o, path), InputError);
  o.teeth = 3, o.flank_size = -1;
  EXPECT_THROW(write_bevel_segment_mesh(member, 2e-3, o, path), InputError);
  o.flank_size = 0, o.rim_thickness = 1; // through the axis
  EXPECT_THROW(write_bevel_segment_mesh(member, 2e-3, o, path), InputError);
  auto sharp        = design;
  sharp.edge_radius = 0; // no fillet to close the tooth
  o.rim_thickness   = 0;
  EXPECT_THROW(
      write_bevel_segment_mesh(BevelMemberFlanks(conjugate_cuts(sharp).first), 2e-3, o, path),
      InputError);
  EXPECT_FALSE(std::filesystem::exists(path));
}

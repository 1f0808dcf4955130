// Tooth-segment meshes: all hexahedra with positive Jacobians at every corner, the volume of the
// nominal segment, every physical group present, and the flank groups' nodes on the exact
// involute flank (which also checks the helix twist's sense against the flank surfaces).
#include "meshes/cylinder_slice.h"
#include "meshes/tooth_segment.h"
#include "tests/fzg_c_pair.h"
#include "tests/meshes/read_mesh.h"
#include "tests/temp_directory_test.h"

#include <Eigen/Dense>
#include <gmsh.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>

using namespace gearkit;
using test_data::hex_corners;
using test_data::hex_volume_and_min_jacobian;
using test_data::MeshFile;
using test_data::read;
using test_data::volume_and_min_jacobian;

namespace
{
class ToothSegmentMesh : public test_data::TempDirectoryTest
{
};

/// The mean volume of the hexahedra with a node in the group.
double
mean_volume_at(const MeshFile &m, int group)
{
  const std::set<std::size_t> nodes(m.group_nodes.at(group).begin(), m.group_nodes.at(group).end());
  double                      v = 0;
  int                         n = 0;
  for (const auto &h : m.hexahedra)
    if (std::any_of(h.begin(), h.end(), [&](std::size_t node) { return nodes.count(node) > 0; }))
      v += hex_volume_and_min_jacobian(hex_corners(m, h)).first, ++n;
  return v / n;
}
/// A mesh without cuts (whole gear or whole rim): hexahedra only, none folded, the analytic
/// volume, no cut groups, and the bore all round at its radius.
void
expect_ring_without_cuts(const MeshFile &m, const SegmentMeshInfo &info, double beta)
{
  EXPECT_TRUE(info.whole);
  EXPECT_TRUE(m.other_element_types.empty());
  const auto [volume, min_j] = volume_and_min_jacobian(m);
  EXPECT_GT(min_j, 0) << beta;
  EXPECT_NEAR(volume / info.analytic_volume, 1, 2e-3) << beta;
  EXPECT_EQ(m.group_nodes.count(boundary::cut_start) + m.group_nodes.count(boundary::cut_end), 0u);
  double r_lo = HUGE_VAL, r_hi = 0, a_lo = HUGE_VAL, a_hi = -HUGE_VAL;
  for (std::size_t tag : m.group_nodes.at(boundary::bore))
    {
      const Vec3   x = m.nodes.at(tag);
      const double r = std::hypot(x.x(), x.y()), a = std::atan2(x.y(), x.x());
      r_lo = std::min(r_lo, r), r_hi = std::max(r_hi, r);
      a_lo = std::min(a_lo, a), a_hi = std::max(a_hi, a);
    }
  EXPECT_NEAR(r_lo / info.rim_inner_radius, 1, 1e-8) << beta; // on the circle (the file's digits)
  EXPECT_NEAR(r_hi / info.rim_inner_radius, 1, 1e-8) << beta;
  EXPECT_GT(a_hi - a_lo, 1.9 * pi) << beta;
}
} // namespace

TEST_F(ToothSegmentMesh, HexahedraVolumeGroupsAndFlanksOnTheInvolute)
{
  for (double beta : {0.0, 15 * pi / 180})
    {
      const auto         gear = InvoluteGear::create(test_data::fzg_c_pair(beta).first);
      SegmentMeshOptions o;
      o.teeth                    = 3;
      o.central_tooth            = 0;
      const std::string     path = (dir / "segment.msh").string();
      const SegmentMeshInfo info = write_tooth_segment_mesh(*gear, o, path);
      EXPECT_TRUE(std::ifstream(path + ".json").good());
      EXPECT_EQ(info.member_teeth, (std::vector<int>{15, 0, 1}));
      const MeshFile m = read(path);
      EXPECT_TRUE(m.other_element_types.empty());
      ASSERT_EQ(m.hexahedra.size(), info.hexahedra);

      const auto [volume, min_j] = volume_and_min_jacobian(m);
      EXPECT_GT(min_j, 0) << beta;
      EXPECT_NEAR(volume / info.analytic_volume, 1, 2e-3) << beta;

      for (int id : {boundary::bore, boundary::cut_start, boundary::cut_end, boundary::end_front,
                     boundary::end_back, boundary::free})
        EXPECT_FALSE(m.group_nodes.count(id) == 0 || m.group_nodes.at(id).empty()) << id;
      // Flank nodes on the exact involute: at the node's radius and z the flank's polar angle.
      double worst = 0;
      for (int i = 0; i < o.teeth; ++i)
        for (FlankSide side : {FlankSide::drive, FlankSide::coast})
          {
            const int id = boundary::flank(i, side);
            ASSERT_TRUE(m.group_nodes.count(id)) << id;
            const InvoluteFlank f = gear->flank(info.member_teeth[i], side);
            for (std::size_t tag : m.group_nodes.at(id))
              {
                const Vec3   x = m.nodes.at(tag);
                const double r = std::hypot(x.x(), x.y());
                const Vec3   p =
                    f.nominal(gear->roll_angle(std::max(r, gear->base_radius)), x.z()).position;
                const double da =
                    std::remainder(std::atan2(x.y(), x.x()) - std::atan2(p.y(), p.x()), 2 * pi);
                worst = std::max(worst, std::abs(da) * r);
              }
          }
      EXPECT_LT(worst, 1e-10) << beta; // snapped onto the exact flank
    }
}

TEST_F(ToothSegmentMesh, BadOptionsAreRejected)
{
  const auto         gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const std::string  path = (dir / "bad.msh").string();
  SegmentMeshOptions o;
  o.teeth = 2;
  EXPECT_THROW(write_tooth_segment_mesh(*gear, o, path), InputError);
  o.teeth            = 3;
  o.rim_inner_radius = gear->root_radius;
  EXPECT_THROW(write_tooth_segment_mesh(*gear, o, path), InputError);
  EXPECT_FALSE(std::ifstream(path).good());
}

TEST_F(ToothSegmentMesh, GradedTowardTheFlanks)
{
  // Sample meshes for scripts/check_mesh.py (written to $GEARKIT_MESH_CHECK_DIR when set, by the
  // CTest fixture), and the grading: hexahedra at the flanks much smaller than at the bore.
  const char       *env = std::getenv("GEARKIT_MESH_CHECK_DIR");
  const std::string out = env ? env : dir.string();
  for (double beta : {0.0, 15 * pi / 180})
    {
      const auto         gear = InvoluteGear::create(test_data::fzg_c_pair(beta).second);
      SegmentMeshOptions o;
      o.teeth                = 5;
      const std::string path = out + (beta == 0 ? "/fzg_gear_spur.msh" : "/fzg_gear_helical.msh");
      const SegmentMeshInfo       info         = write_tooth_segment_mesh(*gear, o, path);
      const MeshFile              m            = read(path);
      double                      flank_volume = 0, bore_volume = 0;
      int                         flank_cells = 0, bore_cells = 0;
      const std::set<std::size_t> flank_nodes(
          m.group_nodes.at(boundary::flank(2, FlankSide::drive)).begin(),
          m.group_nodes.at(boundary::flank(2, FlankSide::drive)).end());
      const std::set<std::size_t> bore_nodes(m.group_nodes.at(boundary::bore).begin(),
                                             m.group_nodes.at(boundary::bore).end());
      for (const auto &h : m.hexahedra)
        {
          std::array<Vec3, 8> x;
          bool                on_flank = false, on_bore = false;
          for (int k = 0; k < 8; ++k)
            {
              x[k] = m.nodes.at(h[k]);
              on_flank |= flank_nodes.count(h[k]) > 0;
              on_bore |= bore_nodes.count(h[k]) > 0;
            }
          const double v = hex_volume_and_min_jacobian(x).first;
          if (on_flank)
            flank_volume += v, ++flank_cells;
          if (on_bore)
            bore_volume += v, ++bore_cells;
        }
      ASSERT_GT(flank_cells, 0);
      ASSERT_GT(bore_cells, 0);
      // default sizes m/5 at the flanks and m at the bore: section areas 1:25
      EXPECT_LT(flank_volume / flank_cells, 0.2 * bore_volume / bore_cells) << beta;
      EXPECT_GT(info.hexahedra, 1000u);
    }
}

TEST_F(ToothSegmentMesh, CylinderSlicesForHertz)
{
  // Both bodies of the Hertz check: all hexahedra, the half-disc volume, graded to the contact.
  const char       *env = std::getenv("GEARKIT_MESH_CHECK_DIR");
  const std::string out = env ? env : dir.string();
  for (bool upper : {true, false})
    {
      CylinderSliceOptions o;
      o.upper        = upper;
      o.radius       = upper ? 10e-3 : 15e-3;
      o.contact_size = 50e-6, o.fine_distance = 0.3e-3;
      const std::string       path = out + (upper ? "/cylinder_upper.msh" : "/cylinder_lower.msh");
      const CylinderSliceInfo info = write_cylinder_slice_mesh(o, path);
      const MeshFile          m    = read(path);
      ASSERT_EQ(m.hexahedra.size(), info.hexahedra);
      const auto [volume, min_j] = volume_and_min_jacobian(m);
      double smallest            = HUGE_VAL;
      for (const auto &h : m.hexahedra)
        {
          const std::array<Vec3, 8> x = hex_corners(m, h);
          if (x[0].head<2>().norm() < 3 * o.contact_size)
            smallest = std::min(smallest, (x[1] - x[0]).norm());
        }
      EXPECT_GT(min_j, 0);
      // chords of the far arcs (size h) lose (h/R)^2 / 6 of the half-disc: 1.7e-3 at h = R / 10
      EXPECT_NEAR(volume / info.analytic_volume, 1, 2e-3);
      EXPECT_LT(smallest, 1.5 * o.contact_size);
      // every node of the contact group on the circle
      for (std::size_t tag : m.group_nodes.at(cylinder_boundary::contact))
        {
          const Vec3 x = m.nodes.at(tag);
          EXPECT_NEAR(std::hypot(x.x(), x.y() - (upper ? 1 : -1) * o.radius), o.radius, 1e-9);
        }
    }
}

TEST_F(ToothSegmentMesh, FineOnlyAtTheLoadedFlanks)
{
  // other_size: the coast flanks and fillets coarser than the drive flanks that carry load.
  const auto         gear = InvoluteGear::create(test_data::fzg_c_pair().second);
  SegmentMeshOptions o;
  o.teeth = 3, o.flank_size = 0.1 * 4.5e-3, o.face_layers = 4;
  const SegmentMeshInfo uniform =
      write_tooth_segment_mesh(*gear, o, (dir / "uniform.msh").string());
  o.other_size               = 0.4 * 4.5e-3;
  const std::string     path = (dir / "loaded_fine.msh").string();
  const SegmentMeshInfo info = write_tooth_segment_mesh(*gear, o, path);
  const MeshFile        m    = read(path);
  // sizes 1:4 asked; the drive flank's grading reaches across the thin tooth, so the coast
  // cells come out about 2.2 times larger in the section (same layers): volumes ~1:5
  EXPECT_GT(mean_volume_at(m, boundary::flank(1, FlankSide::coast)),
            3 * mean_volume_at(m, boundary::flank(1, FlankSide::drive)));
  EXPECT_LT(info.hexahedra, uniform.hexahedra * 2 / 3);
  EXPECT_NEAR(info.analytic_volume, uniform.analytic_volume, 1e-15);
  SegmentMeshOptions bad = o;
  bad.other_size         = -1;
  EXPECT_THROW(write_tooth_segment_mesh(*gear, bad, path), InputError);
}

TEST_F(ToothSegmentMesh, FilletElementSizeTakesTheChordsOffTheToothRoots)
{
  // The root fillets are concave arcs of about the cutter's tip radius (0.38 m_n): gmsh puts
  // four elements on each at flank elements of m_n / 4, whose chords add material at the tooth
  // roots (issue 36: K_m 0.5 % stiff). With fillet elements of m_n / 10 the facets' largest gap
  // to the exact fillet (generated by the rack cutter: InvoluteGear::fillet_point), at their
  // centres on the middle tooth, is less than a third as large (measured 41 -> 10.5 um).
  const auto         gear = InvoluteGear::create(test_data::fzg_c_pair().second);
  const double       mn   = 4.5e-3;
  SegmentMeshOptions o;
  o.teeth = 3, o.flank_size = 0.25 * mn, o.face_layers = 2;
  std::vector<Vec2> fillet; // the exact drive fillet of tooth 0, finely
  for (int k = 0; k <= 2000; ++k)
    fillet.push_back(gear->fillet_point(k / 2000.0));
  auto largest_gap = [&](const std::string &name) {
    const std::string path = (dir / name).string();
    write_tooth_segment_mesh(*gear, o, path);
    const MeshFile m   = read(path);
    double         gap = 0;
    int            n   = 0;
    for (const auto &q : m.group_quads.at(boundary::free))
      {
        Vec3 c = Vec3::Zero();
        for (std::size_t node : q)
          c += m.nodes.at(node) / 4;
        Vec2         x(c.x(), std::abs(c.y())); // the coast fillet: the drive's mirror
        const double r = x.norm();
        if (c.x() < 0 || std::abs(std::atan2(c.y(), c.x())) > pi / gear->teeth() ||
            r < gear->root_radius + 0.05 * mn || r > gear->form_radius)
          continue; // not on the middle tooth's fillets
        double d = HUGE_VAL;
        for (const Vec2 &p : fillet)
          d = std::min(d, (p - x).norm());
        gap = std::max(gap, d), ++n;
      }
    EXPECT_GT(n, 0) << name;
    return gap;
  };
  const double plain = largest_gap("plain.msh");
  o.fillet_size      = 0.1 * mn;
  const double fine  = largest_gap("fillets.msh");
  std::printf("largest gap of the fillet facets to the fillet: %.2f um with fillets as the "
              "flanks, %.2f um with fillet elements of m_n / 10\n",
              plain * 1e6, fine * 1e6);
  EXPECT_GT(plain, 5e-6);
  EXPECT_LT(fine, plain / 3);
  SegmentMeshOptions bad = o;
  bad.fillet_size        = -1;
  EXPECT_THROW(write_tooth_segment_mesh(*gear, bad, (dir / "bad.msh").string()), InputError);
}

TEST_F(ToothSegmentMesh, AnotherAlgorithmWhereFrontalDelaunayFoldsAnElement)
{
  // The FZG C gear's 7-tooth segment at half a module: gmsh 4.8's frontal-Delaunay leaves a
  // sliver at a root land whose subdivision folds (worst corner Jacobian -2.1 spur, -0.51
  // helical of its mean); the mesher tries the next 2-D algorithm.
  for (double beta : {0.0, 15 * pi / 180})
    {
      const auto         gear = InvoluteGear::create(test_data::fzg_c_pair(beta).second);
      SegmentMeshOptions o;
      o.teeth = 7, o.flank_size = 0.5 * 4.5e-3, o.far_size = 4.5e-3;
      const std::string     path = (dir / "segment.msh").string();
      const SegmentMeshInfo info = write_tooth_segment_mesh(*gear, o, path);
      EXPECT_NE(info.mesh_algorithm, 6) << beta; // the fallback is what this test exercises
      EXPECT_GE(info.worst_corner_jacobian, SegmentMeshInfo::acceptable_corner_jacobian) << beta;
      // independently, from the trilinear map's derivative: the worst corner against the
      // element's mean Jacobian (its volume / 8 in reference coordinates [-1, 1]^3)
      const MeshFile m     = read(path);
      double         worst = HUGE_VAL;
      for (const auto &h : m.hexahedra)
        {
          const auto [v, j] = hex_volume_and_min_jacobian(hex_corners(m, h));
          worst             = std::min(worst, j / (v / 8));
        }
      EXPECT_GT(worst, 0.5 * info.worst_corner_jacobian) << beta;
      EXPECT_LT(worst, 2 * info.worst_corner_jacobian) << beta;
      std::ifstream      sidecar(path + ".json");
      std::ostringstream text;
      text << sidecar.rdbuf();
      EXPECT_NE(text.str().find("\"gmsh_2d_algorithm\": " + std::to_string(info.mesh_algorithm)),
                std::string::npos);
    }
}

TEST_F(ToothSegmentMesh, TheWholeGearIsARingWithoutCutsFineAtTheLoadedTeeth)
{
  // teeth = z: every tooth on the rim, the bore a hole all round, no cut faces; only the
  // `fine_teeth` about the central tooth get the flank size.
  for (double beta : {0.0, 15 * pi / 180})
    {
      const auto         gear = InvoluteGear::create(test_data::fzg_c_pair(beta).first);
      SegmentMeshOptions o;
      o.teeth = 16, o.fine_teeth = 3, o.central_tooth = 5, o.face_layers = 4;
      const std::string     path = (dir / "whole.msh").string();
      const SegmentMeshInfo info = write_tooth_segment_mesh(*gear, o, path);
      ASSERT_EQ(info.member_teeth.size(), 16u);
      EXPECT_EQ(std::set<int>(info.member_teeth.begin(), info.member_teeth.end()).size(), 16u);
      EXPECT_EQ(info.member_teeth[8], 5); // the central tooth in the middle, as in a segment
      const MeshFile m = read(path);
      expect_ring_without_cuts(m, info, beta);
      for (int i = 0; i < 16; ++i)
        EXPECT_TRUE(m.group_nodes.count(boundary::flank(i, FlankSide::drive))) << i;
      // the loaded teeth (segment teeth 7..9) fine, the far ones coarse
      EXPECT_GT(mean_volume_at(m, boundary::flank(0, FlankSide::drive)),
                4 * mean_volume_at(m, boundary::flank(8, FlankSide::drive)))
          << beta;
    }
  SegmentMeshOptions bad;
  bad.teeth = 16, bad.fine_teeth = 2;
  EXPECT_THROW(write_tooth_segment_mesh(*InvoluteGear::create(test_data::fzg_c_pair().first), bad,
                                        (dir / "bad.msh").string()),
               InputError);
}

TEST_F(ToothSegmentMesh, FarElementsAreAtMostAThirdOfTheRimThick)
{
  // a far size beyond a third of the rim's thickness meshes as that third (a small pinion's body
  // stays resolved); a finer one gives more elements
  const auto         gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  SegmentMeshOptions o;
  o.teeth = 3, o.face_layers = 2, o.rim_inner_radius = gear->root_radius - 4 * 4.5e-3;
  auto hexahedra = [&](double far_size) {
    o.far_size = far_size;
    return write_tooth_segment_mesh(*gear, o, (dir / "far.msh").string()).hexahedra;
  };
  const std::size_t third = hexahedra(4 * 4.5e-3 / 3);
  EXPECT_EQ(hexahedra(10 * 4.5e-3), third);
  EXPECT_GT(hexahedra(0.5 * 4.5e-3), third);
}

TEST_F(ToothSegmentMesh, TheWholeRimCarriesTheSegmentsTeethAndTheBoreAllRound)
{
  // whole_rim: the segment's teeth on the rim, the root circle round the rest of the gear, the
  // bore a hole all round, no cut faces.
  for (double beta : {0.0, 15 * pi / 180})
    {
      const auto         gear = InvoluteGear::create(test_data::fzg_c_pair(beta).first);
      SegmentMeshOptions o;
      o.teeth = 3, o.central_tooth = 5, o.whole_rim = true, o.face_layers = 4;
      const std::string     path = (dir / "rim.msh").string();
      const SegmentMeshInfo info = write_tooth_segment_mesh(*gear, o, path);
      EXPECT_EQ(info.member_teeth, (std::vector<int>{4, 5, 6}));
      const MeshFile m = read(path);
      expect_ring_without_cuts(m, info, beta);
      // nothing beyond the root circle more than two pitches (plus the helix's twist) from the
      // central tooth; the teeth there reach the tip circle
      const double pitch = 2 * pi / 16, centre = 5 * pitch;
      const double twist = std::tan(beta) * gear->data().face_width / gear->reference_radius;
      double       r_far = 0, r_near = 0;
      for (const auto &[tag, x] : m.nodes)
        {
          const double r     = std::hypot(x.x(), x.y());
          const double a     = std::abs(std::remainder(std::atan2(x.y(), x.x()) - centre, 2 * pi));
          double      &r_max = a > 2 * pitch + twist ? r_far : r_near;
          r_max              = std::max(r_max, r);
        }
      EXPECT_LT(r_far, gear->root_radius * (1 + 1e-9)) << beta;
      EXPECT_NEAR(r_near / gear->tip_radius, 1, 1e-3) << beta;
      for (int i = 0; i < 3; ++i)
        EXPECT_TRUE(m.group_nodes.count(boundary::flank(i, FlankSide::drive))) << i;
    }
}

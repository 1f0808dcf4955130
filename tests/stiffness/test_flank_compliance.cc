// The flank compliance table: bilinear interpolation is exact on bilinear data, reading it
// following the load keeps a kinked kernel's peak, teeth outside the grid are refused, and a
// member that behaves like a half-space leaves no structural part.
#include "stiffness/flank_compliance.h"
#include "tests/fzg_c_pair.h"
#include "tests/seed_bevel_pair.h"

#include <gtest/gtest.h>

#include <random>

using namespace gearkit;

TEST(FlankCompliance, BilinearDataInterpolatedExactly)
{
  const auto                 gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const InvoluteMemberFlanks flanks(gear);
  for (const bool graded : {false, true})
    {
      FlankGridSpec spec;
      spec.teeth  = {15, 0, 1};
      spec.graded = graded;
      FlankCompliance table(flanks, spec);
      const auto     &pts = table.points();
      ASSERT_EQ(pts.size(), 3u * 7 * 7);
      auto f = [](int tooth, double u, double v) {
        return (1 + tooth) * (2 + 3 * u) * (1 - 40 * v);
      };
      Eigen::MatrixXd S(pts.size(), pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i)
        for (std::size_t j = 0; j < pts.size(); ++j)
          S(j, i) =
              f(pts[i].tooth, pts[i].u, pts[i].v) * f(pts[j].tooth, pts[j].u, pts[j].v) * 1e-9;
      table.set(S);
      const FlankDomain d = flanks.flank(0, FlankSide::drive).domain();
      for (double a : {0.13, 0.5, 0.91})
        {
          const double u        = d.u_min + a * (d.u_max - d.u_min),
                       v        = d.v_min + (1 - a) * (d.v_max - d.v_min);
          const double expected = f(1, u, v) * f(15, u, v) * 1e-9;
          EXPECT_NEAR(table(1, u, v, 15, u, v), expected, 1e-12 * std::abs(expected));
        }
      EXPECT_THROW(table(5, d.u_min, 0, 0, d.u_min, 0), InputError);
      // graded (Chebyshev-Lobatto, 7 points): the first face interval (1 - cos(pi / 6)) / 2 of
      // the range, the middle ones (cos(pi / 2) - cos(2 pi / 3)) / 2 = 1/4; equal: 1/6 each
      const double first = pts[1].v - pts[0].v, middle = pts[4].v - pts[3].v;
      EXPECT_NEAR(first / middle, graded ? (1 - std::cos(pi / 6)) / 2 / 0.25 : 1.0, 1e-9);
    }
}

TEST(FlankCompliance, FollowingTheLoadKeepsThePeakAtTheLoad)
{
  // A kernel with a kink at the load, exp(-|du| / L_u - |dv| / L_v) in the flank parameters: at
  // the grid points both readings are exact; between them, reading the load's own flank
  // bilinearly cuts the peak (self term below 1), following the load keeps it (exactly 1);
  // across teeth both read alike.
  const auto                   gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const InvoluteMemberFlanks   flanks(gear);
  const FlankDomain            d  = flanks.flank(0, FlankSide::drive).domain();
  const double                 Lu = (d.u_max - d.u_min) / 4, Lv = (d.v_max - d.v_min) / 4;
  std::vector<FlankCompliance> tables;
  for (const bool follow : {false, true})
    {
      FlankGridSpec spec;
      spec.teeth = {0, 1}, spec.graded = false, spec.follow_load = follow;
      tables.emplace_back(flanks, spec);
      const auto     &pts = tables.back().points();
      Eigen::MatrixXd S(pts.size(), pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i)
        for (std::size_t j = 0; j < pts.size(); ++j)
          S(j, i) =
              std::exp(-std::abs(pts[i].u - pts[j].u) / Lu - std::abs(pts[i].v - pts[j].v) / Lv) *
              (pts[i].tooth == pts[j].tooth ? 1 : 0.5);
      tables.back().set(S);
    }
  const auto &pts = tables[0].points();
  for (const std::size_t k : {std::size_t(0), std::size_t(9), std::size_t(24)})
    for (const FlankCompliance &t : tables)
      EXPECT_NEAR(t(0, pts[k].u, pts[k].v, 0, pts[k].u, pts[k].v), 1, 1e-12) << k;
  // midway between grid points (7 x 7, equally spaced)
  const double u = d.u_min + 0.02 * (d.u_max - d.u_min) + 0.5 / 6 * 0.96 * (d.u_max - d.u_min);
  const double v = d.v_min + 0.02 * (d.v_max - d.v_min) + 2.5 / 6 * 0.96 * (d.v_max - d.v_min);
  EXPECT_LT(tables[0](0, u, v, 0, u, v), 0.95);
  EXPECT_NEAR(tables[1](0, u, v, 0, u, v), 1, 1e-12);
  EXPECT_NEAR(tables[1](1, u, v, 0, u, v), tables[0](1, u, v, 0, u, v), 1e-15);
}

// The matrix over all the cells of a position (each point's weights found once) holds the same
// numbers as reading the table pair by pair, bit for bit: on every tooth, with a cyclic tooth
// (read for teeth anywhere on the gear, refused beyond its reach) and following the load.
TEST(FlankCompliance, MatrixOverAllPointsEqualsThePairs)
{
  const auto                             gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const InvoluteMemberFlanks             flanks(gear);
  const FlankDomain                      d = flanks.flank(0, FlankSide::drive).domain();
  std::mt19937                           random(3);
  std::uniform_real_distribution<double> unit(-0.05, 1.05); // some just beyond the grid
  for (const int variant : {0, 1, 2})
    {
      FlankGridSpec spec;
      spec.teeth = {15, 0, 1};
      if (variant == 1)
        spec.cyclic_tooth = 0, spec.cyclic_reach = 1;
      spec.follow_load = variant == 2;
      FlankCompliance table(flanks, spec);
      Eigen::MatrixXd S(table.points().size(), table.load_points().size());
      for (Eigen::Index k = 0; k < S.size(); ++k)
        S.data()[k] = 1e-10 * (1 + unit(random));
      table.set(S);
      const std::vector<int> teeth =
          variant == 1 ? std::vector<int>{7, 8} : std::vector<int>{15, 0, 1};
      std::vector<FlankCompliance::Location> at;
      for (int k = 0; k < 12; ++k)
        at.push_back({teeth[std::size_t(k) % teeth.size()],
                      d.u_min + unit(random) * (d.u_max - d.u_min),
                      d.v_min + unit(random) * (d.v_max - d.v_min)});
      const Eigen::MatrixXd M = table.matrix(at);
      ASSERT_EQ(M.rows(), 12);
      for (std::size_t i = 0; i < at.size(); ++i)
        for (std::size_t j = 0; j < at.size(); ++j)
          EXPECT_EQ(M(Eigen::Index(j), Eigen::Index(i)),
                    table(at[i].tooth, at[i].u, at[i].v, at[j].tooth, at[j].u, at[j].v))
              << variant << ": " << i << " " << j;
      if (variant == 1)
        {
          at.push_back({9, d.u_min, d.v_min}); // two teeth from tooth 7: beyond the reach
          EXPECT_THROW(table.matrix(at), InputError);
        }
    }
}

TEST(FlankCompliance, HalfSpaceMemberHasNoStructuralPart)
{
  // Spur and helical flanks (responses off the normal line on helical flanks), with different
  // depths per point: the subtraction matches the half-space response wherever it is read.
  for (double helix : {0.0, 0.35})
    {
      InvoluteGearData data           = test_data::fzg_c_pair().first;
      data.helix_angle                = helix;
      const auto                 gear = InvoluteGear::create(data);
      const InvoluteMemberFlanks flanks(gear);
      FlankGridSpec              spec;
      spec.teeth = {0};
      spec.n_u = spec.n_v = 4;
      FlankCompliance     table(flanks, spec);
      const Material      steel{210e9, 0.3};
      std::vector<double> depths;
      for (std::size_t i = 0; i < table.points().size(); ++i)
        depths.push_back(1e-3 * (1 + 0.25 * double(i % 3)));
      // a "member" whose response is the Boussinesq field of each load in its own tangent plane
      const ElasticResponse half_space = [&](const std::vector<FlankLoad>             &loads,
                                             const std::vector<std::pair<Vec3, Vec3>> &responses) {
        Eigen::MatrixXd D(responses.size(), loads.size());
        for (std::size_t i = 0; i < loads.size(); ++i)
          for (std::size_t j = 0; j < responses.size(); ++j)
            {
              const Vec3   n = -loads[i].direction; // outward
              const Vec3   d = responses[j].first - loads[i].point;
              const double z = -d.dot(n);
              D(j, i) = point_load_displacement((d + z * n).norm(), std::max(z, 0.0), 1.0, steel);
            }
        return D;
      };
      fill_structural_compliance(table, half_space, depths, steel);
      EXPECT_LT(table.matrix().cwiseAbs().maxCoeff(), 1e-25) << helix;
      // each response lies its depth below its own tangent plane
      for (std::size_t i = 0; i < table.points().size(); ++i)
        EXPECT_NEAR(-response_offset(table.points()[i]).dot(table.points()[i].normal), 1.0, 1e-12);
    }
}

TEST(FlankCompliance, DiskLoadAtDepthAgainstBruteForce)
{
  // The unit force spread over a disk of radius R, seen at depth z >= 2 R: the quadrature of
  // disk_load_displacement against a fine Cartesian sum, and the point force in the limit.
  const Material steel{206e9, 0.3};
  const double   R = 1e-3;
  for (const auto &[r, z] : {std::pair{0.0, 2e-3}, std::pair{1.5e-3, 3e-3}, std::pair{4e-3, 2e-3}})
    {
      const int n     = 400;
      double    sum   = 0;
      int       count = 0;
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k)
          {
            const double x = -R + (i + 0.5) * 2 * R / n, y = -R + (k + 0.5) * 2 * R / n;
            if (x * x + y * y <= R * R)
              sum += point_load_displacement(std::hypot(r - x, y), z, 1.0, steel), ++count;
          }
      EXPECT_NEAR(disk_load_displacement(r, z, R, steel) / (sum / count), 1, 2e-4) << r << " " << z;
      // under its centre the disk displaces the depth less than the point force does
      if (r == 0)
        {
          EXPECT_LT(disk_load_displacement(r, z, R, steel),
                    point_load_displacement(r, z, 1.0, steel));
        }
    }
  EXPECT_EQ(disk_load_displacement(1e-3, 2e-3, 0, steel),
            point_load_displacement(1e-3, 2e-3, 1.0, steel));
}

TEST(FlankCompliance, SpiralBevelResponsesReadAcrossTheConeElement)
{
  // On a cone the face runs along the pitch cone's element, not the axis: responses are read
  // along the part of the inward normal across it (else they would leave the face at the toe
  // and heel), and the theoretical flank parameters come back from the rotational projection.
  const BevelMemberFlanks member(conjugate_cuts(test_data::seed_bevel_design()).first);
  FlankGridSpec           spec;
  spec.teeth = {0, 7};
  spec.n_u = 5, spec.n_v = 6;
  const FlankCompliance table(member, spec);
  const double          gamma = member.tooth_flank(FlankSide::drive).blank_data().pitch_angle;
  for (const FlankCompliance::Point &p : table.points())
    {
      const Vec3 offset = response_offset(p);
      EXPECT_NEAR(offset.dot(p.face_direction), 0, 1e-12);
      EXPECT_NEAR(-offset.dot(p.normal), 1, 1e-12);
      // the element: at the angle gamma to the axis, in the point's axial plane
      EXPECT_NEAR(p.face_direction.z(), std::cos(gamma), 1e-12);
      EXPECT_NEAR(p.face_direction.cross(Vec3::UnitZ()).dot(p.position), 0, 1e-12);
      const auto [u, v] = member.rotational_parameters(p.position);
      EXPECT_NEAR(u, p.u, 1e-12);
      EXPECT_NEAR(v, p.v, 1e-12);
    }
}

TEST(FlankCompliance, FaceGridPointsFromTheFaceWidth)
{
  // 1 + ceil(2 b / m), at least 7, at most 25: the middle intervals of the graded grid about a
  // module (pi / (2 (n - 1)) b <= m)
  EXPECT_EQ(face_grid_points(20e-3, 2e-3), 21);      // 62/62 spur: b = 10 m
  EXPECT_EQ(face_grid_points(14e-3, 4.5e-3), 8);     // FZG C: b = 3.1 m
  EXPECT_EQ(face_grid_points(19e-3, 2.2423e-3), 18); // seed bevel: b = 8.5 m_mn
  EXPECT_EQ(face_grid_points(4e-3, 4e-3), 7);
  EXPECT_EQ(face_grid_points(100e-3, 8e-3), 25);
  for (double b : {2e-3, 7e-3, 15e-3, 40e-3})
    {
      const int n = face_grid_points(b, 2e-3);
      if (n > 7 && n < 25)
        {
          EXPECT_LE(pi / (2 * (n - 1)) * b, 2e-3 * 1.0001) << b;
        }
    }
  EXPECT_THROW(face_grid_points(0, 2e-3), InputError);
  EXPECT_THROW(face_grid_points(20e-3, -1), InputError);
}

// The flank compliance table: bilinear interpolation is exact on bilinear data, teeth outside
// the grid are refused, and a member that behaves like a half-space leaves no structural part.
#include "../fzg_c_pair.h"
#include "flank_compliance.h"

#include <gtest/gtest.h>

using namespace gearkit;

TEST(FlankCompliance, BilinearDataInterpolatedExactly)
{
  const auto gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const InvoluteMemberFlanks flanks(gear);
  FlankGridSpec spec;
  spec.teeth = {15, 0, 1};
  FlankCompliance table(flanks, spec);
  const auto &pts = table.points();
  ASSERT_EQ(pts.size(), 3u * 7 * 7);
  auto f = [](int tooth, double u, double v) { return (1 + tooth) * (2 + 3 * u) * (1 - 40 * v); };
  Eigen::MatrixXd S(pts.size(), pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = 0; j < pts.size(); ++j)
      S(j, i) = f(pts[i].tooth, pts[i].u, pts[i].v) * f(pts[j].tooth, pts[j].u, pts[j].v) * 1e-9;
  table.set(S);
  const FlankDomain d = flanks.flank(0, FlankSide::drive).domain();
  for (double a : {0.13, 0.5, 0.91})
    {
      const double u = d.u_min + a * (d.u_max - d.u_min), v = d.v_min + (1 - a) * (d.v_max - d.v_min);
      const double expected = f(1, u, v) * f(15, u, v) * 1e-9;
      EXPECT_NEAR(table(1, u, v, 15, u, v), expected, 1e-12 * std::abs(expected));
    }
  EXPECT_THROW(table(5, d.u_min, 0, 0, d.u_min, 0), InputError);
}

TEST(FlankCompliance, HalfSpaceMemberHasNoStructuralPart)
{
  const auto gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const InvoluteMemberFlanks flanks(gear);
  FlankGridSpec spec;
  spec.teeth = {0};
  spec.n_u = spec.n_v = 4;
  FlankCompliance table(flanks, spec);
  const Material steel{210e9, 0.3};
  const double   depth = 1e-3;
  // a "member" whose response is the Boussinesq field of each load in its own tangent plane
  const ElasticResponse half_space = [&](const std::vector<FlankLoad> &loads,
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
  fill_structural_compliance(table, half_space, depth, steel);
  EXPECT_LT(table.matrix().cwiseAbs().maxCoeff(), 1e-25);
}

// The nanoflann point cloud behind every nearest-point query (flank guesses, paper-mode clouds)
// against brute force on random clouds (fixed seed), clustered and uniform, 2-D and 3-D.
#include "geometry/point_cloud.h"

#include <gtest/gtest.h>

#include <random>

using namespace gearkit;

namespace
{
template <int dim>
void
check_against_brute_force(std::size_t n_points, double cluster, unsigned seed)
{
  using Point = typename PointCloud<dim>::Point;
  std::mt19937_64                        rng(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::normal_distribution<double>       normal(0, cluster);
  auto                                   random_point = [&] {
    Point p;
    for (int d = 0; d < dim; ++d)
      p[d] = uniform(rng);
    return p;
  };
  PointCloud<dim> cloud;
  // a few tight clusters (like flank samples in a gear-sized box) plus uniform points
  std::vector<Point> centres;
  for (int c = 0; c < 5; ++c)
    centres.push_back(random_point());
  for (std::size_t i = 0; i < n_points; ++i)
    {
      Point p = random_point();
      if (i % 2 == 0)
        {
          p = centres[i % centres.size()];
          for (int d = 0; d < dim; ++d)
            p[d] += normal(rng);
        }
      cloud.points.push_back(p);
    }
  cloud.build();
  for (int q = 0; q < 2000; ++q)
    {
      const Point query =
          q % 2 ? random_point() : Point(cloud.points[q % n_points] + 1e-3 * random_point());
      std::size_t best = 0;
      double      d2   = HUGE_VAL;
      for (std::size_t i = 0; i < cloud.points.size(); ++i)
        if ((cloud.points[i] - query).squaredNorm() < d2)
          d2 = (cloud.points[i] - query).squaredNorm(), best = i;
      const auto [index, distance2] = cloud.nearest(query);
      // the same distance (ties between equidistant points may pick either index)
      EXPECT_DOUBLE_EQ(distance2, d2) << q;
      EXPECT_DOUBLE_EQ((cloud.points[index] - query).squaredNorm(), d2) << q;
      if (index != best)
        {
          EXPECT_EQ((cloud.points[index] - query).squaredNorm(),
                    (cloud.points[best] - query).squaredNorm());
        }
    }
}
} // namespace

TEST(PointCloud, NearestMatchesBruteForceIn3D)
{
  check_against_brute_force<3>(20000, 1e-2, 1);
  check_against_brute_force<3>(3, 1e-2, 2); // tiny cloud
}

TEST(PointCloud, NearestMatchesBruteForceIn2D) { check_against_brute_force<2>(5000, 1e-3, 3); }

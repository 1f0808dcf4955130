// A point cloud with a nanoflann KD-tree over it: the one adaptor behind every nearest-point
// query (first guesses on flank samples, the paper-mode point clouds).
#pragma once

#include <Eigen/Core>
#include <nanoflann.hpp>

#include <memory>
#include <vector>

namespace gearkit
{
template <int dim> class PointCloud
{
public:
  using Point = Eigen::Matrix<double, dim, 1>;
  std::vector<Point> points;

  /// Builds the tree over the current points (call once they are all in).
  void
  build()
  {
    tree = std::make_unique<Tree>(dim, *this);
  }
  /// Index of the nearest point and the squared distance to it.
  std::pair<std::size_t, double>
  nearest(const Point &q) const
  {
    std::size_t index = 0;
    double      d2    = 0;
    tree->knnSearch(q.data(), 1, &index, &d2);
    return {index, d2};
  }

  // nanoflann's dataset interface
  std::size_t
  kdtree_get_point_count() const
  {
    return points.size();
  }
  double
  kdtree_get_pt(std::size_t i, std::size_t d) const
  {
    return points[i][d];
  }
  template <class Box>
  bool
  kdtree_get_bbox(Box &) const
  {
    return false;
  }

private:
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>,
                                                   PointCloud, dim, std::size_t>;
  std::unique_ptr<Tree> tree;
};
} // namespace gearkit

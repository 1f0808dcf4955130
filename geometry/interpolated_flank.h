// A measured flank made continuous: the grid of measured points interpolated by the tensor-product
// cubic spline over the grid indices (a 4th-order scheme, error O(h^4) inside), with exact
// derivatives and normal. Parameters: u = profile index in [0, n_profile-1], v = face index in
// [0, n_face-1]. The interpolant cannot leave the measured boundary, so no point needs culling;
// beyond the grid it continues linearly (for Newton iterates that step outside).
//
// The spline is built once (Boost's cardinal cubic B-splines along both grid directions give the
// values, first and cross derivatives at every node); each grid cell is then the bicubic Hermite
// patch of its four corners, which is that same piecewise-bicubic C1 spline, evaluated in O(1).
#pragma once

#include "geometry/measured_flank.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace gearkit
{
class InterpolatedFlank : public Flank
{
public:
  /// Needs at least 5 x 5 points (the end derivatives use five-point one-sided differences).
  explicit InterpolatedFlank(const MeasuredFlank &flank);
  FlankPoint
  evaluate(double u, double v) const override;
  FlankDomain
  domain() const override;

private:
  int n_profile, n_face;
  /// Per node (row-major i * n_face + j) and coordinate: value, d/du, d/dv, d2/dudv.
  std::vector<std::array<Vec3, 4>> nodes;
  double                           orientation = 1; ///< makes the normal point out of the tooth
};
} // namespace gearkit

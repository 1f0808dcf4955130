// A measured flank made continuous: the grid of measured points interpolated by tensor-product
// cubic B-splines over the grid indices (a 4th-order scheme, error O(h^4) inside), with exact
// derivatives of the interpolant and its normal. Parameters: u = profile index in [0, n_profile-1],
// v = face index in [0, n_face-1]; the interpolant cannot leave the measured boundary, so no
// point needs culling.
#pragma once

#include "measured_flank.h"

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>

#include <array>
#include <vector>

namespace gearkit
{
class InterpolatedFlank : public Flank
{
public:
  /// Needs at least 5 x 5 points (the end derivatives are estimated from the data).
  explicit InterpolatedFlank(const MeasuredFlank &flank);
  FlankPoint
  evaluate(double u, double v) const override;
  FlankDomain
  domain() const override;

private:
  using Spline = boost::math::interpolators::cardinal_cubic_b_spline<double>;
  int                                n_profile, n_face;
  std::array<std::vector<Spline>, 3> rows; ///< per coordinate, one spline in v per profile row
  double                             orientation = 1; ///< makes the normal point out of the tooth
};
} // namespace gearkit

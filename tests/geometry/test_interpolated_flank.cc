// Interpolated measured flanks: a 4th-order scheme, checked by its convergence rate on an
// involute flank sampled by a virtual CMM.
#include "geometry/interpolated_flank.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

namespace
{
// Largest distance between the interpolant and the exact flank at off-grid parameters.
double
interpolation_error(int n_profile, int n_face)
{
  InvoluteGearData d;
  d.teeth              = 23;
  d.normal_module      = 3e-3;
  d.helix_angle        = 15 * pi / 180;
  d.face_width         = 20e-3;
  const auto        g  = InvoluteGear::create(d);
  const auto        m  = virtual_cmm(*g, "pinion", n_profile, n_face, 0, {2}, false);
  const auto        f  = g->flank(2, FlankSide::drive);
  const auto        df = f.domain();
  InterpolatedFlank s(m.flanks.at(0));
  double            worst = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      {
        const double a = (i + 0.37) / 40, b = (j + 0.61) / 40; // fractions of the ranges
        const Vec3   p = s.evaluate(a * (n_profile - 1), b * (n_face - 1)).position;
        const Vec3   q =
            f.evaluate(df.u_min + a * (df.u_max - df.u_min), df.v_min + b * (df.v_max - df.v_min))
                .position;
        worst = std::max(worst, (p - q).norm());
      }
  return worst;
}
} // namespace

TEST(InterpolatedFlank, ConvergesAtFourthOrder)
{
  // Grid spacing halved in both directions: the error must fall by ~2^4 (rate > 3.5; the
  // end-derivative estimates are of high order too).
  const double coarse = interpolation_error(9, 29), fine = interpolation_error(17, 57);
  const double rate = std::log2(coarse / fine);
  EXPECT_GT(rate, 3.5) << coarse << " " << fine;
  EXPECT_LT(coarse, 1e-7); // the seed's 9 x 29 grid: well below the 1 um CMM accuracy
}

TEST(InterpolatedFlank, NormalIsOutwardAndOrthogonal)
{
  InvoluteGearData d;
  d.teeth         = 30;
  d.normal_module = 2e-3;
  const auto g    = InvoluteGear::create(d);
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      const auto        m = virtual_cmm(*g, "gear", 9, 29, 0, {5}, true);
      InterpolatedFlank s(m.flanks.at(side == FlankSide::drive ? 0 : 1));
      const FlankPoint  p = s.evaluate(3.3, 11.7);
      EXPECT_LT(std::abs(p.normal.dot(p.d_du.normalized())), 1e-12);
      EXPECT_LT(std::abs(p.normal.dot(p.d_dv.normalized())), 1e-12);
      const Vec3 exact = g->flank(5, side).evaluate(0.5, 0).normal; // nearby, same orientation
      EXPECT_GT(p.normal.dot(exact), 0.9);
    }
  MeasuredFlank tiny;
  tiny.n_profile = 4;
  tiny.n_face    = 9;
  tiny.points.assign(36, Vec3::Zero());
  EXPECT_THROW(InterpolatedFlank{tiny}, InputError);
}

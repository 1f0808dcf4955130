// Contact cells of a spur pair: perfect involutes have their normals along the line of action
// (every cell's moment arm is the pinion base radius), contact lines across the whole face, and
// gaps across the line that open with the relative curvature of the two involutes.
#include "stiffness/contact_cells.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

using namespace gearkit;

TEST(ContactCells, SpurPairLeversGapsAndExtent)
{
  const auto [pd, gd]      = test_data::fzg_c_pair();
  const auto        pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
  const double      a     = working_centre_distance(*pinion, *gear);
  const double      alpha = working_pressure_angle(*pinion, *gear);
  const UnloadedTca tca(pinion, gear, a);
  const double      mesh = 2 * pi / pd.teeth;
  for (double phase : {0.1, 0.5})
    {
      const TcaPosition  pos = tca.at(phase * mesh);
      ContactCellOptions o;
      const auto         cells = contact_cells(tca, pos, o);
      ASSERT_FALSE(cells.empty());
      int    touching_cells  = 0;
      double worst_curvature = 0;
      for (const ContactCell &c : cells)
        {
          EXPECT_NEAR(c.lever, pinion->base_radius, 1e-9 * pinion->base_radius);
          EXPECT_NEAR(c.dt * o.cells_along, pd.face_width, 1e-9);
          EXPECT_GE(c.gap, 0);
          const PairContact &p = pos.pairs[c.pair];
          if (p.separation > 0)
            continue;
          // relative curvature of two involutes at roll lengths rho1, rho2 along the line of
          // action: 1/rho1 + 1/rho2; the gap across the line is k s^2 / 2 (to O(s^3))
          const Vec3   r1   = p.position;
          const double rho1 = std::sqrt(std::max(
              0.0, r1.head<2>().squaredNorm() - pinion->base_radius * pinion->base_radius));
          const double rho2 = a * std::sin(alpha) - rho1;
          const double k    = 1 / rho1 + 1 / rho2;
          if (std::abs(c.s) < 0.2e-3)
            worst_curvature = std::max(worst_curvature,
                                       std::abs(c.gap - k * c.s * c.s / 2) / (k * c.s * c.s / 2));
          if (std::abs(c.s) < c.ds / 2) // the middle row (odd count) lies on the contact line
            {
              ++touching_cells;
              EXPECT_LT(c.gap, 1e-10);
            }
        }
      EXPECT_LT(worst_curvature, 0.03) << phase;
      EXPECT_EQ(touching_cells % o.cells_along, 0);
      EXPECT_GE(touching_cells, o.cells_along);
    }
}

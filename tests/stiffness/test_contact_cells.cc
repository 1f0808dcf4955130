// Contact cells of a spur pair: perfect involutes have their normals along the line of action
// (every cell's moment arm is the pinion base radius), contact lines across the whole face, and
// gaps across the line that open with the relative curvature of the two involutes.
#include "stiffness/contact_cells.h"
#include "tests/fzg_c_pair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace gearkit;

TEST(ContactCells, SpurPairLeversGapsAndExtent)
{
  const auto [pd, gd]      = test_data::fzg_c_pair();
  const auto        pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
  const double      a     = working_centre_distance(*pinion, *gear);
  const double      alpha = working_pressure_angle(*pinion, *gear);
  const UnloadedTca tca(pinion, gear, a);
  const double      mesh = 2 * pi / pd.teeth;
  for (const auto [phase, grading] : {std::pair{0.1, 0.0}, {0.5, 0.0}, {0.1, 1.0}, {0.5, 1.0}})
    {
      const TcaPosition  pos = tca.at(phase * mesh);
      ContactCellOptions o;
      o.along_grading  = grading;
      const auto cells = contact_cells(tca, pos, o);
      ASSERT_FALSE(cells.empty());
      int    touching_cells  = 0;
      double worst_curvature = 0;
      // the columns span the face, uniform or graded by cosine spacing towards both face ends
      // (every pair's line, touching or not, runs from face end to face end at no gap)
      std::map<int, double> length; // pair -> sum of its cells' dt
      for (const ContactCell &c : cells)
        {
          EXPECT_NEAR(c.lever, pinion->base_radius, 1e-9 * pinion->base_radius);
          const double xi0 = double(c.column) / o.cells_along, xi1 = xi0 + 1.0 / o.cells_along;
          const double cosine = (std::cos(pi * xi0) - std::cos(pi * xi1)) / 2;
          EXPECT_NEAR(c.dt, pd.face_width * (grading * cosine + (1 - grading) * (xi1 - xi0)),
                      1e-12);
          length[c.pair] += c.dt / o.cells_across;
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
      EXPECT_LT(worst_curvature, 0.03) << phase << ", grading " << grading;
      for (const auto &[pair, l] : length)
        EXPECT_NEAR(l, pd.face_width, 1e-12) << pair;
      EXPECT_EQ(touching_cells % o.cells_along, 0);
      EXPECT_GE(touching_cells, o.cells_along);
    }
}

// As a pair's contact line runs onto the pinion's tip, the band of cells across it is cut at the
// flank's edge: the zone's area falls continuously with the pinion angle (rows kept or dropped
// whole by their centres made steps of 1/17 of it, a row at a time), stays on the flank and
// keeps its number of cells (a contact at the corner keeps its resolution across).
TEST(ContactCells, ZoneCutAtTheTipContinuously)
{
  const auto [pd, gd]             = test_data::fzg_c_pair();
  const auto               pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
  const UnloadedTca        tca(pinion, gear, working_centre_distance(*pinion, *gear));
  const double             mesh = 2 * pi / pd.teeth;
  const ContactCellOptions o;
  // the zone's area of the pair of pinion tooth 0 [m^2], and its outermost cell's radius
  auto zone = [&](double phi, double *outer_radius = nullptr) {
    double area = 0;
    int    n    = 0;
    for (const ContactCell &c : contact_cells(tca, tca.at(phi), o))
      if (c.pinion_tooth == 0)
        {
          area += c.ds * c.dt, ++n;
          if (outer_radius)
            *outer_radius = std::max(*outer_radius, c.position.head<2>().norm());
        }
    EXPECT_TRUE(n == 0 || n == o.cells_across * o.cells_along) << n;
    return area;
  };
  // coarse: the first angle where the zone is cut short by the tip, after it was whole
  const int coarse = 120;
  double    full = 0, first_cut = -1;
  for (int k = 0; k < coarse && first_cut < 0; ++k)
    {
      const double phi = 2 * mesh * k / coarse, a = zone(phi);
      if (a < 0.95 * full)
        first_cut = phi;
      full = std::max(full, a);
    }
  ASSERT_GT(first_cut, 0);
  // fine: a zone half-width (~0.4 mm on the line of action) rolls over in ~40 steps
  const double step     = 0.01e-3 / pinion->base_radius;
  double       previous = zone(first_cut - 2 * mesh / coarse), largest_step = 0, least = full;
  for (int k = 1; k <= 200; ++k)
    {
      double       r = 0;
      const double a = zone(first_cut - 2 * mesh / coarse + k * step, &r);
      if (a == 0)
        break;
      largest_step = std::max(largest_step, std::abs(a - previous));
      least        = std::min(least, a);
      previous     = a;
      EXPECT_LE(r, pinion->tip_radius * (1 + 1e-9));
    }
  EXPECT_LT(least, 0.5 * full);          // the sweep does run the zone off the tip
  EXPECT_LT(largest_step, 0.01 * full);  // whole rows would be 1/17 = 0.059
  EXPECT_GT(largest_step, 0.001 * full); // and it does move
}

// A zone as wide as a study's widened one (a 60 um band, 51 cells across) reaches past the
// pinion's active profile towards its base circle, where the projection onto the flank folds:
// every cell still lies on its own flank point - along each column across the line the pinion's
// profile parameter runs one way - and every column keeps its cells across (its cut shares
// them). A projection taken before it had settled once put cells of a tip contact's column back
// onto points near the contact, with small gaps: spurious load carriers (e_L 3 % low).
TEST(ContactCells, WideZoneCellsLieOnDistinctFlankPoints)
{
  const auto [pd, gd]       = test_data::fzg_c_pair();
  const auto         pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
  const UnloadedTca  tca(pinion, gear, working_centre_distance(*pinion, *gear));
  const double       mesh = 2 * pi / pd.teeth;
  ContactCellOptions o;
  o.gap_band = 60e-6, o.cells_across = 51;
  int columns = 0;
  for (int k = 0; k < 40; ++k)
    {
      const double                                                          phi = mesh * k / 40;
      std::map<std::pair<int, int>, std::vector<std::pair<double, double>>> column; // s, u1
      for (const ContactCell &c : contact_cells(tca, tca.at(phi), o))
        column[{c.pair, c.column}].push_back({c.s, c.u1});
      for (auto &[key, cells] : column)
        {
          ++columns;
          EXPECT_EQ(int(cells.size()), o.cells_across) << "phi " << phi << ", pair " << key.first;
          std::sort(cells.begin(), cells.end());
          int rising = 0, falling = 0;
          for (std::size_t j = 1; j < cells.size(); ++j)
            (cells[j].second > cells[j - 1].second ? rising : falling) += 1;
          EXPECT_TRUE(rising == 0 || falling == 0)
              << "phi " << phi << ", pair " << key.first << ", column " << key.second << ": "
              << rising << " up, " << falling << " down";
        }
    }
  EXPECT_GT(columns, 40 * o.cells_along);
}

// Reference mode on the Hertz problem: two cylinder slices meshed with gmsh (plane strain),
// deal.II/PETSc compliance of strip cells along the contact on both bodies (no half-space
// solution anywhere), the contact problem solved to complementarity. Half-width and peak
// pressure against reference-data.md section 5 within 3 %.
#include "meshes/cylinder_slice.h"
#include "stiffness/contact_solver.h"
#include "stiffness/elastic_segment.h"
#include "stiffness/hertz_reference.h"

#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <filesystem>

using namespace gearkit;

TEST(HertzReference, CylindersHalfWidthAndPeakPressure)
{
  HertzCase c;
  c.element_size        = c.half_width / 8;
  const std::string dir = std::filesystem::temp_directory_path().string();
  const HertzResult r   = solve_hertz_reference(c, dir);
  EXPECT_NEAR(r.half_width / c.half_width, 1, 0.03);
  EXPECT_NEAR(r.peak_pressure / r.exact_peak_pressure, 1, 0.03);
  EXPECT_NEAR(r.total_force / r.applied_force, 1, 1e-9);
  EXPECT_GT(r.active_cells, 8);
}

// The Hertz line contact of two cylinders solved in reference mode: both bodies meshed (gmsh
// plane-strain slices graded to the contact line), their compliance at strip cells along the
// contact computed by finite elements alone (uniform strip tractions, surface displacements),
// and the contact problem solved to complementarity. The validation of the finite-element
// contact path against the exact solution (reference-data.md section 5).
#pragma once

#include "stiffness/half_space.h"

#include <string>

namespace gearkit
{
struct HertzCase
{
  double   radius_upper = 10e-3, radius_lower = 15e-3; ///< R1, R2 [m]
  Material material;                                   ///< both bodies
  double   half_width   = 0.2e-3; ///< the exact Hertz half-width a sets the load [m]
  double   element_size = 25e-6;  ///< at the contact line [m]
  int      degree       = 2;
  double   cell_size    = 0;   ///< strip width [m]; 0: the element size
  double   zone         = 1.5; ///< cells cover |x| <= zone a
};

struct HertzResult
{
  double      applied_force = 0, total_force = 0; ///< per slice [N]
  double      half_width = 0, peak_pressure = 0;  ///< fitted p^2 = p0^2 (1 - x^2 / a^2) [m, Pa]
  double      exact_peak_pressure = 0;            ///< 2 q / (pi a) [Pa]
  int         active_cells = 0, cells = 0;
  std::size_t dofs    = 0; ///< both bodies
  double      seconds = 0;
};

/// Meshes both slices into `work_directory` and solves. Throws InputError for bad sizes.
HertzResult
solve_hertz_reference(const HertzCase &c, const std::string &work_directory);
} // namespace gearkit

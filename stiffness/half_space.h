// Elastic half-space (Boussinesq) solutions: the local part of the contact compliance, which a
// finite-element mesh cannot resolve near a concentrated load (Johnson, Contact Mechanics, ch. 3).
// All SI. "Compliance" factors are (1 - nu^2) / (pi E) per body; for two bodies in contact they
// add: 1 / (pi E*), 1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2.
#pragma once

namespace gearkit
{
struct Material
{
  double youngs_modulus = 210e9; ///< E [Pa]
  double poisson_ratio  = 0.3;   ///< nu
};

/// Plane-strain modulus of the pair, E* with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [Pa].
double
contact_modulus(const Material &a, const Material &b);

/// Normal surface displacement at (x, y) of a half-space of contact modulus E* (one body:
/// E / (1 - nu^2); two bodies: E* of the pair) under a uniform pressure of total force F over
/// the rectangle |x| <= a, |y| <= b (Love 1929; Johnson eq. 3.25), written with asinh so that
/// no logarithm of a difference loses digits far from the rectangle [m].
double
rectangle_displacement(double x, double y, double a, double b, double force, double modulus);

/// Displacement along the load of a point at depth z >= 0 and radial distance r from a normal
/// point force F on the surface of a half-space (E, nu), Boussinesq:
/// u_z = F (1 + nu) / (2 pi E) (2 (1 - nu) / rho + z^2 / rho^3), rho = sqrt(r^2 + z^2) [m].
double
point_load_displacement(double r, double z, double force, const Material &material);
} // namespace gearkit

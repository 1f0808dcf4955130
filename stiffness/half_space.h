// Elastic half-space (Boussinesq) solutions: the local part of the contact compliance, which a
// finite-element mesh cannot resolve near a concentrated load (Johnson, Contact Mechanics, ch. 3).
// All SI. "Compliance" factors are (1 - nu^2) / (pi E) per body; for two bodies in contact they
// add: 1 / (pi E*), 1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2.
#pragma once

#include "base/types.h"

#include <Eigen/Core>

namespace gearkit
{
struct Material
{
  double youngs_modulus = 210e9; ///< E [Pa]
  double poisson_ratio  = 0.3;   ///< nu
};

/// Lamé's constants of the material: lambda = E nu / ((1 + nu) (1 - 2 nu)), mu = G = E / (2 (1 +
/// nu)).
struct Lame
{
  double lambda = 0, mu = 0;
};
Lame
lame(const Material &material);

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

/// A displacement field at a point: u [m] and its gradient, gradient(i, j) = du_i / dx_j.
struct DisplacementField
{
  Vec3            u        = Vec3::Zero();
  Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();
};

/// Boussinesq's whole field of a normal point force F at `origin` on the surface of a
/// half-space whose inward normal is `direction` (unit; the force pushes along it), at any
/// point x: in the frame (e_r, e_z = direction) u_r = F / (4 pi G) (r z / rho^3 - (1 - 2 nu)
/// r / (rho (rho + z))), u_z = F / (4 pi G) (z^2 / rho^3 + 2 (1 - nu) / rho) (Johnson eq.
/// 3.21), in Cartesian components (smooth through the load's axis). Singular at the origin and
/// on the ray outside the half-space opposite the force (rho + z = 0); x must avoid both.
DisplacementField
point_force_field(const Vec3 &x, const Vec3 &origin, const Vec3 &direction, double force,
                  const Material &material);

/// A smooth radial cut-off about a point: 1 within `inner`, 0 beyond `outer`, between them the
/// quintic step (second derivatives continuous); value, gradient and Hessian at x.
struct Cutoff
{
  double          value    = 0;
  Vec3            gradient = Vec3::Zero();
  Eigen::Matrix3d hessian  = Eigen::Matrix3d::Zero();
  /// Where chi is not constant (0 or 1): there chi u leaves a body force. Decided by where x
  /// lies (the constant parts have zero derivatives exactly), not by the value, which rounds to
  /// 1 or 0 just inside the step's ends, where the body force is small but not yet zero.
  bool
  varies() const
  {
    return !gradient.isZero(0) || !hessian.isZero(0);
  }
};
Cutoff
radial_cutoff(const Vec3 &x, const Vec3 &centre, double inner, double outer);

/// A smooth cut-off by elevation above the tangent plane of a point force at `centre` (its
/// inward normal `direction`, unit), seen from the force: 1 where x lies below the plane or at
/// most `from` above it, 0 from `to` on (angles in radians), between them the quintic step in
/// the sine of the elevation; value, gradient and Hessian at x (1 at the centre itself).
Cutoff
elevation_cutoff(const Vec3 &x, const Vec3 &centre, const Vec3 &direction, double from, double to);

/// The product of two cut-offs (value, gradient and Hessian by the product rule).
Cutoff
operator*(const Cutoff &a, const Cutoff &b);

/// The cut-off of a unit load's analytic near field: radial between `inner` and `outer`, and
/// by elevation between 30 and 60 degrees. Boussinesq's field is singular on the ray opposite
/// the force (rho + z = 0) and large near it; whatever of the body lies across the load's
/// tangent plane within 30 degrees of that ray (the next tooth across the gap, a tooth's
/// corner beyond a face end) gets none of it, wherever the sphere reaches, while near the load
/// (a smooth flank, the body below its tangent plane) the field is Boussinesq's own.
Cutoff
near_field_cutoff(const Vec3 &x, const Vec3 &centre, const Vec3 &direction, double inner,
                  double outer);

/// Stress of a displacement gradient in an isotropic body (E, nu): lambda tr(eps) I + 2 mu eps.
Eigen::Matrix3d
stress(const Eigen::Matrix3d &gradient, const Material &material);

/// The near field carried analytically, chi u with chi a cut-off and u the point force field,
/// and what it leaves to the finite elements: its traction sigma(chi u) n on a surface of
/// outward normal n, and the body force it needs, div sigma(chi u) (zero where chi is 1).
struct NearField
{
  Vec3 u        = Vec3::Zero();
  Vec3 traction = Vec3::Zero();
  Vec3 body     = Vec3::Zero();
};
NearField
cut_off_near_field(const DisplacementField &field, const Cutoff &chi, const Vec3 &normal,
                   const Material &material);
} // namespace gearkit

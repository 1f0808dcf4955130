// Mass properties of prismatic gear bodies from their transverse outline.
#pragma once

#include "geometry/types.h"

#include <vector>

namespace gearkit
{
/// Mass, polar moment of inertia (about the member axis) and diametral moment of inertia (about
/// a diameter through the centre of mass), in SI units.
struct MassProperties
{
  double mass              = 0; ///< [kg]
  double polar_inertia     = 0; ///< J_z [kg m^2]
  double diametral_inertia = 0; ///< [kg m^2]
  double volume            = 0; ///< [m^3]
};

/// Area integrals of a closed polygon (counter-clockwise gives positive area): A, int x dA,
/// int y dA, int x^2 dA, int y^2 dA. Exact for the polygon (Green's theorem).
struct AreaMoments
{
  double area = 0, first_x = 0, first_y = 0, second_xx = 0, second_yy = 0;
  double
  polar() const
  {
    return second_xx + second_yy;
  }
  AreaMoments &
  operator-=(const AreaMoments &o);
};

AreaMoments
polygon_moments(const std::vector<Vec2> &polygon);

/// Area moments of a full disc of radius R centred at the origin (exact).
AreaMoments
disc_moments(double radius);

/// Mass properties of a prism of constant section (area moments `section`), axial length b,
/// symmetric about z = 0, density rho. The diametral inertia uses the isotropic mean of the
/// section's second moments (exact for sections with three-fold or higher symmetry).
MassProperties
prism_mass_properties(const AreaMoments &section, double b, double rho);
} // namespace gearkit

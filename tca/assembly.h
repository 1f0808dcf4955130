// How a gear pair is assembled: the pinion turns about the global z axis through the origin; the
// gear's axis passes through (a, 0, 0), nominally parallel, with misalignments. Both members
// are described in their own frames (involute_gear.h); the gear frame is turned by pi + pi/z2 so
// that a gear tooth space faces pinion tooth 0 at zero rotation.
#pragma once

#include "types.h"

#include <Eigen/Geometry>

namespace gearkit
{
/// Assembly errors of a parallel-axis pair (SI: m, rad).
struct Misalignment
{
  double centre_distance_error = 0; ///< added to the nominal centre distance [m]
  /// Gear axis turned about the line of centres (x): crossing axes, the deviation of parallelism
  /// out of the plane of the axes (f_Sigma_beta).
  double crossing_angle = 0;
  /// Gear axis turned about the y axis: intersecting axes, inclination in the plane of the axes
  /// (f_Sigma_delta).
  double intersecting_angle = 0;
  double pinion_axial_shift = 0; ///< pinion moved along its axis [m]
  double gear_axial_shift   = 0; ///< gear moved along its axis [m]
};

/// Rigid placement of both members for a pinion rotation phi (counter-clockwise about +z) and a
/// gear rotation psi (in its driven sense, clockwise about its axis).
class Assembly
{
public:
  Assembly(double centre_distance, int gear_teeth, const Misalignment &m = {});

  /// Global position of a pinion-frame point at pinion rotation phi.
  Vec3
  pinion_to_global(const Vec3 &x, double phi) const;
  Vec3
  pinion_vector_to_global(const Vec3 &v, double phi) const;
  /// Global position of a gear-frame point at gear rotation psi.
  Vec3
  gear_to_global(const Vec3 &x, double psi) const;
  Vec3
  gear_vector_to_global(const Vec3 &v, double psi) const;
  /// Gear-frame coordinates, without the gear rotation, of a global point: Q = R0^T M^T (X - C);
  /// the gear point at rotation psi that lies at X is Rz(psi) Q.
  Vec3
  global_to_gear_unrotated(const Vec3 &X) const;
  /// The same for a direction (no translation).
  Vec3
  global_to_gear_unrotated_vector(const Vec3 &v) const;

  const Vec3 &
  gear_centre() const
  {
    return centre;
  }
  /// Gear axis direction (global).
  Vec3
  gear_axis() const
  {
    return orientation.col(2);
  }

private:
  Vec3            centre;
  Eigen::Matrix3d orientation; ///< M: misalignment rotation
  double          phase;       ///< pi + pi / z2
  double          pinion_shift;
  double          gear_shift;
};
} // namespace gearkit

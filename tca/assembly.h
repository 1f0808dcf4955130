// How a gear pair is assembled: the pinion turns about the global z axis through the origin; the
// gear's axis passes through (a, 0, 0), nominally parallel, with misalignments. Both members
// are described in their own frames (involute_gear.h); the gear frame is turned by pi + pi/z2 so
// that a gear tooth space faces pinion tooth 0 at zero rotation.
#pragma once

#include "geometry/types.h"

#include <Eigen/Geometry>

namespace gearkit
{
/// Assembly errors (SI: m, rad). For parallel axes the names say it; for bevel pairs (axes
/// intersecting at the apex, the origin) the intersecting angle is the shaft angle error
/// Delta gamma, the axial shifts are Delta A1 and Delta A2 and `offset` is the hypoid offset
/// Delta E.
struct Misalignment
{
  /// Gear axis moved along the common perpendicular of the axes (global y) [m].
  double offset                = 0;
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
  /// Parallel axes at the given centre distance: the gear axis through (a, 0, 0).
  Assembly(double centre_distance, int gear_teeth, const Misalignment &m = {});
  /// Intersecting axes (bevel pair): both apexes at the origin, the gear axis at the shaft angle
  /// to the pinion's in the x-z plane; the pitch cones touch along the element at the pinion's
  /// pitch angle on the +x side, where pinion tooth 0 and a gear tooth space face each other.
  static Assembly
  bevel(double shaft_angle, double pinion_pitch_angle, int gear_teeth, const Misalignment &m = {});

  /// The same assembly with the gear axis turned further about the gear centre: by `crossing`
  /// about the global x axis, then by `intersecting` about y (Misalignment's angles; for an
  /// aligned parallel-axis assembly this is Assembly(a, z2, {crossing, intersecting})).
  Assembly
  tilted(double crossing, double intersecting) const;

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

  /// Global position of the pinion frame's origin (the point its moment arms are taken about).
  Vec3
  pinion_centre() const
  {
    return Vec3(0, 0, pinion_shift);
  }

private:
  Assembly(const Vec3 &centre, const Eigen::Matrix3d &frame, double phase, const Misalignment &m);

  Vec3            centre;
  Eigen::Matrix3d orientation; ///< misalignment rotation times the gear's nominal frame
  double          phase;       ///< turns a gear tooth space to the mesh
  double          pinion_shift;
  double          gear_shift;
};

/// The centre distance a parallel-axis pair runs at: the distance of the gear axis from the
/// pinion axis in the pinion's middle transverse section z = 0 (where the gear centre of
/// Assembly(centre_distance, z2, m) lies), sqrt((a + Delta a)^2 + offset^2). The crossing and
/// intersecting angles turn the gear axis about that point: they change the contact along the
/// face (the local centre distance by z * intersecting angle, and to second order by the
/// crossing angle), not the centre distance of the middle section.
double
operating_centre_distance(double centre_distance, const Misalignment &m);

/// The misalignment of the pair once the gear has made the small rigid motion `motion` relative
/// to the pinion (the motion a static deflection of shafts and bearings gives, in the pinion's
/// frame): `m` (the one `assembly` was built with) plus the change. Turns of either member about
/// its own axis are transmission error, left to the contact analysis; the rest goes into
/// - parallel axes: centre distance error, offset, crossing and intersecting angles and the
///   gear's axial shift;
/// - intersecting axes (bevel): offset, shaft angle error (intersecting angle) and both axial
///   shifts.
/// `taken`, if given, receives the part of the motion the change represents (first order: the
/// change of the misalignment reproduces it exactly to first order in its size).
Misalignment
misalignment_after(const Assembly &assembly, const Misalignment &m, const RigidMotion &motion,
                   RigidMotion *taken = nullptr);
} // namespace gearkit

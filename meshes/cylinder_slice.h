// gmsh model of a plane-strain slice of a cylinder for Hertz line-contact validation: the half
// of the disc of radius R that faces the contact, the contact line at the origin, meshed with
// quadrilaterals graded toward the contact point and extruded by one layer of hexahedra of the
// given thickness (rollers on both faces make it plane strain).
//
// Frame: contact point at the origin, the cylinder's axis parallel to z through (0, +R) (or
// (0, -R) for the lower body), faces at z = 0 and z = thickness. Physical groups (boundary ids):
//   volume 1 "body"; surfaces 1 "contact" (the half circle), 2 "cut" (the diametral plane, where
//   the body is held or pushed), 3 "front" (z = 0), 4 "back" (z = thickness).
#pragma once

#include <string>

namespace gearkit
{
namespace cylinder_boundary
{
constexpr int contact = 1, cut = 2, front = 3, back = 4;
}

struct CylinderSliceOptions
{
  double radius           = 10e-3;  ///< R [m]
  bool   upper            = true;   ///< body above the contact plane (centre at +R) or below
  double contact_size     = 20e-6;  ///< element size at the contact point [m]
  double far_size         = 1e-3;   ///< element size far from it [m]
  double fine_distance    = 0.5e-3; ///< the contact size holds within this distance [m]
  double grading_distance = 3e-3;   ///< beyond it the size grows to the far size over this [m]
  double thickness        = 20e-6;  ///< slice thickness [m] (one element layer)
};

struct CylinderSliceInfo
{
  std::size_t hexahedra = 0, nodes = 0;
  double      analytic_volume = 0; ///< pi R^2 / 2 * thickness [m^3]
};

/// Writes the slice to `path` (.msh 4.1) and `path`.json (atomically). Throws InputError for
/// non-positive sizes or a contact size above the far size.
CylinderSliceInfo
write_cylinder_slice_mesh(const CylinderSliceOptions &options, const std::string &path);
} // namespace gearkit

#include "stiffness/iso6336.h"

#include "geometry/types.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace gearkit
{
IsoMeshStiffness
iso6336_mesh_stiffness(const IsoStiffnessInput &in)
{
  if (!(in.z1 >= 5 && in.z2 >= 5 && in.x1 >= -0.5 && in.x1 <= 2 && in.x2 >= -0.5 && in.x2 <= 2 &&
        in.transverse_contact_ratio > 0))
    throw InputError("ISO 6336 stiffness: needs z1, z2 >= 5 (external pair), x in [-0.5, 2] and "
                     "a positive transverse contact ratio");
  const double     cb = std::cos(in.base_helix_angle), c = std::cos(in.helix_angle);
  const double     zn1 = in.z1 / (cb * cb * c), zn2 = in.z2 / (cb * cb * c);
  const double     x1 = in.x1, x2 = in.x2;
  IsoMeshStiffness s;
  s.q_prime = 0.04723 + 0.15551 / zn1 + 0.25791 / zn2 - 0.00635 * x1 - 0.11654 * x1 / zn1 -
              0.00193 * x2 - 0.24188 * x2 / zn2 + 0.00529 * x1 * x1 + 0.00182 * x2 * x2;
  s.c_th                 = 1 / s.q_prime;
  const double alpha_deg = in.pressure_angle * 180 / pi;
  const double C_B       = (1 + 0.5 * (1.2 - in.dedendum_factor)) * (1 - 0.02 * (20 - alpha_deg));
  s.c_prime              = s.c_th * in.C_M * in.C_R * C_B * c;
  s.c_gamma_alpha        = s.c_prime * (0.75 * in.transverse_contact_ratio + 0.25);
  s.c_gamma_beta         = 0.85 * s.c_gamma_alpha;
  return s;
}

IsoPair
iso_pair(const InvoluteGear &pinion, const InvoluteGear &gear, double centre_distance)
{
  const ContactRatios ratios = contact_ratios(pinion, gear, centre_distance);
  IsoPair             p;
  IsoStiffnessInput  &iso = p.input;
  iso.z1 = pinion.teeth(), iso.z2 = gear.teeth();
  iso.x1 = pinion.data().profile_shift, iso.x2 = gear.data().profile_shift;
  iso.helix_angle              = pinion.data().helix_angle;
  iso.base_helix_angle         = pinion.base_helix_angle;
  iso.pressure_angle           = pinion.data().normal_pressure_angle;
  iso.dedendum_factor          = pinion.data().dedendum_factor;
  iso.transverse_contact_ratio = ratios.transverse;
  p.face_width                 = std::min(pinion.data().face_width, gear.data().face_width);
  p.overlap_ratio              = ratios.overlap;
  return p;
}

IsoPair
iso_pair(const BevelPairDesign &d)
{
  const VirtualCylindricalGears v = virtual_cylindrical_gears(d);
  IsoPair                       p;
  IsoStiffnessInput            &iso = p.input;
  iso.z1 = v.z1, iso.z2 = v.z2;
  iso.x1 = d.pinion_addendum - 1, iso.x2 = 1 - d.pinion_addendum;
  iso.helix_angle              = v.helix_angle;
  iso.base_helix_angle         = std::asin(std::sin(v.helix_angle) * std::cos(d.pressure_angle));
  iso.pressure_angle           = d.pressure_angle;
  iso.dedendum_factor          = 1 + d.clearance;
  iso.transverse_contact_ratio = v.transverse_contact_ratio;
  p.face_width                 = v.face_width;
  p.overlap_ratio              = v.overlap_ratio;
  return p;
}
} // namespace gearkit

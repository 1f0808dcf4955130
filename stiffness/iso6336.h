// Mesh stiffness after ISO 6336-1 method B (empirical): the single stiffness c' and the mesh
// stiffness c_gamma of a spur or helical pair, the standard's yardstick for the finite-element
// figures (reference-data.md section 3). Units as in the standard: N/(mm um).
#pragma once

#include "geometry/bevel_gear.h"
#include "geometry/involute_gear.h"

namespace gearkit
{
struct IsoMeshStiffness
{
  double q_prime       = 0; ///< minimum flexibility q' [mm um / N]
  double c_th          = 0; ///< theoretical single stiffness c'_th = 1 / q' [N/(mm um)]
  double c_prime       = 0; ///< single stiffness c' = c'_th C_M C_R C_B cos(beta)
  double c_gamma_alpha = 0; ///< c_gamma_alpha = c' (0.75 eps_alpha + 0.25)
  double c_gamma_beta  = 0; ///< c_gamma_beta = 0.85 c_gamma_alpha
};

struct IsoStiffnessInput
{
  double z1 = 0, z2 = 0;                  ///< tooth numbers (virtual ones may be fractional)
  double x1 = 0, x2 = 0;                  ///< profile shift coefficients
  double helix_angle              = 0;    ///< beta [rad]
  double base_helix_angle         = 0;    ///< beta_b [rad]
  double pressure_angle           = 0;    ///< alpha_n of the basic rack [rad]
  double dedendum_factor          = 1.25; ///< h_fP / m_n of the basic rack
  double transverse_contact_ratio = 0;    ///< eps_alpha
  double C_M                      = 0.8;  ///< correction factor (solid disc gears 0.8)
  double C_R                      = 1.0;  ///< gear blank factor (solid: 1)
};

/// ISO 6336-1 method B; throws InputError outside the standard's range (z >= 5, x in
/// [-0.5, 2], positive contact ratio).
IsoMeshStiffness
iso6336_mesh_stiffness(const IsoStiffnessInput &input);

/// The standard's input for a pair with the face width and contact ratios beside it: an
/// involute pair at centre distance a (common face width), or a bevel pair's virtual
/// cylindrical gears (ISO 10300-1; profile shifts h_a / m_mn - 1, dedendum 1 + clearance).
struct IsoPair
{
  IsoStiffnessInput input;
  double            face_width    = 0; ///< [m]
  double            overlap_ratio = 0; ///< eps_beta
};
IsoPair
iso_pair(const InvoluteGear &pinion, const InvoluteGear &gear, double centre_distance);
IsoPair
iso_pair(const BevelPairDesign &design);
} // namespace gearkit

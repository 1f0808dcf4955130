#include "stiffness/iso6336.h"

#include "geometry/types.h"

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
} // namespace gearkit

// ISO 6336-1 method B against the ISO/TR 6336-30 example (reference-data.md section 3).
#include "geometry/involute_gear.h"
#include "stiffness/iso6336.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

TEST(Iso6336, TechnicalReportExample)
{
  // mn 8 mm, z 17/103, x 0.145/0, beta 15.8 deg, alpha_n 20 deg: c'_th = 17.856, c' = 12.370,
  // c_gamma_alpha = 17.465, c_gamma_beta = 14.845 N/(mm um). The example's basic rack has
  // h_fP = 1.4 m_n (C_B = 0.9, which the c' above needs) and eps_alpha = 1.549.
  IsoStiffnessInput in;
  in.z1 = 17, in.z2 = 103, in.x1 = 0.145, in.x2 = 0;
  in.helix_angle              = 15.8 * pi / 180;
  in.pressure_angle           = 20 * pi / 180;
  const double alpha_t        = std::atan(std::tan(in.pressure_angle) / std::cos(in.helix_angle));
  in.base_helix_angle         = std::atan(std::tan(in.helix_angle) * std::cos(alpha_t));
  in.dedendum_factor          = 1.4;
  in.transverse_contact_ratio = (17.465 / 12.370 - 0.25) / 0.75;
  const IsoMeshStiffness s    = iso6336_mesh_stiffness(in);
  EXPECT_NEAR(s.c_th, 17.856, 0.001);
  EXPECT_NEAR(s.c_prime, 12.370, 0.001);
  EXPECT_NEAR(s.c_gamma_alpha, 17.465, 0.002);
  EXPECT_NEAR(s.c_gamma_beta, 14.845, 0.002);
  in.z1 = 4;
  EXPECT_THROW(iso6336_mesh_stiffness(in), InputError);
}

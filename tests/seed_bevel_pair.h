// The seed's spiral bevel pair (reference-data.md section 1: 55/47 teeth, m_et 3 mm, 20 deg,
// 35 deg spiral, F 19 mm) with the choices of cases/seed_spiral_bevel (cutter radius 76.2 mm,
// blade edge radius 0.2 m_mn), conjugate cuts; shared by the mesh and stiffness tests.
#pragma once

#include "geometry/bevel_gear.h"

namespace gearkit::test_data
{
inline BevelPairDesign
seed_bevel_design()
{
  BevelPairDesign d;
  d.pinion_teeth      = 55;
  d.gear_teeth        = 47;
  d.module            = 3e-3;
  d.module_kind       = BevelModule::outer_transverse;
  d.face_width        = 19e-3;
  d.mean_spiral_angle = 35 * pi / 180;
  d.pressure_angle    = 20 * pi / 180;
  d.pinion_hand       = Hand::right;
  d.cutter_radius     = 76.2e-3;
  d.edge_radius       = 0.2;
  return d;
}
} // namespace gearkit::test_data

// The FZG C-type test gear pair (reference-data.md section 5: m 4.5 mm, z 16/24, x 0.1817/0.1715,
// b 14 mm), optionally helical, unmodified; shared by the TCA tests and benchmarks.
#pragma once

#include "geometry/involute_gear.h"

#include <utility>

namespace gearkit::test_data
{
inline std::pair<InvoluteGearData, InvoluteGearData>
fzg_c_pair(double helix_angle = 0)
{
  InvoluteGearData p;
  p.name                  = "pinion";
  p.teeth                 = 16;
  p.normal_module         = 4.5e-3;
  p.normal_pressure_angle = 20 * pi / 180;
  p.profile_shift         = 0.1817;
  p.face_width            = 14e-3;
  p.helix_angle           = helix_angle;
  p.hand                  = Hand::right;
  InvoluteGearData g      = p;
  g.name                  = "gear";
  g.teeth                 = 24;
  g.profile_shift         = 0.1715;
  g.hand                  = Hand::left;
  return {p, g};
}
} // namespace gearkit::test_data

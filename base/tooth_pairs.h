// The unloaded contact of a gear mesh tooth pair by tooth pair: what the impact dynamics of a
// gear train (dynamics/train.h) needs of the flanks, and what the tooth contact analysis
// (tca/tooth_pairs.h) computes from any member's flanks.
//
// Conventions are the TCA's (tca/unloaded_tca.h): the pinion turns by phi, the gear by psi in
// its driven sense. Pairing k (an integer) is the k-th pinion tooth to pass the line of centres
// and its mate: pinion tooth mod(-k, z1), gear tooth mod(k - 1, z2) on the drive flanks and
// mod(k, z2) on the coast flanks. Its local angles are phi_k = phi - 2 pi k / z1 and
// psi_k = psi - 2 pi k / z2: teeth of one class (the same flanks up to their nominal angle)
// touch at the same local angles, so one curve serves every pairing of a class pair.
//
// For pairing k on side s at (phi, psi) the gear's touch angle is
//   psi_touch = 2 pi k / z2 + (z1 / z2) phi_k + offset(phi_k)
// and the flanks interpenetrate by d = arm(phi_k) (psi_touch - psi) on the drive side and
// d = arm(phi_k) (psi - psi_touch) on the coast side (to first order in the angle: the gear
// flank moves along its normal by arm dpsi), where d > 0. Outside a curve's samples the pair
// cannot touch.
#pragma once

#include <array>
#include <vector>

namespace gearkit
{
/// One class pair, one side: samples at local pinion angles start + i step; none where the
/// pair never touches (e.g. a missing tooth).
struct ToothPairCurve
{
  double              start = 0; ///< local pinion angle of the first sample [rad]
  double              step  = 0; ///< their spacing [rad] (> 0)
  std::vector<double> offset;    ///< gear touch angle less (z1 / z2) x local pinion angle [rad]
  std::vector<double> arm; ///< the gear's moment arm of the contact normal |(a x r) . n_g| [m]
};

enum ToothPairSide
{
  drive_side = 0,
  coast_side = 1
};

struct ToothPairTables
{
  int pinion_teeth = 0, gear_teeth = 0;
  /// Per tooth: teeth of one class have the same flanks up to their nominal angle.
  std::vector<int> pinion_class, gear_class;
  int              pinion_classes = 0, gear_classes = 0;
  /// curves[side][pinion class * gear_classes + gear class]
  std::array<std::vector<ToothPairCurve>, 2> curves;

  const ToothPairCurve &
  curve(int side, int pinion_tooth, int gear_tooth) const
  {
    return curves[side][pinion_class[pinion_tooth] * gear_classes + gear_class[gear_tooth]];
  }
};
} // namespace gearkit

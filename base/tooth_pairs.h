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
// flank moves along its normal by arm dpsi), where d > 0. (UnloadedTca::pair(k, phi) is this
// pairing; UnloadedTca::at's separation of a pair is -d at the gear's actual angle, its arm
// taken with the gear flank's normal.)
//
// Offsets: zero for perfect involutes at the zero-backlash centre distance, on both sides. At a
// larger centre distance (perfect involutes, symmetric about the line of centres at zero
// rotation) the drive offset is -j / (2 r'_2) and the coast offset +j / (2 r'_2),
// j the circumferential backlash on the operating pitch circles (j = p' - s_1(r'_1) -
// s_2(r'_2)): the gear turns freely between them, coast - drive = j_bn / r_b2, j_bn the normal
// backlash (~ 2 da sin(alpha'_wt)). More material on a drive flank (either member) raises the
// drive offset (the gear is met earlier), on a coast flank it lowers the coast offset; an
// eccentric pinion tooth of offset e moves its class's offset by +e / r_b2 (drive), -e / r_b2
// (coast). Each curve runs over every position where the pair can touch, through the edge
// contact of tips and chips, to where the touch angle has fallen behind its most advanced
// value (the conjugate one) by the recess of tca/tooth_pairs.h along the normal: its first and
// last samples stand off by more than that; outside them the pair does not touch (or stands
// off further). A class pair whose teeth never mate (tooth counts with a common factor) has an
// empty curve; it is never looked up by a pairing. A class pair that never touches (a missing
// tooth) has an empty curve too: looked up, it never touches.
#pragma once

#include "base/types.h"

#include <array>
#include <vector>

namespace gearkit
{
/// Where a tooth pair curve changes between flank-to-flank contact and the contact of a flank
/// edge (a tip, a face end, a chipped region) on the other flank: the touch angle is the larger
/// of the two contacts' there, so the curve's slope jumps (a kink, located between the samples).
/// Its offset and arm as the curve reaches it from below [0] and from above [1].
struct CurveKnot
{
  double at        = 0; ///< local pinion angle [rad]
  double offset[2] = {0, 0}, arm[2] = {0, 0};
};

/// One class pair, one side: samples at local pinion angles start + i step (start a multiple
/// of step: one grid through local angle 0 for every curve), and its kinks (at most one between
/// two samples, in increasing order) that the samples' interpolation must not smooth over.
struct ToothPairCurve
{
  double              start = 0; ///< local pinion angle of the first sample [rad]
  double              step  = 0; ///< their spacing [rad] (> 0)
  std::vector<double> offset;    ///< gear touch angle less (z1 / z2) x local pinion angle [rad]
  /// The gear's moment arm of the contact normal |(a x r) . n| [m], a the gear axis, r from the
  /// gear centre to the contact: n the gear flank's normal n_g, but the pinion flank's where an
  /// edge of the gear flank (its tip, a chip) touches the pinion inside its flank (the normal
  /// of the smooth surface; both agree in tangential contact). r_b2 cos(beta_b) for involutes.
  std::vector<double>    arm;
  std::vector<CurveKnot> knots;
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

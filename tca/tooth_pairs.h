// Tooth pair by tooth pair contact curves of a pair (base/tooth_pairs.h) from the members'
// flanks by the unloaded TCA: for every class pair and both sides the gear's touch angle and
// moment arm over the pinion angles at which the pair can touch, including the edge contact at
// the tips and at chipped regions, where the touch angle falls away from the conjugate one
// (the force of a pair leaving mesh under load then fades continuously).
#pragma once

#include "base/tooth_pairs.h"
#include "geometry/member_flanks.h"
#include "tca/assembly.h"

#include <memory>

namespace gearkit
{
struct ToothPairOptions
{
  int samples_per_mesh = 64; ///< curve samples per mesh cycle of the pinion (2 pi / z1)
  /// A curve ends where the pair stops touching, or where its touch angle has fallen this far
  /// behind (drive) or ahead (coast) of the conjugate one, along the contact normal [m].
  double recess          = 100e-6;
  int    profile_samples = 17, face_samples = 3; ///< the TCA's search grid (tca/unloaded_tca.h)
};

/// Both sides' curves of the pair at centre distance a (with misalignments). Throws InputError
/// when a class pair can never touch (flanks that do not mesh).
ToothPairTables
tooth_pair_tables(std::shared_ptr<const MemberFlanks> pinion,
                  std::shared_ptr<const MemberFlanks> gear, double centre_distance,
                  const Misalignment &misalignment = {}, const ToothPairOptions &options = {});
} // namespace gearkit

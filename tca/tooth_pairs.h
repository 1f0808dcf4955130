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
  /// A curve ends where the pair stops touching, or with the first sample whose touch angle has
  /// fallen more than this behind (drive) or ahead (coast) of the most advanced one so far (the
  /// conjugate one), along the contact normal: arm |offset - offset_lead| > recess [m].
  double recess          = 100e-6;
  int    profile_samples = 17, face_samples = 3; ///< the TCA's search grid (tca/unloaded_tca.h)
};

/// Both sides' curves of the pair at centre distance a (with misalignments), each class pair's
/// from one representative pairing (the one nearest pairing 0) walked outwards from its local
/// angle 0 (or the nearest position within three mesh cycles where it touches), the TCA's
/// search made thorough (TcaOptions::robust_search) and started at each sample also around the
/// previous sample's contact, so that it follows edge contacts to the curve's ends. Tooth
/// classes from MemberFlanks::flank_class, renumbered densely in their order. A class pair
/// that never touches while another does (a tooth chipped down to its root: gone) has an empty
/// curve. Throws InputError when no class pair of a side touches (flanks that do not mesh).
ToothPairTables
tooth_pair_tables(std::shared_ptr<const MemberFlanks> pinion,
                  std::shared_ptr<const MemberFlanks> gear, double centre_distance,
                  const Misalignment &misalignment = {}, const ToothPairOptions &options = {});
} // namespace gearkit

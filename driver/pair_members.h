// A scene's pair as flank surfaces and an assembly, for the stages after "flanks": involute
// members from their data, spiral bevel members generated from the design with the pinion's
// modified roll as the flanks stage synthesised it (/flanks/<pair>/pinion_modified_roll_2c).
#pragma once

#include "driver/h5_file.h"
#include "driver/scene.h"

#include <memory>

namespace gearkit
{
struct PairMembers
{
  std::shared_ptr<const MemberFlanks> pinion, gear;
  Assembly                            assembly;
  /// Parallel axes: the centre distance of the analysis (operating_centre_distance: with its
  /// error and offset); bevel pairs: 0.
  double centre_distance = 0;
  /// Pinion radius at which the transmission error is expressed as a displacement: the
  /// operating pitch radius (involute) or the mean pitch radius (spiral bevel) [m].
  double pitch_radius = 0;
};

/// The involute gear behind a member of an involute pair (its flanks are InvoluteMemberFlanks).
inline const InvoluteGear &
involute(const MemberFlanks &member)
{
  return dynamic_cast<const InvoluteMemberFlanks &>(member).involute();
}

/// The pinion mismatch with the modified roll the flanks stage synthesised (spiral bevel).
PinionMismatch
synthesised_mismatch(const PairScene &pair, const H5Group &flanks);

/// The theoretical members of `pair` assembled as `tca` says; `flanks` is the pair's group of
/// the flanks stage, whose starts of active profile (at the centre distance the scene runs the
/// pair at) the involute members take, whatever `tca` moves them to.
PairMembers
theoretical_members(const PairScene &pair, const TcaScene &tca, const H5Group &flanks);
} // namespace gearkit

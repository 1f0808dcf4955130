// How far measured points lie from a member's nominal flanks, and the plausibility checks of a
// measurement built on it: units (from the points' magnitudes), side labels (from the distance
// to either flank and the probe normals), and every point within a tolerance of its flank.
#pragma once

#include "geometry/measured_flank.h"
#include "geometry/member_flanks.h"

#include <string>

namespace gearkit
{
/// The foot of a point on a flank: the flank point whose normal passes through x (Gauss-Newton
/// from the coarse (r, z) guess; the parameters stay inside the flank's domain).
struct FlankFoot
{
  double u = 0, v = 0;
  Vec3   position, normal;
  /// (x - foot) . n: positive outside the material. Off the domain's edge x is not on the
  /// normal through the foot; `distance` is then the full distance |x - foot|, with the sign of
  /// the normal part.
  double signed_distance = 0;
  bool   on_edge         = false;
};

FlankFoot
flank_foot(const MemberFlanks &member, int tooth, FlankSide side, const Vec3 &x);

/// Checks a measurement of a member against its nominal flanks; throws InputError naming
/// `source` (the file), the flank and point, the value and what is allowed when
///  * the coordinates' magnitudes are those of the nominal member in other units (metres read
///    as millimetres or inches, and back): the points' median radius against the flanks';
///  * the points of a flank lie on the tooth's other flank (drive and coast labels swapped), or
///    their probe normals point against the nominal flank's;
///  * any point lies farther than `tolerance` [m] from its nominal flank.
void
check_measurement(const MeasuredMember &measured, const MemberFlanks &nominal, double tolerance,
                  const std::string &source, const std::string &tolerance_parameter);
} // namespace gearkit

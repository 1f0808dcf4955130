#include "driver/pair_members.h"

#include "tca/bevel_synthesis.h"

#include <cmath>

namespace gearkit
{
PinionMismatch
synthesised_mismatch(const PairScene &pair, const H5Group &flanks)
{
  PinionMismatch m = pair.mismatch;
  if (pair.transmission_error_amplitude > 0)
    m.modified_roll_2c = flanks.read_double("pinion_modified_roll_2c");
  return m;
}

PairMembers
theoretical_members(const PairScene &pair, const TcaScene &t, const H5Group &flanks)
{
  if (pair.type == PairType::spiral_bevel)
    {
      const BevelPairFlanks f =
          bevel_pair_flanks(pair.bevel, synthesised_mismatch(pair, flanks), t.misalignment);
      const BevelPairGeometry g = bevel_geometry(pair.bevel);
      return {f.pinion, f.gear, f.assembly, 0,
              g.mean_cone_distance * std::sin(g.pitch_angle_pinion)};
    }
  // The flanks as the flanks stage made them: each member's start of active profile (so its
  // profile evaluation range) at the centre distance the pair runs at in the scene. Read, not
  // computed from `t`: an assembly moved by a deflection (the dynamics) meets the same flanks.
  InvoluteGearData dp = pair.pinion, dg = pair.gear;
  dp.active_profile_start_radius =
      flanks.group("pinion").read_double("active_profile_start_radius");
  dg.active_profile_start_radius = flanks.group("gear").read_double("active_profile_start_radius");
  const auto [pinion, gear]      = create_pair(dp, dg);
  const double a =
      t.centre_distance > 0 ? t.centre_distance : working_centre_distance(*pinion, *gear);
  const int z1 = pinion->teeth(), z2 = gear->teeth();
  return {std::make_shared<InvoluteMemberFlanks>(pinion),
          std::make_shared<InvoluteMemberFlanks>(gear), Assembly(a, z2, t.misalignment),
          operating_centre_distance(a, t.misalignment), a * z1 / (z1 + z2)};
}
} // namespace gearkit

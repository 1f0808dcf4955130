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
  const auto [pinion, gear] = pair.involute_members();
  const double a =
      t.centre_distance > 0 ? t.centre_distance : working_centre_distance(*pinion, *gear);
  const int z1 = pinion->teeth(), z2 = gear->teeth();
  return {std::make_shared<InvoluteMemberFlanks>(pinion),
          std::make_shared<InvoluteMemberFlanks>(gear), Assembly(a, z2, t.misalignment),
          a + t.misalignment.centre_distance_error, a * z1 / (z1 + z2)};
}
} // namespace gearkit

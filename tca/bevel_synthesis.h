// Local synthesis of a spiral bevel pinion (Litvin's idea, done numerically): the modified roll
// of the pinion that gives a predesigned parabolic transmission error of a requested amplitude,
// found by the secant method on 2C with the unloaded TCA in the loop.
#pragma once

#include "geometry/bevel_gear.h"
#include "tca/unloaded_tca.h"

namespace gearkit
{
/// Peak-to-peak of e_0 over one mesh cycle at `positions` positions, the members cut with
/// `mismatch`.
double
bevel_transmission_error_amplitude(const BevelPairDesign &design, const PinionMismatch &mismatch,
                                   int positions = 24, const Misalignment &misalignment = {});

/// `mismatch` with modified_roll_2c set so that the peak-to-peak e_0 over one mesh cycle is
/// `amplitude` [rad] (to 0.1 %), the parabola opening so that the contact stays inside the
/// flanks. Throws InputError if the amplitude cannot be reached (edge contact first).
PinionMismatch
synthesise_modified_roll(const BevelPairDesign &design, PinionMismatch mismatch, double amplitude,
                         int positions = 24);

/// The pair as MemberFlanks and its assembly, ready for UnloadedTca.
struct BevelPairFlanks
{
  std::shared_ptr<const BevelMemberFlanks> pinion, gear;
  Assembly                                 assembly;
};
BevelPairFlanks
bevel_pair_flanks(const BevelPairDesign &design, const PinionMismatch &mismatch = {},
                  const Misalignment &misalignment = {});
} // namespace gearkit

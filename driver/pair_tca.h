// The unloaded TCA of a pair as the ste stage runs it - classical on the theoretical members;
// on measured flanks fast discrete-point or the seed's paper mode (its tables: results_ste.h).
// The dynamics stage runs it again where the static load deflects the pair to.
#pragma once

#include "driver/pair_members.h"
#include "driver/results_ste.h"
#include "dynamics/mesh_cycle.h"
#include "tca/paper_mode.h"

#include <functional>
#include <memory>
#include <utility>

namespace gearkit
{
using MemberPointer = std::shared_ptr<const MemberFlanks>;

/// The measured flanks of both members as the measured stage stored them (its pair group).
std::pair<MemberPointer, MemberPointer>
measured_members(const H5Group &measured_pair);

/// The TCA of pinion and gear placed by `assembly` over the scene's positions; measured flanks
/// in paper mode when the scene says so (`paper`, if given, then receives its extras). `step`
/// is called after each position.
TcaResult
pair_tca(const MemberPointer &pinion, const MemberPointer &gear, const Assembly &assembly,
         const TcaScene &t, bool measured, const std::function<void()> &step,
         PaperModeResult *paper = nullptr);

} // namespace gearkit

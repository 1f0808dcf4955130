// The unloaded TCA of a pair as the ste stage runs it - classical on the theoretical members;
// on measured flanks fast discrete-point or the seed's paper mode - and the tables it writes.
// The dynamics stage runs it again where the static load deflects the pair to.
#pragma once

#include "driver/pair_members.h"
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

/// Writes every table of `r` (an analysis of `members`' pair) to `g`; returns the peak-to-peak
/// of e_0 and the mean pairs in contact for the log.
std::pair<double, double>
write_tca_tables(const TcaResult &r, const TcaScene &t, const PairMembers &members,
                 const H5Group &g);

/// The contact tables the dynamics reads, from an analysis or from its tables in `g`.
ContactTables
contact_tables(const TcaResult &r);
ContactTables
contact_tables(const H5Group &g);

/// Mean contact point of the leading pairs on the gear flank, (radius, axial) in the gear's
/// frame [m], from the tables in `g` (write_tca_tables).
Vec2
contact_pattern_centre(const H5Group &g);
} // namespace gearkit

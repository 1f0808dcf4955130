// Typed results of the ste stage, group ste/<pair> (and its measured/; the dynamics' deflected
// TCA in dynamics/<pair>/<excitation>/deflection/tca): the unloaded TCA's tables, written and
// read here alone (the dataset names, units and descriptions: driver/results_schema.cc).
#pragma once

#include "driver/pair_members.h"
#include "dynamics/mesh_cycle.h"
#include "tca/unloaded_tca.h"

#include <utility>

namespace gearkit
{
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

// A scene's pair ready for the loaded contact (fast mode) as the stiffness stage solves it: the
// theoretical members, both members' compliance tables as the compliance stage computed them,
// the unloaded TCA and the contact options. The stage and the Python module build it here, so
// they solve the same problem.
#pragma once

#include "driver/h5_file.h"
#include "driver/pair_members.h"
#include "driver/scene.h"
#include "stiffness/flank_compliance.h"
#include "stiffness/loaded_contact.h"
#include "tca/unloaded_tca.h"

#include <memory>

namespace gearkit
{
/// The module the scene's element sizes are relative to: the normal module (involute), the mean
/// normal module (spiral bevel).
double
member_module(const PairScene &pair);

/// The scene's finite-element section of a pair with the face grid points resolved (0: from
/// the face width and module).
FeScene
pair_fe(const Scene &scene, const PairScene &pair);

/// The compliance table of one member ("pinion", "gear") as the compliance stage computed it:
/// its group in `tables` (compliance/<pair>, or its coarse subgroup), on the scene's grid.
FlankCompliance
read_table(const MemberFlanks &flanks, const H5Group &tables, const char *member, const FeScene &fe,
           const LoadedScene &lc, FlankSide side);

struct LoadedPair
{
  PairMembers                            members;
  std::shared_ptr<const FlankCompliance> pinion_table, gear_table;
  /// The unloaded TCA of the theoretical members in the scene's assembly.
  std::shared_ptr<const UnloadedTca> theory;
  /// The scene's cells and materials; `covered` by both tables; every core of this process's
  /// share; the positions shared among the processes of MPI_COMM_WORLD.
  LoadedContactOptions options;
  /// The tables as the contact's structural compliances (they refer to the tables above).
  StructuralCompliance pinion_compliance, gear_compliance;
};

/// The pair `pair` of the scene on its compliance tables: `flanks` is the pair's group of the
/// flanks stage, `compliance` its group of the compliance stage.
LoadedPair
loaded_pair(const Scene &scene, const PairScene &pair, const H5Group &flanks,
            const H5Group &compliance);

/// The options for measured flanks on the theoretical pair's tables: each cell looks up the
/// theoretical flank at its own position (MemberFlanks::rotational_parameters); the zone from
/// the gaps (the measured flanks' local curvature carries their noise).
LoadedContactOptions
measured_contact_options(const LoadedPair &pair, const MemberFlanks &measured_pinion,
                         const MemberFlanks &measured_gear, FlankSide side);
} // namespace gearkit

// Typed results of the stiffness stage, group stiffness/<pair> (and its measured/ subgroup):
// the loaded contact over one mesh cycle at the torques solved, written and read here alone
// (the dataset names, units and descriptions: driver/results_schema.cc).
#pragma once

#include "driver/h5_file.h"
#include "stiffness/loaded_contact.h"

#include <vector>

namespace gearkit
{
/// A mesh cycle as stored: the contact at the torques solved and the torques of the scene that
/// were refused (MeshCycleContact::torque_failure is not stored: the stage's `warnings`
/// attribute says why; the record's is empty).
struct StiffnessRecord
{
  MeshCycleContact    cycle;
  std::vector<double> torques, refused;

  /// K_m over the mesh cycle at torque index `k` [N/m].
  std::vector<double>
  mesh_stiffness_at(std::size_t k) const;
};

/// Writes the mesh cycle `c` solved at `torques` (the scene's `refused` ones left out) to `g`.
void
write_mesh_cycle(const H5Group &g, const MeshCycleContact &c, const std::vector<double> &torques,
                 const std::vector<double> &refused);

/// The record write_mesh_cycle wrote to `g`.
StiffnessRecord
read_mesh_cycle(const H5Group &g);
} // namespace gearkit

// A grid over flank modification parameters (a micro-geometry design map): axes over fields of
// ToothModifications (tip relief, crowning, ...), applied to the pinion, the gear or both on top
// of a base design; every variant of the grid is one PairVariant. And the map itself: every
// variant's loaded mesh cycle at every torque on one compliance (MeshCycleStudy), the variants
// dealt round the processes and threads.
#pragma once

#include "study/mesh_cycle_study.h"
#include "study/parameter_grid.h"

#include <functional>
#include <mpi.h>
#include <string>
#include <vector>

namespace gearkit
{
/// The modification fields a grid can vary, by the names results use (snake case: tip_relief,
/// tip_relief_length, root_relief, root_relief_length, lead_crowning, end_relief,
/// end_relief_length, profile_crowning, profile_slope, helix_slope); all in metres.
const std::vector<std::string> &
modification_field_names();

/// The field of a name (modification_field_names); throws InputError naming the known ones.
double ToothModifications::       *
modification_field(const std::string &name);

/// An axis of a modification grid: a modification_field_names entry and its values [m].
using ModificationAxis = GridAxis;

enum class GridMembers
{
  both,
  pinion,
  gear
};

class ModificationGrid
{
public:
  /// Throws InputError for an unknown field, an axis named twice or without values, a
  /// non-finite value, and a grid of more than `most` variants.
  ModificationGrid(PairVariant base, GridMembers members, std::vector<ModificationAxis> axes,
                   std::size_t most = 100000);
  /// Variants: the product of the axes' sizes (1 without axes: the base).
  std::size_t
  size() const
  {
    return grid.size();
  }
  /// Variant g: the base with axis k at its value index(g)[k], the first axis slowest.
  PairVariant
  variant(std::size_t g) const;
  std::vector<std::size_t>
  index(std::size_t g) const
  {
    return grid.index(g);
  }
  const ParameterGrid &
  parameters() const
  {
    return grid;
  }
  const std::vector<ModificationAxis> &
  axes() const
  {
    return grid.axes();
  }
  GridMembers
  members() const
  {
    return on;
  }

private:
  PairVariant   base;
  GridMembers   on;
  ParameterGrid grid;
};

/// Variants 0 .. count - 1 (variant(g): deterministic, thread-safe) at every torque of
/// `options` (one VariantCycle per variant, all torques): one MeshCycleStudy per torque, built
/// while that torque runs (its zones' compliance matrices are the memory: about cells^2 8 bytes
/// per position), the variants dealt round the processes of `communicator` (every process
/// receives all) and each process's round its threads (options.threads). `step` (optional) is
/// called after each variant and torque. `warm_from` (optional): the contact solves start from
/// this variant's active sets (MeshCycleStudy::warm_start_from). Collective.
std::vector<VariantCycle>
evaluate_variants(std::shared_ptr<const InvoluteMemberFlanks> pinion,
                  std::shared_ptr<const InvoluteMemberFlanks> gear, const Assembly &assembly,
                  const TcaOptions &tca, const LoadedContactOptions &contact,
                  const StructuralCompliance &pinion_compliance,
                  const StructuralCompliance &gear_compliance, const MeshCycleStudyOptions &options,
                  std::size_t count, const std::function<PairVariant(std::size_t)> &variant,
                  MPI_Comm communicator, const std::function<void()> &step = {},
                  const PairVariant *warm_from = nullptr);

/// The grid's variants (evaluate_variants).
std::vector<VariantCycle>
microgeometry_map(std::shared_ptr<const InvoluteMemberFlanks> pinion,
                  std::shared_ptr<const InvoluteMemberFlanks> gear, const Assembly &assembly,
                  const TcaOptions &tca, const LoadedContactOptions &contact,
                  const StructuralCompliance &pinion_compliance,
                  const StructuralCompliance &gear_compliance, const MeshCycleStudyOptions &options,
                  const ModificationGrid &grid, MPI_Comm communicator,
                  const std::function<void()> &step = {});
} // namespace gearkit

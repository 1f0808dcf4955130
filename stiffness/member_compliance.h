// The structural compliance table of an involute member from finite elements: a gmsh tooth
// segment around the loaded teeth (bore and radial cuts held), deal.II/PETSc with one
// factorisation, unit normal patch loads at the flank grid points, responses a few elements
// below the flank (where the elements resolve the Boussinesq field, but at most half the chord
// through the tooth) with the half-space part taken out (flank_compliance.h).
#pragma once

#include "flank_compliance.h"
#include "tooth_segment.h"
#include "unloaded_tca.h"

#include <mpi.h>

#include <string>

namespace gearkit
{
struct MemberComplianceOptions
{
  SegmentMeshOptions mesh;            ///< segment: teeth, central tooth, element sizes
  unsigned           degree = 2;      ///< FE_Q degree
  Material           material;
  FlankSide          side = FlankSide::drive;
  std::vector<int>   loaded_teeth;    ///< member teeth with load grids; empty: the segment's
  int                n_u = 9, n_v = 7; ///< grid over profile and face
  double             depth_elements = 3; ///< response depth in flank element sizes
  double             patch_elements = 1; ///< patch load radius in flank element sizes
  bool               hold_cuts = true;   ///< radial cut faces held (else free; the bore always)
  std::string        work_directory;  ///< where the segment mesh is written
  /// The processes that share the finite elements: the first meshes the segment (gmsh), all
  /// solve it together; every process receives the whole table.
  MPI_Comm communicator = MPI_COMM_WORLD;
};

struct MemberComplianceInfo
{
  std::size_t hexahedra = 0, dofs = 0;
  double      depth = 0, patch_radius = 0;  ///< [m]
  /// Grid points whose response depth was limited to half the chord through the tooth along
  /// their response direction (near a thin tip the nominal depth would leave the tooth), and
  /// the smallest depth used [m].
  std::size_t shallow_points = 0;
  double      min_depth      = 0;
  double      mesh_seconds = 0, setup_seconds = 0, solve_seconds = 0;
};

/// The segment a member needs: the teeth of the pairs that stand within `gap_band` of contact
/// at any of the positions (they can carry load), contiguous around the wheel, as the middle
/// tooth and the count (odd).
struct SegmentChoice
{
  int central = 0, teeth = 1;
};
/// For the pinion (first) and the gear (second) of the pair at the given TCA positions.
std::pair<SegmentChoice, SegmentChoice>
loaded_segments(const std::vector<TcaPosition> &positions, int pinion_teeth, int gear_teeth,
                double gap_band);

/// write_tooth_segment_mesh on the first process of `comm`; the others wait and receive the
/// description, or the first process's InputError (every process throws it).
SegmentMeshInfo
write_tooth_segment_mesh_on_first_process(const InvoluteGear &gear,
                                          const SegmentMeshOptions &options,
                                          const std::string &path, MPI_Comm comm);

FlankCompliance
involute_member_compliance(const InvoluteGear &gear, const MemberFlanks &flanks,
                           const MemberComplianceOptions &options,
                           MemberComplianceInfo *info = nullptr);
} // namespace gearkit

// Loaded tooth contact at one mesh position, reference mode: finite elements alone. Both
// members are meshed for this position (gmsh tooth segments graded down to the contact cell
// size around the contact lines of every pair within the gap band), the compliance of every
// contact cell to every other comes from the finite elements of both members (uniform normal
// tractions on the cells, the approach of a cell = its mean normal displacement, the work of
// its own traction: a symmetric compliance; no half-space solution, no interpolation), and the
// frictionless contact problem is solved to complementarity with the torque balance (the same
// active-set solver as the fast mode). The bores are held; the pinion's rigid rotation beyond its
// unloaded position is e_L - e_0.
//
// This is small-sliding, node-free contact on the condensed finite-element system: the
// contact tractions are piecewise constant on the cells, the gaps are the unloaded TCA's
// along the normal. Spur pairs (the contact lines run along the face, so the transverse
// section carries the refinement).
#pragma once

#include "stiffness/loaded_contact.h"
#include "stiffness/member_compliance.h"

#include <string>
#include <vector>

namespace gearkit
{
struct ReferenceContactOptions
{
  LoadedContactOptions cells;      ///< cells (across, along, gap band) and materials
  unsigned             degree = 2; ///< FE_Q degree
  /// Segments: teeth == 0 chooses from this position's pairs within the gap band (at least
  /// `min_segment_teeth`); give both to keep the same segments over a mesh cycle.
  SegmentChoice pinion_segment{0, 0}, gear_segment{0, 0};
  int           min_segment_teeth = 3;
  bool          hold_cuts         = true;   ///< radial cut faces held (the bore always)
  double        elements_per_cell = 1;      ///< element size at the contact = cell width / this
  double      flank_size = 0, far_size = 0; ///< segment sizes away from the contact [m]; 0: m/5, m
  int         layers_per_cell = 1;          ///< face layers per cell along the contact line
  std::string work_directory;               ///< meshes are written here
  std::string vtu_prefix;                   ///< non-empty: <prefix>_torque<k>_{pinion,gear}.vtu
  /// The processes that share the finite elements (the first meshes).
  MPI_Comm communicator = MPI_COMM_WORLD;
};

struct ReferenceContactInfo
{
  std::size_t   hexahedra = 0, dofs = 0; ///< both members
  double        mesh_seconds = 0, solve_seconds = 0, contact_seconds = 0;
  SegmentChoice pinion_segment, gear_segment;
};

/// One loaded position per torque (all >= 0), from one factorisation per member. Throws
/// InputError for helical gears, a missing work directory and what loaded_contact refuses.
std::vector<LoadedPosition>
reference_contact(const InvoluteGear &pinion, const InvoluteGear &gear, const UnloadedTca &tca,
                  const TcaPosition &position, const std::vector<double> &torques,
                  const ReferenceContactOptions &options, ReferenceContactInfo *info = nullptr);
} // namespace gearkit

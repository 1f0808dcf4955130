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
// along the normal. Spur pairs (contact lines along the face): gmsh grades the transverse
// section to the lines. Helical and spiral bevel pairs (and spur pairs if asked): gmsh meshes
// the segment at the flank size and deal.II refines it about the contact cells until the
// elements there are as small as asked (hanging nodes, new flank vertices on the exact flank,
// each pass within half the previous pass's distance: a graded zone).
#pragma once

#include "stiffness/loaded_contact.h"
#include "stiffness/member_compliance.h"

#include <functional>
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
  /// The segments on the whole rim and bore (SegmentMeshOptions::whole_rim).
  bool        pinion_whole_rim = false, gear_whole_rim = false;
  bool        hold_cuts         = true;     ///< radial cut faces held (the bore always)
  double      elements_per_cell = 1;        ///< element size at the contact = cell width / this
  double      flank_size = 0, far_size = 0; ///< segment sizes away from the contact [m]; 0: m/5, m
  int         layers_per_cell = 1;          ///< face layers per cell along the contact line
  std::string work_directory;               ///< meshes are written here
  std::string vtu_prefix;                   ///< non-empty: <prefix>_torque<k>_{pinion,gear}.vtu
  /// Spur pairs too refined about the cells by deal.II (else gmsh grades the transverse section;
  /// helical and bevel pairs always are).
  bool local_refinement = false;
  /// The processes that share the finite elements (the first meshes).
  MPI_Comm communicator = MPI_COMM_WORLD;
};

/// A member as the reference mode meshes it.
struct ReferenceMember
{
  const MemberFlanks *flanks = nullptr;
  /// Writes the member's segment mesh with these options to the path (tooth_segment.h,
  /// bevel_segment.h).
  std::function<SegmentMeshInfo(const SegmentMeshOptions &, const std::string &)> mesher;
  double module = 0, face_width = 0; ///< [m]: the element sizes' unit (m_n, m_mn), b
  /// Contact lines along the face (spur): the section can be graded to them.
  bool straight_lines = false;
};

/// An involute member (spur or helical) with the TCA's flanks of it.
ReferenceMember
involute_reference_member(const InvoluteGear &gear, const MemberFlanks &flanks);
/// A spiral bevel member; `module` = m_mn.
ReferenceMember
bevel_reference_member(const BevelMemberFlanks &flanks, double module);

struct ReferenceContactInfo
{
  std::size_t   hexahedra = 0, dofs = 0; ///< both members (hexahedra after the refinement)
  unsigned      local_refinements = 0;   ///< deal.II's passes about the cells (0: gmsh graded)
  double        mesh_seconds = 0, solve_seconds = 0, contact_seconds = 0;
  SegmentChoice pinion_segment, gear_segment;
};

/// One loaded position per torque (all >= 0), from one factorisation per member; the members'
/// flanks must be the TCA's. Throws InputError for a missing work directory and what
/// loaded_contact refuses.
std::vector<LoadedPosition>
reference_contact(const ReferenceMember &pinion, const ReferenceMember &gear,
                  const UnloadedTca &tca, const TcaPosition &position,
                  const std::vector<double> &torques, const ReferenceContactOptions &options,
                  ReferenceContactInfo *info = nullptr);

/// The same for an involute pair (the TCA's flanks of the two gears).
std::vector<LoadedPosition>
reference_contact(const InvoluteGear &pinion, const InvoluteGear &gear, const UnloadedTca &tca,
                  const TcaPosition &position, const std::vector<double> &torques,
                  const ReferenceContactOptions &options, ReferenceContactInfo *info = nullptr);
} // namespace gearkit

// The structural compliance table of an involute member from finite elements: a gmsh tooth
// segment around the loaded teeth (bore and radial cuts held), deal.II/PETSc with one
// factorisation, unit normal patch loads at the flank grid points, responses a few elements
// below the flank (where the elements resolve the Boussinesq field) with the half-space part
// taken out (flank_compliance.h).
#pragma once

#include "flank_compliance.h"
#include "tooth_segment.h"

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
  std::string        work_directory;  ///< where the segment mesh is written
};

struct MemberComplianceInfo
{
  std::size_t hexahedra = 0, dofs = 0;
  double      depth = 0, patch_radius = 0;  ///< [m]
  double      mesh_seconds = 0, setup_seconds = 0, solve_seconds = 0;
};

FlankCompliance
involute_member_compliance(const InvoluteGear &gear, const MemberFlanks &flanks,
                           const MemberComplianceOptions &options,
                           MemberComplianceInfo *info = nullptr);
} // namespace gearkit

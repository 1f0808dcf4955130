// gmsh models of a multi-tooth segment of an involute (spur or helical) member: the nominal
// transverse section of a few teeth and the rim down to the bore (or a shaft seat), meshed with
// quadrilaterals graded toward the flanks and extruded over the face width (twisted along the
// helix for helical gears) into hexahedra. The frame is the member's (geometry/involute_gear.h):
// axis z, face from -b/2 to +b/2, tooth k centred at polar angle 2 pi k / z in the section z = 0.
//
// Physical groups (the numbers are the boundary ids deal.II reads; names as in the .msh):
//   volume 1 "body";
//   surfaces 1 "bore", 2 "cut_start" (the radial cut at the smaller polar angle), 3 "cut_end"
//   (no cuts when the segment is the whole gear or sits on the whole rim),
//   4 "end_front" (z = -b/2), 5 "end_back" (z = +b/2), 6 "free" (tip lands, root lands, fillets),
//   10 + 2 i "tooth<i>_drive" and 11 + 2 i "tooth<i>_coast" for the i-th tooth of the segment
//   (i = 0 .. teeth - 1 in counter-clockwise order; member tooth central - (teeth - 1) / 2 + i).
// A .json sidecar next to the mesh lists the groups, the member teeth and the analytic volume
// (for scripts/check_mesh.py).
#pragma once

#include "geometry/involute_gear.h"

#include <string>
#include <vector>

namespace gearkit
{
namespace boundary
{
constexpr int bore = 1, cut_start = 2, cut_end = 3, end_front = 4, end_back = 5, free = 6;
constexpr int
flank(int segment_tooth, FlankSide side)
{
  return 10 + 2 * segment_tooth + (side == FlankSide::coast ? 1 : 0);
}
/// The physical group's name ("bore", ..., "tooth<i>_drive").
std::string
name(int id);
} // namespace boundary

struct SegmentMeshOptions
{
  /// Teeth in the segment: odd, >= 1, spanning at most half the gear (on the whole rim: fewer
  /// than the gear's); or the gear's number of teeth: the whole gear (rim and bore all round, no
  /// cuts).
  int teeth         = 3;
  int central_tooth = 0; ///< member tooth in the middle of the segment
  /// The rim and bore all round (no cuts), teeth only on the segment: the whole gear's support
  /// without meshing the far teeth (they hardly stiffen the body: bench/README.md).
  bool whole_rim = false;
  /// Inner radius of the rim [m]: 0 = the bore if the gear has one, else a shaft seat
  /// 3.5 m_n below the root circle (ISO 6336 rim thickness).
  double rim_inner_radius = 0;
  /// Spiral bevel segments (bevel_segment.h): rim thickness below the root cone [m]; 0 = 3.5 m.
  double rim_thickness = 0;
  double flank_size    = 0; ///< element size at the flanks and fillets [m]; 0 = m_n / 5
  /// Element size at the fillets and the flanks of the side other than `fine_side` [m]; 0 = the
  /// flank size. Only the loaded flanks need the fine elements for the compliance.
  double    other_size = 0;
  FlankSide fine_side  = FlankSide::drive;
  /// Element size at the root fillets of the teeth with fine elements [m]; 0 = the size of
  /// their side (flank or other size). The fillets are concave arcs of about the cutter's tip
  /// radius (0.38 m_n): gmsh puts at least four elements on one whatever the sizes, and their
  /// chords add material at the tooth roots (K_m 0.5 % stiff with elements of m_n / 4 on a 20/31
  /// spur pair; bench/README.md, element refinement study).
  double fillet_size = 0;
  /// Teeth about the central one whose flanks and fillets get the sizes above (odd); the others
  /// get the far size. 0: all teeth of the segment.
  int fine_teeth = 0;
  /// Element size far from them [m]; 0 = m_n. At most a third of the rim's thickness (root
  /// circle to its inner radius): a small pinion's body is resolved whatever the module says.
  double far_size     = 0;
  int    face_layers  = 0;  ///< elements over the face width; 0 = b / (2 flank_size)
  int    curve_points = 40; ///< spline points per fillet and per involute
  /// Local refinement (spur segments: the contact lines of one mesh position run along z):
  /// element size `refine_size` within `refine_radius` of these transverse-section points,
  /// growing by at most 1/4 of the distance beyond it up to the flank size.
  std::vector<Vec2> refine_points;
  double            refine_size = 0, refine_radius = 0;
};

struct SegmentMeshInfo
{
  std::size_t      hexahedra = 0, nodes = 0;
  double           analytic_volume  = 0; ///< nominal segment volume [m^3]
  double           rim_inner_radius = 0; ///< the one used [m]
  std::vector<int> member_teeth;         ///< member tooth of each segment tooth
  bool             whole = false;        ///< the whole gear or rim: no cut faces
  /// The worst hexahedron: its smallest corner Jacobian relative to its mean (1 for a
  /// parallelepiped, <= 0 folded), and gmsh's 2-D algorithm that gave it (6 frontal-Delaunay,
  /// 5 Delaunay, 1 MeshAdapt: the next is tried while the worst is below the acceptable value).
  double                  worst_corner_jacobian      = 0;
  int                     mesh_algorithm             = 0;
  static constexpr double acceptable_corner_jacobian = 0.05;
};

/// The .json sidecar of a segment mesh (for scripts/check_mesh.py): the member's name, the
/// analytic volume, sizes, member teeth and the physical groups (boundary ids) present.
std::string
segment_sidecar(const std::string &member, const SegmentMeshInfo &info,
                const std::vector<int> &boundary_ids);

/// Builds the segment with gmsh and writes it to `path` (.msh 4.1) and `path`.json, each via a
/// temporary file and a rename. Throws InputError for bad options (name, value, allowed range),
/// when gmsh cannot mesh the section with quadrilaterals only, and when every 2-D algorithm
/// folds an element.
SegmentMeshInfo
write_tooth_segment_mesh(const InvoluteGear &gear, const SegmentMeshOptions &options,
                         const std::string &path);
} // namespace gearkit

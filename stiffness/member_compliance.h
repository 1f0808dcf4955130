// The structural compliance table of a member from finite elements: a tooth segment (gmsh)
// around the loaded teeth (bore and radial cuts held; optionally meshed coarser and refined by
// deal.II near the loaded flanks), deal.II/PETSc with one factorisation, unit normal loads at
// the flank grid points: by default point forces whose near field is carried analytically,
// the elements solving the smooth remainder, read at the flank; optionally patch loads read a
// few elements below the flank with the half-space part above taken out (flank_compliance.h).
#pragma once

#include "meshes/bevel_segment.h"
#include "meshes/tooth_segment.h"
#include "stiffness/elastic_segment.h"
#include "stiffness/flank_compliance.h"
#include "tca/unloaded_tca.h"

#include <functional>
#include <mpi.h>
#include <string>

namespace gearkit
{
struct MemberComplianceOptions
{
  SegmentMeshOptions mesh;       ///< segment: teeth, central tooth, element sizes
  unsigned           degree = 2; ///< FE_Q degree
  Material           material;
  FlankSide          side = FlankSide::drive;
  std::vector<int>   loaded_teeth; ///< member teeth that can carry load; empty: the segment's
  /// -1: unit loads on every loaded tooth. Otherwise the member tooth (the segment's middle)
  /// that alone carries unit loads, responses read on the teeth within `cyclic_reach` of it,
  /// its table read for every loaded tooth turned (FlankGridSpec); only its loaded flank is
  /// refined (local refinements).
  int    cyclic_tooth = -1, cyclic_reach = 0;
  int    n_u = 9, n_v = 7;      ///< grid over profile and face
  bool   graded_grid    = true; ///< grid clustered towards the edges (FlankGridSpec)
  double depth_elements = 3;    ///< response depth in flank element sizes
  double patch_elements = 1;    ///< patch load radius in flank element sizes
  /// Radial cut faces held (else free; the bore always; a whole gear has none).
  bool hold_cuts = true;
  /// The near field of each unit load: false, read a response depth below the flank and take
  /// the half-space part above it out; true, carry Boussinesq's field analytically (cut off
  /// within `near_field_radius`, less where the body comes back across the load's normal or a
  /// held face is nearer) and solve only the smooth remainder with the finite elements, read
  /// at the flank itself (ElasticSegment::remainder_response).
  bool   analytic_near_field = true;
  double near_field_radius   = 0; ///< [m]; 0: twice the module
  /// Local refinement: the segment meshed with every element size 2^k times larger and the
  /// elements within `refine_depth` of those sizes of the loaded flanks refined k times by
  /// deal.II (hanging nodes; new flank vertices on the exact flank), so that the loaded flanks
  /// have the element sizes asked for and the rest of the segment (the other teeth, the face
  /// layers of the rim) is coarse.
  unsigned    local_refinements = 0;
  double      refine_depth      = 1;
  std::string work_directory; ///< where the segment mesh is written
  /// The processes that share the finite elements: the first meshes the segment (gmsh), all
  /// solve it together; every process receives the whole table.
  MPI_Comm communicator = MPI_COMM_WORLD;
  /// Memory the finite elements may take on each machine [bytes]; 0: what it has available
  /// (ElasticSegmentOptions::memory_available).
  double   memory_available = 0;
  unsigned threads          = 0; ///< threads per process for the unit loads; 0: the hardware's
  /// Told what comes next ("meshing", "set-up", "189 unit loads on 103095 dofs"): a progress
  /// line's note (base/progress.h); may be empty.
  std::function<void(const std::string &)> on_phase;
};

struct MemberComplianceInfo
{
  std::size_t hexahedra = 0, dofs = 0;     ///< elements (after the local refinement), dofs
  double      depth = 0, patch_radius = 0; ///< [m]
  /// Grid points whose response depth was limited to half the chord through the tooth along
  /// their response direction (near a thin tip the nominal depth would leave the tooth), and
  /// the smallest depth used [m].
  std::size_t shallow_points = 0;
  double      min_depth      = 0;
  /// With the analytic near field: the smallest cut-off radius used [m] (less than the
  /// option where the body comes back across a point's normal or a held face is near).
  double min_near_field_radius = 0;
  /// Wall times [s]: the segment's mesh; reading, refining and numbering it (set-up); the unit
  /// loads (solve), which include the stiffness matrix's assembly and factorisation (solver,
  /// beside the loads' assembly) and of that the factorisation (factor).
  double mesh_seconds = 0, setup_seconds = 0, solve_seconds = 0;
  double solver_seconds = 0, factor_seconds = 0;
  /// The processes that computed the table (member_compliances: a group's or all).
  int processes = 1;
  /// The factors kept in files: in memory they did not fit (ElasticSegment).
  bool out_of_core = false;
};

/// The segment a member needs: the teeth of the pairs that stand within `gap_band` of contact
/// at any of the positions (they can carry load), contiguous around the wheel, as the middle
/// tooth and the count (odd), and how far apart teeth stand within the band at once.
struct SegmentChoice
{
  int central = 0, teeth = 1;
  int span = 0; ///< the largest offset between teeth within the gap band at one position
};
/// For the pinion (first) and the gear (second) of the pair at the given TCA positions.
std::pair<SegmentChoice, SegmentChoice>
loaded_segments(const std::vector<TcaPosition> &positions, int pinion_teeth, int gear_teeth,
                double gap_band);

/// The exact surface of a segment's loaded flanks (ElasticSegmentOptions::boundary_surface):
/// the point of the exact flank of its segment tooth (`member_teeth` as in the segment's
/// description) at the point's rotational parameters, with the flank's outward normal there.
/// Keeps a reference to `flanks`.
std::function<SurfacePoint(int, const Vec3 &)>
flank_surface(const MemberFlanks &flanks, const std::vector<int> &member_teeth, FlankSide side);

/// Writes a member's segment mesh to the path given and describes it.
using SegmentMesher = std::function<SegmentMeshInfo(const std::string &path)>;

/// The mesher on the first process of `comm`; the others wait and receive the description, or
/// the first process's InputError (every process throws it).
SegmentMeshInfo
segment_mesh_on_first_process(const SegmentMesher &mesher, const std::string &path, MPI_Comm comm);

/// The table of any member on the segment the mesher writes (its flank groups as in
/// tooth_segment.h); `flank_size` is the mesher's element size at the loaded flanks [m] (the
/// response depth and patch radius are multiples of it); `name` names the mesh file.
FlankCompliance
member_compliance(const MemberFlanks &flanks, const std::string &name, const SegmentMesher &mesher,
                  double flank_size, const MemberComplianceOptions &options,
                  MemberComplianceInfo *info = nullptr);

/// One member's table for member_compliances: its flanks, and how to compute it on the given
/// processes within the given memory per machine (as options.communicator and
/// options.memory_available of member_compliance).
struct MemberJob
{
  using Compute = std::function<FlankCompliance(MPI_Comm, double memory, MemberComplianceInfo &)>;
  const MemberFlanks *flanks = nullptr;
  Compute             compute;
};

/// The members' tables, each on every process of `comm`. On one process one after another. On
/// several, at once: the processes split into min(jobs, processes) groups (job k on the group
/// of the processes whose rank is k modulo that count), each with its share of its machine's
/// available memory (its processes there over the machine's), and each table is then sent from
/// its group to every process. A job its group refuses for want of memory (MemoryRefusal) is
/// computed again on all processes with all the memory. An InputError of any job is thrown on
/// every process (the lowest failed job's), after every group has finished.
std::vector<std::pair<FlankCompliance, MemberComplianceInfo>>
member_compliances(const std::vector<MemberJob> &jobs, MPI_Comm comm);

/// On a gmsh tooth segment of the involute gear (options.mesh; flank size default m_n / 5).
FlankCompliance
involute_member_compliance(const InvoluteGear &gear, const MemberFlanks &flanks,
                           const MemberComplianceOptions &options,
                           MemberComplianceInfo          *info = nullptr);

/// On a spiral bevel segment (bevel_segment.h; flank size default m_mn / 5, `module` = m_mn);
/// `name` names the mesh file.
FlankCompliance
bevel_member_compliance(const BevelMemberFlanks &flanks, const std::string &name, double module,
                        const MemberComplianceOptions &options,
                        MemberComplianceInfo          *info = nullptr);
} // namespace gearkit

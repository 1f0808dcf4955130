// Linear elasticity of one meshed body (a tooth segment, a cylinder slice, a test block) with
// deal.II on a shared triangulation (the mesh on every process, each owning a part; deal.II
// refines it) and PETSc with distributed matrices: the stiffness matrix assembled once,
// factorised once (MUMPS Cholesky) and reused for many load cases; concentrated loads applied
// as uniform tractions over small surface patches; displacements read at arbitrary points
// through precomputed evaluation functionals. MPI-parallel (the owning rank evaluates a point).
//
// The direct factorisation is sized first (MUMPS's analysis) and refused with its estimate when
// it would not fit in the memory available.
//
// Run-time solver options the PETSc way, prefix "gearkit_": e.g. PETSC_OPTIONS=
// "-gearkit_pc_factor_mat_solver_type superlu_dist" or "-gearkit_ksp_type cg -gearkit_pc_type
// gamg" replaces the direct factorisation by an iterative solve.
#pragma once

#include "geometry/types.h"
#include "stiffness/half_space.h"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <mpi.h>
#include <set>
#include <string>
#include <vector>

namespace gearkit
{
/// A point of a surface and its outward unit normal there.
struct SurfacePoint
{
  Vec3 position = Vec3::Zero(), normal = Vec3::Zero();
};

/// A body refused before its memory is taken: its stiffness matrix or direct factorisation
/// would need more than the memory available to it (ElasticSegmentOptions::memory_available);
/// the message gives the estimate and what is available.
class MemoryRefusal : public InputError
{
public:
  using InputError::InputError;
};

/// MemAvailable of /proc/meminfo [bytes] (0 where it cannot be read), after handing this
/// process's own freed heap back to the system.
double
memory_available_now();

struct ElasticSegmentOptions
{
  unsigned      degree      = 1; ///< FE_Q degree (1 or 2)
  unsigned      refinements = 0; ///< global refinements of the gmsh mesh
  Material      material;
  std::set<int> clamped; ///< boundary ids held fixed (all components)
  /// (boundary id, component): one displacement component held (rollers, symmetry, plane strain)
  std::vector<std::pair<int, int>> rollers;
  /// The processes that share the body (MPI_COMM_SELF: this process alone).
  MPI_Comm communicator = MPI_COMM_WORLD;
  /// Local refinement (hanging nodes), after the global refinements: `local_refinements` times
  /// the cells with a vertex within `refine_distance` [m] of the boundaries `refine_boundaries`
  /// (of a vertex or centre of their faces in the mesh read).
  std::set<int> refine_boundaries;
  double        refine_distance   = 0;
  unsigned      local_refinements = 0;
  /// Only within these boxes (centre, half sizes along the rows of `axes`, orthonormal): the
  /// boundaries' faces with a sample point in one of them (empty: the whole boundaries).
  struct Box
  {
    Vec3            centre = Vec3::Zero(), half_size = Vec3::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  };
  std::vector<Box> refine_boxes;
  /// Each pass within half the previous pass's distance (the cells it refines are half as
  /// large): a graded zone whose finest layer is as thick as its elements, not the first pass's.
  bool halve_refine_distance = false;
  /// The exact surfaces the facets of the boundaries `surface_boundaries` approximate: given
  /// the boundary id and a point on or near its facets, the point of the surface it stands for
  /// and the surface's outward unit normal there. A vertex new in a refinement of these
  /// boundaries goes onto the surface (else between its parents, on the facets), and the
  /// traction of an analytic near field on them (remainder_response) is taken with the exact
  /// normal (else with the facets' vertex normals interpolated, which on a strongly curved
  /// surface tilt by a good part of an element's angle: the force's 1/r^2 stresses then put a
  /// traction on the facets around it that no quadrature integrates reliably).
  std::set<int>                                           surface_boundaries;
  std::function<SurfacePoint(int boundary, const Vec3 &)> boundary_surface;
  /// Threads that assemble the remainder loads (remainder_response); 0: as many as the
  /// hardware runs.
  unsigned threads = 0;
  /// Memory the direct factorisation may take on each machine [bytes]; 0: what the machine
  /// has available now (MemAvailable). Before factorising, MUMPS's analysis estimates its need
  /// (per process, times the processes on the machine); where the factorisation does not fit
  /// in memory but does with its factors in files (out of core), it is done so; a body that
  /// would not fit either way is refused (MemoryRefusal with the estimates) instead of being
  /// killed for want of memory half way.
  double memory_available = 0;
};

/// A force F (vector) spread uniformly over the part of the boundary (ids `boundaries`) within
/// `radius` of `point` (or, with a non-zero `half_size`, within the box of those half sizes
/// about `point` along the rows of `axes`, orthonormal); the total applied equals F exactly.
struct PatchLoad
{
  Vec3            point  = Vec3::Zero();
  Vec3            force  = Vec3::Zero();
  double          radius = 0;
  std::set<int>   boundaries;
  Vec3            half_size = Vec3::Zero();
  Eigen::Matrix3d axes      = Eigen::Matrix3d::Identity();
};

/// A unit normal point force on the boundary whose near field is carried analytically:
/// Boussinesq's field of the half-space tangent at `point` (inward normal `direction`, unit:
/// the force pushes along it), cut off smoothly between the radii `inner` and `outer` about the
/// point [m], and by elevation above the tangent plane (near_field_cutoff: none of it within
/// 30 degrees of the ray opposite the force, where it is singular, so the sphere may reach the
/// body across the force). The cut-off sphere must not reach a held boundary.
struct NearFieldLoad
{
  Vec3   point = Vec3::Zero(), direction = Vec3::Zero();
  double inner = 0, outer = 0;
};

/// The libraries the finite elements run on, with their versions, and OpenBLAS's kernels
/// ("deal.II 9.4.0, PETSc 3.18.4, gmsh 4.8.4, OpenBLAS SkylakeX kernels").
std::string
finite_element_versions();

/// A displacement component to read: the displacement at `point` projected on `direction`.
struct Probe
{
  Vec3 point = Vec3::Zero(), direction = Vec3::Zero();
};

class ElasticSegment
{
public:
  /// Reads the gmsh mesh (hexahedra; physical surface tags become boundary ids), refines it and
  /// numbers its dofs; the stiffness matrix is assembled and factorised at the first solve (or
  /// the first question about the solver below), remainder_response's loads beside it. Throws
  /// InputError for a missing or non-hexahedral file, a bad material, degree or an unknown
  /// boundary id, and a body that is not held (singular stiffness); MemoryRefusal where the
  /// matrix would not fit (here) or its factors (at the first solve).
  ElasticSegment(const std::string &mesh_file, const ElasticSegmentOptions &options);
  ~ElasticSegment();

  /// D(j, i): probe j's displacement under load i alone [m per load as given].
  Eigen::MatrixXd
  response(const std::vector<PatchLoad> &loads, const std::vector<Probe> &probes) const;

  /// D(j, i): the work of measure j (a patch load, its force a unit vector) on the displacement
  /// under load i alone, i.e. the displacement along measure j's force averaged over its patch.
  /// With the loads as their own measures: the symmetric compliance of the patches (the
  /// Galerkin counterpart of point probes, smooth where patches cut elements).
  Eigen::MatrixXd
  patch_response(const std::vector<PatchLoad> &loads, const std::vector<PatchLoad> &measures) const;

  /// D(j, i): probe j's displacement under the unit point force i less the force's cut-off
  /// half-space field chi u (half_space.h: near_field_cutoff, cut_off_near_field), which the caller
  /// adds analytically where it needs it. The finite elements solve only the smooth remainder w:
  /// a(w, v) = -(boundary integral of sigma(chi u) n . v) + (integral of div sigma(chi u) . v),
  /// so that no element has to resolve the 1/r field of the force; the total displacement is
  /// chi u + w. Each load is balanced to its unit force exactly, as the continuous remainder's
  /// is (the elements carry all of it to the held faces): assembled on the faceted elements
  /// against the exact surface it is out of balance by up to a few per cent, which is spread
  /// back over the cut-off's shell like |grad chi|.
  Eigen::MatrixXd
  remainder_response(const std::vector<NearFieldLoad> &loads,
                     const std::vector<Probe>         &probes) const;

  /// The same for one load set applied together; the sum of the reaction forces at the held
  /// boundaries equals minus the sum of the loads.
  Eigen::VectorXd
  response(const std::vector<PatchLoad> &loads_together, const std::vector<Probe> &probes,
           Vec3 *reaction) const;

  /// Displacement and von Mises stress of a load set applied together, as VTU (one file per
  /// process with a .pvtu record when parallel), written via temporary names.
  void
  write_vtu(const std::vector<PatchLoad> &loads_together, const std::string &path) const;

  /// For each point: a lower bound of its distance to the held boundaries (the nearest held
  /// face's centre less half its diameter) [m]. Collective.
  std::vector<double>
  distance_to_held(const std::vector<Vec3> &points) const;

  /// For each point: does it lie in the body (on any process)? Collective.
  std::vector<bool>
  contains(const std::vector<Vec3> &points) const;

  std::size_t
  cells() const;
  std::size_t
  dofs() const;
  /// The factorisation's wall time, and that of the matrix's assembly and factorisation
  /// together (solver set-up) [s]. These and the two below set the solver up if no solve has.
  double
  factorisation_seconds() const;
  double
  solver_seconds() const;
  /// Whether MUMPS keeps its factors in files: taken where they did not fit in memory but do
  /// so (ElasticSegmentOptions::memory_available).
  bool
  factors_out_of_core() const;
  /// The PETSc solver in use, "<ksp type>/<pc type>": "preonly/cholesky" unless run-time
  /// options chose another (e.g. "cg/gamg").
  std::string
  solver() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
} // namespace gearkit

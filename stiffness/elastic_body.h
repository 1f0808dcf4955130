// Linear elasticity of one 3-D body with deal.II (distributed triangulation, FE_Q^3 of degree 1
// or 2, hanging nodes) and PETSc: the stiffness matrix assembled once; loads as constant
// tractions on boundaries or as total forces spread uniformly over surface patches; solved
// iteratively (CG + algebraic multigrid) or directly (MUMPS Cholesky factorised once, reused for
// every right-hand side); read back as point displacements, patch averages, rigid motions of
// boundaries, reactions, and VTU files. All quantities SI (m, N, Pa, rad). MPI-parallel: every
// function is collective over the body's communicator and returns the same value on every rank.
//
// Run-time solver options the PETSc way (PETSC_OPTIONS environment variable, command line, or
// PetscOptionsSetValue before the first solve of that kind):
//  * iterative solver, no prefix: every KSP and PC option (-ksp_type, -ksp_rtol, -ksp_max_it,
//    -ksp_norm_type, -ksp_monitor, -ksp_view, -pc_type, -pc_hypre_boomeramg_*, -pc_gamg_*, ...)
//    overrides the defaults set from ElasticBodyOptions (CG, unpreconditioned residual norm,
//    the chosen preconditioner, relative_tolerance, max_iterations);
//  * direct solver, prefix "direct_": e.g. -direct_pc_factor_mat_solver_type superlu_dist,
//    -direct_pc_type lu, -direct_mat_mumps_icntl_14 50, -direct_ksp_view.
// Options are read when the solver is set up (the first solve_iterative, resp. factorise()).
#pragma once

#include "half_space.h"
#include "types.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <petscksp.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace gearkit
{
/// One refinement sweep: every cell that may meet the ball is split in eight.
struct RefinementBall
{
  Vec3   centre = Vec3::Zero();
  double radius = 0; ///< [m]
};

struct ElasticBodyOptions
{
  unsigned degree             = 1; ///< FE_Q degree: 1 or 2
  unsigned global_refinements = 0; ///< uniform refinements of the coarse mesh
  /// Local refinement sweeps after the global ones, in order (nested balls grade the mesh).
  std::vector<RefinementBall> local_refinements;
  Material                    material; ///< isotropic: E > 0, -1 < nu < 0.5
  /// Boundary ids held fixed (all displacement components zero).
  std::set<dealii::types::boundary_id> clamped;
  /// (boundary id, component 0/1/2): one displacement component held zero (roller, symmetry).
  std::vector<std::pair<dealii::types::boundary_id, unsigned>> fixed_components;
  std::string preconditioner     = "boomeramg"; ///< iterative solver: "boomeramg" or "gamg"
  double      relative_tolerance = 1e-10; ///< iterative: |f - K u| <= tolerance |f|
  unsigned    max_iterations     = 2000;  ///< iterative
  MPI_Comm    communicator       = MPI_COMM_WORLD;
};

/// A constant traction on a whole boundary [Pa].
struct Traction
{
  dealii::types::boundary_id boundary = 0;
  Vec3                       traction = Vec3::Zero();
};

/// The part of a boundary whose face quadrature points lie within `radius` of `centre`.
/// Loads and averages on a patch use the same points, so they are work-conjugate.
struct SurfacePatch
{
  dealii::types::boundary_id boundary = 0;
  Vec3                       centre   = Vec3::Zero();
  double                     radius   = 0; ///< [m]
};

/// A total force [N] applied as the uniform traction force / area over a patch; the applied
/// total equals `force` exactly, whatever the mesh.
struct PatchForce
{
  SurfacePatch patch;
  Vec3         force = Vec3::Zero();
};

/// Loads applied together: one right-hand side.
struct LoadSet
{
  std::vector<Traction>   tractions;
  std::vector<PatchForce> patch_forces;
};

/// An assembled load set: `constrained` is the right-hand side the solvers take, `nodal` the
/// consistent nodal forces before constraints (reactions subtract them) [N].
struct AssembledLoad
{
  dealii::PETScWrappers::MPI::Vector constrained, nodal;
};

/// Least-squares rigid motion u(x) ~ translation + rotation x (x - reference point).
struct RigidMotion
{
  Vec3 translation = Vec3::Zero(); ///< of the reference point [m]
  Vec3 rotation    = Vec3::Zero(); ///< rotation vector [rad]; independent of the reference
};

/// Resultant of the forces the supports exert on the body at one boundary.
struct Wrench
{
  Vec3 force  = Vec3::Zero(); ///< [N]
  Vec3 moment = Vec3::Zero(); ///< about the point given [N m]
};

/// Sizes and wall times (seconds, the slowest rank) of the work done so far.
struct ElasticBodyStatistics
{
  std::size_t cells = 0, dofs = 0;
  double      setup_seconds            = 0; ///< mesh, dofs, constraints, matrix assembly
  double      factorisation_seconds    = 0; ///< the MUMPS factorisation (once)
  double      last_direct_seconds      = 0; ///< last solve_direct (with the factorisation if it
                                            ///< triggered it)
  double      last_iterative_seconds   = 0; ///< last solve_iterative (the first one includes the
                                            ///< preconditioner set-up)
  unsigned    last_iterations          = 0; ///< of the last solve_iterative
  std::string iterative_method;             ///< "KSP type + PC type" actually used, e.g. "cg + hypre"
};

class ElasticBody
{
public:
  /// Displacement field: a ghosted PETSc vector (locally owned and relevant entries) [m].
  using Displacement = dealii::PETScWrappers::MPI::Vector;

  /// Reads a gmsh .msh file (all hexahedra; physical surface tags become boundary ids), refines,
  /// sets up the constraints and assembles the stiffness matrix. Throws InputError for a missing
  /// or unreadable file, cells that are not hexahedra, bad options or an unknown boundary id.
  ElasticBody(const std::string &mesh_file, const ElasticBodyOptions &options);

  /// The same from a coarse (unrefined, all-hexahedral) triangulation, e.g. from GridGenerator.
  ElasticBody(const dealii::Triangulation<3> &coarse_mesh, const ElasticBodyOptions &options);

  ~ElasticBody();
  ElasticBody(const ElasticBody &) = delete;
  ElasticBody &
  operator=(const ElasticBody &) = delete;

  /// Right-hand side of a load set. Throws InputError for an unknown boundary id, a patch of
  /// radius <= 0 or one that contains no face quadrature point.
  AssembledLoad
  assemble(const LoadSet &loads) const;

  /// Iterative solve (CG + BoomerAMG or GAMG, see ElasticBodyOptions and the run-time options
  /// above); the preconditioner is set up on the first call and reused. Throws InputError when
  /// the solver does not converge.
  Displacement
  solve_iterative(const AssembledLoad &load);

  /// Factorises the stiffness matrix (MUMPS Cholesky); done once, kept for every solve_direct.
  /// Throws InputError when the factorisation fails (e.g. a body free to move rigidly).
  void
  factorise();

  /// Direct solve with the kept factorisation (factorises first if not done yet).
  Displacement
  solve_direct(const AssembledLoad &load);

  /// Displacements at points anywhere in the body [m] (evaluated by the owning rank, known on
  /// all). Throws InputError for a point outside the mesh.
  std::vector<Vec3>
  displacements(const Displacement &u, const std::vector<Vec3> &points) const;

  /// Area of a patch as loads and averages see it (sum of its quadrature weights) [m^2].
  double
  patch_area(const SurfacePatch &patch) const;

  /// Work-conjugate mean displacement of a patch, the integral of u over the patch / area [m]:
  /// a PatchForce F on the same patch does the work F . mean.
  Vec3
  patch_average(const Displacement &u, const SurfacePatch &patch) const;

  /// Least-squares rigid motion of a boundary (6 unknowns, area-weighted on the face quadrature
  /// points), the translation given at `reference_point`. Throws InputError for an unknown id.
  RigidMotion
  rigid_motion(const Displacement &u, dealii::types::boundary_id boundary,
               const Vec3 &reference_point) const;

  /// Rotation [rad] of a boundary about an axis (through `axis_point` along `axis_direction`,
  /// right-handed), from the rigid fit: e.g. the loaded rotation of a gear from its bore.
  double
  rigid_rotation(const Displacement &u, dealii::types::boundary_id boundary,
                 const Vec3 &axis_point, const Vec3 &axis_direction) const;

  /// Force and moment (about `moment_point`) that the supports exert on the body on a boundary:
  /// the residual K u - f summed over the boundary's degrees of freedom (exact equilibrium with
  /// the applied loads; a node on an edge shared by two boundaries counts for both).
  Wrench
  reaction(const Displacement &u, const AssembledLoad &load, dealii::types::boundary_id boundary,
           const Vec3 &moment_point) const;

  /// Writes displacement and von Mises stress [Pa] as `directory`/`name`.vtu (one process) or
  /// `name`.pvtu with pieces `name`.<rank>.vtu; each file goes to a temporary name first and is
  /// renamed when all are complete. Returns the path of the .vtu/.pvtu file. Throws InputError
  /// when writing fails, leaving none of the files behind.
  std::string
  write_vtu(const Displacement &u, const std::string &directory, const std::string &name) const;

  /// Number of active cells (all ranks).
  std::size_t
  n_cells() const;
  /// Number of degrees of freedom (all ranks).
  std::size_t
  n_dofs() const;
  /// Sizes and timings.
  const ElasticBodyStatistics &
  statistics() const;

private:
  /// Sets up everything once the coarse mesh is known; `source` names it in messages.
  ElasticBody(const dealii::Triangulation<3> &coarse_mesh, const ElasticBodyOptions &options,
              const std::string &source);

  void
  require_boundary(dealii::types::boundary_id id, const char *what) const;
  void
  assemble_matrix();
  /// Element stiffness of a cell (sigma = lambda tr(eps) I + 2 mu eps).
  void
  cell_matrix(const dealii::DoFHandler<3>::active_cell_iterator &cell,
              dealii::FEValues<3> &values, dealii::FullMatrix<double> &local) const;
  /// Rigid-body modes as the near null space of the matrix (used by GAMG).
  void
  attach_rigid_body_modes();
  /// Ghosted displacement from the solver's result, constraints applied.
  Displacement
  completed(dealii::PETScWrappers::MPI::Vector &x) const;

  ElasticBodyOptions                      options;
  std::string                             source;
  MPI_Comm                                comm;
  double                                  lambda = 0, mu = 0;
  dealii::parallel::distributed::Triangulation<3> triangulation;
  dealii::FESystem<3>                     fe;
  dealii::MappingQ<3>                     mapping;
  dealii::DoFHandler<3>                   dof_handler;
  dealii::IndexSet                        owned, relevant;
  dealii::AffineConstraints<double>       constraints;
  dealii::PETScWrappers::MPI::SparseMatrix matrix;
  std::set<dealii::types::boundary_id>    boundary_ids;
  KSP                                     iterative = nullptr, direct = nullptr;
  ElasticBodyStatistics                   stats;
};
} // namespace gearkit

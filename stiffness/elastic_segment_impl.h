// The implementation of ElasticSegment (elastic_segment.h), private to its sources: the body's
// state, the phases that build and use it, and the few helpers more than one source needs. One
// source per phase:
//   elastic_segment.cc             the public class: the constructor runs the phases in order;
//                                  sizes, timings, point queries, a load set's response, VTU,
//                                  the memory estimates every phase checks against
//   elastic_segment_mesh.cc        the mesh read and checked, refined (globally, about boundaries,
//                                  onto exact surfaces), its dofs numbered and held, the boundary
//                                  faces' caches
//   elastic_segment_assembly.cc    the stiffness matrix (element matrices, condensed rows) and
//                                  the reaction forces
//   elastic_segment_near_field.cc  the remainder loads of unit point forces whose near field is
//                                  carried analytically: their quadratures about the cut-off's
//                                  shell, the exact surfaces, the balance
//   elastic_segment_unit_loads.cc  patch loads, probes and load functionals, and the responses
//                                  to many unit loads
//   elastic_segment_solver.cc      the solver's set-up (MUMPS Cholesky with its memory check, or
//                                  what run-time options ask for) and the solves, one and blocks
// Included by those sources alone, which all speak deal.II's names (the using-directive below).
#pragma once

#include "stiffness/elastic_segment.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mpi.h>
#include <petscksp.h>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace gearkit
{
/// Helpers of the elastic segment's sources (elastic_segment_impl.h).
namespace elastic_segment_detail
{
/// Throws InputError naming the PETSc call that failed.
inline void
petsc_check(PetscErrorCode error, const char *what)
{
  if (error != 0)
    throw InputError(std::string("elastic segment: PETSc failed in ") + what + " (error " +
                     std::to_string(error) + "); check the solver options given at run time");
}

inline dealii::Point<3>
point(const Vec3 &x)
{
  return dealii::Point<3>(x.x(), x.y(), x.z());
}

/// The bytes that `need` (this process's) add up to over the processes on each machine, and
/// whether every machine has them (`have`: its available memory; <= 0: unknown, fits).
std::pair<double, bool>
machine_need(double need, double have, MPI_Comm comm);

/// Throws MemoryRefusal "elastic segment: <what> needs about <X> GB on a machine with <Y> GB
/// available. <advice>" unless `need` bytes per process fit (machine_need; collective).
void
require_memory(double need, double have, MPI_Comm comm, const std::string &what,
               const std::string &advice);

/// Bytes of the assembled system per degree of freedom (FE_Q(p) hexahedra): a node couples with
/// the nodes of the elements around it, (2p + 1)^3 for a vertex, (2p + 1)^2 (p + 1) for an edge
/// node, (2p + 1) (p + 1)^2 for a face node and (p + 1)^3 for an interior one; per element 1,
/// 3 (p - 1), 3 (p - 1)^2 and (p - 1)^3 of them (64 couplings per node on average for Q2);
/// about 40 bytes per nonzero (pattern, PETSc's matrix, MUMPS's copy).
double
matrix_bytes_per_dof(unsigned degree);

/// Gauss rules on the cells and faces of a near-field load's cut-off shell are subdivided up
/// to this many times per direction.
constexpr unsigned max_rule_subdivisions = 4;
} // namespace elastic_segment_detail

using namespace dealii;
using namespace elastic_segment_detail;

struct ElasticSegment::Impl
{
  MPI_Comm              comm;
  ElasticSegmentOptions options;
  /// The whole mesh on every process, each owning a part (deal.II refines it: p4est's balance
  /// crashed on twisted helical segments refined about contact cells)
  parallel::shared::Triangulation<3> tria;
  FESystem<3>                        fe;
  /// The scalar element of each component: the remainder loads' quadratures use its shape
  /// values (FESystem would copy its base's values into its own on every cell).
  FE_Q<3>                              scalar_fe;
  DoFHandler<3>                        dofs;
  MappingQ1<3>                         mapping;
  std::unique_ptr<GridTools::Cache<3>> cache_ptr; ///< cell search (R-tree) for probes
  IndexSet                             owned, relevant;
  AffineConstraints<double>            constraints;
  Mat                                  K   = nullptr; ///< the stiffness matrix (assemble_matrix)
  KSP                                  ksp = nullptr;
  std::string                          solver_name; ///< KSP type / PC type
  /// The MUMPS Cholesky factor (the default); null where run-time options chose another solver
  /// (the KSP then solves).
  Mat    factor         = nullptr;
  bool   out_of_core    = false; ///< the factors in files (factorise: in core they did not fit)
  double factor_seconds = 0;
  /// The stiffness matrix's assembly and the factorisation (or whatever the run-time options
  /// chose) wait for the first solve (set_up_solver), so that a block of right-hand sides can
  /// be assembled beside them (remainder_response).
  std::string mesh_file;
  bool        solver_ready   = false;
  double      solver_seconds = 0; ///< the matrix's assembly and the factorisation
  double      lambda = 0, mu = 0;

  /// Boundary quadrature of the faces with a boundary id, cached for fast load assembly.
  struct FaceData;
  std::vector<FaceData> faces;
  /// Per (vertex, boundary id): the area-weighted mean outward normal of the boundary faces
  /// with that id around the vertex; interpolated over a face, a smooth normal field of the
  /// curved surface the facets approximate (see smooth_normal).
  std::map<std::pair<unsigned, int>, Tensor<1, 3>> vertex_normals;
  /// A boundary face's id, corners and the mean normals there (summed, with their lengths).
  struct FaceNormals;
  FaceNormals
  face_normals(const typename DoFHandler<3>::active_cell_iterator &cell, unsigned face) const;
  /// The smooth outward normal at a point of a boundary face (bilinear in the face's vertex
  /// normals): the traction a curved surface would carry, without the facets' kinks.
  static Tensor<1, 3>
  smooth_normal(const FaceNormals &face, const Point<3> &x);
  /// The surface a point of a boundary face stands for, and its outward normal there: the
  /// exact surface's point and normal where the options give one for the face's boundary,
  /// else the point itself and the smooth normal.
  std::pair<Point<3>, Tensor<1, 3>>
  surface_point(const FaceNormals &face, const Point<3> &x) const;
  /// A rule on a boundary face split at the face's point nearest to x (SplitRule), if that
  /// point is within `within` of x (else empty).
  struct SplitRule;
  SplitRule
  split_face_rule(const typename Triangulation<3>::active_cell_iterator &cell, unsigned face,
                  const Point<3> &x, double within) const;
  /// A cell's Gauss rule subdivided k times per direction (see its definition).
  struct SubdividedRule;
  /// What one thread needs to assemble remainder loads (see its definition).
  struct RemainderScratch;
  /// The exact-surface points and normals (surface_point) of a boundary face's quadrature
  /// points on one of its rules: the same for every load, and costly on a generated spiral
  /// bevel flank (a Newton solve each). Per (active cell, face, rule: the subdivided ones, then
  /// near_face), filled as the loads first need them, from any thread; kept with the body.
  struct SurfacePoints;
  static constexpr unsigned                               face_rules = max_rule_subdivisions + 1;
  mutable std::unique_ptr<std::atomic<SurfacePoints *>[]> surface_points;
  const SurfacePoints &
  face_surface_points(const typename Triangulation<3>::active_cell_iterator &cell, unsigned face,
                      unsigned rule, const FaceNormals &normals,
                      const FEFaceValues<3> &values) const;
  /// A fine face quadrature for the faces a patch's edge cuts (a patch's area and centroid
  /// then do not jump with where its edge falls between the Gauss points).
  std::unique_ptr<FEFaceValues<3>> fine_face_values;

  Impl(unsigned degree, MPI_Comm communicator);
  ~Impl();

  // The body, in the constructor's order (elastic_segment_mesh.cc).
  /// Reads mesh_file into `coarse`; refuses (InputError) a file deal.II cannot read, cells
  /// other than hexahedra, and degenerate or inverted hexahedra.
  void
  read_mesh(Triangulation<3> &coarse) const;
  /// tria: `coarse` with its exact surfaces (manifolds), refined globally and then about the
  /// boundaries asked for; the cell search's cache on it.
  void
  refine(Triangulation<3> &coarse);
  /// The boundary ids of the refined mesh (all processes'). Collective.
  std::set<types::boundary_id>
  boundary_ids() const;
  /// Numbers the dofs (owned ones and dof_component).
  void
  distribute_dofs();
  /// The hanging nodes' and the held boundaries' constraints; refuses boundary ids of the
  /// options that are not among `present` and bad roller components.
  void
  make_constraints(const std::set<types::boundary_id> &present);
  /// The boundary faces' caches: their quadrature for patch loads (faces), the vertex normals
  /// and the fine face quadrature.
  void
  cache_boundary_faces();

  bool
  held(int boundary) const;
  /// A lower bound of x's distance to this process's held faces (centre less half the
  /// diameter; HUGE_VAL without any).
  double
  local_distance_to_held(const Point<3> &x) const;
  /// The six rigid-body motions as the near-null space of K (for smoothed aggregation AMG).
  void
  set_rigid_body_near_null_space();
  /// Throws InputError when the sparsity pattern, the matrix and the direct solver's copy of
  /// it (about 40 bytes per nonzero, the nonzeros estimated from the element's couplings) would
  /// not fit in the memory available on some machine: refused before they are built.
  void
  check_assembly_fits() const;
  /// The MUMPS Cholesky factor of K; throws InputError when MUMPS's analysis estimates more
  /// memory for it on some machine than the machine has available (options.memory_available,
  /// else MemAvailable), before factorising.
  void
  factorise();
  /// Assembles the stiffness matrix and sets its solver up (MUMPS: factorises), once;
  /// collective.
  void
  set_up_solver();
  /// The stiffness matrix K, sigma = lambda tr(eps) I + 2 mu eps, condensed by the
  /// constraints (see the definition).
  void
  assemble_matrix();
  /// Element stiffness of a cell (values: gradients and JxW on the cell quadrature).
  void
  local_matrix(const typename DoFHandler<3>::active_cell_iterator &cell, FEValues<3> &values,
               FullMatrix<double> &local) const;
  /// The sum of the reaction forces at the held boundaries under the displacement u (all
  /// processes'). Collective.
  Vec3
  reaction(const PETScWrappers::MPI::Vector &u) const;
  PETScWrappers::MPI::Vector
  assemble_loads(const std::vector<PatchLoad> &loads) const;
  /// Refuses (InputError, on every process) a near-field load with bad data or whose cut-off
  /// sphere reaches a held boundary. Collective.
  void
  check_near_field_loads(const std::vector<NearFieldLoad> &loads) const;
  /// Adds this process's cells' part of the load vector of the remainder w of a near-field
  /// load (see remainder_response) to scratch.f, and that of the weight the balance spreads
  /// (|grad chi| over the cut-off's shell) to scratch.g. Thread-safe (no MPI).
  void
  assemble_remainder_load(const NearFieldLoad &load, RemainderScratch &scratch) const;
  /// A near-field load's cut-off shell: chi, the field chi u, and the resolution the
  /// quadratures need about an object there (elastic_segment_near_field.cc).
  struct LoadShell;
  /// assemble_remainder_load's phases on one cell near the load (`tria_cell` and `cell` the
  /// same cell, of the triangulation and of the dofs): the body force of chi u in the cell
  /// (`radius`: half the cell's diameter; `resolved`: the length its rule must resolve) with
  /// the spread weight (into scratch.g), then the traction of chi u on the cell's boundary
  /// faces within the outer radius; both added to `local`, the cell's load.
  void
  add_remainder_body_force(const LoadShell                                       &shell,
                           const typename Triangulation<3>::active_cell_iterator &tria_cell,
                           const typename DoFHandler<3>::active_cell_iterator &cell, double radius,
                           double resolved, RemainderScratch &scratch, Vector<double> &local,
                           std::vector<types::global_dof_index> &indices) const;
  void
  add_remainder_traction(const LoadShell                                       &shell,
                         const typename Triangulation<3>::active_cell_iterator &tria_cell,
                         const typename DoFHandler<3>::active_cell_iterator    &cell,
                         RemainderScratch &scratch, Vector<double> &local) const;
  /// Balances the remainder loads (entries per load from every process: dofs, values and the
  /// spread weights g beside them) to their unit forces exactly, as the continuous problem's
  /// are; see remainder_response. Returns each load's resultant before (all processes').
  /// Collective.
  std::vector<Vec3>
  balance_remainder_loads(const std::vector<NearFieldLoad>         &loads,
                          const std::vector<std::vector<PetscInt>> &rows,
                          std::vector<std::vector<double>>         &values,
                          const std::vector<std::vector<double>>   &spreads) const;
  /// The displacement component (0, 1, 2) of each dof of this process's cells.
  std::vector<unsigned char> dof_component;
  PETScWrappers::MPI::Vector
  solve(const PETScWrappers::MPI::Vector &rhs) const;
  /// Per probe: the owning rank's functional (dof indices, coefficients); empty elsewhere.
  std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>>
  probe_functionals(const std::vector<Probe> &probes) const;
  /// Per load: its load vector's owned entries (the work it does on a displacement field).
  std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>>
  load_functionals(const std::vector<PatchLoad> &loads) const;
  Eigen::VectorXd
  evaluate(
      const std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>> &f,
      const PETScWrappers::MPI::Vector &u) const;
  /// The functionals (as from probe_functionals) as the rows of a sparse matrix over the dofs,
  /// all rows on the first process, every constrained dof's coefficient moved onto the dofs
  /// it is bound to: row j times a solution of K is functional j of the displacement field
  /// the constraints complete it to. Collective; the caller destroys it.
  Mat
  functional_matrix(
      const std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>> &f)
      const;
  /// Load vector i's entries from this process (global dofs, values; dofs of other processes
  /// too: they are added where they live).
  using LoadEntries =
      std::function<void(std::size_t i, std::vector<PetscInt> &dofs, std::vector<double> &values)>;
  /// D(j, i): functional j of the displacement under load vector i alone (n load vectors).
  Eigen::MatrixXd
  responses(std::size_t n, const LoadEntries &entries,
            const std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>>
                &functionals) const;
};

struct ElasticSegment::Impl::FaceData
{
  int                                          boundary;
  Point<3>                                     centre;
  double                                       diameter;
  std::vector<types::global_dof_index>         dof_indices;
  std::vector<Point<3>>                        q_points;
  std::vector<double>                          JxW;
  std::vector<std::array<double, 3>>           shape; ///< [q * dofs_per_cell + i] -> components
  typename DoFHandler<3>::active_cell_iterator cell;
  unsigned                                     face_no = 0;
  std::array<Point<3>, 4>                      vertices;
};

struct ElasticSegment::Impl::FaceNormals
{
  int                         boundary = 0;
  std::array<Point<3>, 4>     vertex;
  std::array<Tensor<1, 3>, 4> sum;
  std::array<double, 4>       length;
};

/// A rule on a boundary face split at the face's point nearest to x into triangles, each with
/// the Duffy rule collapsed there (deal.II QSplit of QDuffy: exact for a 1 / r singularity at
/// that point): the scalar element's values at its points (FEValues on the rule projected to
/// the face, which sets up far fewer shape values than FEFaceValues) and the points' surface
/// weights.
struct ElasticSegment::Impl::SplitRule
{
  std::unique_ptr<FEValues<3>> values;
  std::vector<double>          JxW;
};

/// A cell's Gauss rule subdivided k times per direction, point by point of its k^3 sub-cells
/// (each sub-cell's points together), with the scalar shape functions' values there (the same
/// on every cell).
struct ElasticSegment::Impl::SubdividedRule
{
  unsigned              k = 1, per_subcell = 0;
  std::vector<Point<3>> points;  ///< on the reference cell
  std::vector<double>   weights; ///< (summing to 1)
  Eigen::MatrixXd       phi;     ///< (scalar shape function, point)
  SubdividedRule(const FiniteElement<3> &scalar_fe, unsigned gauss, unsigned k);
};

/// What one thread needs to assemble remainder loads: their quadratures (built once per thread,
/// their shape values are costly to set up) and a load vector over all dofs. The cut-off's shell
/// is often no wider than an element where a tooth is thin: a cell or face there takes its
/// Gauss rule subdivided (rule_subdivisions), the faces next to the force a finer rule still.
struct ElasticSegment::Impl::RemainderScratch
{
  std::vector<SubdividedRule>                   volume;    ///< [m - 1]: m subdivisions
  std::vector<std::unique_ptr<FEFaceValues<3>>> face;      ///< [m - 1]: m subdivisions
  FEFaceValues<3>                               near_face; ///< (of the scalar element)
  /// A sub-cell's body forces (point, component) and a cell's sums (scalar shape function,
  /// component).
  Eigen::Matrix<double, Eigen::Dynamic, 3> forces, body;
  /// The same for the weight |grad chi| that spreads the balance (balance_remainder_loads):
  /// a sub-cell's (point) and a cell's sums (scalar shape function).
  Eigen::VectorXd spread_at, spread;
  /// Per shape function of the vector element: its component and scalar shape function.
  std::vector<unsigned> component, scalar;
  /// The load vector, and per dof the integral of its shape function times |grad chi|.
  Vector<double> f, g;
  explicit RemainderScratch(const Impl &m);
};

struct ElasticSegment::Impl::SurfacePoints
{
  std::vector<Point<3>>     at;
  std::vector<Tensor<1, 3>> normal;
};
} // namespace gearkit

#include "stiffness/elastic_segment.h"

#include "base/blas_kernels.h"
#include "base/parallel.h"
#include "meshes/gmsh_session.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/qprojector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/rtree.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <malloc.h>
#include <map>
#include <petscksp.h>
#include <petscversion.h>
#include <sstream>
#include <stdexcept>

namespace gearkit
{
using namespace dealii;

namespace
{
void
petsc_check(PetscErrorCode error, const char *what)
{
  if (error != 0)
    throw InputError(std::string("elastic segment: PETSc failed in ") + what + " (error " +
                     std::to_string(error) + "); check the solver options given at run time");
}

Point<3>
point(const Vec3 &x)
{
  return Point<3>(x.x(), x.y(), x.z());
}

/// The new vertices of a refined boundary face or edge placed on the exact surface: the
/// flat average of their parents, projected.
class ProjectedSurface : public Manifold<3>
{
public:
  ProjectedSurface(int boundary, std::function<SurfacePoint(int, const Vec3 &)> project)
      : boundary(boundary)
      , project(std::move(project))
  {
  }
  std::unique_ptr<Manifold<3>>
  clone() const override
  {
    return std::make_unique<ProjectedSurface>(boundary, project);
  }
  Point<3>
  get_new_point(const ArrayView<const Point<3>> &points,
                const ArrayView<const double>   &weights) const override
  {
    Vec3 x = Vec3::Zero();
    for (std::size_t i = 0; i < points.size(); ++i)
      x += weights[i] * Vec3(points[i][0], points[i][1], points[i][2]);
    const Vec3 y = project(boundary, x).position;
    if (!y.allFinite())
      throw InputError("elastic segment: the surface of boundary " + std::to_string(boundary) +
                       " has no point for a refined vertex near (" + std::to_string(x.x() * 1e3) +
                       ", " + std::to_string(x.y() * 1e3) + ", " + std::to_string(x.z() * 1e3) +
                       ") mm");
    return point(y);
  }

private:
  int                                            boundary;
  std::function<SurfacePoint(int, const Vec3 &)> project;
};

/// von Mises stress from the displacement gradient.
class VonMises : public DataPostprocessorScalar<3>
{
public:
  VonMises(double lambda, double mu)
      : DataPostprocessorScalar<3>("von_mises_stress", update_gradients)
      , lambda(lambda)
      , mu(mu)
  {
  }
  void
  evaluate_vector_field(const DataPostprocessorInputs::Vector<3> &in,
                        std::vector<Vector<double>>              &out) const override
  {
    for (std::size_t q = 0; q < in.solution_gradients.size(); ++q)
      {
        Tensor<2, 3> grad;
        for (unsigned c = 0; c < 3; ++c)
          grad[c] = in.solution_gradients[q][c];
        const SymmetricTensor<2, 3> eps = symmetrize(grad);
        const SymmetricTensor<2, 3> sigma =
            lambda * trace(eps) * unit_symmetric_tensor<3>() + 2 * mu * eps;
        const SymmetricTensor<2, 3> dev = deviator(sigma);
        out[q](0)                       = std::sqrt(1.5 * (dev * dev));
      }
  }

private:
  double lambda, mu;
};
/// The bytes that `need` (this process's) add up to over the processes on each machine, and
/// whether every machine has them (`have`: its available memory; <= 0: unknown, fits).
std::pair<double, bool>
machine_need(double need, double have, MPI_Comm comm)
{
  MPI_Comm machine;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
  const double here = Utilities::MPI::sum(need, machine);
  MPI_Comm_free(&machine);
  const bool fits = !(have > 0) || here <= have;
  return {here, Utilities::MPI::min(fits ? 1 : 0, comm) == 1};
}

/// Bytes of the assembled system per degree of freedom (FE_Q(p) hexahedra): a node couples with
/// the nodes of the elements around it, (2p + 1)^3 for a vertex, (2p + 1)^2 (p + 1) for an edge
/// node, (2p + 1) (p + 1)^2 for a face node and (p + 1)^3 for an interior one; per element 1,
/// 3 (p - 1), 3 (p - 1)^2 and (p - 1)^3 of them (64 couplings per node on average for Q2);
/// about 40 bytes per nonzero (pattern, PETSc's matrix, MUMPS's copy).
double
matrix_bytes_per_dof(unsigned degree)
{
  const double p = degree, a = 2 * p + 1, b = p + 1;
  const double per_node = (a * a * a + 3 * (p - 1) * a * a * b + 3 * (p - 1) * (p - 1) * a * b * b +
                           (p - 1) * (p - 1) * (p - 1) * b * b * b) /
                          (p * p * p);
  return 3 * per_node * 40;
}

/// Refines (options.local_refinements times) the cells of `tria` with a vertex within
/// options.refine_distance (halved per pass if asked) of the samples of the faces of `mesh` (the
/// mesh read, whole on every process) with one of options.refine_boundaries (and inside one of
/// options.refine_boxes, if any).
void
refine_near_boundaries(const Triangulation<3> &mesh, parallel::shared::Triangulation<3> &tria,
                       const ElasticSegmentOptions &options)
{
  if (!(options.refine_distance >= 0) || options.refine_boundaries.empty())
    throw InputError("elastic segment: local refinement needs boundaries and a distance >= 0");
  // the boxes' centres in an R-tree; a point is in a box if it is in one of the nearest eight's
  std::vector<std::pair<Point<3>, std::size_t>> centres;
  for (std::size_t i = 0; i < options.refine_boxes.size(); ++i)
    centres.emplace_back(point(options.refine_boxes[i].centre), i);
  const auto centre_tree = pack_rtree(centres);
  auto       in_a_box    = [&](const Point<3> &x, double margin) {
    if (centres.empty())
      return true;
    std::vector<std::pair<Point<3>, std::size_t>> nearest;
    centre_tree.query(boost::geometry::index::nearest(x, 8), std::back_inserter(nearest));
    for (const auto &[c, i] : nearest)
      {
        const ElasticSegmentOptions::Box &b     = options.refine_boxes[i];
        const Vec3                        local = b.axes * (Vec3(x[0], x[1], x[2]) - b.centre);
        if ((local.cwiseAbs() - b.half_size).maxCoeff() <= margin)
          return true;
      }
    return false;
  };
  // the faces sampled at their vertices and centre; with halving distances or boxes on a grid
  // at most half the last pass's distance apart (the finest cells must all find the boundary)
  const double last = options.refine_distance *
                      (options.halve_refine_distance
                           ? std::ldexp(1.0, 1 - int(std::max(1u, options.local_refinements)))
                           : 1);
  std::vector<Point<3>> samples;
  for (const auto &face : mesh.active_face_iterators())
    if (face->at_boundary() && options.refine_boundaries.count(int(face->boundary_id())) &&
        in_a_box(face->center(), face->diameter()))
      {
        std::vector<Point<3>> x{face->center()};
        for (unsigned v = 0; v < 4; ++v)
          x.push_back(face->vertex(v));
        const int n = options.halve_refine_distance || !centres.empty()
                          ? std::max(1, int(std::ceil(2 * face->diameter() / last)))
                          : 1;
        if (n > 1)
          for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j)
              {
                const double a = double(i) / n, b = double(j) / n; // bilinear on the face
                x.push_back(Point<3>((1 - a) * (1 - b) * face->vertex(0) +
                                     a * (1 - b) * face->vertex(1) + (1 - a) * b * face->vertex(2) +
                                     a * b * face->vertex(3)));
              }
        std::copy_if(x.begin(), x.end(), std::back_inserter(samples),
                     [&](const Point<3> &y) { return in_a_box(y, 0); });
      }
  if (samples.empty())
    throw InputError("elastic segment: none of the boundaries to refine near is in the mesh" +
                     std::string(centres.empty() ? "" : " within the boxes given"));
  const auto     tree     = pack_rtree(samples);
  double         distance = options.refine_distance;
  const MPI_Comm comm     = tria.get_communicator();
  const double   have =
      options.memory_available > 0 ? options.memory_available : memory_available_now();
  for (unsigned pass = 0; pass < options.local_refinements;
       ++pass, distance *= options.halve_refine_distance ? 0.5 : 1)
    {
      // every process flags every cell alike (each refines the whole mesh)
      for (const auto &cell : tria.active_cell_iterators())
        for (unsigned v = 0; v < GeometryInfo<3>::vertices_per_cell; ++v)
          {
            std::vector<Point<3>> nearest;
            tree.query(boost::geometry::index::nearest(cell->vertex(v), 1),
                       std::back_inserter(nearest));
            if (nearest[0].distance(cell->vertex(v)) <= distance)
              {
                cell->set_refine_flag();
                break;
              }
          }
      // refused before the pass when the refined body's matrix would not fit (the same
      // estimate as before the assembly; each refined cell becomes eight)
      std::size_t flagged = 0;
      for (const auto &cell : tria.active_cell_iterators())
        flagged += cell->refine_flag_set() ? 1 : 0; // (a RefinementCase: 7 for isotropic)
      const double cells_after = double(tria.n_active_cells() + 7 * flagged);
      const double p           = options.degree;
      const auto [here, fits] =
          machine_need(cells_after * 3 * p * p * p * matrix_bytes_per_dof(options.degree) /
                           Utilities::MPI::n_mpi_processes(comm),
                       have, comm);
      if (!fits)
        {
          std::ostringstream msg;
          msg.precision(3);
          msg << "elastic segment: local refinement pass " << pass + 1 << " of "
              << options.local_refinements << " would make about " << cells_after
              << " elements, whose stiffness matrix needs about "
              << Utilities::MPI::max(here, comm) / 1e9 << " GB on a machine with "
              << Utilities::MPI::min(have, comm) / 1e9
              << " GB available. Use fewer refinements (larger elements at the contact) or "
                 "more machines under mpirun";
          throw MemoryRefusal(msg.str());
        }
      tria.execute_coarsening_and_refinement();
    }
}

/// Right-hand sides solved together: MUMPS's block (ICNTL(27), its default 32) and the most
/// columns of our dense blocks. 128 took the ISO/TR 6336-30 segments' solves from 18 s to 13 s;
/// larger blocks of ours took memory and no time.
constexpr std::size_t solve_block = 128;

/// (xi, eta) of the point of the bilinear face (vertices in lexicographic order: (0, 0),
/// (1, 0), (0, 1), (1, 1)) nearest to x, by Gauss-Newton; not clamped to the face.
std::pair<double, double>
bilinear_coordinates(const std::array<Point<3>, 4> &v, const Point<3> &x)
{
  double xi = 0.5, eta = 0.5;
  for (int it = 0; it < 8; ++it)
    {
      const Tensor<1, 3> r = v[0] * (1 - xi) * (1 - eta) + v[1] * xi * (1 - eta) +
                             v[2] * (1 - xi) * eta + v[3] * xi * eta - x;
      const Tensor<1, 3> dxi  = (v[1] - v[0]) * (1 - eta) + (v[3] - v[2]) * eta;
      const Tensor<1, 3> deta = (v[2] - v[0]) * (1 - xi) + (v[3] - v[1]) * xi;
      const double       a = dxi * dxi, b = dxi * deta, c = deta * deta;
      const double       p = -(dxi * r), q = -(deta * r), det = a * c - b * b;
      const double       step_xi = (c * p - b * q) / det, step_eta = (a * q - b * p) / det;
      xi += step_xi;
      eta += step_eta;
      if (std::abs(step_xi) + std::abs(step_eta) < 1e-13)
        break;
    }
  return {xi, eta};
}

/// Gauss rules on the cells and faces of a near-field load's cut-off shell are subdivided up
/// to this many times per direction.
constexpr unsigned max_rule_subdivisions = 4;

/// How often to subdivide the Gauss rule on a cell or face of about `size` (an edge) for it
/// to resolve a cut-off shell of width `shell`: into parts of at most half the shell. Measured
/// on a shell one element wide: the remainder at the force moved by 30 % as the force moved
/// within an element on the plain rule, by 3 % on rules subdivided twice or four times.
unsigned
rule_subdivisions(double size, double shell)
{
  return unsigned(std::clamp(std::ceil(2 * size / shell), 1.0, double(max_rule_subdivisions)));
}
} // namespace

double
memory_available_now()
{
  malloc_trim(0);
  std::ifstream in("/proc/meminfo");
  std::string   key;
  double        kb = 0;
  std::string   unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:")
      return kb * 1024;
  return 0;
}

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
  struct FaceData
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
  std::vector<FaceData> faces;
  /// Per (vertex, boundary id): the area-weighted mean outward normal of the boundary faces
  /// with that id around the vertex; interpolated over a face, a smooth normal field of the
  /// curved surface the facets approximate (see smooth_normal).
  std::map<std::pair<unsigned, int>, Tensor<1, 3>> vertex_normals;
  /// A boundary face's id, corners and the mean normals there (summed, with their lengths).
  struct FaceNormals
  {
    int                         boundary = 0;
    std::array<Point<3>, 4>     vertex;
    std::array<Tensor<1, 3>, 4> sum;
    std::array<double, 4>       length;
  };
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
  /// A rule on a boundary face split at the face's point nearest to x into triangles, each
  /// with the Duffy rule collapsed there (deal.II QSplit of QDuffy: exact for a 1 / r
  /// singularity at that point), if that point is within `within` of x (else empty): the
  /// scalar element's values at its points (FEValues on the rule projected to the face, which
  /// sets up far fewer shape values than FEFaceValues) and the points' surface weights.
  struct SplitRule
  {
    std::unique_ptr<FEValues<3>> values;
    std::vector<double>          JxW;
  };
  SplitRule
  split_face_rule(const typename Triangulation<3>::active_cell_iterator &cell, unsigned face,
                  const Point<3> &x, double within) const;
  /// A cell's Gauss rule subdivided k times per direction, point by point of its k^3
  /// sub-cells (each sub-cell's points together), with the scalar shape functions' values
  /// there (the same on every cell).
  struct SubdividedRule
  {
    unsigned              k = 1, per_subcell = 0;
    std::vector<Point<3>> points;  ///< on the reference cell
    std::vector<double>   weights; ///< (summing to 1)
    Eigen::MatrixXd       phi;     ///< (scalar shape function, point)
    SubdividedRule(const FiniteElement<3> &scalar_fe, unsigned gauss, unsigned k);
  };
  /// What one thread needs to assemble remainder loads: their quadratures (built once per
  /// thread, their shape values are costly to set up) and a load vector over all dofs. The
  /// cut-off's shell is often no wider than an element where a tooth is thin: a cell or face
  /// there takes its Gauss rule subdivided (rule_subdivisions), the faces next to the force a
  /// finer rule still.
  struct RemainderScratch
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
  /// The exact-surface points and normals (surface_point) of a boundary face's quadrature
  /// points on one of its rules: the same for every load, and costly on a generated spiral
  /// bevel flank (a Newton solve each). Per (active cell, face, rule: the subdivided ones, then
  /// near_face), filled as the loads first need them, from any thread; kept with the body.
  struct SurfacePoints
  {
    std::vector<Point<3>>     at;
    std::vector<Tensor<1, 3>> normal;
  };
  static constexpr unsigned                               face_rules = max_rule_subdivisions + 1;
  mutable std::unique_ptr<std::atomic<SurfacePoints *>[]> surface_points;
  const SurfacePoints &
  face_surface_points(const typename Triangulation<3>::active_cell_iterator &cell, unsigned face,
                      unsigned rule, const FaceNormals &normals,
                      const FEFaceValues<3> &values) const;
  /// A fine face quadrature for the faces a patch's edge cuts (a patch's area and centroid
  /// then do not jump with where its edge falls between the Gauss points).
  std::unique_ptr<FEFaceValues<3>> fine_face_values;

  Impl(unsigned degree, MPI_Comm communicator)
      : comm(communicator)
      , tria(communicator, Triangulation<3>::none, false,
             parallel::shared::Triangulation<3>::partition_zorder)
      , fe(FE_Q<3>(degree), 3)
      , scalar_fe(degree)
  {
  }
  ~Impl()
  {
    if (surface_points)
      for (std::size_t i = 0; i < tria.n_active_cells() * 6 * face_rules; ++i)
        delete surface_points[i].load();
    if (factor)
      MatDestroy(&factor);
    if (ksp)
      KSPDestroy(&ksp);
    if (K)
      MatDestroy(&K);
  }

  bool
  held(int boundary) const
  {
    return options.clamped.count(boundary) ||
           std::any_of(options.rollers.begin(), options.rollers.end(),
                       [&](const auto &r) { return r.first == boundary; });
  }
  /// A lower bound of x's distance to this process's held faces (centre less half the
  /// diameter; HUGE_VAL without any).
  double
  local_distance_to_held(const Point<3> &x) const
  {
    double d = HUGE_VAL;
    for (const FaceData &face : faces)
      if (held(face.boundary))
        d = std::min(d, face.centre.distance(x) - face.diameter / 2);
    return d;
  }
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

ElasticSegment::ElasticSegment(const std::string &file, const ElasticSegmentOptions &o)
{
  if (!(o.degree == 1 || o.degree == 2))
    throw InputError("elastic segment: degree = " + std::to_string(o.degree) +
                     " is not allowed; expected 1 or 2");
  if (!(o.material.youngs_modulus > 0 && o.material.poisson_ratio > -1 &&
        o.material.poisson_ratio < 0.5))
    throw InputError("elastic segment: the material needs E > 0 and Poisson's ratio in (-1, 0.5)");
  if (!std::ifstream(file).good())
    throw InputError("elastic segment: cannot read the mesh file " + file);
  impl        = std::make_unique<Impl>(o.degree, o.communicator);
  Impl &m     = *impl;
  m.options   = o;
  m.mesh_file = file;
  m.lambda    = lame(o.material).lambda;
  m.mu        = lame(o.material).mu;

  Triangulation<3> coarse;
  {
    GridIn<3> in;
    in.attach_triangulation(coarse);
    try
      {
        in.read_msh(file);
      }
    catch (const std::exception &e)
      {
        throw InputError("elastic segment: " + file +
                         " is not a hexahedral gmsh mesh deal.II can read (" + e.what() + ")");
      }
  }
  if (coarse.n_active_cells() == 0 || !coarse.all_reference_cells_are_hyper_cube())
    throw InputError("elastic segment: " + file +
                     " must contain hexahedra only (gmsh: recombine and extrude, or subdivide)");
  {
    // Degenerate or inverted elements: the Jacobian at some corner not positive (relative to
    // the element's mean, so thin elements pass).
    const FE_Q<3>       q1(1);
    const QTrapezoid<3> corners;
    FEValues<3>         values(m.mapping, q1, corners, update_JxW_values);
    for (const auto &cell : coarse.active_cell_iterators())
      {
        values.reinit(cell);
        double mean = 0, worst = HUGE_VAL;
        for (unsigned q = 0; q < corners.size(); ++q)
          mean += std::abs(values.JxW(q)), worst = std::min(worst, values.JxW(q));
        if (!(worst > 1e-9 * mean))
          {
            std::ostringstream msg;
            msg << "elastic segment: " << file << " has a degenerate or inverted hexahedron (cell "
                << cell->index() << " at " << cell->center() * 1e3 << " mm: corner Jacobian "
                << worst / mean * corners.size()
                << " of its mean); allowed: positive Jacobians at every corner";
            throw InputError(msg.str());
          }
      }
  }
  // The faces and edges of boundaries with an exact surface refined onto it (manifold id =
  // boundary id).
  if (!o.surface_boundaries.empty() && !o.boundary_surface)
    throw InputError("elastic segment: boundaries with an exact surface need its function");
  for (int id : o.surface_boundaries)
    coarse.set_all_manifold_ids_on_boundary(types::boundary_id(id), types::manifold_id(id));
  m.tria.copy_triangulation(coarse);
  for (int id : o.surface_boundaries)
    m.tria.set_manifold(types::manifold_id(id), ProjectedSurface(id, o.boundary_surface));
  m.tria.refine_global(o.refinements);
  if (o.local_refinements > 0)
    refine_near_boundaries(coarse, m.tria, o);
  m.cache_ptr = std::make_unique<GridTools::Cache<3>>(m.tria, m.mapping);

  std::set<types::boundary_id> present;
  for (const auto &face : m.tria.active_face_iterators())
    if (face->at_boundary())
      present.insert(face->boundary_id());
  present      = Utilities::MPI::compute_set_union(present, m.comm);
  auto require = [&](int id) {
    if (!present.count(types::boundary_id(id)))
      throw InputError("elastic segment: boundary id " + std::to_string(id) + " is not in " + file);
  };
  if (o.clamped.empty() && o.rollers.empty())
    throw InputError("elastic segment: the body is not held (no clamped or roller boundary)");

  m.dofs.reinit(m.tria);
  m.dofs.distribute_dofs(m.fe);
  m.owned = m.dofs.locally_owned_dofs();
  {
    // the component of every dof a remainder load can reach (balance_remainder_loads)
    m.dof_component.assign(m.dofs.n_dofs(), 0);
    std::vector<types::global_dof_index> indices(m.fe.n_dofs_per_cell());
    for (const auto &cell : m.dofs.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(indices);
          for (unsigned i = 0; i < indices.size(); ++i)
            m.dof_component[indices[i]] =
                static_cast<unsigned char>(m.fe.system_to_component_index(i).first);
        }
  }
  m.check_assembly_fits();
  DoFTools::extract_locally_relevant_dofs(m.dofs, m.relevant);
  m.constraints.reinit(m.relevant);
  DoFTools::make_hanging_node_constraints(m.dofs, m.constraints);
  for (int id : o.clamped)
    {
      require(id);
      VectorTools::interpolate_boundary_values(m.mapping, m.dofs, types::boundary_id(id),
                                               Functions::ZeroFunction<3>(3), m.constraints);
    }
  for (const auto &[id, component] : o.rollers)
    {
      require(id);
      if (component < 0 || component > 2)
        throw InputError("elastic segment: roller component must be 0, 1 or 2");
      ComponentMask mask(3, false);
      mask.set(component, true);
      VectorTools::interpolate_boundary_values(m.mapping, m.dofs, types::boundary_id(id),
                                               Functions::ZeroFunction<3>(3), m.constraints, mask);
    }
  m.constraints.close();

  // Boundary quadrature cache for the loads.
  const unsigned  n = m.fe.n_dofs_per_cell();
  const QGauss<2> face_quadrature(o.degree + 2);
  FEFaceValues<3> face_values(m.mapping, m.fe, face_quadrature,
                              update_values | update_quadrature_points | update_JxW_values);
  for (const auto &cell : m.dofs.active_cell_iterators())
    if (cell->is_locally_owned())
      for (unsigned f = 0; f < GeometryInfo<3>::faces_per_cell; ++f)
        if (cell->face(f)->at_boundary())
          {
            face_values.reinit(cell, f);
            Impl::FaceData d;
            d.boundary = int(cell->face(f)->boundary_id());
            d.centre   = cell->face(f)->center();
            d.diameter = cell->face(f)->diameter();
            d.dof_indices.resize(n);
            cell->get_dof_indices(d.dof_indices);
            d.cell    = cell;
            d.face_no = f;
            for (unsigned v = 0; v < 4; ++v)
              d.vertices[v] = cell->face(f)->vertex(v);
            for (unsigned q = 0; q < face_quadrature.size(); ++q)
              {
                d.q_points.push_back(face_values.quadrature_point(q));
                d.JxW.push_back(face_values.JxW(q));
                for (unsigned i = 0; i < n; ++i)
                  {
                    std::array<double, 3> s{{0, 0, 0}};
                    s[m.fe.system_to_component_index(i).first] = face_values.shape_value(i, q);
                    d.shape.push_back(s);
                  }
              }
            m.faces.push_back(std::move(d));
          }
  for (const auto &cell : m.dofs.active_cell_iterators())
    if (cell->is_locally_owned() || cell->is_ghost())
      for (unsigned f = 0; f < GeometryInfo<3>::faces_per_cell; ++f)
        if (cell->face(f)->at_boundary())
          {
            const auto         face = cell->face(f);
            Tensor<1, 3>       a    = cross_product_3d(face->vertex(3) - face->vertex(0),
                                                       face->vertex(2) - face->vertex(1));
            const Tensor<1, 3> out  = face->center() - cell->center();
            if (a * out < 0)
              a = -a;
            for (unsigned v = 0; v < 4; ++v)
              m.vertex_normals[{face->vertex_index(v), int(face->boundary_id())}] += a;
          }
  m.fine_face_values = std::make_unique<FEFaceValues<3>>(
      m.mapping, m.fe, QIterated<2>(QGauss<1>(o.degree + 1), 8),
      update_values | update_quadrature_points | update_JxW_values);
}

void
ElasticSegment::Impl::assemble_matrix()
{
  // The rows of this process's dofs, condensed by the constraints (a hanging dof's entries go
  // to its parents, held dofs drop out; a constrained dof's row keeps a positive diagonal
  // alone, its right-hand side is zero), in CSR arrays on deal.II's sparsity pattern, handed
  // to PETSc at once. Every cell that reaches an owned row adds to it here (the shared
  // triangulation has them all), so no entry travels between processes; deal.II's matrix
  // with distribute_local_to_global built the same in twice the time.
  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  const std::size_t     rows = owned.n_elements();
  std::vector<PetscInt> start(rows + 1, 0);
  std::vector<PetscInt> columns;
  std::vector<double>   entries;
  {
    std::size_t total = 0;
    for (std::size_t r = 0; r < rows; ++r)
      total += dsp.row_length(owned.nth_index_in_set(r));
    if (total > std::size_t(std::numeric_limits<PetscInt>::max()))
      throw MemoryRefusal("elastic segment: " + mesh_file + " has " +
                          std::to_string(dofs.n_dofs()) + " degrees of freedom and " +
                          std::to_string(total) +
                          " matrix entries on one process, more than PETSc's 32-bit indices "
                          "hold; use coarser elements or more processes under mpirun");
    columns.resize(total);
    entries.assign(total, 0.0);
    for (std::size_t r = 0; r < rows; ++r)
      {
        const types::global_dof_index row    = owned.nth_index_in_set(r);
        const unsigned                length = dsp.row_length(row);
        start[r + 1]                         = start[r] + PetscInt(length);
        for (unsigned k = 0; k < length; ++k)
          columns[std::size_t(start[r]) + k] = PetscInt(dsp.column_number(row, k));
        std::sort(columns.begin() + start[r], columns.begin() + start[r + 1]);
      }
  }
  dsp = DynamicSparsityPattern();
  // the entry of row r and the given column, searched along the row's sorted columns from k on
  const auto position = [&](std::size_t r, types::global_dof_index column, std::size_t k) {
    const std::size_t end = std::size_t(start[r + 1]);
    while (k < end && columns[k] < PetscInt(column))
      ++k;
    if (k == end || columns[k] != PetscInt(column))
      throw std::logic_error("elastic segment: an element entry outside the sparsity pattern");
    return k;
  };

  const QGauss<3>    quadrature(options.degree + 1);
  FEValues<3>        values(mapping, fe, quadrature, update_gradients | update_JxW_values);
  FullMatrix<double> local(fe.n_dofs_per_cell(), fe.n_dofs_per_cell());
  std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
  struct Resolved
  {
    unsigned                local;  ///< the cell's dof
    types::global_dof_index global; ///< an unconstrained dof it stands for
    double                  weight;
    std::size_t             row; ///< the owned row of `global`, or rows if another's
  };
  std::vector<Resolved> resolved;
  for (const auto &cell : dofs.active_cell_iterators())
    {
      if (cell->is_artificial())
        continue;
      cell->get_dof_indices(indices);
      resolved.clear();
      bool       reaches = false;
      const auto add     = [&](unsigned i, types::global_dof_index j, double w) {
        const std::size_t r = owned.is_element(j) ? owned.index_within_set(j) : rows;
        reaches             = reaches || r < rows;
        resolved.push_back({i, j, w, r});
      };
      for (unsigned i = 0; i < indices.size(); ++i)
        if (!constraints.is_constrained(indices[i]))
          add(i, indices[i], 1.0);
        else if (const auto *parents = constraints.get_constraint_entries(indices[i]))
          for (const auto &[j, w] : *parents)
            add(i, j, w);
      if (!reaches)
        continue;
      local_matrix(cell, values, local);
      // by column: a row's entries then found in one pass along its sorted columns
      std::sort(resolved.begin(), resolved.end(),
                [](const Resolved &a, const Resolved &b) { return a.global < b.global; });
      for (const Resolved &a : resolved)
        if (a.row < rows)
          {
            std::size_t k = std::size_t(start[a.row]);
            for (const Resolved &b : resolved)
              {
                k = position(a.row, b.global, k);
                entries[k] += a.weight * b.weight * local(a.local, b.local);
              }
          }
    }
  // a constrained dof's row: the mean diagonal of the others (any positive value would do;
  // this one keeps the matrix's scale)
  const auto diagonal_of = [&](std::size_t r) -> double & {
    return entries[position(r, owned.nth_index_in_set(r), std::size_t(start[r]))];
  };
  double      diagonal = 0;
  std::size_t free     = 0;
  for (std::size_t r = 0; r < rows; ++r)
    if (!constraints.is_constrained(owned.nth_index_in_set(r)))
      diagonal += diagonal_of(r), ++free;
  diagonal = Utilities::MPI::sum(diagonal, comm) /
             double(std::max<std::size_t>(1, Utilities::MPI::sum(free, comm)));
  for (std::size_t r = 0; r < rows; ++r)
    if (constraints.is_constrained(owned.nth_index_in_set(r)))
      diagonal_of(r) = diagonal;

  petsc_check(MatCreate(comm, &K), "MatCreate");
  petsc_check(MatSetSizes(K, PetscInt(rows), PetscInt(rows), PetscInt(dofs.n_dofs()),
                          PetscInt(dofs.n_dofs())),
              "MatSetSizes");
  petsc_check(MatSetType(K, MATAIJ), "MatSetType");
  petsc_check(MatSeqAIJSetPreallocationCSR(K, start.data(), columns.data(), entries.data()),
              "MatSeqAIJSetPreallocationCSR");
  petsc_check(MatMPIAIJSetPreallocationCSR(K, start.data(), columns.data(), entries.data()),
              "MatMPIAIJSetPreallocationCSR");
}

void
ElasticSegment::Impl::set_up_solver()
{
  if (solver_ready)
    return;
  Impl &m = *this;
  Timer all;
  m.assemble_matrix();

  // The factorisation (or whatever the run-time options ask for), kept for every solve.
  Timer timer;
  petsc_check(KSPCreate(m.comm, &m.ksp), "KSPCreate");
  petsc_check(KSPSetOperators(m.ksp, m.K, m.K), "KSPSetOperators");
  petsc_check(KSPSetType(m.ksp, KSPPREONLY), "KSPSetType");
  PC pc;
  petsc_check(KSPGetPC(m.ksp, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  petsc_check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  petsc_check(KSPSetOptionsPrefix(m.ksp, "gearkit_"), "KSPSetOptionsPrefix");
  petsc_check(KSPSetTolerances(m.ksp, 1e-12, 1e-50, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  petsc_check(KSPSetFromOptions(m.ksp), "KSPSetFromOptions");
  PCType chosen;
  petsc_check(PCGetType(pc, &chosen), "PCGetType");
  if (std::string(chosen) == PCGAMG || std::string(chosen) == PCML)
    m.set_rigid_body_near_null_space();
  if (std::string(chosen) == PCHYPRE)
    petsc_check(MatSetBlockSize(m.K, 3), "MatSetBlockSize"); // x, y, z of a node together
  MatSolverType solver_type = nullptr;
  if (std::string(chosen) == PCCHOLESKY)
    petsc_check(PCFactorGetMatSolverType(pc, &solver_type), "PCFactorGetMatSolverType");
  m.solver_name = std::string(KSPPREONLY) + "/" + chosen;
  if (solver_type && std::string(solver_type) == MATSOLVERMUMPS)
    {
      m.factorise(); // MUMPS's analysis once, for the memory check and the factorisation
      // MUMPS keeps its own copy of the entries: the matrix and the solver object that holds it
      // go (a quarter of a member's memory at the recommended settings)
      KSPDestroy(&m.ksp);
      MatDestroy(&m.K);
    }
  else
    {
      petsc_check(KSPSetUp(m.ksp), "KSPSetUp (factorisation: is the body held?)");
      KSPType ksp_type;
      petsc_check(KSPGetType(m.ksp, &ksp_type), "KSPGetType");
      m.solver_name = std::string(ksp_type) + "/" + chosen;
    }
  m.factor_seconds = timer.wall_time();
  m.solver_seconds = all.wall_time();
  m.solver_ready   = true;
}

void
ElasticSegment::Impl::check_assembly_fits() const
{
  const double need = double(owned.n_elements()) * matrix_bytes_per_dof(options.degree);
  const double have =
      options.memory_available > 0 ? options.memory_available : memory_available_now();
  const auto [here, fits] = machine_need(need, have, comm);
  if (!fits)
    {
      std::ostringstream msg;
      msg.precision(3);
      msg << "elastic segment: " << mesh_file << " has " << dofs.n_dofs()
          << " degrees of freedom; assembling its stiffness matrix needs about "
          << Utilities::MPI::max(here, comm) / 1e9 << " GB on a machine with "
          << Utilities::MPI::min(have, comm) / 1e9
          << " GB available. Use coarser elements (fewer refinements, larger flank elements) "
             "or more machines under mpirun";
      throw MemoryRefusal(msg.str());
    }
}

void
ElasticSegment::Impl::factorise()
{
  // MUMPS's analysis (ordering, symbolic factorisation) first: its estimates of the in-core
  // factorisation's memory, the largest process's (INFOG(16)) and all processes' (INFOG(17)),
  // in millions of bytes
  petsc_check(MatGetFactor(K, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &factor), "MatGetFactor");
  petsc_check(MatSetOptionsPrefix(factor, "gearkit_"), "MatSetOptionsPrefix");
  // the compliance solves a few hundred right-hand sides at once (solve_block);
  // -gearkit_mat_mumps_icntl_27 still overrides it
  petsc_check(MatMumpsSetIcntl(factor, 27, PetscInt(solve_block)), "MatMumpsSetIcntl");
  MatFactorInfo info;
  petsc_check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  petsc_check(MatCholeskyFactorSymbolic(factor, K, nullptr, &info),
              "MatCholeskyFactorSymbolic (MUMPS analysis)");
  // MB: the largest process's and all processes' in core (INFOG(16), (17)), and with the
  // factors written to files (INFOG(26), (27)); the factors' entries (INFOG(3), negative: in
  // millions)
  PetscInt most = 0, total = 0, most_ooc = 0, total_ooc = 0, entries = 0;
  petsc_check(MatMumpsGetInfog(factor, 16, &most), "MatMumpsGetInfog");
  petsc_check(MatMumpsGetInfog(factor, 17, &total), "MatMumpsGetInfog");
  petsc_check(MatMumpsGetInfog(factor, 26, &most_ooc), "MatMumpsGetInfog");
  petsc_check(MatMumpsGetInfog(factor, 27, &total_ooc), "MatMumpsGetInfog");
  petsc_check(MatMumpsGetInfog(factor, 3, &entries), "MatMumpsGetInfog");
  // per machine: its processes (at most the largest's each) against what it has
  const double have =
      options.memory_available > 0 ? options.memory_available : memory_available_now();
  const auto [need, fits] = machine_need(double(most) * 1e6, have, comm);
  if (!fits)
    {
      // Out of core: MUMPS keeps only its working space in memory and writes the factors to
      // files (in MUMPS_OOC_TMPDIR, or -gearkit_mat_mumps_ooc_tmpdir, else /tmp), which every
      // solve reads back: slower solves, the same numbers. Taken where that fits, memory and
      // disk (the factors' entries, 8 bytes each, on the disk of every process).
      const auto [need_ooc, fits_ooc]   = machine_need(double(most_ooc) * 1e6, have, comm);
      char      dir[PETSC_MAX_PATH_LEN] = "";
      PetscBool set                     = PETSC_FALSE;
      petsc_check(PetscOptionsGetString(nullptr, "gearkit_", "-mat_mumps_ooc_tmpdir", dir,
                                        sizeof dir, &set),
                  "PetscOptionsGetString");
      const char       *env         = std::getenv("MUMPS_OOC_TMPDIR");
      const std::string files       = set ? dir : env ? env : "/tmp";
      const double      factor_size = 8 * (entries < 0 ? -1e6 * double(entries) : double(entries));
      std::error_code   error;
      const double      disk = double(std::filesystem::space(files, error).available);
      const bool        on_disk =
          Utilities::MPI::min(!error && disk > 1.1 * factor_size ? 1 : 0, comm) == 1;
      if (fits_ooc && on_disk)
        {
          petsc_check(MatMumpsSetIcntl(factor, 22, 1), "MatMumpsSetIcntl (out of core)");
          out_of_core = true;
        }
      else
        {
          const double       short_need = Utilities::MPI::max(need, comm);
          const double       short_have = Utilities::MPI::min(have, comm);
          std::ostringstream msg;
          msg.precision(3);
          msg << "elastic segment: " << mesh_file << " has " << dofs.n_dofs()
              << " degrees of freedom; its direct factorisation (MUMPS) needs about "
              << double(total) / 1e3 << " GB (" << short_need / 1e9 << " GB on a machine with "
              << short_have / 1e9 << " GB available); with its factors out of core "
              << double(total_ooc) / 1e3 << " GB (" << Utilities::MPI::max(need_ooc, comm) / 1e9
              << " GB on a machine) and " << factor_size / 1e9 << " GB of files in " << files
              << " (" << (error ? 0.0 : disk / 1e9)
              << " GB free). Use coarser elements (fewer refinements, larger flank elements), "
                 "more machines under mpirun, or an iterative solver "
                 "(PETSC_OPTIONS=\"-gearkit_ksp_type cg -gearkit_pc_type gamg\")";
          throw MemoryRefusal(msg.str());
        }
    }
  petsc_check(MatCholeskyFactorNumeric(factor, K, &info),
              "MatCholeskyFactorNumeric (factorisation: is the body held?)");
}

void
ElasticSegment::Impl::set_rigid_body_near_null_space()
{
  // Smoothed-aggregation multigrid needs the six rigid-body motions of elasticity (three
  // translations, three rotations about the centroid) to build coarse spaces that converge
  // independently of the mesh; without them GAMG takes hundreds of iterations on a cantilever.
  std::map<types::global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(mapping, dofs, support);
  Point<3> centre;
  for (const auto &[index, x] : support)
    centre += x / double(support.size());
  std::array<Vec, 6> modes;
  for (auto &mode : modes)
    petsc_check(MatCreateVecs(K, &mode, nullptr), "MatCreateVecs");
  std::map<types::global_dof_index, unsigned> component;
  std::vector<types::global_dof_index>        indices(fe.n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        cell->get_dof_indices(indices);
        for (unsigned i = 0; i < indices.size(); ++i)
          component[indices[i]] = fe.system_to_component_index(i).first;
      }
  for (const auto &[index, x] : support)
    if (owned.is_element(index))
      {
        const unsigned     c = component.at(index);
        const Tensor<1, 3> r = x - centre;
        // rotation k: component c of e_k x r
        const double values[6] = {c == 0 ? 1.0 : 0.0,
                                  c == 1 ? 1.0 : 0.0,
                                  c == 2 ? 1.0 : 0.0,
                                  c == 1   ? -r[2]
                                  : c == 2 ? r[1]
                                           : 0.0,
                                  c == 0   ? r[2]
                                  : c == 2 ? -r[0]
                                           : 0.0,
                                  c == 0   ? -r[1]
                                  : c == 1 ? r[0]
                                           : 0.0};
        for (unsigned k = 0; k < 6; ++k)
          petsc_check(VecSetValue(modes[k], PetscInt(index), values[k], INSERT_VALUES),
                      "VecSetValue");
      }
  for (auto &mode : modes)
    {
      petsc_check(VecAssemblyBegin(mode), "VecAssemblyBegin");
      petsc_check(VecAssemblyEnd(mode), "VecAssemblyEnd");
    }
  // MatNullSpaceCreate wants an orthonormal set: modified Gram-Schmidt.
  for (unsigned k = 0; k < 6; ++k)
    {
      for (unsigned j = 0; j < k; ++j)
        {
          PetscScalar dot;
          petsc_check(VecDot(modes[k], modes[j], &dot), "VecDot");
          petsc_check(VecAXPY(modes[k], -dot, modes[j]), "VecAXPY");
        }
      petsc_check(VecNormalize(modes[k], nullptr), "VecNormalize");
    }
  MatNullSpace space;
  petsc_check(MatNullSpaceCreate(comm, PETSC_FALSE, 6, modes.data(), &space), "MatNullSpaceCreate");
  petsc_check(MatSetNearNullSpace(K, space), "MatSetNearNullSpace");
  petsc_check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
  for (auto &mode : modes)
    petsc_check(VecDestroy(&mode), "VecDestroy");
}

void
ElasticSegment::Impl::local_matrix(const typename DoFHandler<3>::active_cell_iterator &cell,
                                   FEValues<3> &values, FullMatrix<double> &local) const
{
  // With the scalar shape functions' gradients weighted by sqrt(JxW), B(q, 3 a + c) =
  // sqrt(w_q) d phi_a / dx_c, and M = B^T B, shape function i (phi_a moving component c) and j
  // (phi_b moving d) couple by 2 mu eps_i : eps_j + lambda tr eps_i tr eps_j =
  // lambda M(3a + c, 3b + d) + mu M(3a + d, 3b + c) + delta(c, d) mu sum_e M(3a + e, 3b + e).
  values.reinit(cell);
  const unsigned  n = fe.n_dofs_per_cell(), nq = values.n_quadrature_points;
  Eigen::MatrixXd B(nq, n);
  for (unsigned i = 0; i < n; ++i)
    if (const auto [c, a] = fe.system_to_component_index(i); c == 0)
      for (unsigned q = 0; q < nq; ++q)
        {
          const Tensor<1, 3> g = values.shape_grad(i, q) * std::sqrt(values.JxW(q));
          for (unsigned d = 0; d < 3; ++d)
            B(q, 3 * a + d) = g[d];
        }
  Eigen::MatrixXd M(n, n);
  M.noalias() = B.transpose() * B;
  for (unsigned i = 0; i < n; ++i)
    {
      const auto [c, a] = fe.system_to_component_index(i);
      for (unsigned j = 0; j <= i; ++j)
        {
          const auto [d, b] = fe.system_to_component_index(j);
          double k          = lambda * M(3 * a + c, 3 * b + d) + mu * M(3 * a + d, 3 * b + c);
          if (c == d)
            k += mu * (M(3 * a, 3 * b) + M(3 * a + 1, 3 * b + 1) + M(3 * a + 2, 3 * b + 2));
          local(i, j) = local(j, i) = k;
        }
    }
}

ElasticSegment::~ElasticSegment() = default;

std::size_t
ElasticSegment::cells() const
{
  return impl->tria.n_global_active_cells();
}

std::size_t
ElasticSegment::dofs() const
{
  return impl->dofs.n_dofs();
}

double
ElasticSegment::factorisation_seconds() const
{
  impl->set_up_solver();
  return impl->factor_seconds;
}

double
ElasticSegment::solver_seconds() const
{
  impl->set_up_solver();
  return impl->solver_seconds;
}

bool
ElasticSegment::factors_out_of_core() const
{
  impl->set_up_solver();
  return impl->out_of_core;
}

std::vector<double>
ElasticSegment::distance_to_held(const std::vector<Vec3> &points) const
{
  std::vector<double> d(points.size());
  for (std::size_t j = 0; j < points.size(); ++j)
    d[j] = impl->local_distance_to_held(point(points[j]));
  Utilities::MPI::min(d, impl->comm, d);
  return d;
}

std::vector<bool>
ElasticSegment::contains(const std::vector<Vec3> &points) const
{
  // Candidates from the R-tree of the locally owned cells' bounding boxes, then the inverse
  // mapping (cheaper than a cell search, which hunts widely before it gives up on a point
  // outside the mesh).
  namespace bgi              = boost::geometry::index;
  const auto           &tree = impl->cache_ptr->get_locally_owned_cell_bounding_boxes_rtree();
  std::vector<unsigned> inside(points.size(), 0);
  for (std::size_t j = 0; j < points.size(); ++j)
    {
      const Point<3> x = point(points[j]);
      for (auto it = tree.qbegin(bgi::intersects(x)); it != tree.qend() && !inside[j]; ++it)
        try
          {
            const Point<3> unit = impl->mapping.transform_real_to_unit_cell(it->second, x);
            inside[j]           = GeometryInfo<3>::is_inside_unit_cell(unit, 1e-10);
          }
        catch (const std::exception &)
          {
            // the inverse mapping did not converge: not in this cell
          }
    }
  Utilities::MPI::max(inside, impl->comm, inside);
  return std::vector<bool>(inside.begin(), inside.end());
}

std::string
ElasticSegment::solver() const
{
  impl->set_up_solver();
  return impl->solver_name;
}

PETScWrappers::MPI::Vector
ElasticSegment::Impl::assemble_loads(const std::vector<PatchLoad> &loads) const
{
  PETScWrappers::MPI::Vector f(owned, comm);
  const unsigned             n = fe.n_dofs_per_cell();
  Vector<double>             local(n);
  for (const PatchLoad &load : loads)
    {
      const bool box = load.half_size.maxCoeff() > 0;
      if (!(box ? load.half_size.minCoeff() > 0 : load.radius > 0) || load.boundaries.empty() ||
          !load.force.allFinite())
        throw InputError("elastic segment: a patch load needs a radius (or box half sizes) > 0, "
                         "boundary ids and a finite force");
      const Point<3> x0       = point(load.point);
      const double   reach    = box ? load.half_size.norm() : load.radius;
      auto           in_patch = [&](const FaceData &d) {
        return load.boundaries.count(d.boundary) && d.centre.distance(x0) <= reach + d.diameter;
      };
      auto inside = [&](const Point<3> &q) {
        if (!box)
          return q.distance(x0) <= load.radius;
        const Vec3 local = load.axes * Vec3(q[0] - x0[0], q[1] - x0[1], q[2] - x0[2]);
        return (local.cwiseAbs().array() <= load.half_size.array()).all();
      };
      // Integrates the traction t over the part of face d inside the patch into `local`
      // (when given); returns that part's area.
      auto integrate = [&](const FaceData &d, const Vec3 &t, Vector<double> *local) {
        bool whole = true;
        for (const Point<3> &v : d.vertices)
          whole = whole && inside(v);
        double a = 0;
        if (whole)
          for (std::size_t q = 0; q < d.q_points.size(); ++q)
            {
              a += d.JxW[q];
              if (local)
                for (unsigned i = 0; i < n; ++i)
                  {
                    const auto &s = d.shape[q * n + i];
                    (*local)(i) += (s[0] * t.x() + s[1] * t.y() + s[2] * t.z()) * d.JxW[q];
                  }
            }
        else
          {
            FEFaceValues<3> &v = *fine_face_values;
            v.reinit(d.cell, d.face_no);
            for (unsigned q = 0; q < v.n_quadrature_points; ++q)
              if (inside(v.quadrature_point(q)))
                {
                  a += v.JxW(q);
                  if (local)
                    for (unsigned i = 0; i < n; ++i)
                      (*local)(i) +=
                          v.shape_value(i, q) * t[fe.system_to_component_index(i).first] * v.JxW(q);
                }
          }
        return a;
      };
      double area = 0;
      for (const FaceData &d : faces)
        if (in_patch(d))
          area += integrate(d, Vec3::Zero(), nullptr);
      area = Utilities::MPI::sum(area, comm);
      if (!(area > 0))
        {
          std::ostringstream msg;
          msg << "elastic segment: the patch load at (" << load.point.transpose() * 1e3
              << ") mm of size " << reach * 1e3
              << " mm covers no quadrature point of its boundary; make it larger than the "
                 "elements there";
          throw InputError(msg.str());
        }
      const Vec3 traction = load.force / area;
      for (const FaceData &d : faces)
        if (in_patch(d))
          {
            local = 0;
            integrate(d, traction, &local);
            constraints.distribute_local_to_global(local, d.dof_indices, f);
          }
    }
  f.compress(VectorOperation::add);
  return f;
}

PETScWrappers::MPI::Vector
ElasticSegment::Impl::solve(const PETScWrappers::MPI::Vector &rhs) const
{
  PETScWrappers::MPI::Vector x(owned, comm);
  if (factor)
    petsc_check(MatSolve(factor, rhs, x), "MatSolve");
  else
    {
      petsc_check(KSPSolve(ksp, rhs, x), "KSPSolve");
      KSPConvergedReason reason;
      KSPGetConvergedReason(ksp, &reason);
      if (reason < 0)
        throw InputError("elastic segment: the linear solver did not converge (PETSc reason " +
                         std::to_string(int(reason)) + ")");
    }
  constraints.distribute(x);
  PETScWrappers::MPI::Vector ghosted(owned, relevant, comm);
  ghosted = x;
  return ghosted;
}

std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>>
ElasticSegment::Impl::probe_functionals(const std::vector<Probe> &probes) const
{
  const unsigned             rank  = Utilities::MPI::this_mpi_process(comm);
  const GridTools::Cache<3> &cache = *cache_ptr;
  std::vector<unsigned>      claim(probes.size(), std::numeric_limits<unsigned>::max());
  std::vector<std::pair<typename DoFHandler<3>::active_cell_iterator, Point<3>>> found(
      probes.size());
  for (std::size_t j = 0; j < probes.size(); ++j)
    {
      try
        {
          const auto r = GridTools::find_active_cell_around_point(cache, point(probes[j].point));
          if (r.first.state() == IteratorState::valid && r.first->is_locally_owned())
            {
              found[j] = {typename DoFHandler<3>::active_cell_iterator(*r.first, &dofs), r.second};
              claim[j] = rank;
            }
        }
      catch (const std::exception &)
        {
          // not in this rank's part of the mesh
        }
    }
  Utilities::MPI::min(claim, comm, claim);
  std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>> out(
      probes.size());
  const unsigned n = fe.n_dofs_per_cell();
  for (std::size_t j = 0; j < probes.size(); ++j)
    {
      if (claim[j] == std::numeric_limits<unsigned>::max())
        {
          std::ostringstream msg;
          msg << "elastic segment: the probe point (" << probes[j].point.transpose() * 1e3
              << ") mm lies outside the mesh";
          throw InputError(msg.str());
        }
      if (claim[j] != rank)
        continue;
      const auto &[cell, ref] = found[j];
      out[j].first.resize(n);
      cell->get_dof_indices(out[j].first);
      for (unsigned i = 0; i < n; ++i)
        {
          const unsigned c = fe.system_to_component_index(i).first;
          out[j].second.push_back(fe.shape_value(i, ref) * probes[j].direction[c]);
        }
    }
  return out;
}

Eigen::VectorXd
ElasticSegment::Impl::evaluate(
    const std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>> &f,
    const PETScWrappers::MPI::Vector &u) const
{
  std::vector<double> values(f.size(), 0.0);
  for (std::size_t j = 0; j < f.size(); ++j)
    for (std::size_t i = 0; i < f[j].first.size(); ++i)
      values[j] += f[j].second[i] * u(f[j].first[i]);
  Utilities::MPI::sum(values, comm, values);
  return Eigen::Map<Eigen::VectorXd>(values.data(), Eigen::Index(values.size()));
}

std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>>
ElasticSegment::Impl::load_functionals(const std::vector<PatchLoad> &loads) const
{
  std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>> out(
      loads.size());
  for (std::size_t j = 0; j < loads.size(); ++j)
    {
      const PETScWrappers::MPI::Vector f = assemble_loads({loads[j]});
      for (const types::global_dof_index i : owned)
        if (const double v = f(i); v != 0)
          out[j].first.push_back(i), out[j].second.push_back(v);
    }
  return out;
}

namespace
{
/// Patch loads one after the other (their assembly is collective).
/// A patch load's vector as its nonzero entries (those of this process's dofs).
std::function<void(std::size_t, std::vector<PetscInt> &, std::vector<double> &)>
patch_entries(const std::function<PETScWrappers::MPI::Vector(std::size_t)> &load_vector)
{
  return [load_vector](std::size_t i, std::vector<PetscInt> &dofs, std::vector<double> &values) {
    const PETScWrappers::MPI::Vector f = load_vector(i);
    PetscInt                         first, last;
    petsc_check(VecGetOwnershipRange(f, &first, &last), "VecGetOwnershipRange");
    const PetscScalar *v;
    petsc_check(VecGetArrayRead(f, &v), "VecGetArrayRead");
    for (PetscInt k = 0; k < last - first; ++k)
      if (v[k] != 0)
        dofs.push_back(first + k), values.push_back(v[k]);
    petsc_check(VecRestoreArrayRead(f, &v), "VecRestoreArrayRead");
  };
}
} // namespace

Eigen::MatrixXd
ElasticSegment::response(const std::vector<PatchLoad> &loads,
                         const std::vector<Probe>     &probes) const
{
  impl->set_up_solver();
  return impl->responses(
      loads.size(), patch_entries([&](std::size_t i) { return impl->assemble_loads({loads[i]}); }),
      impl->probe_functionals(probes));
}

Eigen::MatrixXd
ElasticSegment::patch_response(const std::vector<PatchLoad> &loads,
                               const std::vector<PatchLoad> &measures) const
{
  impl->set_up_solver();
  return impl->responses(
      loads.size(), patch_entries([&](std::size_t i) { return impl->assemble_loads({loads[i]}); }),
      impl->load_functionals(measures));
}

Eigen::MatrixXd
ElasticSegment::remainder_response(const std::vector<NearFieldLoad> &loads,
                                   const std::vector<Probe>         &probes) const
{
  const Impl &m = *impl;
  m.check_near_field_loads(loads);
  m.cache_ptr->get_locally_owned_cell_bounding_boxes_rtree(); // built here, read by threads
  if (!m.surface_points)
    m.surface_points.reset(
        new std::atomic<Impl::SurfacePoints *>[m.tria.n_active_cells() * 6 * Impl::face_rules]());
  // The load vectors on threads (each its own quadratures and a vector over all dofs), their
  // entries kept (nonzero only about each load), beside the stiffness matrix's assembly and
  // factorisation if those are still to come: a helper thread starts on the loads while the
  // calling thread sets the solver up (no load needs it; PETSc and MPI stay on this thread),
  // then joins the loads. Entries of other processes' dofs travel with the right-hand sides.
  std::vector<std::vector<PetscInt>> rows(loads.size());
  std::vector<std::vector<double>>   values(loads.size()), spreads(loads.size());
  parallel_for_beside([&] { impl->set_up_solver(); }, loads.size(), m.options.threads,
                      [&] { return Impl::RemainderScratch(m); },
                      [&](Impl::RemainderScratch &scratch, std::size_t c) {
                        scratch.f = 0;
                        scratch.g = 0;
                        m.assemble_remainder_load(loads[c], scratch);
                        for (types::global_dof_index i = 0; i < scratch.f.size(); ++i)
                          if (scratch.f(i) != 0 || scratch.g(i) != 0)
                            rows[c].push_back(PetscInt(i)), values[c].push_back(scratch.f(i)),
                                spreads[c].push_back(scratch.g(i));
                      });
  m.balance_remainder_loads(loads, rows, values, spreads);
  spreads            = {};
  const auto entries = [&](std::size_t i, std::vector<PetscInt> &dofs, std::vector<double> &v) {
    dofs.swap(rows[i]);
    v.swap(values[i]);
  };
  return m.responses(loads.size(), entries, m.probe_functionals(probes));
}

ElasticSegment::Impl::FaceNormals
ElasticSegment::Impl::face_normals(const typename DoFHandler<3>::active_cell_iterator &cell,
                                   unsigned                                            f) const
{
  const auto  face = cell->face(f);
  FaceNormals out;
  out.boundary = int(face->boundary_id());
  for (unsigned k = 0; k < 4; ++k)
    {
      out.vertex[k] = face->vertex(k);
      out.sum[k]    = vertex_normals.at({face->vertex_index(k), int(face->boundary_id())});
      out.length[k] = out.sum[k].norm();
    }
  return out;
}

Tensor<1, 3>
ElasticSegment::Impl::smooth_normal(const FaceNormals &face, const Point<3> &x)
{
  // the vertex normals interpolated with the bilinear face's weights at x
  const auto [xi, eta] = bilinear_coordinates(face.vertex, x);
  const double w[4]    = {(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta, xi * eta};
  Tensor<1, 3> n;
  for (unsigned k = 0; k < 4; ++k)
    n += w[k] * face.sum[k] / face.length[k];
  return n / n.norm();
}

std::pair<Point<3>, Tensor<1, 3>>
ElasticSegment::Impl::surface_point(const FaceNormals &face, const Point<3> &x) const
{
  if (!options.surface_boundaries.count(face.boundary))
    return {x, smooth_normal(face, x)};
  const SurfacePoint s = options.boundary_surface(face.boundary, Vec3(x[0], x[1], x[2]));
  if (!(s.position.allFinite() && s.normal.allFinite() && std::abs(s.normal.norm() - 1) < 1e-6))
    {
      std::ostringstream msg;
      msg << "elastic segment: the exact surface of boundary " << face.boundary
          << " has no point with a unit normal for (" << 1e3 * x << ") mm";
      throw InputError(msg.str());
    }
  return {point(s.position), Tensor<1, 3>({s.normal.x(), s.normal.y(), s.normal.z()})};
}

ElasticSegment::Impl::SplitRule
ElasticSegment::Impl::split_face_rule(const typename Triangulation<3>::active_cell_iterator &cell,
                                      unsigned face, const Point<3> &x, double within) const
{
  SplitRule rule;
  // the face's point nearest to x: (xi, eta) on the bilinear face of the corners, clamped
  std::array<Point<3>, 4> corner;
  auto                    nearest = [&] {
    auto [xi, eta] = bilinear_coordinates(corner, x);
    xi = std::clamp(xi, 0.0, 1.0), eta = std::clamp(eta, 0.0, 1.0);
    const Point<3> at = corner[0] * (1 - xi) * (1 - eta) + corner[1] * xi * (1 - eta) +
                        corner[2] * (1 - xi) * eta + corner[3] * xi * eta;
    return std::make_pair(Point<2>(xi, eta), at.distance(x));
  };
  // first on the face's own vertices (lexicographic in the face): most faces are farther
  for (unsigned k = 0; k < 4; ++k)
    corner[k] = cell->face(face)->vertex(k);
  if (!(nearest().second < within))
    return rule;
  // then in the coordinates of the rules projected to the face
  static const Quadrature<2> corner_rule(
      std::vector<Point<2>>{Point<2>(0, 0), Point<2>(1, 0), Point<2>(0, 1), Point<2>(1, 1)},
      std::vector<double>(4, 0.25));
  const Quadrature<3> corners_in_cell =
      QProjector<3>::project_to_face(ReferenceCells::Hexahedron, corner_rule, face);
  for (unsigned k = 0; k < 4; ++k)
    corner[k] = mapping.transform_unit_to_real_cell(cell, corners_in_cell.point(k));
  const QSplit<2>     split(QDuffy(options.degree + 4, 1.0), nearest().first);
  const Quadrature<3> in_cell =
      QProjector<3>::project_to_face(ReferenceCells::Hexahedron, split, face);
  rule.values = std::make_unique<FEValues<3>>(
      mapping, scalar_fe, in_cell, update_values | update_quadrature_points | update_jacobians);
  rule.values->reinit(cell);
  // the surface weight: the reference face's two axes mapped, their cross product's length
  const unsigned a = (face / 2 + 1) % 3, b = (face / 2 + 2) % 3;
  for (unsigned q = 0; q < in_cell.size(); ++q)
    {
      const DerivativeForm<1, 3, 3> &J = rule.values->jacobian(q);
      Tensor<1, 3>                   ta, tb;
      for (unsigned d = 0; d < 3; ++d)
        ta[d] = J[d][a], tb[d] = J[d][b];
      rule.JxW.push_back(split.weight(q) * cross_product_3d(ta, tb).norm());
    }
  return rule;
}

ElasticSegment::Impl::RemainderScratch::RemainderScratch(const Impl &m)
    : near_face(m.mapping, m.scalar_fe, QIterated<2>(QGauss<1>(m.options.degree + 1), 8),
                update_values | update_quadrature_points | update_JxW_values)
    , body(m.scalar_fe.n_dofs_per_cell(), 3)
    , spread(m.scalar_fe.n_dofs_per_cell())
    , f(m.dofs.n_dofs())
    , g(m.dofs.n_dofs())
{
  for (unsigned i = 0; i < m.fe.n_dofs_per_cell(); ++i)
    component.push_back(m.fe.system_to_component_index(i).first),
        scalar.push_back(m.fe.system_to_component_index(i).second);
  const auto flags = update_values | update_quadrature_points | update_JxW_values;
  for (unsigned k = 1; k <= max_rule_subdivisions; ++k)
    {
      volume.emplace_back(m.scalar_fe, m.options.degree + 2, k);
      face.push_back(std::make_unique<FEFaceValues<3>>(
          m.mapping, m.scalar_fe, QIterated<2>(QGauss<1>(m.options.degree + 2), k), flags));
    }
}

ElasticSegment::Impl::SubdividedRule::SubdividedRule(const FiniteElement<3> &scalar_fe,
                                                     unsigned gauss, unsigned subdivisions)
    : k(subdivisions)
{
  const QGauss<3> base(gauss);
  per_subcell = base.size();
  for (unsigned sz = 0; sz < k; ++sz)
    for (unsigned sy = 0; sy < k; ++sy)
      for (unsigned sx = 0; sx < k; ++sx)
        for (unsigned q = 0; q < base.size(); ++q)
          {
            const Point<3> &p = base.point(q);
            points.emplace_back((sx + p[0]) / k, (sy + p[1]) / k, (sz + p[2]) / k);
            weights.push_back(base.weight(q) / (k * k * k));
          }
  phi.resize(scalar_fe.n_dofs_per_cell(), Eigen::Index(points.size()));
  for (unsigned a = 0; a < scalar_fe.n_dofs_per_cell(); ++a)
    for (std::size_t q = 0; q < points.size(); ++q)
      phi(a, Eigen::Index(q)) = scalar_fe.shape_value(a, points[q]);
}

void
ElasticSegment::Impl::check_near_field_loads(const std::vector<NearFieldLoad> &loads) const
{
  for (const NearFieldLoad &load : loads)
    if (!(load.inner > 0 && load.outer > load.inner) || !load.point.allFinite() ||
        !(std::abs(load.direction.norm() - 1) < 1e-9))
      throw InputError("elastic segment: a near-field load needs 0 < inner < outer radius, a "
                       "finite point and a unit direction");
  // on every process together (a throw on one alone would leave the others waiting)
  std::vector<double> held_at(loads.size());
  for (std::size_t i = 0; i < loads.size(); ++i)
    held_at[i] = local_distance_to_held(point(loads[i].point));
  Utilities::MPI::min(held_at, comm, held_at);
  for (std::size_t i = 0; i < loads.size(); ++i)
    if (held_at[i] < loads[i].outer)
      {
        std::ostringstream msg;
        msg << "elastic segment: the near field of the load at ("
            << loads[i].point.transpose() * 1e3 << ") mm reaches a held boundary "
            << held_at[i] * 1e3 << " mm away (cut-off radius " << loads[i].outer * 1e3
            << " mm); expected a smaller radius";
        throw InputError(msg.str());
      }
}

const ElasticSegment::Impl::SurfacePoints &
ElasticSegment::Impl::face_surface_points(
    const typename Triangulation<3>::active_cell_iterator &cell, unsigned face, unsigned rule,
    const FaceNormals &normals, const FEFaceValues<3> &values) const
{
  std::atomic<SurfacePoints *> &slot =
      surface_points[(cell->active_cell_index() * 6 + face) * face_rules + rule];
  if (const SurfacePoints *known = slot.load(std::memory_order_acquire))
    return *known;
  auto made = std::make_unique<SurfacePoints>();
  for (unsigned q = 0; q < values.n_quadrature_points; ++q)
    {
      const auto [at, normal] = surface_point(normals, values.quadrature_point(q));
      made->at.push_back(at), made->normal.push_back(normal);
    }
  SurfacePoints *expected = nullptr; // another thread may have made it meanwhile: the same
  if (slot.compare_exchange_strong(expected, made.get(), std::memory_order_acq_rel))
    return *made.release();
  return *expected;
}

void
ElasticSegment::Impl::assemble_remainder_load(const NearFieldLoad &load,
                                              RemainderScratch    &scratch) const
{
  const Point<3>  x0       = point(load.point);
  const Material &material = options.material;
  const Vec3      axis     = load.direction.normalized();
  auto            cutoff   = [&](const Point<3> &x) {
    return near_field_cutoff(Vec3(x[0], x[1], x[2]), load.point, axis, load.inner, load.outer);
  };
  auto near = [&](const Point<3> &x, const Cutoff &chi, const Tensor<1, 3> &normal) {
    const Vec3 y(x[0], x[1], x[2]);
    return cut_off_near_field(point_force_field(y, load.point, load.direction, 1.0, material), chi,
                              Vec3(normal[0], normal[1], normal[2]), material);
  };
  const unsigned                       n = fe.n_dofs_per_cell();
  Vector<double>                       local(n);
  std::vector<types::global_dof_index> indices(n);
  // the body force lives where the cut-off varies: in the shell between the radii and where
  // the body rises 30 to 60 degrees above the load's tangent plane (near_field_cutoff); the
  // traction on every boundary face within the outer radius, on faces near the force with a
  // finely subdivided rule (the residual traction of a curved surface grows like 1/r toward the
  // force). The length the rules must resolve: the shell's thickness, or the elevation step's
  // width at the distance of an object (centre, radius) that may meet it.
  const double shell = load.outer - load.inner;
  // the lowest and highest elevation above the force's tangent plane of the ball about centre
  // of the given radius (which must not contain the force), seen from it
  const auto elevations = [&](const Point<3> &centre, double radius) {
    const double reach = centre.distance(x0);
    const double elevation =
        std::asin(std::clamp(-((centre - x0) * point(axis)) / reach, -1.0, 1.0));
    const double spread = std::asin(std::min(1.0, radius / reach));
    return std::make_pair(elevation - spread, elevation + spread);
  };
  auto scale = [&](const Point<3> &centre, double radius) {
    const double reach = centre.distance(x0);
    if (reach <= radius)
      return 0.0; // contains the force: the finest rule
    const auto [lowest, highest] = elevations(centre, radius);
    const bool steps             = highest > pi / 6 && lowest < pi / 3;
    return steps ? std::min(shell, 0.5 * (reach - radius)) : shell;
  };
  // chi (near_field_cutoff: radial step from inner to outer times the elevation step from 30
  // to 60 degrees) constant, 0 or 1, on the ball about centre of the given radius (with a
  // margin of rounding)
  const auto cutoff_constant_on = [&](const Point<3> &centre, double radius) {
    const double reach = centre.distance(x0), margin = 1e-9 * load.outer;
    if (reach - radius >= load.outer + margin)
      return true; // chi = 0
    if (reach <= radius + margin)
      return false; // contains the force
    const auto [lowest, highest] = elevations(centre, radius + margin);
    if (lowest > pi / 3 + 1e-9)
      return true;                                                           // chi = 0
    return reach + radius <= load.inner - margin && highest < pi / 6 - 1e-9; // chi = 1
  };
  // the cells whose bounding boxes meet the cube about the outer sphere
  Point<3> low = x0, high = x0;
  for (unsigned d = 0; d < 3; ++d)
    low[d] -= load.outer, high[d] += load.outer;
  std::vector<std::pair<BoundingBox<3>, typename Triangulation<3>::active_cell_iterator>>
      near_cells;
  cache_ptr->get_locally_owned_cell_bounding_boxes_rtree().query(
      boost::geometry::index::intersects(BoundingBox<3>(std::make_pair(low, high))),
      std::back_inserter(near_cells));
  for (const auto &[box, tria_cell] : near_cells)
    {
      const typename DoFHandler<3>::active_cell_iterator cell(*tria_cell, &dofs);
      const double reach = cell->center().distance(x0), radius = cell->diameter() / 2;
      if (reach - radius > load.outer)
        continue;
      local                 = 0;
      const double resolved = scale(cell->center(), radius);
      if (reach + radius > load.inner || resolved < shell)
        {
          const SubdividedRule &rule =
              scratch.volume[rule_subdivisions(2 * radius / std::sqrt(3.0), resolved) - 1];
          // the cell's trilinear map (MappingQ1's), x = c0 + c1 xi + c2 eta + c3 zeta + c4 xi eta
          // + c5 xi zeta + c6 eta zeta + c7 xi eta zeta from its vertices (lexicographic)
          std::array<Tensor<1, 3>, 8> c;
          {
            std::array<Tensor<1, 3>, 8> X;
            for (unsigned v = 0; v < 8; ++v)
              X[v] = tria_cell->vertex(v);
            c = {{X[0], X[1] - X[0], X[2] - X[0], X[4] - X[0], X[3] - X[1] - X[2] + X[0],
                  X[5] - X[1] - X[4] + X[0], X[6] - X[2] - X[4] + X[0],
                  X[7] - X[3] - X[5] - X[6] + X[1] + X[2] + X[4] - X[0]}};
          }
          const auto map = [&c](const Point<3> &xi) {
            return Point<3>(c[0] + xi[0] * c[1] + xi[1] * c[2] + xi[2] * c[3] +
                            xi[0] * xi[1] * c[4] + xi[0] * xi[2] * c[5] + xi[1] * xi[2] * c[6] +
                            xi[0] * xi[1] * xi[2] * c[7]);
          };
          const auto jacobian_determinant = [&c](const Point<3> &xi) {
            const Tensor<1, 3> d0 = c[1] + xi[1] * c[4] + xi[2] * c[5] + xi[1] * xi[2] * c[7],
                               d1 = c[2] + xi[0] * c[4] + xi[2] * c[6] + xi[0] * xi[2] * c[7],
                               d2 = c[3] + xi[0] * c[5] + xi[1] * c[6] + xi[0] * xi[1] * c[7];
            return d0 * cross_product_3d(d1, d2);
          };
          const unsigned m_q = rule.per_subcell, k = rule.k;
          scratch.body.setZero();
          scratch.spread.setZero();
          for (unsigned sub = 0; sub < k * k * k; ++sub)
            {
              // a sub-cell lies within the ball about its mapped corners' mean through the
              // farthest of them (a trilinear map keeps it in their convex hull): skipped where
              // chi is constant on that ball
              const unsigned          sx = sub % k, sy = (sub / k) % k, sz = sub / (k * k);
              std::array<Point<3>, 8> corner;
              Point<3>                centre;
              for (unsigned v = 0; v < 8; ++v)
                {
                  corner[v] =
                      map(Point<3>(double(sx + (v & 1)) / k, double(sy + ((v >> 1) & 1)) / k,
                                   double(sz + ((v >> 2) & 1)) / k));
                  centre += corner[v] / 8;
                }
              double rho = 0;
              for (const Point<3> &c : corner)
                rho = std::max(rho, c.distance(centre));
              if (cutoff_constant_on(centre, rho))
                continue;
              scratch.forces.setZero(m_q, 3);
              scratch.spread_at.setZero(m_q);
              for (unsigned q = 0; q < m_q; ++q)
                {
                  const Point<3> &xi  = rule.points[sub * m_q + q];
                  const Point<3>  x   = map(xi);
                  const Cutoff    chi = cutoff(x);
                  if (!chi.varies())
                    continue; // chi constant: no body force
                  const double dx       = jacobian_determinant(xi) * rule.weights[sub * m_q + q];
                  scratch.forces.row(q) = near(x, chi, Tensor<1, 3>()).body * dx;
                  scratch.spread_at(q)  = chi.gradient.norm() * dx;
                }
              scratch.body.noalias() += rule.phi.middleCols(sub * m_q, m_q) * scratch.forces;
              scratch.spread.noalias() += rule.phi.middleCols(sub * m_q, m_q) * scratch.spread_at;
            }
          for (unsigned i = 0; i < n; ++i)
            local(i) += scratch.body(scratch.scalar[i], scratch.component[i]);
          if (scratch.spread.sum() > 0)
            {
              Vector<double> spread(n);
              for (unsigned i = 0; i < n; ++i)
                spread(i) = scratch.spread(scratch.scalar[i]);
              cell->get_dof_indices(indices);
              constraints.distribute_local_to_global(spread, indices, scratch.g);
            }
        }
      for (unsigned face = 0; face < GeometryInfo<3>::faces_per_cell; ++face)
        if (cell->face(face)->at_boundary() &&
            cell->face(face)->center().distance(x0) - cell->face(face)->diameter() / 2 < load.outer)
          {
            const double      diameter = cell->face(face)->diameter();
            const bool        close    = cell->face(face)->center().distance(x0) < 2 * diameter;
            const FaceNormals normals  = face_normals(cell, face);
            // next to the force, a rule split at the face's point nearest to it (Duffy:
            // exact for the residual traction's 1/r there, wherever the force falls)
            const SplitRule split =
                close ? split_face_rule(tria_cell, face, x0, 0.25 * diameter) : SplitRule();
            const unsigned rule =
                close ? face_rules - 1
                      : rule_subdivisions(diameter / std::sqrt(2.0),
                                          scale(cell->face(face)->center(), diameter / 2)) -
                            1;
            FEFaceValues<3>     &v      = close ? scratch.near_face : *scratch.face[rule];
            const SurfacePoints *cached = nullptr;
            if (!split.values)
              {
                v.reinit(tria_cell, face);
                cached = &face_surface_points(tria_cell, face, rule, normals, v);
              }
            const unsigned n_q =
                split.values ? split.values->n_quadrature_points : v.n_quadrature_points;
            for (unsigned q = 0; q < n_q; ++q)
              {
                // on a boundary with an exact surface, the point of the surface the facet's
                // point stands for: the force lies on it, so the traction left to the elements
                // is the surface's curvature's, ~ 1 / r, not the facets' tilt's, ~ 1 / r^2
                const auto [at, normal] =
                    cached ? std::make_pair(cached->at[q], cached->normal[q])
                           : surface_point(normals, split.values->quadrature_point(q));
                if (at.distance(x0) < 1e-12 * cell->diameter())
                  continue; // the force itself (its part is carried by chi u)
                const Cutoff chi = cutoff(at);
                if (chi.value == 0)
                  continue;
                const Vec3 t =
                    near(at, chi, normal).traction * (split.values ? split.JxW[q] : v.JxW(q));
                for (unsigned i = 0; i < n; ++i)
                  local(i) -= (split.values ? split.values->shape_value(scratch.scalar[i], q)
                                            : v.shape_value(scratch.scalar[i], q)) *
                              t[scratch.component[i]];
              }
          }
      cell->get_dof_indices(indices);
      constraints.distribute_local_to_global(local, indices, scratch.f);
    }
}

std::vector<Vec3>
ElasticSegment::Impl::balance_remainder_loads(const std::vector<NearFieldLoad>         &loads,
                                              const std::vector<std::vector<PetscInt>> &rows,
                                              std::vector<std::vector<double>>         &values,
                                              const std::vector<std::vector<double>> &spreads) const
{
  // The continuous remainder's load (the body force of chi u in the cut-off's shell, less its
  // traction on the boundary) balances the unit force exactly: the finite elements must carry
  // all of it to the held faces. The body force is integrated over the elements' faceted body,
  // the traction on the exact flank it stands for; between the two lie the slivers between
  // facets and the curved flank (and fillet), where the shell's body force is large, so the
  // assembled load is out of balance by 0.2 to 5 % of the force (most near the base circle and
  // the tip, where the involute is most curved; bench/README.md, issue 36), by an amount that
  // changes with the mesh, and the whole structural response with it. The missing force goes
  // back where the slivers lie: spread over the shell like |grad chi|, a smooth field the
  // elements resolve as they resolve the body force.
  const std::size_t   n = loads.size();
  std::vector<double> sums(4 * n, 0.0); // per load: the resultant, then the spread's integral
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t e = 0; e < rows[k].size(); ++e)
      {
        const unsigned c = dof_component[std::size_t(rows[k][e])];
        sums[4 * k + c] += values[k][e];
        if (c == 0) // the scalar shape functions sum to 1: one component's weights integrate it
          sums[4 * k + 3] += spreads[k][e];
      }
  Utilities::MPI::sum(sums, comm, sums);
  std::vector<Vec3> before(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      before[k]           = Vec3(sums[4 * k], sums[4 * k + 1], sums[4 * k + 2]);
      const double spread = sums[4 * k + 3];
      if (!(spread > 0))
        throw std::logic_error("elastic segment: a near-field load whose cut-off shell misses "
                               "the body");
      const Vec3 missing = loads[k].direction.normalized() - before[k];
      for (std::size_t e = 0; e < rows[k].size(); ++e)
        values[k][e] += missing[dof_component[std::size_t(rows[k][e])]] * spreads[k][e] / spread;
    }
  return before;
}

Mat
ElasticSegment::Impl::functional_matrix(
    const std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>> &f)
    const
{
  // condensed: coefficients on unconstrained dofs only (the constraints are closed, chains
  // resolved; held dofs are zero, hanging ones weighted sums of their parents)
  std::vector<std::map<types::global_dof_index, double>> rows(f.size());
  PetscInt                                               longest = 0;
  for (std::size_t j = 0; j < f.size(); ++j)
    {
      for (std::size_t i = 0; i < f[j].first.size(); ++i)
        {
          const types::global_dof_index dof = f[j].first[i];
          if (const auto *line = constraints.get_constraint_entries(dof))
            for (const auto &[parent, weight] : *line)
              rows[j][parent] += f[j].second[i] * weight;
          else
            rows[j][dof] += f[j].second[i];
        }
      longest = std::max(longest, PetscInt(rows[j].size()));
    }
  longest              = Utilities::MPI::max(longest, comm);
  const bool     first = Utilities::MPI::this_mpi_process(comm) == 0;
  const PetscInt n     = PetscInt(f.size());
  Mat            F;
  petsc_check(MatCreateAIJ(comm, first ? n : 0, PetscInt(owned.n_elements()), n,
                           PetscInt(dofs.n_dofs()), longest, nullptr, longest, nullptr, &F),
              "MatCreateAIJ");
  for (PetscInt j = 0; j < n; ++j)
    for (const auto &[dof, value] : rows[std::size_t(j)])
      {
        const PetscInt column = PetscInt(dof);
        petsc_check(MatSetValues(F, 1, &j, 1, &column, &value, ADD_VALUES), "MatSetValues");
      }
  petsc_check(MatAssemblyBegin(F, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(F, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return F;
}

Eigen::MatrixXd
ElasticSegment::Impl::responses(
    std::size_t n_loads, const LoadEntries &entries,
    const std::vector<std::pair<std::vector<types::global_dof_index>, std::vector<double>>>
        &functionals) const
{
  const Impl     &m = *this;
  Eigen::MatrixXd D(functionals.size(), Eigen::Index(n_loads));
  // All right-hand sides in blocks of columns, solved together (the direct factorisation
  // does a block solve: one pass over the factor per block; an iterative run-time choice
  // solves column by column); a block's solutions take at most about 1 GB (at least 16
  // columns) and at most solve_block columns.
  const std::size_t block =
      std::clamp<std::size_t>((std::size_t(1) << 30) / (8 * m.dofs.n_dofs()), 16, solve_block);
  const PetscInt local = PetscInt(m.owned.n_elements());
  const PetscInt N     = PetscInt(m.dofs.n_dofs());
  const bool     root  = Utilities::MPI::this_mpi_process(m.comm) == 0;
  if (functionals.empty() || n_loads == 0)
    return D;
  Mat F = m.functional_matrix(functionals);
  for (std::size_t first = 0; first < n_loads; first += block)
    {
      const PetscInt cols = PetscInt(std::min<std::size_t>(block, n_loads - first));
      std::vector<std::vector<PetscInt>> dofs(static_cast<std::size_t>(cols));
      std::vector<std::vector<double>>   values(static_cast<std::size_t>(cols));
      std::vector<PetscInt>              counts(static_cast<std::size_t>(cols));
      for (PetscInt c = 0; c < cols; ++c)
        {
          entries(first + std::size_t(c), dofs[std::size_t(c)], values[std::size_t(c)]);
          counts[std::size_t(c)] = PetscInt(dofs[std::size_t(c)].size());
        }
      // the block's loads added to B by column (transposed: to B^T by row), then assembled
      const auto add_loads = [&](Mat B, bool transposed) {
        for (PetscInt c = 0; c < cols; ++c)
          {
            const auto    &d = dofs[std::size_t(c)];
            const PetscInt n = PetscInt(d.size());
            petsc_check(transposed ? MatSetValues(B, 1, &c, n, d.data(),
                                                  values[std::size_t(c)].data(), ADD_VALUES)
                                   : MatSetValues(B, n, d.data(), 1, &c,
                                                  values[std::size_t(c)].data(), ADD_VALUES),
                        "MatSetValues");
          }
        petsc_check(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
        petsc_check(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
      };
      Mat X;
      petsc_check(MatCreateDense(m.comm, local, PETSC_DECIDE, N, cols, nullptr, &X),
                  "MatCreateDense");
      if (m.factor)
        {
          // MUMPS takes sparse right-hand sides by column on the first process: their
          // transpose, all its rows there (its forward elimination then skips the parts of
          // the elimination tree a block's loads do not reach)
          MPI_Allreduce(MPI_IN_PLACE, counts.data(), int(cols), MPIU_INT, MPI_SUM, m.comm);
          Mat Bt;
          petsc_check(MatCreateAIJ(m.comm, root ? cols : 0, root ? N : 0, cols, N, 0,
                                   root ? counts.data() : nullptr, 0, nullptr, &Bt),
                      "MatCreateAIJ");
          add_loads(Bt, true);
          petsc_check(MatMatTransposeSolve(m.factor, Bt, X), "MatMatTransposeSolve");
          MatDestroy(&Bt);
        }
      else
        {
          Mat B;
          petsc_check(MatCreateDense(m.comm, local, PETSC_DECIDE, N, cols, nullptr, &B),
                      "MatCreateDense");
          add_loads(B, false);
          petsc_check(KSPMatSolve(m.ksp, B, X), "KSPMatSolve");
          MatDestroy(&B);
        }
      // the block's responses at once: F X on the first process, then on every process
      Mat product;
      petsc_check(MatMatMult(F, X, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &product), "MatMatMult");
      Eigen::MatrixXd found(D.rows(), cols);
      if (root)
        {
          const PetscScalar *v;
          PetscInt           lda;
          petsc_check(MatDenseGetLDA(product, &lda), "MatDenseGetLDA");
          petsc_check(MatDenseGetArrayRead(product, &v), "MatDenseGetArrayRead");
          for (PetscInt c = 0; c < cols; ++c)
            for (Eigen::Index j = 0; j < D.rows(); ++j)
              found(j, c) = v[c * lda + j];
          petsc_check(MatDenseRestoreArrayRead(product, &v), "MatDenseRestoreArrayRead");
        }
      MatDestroy(&product);
      MPI_Bcast(found.data(), int(found.size()), MPI_DOUBLE, 0, m.comm);
      D.middleCols(Eigen::Index(first), cols) = found;
      MatDestroy(&X);
    }
  MatDestroy(&F);
  return D;
}

Eigen::VectorXd
ElasticSegment::response(const std::vector<PatchLoad> &loads, const std::vector<Probe> &probes,
                         Vec3 *reaction) const
{
  impl->set_up_solver();
  const Impl                      &m = *impl;
  const PETScWrappers::MPI::Vector f = m.assemble_loads(loads);
  const PETScWrappers::MPI::Vector u = m.solve(f);
  if (reaction)
    {
      // Reactions: the internal forces K u of the unconstrained element matrices, summed over
      // the held degrees of freedom by component (no load acts there).
      const QGauss<3>    quadrature(m.options.degree + 1);
      FEValues<3>        values(m.mapping, m.fe, quadrature, update_gradients | update_JxW_values);
      const unsigned     n = m.fe.n_dofs_per_cell();
      FullMatrix<double> local(n, n);
      Vector<double>     ul(n), rl(n);
      std::vector<types::global_dof_index> indices(n);
      std::map<types::global_dof_index, std::pair<unsigned, double>>
          held; // dof -> (component, force)
      for (const auto &cell : m.dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(indices);
            bool any = false;
            for (auto i : indices)
              any |= m.constraints.is_constrained(i);
            if (!any)
              continue;
            m.local_matrix(cell, values, local);
            for (unsigned i = 0; i < n; ++i)
              ul(i) = u(indices[i]);
            local.vmult(rl, ul);
            for (unsigned i = 0; i < n; ++i)
              if (m.constraints.is_constrained(indices[i]))
                {
                  auto &h = held[indices[i]];
                  h.first = m.fe.system_to_component_index(i).first;
                  h.second += rl(i);
                }
          }
      // each rank sums its own cells' parts; the ranks' sums add up
      std::array<double, 3> sum{{0, 0, 0}};
      for (const auto &[dof, h] : held)
        sum[h.first] += h.second;
      Utilities::MPI::sum(ArrayView<const double>(sum.data(), 3), m.comm,
                          ArrayView<double>(sum.data(), 3));
      *reaction = Vec3(sum[0], sum[1], sum[2]);
    }
  return m.evaluate(m.probe_functionals(probes), u);
}

void
ElasticSegment::write_vtu(const std::vector<PatchLoad> &loads, const std::string &path) const
{
  impl->set_up_solver();
  const Impl                      &m = *impl;
  const PETScWrappers::MPI::Vector u = m.solve(m.assemble_loads(loads));
  DataOut<3>                       out;
  out.attach_dof_handler(m.dofs);
  std::vector<DataComponentInterpretation::DataComponentInterpretation> kind(
      3, DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(u, std::vector<std::string>(3, "displacement"), DataOut<3>::type_dof_data,
                      kind);
  const VonMises von_mises(m.lambda, m.mu);
  out.add_data_vector(u, von_mises);
  out.build_patches(m.mapping, m.options.degree);
  const std::string tmp = path + ".tmp";
  out.write_vtu_in_parallel(tmp, m.comm);
  MPI_Barrier(m.comm);
  if (Utilities::MPI::this_mpi_process(m.comm) == 0 && std::rename(tmp.c_str(), path.c_str()) != 0)
    {
      std::remove(tmp.c_str());
      throw InputError("elastic segment: cannot write " + path);
    }
}
std::string
finite_element_versions()
{
  std::ostringstream v;
  v << "deal.II " << DEAL_II_PACKAGE_VERSION << ", PETSc " << PETSC_VERSION_MAJOR << '.'
    << PETSC_VERSION_MINOR << '.' << PETSC_VERSION_SUBMINOR << ", gmsh " << gmsh_version();
  if (const std::string core = blas_core_name(); !core.empty())
    v << ", OpenBLAS " << core << " kernels";
  return v.str();
}
} // namespace gearkit

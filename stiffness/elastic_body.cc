#include "elastic_body.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

namespace gearkit
{
using namespace dealii;

namespace
{
Point<3>
to_point(const Vec3 &x)
{
  return Point<3>(x.x(), x.y(), x.z());
}

Vec3
to_vec(const Tensor<1, 3> &x)
{
  return Vec3(x[0], x[1], x[2]);
}

std::string
format(const Vec3 &x)
{
  std::ostringstream s;
  s << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return s.str();
}

void
check(PetscErrorCode error, const char *call)
{
  if (error != 0)
    throw InputError(std::string("ElasticBody: PETSc failed in ") + call + " (error " +
                     std::to_string(error) + "); check the PETSc options given at run time");
}

/// Wall time between construction and seconds(), synchronised over the communicator.
class Stopwatch
{
public:
  explicit Stopwatch(MPI_Comm comm)
      : comm(comm)
  {
    MPI_Barrier(comm);
    start = MPI_Wtime();
  }
  double
  seconds() const
  {
    MPI_Barrier(comm);
    return MPI_Wtime() - start;
  }

private:
  MPI_Comm comm;
  double   start;
};

/// The face quadrature shared by loads, patch averages and rigid fits.
QGauss<2>
face_quadrature(unsigned degree)
{
  return QGauss<2>(degree + 2);
}

bool
in_ball(const Point<3> &x, const SurfacePatch &patch)
{
  return x.distance(to_point(patch.centre)) <= patch.radius;
}

/// Whether a face may contain quadrature points of the patch.
bool
may_touch(const typename Triangulation<3>::face_iterator &face, const SurfacePatch &patch)
{
  return face->boundary_id() == patch.boundary &&
         face->center().distance(to_point(patch.centre)) <= patch.radius + face->diameter();
}

const ElasticBodyOptions &
validated(const ElasticBodyOptions &o)
{
  std::ostringstream bad;
  const double       E = o.material.youngs_modulus, nu = o.material.poisson_ratio;
  if (o.degree != 1 && o.degree != 2)
    bad << "degree = " << o.degree << " is not allowed; expected 1 or 2";
  else if (!(E > 0 && std::isfinite(E)))
    bad << "Young's modulus (material.youngs_modulus) = " << E << " Pa is not allowed; expected "
        << "E > 0";
  else if (!(nu > -1 && nu < 0.5))
    bad << "Poisson's ratio (material.poisson_ratio) = " << nu << " is not allowed; expected "
        << "-1 < nu < 0.5";
  else if (o.preconditioner != "boomeramg" && o.preconditioner != "gamg")
    bad << "preconditioner = \"" << o.preconditioner << "\" is not allowed; expected "
        << "\"boomeramg\" or \"gamg\"";
  else if (!(o.relative_tolerance > 0 && o.relative_tolerance < 1))
    bad << "relative_tolerance = " << o.relative_tolerance << " is not allowed; expected 0 < "
        << "tolerance < 1";
  else if (o.max_iterations == 0)
    bad << "max_iterations = 0 is not allowed; expected at least 1";
  for (const auto &[id, component] : o.fixed_components)
    if (bad.str().empty() && component > 2)
      bad << "fixed_components: component " << component << " of boundary " << id
          << " is not allowed; expected 0 (x), 1 (y) or 2 (z)";
  for (const RefinementBall &ball : o.local_refinements)
    if (bad.str().empty() && !(ball.radius > 0))
      bad << "local_refinements: radius = " << ball.radius << " m is not allowed; expected > 0";
  if (o.clamped.empty() && o.fixed_components.empty() && bad.str().empty())
    bad << "no boundary is held (clamped and fixed_components are empty); the body would move "
           "rigidly";
  if (!bad.str().empty())
    throw InputError("ElasticBody: " + bad.str());
  return o;
}

/// The additional information of a deal.II exception, else what().
std::string
reason(const std::exception &e)
{
  if (const auto *d = dynamic_cast<const ExceptionBase *>(&e))
    {
      std::ostringstream s;
      d->print_info(s);
      std::string text = s.str();
      while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
      return text;
    }
  return e.what();
}

std::unique_ptr<Triangulation<3>>
read_mesh(const std::string &file)
{
  if (!std::ifstream(file).good())
    throw InputError("ElasticBody: cannot open the mesh file \"" + file + "\"");
  auto      mesh = std::make_unique<Triangulation<3>>();
  GridIn<3> in;
  in.attach_triangulation(*mesh);
  try
    {
      in.read_msh(file);
    }
  catch (const std::exception &e)
    {
      throw InputError("ElasticBody: the mesh file \"" + file +
                       "\" is not a gmsh mesh of a 3-D body that deal.II can read: " + reason(e));
    }
  return mesh;
}

/// von Mises equivalent stress [Pa] from the displacement gradient.
class VonMisesStress : public DataPostprocessorScalar<3>
{
public:
  VonMisesStress(double lambda, double mu)
      : DataPostprocessorScalar<3>("von_mises_stress", update_gradients)
      , lambda(lambda)
      , mu(mu)
  {}

  void
  evaluate_vector_field(const DataPostprocessorInputs::Vector<3> &inputs,
                        std::vector<Vector<double>> &computed) const override
  {
    for (std::size_t q = 0; q < inputs.solution_gradients.size(); ++q)
      {
        Tensor<2, 3> gradient;
        for (unsigned c = 0; c < 3; ++c)
          gradient[c] = inputs.solution_gradients[q][c];
        const SymmetricTensor<2, 3> strain = symmetrize(gradient);
        const SymmetricTensor<2, 3> stress =
            lambda * trace(strain) * unit_symmetric_tensor<3>() + 2 * mu * strain;
        const SymmetricTensor<2, 3> s = deviator(stress);
        computed[q](0)                = std::sqrt(1.5 * (s * s));
      }
  }

private:
  double lambda, mu;
};
} // namespace

ElasticBody::ElasticBody(const std::string &mesh_file, const ElasticBodyOptions &o)
    : ElasticBody(*read_mesh(mesh_file), o, "the mesh file \"" + mesh_file + "\"")
{}

ElasticBody::ElasticBody(const Triangulation<3> &coarse_mesh, const ElasticBodyOptions &o)
    : ElasticBody(coarse_mesh, o, "the given triangulation")
{}

ElasticBody::ElasticBody(const Triangulation<3> &coarse_mesh, const ElasticBodyOptions &o,
                         const std::string &source_name)
    : options(validated(o))
    , source(source_name)
    , comm(o.communicator)
    , triangulation(o.communicator)
    , fe(FE_Q<3>(o.degree), 3)
    , mapping(1)
{
  const Stopwatch watch(comm);
  if (coarse_mesh.n_active_cells() == 0)
    throw InputError("ElasticBody: " + source + " has no cells");
  if (coarse_mesh.n_levels() != 1)
    throw InputError("ElasticBody: " + source +
                     " is refined; pass the coarse mesh and ask for global_refinements");
  if (!coarse_mesh.all_reference_cells_are_hyper_cube())
    throw InputError("ElasticBody: " + source +
                     " has cells that are not hexahedra (tetrahedra, prisms or pyramids); "
                     "only all-hexahedral meshes are allowed");
  for (const auto &face : coarse_mesh.active_face_iterators())
    if (face->at_boundary())
      boundary_ids.insert(face->boundary_id());
  for (const types::boundary_id id : options.clamped)
    require_boundary(id, "clamped");
  for (const auto &fixed : options.fixed_components)
    require_boundary(fixed.first, "fixed_components");

  const double E = options.material.youngs_modulus, nu = options.material.poisson_ratio;
  lambda         = E * nu / ((1 + nu) * (1 - 2 * nu));
  mu             = E / (2 * (1 + nu));

  triangulation.copy_triangulation(coarse_mesh);
  triangulation.refine_global(options.global_refinements);
  for (const RefinementBall &ball : options.local_refinements)
    {
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned() &&
            cell->center().distance(to_point(ball.centre)) <= ball.radius + cell->diameter() / 2)
          cell->set_refine_flag();
      triangulation.execute_coarsening_and_refinement();
    }

  dof_handler.reinit(triangulation);
  dof_handler.distribute_dofs(fe);
  owned = dof_handler.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);

  constraints.reinit(relevant);
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);
  for (const types::boundary_id id : options.clamped)
    VectorTools::interpolate_boundary_values(mapping, dof_handler, id,
                                             Functions::ZeroFunction<3>(3), constraints);
  for (const auto &[id, component] : options.fixed_components)
    {
      ComponentMask mask(3, false);
      mask.set(component, true);
      VectorTools::interpolate_boundary_values(mapping, dof_handler, id,
                                               Functions::ZeroFunction<3>(3), constraints, mask);
    }
  constraints.close();

  DynamicSparsityPattern pattern(relevant);
  DoFTools::make_sparsity_pattern(dof_handler, pattern, constraints, false);
  SparsityTools::distribute_sparsity_pattern(pattern, owned, comm, relevant);
  matrix.reinit(owned, owned, pattern, comm);
  assemble_matrix();

  stats.cells         = triangulation.n_global_active_cells();
  stats.dofs          = dof_handler.n_dofs();
  stats.setup_seconds = watch.seconds();
}

ElasticBody::~ElasticBody()
{
  if (iterative)
    KSPDestroy(&iterative);
  if (direct)
    KSPDestroy(&direct);
}

void
ElasticBody::require_boundary(types::boundary_id id, const char *what) const
{
  if (boundary_ids.count(id))
    return;
  std::ostringstream message;
  message << "ElasticBody: boundary id " << id << " (" << what << ") is not in " << source
          << "; its boundary ids are";
  for (const types::boundary_id present : boundary_ids)
    message << " " << present;
  throw InputError(message.str());
}

void
ElasticBody::cell_matrix(const DoFHandler<3>::active_cell_iterator &cell, FEValues<3> &values,
                         FullMatrix<double> &local) const
{
  // Each shape function has one non-zero component c(i); with g_i its gradient,
  // K_ij = sum_q (lambda g_i[c(i)] g_j[c(j)] + mu g_i[c(j)] g_j[c(i)] + mu [c(i)=c(j)] g_i.g_j) w_q.
  values.reinit(cell);
  local = 0;
  const unsigned n = fe.n_dofs_per_cell();
  for (unsigned q = 0; q < values.n_quadrature_points; ++q)
    {
      const double w = values.JxW(q);
      for (unsigned i = 0; i < n; ++i)
        {
          const unsigned      ci = fe.system_to_component_index(i).first;
          const Tensor<1, 3> &gi = values.shape_grad(i, q);
          for (unsigned j = 0; j <= i; ++j)
            {
              const unsigned      cj = fe.system_to_component_index(j).first;
              const Tensor<1, 3> &gj = values.shape_grad(j, q);
              double              k  = lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci];
              if (ci == cj)
                k += mu * (gi * gj);
              local(i, j) += k * w;
            }
        }
    }
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = i + 1; j < n; ++j)
      local(i, j) = local(j, i);
}

void
ElasticBody::assemble_matrix()
{
  const QGauss<3> quadrature(options.degree + 1);
  FEValues<3>     values(mapping, fe, quadrature, update_gradients | update_JxW_values);
  const unsigned  n = fe.n_dofs_per_cell();
  FullMatrix<double>                   local(n, n);
  std::vector<types::global_dof_index> indices(n);
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        cell_matrix(cell, values, local);
        cell->get_dof_indices(indices);
        constraints.distribute_local_to_global(local, indices, matrix);
      }
  matrix.compress(VectorOperation::add);
  check(MatSetOption(matrix, MAT_SPD, PETSC_TRUE), "MatSetOption");
}

double
ElasticBody::patch_area(const SurfacePatch &patch) const
{
  require_boundary(patch.boundary, "a surface patch");
  if (!(patch.radius > 0) || !patch.centre.allFinite())
    throw InputError("ElasticBody: a surface patch needs a finite centre and a radius > 0 (got " +
                     std::to_string(patch.radius) + " m)");
  const QGauss<2> quadrature = face_quadrature(options.degree);
  FEFaceValues<3> values(mapping, fe, quadrature, update_quadrature_points | update_JxW_values);
  double          area = 0;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned f : cell->face_indices())
        if (cell->face(f)->at_boundary() && may_touch(cell->face(f), patch))
          {
            values.reinit(cell, f);
            for (unsigned q = 0; q < quadrature.size(); ++q)
              if (in_ball(values.quadrature_point(q), patch))
                area += values.JxW(q);
          }
  area = Utilities::MPI::sum(area, comm);
  if (!(area > 0))
    throw InputError("ElasticBody: the surface patch on boundary " +
                     std::to_string(patch.boundary) + " around " + format(patch.centre) +
                     " m with radius " + std::to_string(patch.radius) +
                     " m contains no face quadrature point; make it larger than the faces there");
  return area;
}

AssembledLoad
ElasticBody::assemble(const LoadSet &loads) const
{
  for (const Traction &t : loads.tractions)
    {
      require_boundary(t.boundary, "a traction");
      if (!t.traction.allFinite())
        throw InputError("ElasticBody: the traction on boundary " + std::to_string(t.boundary) +
                         " is not finite");
    }
  std::vector<Vec3> patch_tractions;
  for (const PatchForce &p : loads.patch_forces)
    {
      if (!p.force.allFinite())
        throw InputError("ElasticBody: a patch force is not finite");
      patch_tractions.push_back(p.force / patch_area(p.patch));
    }

  AssembledLoad out;
  out.constrained.reinit(owned, comm);
  out.nodal.reinit(owned, comm);
  const QGauss<2> quadrature = face_quadrature(options.degree);
  FEFaceValues<3> values(mapping, fe, quadrature,
                         update_values | update_quadrature_points | update_JxW_values);
  const unsigned                       n = fe.n_dofs_per_cell();
  Vector<double>                       local(n);
  std::vector<types::global_dof_index> indices(n);
  std::vector<std::size_t>             near; // patch forces that may touch the face
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned f : cell->face_indices())
        {
          const auto face = cell->face(f);
          if (!face->at_boundary())
            continue;
          Vec3 uniform = Vec3::Zero(); // sum of the tractions on this boundary
          bool loaded  = false;
          for (const Traction &t : loads.tractions)
            if (t.boundary == face->boundary_id())
              uniform += t.traction, loaded = true;
          near.clear();
          for (std::size_t k = 0; k < loads.patch_forces.size(); ++k)
            if (may_touch(face, loads.patch_forces[k].patch))
              near.push_back(k), loaded = true;
          if (!loaded)
            continue;
          values.reinit(cell, f);
          local = 0;
          for (unsigned q = 0; q < quadrature.size(); ++q)
            {
              Vec3 t = uniform;
              for (const std::size_t k : near)
                if (in_ball(values.quadrature_point(q), loads.patch_forces[k].patch))
                  t += patch_tractions[k];
              for (unsigned i = 0; i < n; ++i)
                local(i) += t[fe.system_to_component_index(i).first] * values.shape_value(i, q) *
                            values.JxW(q);
            }
          cell->get_dof_indices(indices);
          constraints.distribute_local_to_global(local, indices, out.constrained);
          out.nodal.add(indices, local);
        }
  out.constrained.compress(VectorOperation::add);
  out.nodal.compress(VectorOperation::add);
  return out;
}

void
ElasticBody::attach_rigid_body_modes()
{
  // Support points of the owned dofs (every owned dof lies on a locally owned cell).
  const Quadrature<3> support(fe.get_unit_support_points());
  FEValues<3>         values(mapping, fe, support, update_quadrature_points);
  const unsigned      n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index>              indices(n);
  std::vector<std::pair<types::global_dof_index, unsigned>> dofs; // (dof, component)
  std::vector<Vec3>                                  points;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        values.reinit(cell);
        cell->get_dof_indices(indices);
        for (unsigned i = 0; i < n; ++i)
          if (owned.is_element(indices[i]))
            {
              dofs.emplace_back(indices[i], fe.system_to_component_index(i).first);
              points.push_back(to_vec(values.quadrature_point(i)));
            }
      }
  std::array<double, 4> sum{{0, 0, 0, double(points.size())}};
  for (const Vec3 &x : points)
    for (int k = 0; k < 3; ++k)
      sum[k] += x[k];
  Utilities::MPI::sum(ArrayView<const double>(sum.data(), 4), comm,
                      ArrayView<double>(sum.data(), 4));
  const Vec3 centre = Vec3(sum[0], sum[1], sum[2]) / sum[3];

  // Three translations and three rotations about the centre, orthonormalised.
  std::array<PETScWrappers::MPI::Vector, 6> modes;
  for (auto &mode : modes)
    mode.reinit(owned, comm);
  for (std::size_t k = 0; k < dofs.size(); ++k)
    {
      const auto [dof, c] = dofs[k];
      modes[c](dof)       = 1;
      for (int axis = 0; axis < 3; ++axis)
        modes[3 + axis](dof) = Vec3::Unit(axis).cross(points[k] - centre)[c];
    }
  for (auto &mode : modes)
    mode.compress(VectorOperation::insert);
  std::array<Vec, 6> vectors;
  for (std::size_t k = 0; k < modes.size(); ++k)
    {
      for (std::size_t j = 0; j < k; ++j)
        modes[k].add(-(modes[k] * modes[j]), modes[j]);
      modes[k] /= modes[k].l2_norm();
      vectors[k] = modes[k];
    }
  MatNullSpace space;
  check(MatNullSpaceCreate(comm, PETSC_FALSE, 6, vectors.data(), &space), "MatNullSpaceCreate");
  check(MatSetNearNullSpace(matrix, space), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&space), "MatNullSpaceDestroy");
}

ElasticBody::Displacement
ElasticBody::completed(PETScWrappers::MPI::Vector &x) const
{
  constraints.distribute(x);
  Displacement u(owned, relevant, comm);
  u = x;
  return u;
}

ElasticBody::Displacement
ElasticBody::solve_iterative(const AssembledLoad &load)
{
  const Stopwatch watch(comm);
  if (!iterative)
    {
      attach_rigid_body_modes();
      check(KSPCreate(comm, &iterative), "KSPCreate");
      check(KSPSetOperators(iterative, matrix, matrix), "KSPSetOperators");
      check(KSPSetType(iterative, KSPCG), "KSPSetType");
      check(KSPSetNormType(iterative, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
      check(KSPSetTolerances(iterative, options.relative_tolerance, PETSC_DEFAULT, PETSC_DEFAULT,
                             PetscInt(options.max_iterations)),
            "KSPSetTolerances");
      PC pc;
      check(KSPGetPC(iterative, &pc), "KSPGetPC");
      if (options.preconditioner == "gamg")
        check(PCSetType(pc, PCGAMG), "PCSetType");
      else
        {
          check(PCSetType(pc, PCHYPRE), "PCSetType");
          check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
        }
      check(KSPSetFromOptions(iterative), "KSPSetFromOptions");
    }
  PETScWrappers::MPI::Vector x(owned, comm);
  check(KSPSolve(iterative, load.constrained, x), "KSPSolve");
  KSPConvergedReason converged;
  check(KSPGetConvergedReason(iterative, &converged), "KSPGetConvergedReason");
  PetscInt iterations;
  check(KSPGetIterationNumber(iterative, &iterations), "KSPGetIterationNumber");
  if (converged < 0)
    {
      const char *why;
      KSPGetConvergedReasonString(iterative, &why);
      throw InputError("ElasticBody: the iterative solver did not converge (" + std::string(why) +
                       " after " + std::to_string(iterations) +
                       " iterations); is the body held against rigid motion?");
    }
  KSPType ksp_type;
  PCType  pc_type;
  PC      pc;
  check(KSPGetType(iterative, &ksp_type), "KSPGetType");
  check(KSPGetPC(iterative, &pc), "KSPGetPC");
  check(PCGetType(pc, &pc_type), "PCGetType");
  stats.iterative_method = std::string(ksp_type) + " + " + pc_type;
  stats.last_iterations  = unsigned(iterations);
  Displacement u         = completed(x);
  stats.last_iterative_seconds = watch.seconds();
  return u;
}

void
ElasticBody::factorise()
{
  if (direct)
    return;
  const Stopwatch watch(comm);
  check(KSPCreate(comm, &direct), "KSPCreate");
  check(KSPSetOperators(direct, matrix, matrix), "KSPSetOperators");
  check(KSPSetOptionsPrefix(direct, "direct_"), "KSPSetOptionsPrefix");
  check(KSPSetType(direct, KSPPREONLY), "KSPSetType");
  PC pc;
  check(KSPGetPC(direct, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetFromOptions(direct), "KSPSetFromOptions");
  const PetscErrorCode error = KSPSetUp(direct);
  PCFailedReason       failed = PC_NOERROR;
  if (error == 0)
    PCGetFailedReason(pc, &failed);
  if (error != 0 || failed != PC_NOERROR)
    {
      KSPDestroy(&direct);
      throw InputError("ElasticBody: the factorisation of the stiffness matrix of " + source +
                       " failed (PETSc error " + std::to_string(error) + ", " +
                       PCFailedReasons[failed] + "); is the body held against rigid motion?");
    }
  stats.factorisation_seconds = watch.seconds();
}

ElasticBody::Displacement
ElasticBody::solve_direct(const AssembledLoad &load)
{
  const Stopwatch watch(comm);
  factorise();
  PETScWrappers::MPI::Vector x(owned, comm);
  check(KSPSolve(direct, load.constrained, x), "KSPSolve");
  KSPConvergedReason converged;
  check(KSPGetConvergedReason(direct, &converged), "KSPGetConvergedReason");
  if (converged < 0)
    throw InputError("ElasticBody: the direct solve failed (PETSc reason " +
                     std::to_string(int(converged)) + ")");
  Displacement u            = completed(x);
  stats.last_direct_seconds = watch.seconds();
  return u;
}

std::vector<Vec3>
ElasticBody::displacements(const Displacement &u, const std::vector<Vec3> &points) const
{
  std::vector<Point<3>> at;
  for (const Vec3 &x : points)
    at.push_back(to_point(x));
  Utilities::MPI::RemotePointEvaluation<3> evaluation;
  const auto values = VectorTools::point_values<3>(mapping, dof_handler, u, at, evaluation);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!evaluation.point_found(k))
      throw InputError("ElasticBody: the point " + format(points[k]) + " m is outside " + source);
  std::vector<Vec3> out;
  for (const auto &value : values)
    out.push_back(to_vec(value));
  return out;
}

Vec3
ElasticBody::patch_average(const Displacement &u, const SurfacePatch &patch) const
{
  const double    area       = patch_area(patch);
  const QGauss<2> quadrature = face_quadrature(options.degree);
  FEFaceValues<3> values(mapping, fe, quadrature,
                         update_values | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<1, 3>>        u_q(quadrature.size());
  Tensor<1, 3>                     integral;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned f : cell->face_indices())
        if (cell->face(f)->at_boundary() && may_touch(cell->face(f), patch))
          {
            values.reinit(cell, f);
            values[displacement].get_function_values(u, u_q);
            for (unsigned q = 0; q < quadrature.size(); ++q)
              if (in_ball(values.quadrature_point(q), patch))
                integral += u_q[q] * values.JxW(q);
          }
  integral = Utilities::MPI::sum(integral, comm);
  return to_vec(integral) / area;
}

RigidMotion
ElasticBody::rigid_motion(const Displacement &u, types::boundary_id boundary,
                          const Vec3 &reference_point) const
{
  require_boundary(boundary, "a rigid fit");
  // Normal equations of min sum_q w_q |u_q - c - omega x r_q|^2, r = x - reference point:
  // row block A_q = [I, -[r_q]x] for the unknowns (c, omega).
  const QGauss<2> quadrature = face_quadrature(options.degree);
  FEFaceValues<3> values(mapping, fe, quadrature,
                         update_values | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<1, 3>>        u_q(quadrature.size());
  std::array<double, 42>           sums{}; // 6 x 6 normal matrix, then the right-hand side
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == boundary)
          {
            values.reinit(cell, f);
            values[displacement].get_function_values(u, u_q);
            for (unsigned q = 0; q < quadrature.size(); ++q)
              {
                const Vec3 r = to_vec(values.quadrature_point(q)) - reference_point;
                Eigen::Matrix<double, 3, 6> A;
                Eigen::Matrix3d             cross;
                cross << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
                A << Eigen::Matrix3d::Identity(), -cross;
                const Eigen::Matrix<double, 6, 6> N = values.JxW(q) * A.transpose() * A;
                const Eigen::Matrix<double, 6, 1> b = values.JxW(q) * A.transpose() * to_vec(u_q[q]);
                for (int i = 0; i < 6; ++i)
                  {
                    for (int j = 0; j < 6; ++j)
                      sums[6 * i + j] += N(i, j);
                    sums[36 + i] += b(i);
                  }
              }
          }
  Utilities::MPI::sum(ArrayView<const double>(sums.data(), sums.size()), comm,
                      ArrayView<double>(sums.data(), sums.size()));
  const Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> N(sums.data());
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>>                  b(sums.data() + 36);
  // Scaled to unit diagonal, a rigid motion is determined when no eigenvalue nearly vanishes.
  const Eigen::VectorXd scale = N.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * N * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  if (!scale.allFinite() || !(eigen.eigenvalues().minCoeff() > 1e-10))
    throw InputError("ElasticBody: boundary " + std::to_string(boundary) + " of " + source +
                     " does not determine a rigid motion (its points lie on a line)");
  const Eigen::Matrix<double, 6, 1> x = N.ldlt().solve(b);
  return {x.head<3>(), x.tail<3>()};
}

double
ElasticBody::rigid_rotation(const Displacement &u, types::boundary_id boundary,
                            const Vec3 &axis_point, const Vec3 &axis_direction) const
{
  if (!(axis_direction.norm() > 0) || !axis_direction.allFinite())
    throw InputError("ElasticBody: the rotation axis needs a non-zero direction");
  return rigid_motion(u, boundary, axis_point).rotation.dot(axis_direction.normalized());
}

Wrench
ElasticBody::reaction(const Displacement &u, const AssembledLoad &load,
                      types::boundary_id boundary, const Vec3 &moment_point) const
{
  require_boundary(boundary, "a reaction");
  const IndexSet on_boundary = DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(),
                                                               {boundary});
  // K u with the unconstrained element matrices of the cells touching the boundary, and the
  // support point and component of every owned boundary dof.
  const QGauss<3>     quadrature(options.degree + 1);
  FEValues<3>         values(mapping, fe, quadrature, update_gradients | update_JxW_values);
  const Quadrature<3> support(fe.get_unit_support_points());
  FEValues<3>         support_values(mapping, fe, support, update_quadrature_points);
  const unsigned      n = fe.n_dofs_per_cell();
  FullMatrix<double>                   local(n, n);
  Vector<double>                       u_local(n), f_local(n);
  std::vector<types::global_dof_index> indices(n);
  std::map<types::global_dof_index, std::pair<unsigned, Vec3>> nodes; // dof -> (component, x)
  PETScWrappers::MPI::Vector ku(owned, comm);
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        cell->get_dof_indices(indices);
        bool touches = false;
        for (const auto i : indices)
          touches = touches || on_boundary.is_element(i);
        if (!touches)
          continue;
        cell_matrix(cell, values, local);
        cell->get_dof_values(u, u_local);
        local.vmult(f_local, u_local);
        ku.add(indices, f_local);
        support_values.reinit(cell);
        for (unsigned i = 0; i < n; ++i)
          if (on_boundary.is_element(indices[i]) && owned.is_element(indices[i]))
            nodes[indices[i]] = {fe.system_to_component_index(i).first,
                                 to_vec(support_values.quadrature_point(i))};
      }
  ku.compress(VectorOperation::add);
  std::array<double, 6> sums{};
  for (const auto &[dof, node] : nodes)
    {
      const Vec3 force = (ku(dof) - load.nodal(dof)) * Vec3::Unit(node.first);
      const Vec3 moment = (node.second - moment_point).cross(force);
      for (int k = 0; k < 3; ++k)
        sums[k] += force[k], sums[3 + k] += moment[k];
    }
  Utilities::MPI::sum(ArrayView<const double>(sums.data(), 6), comm,
                      ArrayView<double>(sums.data(), 6));
  return {Vec3(sums[0], sums[1], sums[2]), Vec3(sums[3], sums[4], sums[5])};
}

std::string
ElasticBody::write_vtu(const Displacement &u, const std::string &directory,
                       const std::string &name) const
{
  const unsigned rank = Utilities::MPI::this_mpi_process(comm);
  const unsigned size = Utilities::MPI::n_mpi_processes(comm);
  DataOut<3>     out;
  out.attach_dof_handler(dof_handler);
  out.add_data_vector(u, std::vector<std::string>(3, "displacement"), DataOut<3>::type_dof_data,
                      std::vector<DataComponentInterpretation::DataComponentInterpretation>(
                          3, DataComponentInterpretation::component_is_part_of_vector));
  const VonMisesStress von_mises(lambda, mu);
  out.add_data_vector(u, von_mises);
  out.build_patches(mapping, options.degree);

  // Mine: this rank's piece, and on rank 0 the parallel record.
  const std::string stem = directory + "/" + name;
  std::vector<std::string> mine, pieces;
  for (unsigned r = 0; r < size; ++r)
    pieces.push_back(name + "." + std::to_string(r) + ".vtu");
  const std::string main_file = size == 1 ? stem + ".vtu" : stem + ".pvtu";
  mine.push_back(size == 1 ? main_file : directory + "/" + pieces[rank]);
  if (size > 1 && rank == 0)
    mine.push_back(main_file);
  bool ok = true;
  for (const std::string &file : mine)
    {
      std::ofstream stream(file + ".tmp");
      if (file == main_file && size > 1)
        out.write_pvtu_record(stream, pieces);
      else
        out.write_vtu(stream);
      stream.close();
      ok = ok && bool(stream);
    }
  ok = Utilities::MPI::min(unsigned(ok), comm) == 1;
  // Pieces renamed before the record that names them; on any failure everything is removed.
  for (int pass = 0; ok && pass < 2; ++pass)
    {
      for (const std::string &file : mine)
        if ((file == main_file) == (pass == 1))
          ok = ok && std::rename((file + ".tmp").c_str(), file.c_str()) == 0;
      ok = Utilities::MPI::min(unsigned(ok), comm) == 1;
    }
  if (!ok)
    {
      for (const std::string &file : mine)
        {
          std::remove((file + ".tmp").c_str());
          std::remove(file.c_str());
        }
      throw InputError("ElasticBody: cannot write " + main_file + " (is \"" + directory +
                       "\" a writable directory?)");
    }
  return main_file;
}

std::size_t
ElasticBody::n_cells() const
{
  return stats.cells;
}

std::size_t
ElasticBody::n_dofs() const
{
  return stats.dofs;
}

const ElasticBodyStatistics &
ElasticBody::statistics() const
{
  return stats;
}
} // namespace gearkit

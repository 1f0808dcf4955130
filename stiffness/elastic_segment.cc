// The public class of an elastic segment: its constructor runs the phases that build the body
// (elastic_segment_mesh.cc) in order; its sizes, timings and point queries, a load set's
// response and VTU; and the memory estimates every phase checks against. The phases' other
// sources are listed in elastic_segment_impl.h.
#include "stiffness/elastic_segment.h"

#include "base/blas_kernels.h"
#include "meshes/gmsh_session.h"
#include "stiffness/collective.h"
#include "stiffness/elastic_segment_impl.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/rtree.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <malloc.h>
#include <petscversion.h>
#include <sstream>

namespace gearkit
{
namespace
{
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
} // namespace

namespace elastic_segment_detail
{
std::pair<double, bool>
machine_need(double need, double have, MPI_Comm comm)
{
  const double here = sum_on_this_machine(need, comm);
  const bool   fits = !(have > 0) || here <= have;
  return {here, Utilities::MPI::min(fits ? 1 : 0, comm) == 1};
}

void
require_memory(double need, double have, MPI_Comm comm, const std::string &what,
               const std::string &advice)
{
  const auto [here, fits] = machine_need(need, have, comm);
  if (fits)
    return;
  std::ostringstream msg;
  msg.precision(3);
  msg << "elastic segment: " << what << " needs about " << Utilities::MPI::max(here, comm) / 1e9
      << " GB on a machine with " << Utilities::MPI::min(have, comm) / 1e9 << " GB available. "
      << advice;
  throw MemoryRefusal(msg.str());
}

double
matrix_bytes_per_dof(unsigned degree)
{
  const double p = degree, a = 2 * p + 1, b = p + 1;
  const double per_node = (a * a * a + 3 * (p - 1) * a * a * b + 3 * (p - 1) * (p - 1) * a * b * b +
                           (p - 1) * (p - 1) * (p - 1) * b * b * b) /
                          (p * p * p);
  return 3 * per_node * 40;
}
} // namespace elastic_segment_detail

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

  // The body, phase by phase (elastic_segment_mesh.cc): the matrix's memory checked as soon as
  // the dofs are counted, before the constraints and caches take theirs.
  Triangulation<3> coarse;
  m.read_mesh(coarse);
  m.refine(coarse);
  const std::set<types::boundary_id> present = m.boundary_ids();
  if (o.clamped.empty() && o.rollers.empty())
    throw InputError("elastic segment: the body is not held (no clamped or roller boundary)");
  m.distribute_dofs();
  m.check_assembly_fits();
  m.make_constraints(present);
  m.cache_boundary_faces();
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

Eigen::VectorXd
ElasticSegment::response(const std::vector<PatchLoad> &loads, const std::vector<Probe> &probes,
                         Vec3 *reaction) const
{
  impl->set_up_solver();
  const Impl                      &m = *impl;
  const PETScWrappers::MPI::Vector f = m.assemble_loads(loads);
  const PETScWrappers::MPI::Vector u = m.solve(f);
  if (reaction)
    *reaction = m.reaction(u);
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

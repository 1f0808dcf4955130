// The loads of an elastic segment and what is read off its displacements: patch loads (uniform
// tractions over parts of boundaries), probes (a displacement component at a point) and load
// functionals (a patch's mean displacement along its force), and the responses to many unit
// loads, each alone: patch loads, and point forces whose near field is carried analytically.
#include "base/parallel.h"
#include "stiffness/elastic_segment_impl.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <map>
#include <sstream>

namespace gearkit
{
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
} // namespace gearkit

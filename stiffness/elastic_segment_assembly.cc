// The stiffness matrix of an elastic segment: the element matrices, condensed by the
// constraints into this process's rows and handed to PETSc at once; the memory check before it,
// and the reaction forces of a solved displacement from the same element matrices.
#include "stiffness/elastic_segment_impl.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace gearkit
{
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
ElasticSegment::Impl::check_assembly_fits() const
{
  const double need = double(owned.n_elements()) * matrix_bytes_per_dof(options.degree);
  const double have =
      options.memory_available > 0 ? options.memory_available : memory_available_now();
  require_memory(need, have, comm,
                 mesh_file + " has " + std::to_string(dofs.n_dofs()) +
                     " degrees of freedom; assembling its stiffness matrix",
                 "Use coarser elements (fewer refinements, larger flank elements) or more "
                 "machines under mpirun");
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

Vec3
ElasticSegment::Impl::reaction(const PETScWrappers::MPI::Vector &u) const
{
  // Reactions: the internal forces K u of the unconstrained element matrices, summed over
  // the held degrees of freedom by component (no load acts there).
  const QGauss<3>    quadrature(options.degree + 1);
  FEValues<3>        values(mapping, fe, quadrature, update_gradients | update_JxW_values);
  const unsigned     n = fe.n_dofs_per_cell();
  FullMatrix<double> local(n, n);
  Vector<double>     ul(n), rl(n);
  std::vector<types::global_dof_index> indices(n);
  std::map<types::global_dof_index, std::pair<unsigned, double>>
      held_forces; // dof -> (component, force)
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        cell->get_dof_indices(indices);
        bool any = false;
        for (auto i : indices)
          any |= constraints.is_constrained(i);
        if (!any)
          continue;
        local_matrix(cell, values, local);
        for (unsigned i = 0; i < n; ++i)
          ul(i) = u(indices[i]);
        local.vmult(rl, ul);
        for (unsigned i = 0; i < n; ++i)
          if (constraints.is_constrained(indices[i]))
            {
              auto &h = held_forces[indices[i]];
              h.first = fe.system_to_component_index(i).first;
              h.second += rl(i);
            }
      }
  // each rank sums its own cells' parts; the ranks' sums add up
  std::array<double, 3> sum{{0, 0, 0}};
  for (const auto &[dof, h] : held_forces)
    sum[h.first] += h.second;
  Utilities::MPI::sum(ArrayView<const double>(sum.data(), 3), comm,
                      ArrayView<double>(sum.data(), 3));
  return Vec3(sum[0], sum[1], sum[2]);
}
} // namespace gearkit

// The solver of an elastic segment: set up once at the first solve (the stiffness matrix
// assembled, then factorised by MUMPS's Cholesky after its analysis has sized the factors against
// the memory available, or whatever run-time options ask for), and its solves: one right-hand side,
// or many in blocks with the functionals read off each block's solutions.
#include "stiffness/elastic_segment_impl.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

namespace gearkit
{
namespace
{
/// Right-hand sides solved together: MUMPS's block (ICNTL(27), its default 32) and the most
/// columns of our dense blocks. 128 took the ISO/TR 6336-30 segments' solves from 18 s to 13 s;
/// larger blocks of ours took memory and no time.
constexpr std::size_t solve_block = 128;
} // namespace

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
} // namespace gearkit

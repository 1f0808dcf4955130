// Factorisation and solve times of the elasticity engine on a clamped block (Q1 or Q2, global
// refinements), to choose the direct solver's settings. Run-time PETSc options apply, e.g.
//   PETSC_OPTIONS="-gearkit_mat_mumps_icntl_7 5" build/bench_fe_factorisation 2 1
// usage: bench_fe_factorisation [degree=2] [refinements=0] [elements per side=12]
#include "base/blas_kernels.h"
#include "meshes/box.h"
#include "stiffness/elastic_segment.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

using namespace gearkit;

int
main(int argc, char **argv)
{
  gearkit::use_fitting_blas_kernels(argv); // before MPI: may run the program again
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned                           degree = argc > 1 ? unsigned(std::atoi(argv[1])) : 2;
  const unsigned                           refine = argc > 2 ? unsigned(std::atoi(argv[2])) : 0;
  const int                                n      = argc > 3 ? std::atoi(argv[3]) : 12;
  const std::string                        mesh   = "/tmp/gearkit-bench-block.msh";
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    write_box_mesh(Vec3(60e-3, 60e-3, 30e-3), n, n, n / 2, mesh);
  MPI_Barrier(MPI_COMM_WORLD);
  ElasticSegmentOptions o;
  o.degree = degree, o.refinements = refine, o.clamped = {5};
  dealii::Timer                   setup;
  std::unique_ptr<ElasticSegment> made;
  try
    {
      made = std::make_unique<ElasticSegment>(mesh, o);
    }
  catch (const InputError &e)
    {
      std::fprintf(stderr, "%s\n", e.what());
      return 1;
    }
  const ElasticSegment &body    = *made;
  const double          t_setup = setup.wall_time();
  dealii::Timer         solve;
  const Eigen::MatrixXd D =
      body.response({{Vec3(30e-3, 30e-3, 30e-3), Vec3(0, 0, -1000), 2e-3, {6}}},
                    {{Vec3(30e-3, 30e-3, 25e-3), -Vec3::UnitZ()}});
  const double                           t_solve = solve.wall_time();
  dealii::Utilities::System::MemoryStats mem;
  dealii::Utilities::System::get_memory_stats(mem);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::printf("Q%u, %zu cells, %zu dofs: setup %.2f s (factorisation %.2f s), one solve %.3f s, "
                "peak RSS %.0f MB, w = %.4e m\n",
                degree, body.cells(), body.dofs(), t_setup, body.factorisation_seconds(), t_solve,
                mem.VmHWM / 1024.0, D(0, 0));
}

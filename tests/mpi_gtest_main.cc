// GoogleTest main for the suites that reach MPI and PETSc (stiffness, driver): initialised once
// per process (also when run under mpirun); only rank 0 prints.
#include "base/blas_kernels.h"

#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

int
main(int argc, char **argv)
{
  gearkit::use_fitting_blas_kernels(argv); // before MPI: may run the program again
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    {
      auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
  return RUN_ALL_TESTS();
}

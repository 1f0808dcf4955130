// gearkit: one executable, one scene file. See `gearkit --help`.
#include "base/blas_kernels.h"
#include "base/progress.h"
#include "driver/driver.h"

#include <deal.II/base/mpi.h>

#include <iostream>
#include <unistd.h>

int
main(int argc, char **argv)
{
  // OpenBLAS's fast kernels where it fell back to generic ones (may run the program again)
  gearkit::use_fitting_blas_kernels(argv);
  // MPI and PETSc for the finite-element stages (a single process unless run under mpirun).
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // On a terminal the log's lines wipe the progress line they would run into.
  gearkit::LineWipingBuffer wiping(std::cout.rdbuf());
  std::ostream              terminal_log(&wiping);
  const bool                wipe = gearkit::Progress::shown() && isatty(STDOUT_FILENO) == 1;
  return gearkit::gearkit_main(std::vector<std::string>(argv + 1, argv + argc),
                               wipe ? terminal_log : std::cout, std::cerr);
}

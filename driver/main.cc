// gearkit: one executable, one scene file. See `gearkit --help`.
#include "driver/driver.h"

#include <deal.II/base/mpi.h>

#include <iostream>

int
main(int argc, char **argv)
{
  // MPI and PETSc for the finite-element stages (a single process unless run under mpirun).
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return gearkit::gearkit_main(std::vector<std::string>(argv + 1, argv + argc), std::cout,
                               std::cerr);
}

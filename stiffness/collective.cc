#include "stiffness/collective.h"

#include <cmath>

namespace gearkit
{
std::vector<std::size_t>
my_jobs(std::size_t jobs, MPI_Comm comm)
{
  const unsigned           size = dealii::Utilities::MPI::n_mpi_processes(comm);
  const unsigned           rank = dealii::Utilities::MPI::this_mpi_process(comm);
  std::vector<std::size_t> mine;
  for (std::size_t j = rank; j < jobs; j += size)
    mine.push_back(j);
  return mine;
}

double
sum_on_this_machine(double value, MPI_Comm comm)
{
  MPI_Comm machine;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
  const double sum = dealii::Utilities::MPI::sum(value, machine);
  MPI_Comm_free(&machine);
  return sum;
}

unsigned
processes_on_this_machine(MPI_Comm comm)
{
  return unsigned(std::lround(sum_on_this_machine(1.0, comm)));
}
} // namespace gearkit

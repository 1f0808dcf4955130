// Work that every process of a communicator does and that may fail on some of them: the
// failure is thrown on all, so that no process waits in a collective call the others left.
#pragma once

#include "base/types.h"
#include "stiffness/elastic_segment.h"

#include <deal.II/base/mpi.h>

#include <stdexcept>
#include <string>

namespace gearkit
{
/// Runs work() on this process of comm. Where it throws on any process, every process throws
/// the error of the lowest such process: a MemoryRefusal or an InputError as itself, anything
/// else as std::runtime_error with its message. On one process the error passes unchanged.
/// Collective (one all-gather of the messages after the work).
template <class Work>
void
collectively(MPI_Comm comm, const Work &work)
{
  const bool  alone = dealii::Utilities::MPI::n_mpi_processes(comm) == 1;
  std::string failure; // its kind ('M', 'I' or 'R'), then its message
  try
    {
      work();
    }
  catch (const MemoryRefusal &e)
    {
      if (alone)
        throw;
      failure = std::string("M") + e.what();
    }
  catch (const InputError &e)
    {
      if (alone)
        throw;
      failure = std::string("I") + e.what();
    }
  catch (const std::exception &e)
    {
      if (alone)
        throw;
      failure = std::string("R") + e.what();
    }
  if (alone)
    return;
  for (const std::string &f : dealii::Utilities::MPI::all_gather(comm, failure))
    if (!f.empty())
      {
        const std::string message = f.substr(1);
        if (f[0] == 'M')
          throw MemoryRefusal(message);
        if (f[0] == 'I')
          throw InputError(message);
        throw std::runtime_error(message);
      }
}
} // namespace gearkit

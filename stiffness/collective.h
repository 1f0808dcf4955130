// The MPI helpers of gearkit, in one place: work that every process of a communicator does
// and that may fail on some of them (the failure is thrown on all, so that no process waits in
// a collective call the others left); jobs dealt round the processes and their results sent to
// every process; the processes sharing this machine. The loaded contact's positions, the
// dynamics' sweeps and the members' compliance tables are spread with them.
#pragma once

#include "base/types.h"
#include "stiffness/elastic_segment.h"

#include <deal.II/base/mpi.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

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

/// The jobs 0 .. jobs - 1 this process of comm takes: rank, rank + size, rank + 2 size, ...
std::vector<std::size_t>
my_jobs(std::size_t jobs, MPI_Comm comm);

/// Sends each process's results of its jobs (`mine`, from my_jobs) to every process, as
/// numbers: pack(job, out) appends the record of one of this process's jobs to `out`;
/// unpack(job, in, at) reads the record of another process's job from `in` at `at` (and moves
/// `at` past it). On one process nothing is sent. Collective.
template <class Pack, class Unpack>
void
share_jobs(MPI_Comm comm, const std::vector<std::size_t> &mine, const Pack &pack,
           const Unpack &unpack)
{
  if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
    return;
  std::vector<double> payload;
  for (const std::size_t job : mine)
    {
      payload.push_back(double(job));
      pack(job, payload);
    }
  const unsigned rank = dealii::Utilities::MPI::this_mpi_process(comm);
  unsigned       from = 0;
  for (const std::vector<double> &in : dealii::Utilities::MPI::all_gather(comm, payload))
    {
      if (from++ != rank) // this process's own are in place
        for (std::size_t at = 0; at < in.size();)
          {
            const auto job = std::size_t(in[at++]);
            unpack(job, in, at);
          }
    }
}

/// The sum of `value` over the processes of comm that run on this machine (share its memory
/// and cores); processes_on_this_machine counts them. Collective.
double
sum_on_this_machine(double value, MPI_Comm comm);
unsigned
processes_on_this_machine(MPI_Comm comm);
} // namespace gearkit

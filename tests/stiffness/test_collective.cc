// Work that fails on some processes (stiffness/collective.h): every process throws the lowest
// failed process's error, with its kind; without a failure nothing is thrown. Also run on two
// processes (stiffness_mpi_np2), where the failing process is the last one only.
#include "stiffness/collective.h"

#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <string>

using namespace gearkit;

namespace
{
/// The message of what collectively(work) throws on this process ("" if nothing).
template <class Expected, class Work>
std::string
thrown(const Work &work)
{
  try
    {
      collectively(MPI_COMM_WORLD, work);
    }
  catch (const Expected &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

TEST(Collectively, AFailureOnOneProcessIsThrownOnAllWithItsKind)
{
  const unsigned    rank = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const unsigned    last = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) - 1;
  const std::string who  = "on process " + std::to_string(last);
  EXPECT_EQ(thrown<InputError>([&] {
              if (rank == last)
                throw InputError("bad input " + who);
            }),
            "bad input " + who);
  EXPECT_EQ(thrown<MemoryRefusal>([&] {
              if (rank == last)
                throw MemoryRefusal("too large " + who);
            }),
            "too large " + who);
  // any other error: with its message, never as an input error (on one process unchanged,
  // on several a runtime_error)
  try
    {
      collectively(MPI_COMM_WORLD, [&] {
        if (rank == last)
          throw std::logic_error("internal " + who);
      });
      ADD_FAILURE() << "nothing thrown";
    }
  catch (const InputError &)
    {
      ADD_FAILURE() << "an internal error became an input error";
    }
  catch (const std::exception &e)
    {
      EXPECT_EQ(std::string(e.what()), "internal " + who);
    }
  // the lowest failed process's error where several fail
  EXPECT_EQ(thrown<InputError>([&] { throw InputError("on " + std::to_string(rank)); }), "on 0");
  // no failure: nothing thrown, the work done once
  int runs = 0;
  EXPECT_EQ(thrown<std::exception>([&] { ++runs; }), "");
  EXPECT_EQ(runs, 1);
}

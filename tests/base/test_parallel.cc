// Independent jobs on threads (base/parallel.h): every job runs once whatever the thread count,
// each thread makes its state once, and a failure reaches the caller as the lowest failed job's.
#include "base/parallel.h"
#include "base/types.h"

#include <gtest/gtest.h>

#include <mutex>
#include <set>
#include <stdexcept>

using namespace gearkit;

TEST(ParallelFor, EveryJobOnceWhateverTheThreads)
{
  for (unsigned threads : {0u, 1u, 2u, 5u})
    {
      std::vector<int> runs(100, 0);
      parallel_for(runs.size(), threads, [&](std::size_t i) { runs[i] += int(i); });
      for (std::size_t i = 0; i < runs.size(); ++i)
        EXPECT_EQ(runs[i], int(i)) << threads;
    }
  parallel_for(0, 2, [](std::size_t) { FAIL() << "no job to run"; });
}

TEST(ParallelFor, EachThreadMakesItsStateOnce)
{
  std::mutex             guard;
  int                    states = 0;
  std::set<const void *> used;
  parallel_for(
      50, 3,
      [&] {
        const std::lock_guard<std::mutex> lock(guard);
        ++states;
        return std::vector<double>(10, 0.0);
      },
      [&](std::vector<double> &scratch, std::size_t i) {
        scratch[i % 10] += 1;
        const std::lock_guard<std::mutex> lock(guard);
        used.insert(scratch.data());
      });
  EXPECT_LE(states, 3);
  EXPECT_GE(states, 1);
  EXPECT_LE(int(used.size()), states); // a thread may find every job taken
}

TEST(ParallelFor, TheLowestFailedJobsErrorReachesTheCaller)
{
  for (unsigned threads : {1u, 2u, 4u})
    try
      {
        parallel_for(40, threads, [](std::size_t i) {
          if (i == 7 || i == 30)
            throw InputError("job " + std::to_string(i));
        });
        ADD_FAILURE() << "no exception with " << threads << " threads";
      }
    catch (const InputError &e)
      {
        // jobs start in order: job 30 fails only if it started before job 7 failed; then the
        // lower wins
        EXPECT_EQ(std::string(e.what()), "job 7") << threads;
      }
}

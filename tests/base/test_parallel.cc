// Independent jobs on threads (base/parallel.h): every job runs once whatever the thread count,
// each thread makes its state once, and a failure reaches the caller as the lowest failed job's.
#include "base/parallel.h"
#include "base/types.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

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

TEST(ParallelForBeside, TheTaskRunsOnceBesideTheJobsThenTheCallerJoinsThem)
{
  for (unsigned threads : {1u, 2u, 3u})
    {
      std::vector<int>         runs(200, 0);
      std::atomic<int>         tasks{0};
      std::atomic<std::size_t> done_during_task{0};
      std::atomic<std::size_t> done{0};
      const std::thread::id    caller = std::this_thread::get_id();
      std::atomic<bool>        caller_took_a_job{false};
      parallel_for_beside(
          [&] {
            ++tasks;
            // with helpers, jobs proceed meanwhile: wait (bounded) until some have run
            for (int k = 0; k < 2000 && threads > 1 && done < 10; ++k)
              std::this_thread::sleep_for(std::chrono::milliseconds(1));
            done_during_task = done.load();
          },
          runs.size(), threads, [] { return 0; },
          [&](int, std::size_t i) {
            runs[i] += int(i) + 1;
            caller_took_a_job = caller_took_a_job || std::this_thread::get_id() == caller;
            if (threads > 1 && std::this_thread::get_id() != caller)
              std::this_thread::sleep_for(std::chrono::milliseconds(1));
            ++done;
          });
      EXPECT_EQ(tasks, 1) << threads;
      for (std::size_t i = 0; i < runs.size(); ++i)
        EXPECT_EQ(runs[i], int(i) + 1) << threads;
      if (threads == 1)
        {
          EXPECT_EQ(done_during_task, 0u); // the task first, then the jobs on the caller
        }
      else
        {
          EXPECT_GE(done_during_task, 10u) << threads; // the helpers did not wait for the task
        }
      EXPECT_TRUE(caller_took_a_job) << threads; // the caller joined the jobs
    }
}

TEST(ParallelForBeside, TheTasksErrorFirstAndNoJobStartsAfterIt)
{
  for (unsigned threads : {1u, 2u})
    {
      std::atomic<int> started{0};
      try
        {
          parallel_for_beside([] { throw InputError("task"); }, 1000, threads, [] { return 0; },
                              [&](int, std::size_t i) {
                                ++started;
                                if (i == 3)
                                  throw InputError("job 3");
                              });
          ADD_FAILURE() << "no exception with " << threads << " threads";
        }
      catch (const InputError &e)
        {
          EXPECT_EQ(std::string(e.what()), "task") << threads;
        }
      EXPECT_LT(started, 1000) << threads; // the jobs stopped (one thread: none started)
      if (threads == 1)
        {
          EXPECT_EQ(started, 0);
        }
    }
  // without a failing task, the lowest failed job's error
  try
    {
      parallel_for_beside([] {}, 40, 2, [] { return 0; },
                          [](int, std::size_t i) {
                            if (i == 7)
                              throw InputError("job 7");
                          });
      ADD_FAILURE() << "no exception";
    }
  catch (const InputError &e)
    {
      EXPECT_EQ(std::string(e.what()), "job 7");
    }
}

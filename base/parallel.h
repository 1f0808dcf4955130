// Independent jobs on a few threads: speed sweeps, the loaded positions of a mesh cycle, the
// unit loads of a compliance table. Each thread takes the next job in turn; the results do not
// depend on the number of threads (each job writes only its own output).
#pragma once

#include "base/blas_kernels.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace gearkit
{
/// Runs task() on the calling thread while `threads` - 1 helper threads (0: as many as the
/// hardware runs) work through job(state, i), i = 0 .. n - 1; once task() returns, the calling
/// thread joins them in the jobs. For a task that needs no job's result but uses the cores only
/// in part (a sparse factorisation beside the assembly of its right-hand sides). Each thread
/// first makes its own state with make_state() (scratch it reuses over its jobs). After the
/// task or a job throws, no further job starts; once all threads stop, the task's exception, or
/// else that of the lowest failed job, is rethrown. With more than one thread, OpenBLAS runs on
/// one thread meanwhile (BlasThreads), the task's BLAS calls included.
template <class Task, class MakeState, class Job>
void
parallel_for_beside(const Task &task, std::size_t n, unsigned threads, const MakeState &make_state,
                    const Job &job)
{
  if (threads == 0)
    threads = std::max(1u, std::thread::hardware_concurrency());
  threads = unsigned(std::min<std::size_t>(threads, n + 1));
  const BlasThreads        blas(threads > 1 ? 1 : blas_threads());
  std::atomic<std::size_t> next{0};
  std::mutex               guard;
  std::exception_ptr       failure, task_failure;
  std::size_t              failed = n; // the failed job (n: making a state)
  const auto               fail   = [&](std::size_t i) {
    const std::lock_guard<std::mutex> lock(guard);
    if (!failure || i < failed)
      failure = std::current_exception(), failed = i;
    next = n;
  };
  const auto work = [&] {
    try
      {
        auto state = make_state();
        for (std::size_t i = next++; i < n; i = next++)
          try
            {
              job(state, i);
            }
          catch (...)
            {
              fail(i);
            }
      }
    catch (...)
      {
        fail(n);
      }
  };
  std::vector<std::thread> helpers;
  for (unsigned t = 1; t < threads; ++t)
    helpers.emplace_back(work);
  try
    {
      task();
    }
  catch (...)
    {
      task_failure = std::current_exception();
      next         = n;
    }
  if (n > 0 && !task_failure)
    work();
  for (std::thread &t : helpers)
    t.join();
  if (task_failure)
    std::rethrow_exception(task_failure);
  if (failure)
    std::rethrow_exception(failure);
}

/// Runs job(state, i) for i = 0 .. n - 1 on `threads` threads (0: as many as the hardware
/// runs; never more than n), the calling thread among them. Each thread first makes its own
/// state with make_state() (scratch it reuses over its jobs). After a job throws, no further job
/// starts; once all threads stop, the exception of the lowest failed job is rethrown. With more
/// than one thread, OpenBLAS runs on one thread meanwhile (BlasThreads).
template <class MakeState, class Job>
void
parallel_for(std::size_t n, unsigned threads, const MakeState &make_state, const Job &job)
{
  if (threads == 0)
    threads = std::max(1u, std::thread::hardware_concurrency());
  parallel_for_beside([] {}, n, unsigned(std::clamp<std::size_t>(n, 1, threads)), make_state, job);
}

/// The same without per-thread state: job(i).
template <class Job>
void
parallel_for(std::size_t n, unsigned threads, const Job &job)
{
  parallel_for(
      n, threads, [] { return 0; }, [&](int, std::size_t i) { job(i); });
}
} // namespace gearkit

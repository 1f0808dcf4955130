// Shared by the time-against-error benchmarks: the median wall time of a few runs.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace gearkit::bench
{
template <typename F>
double
median_seconds(F &&f, int runs = 5)
{
  std::vector<double> t;
  for (int r = 0; r < runs; ++r)
    {
      const auto start = std::chrono::steady_clock::now();
      f();
      t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}
} // namespace gearkit::bench

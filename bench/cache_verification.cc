// The cost of the cache's integrity checks (driver/cache.h) on the cache files of a finished
// run: for each file its size, the time to record its digest (what a stage adds after writing,
// besides the manifest walk) and to verify it (digest of the bytes, then the manifest walk over
// every dataset and attribute: what a reuse costs, and more than the seal's walk). Medians of 5.
//
//   build/bench_cache_verification out/default
//
// Compare the totals with the run's wall time (bench/README.md).
#include "bench/timing.h"
#include "driver/cache.h"

#include <filesystem>
#include <iomanip>
#include <iostream>

namespace fs = std::filesystem;

int
main(int argc, char **argv)
{
  if (argc != 2)
    {
      std::cerr << "usage: bench_cache_verification RUN_FOLDER (e.g. out/default)\n";
      return 2;
    }
  const fs::path cache        = fs::path(argv[1]) / "cache";
  const fs::path copy         = fs::temp_directory_path() / "gearkit-bench-cache.h5";
  double         total_record = 0, total_verify = 0, total_mb = 0;
  std::cout << std::setw(44) << std::left << "cache file" << std::right << std::setw(10) << "MB"
            << std::setw(14) << "digest [s]" << std::setw(14) << "verify [s]"
            << "\n";
  for (const fs::path &f : fs::directory_iterator(cache))
    {
      if (f.extension() != ".h5")
        continue;
      const std::string name  = f.filename().string();
      const std::string stage = name.substr(0, name.find('-'));
      const std::string key   = f.stem().string().substr(stage.size() + 1);
      fs::copy_file(f, copy, fs::copy_options::overwrite_existing);
      const double record =
          gearkit::bench::median_seconds([&] { gearkit::record_cache_digest(copy.string()); });
      std::string  problem;
      const double verify = gearkit::bench::median_seconds(
          [&] { problem = gearkit::cache_file_problem(copy.string(), stage, key); });
      const double mb = double(fs::file_size(f)) / 1e6;
      std::cout << std::setw(44) << std::left << name << std::right << std::fixed
                << std::setprecision(2) << std::setw(10) << mb << std::setprecision(4)
                << std::setw(14) << record << std::setw(14) << verify
                << (problem.empty() ? "" : "  (" + problem + ")") << "\n";
      total_record += record, total_verify += verify, total_mb += mb;
    }
  fs::remove(copy);
  fs::remove(copy.string() + ".digest");
  std::cout << std::setw(44) << std::left << "all" << std::right << std::setprecision(2)
            << std::setw(10) << total_mb << std::setprecision(4) << std::setw(14) << total_record
            << std::setw(14) << total_verify << "\n";
}

// libFuzzer target for the cache reader gearkit::cache_file_problem (driver/cache.h). An input
// is a digest record and a cache file, split at the first NUL byte (no NUL: the record alone, an
// empty file); both are written to one temporary folder per process. The reader must answer
// with a reason or with "" and never throw, crash or hang. With random bytes the recorded digest
// rarely fits, which is the point of checking it first: HDF5 only reads files whose bytes are
// those gearkit wrote (HDF5 itself is not robust against arbitrary files, and not ours to fix).
#include "driver/cache.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{
struct TemporaryFolder
{
  TemporaryFolder()
      : dir(std::filesystem::temp_directory_path() /
            ("gearkit-fuzz-cache-" + std::to_string(::getpid())))
  {
    std::filesystem::create_directories(dir);
  }
  ~TemporaryFolder()
  {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
  const std::filesystem::path dir;
};

void
write(const std::string &path, const char *data, std::size_t size)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data, std::streamsize(size));
  if (!out)
    {
      std::perror(path.c_str());
      std::abort(); // not a finding: the fuzzer's own set-up failed
    }
}
} // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  static const TemporaryFolder folder;
  const std::string            file  = (folder.dir / "flanks-0123456789abcdef.h5").string();
  const char                  *bytes = reinterpret_cast<const char *>(data);
  std::size_t                  split = 0;
  while (split < size && bytes[split] != '\0')
    ++split;
  write(file + ".digest", bytes, split);
  write(file, bytes + std::min(size, split + 1), size - std::min(size, split + 1));
  const std::string problem = gearkit::cache_file_problem(file, "flanks", "0123456789abcdef");
  (void)problem;
  return 0;
}

// libFuzzer target for the cache reader gearkit::cache_file_problem (driver/cache.h). An input
// is a line "<stage> <key>" (what the file is asked for), a digest record and a cache file, the
// last two split at the first NUL byte (no NUL: the record alone, an empty file); both are
// written to one temporary folder per process. Seeds (tests/fuzz/corpus/cache) are real cache
// files of a small scene, so that mutations start inside the manifest walk. The reader must answer
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
  const std::string            file  = (folder.dir / "stage.h5").string();
  const char                  *bytes = reinterpret_cast<const char *>(data);
  std::size_t                  line  = 0;
  while (line < size && bytes[line] != '\n')
    ++line;
  const std::string request(bytes, line),
      stage = request.substr(0, request.find(' ')),
      key   = request.find(' ') == std::string::npos ? "" : request.substr(request.find(' ') + 1);
  const std::size_t start = std::min(size, line + 1);
  std::size_t       split = start;
  while (split < size && bytes[split] != '\0')
    ++split;
  write(file + ".digest", bytes + start, split - start);
  write(file, bytes + std::min(size, split + 1), size - std::min(size, split + 1));
  const std::string problem = gearkit::cache_file_problem(file, stage, key);
  (void)problem;
  return 0;
}

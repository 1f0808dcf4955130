// libFuzzer target for the scene reader gearkit::read_scene (driver/scene.h) and its pre-reader
// (driver/scene_text.h: line breaks, byte-order marks, keyword case, includes, duplicates, JSON
// and XML). The reader takes a path, so every input is written to files in one temporary folder
// per process first: the input up to its first line "#=== <name>" is the scene, each such line
// starts another file <name> (letters, digits, . _ -, at most 16 characters) that the scene can
// include. The scene is fuzz.json when its text starts with '{', fuzz.xml with '<', else
// fuzz.prm. It must end normally or with gearkit::InputError.
#include "driver/scene.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace
{
/// <temp>/gearkit-fuzz-scene-<pid>/, emptied before each input (relative file names in a scene
/// resolve against it; the file name is the scene name when `set name` is empty), removed when
/// the process ends normally.
struct TemporaryFolder
{
  TemporaryFolder()
      : dir(std::filesystem::temp_directory_path() /
            ("gearkit-fuzz-scene-" + std::to_string(::getpid())))
  {
  }
  ~TemporaryFolder()
  {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
  const std::filesystem::path dir;
};

const std::filesystem::path &
folder()
{
  static const TemporaryFolder f;
  return f.dir;
}

void
write(const std::filesystem::path &path, const std::string &bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out)
    {
      std::perror(path.c_str());
      std::abort(); // not a finding: the fuzzer's own set-up failed
    }
}

/// The input's files: (name, content), the scene first.
std::vector<std::pair<std::string, std::string>>
split_files(const std::string &input)
{
  const std::string marker = "\n#=== ";
  std::size_t       end    = input.find(marker);
  std::string       scene  = input.substr(0, end);
  const std::size_t start  = scene.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  const char        first  = scene.size() > start ? scene[start] : ' ';
  std::vector<std::pair<std::string, std::string>> files = {{first == '{'   ? "fuzz.json"
                                                             : first == '<' ? "fuzz.xml"
                                                                            : "fuzz.prm",
                                                             scene}};
  while (end != std::string::npos)
    {
      const std::size_t name_begin = end + marker.size();
      const std::size_t line_end   = input.find('\n', name_begin);
      const std::string name       = input.substr(
                name_begin, line_end == std::string::npos ? line_end : line_end - name_begin);
      end                = line_end == std::string::npos ? line_end : input.find(marker, line_end);
      const bool name_ok = !name.empty() && name.size() <= 16 &&
                           std::isalnum(static_cast<unsigned char>(name[0])) &&
                           name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRST"
                                                  "UVWXYZ0123456789._-") == std::string::npos;
      if (name_ok && line_end != std::string::npos)
        files.push_back({name, input.substr(line_end + 1,
                                            end == std::string::npos ? end : end - line_end - 1)});
    }
  return files;
}
} // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  const auto      files = split_files(std::string(reinterpret_cast<const char *>(data), size));
  std::error_code ignored;
  std::filesystem::remove_all(folder(), ignored);
  std::filesystem::create_directories(folder());
  for (const auto &[name, content] : files)
    write(folder() / name, content);
  try
    {
      gearkit::read_scene((folder() / files.front().first).string());
    }
  catch (const gearkit::InputError &)
    {
      // refused with a message: the expected end for malformed input
    }
  return 0;
}

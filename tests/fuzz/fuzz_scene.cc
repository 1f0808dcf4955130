// libFuzzer target for the scene reader gearkit::read_scene (driver/scene.h). The reader takes a
// path (deal.II's ParameterHandler parses files), so every input is written to one temporary
// .prm file per process first. It must end normally or with gearkit::InputError.
#include "driver/scene.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace
{
/// <temp>/gearkit-fuzz-scene-<pid>/fuzz.prm, in its own folder (relative file names in a scene
/// resolve against it; the file name is the scene name when `set name` is empty), removed when
/// the process ends normally.
struct TemporaryScene
{
  TemporaryScene()
      : dir(std::filesystem::temp_directory_path() /
            ("gearkit-fuzz-scene-" + std::to_string(::getpid())))
      , path((dir / "fuzz.prm").string())
  {
    std::filesystem::create_directories(dir);
  }
  ~TemporaryScene()
  {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
  const std::filesystem::path dir;
  const std::string           path;
};

const std::string &
scene_path()
{
  static const TemporaryScene scene;
  return scene.path;
}
} // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  {
    std::ofstream out(scene_path(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(data), std::streamsize(size));
    if (!out)
      {
        std::perror(scene_path().c_str());
        std::abort(); // not a finding: the fuzzer's own set-up failed
      }
  }
  try
    {
      gearkit::read_scene(scene_path());
    }
  catch (const gearkit::InputError &)
    {
      // refused with a message: the expected end for malformed input
    }
  return 0;
}

// The fixture the driver tests share: a fresh folder per test (TempDirectoryTest) and the
// command line run in this process, its output and messages captured.
#pragma once

#include "base/types.h"
#include "driver/driver.h"
#include "driver/scene.h"
#include "tests/temp_directory_test.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace gearkit::test_data
{
class GearkitRun : public TempDirectoryTest
{
protected:
  /// gearkit with `args`, results under `root` (default <dir>/out); the exit status. The log
  /// goes to `out`, the messages to `err`.
  int
  run(std::vector<std::string> args, const std::string &root = "")
  {
    out.str("");
    err.str("");
    args.insert(args.begin(), {"--output-root", root.empty() ? (dir / "out").string() : root});
    return gearkit_main(args, out, err);
  }

  std::ostringstream out, err;
};

/// The message read_scene refuses a scene file with ("" if it reads it).
inline std::string
refusal(const std::string &path)
{
  try
    {
      read_scene(path);
    }
  catch (const InputError &e)
    {
      return e.what();
    }
  return "";
}

/// Every piece in `text` (a message, a log), each missing one reported.
inline void
expect_contains(const std::string &text, const std::vector<std::string> &pieces)
{
  for (const std::string &p : pieces)
    EXPECT_NE(text.find(p), std::string::npos) << "'" << p << "' in: " << text;
}
} // namespace gearkit::test_data

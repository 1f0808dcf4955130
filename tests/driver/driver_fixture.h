// The fixture the driver tests share: a fresh folder per test (TempDirectoryTest) and the
// command line run in this process, its output and messages captured.
#pragma once

#include "driver/driver.h"
#include "tests/temp_directory_test.h"

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
} // namespace gearkit::test_data

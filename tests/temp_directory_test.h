// A GoogleTest fixture with a fresh directory per test (named after the suite and test), removed
// afterwards, and a helper to write a text file into it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace gearkit::test_data
{
class TempDirectoryTest : public ::testing::Test
{
protected:
  void
  SetUp() override
  {
    // Unique and flat: suite, test (parameterised names contain '/') and process id.
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("gearkit-") + info->test_suite_name() + "-" + info->name() +
                       "-" + std::to_string(::getpid());
    std::replace(name.begin(), name.end(), '/', '_');
    dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  void
  TearDown() override
  {
    std::filesystem::remove_all(dir);
  }
  /// Writes `text` to <dir>/<name>; returns the path.
  std::string
  file(const std::string &name, const std::string &text) const
  {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }

  std::filesystem::path dir;
};
} // namespace gearkit::test_data

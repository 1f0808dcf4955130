// Results that can be trusted when the cache, the disk or the command line is wrong: a damaged,
// swapped or foreign cache file is recomputed (never reused, never fatal), with one line saying
// why, and the results equal a clean run's bit for bit; no shell sees the user's paths; one
// run per output folder; a failed report keeps the results. (Failures of the process as a whole
// - a full disk, signals at exit - are checked on the executable: check_failure_paths.py.)
#include "driver/cache.h"
#include "driver/driver.h"
#include "driver/h5_file.h"
#include "tests/driver/driver_fixture.h"
#include "tests/driver/small_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <sys/file.h>
#include <sys/resource.h>
#include <unistd.h>

using namespace gearkit;
namespace fs = std::filesystem;

namespace
{
class CacheIntegrity : public test_data::GearkitRun
{
protected:
  int
  run(const std::string &scene_file, const std::string &root = "")
  {
    return GearkitRun::run({scene_file}, root);
  }
  /// The cache file of `stage` in the last run's log.
  fs::path
  cache_file(const std::string &stage) const
  {
    std::smatch       m;
    const std::string log = out.str();
    EXPECT_TRUE(std::regex_search(
        log, m, std::regex("stage " + stage + ": \\w+ in [0-9.]+ s \\(([^)]+)\\)")))
        << log;
    return dir / "out/small/cache" / m[1].str();
  }
};

// flanks -> measured (synthesised: noise from a seed) -> ste: three stages, a few seconds.
const std::string integrity_scene = test_data::scene_section("small", "ste", "p1") +
                                    test_data::flanks_section({test_data::SpurPair{}}) +
                                    R"(subsection Measured flanks
  subsection p1
    set source         = synthesised
    set profile points = 5
    set face points    = 5
    subsection Synthesis
      set noise = 0.5
    end
  end
end
subsection TCA
  subsection p1
    set positions per mesh cycle = 20
    set mesh cycles              = 1
    set measured flanks          = true
  end
end
)";

/// Every dataset of a file as raw doubles, by path (an independent walk: the H5Group API).
std::map<std::string, std::vector<double>>
datasets(const std::string &file)
{
  std::map<std::string, std::vector<double>> all;
  const H5File                               f    = H5File::open(file);
  std::function<void(const H5Group &)>       walk = [&](const H5Group &g) {
    for (const std::string &name : g.children())
      {
        H5Handle object(H5Oopen(g.id(), name.c_str(), H5P_DEFAULT), H5Oclose);
        if (H5Iget_type(object.id()) == H5I_GROUP)
          walk(g.group(name));
        else
          all[g.path() + name] = g.read_doubles(name);
      }
  };
  walk(f.root());
  return all;
}

bool
bitwise_equal(const std::vector<double> &a, const std::vector<double> &b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// The path of the first floating-point dataset below `group` of an HDF5 file.
std::string
first_dataset(const H5Group &g)
{
  for (const std::string &name : g.children())
    {
      H5Handle object(H5Oopen(g.id(), name.c_str(), H5P_DEFAULT), H5Oclose);
      if (H5Iget_type(object.id()) == H5I_GROUP)
        {
          if (std::string p = first_dataset(g.group(name)); !p.empty())
            return p;
        }
      else if (g.read_doubles(name).size() > 1)
        return g.path() + name;
    }
  return "";
}

/// Opens an HDF5 file for changing it in place (as a user or a disk would).
H5Handle
open_for_writing(const fs::path &file)
{
  return H5Handle(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
}
} // namespace

TEST_F(CacheIntegrity, DamagedCacheFilesAreRecomputedAndTheResultsEqualACleanRun)
{
  const std::string file = this->file("small.prm", integrity_scene);
  ASSERT_EQ(run(file), 0) << err.str();
  const auto clean = datasets((dir / "out/small/results.h5").string());
  ASSERT_GT(clean.size(), 30u);
  const fs::path flanks = cache_file("flanks"), measured = cache_file("measured"),
                 ste = cache_file("ste");
  for (const fs::path &f : {flanks, measured, ste})
    EXPECT_EQ(cache_file_problem(f.string(),
                                 f.filename().string().substr(0, f.filename().string().find('-')),
                                 f.stem().string().substr(f.stem().string().find('-') + 1)),
              "")
        << f;

  // The damage, the cache file it hits, whether it comes with a digest record that fits the
  // damaged bytes (so that the record inside the file has to find it), and a word the log must
  // give as the reason.
  struct Damage
  {
    std::string                           what;
    fs::path                              file;
    std::function<void(const fs::path &)> apply;
    bool                                  digest_fits;
    std::string                           reason;
  };
  // the 21-tooth pinion's flanks of the same scene (another key) for the swap below
  const fs::path other = dir / "other";
  {
    const std::string text = std::regex_replace(integrity_scene, std::regex("number of teeth = 19"),
                                                "number of teeth = 21");
    ASSERT_EQ(run(this->file("small21.prm", text), other.string()), 0) << err.str();
  }
  fs::path other_flanks;
  for (const fs::path &f : fs::directory_iterator(other / "small/cache"))
    if (f.filename().string().rfind("flanks-", 0) == 0 && f.extension() == ".h5")
      other_flanks = f;
  ASSERT_NE(other_flanks, fs::path());
  ASSERT_NE(other_flanks.filename(), flanks.filename());
  auto nan_over_first_dataset = [](const fs::path &f) {
    std::string path;
    {
      const H5File h = H5File::open(f.string());
      path           = first_dataset(h.root().group("ste"));
    }
    ASSERT_FALSE(path.empty());
    H5Handle            file = open_for_writing(f);
    H5Handle            set(H5Dopen2(file.id(), path.c_str(), H5P_DEFAULT), H5Dclose);
    H5Handle            space(H5Dget_space(set.id()), H5Sclose);
    std::vector<double> nan(std::size_t(H5Sget_simple_extent_npoints(space.id())),
                            std::numeric_limits<double>::quiet_NaN());
    ASSERT_GE(H5Dwrite(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, nan.data()), 0);
  };
  auto delete_first_dataset = [](const fs::path &f) {
    std::string path;
    {
      const H5File h = H5File::open(f.string());
      path           = first_dataset(h.root().group("measured"));
    }
    H5Handle file = open_for_writing(f);
    ASSERT_GE(H5Ldelete(file.id(), path.c_str(), H5P_DEFAULT), 0);
  };
  auto change_units = [](const fs::path &f) {
    std::string path;
    {
      const H5File h = H5File::open(f.string());
      path           = first_dataset(h.root().group("flanks"));
    }
    H5Handle file = open_for_writing(f);
    H5Handle set(H5Dopen2(file.id(), path.c_str(), H5P_DEFAULT), H5Dclose);
    H5Group(std::move(set), path).attribute("units", "mm");
  };
  // a cache file and its digest record copied over another's
  auto copy_from = [](const fs::path &from) {
    return [from](const fs::path &f) {
      fs::copy_file(from, f, fs::copy_options::overwrite_existing);
      fs::copy_file(from.string() + ".digest", f.string() + ".digest",
                    fs::copy_options::overwrite_existing);
    };
  };
  const std::string   bytes   = "its bytes are not those written by the stage";
  std::vector<Damage> damages = {
      {"a dataset overwritten with NaN", ste, nan_over_first_dataset, false, bytes},
      {"a dataset deleted", measured, delete_first_dataset, false, bytes},
      {"a units attribute changed", flanks, change_units, false, bytes},
      {"cut short", ste, [](const fs::path &f) { fs::resize_file(f, fs::file_size(f) / 2); }, false,
       bytes},
      {"not HDF5 at all", measured, [](const fs::path &f) { std::ofstream(f) << "text"; }, false,
       bytes},
      {"its digest record lost", flanks,
       [](const fs::path &f) { fs::remove(f.string() + ".digest"); }, false, "no digest record"},
      // the digest record made after the damage: the record inside the file finds it
      {"NaN, recorded", ste, nan_over_first_dataset, true, "changed after it was written"},
      {"not HDF5, recorded", measured, [](const fs::path &f) { std::ofstream(f) << "text"; }, true,
       "cannot be read"},
      {"a dataset deleted, recorded", measured, delete_first_dataset, true, "it lacks /measured"},
      {"units changed, recorded", flanks, change_units, true, "changed after it was written"},
      {"another scene's flanks (21 pinion teeth) in its place", flanks, copy_from(other_flanks),
       false, "was made for key"},
      {"the ste file in the flanks file's place", flanks, copy_from(ste), false,
       "holds the results of stage 'ste', not 'flanks'"},
  };
  for (const Damage &d : damages)
    {
      SCOPED_TRACE(d.what);
      d.apply(d.file);
      if (d.digest_fits)
        record_cache_digest(d.file.string());
      ASSERT_EQ(run(file), 0) << err.str();
      const std::string log = out.str(), stage = d.file.filename().string().substr(
                                             0, d.file.filename().string().find('-'));
      EXPECT_NE(log.find("stage " + stage + ": cache file " + d.file.string() + " not reused: "),
                std::string::npos)
          << log;
      EXPECT_NE(log.find(d.reason), std::string::npos) << log;
      // exactly the damaged stage ran again
      for (const std::string s : {"flanks", "measured", "ste"})
        EXPECT_NE(log.find("stage " + s + (s == stage ? ": ran" : ": reused")), std::string::npos)
            << s << "\n"
            << log;
      const auto again = datasets((dir / "out/small/results.h5").string());
      ASSERT_EQ(again.size(), clean.size());
      for (const auto &[path, values] : clean)
        EXPECT_TRUE(bitwise_equal(values, again.at(path))) << path;
      EXPECT_EQ(
          cache_file_problem(d.file.string(), stage,
                             d.file.stem().string().substr(d.file.stem().string().find('-') + 1)),
          "");
    }
}

TEST_F(CacheIntegrity, NoShellSeesThePathsAndAFailedReportKeepsTheResults)
{
  // Quotes, $(...), back quotes, spaces, a newline and non-ASCII in the output root and in the
  // scene file's folder: a shell would run the commands.
  const fs::path strange = dir / "it's $(touch INJECTED) `touch INJECTED2` a\nb ÄÖ";
  fs::create_directories(strange);
  const std::string file = (strange / "small.prm").string();
  std::ofstream(file) << integrity_scene;
  const fs::path root = strange / "out 'x'";
  ASSERT_EQ(run(file, root.string()), 0) << err.str();
  EXPECT_TRUE(fs::exists(root / "small/results.h5"));
  EXPECT_TRUE(fs::exists(root / "small/report.html")) << out.str();
  for (const fs::path &p : fs::recursive_directory_iterator(dir))
    EXPECT_TRUE(p.filename() != "INJECTED" && p.filename() != "INJECTED2") << p;
  EXPECT_FALSE(fs::exists("INJECTED"));
  EXPECT_FALSE(fs::exists("INJECTED2"));

  // The report cannot be written (a folder where its file goes): the results stay, exit 3.
  fs::remove(root / "small/report.html");
  fs::create_directories(root / "small/report.html");
  EXPECT_EQ(run(file, root.string()), 3);
  EXPECT_NE(err.str().find("writing the report failed"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("the results are complete in " + (root / "small/results.h5").string()),
            std::string::npos)
      << err.str();
  EXPECT_TRUE(fs::exists(root / "small/results.h5"));
  EXPECT_FALSE(fs::exists(root / "small/report.html.tmp")) << "half-written";
}

TEST_F(CacheIntegrity, OneRunAtATimeInAnOutputFolder)
{
  const std::string file = this->file("small.prm", integrity_scene);
  ASSERT_EQ(run(file), 0) << err.str();
  // Another run holds the folder (a lock on an open file of its own, as another process would).
  const fs::path lock = dir / "out/small/.gearkit.lock";
  const int      held = ::open(lock.c_str(), O_RDWR);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
  const auto before = fs::last_write_time(dir / "out/small/results.h5");
  EXPECT_EQ(run(file), 1);
  EXPECT_NE(err.str().find("the output folder " + (dir / "out/small").string() +
                           " is in use by another gearkit run (process " +
                           std::to_string(::getpid()) + ")"),
            std::string::npos)
      << err.str();
  EXPECT_EQ(out.str().find("stage "), std::string::npos) << "a stage ran";
  EXPECT_EQ(fs::last_write_time(dir / "out/small/results.h5"), before);
  ::close(held);
  EXPECT_EQ(run(file), 0) << err.str(); // free again
}

TEST_F(CacheIntegrity, OutputRootWithoutAValueIsNamed)
{
  std::ostringstream o, e;
  EXPECT_EQ(gearkit_main({"x.prm", "--output-root"}, o, e), 2);
  EXPECT_NE(e.str().find("--output-root needs a value"), std::string::npos) << e.str();
}

// The disk fills while a file is being written (a file size limit on this process: writes past
// it fail with EFBIG, as on a full disk with ENOSPC): first a stage's cache file, then
// results.h5 with the stage reused. Each ends with a message naming the file and the cause,
// nothing under the final name and no temporary left; the process goes on (and ends) normally:
// gtest runs this test in a process of its own, so a crash in HDF5's exit handling fails it.
TEST_F(CacheIntegrity, DiskFullWhileWritingEndsWithTheFileAndTheCauseNamed)
{
  const std::string file = this->file("small.prm", integrity_scene);
  struct FileSizeLimit
  {
    explicit FileSizeLimit(rlim_t bytes)
    {
      getrlimit(RLIMIT_FSIZE, &before);
      signal(SIGXFSZ, SIG_IGN); // a failed write, not a signal
      const rlimit limit{bytes, before.rlim_max};
      EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
    }
    ~FileSizeLimit() { setrlimit(RLIMIT_FSIZE, &before); }
    rlimit before{};
  };
  auto temporaries = [&] {
    std::vector<std::string> left;
    for (const fs::path &p : fs::recursive_directory_iterator(dir / "out"))
      if (p.string().find(".tmp") != std::string::npos)
        left.push_back(p.string());
    return left;
  };
  {
    const FileSizeLimit limit(64 * 1024); // the flanks cache file has ~400 kB
    EXPECT_EQ(run(file), 1);
  }
  EXPECT_NE(err.str().find("/out/small/cache/flanks-"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("File too large"), std::string::npos) << err.str();
  EXPECT_EQ(temporaries(), std::vector<std::string>{});
  for (const fs::path &p : fs::directory_iterator(dir / "out/small/cache"))
    ADD_FAILURE() << "a cache file written: " << p;

  ASSERT_EQ(run(file), 0) << err.str();
  fs::remove(dir / "out/small/results.h5");
  {
    const FileSizeLimit limit(64 * 1024);
    EXPECT_EQ(run(file), 1);
  }
  EXPECT_NE(out.str().find("stage flanks: reused"), std::string::npos) << out.str();
  EXPECT_NE(err.str().find("/out/small/results.h5"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("File too large"), std::string::npos) << err.str();
  EXPECT_EQ(temporaries(), std::vector<std::string>{});
  EXPECT_FALSE(fs::exists(dir / "out/small/results.h5"));
  ASSERT_EQ(run(file), 0) << err.str(); // room again: the same scene runs
}

#include "driver/driver.h"

#include "base/blas_kernels.h"
#include "driver/cache.h"
#include "driver/results_schema.h"
#include "driver/stages.h"
#include "stiffness/elastic_segment.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <spawn.h>
#include <sstream>
#include <sys/file.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char **environ;

namespace gearkit
{
namespace fs = std::filesystem;

namespace
{
// Runs `work` on every process. If it throws on some, every process throws the message of the
// first that failed: an error on one process alone (a file system failure on the first, which
// writes) would otherwise leave the others waiting at the next collective call.
template <typename Work>
void
together(Work &&work)
{
  std::string error;
  try
    {
      work();
    }
  catch (const std::exception &e)
    {
      error = e.what();
    }
  const unsigned n_processes = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const unsigned rank        = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const unsigned failed =
      dealii::Utilities::MPI::min(error.empty() ? n_processes : rank, MPI_COMM_WORLD);
  if (failed < n_processes)
    throw InputError(dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, error, failed));
}

/// Cores, memory and processes, for the report.
std::string
machine_description()
{
  std::ostringstream m;
  m << std::thread::hardware_concurrency() << " cores, " << std::setprecision(3)
    << double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / (1u << 30)
    << " GiB memory, " << dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
    << " MPI process(es)";
  std::ifstream cpu("/proc/cpuinfo");
  for (std::string line; std::getline(cpu, line);)
    if (line.rfind("model name", 0) == 0)
      {
        m << ", " << line.substr(line.find(':') + 2);
        break;
      }
  return m.str();
}

/// One writer per output folder: an exclusive lock (flock) on <folder>/.gearkit.lock, which
/// holds the process id of the run that has it. The kernel frees the lock when that process
/// ends, however it ends; the file stays.
class FolderLock
{
public:
  explicit FolderLock(const fs::path &folder)
  {
    const fs::path file = folder / ".gearkit.lock";
    descriptor          = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (descriptor < 0)
      throw InputError("cannot open " + file.string() + " (" + std::strerror(errno) +
                       "); is the output folder writable?");
    if (::flock(descriptor, LOCK_EX | LOCK_NB) != 0)
      {
        std::string other;
        std::ifstream(file) >> other;
        ::close(descriptor);
        throw InputError("the output folder " + folder.string() +
                         " is in use by another gearkit run (process " +
                         (other.empty() ? "unknown" : other) +
                         "); wait for it to end, or give this run another --output-root or "
                         "Scene/name");
      }
    // the process id, for the other run's message (nothing depends on it being written)
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(descriptor, 0) == 0)
      {
        [[maybe_unused]] const auto written = ::write(descriptor, pid.data(), pid.size());
      }
  }
  FolderLock(const FolderLock &) = delete;
  FolderLock &
  operator=(const FolderLock &) = delete;
  ~FolderLock()
  {
    ::close(descriptor); // releases the lock
  }

private:
  int descriptor = -1;
};

/// Runs a program from an argument vector (no shell: quotes, $(...) and spaces in the
/// arguments are plain characters) with this process's environment; waits for it. Its exit
/// status, or a sentence saying why it did not run or end normally.
std::string
run_program(const std::vector<std::string> &arguments)
{
  std::vector<char *> argv;
  for (const std::string &a : arguments)
    argv.push_back(const_cast<char *>(a.c_str()));
  argv.push_back(nullptr);
  pid_t     child  = 0;
  const int failed = posix_spawn(&child, argv[0], nullptr, nullptr, argv.data(), environ);
  if (failed != 0)
    return std::string("could not start ") + argv[0] + " (" + std::strerror(failed) + ")";
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR)
      return std::string("lost ") + argv[0] + " (" + std::strerror(errno) + ")";
  if (WIFEXITED(status))
    return WEXITSTATUS(status) == 0 ? ""
                                    : "exited with status " + std::to_string(WEXITSTATUS(status));
  return "ended by signal " + std::to_string(WTERMSIG(status));
}
} // namespace

std::string
stage_side_directory(const H5Group &out, const std::string &suffix)
{
  std::string dir;
  together([&] {
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    std::string cache = out.file_name(); // <cache>/<stage>-<key>.h5.tmp while running
    if (cache.size() > 4 && cache.substr(cache.size() - 4) == ".tmp")
      cache.resize(cache.size() - 4);
    dir = fs::path(cache).replace_extension("").string() + suffix;
    fs::create_directories(dir);
  });
  dir = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, dir, 0);
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

RunSummary
run_stages(const Scene &scene, const std::string &output_root,
           const std::vector<std::string> &stages, std::ostream &out_log)
{
  for (const std::string &name : stages)
    if (std::none_of(stage_definitions().begin(), stage_definitions().end(),
                     [&](const StageDefinition &d) { return d.name == name; }))
      {
        std::string known;
        for (const StageDefinition &d : stage_definitions())
          known += (known.empty() ? "" : ", ") + d.name;
        throw InputError("no stage '" + name + "'; the stages: " + known);
      }

  // Under mpirun every process runs every stage (the finite elements together, the rest
  // redundantly: they are cheap); the first process alone decides what the cache holds,
  // writes files and logs.
  const unsigned     rank = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  std::ostringstream quiet;
  std::ostream      &log   = rank == 0 ? out_log : quiet;
  const fs::path     dir   = fs::path(output_root) / scene.name;
  const fs::path     cache = dir / "cache";
  together([&] {
    if (rank == 0)
      fs::create_directories(cache);
  });
  log << "gearkit: scene " << scene.file << " -> " << dir.string() << "\n";
  for (const std::string &w : scene.warnings)
    log << "gearkit: WARNING: " << w << "\n";

  RunSummary                                     summary;
  std::map<std::string, std::unique_ptr<H5File>> files;
  for (const std::string &name : required_stages(scene, stages))
    {
      const StageDefinition &s = stage_definition(name);
      StageRun               run;
      run.name                = name;
      const auto        start = std::chrono::steady_clock::now();
      const std::string key   = stage_key(scene, name);
      run.cache_file          = (cache / (name + "-" + key + ".h5")).string();
      // A cache file is reused only when it verifies (driver/cache.h); one that does not is
      // recomputed, with a line saying why.
      if (rank == 0 && fs::exists(run.cache_file))
        {
          if (const std::string problem = cache_file_problem(run.cache_file, name, key);
              problem.empty())
            run.reused = true;
          else
            {
              log << "stage " << name << ": cache file " << run.cache_file
                  << " not reused: " << problem << "; recomputing" << std::endl;
              std::error_code ignored; // the new file replaces it by a rename in any case
              fs::remove(run.cache_file, ignored);
              fs::remove(run.cache_file + ".digest", ignored);
            }
        }
      run.reused = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, run.reused, 0);
      if (!run.reused)
        {
          log << "stage " << name << ": running (" << s.description << ")" << std::endl;
          // Upstream results as stored in their cache files.
          std::vector<H5Group>           groups;
          const std::vector<std::string> ups = upstream_of(scene, s);
          groups.reserve(ups.size());
          Upstream upstream;
          for (const std::string &up : ups)
            {
              groups.push_back(files.at(up)->root().group(up));
              upstream[up] = &groups.back();
            }
          together([&] {
            H5File out = H5File::create(
                rank == 0 ? run.cache_file : run.cache_file + ".process" + std::to_string(rank));
            s.run(scene, upstream, out.root().group(name), log);
            if (rank == 0)
              {
                seal_cache_file(out, name, key);
                out.commit(); // the other processes' private files go with `out`
                record_cache_digest(run.cache_file);
              }
          });
        }
      MPI_Barrier(MPI_COMM_WORLD);
      files[name] = std::make_unique<H5File>(H5File::open(run.cache_file));
      run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      log << "stage " << name << ": " << (run.reused ? "reused" : "ran") << " in " << std::fixed
          << std::setprecision(3) << run.seconds << " s ("
          << fs::path(run.cache_file).filename().string() << ")" << std::endl;
      log.unsetf(std::ios::fixed);
      summary.stages.push_back(run);
    }
  return summary;
}

StageUpstream::StageUpstream(const Scene &scene, const std::string &stage,
                             const std::string &output_root, std::ostream &log)
    : StageUpstream(scene, upstream_of(scene, stage_definition(stage)), output_root, log)
{
}

StageUpstream::StageUpstream(const Scene &scene, const std::vector<std::string> &ups,
                             const std::string &output_root, std::ostream &log)
{
  runs = run_stages(scene, output_root, ups, log);
  for (const StageRun &r : runs.stages)
    files[r.name] = std::make_unique<H5File>(H5File::open(r.cache_file));
  for (const std::string &up : ups)
    {
      groups.push_back(files.at(up)->root().group(up));
      map[up] = &groups.back();
    }
}

RunSummary
run_scene(const Scene &scene, const std::string &output_root, std::ostream &out_log)
{
  const unsigned     rank = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  std::ostringstream quiet;
  std::ostream      &log     = rank == 0 ? out_log : quiet;
  const fs::path     dir     = fs::path(output_root) / scene.name;
  RunSummary         summary = run_stages(scene, output_root, required_stages(scene), out_log);
  std::map<std::string, std::unique_ptr<H5File>> files;
  for (const StageRun &r : summary.stages)
    files[r.name] = std::make_unique<H5File>(H5File::open(r.cache_file));
  summary.results_file = (dir / "results.h5").string();
  if (rank != 0)
    return summary;
  H5File results = H5File::create(summary.results_file);
  {
    const H5Group root = results.root();
    root.attribute("scene", scene.name);
    root.attribute("scene_file", scene.file);
    root.attribute("gearkit_version", GEARKIT_VERSION);
    std::string        stages;
    std::ostringstream table, parameters;
    for (const StageRun &r : summary.stages)
      {
        stages += r.name + (r.reused ? " (reused)" : " (ran)") + "\n";
        table << r.name << '\t' << (r.reused ? "reused" : "ran") << '\t' << r.seconds << '\t'
              << fs::path(r.cache_file).filename().string() << '\n';
      }
    root.attribute("stages", stages);
    // For the report (scripts/report.py): each stage's time and cache file (its key), the
    // scene's parameters as run, what ran them.
    root.attribute("stage_table", table.str());
    for (const auto &[section, text] : scene.sections)
      parameters << "subsection " << section << "\n" << text << "end\n";
    root.attribute("scene_parameters", parameters.str());
    root.attribute("versions", "gearkit " GEARKIT_VERSION ", " + finite_element_versions() +
                                   ", compiler " __VERSION__);
    root.attribute("machine", machine_description());
    std::string warnings;
    for (const std::string &w : scene.warnings)
      warnings += w + "\n";
    root.attribute("warnings", warnings);
    // Caveats for the report to show next to the numbers they qualify (section Notes): one
    // line per note, "<name>\t<area>\t<text>" (notes_text).
    root.attribute("notes", notes_text(scene.notes));
  }
  for (const StageRun &r : summary.stages)
    results.copy_from(*files.at(r.name), "/" + r.name, "/" + r.name);
  results.commit();
  log << "results: " << summary.results_file << std::endl;
  // Files a stage wrote beside its cache file (VTU of the reference mode) go to <dir>/vtu/.
  for (const StageRun &r : summary.stages)
    {
      const fs::path beside = fs::path(r.cache_file).replace_extension("").string() + "-vtu";
      if (!fs::is_directory(beside))
        continue;
      fs::create_directories(dir / "vtu");
      for (const auto &f : fs::directory_iterator(beside))
        if (f.path().extension() == ".vtu" || f.path().extension() == ".pvtu")
          {
            fs::copy_file(f.path(), dir / "vtu" / f.path().filename(),
                          fs::copy_options::overwrite_existing);
            log << "vtu: " << (dir / "vtu" / f.path().filename()).string() << std::endl;
          }
    }
  if (files.count("measured"))
    export_measured_cmm(scene, files.at("measured")->root().group("measured"),
                        (dir / "cmm").string(), log);
  return summary;
}

namespace
{
/// The cases that ship with gearkit: cases/*.prm and cases/*/*.prm, each with the first
/// sentence of its opening comment.
void
list_cases(std::ostream &out)
{
  std::vector<fs::path> files;
  for (const auto &e : fs::recursive_directory_iterator(GEARKIT_SOURCE_DIR "/cases"))
    if (e.path().extension() == ".prm")
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  out << "cases (gearkit [options] <file>; ./run <file>):\n";
  for (const fs::path &f : files)
    {
      std::ifstream in(f);
      std::string   text;
      for (std::string line; std::getline(in, line) && line.rfind("#", 0) == 0;)
        text += line.substr(std::min<std::size_t>(2, line.size())) + " ";
      for (const char *prefix : {"gearkit case: ", "gearkit "})
        if (text.rfind(prefix, 0) == 0)
          text = text.substr(std::string(prefix).size());
      if (const auto stop = text.find(". "); stop != std::string::npos)
        text.resize(stop + 1);
      out << "  " << fs::relative(f, GEARKIT_SOURCE_DIR).string() << "\n";
      std::istringstream words(text);
      std::string        line, word;
      while (words >> word)
        {
          if (!line.empty() && line.size() + 1 + word.size() > 90)
            out << "      " << line << "\n", line.clear();
          line += (line.empty() ? "" : " ") + word;
        }
      out << "      " << line << "\n";
    }
}

const char *usage = R"(usage: gearkit [options] SCENE.prm

Reads one scene file, runs the stages its outputs need (reusing cached results of unchanged
stages) and writes <output root>/<scene name>/results.h5 and report.html (the scene's
parameters, key numbers with their accuracy, pictures, times, versions: open it in a browser).

options:
  --help                  this text
  --list-cases            the scene files that ship with gearkit, with what each computes
  --print-parameters      every scene parameter with its default, allowed values and help
  --print-results [json]  every dataset results.h5 can hold: group, dataset, shape, units and
                          description (a table; json: an array of objects, for scripts)
  --output-root DIR       where scene result folders go (default: out)
  --plot                  also draw the PNG pictures of the results (scripts/plot_results.py)

exit status: 0 done; 1 an error (the message says what; no results.h5 written); 2 a wrong
command line; 3 results.h5 written, but the pictures or the report failed (the message says
which).
)";

} // namespace

void
blas_threads_per_process()
{
  if (!std::getenv("OPENBLAS_NUM_THREADS"))
    set_blas_threads(int(cores_per_process()));
}

RunSummary
run_and_report(const Scene &scene, const std::string &output_root, bool plot, std::ostream &out,
               std::ostream &err)
{
  const bool first = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  // One run at a time in a scene's output folder (the first process holds the lock).
  std::unique_ptr<FolderLock> lock;
  together([&] {
    if (!first)
      return;
    fs::create_directories(fs::path(output_root) / scene.name);
    lock = std::make_unique<FolderLock>(fs::path(output_root) / scene.name);
  });
  RunSummary summary = run_scene(scene, output_root, out);
  // The first process draws the pictures (if asked for), then the report that shows them
  // (every run). Both from an argument vector: no shell sees the paths.
  std::vector<std::pair<std::string, std::string>> scripts;
  if (first && plot)
    scripts.emplace_back("plot_results.py", "plotting");
  if (first)
    scripts.emplace_back("report.py", "writing the report");
  for (const auto &[script, what] : scripts)
    {
      out.flush(); // the log first, then the script's lines
      const std::string path = GEARKIT_SOURCE_DIR "/scripts/" + script;
      if (const std::string failed = run_program({"/usr/bin/python3", path, summary.results_file});
          !failed.empty())
        {
          err << "gearkit: " << what << " failed (/usr/bin/python3 " << path << ": " << failed
              << "); the results are complete in " << summary.results_file << "\n";
          summary.status = 3;
        }
    }
  return summary;
}

int
gearkit_main(const std::vector<std::string> &args, std::ostream &out_0, std::ostream &err_0)
{
  // Under mpirun every process parses the same arguments and meets the same errors: only the
  // first one speaks.
  blas_threads_per_process();
  std::ostream  silent(nullptr);
  const bool    first       = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  std::ostream &out         = first ? out_0 : silent;
  std::ostream &err         = first ? err_0 : silent;
  std::string   output_root = "out", scene_file;
  bool          plot        = false;
  for (std::size_t i = 0; i < args.size(); ++i)
    {
      const std::string &a = args[i];
      if (a == "--help" || a == "-h")
        {
          out << usage;
          return 0;
        }
      else if (a == "--list-cases")
        {
          list_cases(out);
          return 0;
        }
      else if (a == "--print-parameters")
        {
          print_parameters(out);
          return 0;
        }
      else if (a == "--print-results")
        {
          const bool json = i + 1 < args.size() && args[i + 1] == "json";
          print_results_schema(out, json ? "json" : "table");
          return 0;
        }
      else if (a == "--output-root")
        {
          if (i + 1 == args.size() || args[i + 1].empty())
            {
              err << "gearkit: --output-root needs a value: the folder where scene result "
                     "folders go (e.g. --output-root out)\n";
              return 2;
            }
          output_root = args[++i];
        }
      else if (a == "--plot")
        plot = true;
      else if (!a.empty() && a[0] == '-')
        {
          err << "gearkit: unknown option '" << a << "'\n" << usage;
          return 2;
        }
      else if (scene_file.empty())
        scene_file = a;
      else
        {
          err << "gearkit: more than one scene given ('" << scene_file << "', '" << a << "')\n";
          return 2;
        }
    }
  if (scene_file.empty())
    {
      err << "gearkit: no scene file given\n" << usage;
      return 2;
    }
  try
    {
      return run_and_report(read_scene(scene_file), output_root, plot, out, err).status;
    }
  catch (const std::exception &e) // InputError and the rest
    {
      err << "gearkit: error: " << e.what() << "\n";
    }
  return 1;
}
} // namespace gearkit

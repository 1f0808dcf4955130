// The gearkit driver: scene -> stage graph -> cached stage results -> results.h5 (+ plots).
#pragma once

#include "driver/scene.h"
#include "driver/stages.h"

#include <deque>
#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gearkit
{
struct StageRun
{
  std::string name;
  bool        reused  = false;
  double      seconds = 0;
  std::string cache_file;
};

struct RunSummary
{
  std::string           results_file;
  std::vector<StageRun> stages;
  /// run_and_report: 0, or 3 where the results are complete but a picture or the report failed.
  int status = 0;
};

/// Runs (or reuses from the cache, verified) the stages `stages` and every stage they need,
/// upstream first, in <output_root>/<scene name>/cache: each StageRun's cache file holds its
/// results. No results.h5. Collective; an unknown stage name is an InputError.
RunSummary
run_stages(const Scene &scene, const std::string &output_root,
           const std::vector<std::string> &stages, std::ostream &log);

/// What stage `stage` reads for this scene, as it reads it: its upstream stages run or reused
/// from the cache (run_stages, logging to `log`), their cache files open, and the Upstream map
/// its run function gets (for a library-level caller that builds what the stage builds). The
/// stage itself is not run. Collective.
class StageUpstream
{
public:
  StageUpstream(const Scene &scene, const std::string &stage, const std::string &output_root,
                std::ostream &log);
  /// The same for the stages `stages` themselves (and what they need, run but not mapped).
  StageUpstream(const Scene &scene, const std::vector<std::string> &stages,
                const std::string &output_root, std::ostream &log);
  StageUpstream(const StageUpstream &) = delete;
  StageUpstream &
  operator=(const StageUpstream &) = delete;

  const Upstream &
  upstream() const
  {
    return map;
  }
  /// The upstream stages' runs (cache files, reused or not).
  const RunSummary &
  summary() const
  {
    return runs;
  }

private:
  RunSummary                                     runs;
  std::map<std::string, std::unique_ptr<H5File>> files;
  std::deque<H5Group>                            groups;
  Upstream                                       map;
};

/// Runs (or reuses) every stage the scene's outputs need and writes
/// <output_root>/<scene name>/results.h5 atomically. Logs to `log`.
RunSummary
run_scene(const Scene &scene, const std::string &output_root, std::ostream &log);

/// What `gearkit [--plot] SCENE` does with a scene it has read: one run at a time in the scene's
/// output folder (a lock file), run_scene, then the pictures (`plot`) and the report, each a
/// child process started from an argument vector. Under mpirun every process calls it.
RunSummary
run_and_report(const Scene &scene, const std::string &output_root, bool plot, std::ostream &out,
               std::ostream &err);

/// OpenBLAS on this process's share of the machine's cores, unless OPENBLAS_NUM_THREADS says
/// otherwise (by default it takes every core in every process and crowds itself under mpirun).
/// Collective (cores_per_process).
void
blas_threads_per_process();

/// The command line: gearkit [--help] [--list-cases] [--print-parameters] [--print-results [json]]
/// [--output-root DIR] [--plot] SCENE.
/// Returns the process exit code; messages go to out / err.
int
gearkit_main(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);
} // namespace gearkit

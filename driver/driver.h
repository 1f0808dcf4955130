// The gearkit driver: scene -> stage graph -> cached stage results -> results.h5 (+ plots).
#pragma once

#include "driver/scene.h"
#include "driver/stages.h"

#include <iosfwd>
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
};

/// Runs (or reuses) every stage the scene's outputs need and writes
/// <output_root>/<scene name>/results.h5 atomically. Logs to `log`.
RunSummary
run_scene(const Scene &scene, const std::string &output_root, std::ostream &log);

/// The command line: gearkit [--help] [--list-cases] [--print-parameters] [--print-results [json]]
/// [--output-root DIR] [--plot] SCENE.
/// Returns the process exit code; messages go to out / err.
int
gearkit_main(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);
} // namespace gearkit

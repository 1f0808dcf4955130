#include "driver/stages.h"

#include <ostream>

namespace gearkit
{
Progress::Progress(std::ostream &l, std::string s, std::size_t t)
    : log(l)
    , stage(std::move(s))
    , total(t)
    , last(std::chrono::steady_clock::now())
{
}

void
Progress::step(std::size_t n)
{
  done += n;
  const auto now = std::chrono::steady_clock::now();
  if (now - last > std::chrono::seconds(2) && total > 0)
    {
      log << "  " << stage << ": " << 100 * done / total << " %" << std::endl;
      last = now;
    }
}

const std::vector<StageDefinition> &
stage_definitions()
{
  static const std::vector<StageDefinition> stages = {
      {"flanks",
       "flank geometry (involute or spiral bevel), flank grids, mass properties",
       {},
       {"Flanks"},
       3,
       [](const Scene &) { return std::vector<std::string>{}; },
       run_flanks_stage},
      {"measured",
       "measured flank point sets (virtual CMM, synthesised, or read from files)",
       {"flanks"},
       {"Measured flanks"},
       3,
       [](const Scene &scene) {
         std::vector<std::string> files;
         for (const auto &[pair, m] : scene.measured)
           if (m.source == MeasuredSource::cmm_files ||
               m.source == MeasuredSource::topography_files)
             files.insert(files.end(), {m.pinion_file, m.gear_file});
         return files;
       },
       run_measured_stage},
      {"ste",
       "unloaded tooth contact analysis: static transmission error, contact path, normals",
       {"flanks", "measured"},
       {"TCA"},
       5,
       [](const Scene &) { return std::vector<std::string>{}; },
       run_ste_stage},
      {"compliance",
       "finite-element compliance of both members (gmsh tooth segments, deal.II + PETSc)",
       {"flanks"},
       {"Flanks", "TCA", "Finite elements"},
       4,
       [](const Scene &) { return std::vector<std::string>{}; },
       run_compliance_stage},
      {"stiffness",
       "loaded contact over the mesh cycle: loaded TE, mesh stiffness, load sharing, pressure",
       {"flanks", "measured", "compliance"},
       {"TCA", "Loaded contact"},
       6,
       [](const Scene &) { return std::vector<std::string>{}; },
       run_stiffness_stage},
      {"dynamics",
       "14-DOF pair dynamics: static equilibrium, modes, speed sweeps up and down",
       {"flanks", "ste"},
       {"TCA", "Measured flanks", "Dynamics"},
       5,
       [](const Scene &) { return std::vector<std::string>{}; },
       run_dynamics_stage,
       [](const Scene &scene) {
         for (const auto &[name, d] : scene.dynamics)
           if (d.fe_stiffness)
             return std::vector<std::string>{"stiffness"};
         return std::vector<std::string>{};
       }},
  };
  return stages;
}

std::vector<std::string>
upstream_of(const Scene &scene, const StageDefinition &stage)
{
  std::vector<std::string> up = stage.upstream;
  if (stage.upstream_if)
    for (const std::string &s : stage.upstream_if(scene))
      up.push_back(s);
  return up;
}

const std::map<std::string, std::string> &
output_stages()
{
  static const std::map<std::string, std::string> map = {{"flanks", "flanks"},
                                                         {"measured", "measured"},
                                                         {"ste", "ste"},
                                                         {"stiffness", "stiffness"},
                                                         {"dynamics", "dynamics"}};
  return map;
}
} // namespace gearkit

// The stage graph in one place: every stage with its upstream stages, the scene sections and
// input files it reads and the code it runs (which together make its cache key), and the
// outputs a scene can ask for.
#include "driver/stages.h"

#include "driver/cache.h"
#include "driver/results_schema.h"
#include "driver/source_hashes.h"
#include "stiffness/collective.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <iomanip>
#include <mpi.h>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

namespace gearkit
{
namespace
{
std::string
file_contents(const std::string &path)
{
  std::ifstream      in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The driver files every stage runs: the scene reading (its pairs and TCA sections every stage
/// uses), the stage graph, the cache and HDF5 files, the pairs' members and TCA set-up. Each
/// stage adds its own stage file and section files (StageDefinition::code); driver.cc, main.cc,
/// the notes and the other stages' files enter no other stage's key. Of the results schema the
/// interface: each stage's key holds its own entries as they are written (stage_key), so that an
/// entry of another stage recomputes nothing.
const std::vector<std::string> &
driver_code_of_every_stage()
{
  static const std::vector<std::string> files = {
      "driver/cache.cc",        "driver/cache.h",
      "driver/h5_file.cc",      "driver/h5_file.h",
      "driver/pair_members.cc", "driver/pair_members.h",
      "driver/pair_tca.cc",     "driver/pair_tca.h",
      "driver/results_ste.cc",  "driver/results_ste.h",
      "driver/scene.cc",        "driver/scene.h",
      "driver/scene_flanks.cc", "driver/scene_parameters.h",
      "driver/scene_tca.cc",    "driver/scene_text.cc",
      "driver/scene_text.h",    "driver/stages.cc",
      "driver/stages.h",        "driver/results_schema.h"};
  return files;
}
} // namespace

const std::vector<StageDefinition> &
stage_definitions()
{
  static const std::vector<StageDefinition> stages = {
      {"flanks",
       "flank geometry (involute or spiral bevel), flank grids, mass properties",
       {},
       {"Flanks"},
       // tca: the spiral bevel's modified-roll synthesis
       {"base", "geometry", "tca", "driver/stage_flanks.cc"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_flanks_stage,
       nullptr,
       [](const Scene &scene) {
         // the centre distance each involute pair runs at (TCA section): the active profiles
         // refer to it; the rest of the TCA section does not change the flanks
         std::ostringstream s;
         s << std::hexfloat;
         for (const PairScene &pair : scene.pairs)
           if (pair.type == PairType::involute)
             s << pair.name << " operating centre distance "
               << pair.operating_centre_distance(scene.tca.at(pair.name)) << "\n";
         return s.str();
       }},
      {"measured",
       "measured flank point sets (virtual CMM, synthesised, or read from files)",
       {"flanks"},
       {"Measured flanks"},
       {"base", "geometry", "driver/stage_measured.cc", "driver/scene_measured.cc"},
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
       {"base", "geometry", "tca", "driver/stage_ste.cc"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_ste_stage},
      {"compliance",
       "finite-element compliance of both members (gmsh tooth segments, deal.II + PETSc)",
       {"flanks"},
       {"Flanks", "TCA", "Finite elements"},
       {"base", "geometry", "tca", "meshes", "stiffness", "driver/stage_stiffness.cc",
        "driver/scene_stiffness.cc", "driver/results_compliance.cc", "driver/results_compliance.h",
        "driver/pair_contact.cc", "driver/pair_contact.h"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_compliance_stage},
      {"stiffness",
       "loaded contact over the mesh cycle: loaded TE, mesh stiffness, load sharing, pressure",
       {"flanks", "measured", "compliance"},
       {"TCA", "Loaded contact"},
       {"base", "geometry", "tca", "meshes", "stiffness", "driver/stage_stiffness.cc",
        "driver/scene_stiffness.cc", "driver/results_compliance.cc", "driver/results_compliance.h",
        "driver/results_stiffness.cc", "driver/results_stiffness.h", "driver/pair_contact.cc",
        "driver/pair_contact.h"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_stiffness_stage},
      {"dynamics",
       "14-DOF pair dynamics: static equilibrium, modes, speed sweeps up and down",
       {"flanks", "ste"},
       {"TCA", "Measured flanks", "Dynamics"},
       {"base", "geometry", "tca", "dynamics", "driver/stage_dynamics.cc",
        "driver/dynamics_models.h", "driver/scene_dynamics.cc", "driver/scene_measured.cc",
        "driver/results_stiffness.cc", "driver/results_stiffness.h", "driver/results_dynamics.cc",
        "driver/results_dynamics.h"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_dynamics_stage,
       [](const Scene &scene) {
         // K_m from the finite elements; the measured flanks for their deflected TCA
         std::vector<std::string> up;
         for (const auto &[name, d] : scene.dynamics)
           {
             if (d.fe_stiffness)
               up.push_back("stiffness");
             if (d.measured && d.system_deflection)
               up.push_back("measured");
           }
         std::sort(up.begin(), up.end());
         up.erase(std::unique(up.begin(), up.end()), up.end());
         return up;
       }},
      {"train",
       "gear-train impact dynamics: tooth pair curves, IMPACT contact, CVODE run, spectra",
       {"flanks"},
       {"Flanks", "TCA", "Train"},
       {"base", "geometry", "tca", "dynamics", "driver/stage_train.cc", "driver/dynamics_models.h",
        "driver/scene_train.cc", "driver/results_stiffness.cc", "driver/results_stiffness.h"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_train_stage,
       [](const Scene &scene) {
         for (const TrainScene &t : scene.trains)
           for (const TrainMeshScene &m : t.meshes)
             if (m.fe_stiffness)
               return std::vector<std::string>{"stiffness"};
         return std::vector<std::string>{};
       }},
      {"study",
       "design study on one compliance: micro-geometry map of loaded TE, K_m and pressure",
       {"flanks", "compliance"},
       {"TCA", "Loaded contact", "Study"},
       {"base", "geometry", "tca", "meshes", "stiffness", "study", "driver/stage_study.cc",
        "driver/scene_study.cc", "driver/results_compliance.cc", "driver/results_compliance.h",
        "driver/pair_contact.cc", "driver/pair_contact.h"},
       [](const Scene &) { return std::vector<std::string>{}; },
       run_study_stage},
  };
  return stages;
}

const StageDefinition &
stage_definition(const std::string &name)
{
  for (const StageDefinition &s : stage_definitions())
    if (s.name == name)
      return s;
  throw std::logic_error("unknown stage " + name);
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
  static const std::map<std::string, std::string> map = {
      {"flanks", "flanks"},       {"measured", "measured"}, {"ste", "ste"},
      {"stiffness", "stiffness"}, {"dynamics", "dynamics"}, {"train", "train"},
      {"study", "study"}};
  return map;
}
std::vector<std::string>
required_stages(const std::vector<std::string> &outputs)
{
  Scene scene;
  scene.outputs = outputs;
  return required_stages(scene);
}

std::vector<std::string>
required_stages(const Scene &scene)
{
  std::vector<std::string> targets;
  for (const std::string &o : scene.outputs)
    targets.push_back(output_stages().at(o));
  return required_stages(scene, targets);
}

std::vector<std::string>
required_stages(const Scene &scene, const std::vector<std::string> &targets)
{
  std::set<std::string>                    needed;
  std::function<void(const std::string &)> add = [&](const std::string &stage) {
    if (needed.insert(stage).second)
      for (const std::string &up : upstream_of(scene, stage_definition(stage)))
        add(up);
  };
  for (const std::string &t : targets)
    add(stage_definition(t).name);
  std::vector<std::string> order; // stage_definitions() is already in dependency order
  for (const StageDefinition &s : stage_definitions())
    if (needed.count(s.name))
      order.push_back(s.name);
  return order;
}

std::string
stage_key(const Scene &scene, const std::string &stage)
{
  const StageDefinition &s    = stage_definition(stage);
  std::string            text = s.name + "\n";
  for (const std::string &code : driver_code_of_every_stage())
    text += "code " + code + " " + source_hashes().at(code) + "\n";
  for (const std::string &code : s.code)
    text += "code " + code + " " + source_hashes().at(code) + "\n";
  // the stage's datasets in the results schema, their units and descriptions as its cache file
  // holds them
  for (const ResultDataset &d : results_schema())
    if (d.group.rfind(s.name + "/", 0) == 0)
      {
        text += "result " + d.group + " " + d.name + " " + d.shape + " " + d.units + "\n";
        for (const std::string &description : result_descriptions(d))
          text += "  " + description + "\n";
      }
  for (const std::string &section : s.sections)
    {
      const auto it = scene.sections.find(section);
      text += "[" + section + "]\n" + (it == scene.sections.end() ? "" : it->second);
    }
  if (s.derived_parameters)
    text += "[derived]\n" + s.derived_parameters(scene);
  for (const std::string &f : s.input_files(scene))
    text += "file " + f + " " + text_digest(file_contents(f)) + "\n";
  for (const std::string &up : upstream_of(scene, s))
    text += "upstream " + up + " " + stage_key(scene, up) + "\n";
  return text_digest(text); // a cache key, not a security measure
}

unsigned
cores_per_process()
{
  // counted once (collectively: gearkit_main asks first, on every process)
  static const unsigned cores = [] {
    return std::max(1u, std::thread::hardware_concurrency() /
                            processes_on_this_machine(MPI_COMM_WORLD));
  }();
  return cores;
}
} // namespace gearkit

// The stages the driver can run, each a function from the scene (and upstream stage results,
// read back from their cache files) to one HDF5 group. The driver works out which stages the
// requested outputs need, keys each by a hash of exactly what it depends on, and reuses cached
// results.
#pragma once

#include "base/progress.h"
#include "driver/h5_file.h"
#include "driver/scene.h"
#include "geometry/measured_flank.h"

#include <chrono>
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace gearkit
{
/// The cores of this machine per process of MPI_COMM_WORLD running on it (at least 1): the
/// threads a process may use without crowding the others. The first call is collective (every
/// process makes it: gearkit_main does); later ones return the count.
unsigned
cores_per_process();

/// Upstream results a stage may read: stage name -> its group in its cache file.
using Upstream = std::map<std::string, const H5Group *>;

/// A directory beside the cache file of the running stage `out` belongs to ("<cache>/<stage>-
/// <key><suffix>"), created, the same on every MPI process (under mpirun only the first
/// process writes the cache file; the others compute into private files). For files the stage
/// writes besides its HDF5 results: meshes, VTU.
std::string
stage_side_directory(const H5Group &out, const std::string &suffix);

struct StageDefinition
{
  std::string              name;
  std::string              description;
  std::vector<std::string> upstream; ///< stages whose results this one needs
  /// Scene sections whose parameters enter the key (never "Notes": a note changes no result).
  std::vector<std::string> sections;
  /// Library folders ("stiffness") and driver files ("driver/stage_stiffness.cc") whose code
  /// the stage runs besides the driver files every stage runs (stages.cc): their source hashes
  /// (driver/source_hashes.py: tokens, without comments and help texts) enter the key, so
  /// changed code re-runs the stage and a reworded help text or comment does not.
  std::vector<std::string> code;
  /// Input files whose contents enter the key (e.g. CMM files).
  std::function<std::vector<std::string>(const Scene &)>                                input_files;
  std::function<void(const Scene &, const Upstream &, const H5Group &, std::ostream &)> run;
  /// Stages whose results this one needs only when the scene says so (empty: none).
  std::function<std::vector<std::string>(const Scene &)> upstream_if = nullptr;
  /// Values the stage takes from sections not in `sections` (text; they enter the key): so that
  /// the stage re-runs when they change, and only then (empty: none).
  std::function<std::string(const Scene &)> derived_parameters = nullptr;
};

/// The stage's upstream stages for this scene (upstream and upstream_if).
std::vector<std::string>
upstream_of(const Scene &scene, const StageDefinition &stage);

/// All stages in dependency order.
const std::vector<StageDefinition> &
stage_definitions();

/// The definition of the stage of this name.
const StageDefinition &
stage_definition(const std::string &name);

/// The stages the requested outputs need, upstream first.
std::vector<std::string>
required_stages(const std::vector<std::string> &outputs);
/// The same for a scene (stages needed only when its parameters say so included).
std::vector<std::string>
required_stages(const Scene &scene);
/// The stages `targets` need for a scene, the targets included, upstream first.
std::vector<std::string>
required_stages(const Scene &scene, const std::vector<std::string> &targets);

/// Cache key of a stage: a hash of its code (the sources of driver/ and of the folders in
/// `code`), its scene sections, its input files' contents and the keys of its upstream stages
/// (hex string).
std::string
stage_key(const Scene &scene, const std::string &stage);

/// Output name (Scene/outputs) -> the stage that produces it.
const std::map<std::string, std::string> &
output_stages();

// The stages (one source file each; compliance and stiffness share stage_stiffness.cc).
void
run_compliance_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_stiffness_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_flanks_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_measured_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_ste_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_dynamics_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_train_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);
void
run_study_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &);

/// A member's measured flanks as the measured stage stored them (for later stages and exports).
MeasuredMember
read_measured(const H5Group &member_group, const std::string &member);

/// Writes the virtual or synthesised measurements of every pair as CMM point files
/// <dir>/<pair>_<member>.cmm (a starting point for users and for `source = cmm files`).
void
export_measured_cmm(const Scene &scene, const H5Group &measured, const std::string &dir,
                    std::ostream &log);
} // namespace gearkit

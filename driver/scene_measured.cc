// Section Measured flanks/<pair>: where the pair's measured flanks come from (virtual CMM,
// synthesis, CMM or topography files) and how they are sampled or synthesised.
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <filesystem>
#include <tuple>

namespace gearkit
{
void
MeasuredScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("source", "none",
                    Patterns::Selection("none|virtual cmm|synthesised|cmm files|topography files"),
                    "Where measured flanks come from: none; virtual cmm (sampled from the "
                    "theoretical flanks); synthesised (theoretical plus the errors below); cmm "
                    "files or topography files (see docs/cmm-format.md).");
  prm.declare_entry("pinion file", "", Patterns::Anything(),
                    "Pinion CMM or topography file, relative to the scene file.");
  prm.declare_entry("gear file", "", Patterns::Anything(),
                    "Gear CMM or topography file, relative to the scene file.");
  prm.declare_entry("nominal tolerance", "100", Patterns::Double(0.001, 100000),
                    "[um] Files: every measured point must lie within this distance of its "
                    "nominal flank (the Flanks section's, with its modifications and "
                    "deviations); a point beyond it, swapped drive and coast labels or "
                    "coordinates in other units than the header says stop the run.");
  prm.declare_entry("profile points", "29", Patterns::Integer(2, 10000),
                    "Grid points along the profile per flank (virtual CMM).");
  prm.declare_entry("face points", "9", Patterns::Integer(2, 10000),
                    "Grid points along the face per flank (virtual CMM).");
  prm.declare_entry("edge margin", "0", Patterns::Double(0, 0.45),
                    "Fraction of the profile and face ranges left out at each edge.");
  prm.declare_entry("pinion teeth", "", Patterns::List(Patterns::Integer(0), 0, 100000),
                    "Pinion teeth to measure (empty = all).");
  prm.declare_entry("gear teeth", "", Patterns::List(Patterns::Integer(0), 0, 100000),
                    "Gear teeth to measure (empty = all).");
  prm.enter_subsection("Synthesis");
  prm.declare_entry("seed", "1", Patterns::Integer(0), "Random seed (same seed, same flanks).");
  prm.declare_entry("form error", "2", Patterns::Double(0),
                    "[um] Amplitude of smooth low-order form deviations per flank.");
  prm.declare_entry("waviness amplitude", "0.5", Patterns::Double(0), "[um] Waviness amplitude.");
  prm.declare_entry("waviness wavelength", "1", Patterns::Double(0),
                    "[mm] Waviness wavelength along the flank.");
  prm.declare_entry("roughness", "0.3", Patterns::Double(0), "[um] Roughness amplitude.");
  prm.declare_entry("noise", "1", Patterns::Double(0),
                    "[um] Standard deviation of the measurement noise.");
  prm.declare_entry("pitch error", "3", Patterns::Double(0),
                    "[um] Standard deviation of the single pitch deviations.");
  prm.leave_subsection();
}

void
MeasuredScene::parse(ParameterHandler &prm, const std::string &scene_directory)
{
  static const std::map<std::string, MeasuredSource> sources = {
      {"none", MeasuredSource::none},
      {"virtual cmm", MeasuredSource::virtual_cmm},
      {"synthesised", MeasuredSource::synthesised},
      {"cmm files", MeasuredSource::cmm_files},
      {"topography files", MeasuredSource::topography_files}};
  source    = sources.at(prm.get("source"));
  auto path = [&](const char *key) {
    const std::string f = prm.get(key);
    return f.empty() ? f : (std::filesystem::path(scene_directory) / f).lexically_normal().string();
  };
  pinion_file       = path("pinion file");
  gear_file         = path("gear file");
  nominal_tolerance = prm.get_double("nominal tolerance") * um;
  profile_points    = prm.get_integer("profile points");
  face_points       = prm.get_integer("face points");
  edge_margin       = prm.get_double("edge margin");
  pinion_teeth      = get_integers(prm, "pinion teeth");
  gear_teeth        = get_integers(prm, "gear teeth");
  prm.enter_subsection("Synthesis");
  seed                = prm.get_integer("seed");
  form_error          = prm.get_double("form error") * um;
  waviness_amplitude  = prm.get_double("waviness amplitude") * um;
  waviness_wavelength = prm.get_double("waviness wavelength") * mm;
  roughness           = prm.get_double("roughness") * um;
  noise               = prm.get_double("noise") * um;
  pitch_error         = prm.get_double("pitch error") * um;
  prm.leave_subsection();
}

void
MeasuredScene::check(const PairScene &pair) const
{
  const std::string where = "Measured flanks/" + pair.name + ": ";
  if (source == MeasuredSource::cmm_files || source == MeasuredSource::topography_files)
    for (const auto &[key, f] : {std::pair{"pinion file", pinion_file}, {"gear file", gear_file}})
      if (f.empty() || !std::filesystem::is_regular_file(f))
        throw InputError(where + key + " = '" + f + "' does not name a readable file (source = " +
                         (source == MeasuredSource::cmm_files ? "cmm files" : "topography files") +
                         ")");
  if (source == MeasuredSource::topography_files && pair.type != PairType::involute)
    throw InputError(where + "source = topography files: topography grids are defined on "
                             "involute flanks; for a spiral bevel pair use cmm files");
  const auto [z1, z2] = pair_teeth(pair);
  for (const auto &[key, teeth, z] :
       {std::tuple{"pinion teeth", &pinion_teeth, z1}, {"gear teeth", &gear_teeth, z2}})
    for (const int k : *teeth)
      if (k >= z)
        throw InputError(where + key + ": tooth " + std::to_string(k) +
                         " is not allowed; the member's teeth are 0 to " + std::to_string(z - 1));
}
} // namespace gearkit

// Section Study/<pair>: design studies of the pair on its compliance (stage "study"): a
// micro-geometry map, a tolerance Monte Carlo, a misalignment (V-H) check.
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace gearkit
{
namespace
{
/// The scene entry of a modification field: its name with spaces ("tip relief").
std::string
entry_name(std::string field)
{
  std::replace(field.begin(), field.end(), '_', ' ');
  return field;
}

bool
is_length(const std::string &field)
{
  return field.size() > 7 && field.compare(field.size() - 7, 7, "_length") == 0;
}

bool
is_slope(const std::string &field)
{
  return field.size() > 6 && field.compare(field.size() - 6, 6, "_slope") == 0;
}

/// The unit of a misalignment field's scene entry (as the TCA section's entry of that name):
/// its factor to SI and its name.
std::pair<double, const char *>
misalignment_unit(const std::string &field)
{
  if (field == "offset" || field == "centre_distance_error")
    return {um, "um"};
  if (field.find("angle") != std::string::npos)
    return {mrad, "mrad"};
  return {mm, "mm"};
}
} // namespace

void
StudyScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("kind", "microgeometry map",
                    Patterns::Selection("microgeometry map|tolerances|misalignments"),
                    "microgeometry map: every combination of the modification values below at "
                    "every torque. tolerances: samples of the design (the Flanks section's "
                    "modifications with single values below) whose teeth, pitches and runout "
                    "are drawn within ISO 1328-1:2013 flank tolerance classes: percentiles of "
                    "the loaded TE peak-to-peak, K_m and pressure, and which deviation drives "
                    "them. misalignments: every combination of the misalignment values below "
                    "(a V-H check of a bevel pair: offset, pinion and gear axial shift, "
                    "intersecting angle): e_0, e_L, K_m and the contact pattern on the gear "
                    "flank, any pair type.");
  prm.declare_entry("pinion class", "6", Patterns::Integer(0, 11),
                    "Tolerances: the pinion's ISO 1328-1 flank tolerance class (0: perfect).");
  prm.declare_entry("gear class", "6", Patterns::Integer(0, 11),
                    "Tolerances: the gear's ISO 1328-1 flank tolerance class (0: perfect).");
  prm.declare_entry("distribution", "normal", Patterns::Selection("normal|uniform"),
                    "Tolerances: normal (the tolerance is 3 sigma, values beyond drawn again) "
                    "or uniform within the tolerance.");
  prm.declare_entry("samples", "200", Patterns::Integer(1, 1000000),
                    "Tolerances: the samples drawn (each its own random stream from the seed "
                    "and its number: the same on any number of processes).");
  prm.declare_entry("seed", "1", Patterns::Integer(0), "Tolerances: the random seed.");
  prm.declare_entry("assembly deviations", "true", Patterns::Bool(),
                    "Tolerances: also tilt the gear axis within ISO/TR 10064-3's parallelism "
                    "recommendation for the gear's class (crossing 0.5 F_beta / b, intersecting "
                    "F_beta / b).");
  prm.declare_entry("mesh cycles", "0", Patterns::Integer(0, 100000),
                    "Tolerances: the mesh cycles each sample runs over (0: a pinion "
                    "revolution, z1 cycles: every pinion tooth meshes once).");
  prm.declare_entry("torques", "", Patterns::List(Patterns::Double(0), 0, 1000),
                    "[N m] Pinion torques of the map (empty: the Loaded contact section's); "
                    "run in ascending order, the design torque added where missing.");
  prm.declare_entry("design torque", "0", Patterns::Double(0),
                    "[N m] The torque the design is for: marked on the map, where the best "
                    "relief is interpolated and compared with the classical rule F_bt / (b "
                    "c_gamma). 0: none.");
  prm.declare_entry("positions per mesh cycle", "40", Patterns::Integer(4, 1000),
                    "Pinion positions over one mesh cycle of every variant.");
  prm.declare_entry("zone widening", "2", Patterns::Double(1, 10),
                    "How much wider across the contact line than the unmodified pair's own the "
                    "fixed contact zone of each position is (cells of the same size): a variant's "
                    "contact must stay inside it (checked: results/study/<pair>/zone_edge).");
  prm.declare_entry("harmonics", "4", Patterns::Integer(1, 50),
                    "Mesh orders of the loaded TE reported per variant and torque.");
  for (const std::string &field : misalignment_field_names())
    prm.declare_entry(entry_name(field), "", Patterns::List(Patterns::Double(), 0, 1000),
                      std::string("[") + misalignment_unit(field).second +
                          "] Misalignments: values of the " + entry_name(field) +
                          " (as the TCA section's entry of this name, which each replaces) the "
                          "check runs over; the grid is every combination of the axes given.");
  prm.declare_entry("pattern profile bins", "16", Patterns::Integer(1, 1000),
                    "Misalignments: bins of the contact pattern's raster along the gear "
                    "flank's profile.");
  prm.declare_entry("pattern face bins", "40", Patterns::Integer(1, 1000),
                    "Misalignments: bins of the contact pattern's raster along the face.");
  prm.declare_entry("members", "both", Patterns::Selection("both|pinion|gear"),
                    "Which members' working flanks the grid's modifications are applied to "
                    "(the others keep the Flanks section's).");
  for (const std::string &field : modification_field_names())
    {
      const bool length = is_length(field), slope = is_slope(field);
      prm.declare_entry(entry_name(field), "",
                        Patterns::List(slope ? Patterns::Double() : Patterns::Double(0), 0, 1000),
                        std::string(length ? "[mm]" : "[um]") + " Values of the " +
                            entry_name(field) +
                            " the map runs over (one axis of the grid; empty: the Flanks "
                            "section's value). The grid is every combination of the axes given.");
    }
}

void
StudyScene::parse(ParameterHandler &prm)
{
  const std::string k   = prm.get("kind");
  kind                  = k == "tolerances"      ? Kind::tolerances
                          : k == "misalignments" ? Kind::misalignments
                                                 : Kind::microgeometry_map;
  sampling.pinion_class = prm.get_integer("pinion class");
  sampling.gear_class   = prm.get_integer("gear class");
  sampling.distribution = prm.get("distribution") == "uniform" ? ToleranceDistribution::uniform
                                                               : ToleranceDistribution::normal;
  sampling.seed         = std::uint64_t(prm.get_integer("seed"));
  sampling.assembly     = prm.get_bool("assembly deviations");
  samples               = prm.get_integer("samples");
  mesh_cycles           = prm.get_integer("mesh cycles");
  torques               = get_doubles(prm, "torques");
  design_torque         = prm.get_double("design torque");
  positions             = prm.get_integer("positions per mesh cycle");
  widening              = prm.get_double("zone widening");
  harmonics             = prm.get_integer("harmonics");
  const std::string m   = prm.get("members");
  members               = m == "both"     ? GridMembers::both
                          : m == "pinion" ? GridMembers::pinion
                                          : GridMembers::gear;
  axes.clear();
  for (const std::string &field : modification_field_names())
    {
      const std::vector<double> values =
          get_doubles(prm, entry_name(field), is_length(field) ? mm : um);
      if (!values.empty())
        axes.push_back({field, values});
    }
  misalignment_axes.clear();
  for (const std::string &field : misalignment_field_names())
    {
      const std::vector<double> values =
          get_doubles(prm, entry_name(field), misalignment_unit(field).first);
      if (!values.empty())
        misalignment_axes.push_back({field, values});
    }
  profile_bins = prm.get_integer("pattern profile bins");
  face_bins    = prm.get_integer("pattern face bins");
}

std::vector<double>
StudyScene::study_torques(const LoadedScene &loaded) const
{
  std::vector<double> t = torques.empty() ? loaded.torques : torques;
  if (design_torque > 0)
    t.push_back(design_torque);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

void
StudyScene::check(const PairScene &pair, const LoadedScene &loaded, bool run,
                  std::vector<std::string> &warnings) const
{
  if (!run)
    return;
  const std::string where = "Study/" + pair.name + "/";
  if (kind == Kind::misalignments)
    {
      check_misalignments(pair, loaded, warnings);
      return;
    }
  if (!misalignment_axes.empty())
    throw InputError(where + misalignment_axes[0].name +
                     ": misalignment values belong to kind = misalignments (the kind is " +
                     (kind == Kind::tolerances ? "tolerances)" : "microgeometry map)"));
  if (pair.type != PairType::involute)
    throw InputError(where + ": the micro-geometry map needs an involute (spur or helical) pair; " +
                     pair.name + " is a spiral bevel pair");
  const std::vector<double> t = study_torques(loaded);
  for (const double T : t)
    {
      if (!(T > 0))
        throw InputError(where + "torques: " + std::to_string(T) +
                         " N m; the map's torques must be > 0");
      check_torque(where + "torques", T, pair, warnings);
    }
  if (harmonics > positions / 2)
    throw InputError(where + "harmonics = " + std::to_string(harmonics) +
                     " exceeds half the positions per mesh cycle (" + std::to_string(positions) +
                     "): orders above the Nyquist limit are not resolved");
  const ModificationGrid grid(PairVariant{}, members, axes); // the grid's size and names
  if (kind == Kind::tolerances && grid.size() > 1)
    throw InputError(where +
                     "kind = tolerances samples one design: give the modifications single "
                     "values (a list of " +
                     std::to_string(grid.size()) + " combinations was given)");
  const std::size_t cycles =
      kind == Kind::tolerances ? std::size_t(mesh_cycles > 0 ? mesh_cycles : pair.pinion.teeth) : 1;
  const std::size_t variants = (kind == Kind::tolerances ? std::size_t(samples) : grid.size()) *
                               t.size() * std::size_t(positions) * cycles;
  if (variants > 2000000)
    warnings.push_back(where + ": " + std::to_string(variants) +
                       " contact solves (variants or samples x torques x positions x cycles; "
                       "about 2 ms each per core)");
}
} // namespace gearkit

namespace gearkit
{
void
StudyScene::check_misalignments(const PairScene &pair, const LoadedScene &loaded,
                                std::vector<std::string> &warnings) const
{
  const std::string where = "Study/" + pair.name + "/";
  if (!axes.empty())
    throw InputError(where + entry_name(axes[0].name) +
                     ": modification values belong to a micro-geometry map or a tolerance "
                     "study; kind = misalignments checks the Flanks section's design");
  const ParameterGrid grid(misalignment_axes, misalignment_field_names(), where + "misalignments",
                           10000);
  // A misalignment as large as the face width moves the contact off the teeth: a unit slip
  // (offsets and centre distance errors are in um, axial shifts in mm, angles in mrad).
  const double b = pair.type == PairType::involute
                       ? std::min(pair.pinion.face_width, pair.gear.face_width)
                       : pair.bevel.face_width;
  for (const GridAxis &a : misalignment_axes)
    for (const double v : a.values)
      {
        const bool   angle = a.name.find("angle") != std::string::npos;
        const double limit = angle ? 50 * mrad : b;
        if (std::abs(v) > limit)
          throw InputError(where + entry_name(a.name) + " = " +
                           plausible_number(v / misalignment_unit(a.name).first) + " " +
                           misalignment_unit(a.name).second + ": beyond " +
                           (angle ? "50 mrad" : "the face width") +
                           "; likely a unit slip (offsets and centre distance errors are in "
                           "um, axial shifts in mm, angles in mrad)");
      }
  const std::vector<double> t = study_torques(loaded);
  if (t.empty())
    throw InputError(where + "torques: none given (here or in the Loaded contact section)");
  for (const double T : t)
    {
      if (!(T > 0))
        throw InputError(where + "torques: " + std::to_string(T) +
                         " N m; the check's torques must be > 0");
      check_torque(where + "torques", T, pair, warnings);
    }
  const std::size_t solves = grid.size() * t.size() * std::size_t(positions);
  if (solves > 20000)
    warnings.push_back(where + ": " + std::to_string(solves) +
                       " loaded contact solves (grid points x torques x positions; each with "
                       "its own zone: about 50 ms per core)");
}
} // namespace gearkit

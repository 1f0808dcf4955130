// Section Study/<pair>: a micro-geometry map of the pair on its compliance (stage "study").
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
} // namespace

void
StudyScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("kind", "microgeometry map",
                    Patterns::Selection("microgeometry map|tolerances"),
                    "microgeometry map: every combination of the modification values below at "
                    "every torque. tolerances: samples of the design (the Flanks section's "
                    "modifications with single values below) whose teeth, pitches and runout "
                    "are drawn within ISO 1328-1:2013 flank tolerance classes: percentiles of "
                    "the loaded TE peak-to-peak, K_m and pressure, and which deviation drives "
                    "them.");
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
  kind = prm.get("kind") == "tolerances" ? Kind::tolerances : Kind::microgeometry_map;
  sampling.pinion_class = prm.get_integer("pinion class");
  sampling.gear_class   = prm.get_integer("gear class");
  sampling.distribution = prm.get("distribution") == "uniform" ? ToleranceDistribution::uniform
                                                               : ToleranceDistribution::normal;
  sampling.seed         = std::uint64_t(prm.get_integer("seed"));
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

// Section TCA/<pair>: the unloaded tooth contact analysis - working flanks, positions, the
// assembly (centre distance, misalignments), the measured flanks' method.
#include "driver/scene.h"
#include "driver/scene_parameters.h"
#include "geometry/involute_gear.h"

#include <cmath>
#include <numeric>

namespace gearkit
{
void
TcaScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("working flanks", "drive", Patterns::Selection("drive|coast"),
                    "Which flanks carry the contact: drive (the pinion drives forward) or coast.");
  prm.declare_entry("positions per mesh cycle", "50", Patterns::Integer(1, 100000),
                    "Pinion positions per mesh cycle (2 pi / z1).");
  prm.declare_entry("mesh cycles", "3", Patterns::Integer(1, 100000), "Mesh cycles analysed.");
  prm.declare_entry("hunting cycle", "false", Patterns::Bool(),
                    "Analyse the hunting-tooth cycle, lcm(z1, z2) mesh cycles (replaces mesh "
                    "cycles), and report the spectrum in pinion shaft orders.");
  prm.declare_entry("start angle", "0", Patterns::Double(-360, 360),
                    "[deg] First pinion angle (0: pinion tooth 0 on the line of centres).");
  prm.declare_entry("centre distance", "0", Patterns::Double(0),
                    "[mm] Centre distance; 0 = the zero-backlash working centre distance.");
  prm.declare_entry("centre distance error", "0", Patterns::Double(),
                    "[um] Added to the centre distance.");
  prm.declare_entry("crossing angle", "0", Patterns::Double(-100, 100),
                    "[mrad] Gear axis turned about the line of centres (crossing axes, "
                    "f_Sigma_beta).");
  prm.declare_entry("intersecting angle", "0", Patterns::Double(-100, 100),
                    "[mrad] Gear axis turned in the plane of the axes (intersecting axes, "
                    "f_Sigma_delta).");
  prm.declare_entry("offset", "0", Patterns::Double(),
                    "[um] Gear axis moved along the common perpendicular of the axes (the "
                    "hypoid offset Delta E of a bevel pair).");
  prm.declare_entry("pinion axial shift", "0", Patterns::Double(),
                    "[mm] Pinion moved along its axis.");
  prm.declare_entry("gear axial shift", "0", Patterns::Double(), "[mm] Gear moved along its axis.");
  prm.declare_entry("harmonics", "10", Patterns::Integer(1, 1000),
                    "Mesh orders of the transmission error reported.");
  prm.declare_entry("elastic approach", "6.32", Patterns::Double(0.001),
                    "[um] Elastic approach of the contact ellipses (Litvin's usual 6.32 um).");
  prm.declare_entry(
      "measured flanks", "false", Patterns::Bool(),
      "Also analyse the pair's measured flanks (Measured flanks section): the fast "
      "discrete-point STE on flanks interpolated from the measured points; results in "
      "/ste/<pair>/measured. Teeth that were not measured take the measured flank of "
      "the nearest measured tooth.");
  prm.declare_entry("discrete-point method", "fast", Patterns::Selection("fast|paper"),
                    "Method for the measured flanks: fast (exact contact search on the "
                    "interpolated measured flanks) or paper (the seed's literal method: point "
                    "clouds at the paper spacing, the driven member stepped until the clouds are "
                    "within E = sqrt((a/2)^2 + (b/2)^2 + (r theta)^2); slow, error ~E, see "
                    "bench/README.md).");
  prm.declare_entry("paper spacing", "100", Patterns::Double(0.1),
                    "[um] Paper mode: point spacing a = b of the clouds.");
  prm.declare_entry("paper rotation step", "1", Patterns::Double(1e-3),
                    "[urad] Paper mode: driven-member rotation step theta.");
  prm.declare_entry("paper tolerance", "0", Patterns::Double(0),
                    "[um] Paper mode: contact tolerance E; 0 = the smallest admissible, "
                    "sqrt((a/2)^2 + (b/2)^2 + (r theta)^2); a smaller value is refused.");
}

void
TcaScene::parse(ParameterHandler &prm)
{
  options.side = prm.get("working flanks") == "drive" ? FlankSide::drive : FlankSide::coast;
  options.positions_per_mesh         = prm.get_integer("positions per mesh cycle");
  options.mesh_cycles                = prm.get_integer("mesh cycles");
  options.start_angle                = prm.get_double("start angle") * deg;
  centre_distance                    = prm.get_double("centre distance") * mm;
  misalignment.centre_distance_error = prm.get_double("centre distance error") * um;
  misalignment.crossing_angle        = prm.get_double("crossing angle") * mrad;
  misalignment.intersecting_angle    = prm.get_double("intersecting angle") * mrad;
  misalignment.pinion_axial_shift    = prm.get_double("pinion axial shift") * mm;
  misalignment.gear_axial_shift      = prm.get_double("gear axial shift") * mm;
  misalignment.offset                = prm.get_double("offset") * um;
  harmonics                          = prm.get_integer("harmonics");
  elastic_approach                   = prm.get_double("elastic approach") * um;
  measured                           = prm.get_bool("measured flanks");
  hunting                            = prm.get_bool("hunting cycle");
  paper_mode                         = prm.get("discrete-point method") == "paper";
  paper.spacing                      = prm.get_double("paper spacing") * um;
  paper.rotation_step                = prm.get_double("paper rotation step") * urad;
  paper.tolerance                    = prm.get_double("paper tolerance") * um;
}

namespace
{
// A pair whose total contact ratio eps_gamma = eps_alpha + eps_beta is below 1 has no tooth pair
// in conjugate contact over 1 - eps_gamma of every mesh cycle. Warned, not refused: the
// unloaded TCA computes what rigid teeth do there - the outgoing pair touches at a tip edge
// (the tip corner on the mate's flank beyond the path of contact: edge contact), and e_0 rises
// steeply until the next pair takes over, a spike every mesh cycle; under load the teeth part
// there and strike the next pair. A helical pair with eps_alpha < 1 whose overlap ratio makes
// eps_gamma >= 1 meshes without a gap (ISO 6336 rates such designs) and is not warned.
void
warn_contact_gap(const std::string &pair, double eps_alpha, double eps_beta,
                 const std::string &where, std::vector<std::string> &warnings)
{
  const double eps_gamma = eps_alpha + eps_beta;
  if (eps_gamma >= 1)
    return;
  warnings.push_back(
      "Flanks/" + pair + ": the total contact ratio eps_gamma = " + plausible_number(eps_gamma) +
      " (eps_alpha " + plausible_number(eps_alpha) + where + ", eps_beta " +
      plausible_number(eps_beta) + ") is unusual: below 1, no tooth pair meets on its flanks " +
      "over " + plausible_number(std::round(1000 * (1 - eps_gamma)) / 10) +
      " % of every mesh cycle; there the unloaded TCA finds the teeth touching at a tip edge "
      "(ste edge_contact) and e_0 rises steeply until the next pair takes over, a spike each "
      "mesh cycle (under load the teeth part and strike the next pair); real designs have "
      "eps_gamma of at least 1.1 (more addendum, less centre distance, or a helix); the run goes "
      "on with the pair as given");
}
} // namespace

void
TcaScene::complete_and_check(const PairScene &pair, const MeasuredScene &measured_flanks,
                             std::vector<std::string> &warnings)
{
  const std::string where = "TCA/" + pair.name + "/";
  if (hunting)
    {
      // lcm(z1, z2) mesh cycles, in 64 bits (tooth counts up to 100 000 overflow an int)
      const long long cycles = std::lcm<long long>(pair_teeth(pair).first, pair_teeth(pair).second);
      if (cycles > 100000)
        throw InputError(where + "hunting cycle: the hunting cycle of " +
                         std::to_string(pair_teeth(pair).first) + "/" +
                         std::to_string(pair_teeth(pair).second) + " teeth is " +
                         std::to_string(cycles) +
                         " mesh cycles; allowed: at most 100000 (set mesh cycles instead)");
      options.mesh_cycles = int(cycles);
    }
  if (double(options.mesh_cycles) * options.positions_per_mesh > 1e7)
    throw InputError(where + "positions per mesh cycle x mesh cycles = " +
                     std::to_string(double(options.mesh_cycles) * options.positions_per_mesh) +
                     " positions is not allowed; at most 10 million");
  paper.side               = options.side;
  paper.positions_per_mesh = options.positions_per_mesh;
  paper.mesh_cycles        = options.mesh_cycles;
  paper.start_angle        = options.start_angle;

  if (measured && measured_flanks.source == MeasuredSource::none)
    throw InputError(where + "measured flanks = true needs measured flanks: set Measured flanks/" +
                     pair.name + "/source");
  if (pair.type == PairType::spiral_bevel)
    {
      if (centre_distance != 0)
        throw InputError(where + "centre distance: a spiral bevel pair has intersecting axes; "
                                 "leave it 0 and move the members with offset and the axial "
                                 "shifts");
      const VirtualCylindricalGears v = virtual_cylindrical_gears(pair.bevel);
      warn_contact_gap(pair.name, v.transverse_contact_ratio, v.overlap_ratio,
                       " of the virtual cylindrical gears, ISO 10300", warnings);
      return;
    }
  // Parallel axes: the teeth must neither overlap (below the zero-backlash working centre
  // distance the flanks would interpenetrate: no rigid contact exists) nor miss each other
  // (the path of contact between the tip circles must not be empty).
  const auto [pinion, gear] = pair.involute_members();
  const double a_w          = working_centre_distance(*pinion, *gear);
  const double a =
      (centre_distance > 0 ? centre_distance : a_w) + misalignment.centre_distance_error;
  const auto mm_text = [](double x) { return std::to_string(x / mm) + " mm"; };
  if (a < a_w * (1 - 1e-12))
    throw InputError(where + "centre distance: " + mm_text(a) +
                     " (with the centre distance error) is not allowed; the teeth would overlap "
                     "below the zero-backlash working centre distance " +
                     mm_text(a_w) + " (allowed: at least that)");
  // a >= a_w > r_b1 + r_b2 here, so the contact ratio exists; <= 0: an empty path of contact
  const ContactRatios eps = contact_ratios(*pinion, *gear, a);
  if (eps.transverse <= 0)
    throw InputError(where + "centre distance: " + mm_text(a) +
                     " is not allowed; the teeth do not reach each other there (the path of "
                     "contact would be empty)");
  warn_contact_gap(pair.name, eps.active_transverse, eps.overlap,
                   " over the active profiles at the centre distance of " +
                       plausible_number(a / mm) + " mm (TCA/" + pair.name + ")",
                   warnings);
}
} // namespace gearkit

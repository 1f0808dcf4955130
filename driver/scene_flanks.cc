// Section Flanks/<pair>: the pair's type, its involute members (Pinion, Gear: data,
// modifications per flank side, deviations) or its spiral bevel design, declared, read and
// checked side by side.
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <cmath>
#include <sstream>

namespace gearkit
{
namespace
{
void
declare_modifications(ParameterHandler &prm)
{
  prm.declare_entry("tip relief", "0", Patterns::Double(0), "[um] C_a, removal at the tip.");
  prm.declare_entry("tip relief length", "0", Patterns::Double(0),
                    "[mm] Roll length (transverse, along the line of action) from the tip over "
                    "which the tip relief acts.");
  prm.declare_entry("tip relief shape", "linear", Patterns::Selection("linear|parabolic"),
                    "Shape of the tip relief.");
  prm.declare_entry("root relief", "0", Patterns::Double(0),
                    "[um] C_f, removal at the start of the involute (form circle).");
  prm.declare_entry("root relief length", "0", Patterns::Double(0),
                    "[mm] Roll length from the form circle over which the root relief acts.");
  prm.declare_entry("root relief shape", "linear", Patterns::Selection("linear|parabolic"),
                    "Shape of the root relief.");
  prm.declare_entry("lead crowning", "0", Patterns::Double(0),
                    "[um] C_beta, parabolic removal at each face end relative to the middle.");
  prm.declare_entry("end relief", "0", Patterns::Double(0),
                    "[um] C_I, linear removal at each face end.");
  prm.declare_entry("end relief length", "0", Patterns::Double(0),
                    "[mm] Axial length from each face end over which the end relief acts.");
  prm.declare_entry("profile crowning", "0", Patterns::Double(0),
                    "[um] C_alpha, parabolic removal at both ends of the active profile (from "
                    "the start of active profile in mesh with the mate at the TCA's centre "
                    "distance to the tip), none in its middle.");
  prm.declare_entry("profile slope deviation", "0", Patterns::Double(),
                    "[um] f_Halpha over the ISO 1328-1 profile evaluation range (from the start "
                    "of active profile in mesh with the mate, 92 % of the active length toward "
                    "the tip); positive adds material at the tip.");
  prm.declare_entry("helix slope deviation", "0", Patterns::Double(),
                    "[um] f_Hbeta over the ISO 1328-1 helix evaluation range (the face width "
                    "less min(5 % b, m_n) at each end); positive adds material at the +z end.");
  prm.declare_entry("waviness amplitude", "0", Patterns::Double(0),
                    "[um] Amplitude of a sinusoidal profile waviness.");
  prm.declare_entry("waviness wavelength", "0", Patterns::Double(0),
                    "[mm] Wavelength of the profile waviness along the roll length; 0 = none.");
  prm.declare_entry("waviness phase", "0", Patterns::Double(-360, 360),
                    "[deg] Phase of the waviness at the form circle.");
}

ToothModifications
get_modifications(ParameterHandler &prm)
{
  auto shape = [&](const char *name) {
    return prm.get(name) == "linear" ? ReliefShape::linear : ReliefShape::parabolic;
  };
  ToothModifications m;
  m.tip_relief          = prm.get_double("tip relief") * um;
  m.tip_relief_length   = prm.get_double("tip relief length") * mm;
  m.tip_relief_shape    = shape("tip relief shape");
  m.root_relief         = prm.get_double("root relief") * um;
  m.root_relief_length  = prm.get_double("root relief length") * mm;
  m.root_relief_shape   = shape("root relief shape");
  m.lead_crowning       = prm.get_double("lead crowning") * um;
  m.end_relief          = prm.get_double("end relief") * um;
  m.end_relief_length   = prm.get_double("end relief length") * mm;
  m.profile_crowning    = prm.get_double("profile crowning") * um;
  m.profile_slope       = prm.get_double("profile slope deviation") * um;
  m.helix_slope         = prm.get_double("helix slope deviation") * um;
  m.waviness_amplitude  = prm.get_double("waviness amplitude") * um;
  m.waviness_wavelength = prm.get_double("waviness wavelength") * mm;
  m.waviness_phase      = prm.get_double("waviness phase") * deg;
  return m;
}

void
declare_member(ParameterHandler &prm, const std::string &defaults_teeth)
{
  prm.declare_entry("number of teeth", defaults_teeth, Patterns::Integer(3, 100000),
                    "Number of teeth z.");
  prm.declare_entry("normal module", "3", Patterns::Double(0.01, 100), "[mm] Normal module m_n.");
  prm.declare_entry("normal pressure angle", "20", Patterns::Double(0, 45),
                    "[deg] Normal pressure angle alpha_n of the basic rack.");
  prm.declare_entry("helix angle", "0", Patterns::Double(0, 60),
                    "[deg] Helix angle beta at the reference circle (0 = spur).");
  prm.declare_entry("hand", "right", Patterns::Selection("right|left"),
                    "Hand of the helix (a pair of external helical gears has opposite hands).");
  prm.declare_entry("profile shift coefficient", "0", Patterns::Double(-3, 3),
                    "Profile shift coefficient x.");
  prm.declare_entry("face width", "20", Patterns::Double(0, 10000), "[mm] Face width b.");
  prm.declare_entry("addendum factor", "1", Patterns::Double(0, 3),
                    "h_aP*: tip radius r_a = r + (h_aP* + x) m_n.");
  prm.declare_entry("dedendum factor", "1.25", Patterns::Double(0, 3),
                    "h_fP*: root radius r_f = r - (h_fP* - x) m_n.");
  prm.declare_entry("root radius factor", "0.38", Patterns::Double(0, 1),
                    "rho_fP*: tip radius of the generating rack cutter / m_n; it forms the "
                    "trochoidal root fillet.");
  prm.declare_entry("bore diameter", "0", Patterns::Double(0, 100000),
                    "[mm] Bore diameter (0 = solid).");
  prm.declare_entry("density", "7850", Patterns::Double(0, 100000),
                    "[kg/m^3] Density of the gear body.");
  for (const char *side : {"Drive flank modifications", "Coast flank modifications"})
    {
      prm.enter_subsection(side);
      declare_modifications(prm);
      prm.leave_subsection();
    }
  prm.enter_subsection("Deviations");
  prm.declare_entry("single pitch deviations", "", Patterns::List(Patterns::Double(), 0, 100000),
                    "[um] f_p per tooth (entry k: pitch from tooth k-1 to tooth k along the "
                    "reference circle); empty, or one per tooth adding up to zero.");
  prm.declare_entry("runout", "0", Patterns::Double(0),
                    "[um] Eccentricity of the toothing relative to the axis of rotation.");
  prm.declare_entry("runout phase", "0", Patterns::Double(-360, 360),
                    "[deg] Direction of the runout eccentricity in the member frame.");
  prm.declare_entry("eccentric tooth", "-1", Patterns::Integer(-1),
                    "Index of a tooth whose flank is moved along its normal (-1 = none).");
  prm.declare_entry("eccentric tooth flank", "drive", Patterns::Selection("drive|coast"),
                    "Which flank of the eccentric tooth moves.");
  prm.declare_entry("eccentric tooth offset", "0", Patterns::Double(),
                    "[um] Normal offset of the eccentric tooth flank (positive adds material).");
  prm.declare_entry("chipped tooth", "-1", Patterns::Integer(-1),
                    "Index of a chipped tooth (-1 = none).");
  prm.declare_entry("chip diameter", "0", Patterns::Double(0),
                    "[mm] Material above this diameter is gone from the chipped tooth (the root "
                    "diameter removes the whole tooth).");
  prm.declare_entry("chip face fraction", "1", Patterns::Double(0, 1),
                    "Axial extent of the chip from the -z face end, as a fraction of b.");
  prm.leave_subsection();
}

InvoluteGearData
get_member(ParameterHandler &prm, const std::string &name)
{
  InvoluteGearData d;
  d.name                  = name;
  d.teeth                 = prm.get_integer("number of teeth");
  d.normal_module         = prm.get_double("normal module") * mm;
  d.normal_pressure_angle = prm.get_double("normal pressure angle") * deg;
  d.helix_angle           = prm.get_double("helix angle") * deg;
  d.hand                  = prm.get("hand") == "right" ? Hand::right : Hand::left;
  d.profile_shift         = prm.get_double("profile shift coefficient");
  d.face_width            = prm.get_double("face width") * mm;
  d.addendum_factor       = prm.get_double("addendum factor");
  d.dedendum_factor       = prm.get_double("dedendum factor");
  d.root_radius_factor    = prm.get_double("root radius factor");
  d.bore_diameter         = prm.get_double("bore diameter") * mm;
  d.density               = prm.get_double("density");
  prm.enter_subsection("Drive flank modifications");
  d.drive_modifications = get_modifications(prm);
  prm.leave_subsection();
  prm.enter_subsection("Coast flank modifications");
  d.coast_modifications = get_modifications(prm);
  prm.leave_subsection();
  prm.enter_subsection("Deviations");
  d.single_pitch_deviations = get_doubles(prm, "single pitch deviations", um);
  d.runout                  = {prm.get_double("runout") * um, prm.get_double("runout phase") * deg};
  if (const int k = prm.get_integer("eccentric tooth"); k >= 0)
    d.eccentric_teeth.push_back(
        {k, prm.get("eccentric tooth flank") == "drive" ? FlankSide::drive : FlankSide::coast,
         prm.get_double("eccentric tooth offset") * um});
  if (const int k = prm.get_integer("chipped tooth"); k >= 0)
    d.chipped_teeth.push_back(
        {k, prm.get_double("chip diameter") * mm / 2, prm.get_double("chip face fraction")});
  prm.leave_subsection();
  return d;
}

void
declare_bevel(ParameterHandler &prm)
{
  prm.declare_entry("pinion teeth", "12", Patterns::Integer(3, 10000), "Pinion teeth z1.");
  prm.declare_entry("gear teeth", "36", Patterns::Integer(3, 10000), "Gear teeth z2.");
  prm.declare_entry("shaft angle", "90", Patterns::Double(1, 179), "[deg] Shaft angle Sigma.");
  prm.declare_entry("module", "6", Patterns::Double(0.01, 100), "[mm] Module (see module type).");
  prm.declare_entry("module type", "outer transverse",
                    Patterns::Selection("outer transverse|mean normal"),
                    "outer transverse: m_et at the heel; mean normal: m_mn at the mean point.");
  prm.declare_entry("face width", "25.4", Patterns::Double(0, 10000), "[mm] Face width F.");
  prm.declare_entry("mean spiral angle", "35", Patterns::Double(0, 60),
                    "[deg] Mean spiral angle beta_m.");
  prm.declare_entry("pressure angle", "20", Patterns::Double(0, 45),
                    "[deg] Normal pressure angle of both sides (blade angle).");
  prm.declare_entry("pinion hand", "left", Patterns::Selection("right|left"),
                    "Hand of spiral of the pinion; the gear has the other.");
  prm.declare_entry("cutter radius", "76.2", Patterns::Double(0, 10000),
                    "[mm] Mean radius r_c of the head cutter (usually 0.3 to 3 mean cone "
                    "distances). Its tooth traces must reach the toe and the heel at the top of "
                    "the tooth (with the pinion cutter radius change): a smaller radius is "
                    "refused with the least that does (about 0.24 A_m at 35 deg spiral).");
  prm.declare_entry("pinion addendum factor", "1", Patterns::Double(0, 2),
                    "Pinion addendum / m_mn (uniform depth: working depth 2 m_mn).");
  prm.declare_entry("clearance factor", "0.25", Patterns::Double(0, 1), "Clearance / m_mn.");
  prm.declare_entry("pinion thickness factor", "0.5", Patterns::Double(0, 1),
                    "Pinion tooth thickness / normal pitch at the mean point.");
  prm.declare_entry("blade edge radius factor", "0.2", Patterns::Double(0, 1),
                    "Edge radius of the blade tips / m_mn: the rounding cuts the root fillet and "
                    "ends the working flank.");
  prm.declare_entry("pinion cutter radius change", "0", Patterns::Double(),
                    "[mm] Mismatch: pinion blade radii against the gear's, the blades kept "
                    "through the mean point (localises the bearing along the face).");
  prm.declare_entry("pinion blade curvature", "0", Patterns::Double(),
                    "[1/m] Mismatch: parabolic blade curvature of the pinion blades (profile "
                    "crowning).");
  prm.declare_entry("pinion modified roll 2C", "0", Patterns::Double(),
                    "Modified roll 2C of the pinion, expanded about the cradle roll that "
                    "generates each flank's mean point (used when transmission error amplitude "
                    "is 0).");
  prm.declare_entry("pinion modified roll 6D", "0", Patterns::Double(),
                    "Modified roll 6D of the pinion.");
  prm.declare_entry("transmission error amplitude", "0", Patterns::Double(0),
                    "[urad] Predesigned parabolic transmission error (peak-to-peak over a mesh "
                    "cycle) the pinion's modified roll 2C is synthesised for; 0 = none.");
}

void
parse_bevel(ParameterHandler &prm, PairScene &pair)
{
  BevelPairDesign &d            = pair.bevel;
  d.pinion_teeth                = prm.get_integer("pinion teeth");
  d.gear_teeth                  = prm.get_integer("gear teeth");
  d.shaft_angle                 = prm.get_double("shaft angle") * deg;
  d.module                      = prm.get_double("module") * mm;
  d.module_kind                 = prm.get("module type") == "mean normal" ? BevelModule::mean_normal
                                                                          : BevelModule::outer_transverse;
  d.face_width                  = prm.get_double("face width") * mm;
  d.mean_spiral_angle           = prm.get_double("mean spiral angle") * deg;
  d.pressure_angle              = prm.get_double("pressure angle") * deg;
  d.pinion_hand                 = prm.get("pinion hand") == "right" ? Hand::right : Hand::left;
  d.cutter_radius               = prm.get_double("cutter radius") * mm;
  d.pinion_addendum             = prm.get_double("pinion addendum factor");
  d.clearance                   = prm.get_double("clearance factor");
  d.pinion_thickness            = prm.get_double("pinion thickness factor");
  d.edge_radius                 = prm.get_double("blade edge radius factor");
  pair.mismatch.cutter_radius   = prm.get_double("pinion cutter radius change") * mm;
  pair.mismatch.blade_curvature = prm.get_double("pinion blade curvature");
  pair.mismatch.modified_roll_2c    = prm.get_double("pinion modified roll 2C");
  pair.mismatch.modified_roll_6d    = prm.get_double("pinion modified roll 6D");
  pair.transmission_error_amplitude = prm.get_double("transmission error amplitude") * 1e-6;
}

} // namespace

void
PairScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("grid profile points", "9", Patterns::Integer(2, 10000),
                    "Profile points per flank in the stored flank grids (/flanks).");
  prm.declare_entry("grid face points", "29", Patterns::Integer(2, 10000),
                    "Face points per flank in the stored flank grids (/flanks).");
  prm.declare_entry("type", "involute", Patterns::Selection("involute|spiral bevel"),
                    "involute: spur or helical pair (subsections Pinion, Gear); spiral "
                    "bevel: face-milled spiral bevel pair (subsection Spiral bevel).");
  in_subsection(prm, {"Pinion"}, [&] { declare_member(prm, "20"); });
  in_subsection(prm, {"Gear"}, [&] { declare_member(prm, "40"); });
  in_subsection(prm, {"Spiral bevel"}, [&] { declare_bevel(prm); });
}

void
PairScene::parse(ParameterHandler &prm)
{
  grid_profile_points = prm.get_integer("grid profile points");
  grid_face_points    = prm.get_integer("grid face points");
  type = prm.get("type") == "spiral bevel" ? PairType::spiral_bevel : PairType::involute;
  in_subsection(prm, {"Pinion"}, [&] { pinion = get_member(prm, "Flanks/" + name + "/Pinion"); });
  in_subsection(prm, {"Gear"}, [&] { gear = get_member(prm, "Flanks/" + name + "/Gear"); });
  in_subsection(prm, {"Spiral bevel"}, [&] { parse_bevel(prm, *this); });
}

std::string
plausible_number(double x)
{
  // whole numbers as they are typed (7850, 20000; also after a unit conversion's rounding),
  // others to 4 digits (0.349, 3e+08)
  std::ostringstream s;
  if (std::abs(x - std::round(x)) <= 1e-12 * std::abs(x) && std::abs(x) < 1e6)
    s << static_cast<long long>(x);
  else
    {
      s.precision(4);
      s << x;
    }
  return s.str();
}

void
check_plausible(const std::string &parameter, double measure, const std::string &measure_text,
                double plausible_low, double plausible_high, double possible_low,
                double possible_high, const std::vector<UnitSlip> &slips,
                std::vector<std::string> &warnings)
{
  if (measure >= plausible_low && measure <= plausible_high)
    return;
  const bool  refused = !(measure >= possible_low && measure <= possible_high);
  std::string text = parameter + (refused ? " is not allowed: " : " is unusual: ") + measure_text +
                     " is " + plausible_number(measure) + ", where real designs have " +
                     plausible_number(plausible_low) + " to " + plausible_number(plausible_high);
  if (refused)
    text += measure < possible_low ? " (none below " + plausible_number(possible_low) + ")"
                                   : " (none above " + plausible_number(possible_high) + ")";
  const UnitSlip *slip = nullptr;
  for (const UnitSlip &u : slips)
    if (!slip && measure * u.factor >= plausible_low && measure * u.factor <= plausible_high)
      slip = &u;
  if (slip)
    text += "; it looks like " + slip->what;
  if (refused)
    throw InputError(text + (slip ? "" : "; expected a value in the plausible range"));
  warnings.push_back(text + "; the run goes on with the value as given");
}

PairScale
pair_scale(const PairScene &pair)
{
  if (pair.type == PairType::spiral_bevel)
    {
      const BevelPairGeometry g = bevel_geometry(pair.bevel);
      return {g.mean_cone_distance * std::sin(g.pitch_angle_pinion), pair.bevel.face_width,
              g.mean_normal_module};
    }
  const InvoluteGearData &p = pair.pinion;
  return {p.teeth * p.normal_module / std::cos(p.helix_angle) / 2,
          std::min(p.face_width, pair.gear.face_width), p.normal_module};
}

namespace
{
// Angles entered in radians where the scene asks degrees: every angle of a gear below
// 60 deg is at most 1.05 in radians. `lowest` [deg]: below it no gear has the angle (0 excluded
// where 0 means spur or zerol).
void
check_angle_in_degrees(const std::string &parameter, double angle, double lowest,
                       const std::string &plausible, bool zero_allowed)
{
  const double d = angle / deg;
  if ((zero_allowed && d == 0) || d >= lowest)
    return;
  std::string text = parameter + " = " + plausible_number(d) +
                     " deg is not allowed: real designs have " + plausible + " (none " +
                     (zero_allowed ? "between 0 and " : "below ") + plausible_number(lowest) +
                     " deg)";
  if (d > 0 && d < 3.1416 && d / deg >= lowest)
    text += "; it looks like radians typed in a degrees field (" + plausible_number(d) +
            " rad = " + plausible_number(d / deg) + " deg)";
  throw InputError(text);
}

// The plausibility of an involute member's data: what a unit slip gives, checked by name before
// the member is built (whose own checks would blame a consequence: "no tooth pair meets").
void
check_member_plausibility(const InvoluteGearData &d, const std::string &where,
                          std::vector<std::string> &warnings)
{
  // Pressure angles below 5 deg do not exist (the tooth would be undercut to nothing; real
  // ones 14.5 to 30 deg): refused, and 0.349 named as radians. 12..35 deg covers every
  // standard and special design; 5..12 and 35..45 deg warn.
  check_angle_in_degrees(where + "/normal pressure angle", d.normal_pressure_angle, 5,
                         "12 to 35 deg", false);
  check_plausible(
      where + "/normal pressure angle = " + plausible_number(d.normal_pressure_angle / deg) +
          " deg",
      d.normal_pressure_angle / deg, "the pressure angle [deg]", 12, 35, 5, 45, {}, warnings);
  // Helix angles: 0 (spur) or from about 5 deg (helical gears exist for their overlap; below
  // 1 deg the overlap ratio is < 0.05 and nobody cuts one). Below 1.05 deg (= 60 deg in
  // radians) refused as radians; above 45 deg (double helical at most) a warning.
  check_angle_in_degrees(where + "/helix angle", d.helix_angle, 1.05, "0 (spur) or 5 to 45 deg",
                         true);
  check_plausible(where + "/helix angle = " + plausible_number(d.helix_angle / deg) + " deg",
                  d.helix_angle / deg, "the helix angle [deg]", 0, 45, 0, 60, {}, warnings);
  if (d.helix_angle > 0 && d.helix_angle < 5 * deg)
    warnings.push_back(where + "/helix angle = " + plausible_number(d.helix_angle / deg) +
                       " deg is unusual: real designs have 0 (spur) or 5 to 45 deg (a helix this "
                       "small gives hardly any overlap); the run goes on with the value as given");
  // Face width against the normal module: b / m_n from about 1 (thin clock and instrument
  // gears) to about 40 (wide pinions, rolling mill drives); the ISO 6336 rating asks b/m_n <=
  // 30 for most designs. Below 0.1 (a disc a twentieth as thick as its teeth; 0.01 mm on m 3:
  // a pinion of 0.09 g) and above 1000 no gear exists: refused; the slips are metres (x 1000)
  // and inches (x 25.4) typed in the mm field, or micrometres typed as mm.
  const double b = d.face_width / mm, ratio = d.face_width / d.normal_module;
  check_plausible(where + "/face width = " + plausible_number(b) + " mm", ratio,
                  "b/m_n on a normal module of " + plausible_number(d.normal_module / mm) + " mm",
                  1, 40, 0.1, 1000,
                  {{1000, "metres typed in a mm field (" + plausible_number(b) +
                              " m = " + plausible_number(b * 1000) + " mm)"},
                   {25.4, "inches typed in a mm field (" + plausible_number(b) +
                              " in = " + plausible_number(b * 25.4) + " mm)"},
                   {1e-3, "micrometres typed in a mm field (" + plausible_number(b) +
                              " um = " + plausible_number(b / 1000) + " mm)"}},
                  warnings);
  // A bore below a hundredth of the root diameter holds no shaft: metres typed in the mm field
  // (0.03 for 30 mm) - warned, as the gear's mass hardly changes (a solid gear is computed).
  const double root_diameter = d.teeth * d.normal_module / std::cos(d.helix_angle) -
                               2 * (d.dedendum_factor - d.profile_shift) * d.normal_module;
  if (d.bore_diameter > 0 && d.bore_diameter < 0.01 * root_diameter)
    warnings.push_back(where + "/bore diameter = " + plausible_number(d.bore_diameter / mm) +
                       " mm is unusual: a bore of " +
                       plausible_number(d.bore_diameter / root_diameter) +
                       " of the root diameter (" + plausible_number(root_diameter / mm) +
                       " mm) holds no shaft; it looks like metres typed in a mm field (" +
                       plausible_number(d.bore_diameter / mm) +
                       " m = " + plausible_number(d.bore_diameter / mm * 1000) +
                       " mm); the run goes on with the value as given");
  // Density: gear materials from polymers (POM 1410, PA 1140 kg/m^3) to tungsten alloys
  // (19300); wood gears (500..900) are real but rare: warned below 900 and above 20000;
  // below 100 (no solid) or above 23000 (osmium, the densest element, 22590) refused. The slip
  // of note is g/cm^3 (7.85 for steel's 7850).
  check_plausible(where + "/density = " + plausible_number(d.density) + " kg/m^3", d.density,
                  "the density [kg/m^3]", 900, 20000, 100, 23000,
                  {{1000, "g/cm^3 typed in a kg/m^3 field (" + plausible_number(d.density) +
                              " g/cm^3 = " + plausible_number(d.density * 1000) + " kg/m^3)"}},
                  warnings);
}
} // namespace

// A spiral bevel pair's head cutter must generate both members over the whole face: the
// cutter's tooth traces must reach the toe and the heel at the top of the tooth (cutter_reach:
// else the equation of meshing has no solution there), refused by the setting that is at
// fault with the bound that would reach; then both members are generated as the flanks stage
// cuts them (before the modified roll is synthesised), and what still fails (a blade that
// generates only the top of the tooth, an edge radius beyond the dedendum) is refused naming
// the settings.
namespace
{
void
check_generated(const PairScene &pair, const std::string &where, const BevelPairGeometry &g)
{
  const BevelPairDesign &bevel    = pair.bevel;
  const PinionMismatch  &mismatch = pair.mismatch;
  const double           Am       = g.mean_cone_distance;
  const CutterReach      reach    = cutter_reach(bevel, mismatch);
  if (!reach.generated())
    {
      const std::string why =
          " is not allowed: the head cutter does not generate the " + reach.member + "'s " +
          reach.flank + " flank at the " + (reach.heel ? "heel" : "toe") +
          ": the tooth trace of its blade (radius " + plausible_number(reach.blade_radius / mm) +
          " mm at the top of the tooth) turns back before reaching the cone distance of " +
          plausible_number(reach.cone_distance / mm) +
          " mm there (the sine of the spiral angle would be " + plausible_number(reach.sin_spiral) +
          ", and the equation of meshing has no solution)";
      const double least = least_cutter_radius(bevel, mismatch);
      std::string  radius =
          std::isfinite(least)
               ? "a cutter radius of at least " + plausible_number(least / mm) + " mm (" +
                    plausible_number(least / Am) + " of the mean cone distance " +
                    plausible_number(Am / mm) + " mm, for the mean spiral angle of " +
                    plausible_number(bevel.mean_spiral_angle / deg) + " deg, the face width of " +
                    plausible_number(bevel.face_width / mm) +
                    " mm and the pinion cutter radius change of " +
                    plausible_number(mismatch.cutter_radius / mm) + " mm)"
               : "a smaller face width or mean spiral angle (no cutter radius up to 1000 mean "
                 "cone distances reaches the whole face)";
      PinionMismatch unchanged = mismatch;
      unchanged.cutter_radius  = 0;
      if (mismatch.cutter_radius == 0 || !cutter_reach(bevel, unchanged).generated())
        throw InputError(where + "/cutter radius = " + plausible_number(bevel.cutter_radius / mm) +
                         " mm" + why + "; expected " + radius);
      // The radius alone reaches: the pinion's blade radius change takes it too far. Both
      // settings are named, each with its bound given the other: the largest part of the
      // change that still reaches.
      double lo = 0, hi = 1;
      while (hi - lo > 1e-6)
        {
          PinionMismatch t                               = mismatch;
          t.cutter_radius                                = mismatch.cutter_radius * (lo + hi) / 2;
          (cutter_reach(bevel, t).generated() ? lo : hi) = (lo + hi) / 2;
        }
      throw InputError(where + "/cutter radius = " + plausible_number(bevel.cutter_radius / mm) +
                       " mm with pinion cutter radius change = " +
                       plausible_number(mismatch.cutter_radius / mm) + " mm" + why + "; expected " +
                       radius + " with that change, or a pinion cutter radius change of at most " +
                       plausible_number(std::abs(mismatch.cutter_radius) * lo / mm) +
                       " mm either way with that radius");
    }
  try
    {
      const auto [pinion, gear] = mismatched_cuts(bevel, mismatch);
      BevelMemberFlanks{pinion};
      BevelMemberFlanks{gear};
    }
  catch (const InputError &e)
    {
      throw InputError(
          where + ": the members are not generated with the cutter radius of " +
          plausible_number(bevel.cutter_radius / mm) + " mm, the mean spiral angle of " +
          plausible_number(bevel.mean_spiral_angle / deg) + " deg, the pressure angle of " +
          plausible_number(bevel.pressure_angle / deg) + " deg, the blade edge radius factor " +
          plausible_number(bevel.edge_radius) + ", the pinion addendum factor " +
          plausible_number(bevel.pinion_addendum) + " and the pinion cutter radius change of " +
          plausible_number(mismatch.cutter_radius / mm) + " mm: " + e.what());
    }
}
} // namespace

// Both members must build (InvoluteGear checks every parameter, modifications included) and
// mesh with each other; first the values a unit slip gives, each by its name.
void
PairScene::check(std::vector<std::string> &warnings) const
{
  if (type == PairType::spiral_bevel)
    {
      const std::string where = "Flanks/" + name + "/Spiral bevel";
      check_angle_in_degrees(where + "/pressure angle", bevel.pressure_angle, 5, "12 to 35 deg",
                             false);
      check_plausible(
          where + "/pressure angle = " + plausible_number(bevel.pressure_angle / deg) + " deg",
          bevel.pressure_angle / deg, "the pressure angle [deg]", 12, 35, 5, 45, {}, warnings);
      // Spiral angles: 0 (zerol) or from about 10 deg (spiral bevel gears 25..40 deg); below
      // 1.05 deg (60 deg in radians) refused as radians.
      check_angle_in_degrees(where + "/mean spiral angle", bevel.mean_spiral_angle, 1.05,
                             "0 (zerol) or 10 to 45 deg", true);
      // Shaft angles below 3.15 deg: a near-parallel bevel pair does not exist, and pi rad is
      // 180 deg: read as radians.
      check_angle_in_degrees(where + "/shaft angle", bevel.shaft_angle, 3.15, "10 to 170 deg",
                             false);
      // Face width against the module: F / m from about 1 to 20 (the usual limit F <= 10 m_et
      // and A_0 / 3); refused below 0.1 and above 1000 as for involute members.
      const double f = bevel.face_width / mm, ratio = bevel.face_width / bevel.module;
      check_plausible(where + "/face width = " + plausible_number(f) + " mm", ratio,
                      "F/m on a module of " + plausible_number(bevel.module / mm) + " mm", 1, 20,
                      0.1, 1000,
                      {{1000, "metres typed in a mm field (" + plausible_number(f) +
                                  " m = " + plausible_number(f * 1000) + " mm)"},
                       {25.4, "inches typed in a mm field (" + plausible_number(f) +
                                  " in = " + plausible_number(f * 25.4) + " mm)"}},
                      warnings);
      BevelPairGeometry g;
      try
        {
          g = bevel_geometry(bevel);
        }
      catch (const InputError &e)
        {
          throw InputError("Flanks/" + name + "/Spiral bevel: " + e.what());
        }
      // Face-milling cutters have radii of about 0.5 to 2 mean cone distances (the blades'
      // lengthwise curvature against the spiral); below 0.03 or beyond 30 no cutter generates a
      // tooth (the flanks stage failed with "the equation of meshing has no solution"): refused;
      // metres or inches typed in the mm field are the slips.
      const double rc = bevel.cutter_radius / mm;
      check_plausible(where + "/cutter radius = " + plausible_number(rc) + " mm",
                      bevel.cutter_radius / g.mean_cone_distance,
                      "r_c over the mean cone distance (" +
                          plausible_number(g.mean_cone_distance / mm) + " mm)",
                      0.3, 3, 0.03, 30,
                      {{1000, "metres typed in a mm field (" + plausible_number(rc) +
                                  " m = " + plausible_number(rc * 1000) + " mm)"},
                       {25.4, "inches typed in a mm field (" + plausible_number(rc) +
                                  " in = " + plausible_number(rc * 25.4) + " mm)"}},
                      warnings);
      check_generated(*this, where, g);
      return;
    }
  check_member_plausibility(pinion, "Flanks/" + name + "/Pinion", warnings);
  check_member_plausibility(gear, "Flanks/" + name + "/Gear", warnings);
  involute_members();
  if (const std::string why = external_pair_mismatch(pinion, gear); !why.empty())
    throw InputError("Flanks/" + name + ": pinion and gear " + why);
}

std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
PairScene::involute_members() const
{
  return create_pair(pinion, gear);
}

std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
PairScene::involute_members(double operating_centre_distance) const
{
  return create_pair(pinion, gear, operating_centre_distance);
}

// The start of active profile is where the mate's tip circle crosses the line of action, so it
// moves with the centre distance the pair runs at (up the flank when it opens): a profile
// evaluation range taken at the zero-backlash centre distance would give f_Halpha another slope.
std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
PairScene::involute_members(const TcaScene &tca) const
{
  return involute_members(operating_centre_distance(tca));
}

double
PairScene::operating_centre_distance(const TcaScene &tca) const
{
  const double a = tca.centre_distance > 0 ? tca.centre_distance
                                           : working_centre_distance(*InvoluteGear::create(pinion),
                                                                     *InvoluteGear::create(gear));
  return gearkit::operating_centre_distance(a, tca.misalignment);
}
} // namespace gearkit

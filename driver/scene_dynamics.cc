// Section Dynamics/<pair>: the 14-DOF model's parameters (supports, shafts, backlash, damping),
// its excitation (mesh stiffness, transmission error) and the speed sweep.
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

namespace gearkit
{
namespace
{
/// The integrator's name in the scene.
const char *
integrator_name(Integrator i)
{
  return i == Integrator::newmark     ? "newmark"
         : i == Integrator::cvode_bdf ? "cvode bdf"
                                      : "cvode adams";
}
} // namespace

SweepOptions
DynamicsScene::newmark_sweep()
{
  SweepOptions o;
  o.run.method = Integrator::newmark;
  return o;
}

void
DynamicsScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("mesh stiffness source", "finite elements",
                    Patterns::Selection("finite elements|constant"),
                    "finite elements: K_m over the mesh cycle from the stiffness stage (the "
                    "torque nearest the pinion torque below); constant: the value below.");
  prm.declare_entry("mesh stiffness", "300", Patterns::Double(0),
                    "[N/um] Mean K_m when the source is constant.");
  prm.declare_entry("mesh stiffness variation", "0", Patterns::Double(0, 0.9),
                    "Fraction of the mean by which a constant-source K_m varies over the mesh "
                    "cycle (first mesh order, K_m (1 - v cos 2 pi phase)).");
  prm.declare_entry("transmission error source", "tca", Patterns::Selection("tca|analytic"),
                    "tca: E_t = lambda_pz e_0 over the mesh cycle from the unloaded TCA; "
                    "analytic: E_t = amplitude sin(2 pi phase) (the TCA still gives the normals "
                    "and moment arms).");
  prm.declare_entry("transmission error amplitude", "0", Patterns::Double(0),
                    "[um] Of the analytic E_t, as displacement along the line of action.");
  prm.declare_entry("pinion torque", "100", Patterns::Double(0),
                    "[N m] Motor torque on the pinion; the load torque balances it through the "
                    "mean moment arms.");
  prm.declare_entry("motor", "speed controlled", Patterns::Selection("speed controlled|torque"),
                    "speed controlled: the motor turns at the sweep's speed (its torque the "
                    "reaction); torque: a constant motor torque, the train free to drift (the "
                    "seed's model).");
  prm.declare_entry("motor inertia", "0.05", Patterns::Double(0), "[kg m^2] 0: no motor DOF.");
  prm.declare_entry("load inertia", "0.1", Patterns::Double(0), "[kg m^2] 0: no load DOF.");
  prm.declare_entry("motor shaft stiffness", "2e4", Patterns::Double(0), "[N m/rad] Motor-pinion.");
  prm.declare_entry("load shaft stiffness", "3e4", Patterns::Double(0), "[N m/rad] Gear-load.");
  prm.declare_entry("shaft damping", "2", Patterns::Double(0), "[N m s/rad] Both shafts.");
  for (const char *member : {"pinion", "gear"})
    {
      const std::string m = member;
      prm.declare_entry(m + " mass", "2", Patterns::Double(0), "[kg]");
      prm.declare_entry(m + " axial inertia", "4e-3", Patterns::Double(0),
                        "[kg m^2] About its axis.");
      prm.declare_entry(m + " transverse inertia", "6e-3", Patterns::Double(0),
                        "[kg m^2] About axes across it through the body point (the member "
                        "frame's origin: the cone apex of a bevel member).");
      prm.declare_entry(m + " bearing positions", "100, 160",
                        Patterns::List(Patterns::Double(), 1, 4),
                        "[mm] Radial bearings along the member's axis from its frame origin.");
    }
  prm.declare_entry("bearing stiffness", "500", Patterns::Double(0),
                    "[N/um] Radial, every bearing.");
  prm.declare_entry("axial stiffness", "300", Patterns::Double(0), "[N/um] Each member.");
  prm.declare_entry("bearing damping", "500", Patterns::Double(0), "[N s/m] Radial and axial.");
  prm.declare_entry("half backlash", "50", Patterns::Double(0), "[um] b_c.");
  prm.declare_entry("mesh damping ratio", "0.05", Patterns::Double(0, 1),
                    "zeta of c_m = 2 zeta sqrt(K_m m_e); the damping acts in contact only.");
  prm.declare_entry("speed from", "100", Patterns::Double(0.001), "[rpm] Pinion speed.");
  prm.declare_entry("speed to", "12000", Patterns::Double(0.001), "[rpm]");
  prm.declare_entry("speeds", "100", Patterns::Integer(1, 100000),
                    "Speeds of the sweep, swept up and then down.");
  prm.declare_entry("settle cycles", std::to_string(SweepOptions().settle_cycles),
                    Patterns::Integer(0),
                    "Most mesh cycles to settle at each speed (less when the motion repeats).");
  prm.declare_entry("record cycles", std::to_string(SweepOptions().record_cycles),
                    Patterns::Integer(1), "Mesh cycles recorded per speed.");
  prm.declare_entry("steady tolerance", plausible_number(SweepOptions().steady_tolerance),
                    Patterns::Double(0),
                    "Settled when the states at whole excitation periods repeat within this, "
                    "relative to the static mesh deflection, over three whole periods of the "
                    "motion (1 to 4 excitation periods; CVODE: at least 1e3 times its "
                    "tolerance); settling goes on past settle cycles (up to five times) while "
                    "the states still converge fast enough; 0: always settle cycles.");
  prm.declare_entry(
      "integrator", integrator_name(newmark_sweep().run.method),
      Patterns::Selection("newmark|cvode bdf|cvode adams"),
      "newmark: fixed steps per speed, as many as the accuracy asks (the fast path); cvode: "
      "adaptive, events at the backlash.");
  prm.declare_entry("accuracy", plausible_number(SweepOptions().accuracy), Patterns::Double(0, 0.5),
                    "Newmark: the relative RMS error of the DTE wanted; the steps per mesh "
                    "cycle then follow at each speed from an estimate of the rule's error "
                    "(dynamics/newmark_error.h: its frequency warping, for the tables' forcing "
                    "and for the recorded motion's harmonics), written per speed beside the "
                    "results (0.005: the seed spiral bevel case within 0.32 % of CVODE BDF at "
                    "1e-8 at every settled speed, the Kahraman-Singh sweep within 0.31 %); 0: "
                    "steps per mesh cycle at every speed (the estimate still written). At most "
                    "65536 steps per mesh cycle are taken: an accuracy whose estimate asks for "
                    "more at some speed is refused, with the accuracy reachable within them; "
                    "where the recorded motion asks for more, the log names the speeds.");
  prm.declare_entry("steps per mesh cycle", std::to_string(RunOptions().steps_per_cycle),
                    Patterns::Integer(8, 100000),
                    "Newmark: the least steps per mesh cycle (with accuracy 0: the steps); "
                    "from 32 on a multiple of 32 (the samples recorded per mesh cycle).");
  prm.declare_entry("system deflection", "true", Patterns::Bool(),
                    "true: the static equilibrium's displacements and tilts of both members "
                    "(bearings, shafts) move the pair: the TCA runs again at that misalignment, "
                    "to a fixed point, and the dynamics runs on the deflected mesh's tables "
                    "(with an analytic E_t: as assembled); false: the tables as assembled.");
  prm.declare_entry("excitations", "theoretical",
                    Patterns::MultipleSelection("theoretical|measured"),
                    "Tables swept: the theoretical flanks', the measured flanks' (their TCA: "
                    "TCA/<pair>/measured flanks = true), or both (the seed's comparison).");
  prm.declare_entry("excitation cycles", "0", Patterns::Integer(0),
                    "Mesh cycles of the measured flanks' TCA that form one period of their "
                    "excitation (teeth differ, so it does not repeat with the mesh cycle); 0: "
                    "all the TCA computed (the hunting cycle when it ran over it).");
  prm.declare_entry("time series speeds", "", Patterns::List(Patterns::Double(0), 0),
                    "[rpm] Keep the recorded time series at the swept speeds nearest these.");
  prm.declare_entry("spectrum orders", std::to_string(SweepOptions().spectrum_orders),
                    Patterns::Integer(1, 1000), "DTE spectrum per speed up to this mesh order.");
  prm.declare_entry("sweep blocks", "1", Patterns::Integer(1, 100000),
                    "Each sweep in this many blocks of consecutive speeds, run in parallel "
                    "(threads, and MPI processes under mpirun); 1: one continuation.");
  prm.declare_entry("warm-up speeds", "3", Patterns::Integer(0),
                    "Speeds each block but the first starts early to regain the continuation.");
}

void
DynamicsScene::parse(ParameterHandler &prm)
{
  fe_stiffness                 = prm.get("mesh stiffness source") == "finite elements";
  mesh_stiffness               = prm.get_double("mesh stiffness") * N_per_um;
  stiffness_variation          = prm.get_double("mesh stiffness variation");
  torque                       = prm.get_double("pinion torque");
  tca_transmission_error       = prm.get("transmission error source") == "tca";
  transmission_error_amplitude = prm.get_double("transmission error amplitude") * um;
  PairModelParameters &mp      = model;
  mp.motor_inertia             = prm.get_double("motor inertia");
  mp.speed_controlled_motor    = prm.get("motor") == "speed controlled";
  mp.load_inertia              = prm.get_double("load inertia");
  const double shaft_c         = prm.get_double("shaft damping");
  mp.motor_shaft               = {prm.get_double("motor shaft stiffness"), shaft_c};
  mp.load_shaft                = {prm.get_double("load shaft stiffness"), shaft_c};
  const double kb              = prm.get_double("bearing stiffness") * N_per_um,
               cb              = prm.get_double("bearing damping");
  for (const char *member : {"pinion", "gear"})
    {
      BodyParameters   &b  = std::string(member) == "pinion" ? mp.pinion : mp.gear;
      const std::string m  = member;
      b.mass               = prm.get_double(m + " mass");
      b.axial_inertia      = prm.get_double(m + " axial inertia");
      b.transverse_inertia = prm.get_double(m + " transverse inertia");
      b.bearings.clear();
      for (const double x : get_doubles(prm, m + " bearing positions", mm))
        b.bearings.push_back({x, kb, cb});
      b.axial_stiffness = prm.get_double("axial stiffness") * N_per_um;
      b.axial_damping   = cb;
    }
  mp.half_backlash       = prm.get_double("half backlash") * um;
  mp.mesh_damping_ratio  = prm.get_double("mesh damping ratio");
  speed_from             = from_rpm(prm.get_double("speed from"));
  speed_to               = from_rpm(prm.get_double("speed to"));
  speeds                 = prm.get_integer("speeds");
  sweep.settle_cycles    = prm.get_integer("settle cycles");
  sweep.record_cycles    = prm.get_integer("record cycles");
  sweep.steady_tolerance = prm.get_double("steady tolerance");
  for (const Integrator i : {Integrator::newmark, Integrator::cvode_bdf, Integrator::cvode_adams})
    if (prm.get("integrator") == integrator_name(i))
      sweep.run.method = i;
  sweep.run.steps_per_cycle = prm.get_integer("steps per mesh cycle");
  // the samples recorded per mesh cycle: 32, or the steps where fewer (Newmark's steps per mesh
  // cycle come in multiples of them); one rule for the sweeps, the accuracy check and Floquet
  sweep.run.samples_per_cycle = std::min(32, sweep.run.steps_per_cycle);
  sweep.accuracy              = prm.get_double("accuracy");
  system_deflection           = prm.get_bool("system deflection");
  const auto excitations      = split_list(prm.get("excitations"));
  auto       has              = [&](const char *what) {
    return std::find(excitations.begin(), excitations.end(), what) != excitations.end();
  };
  theoretical       = has("theoretical");
  measured          = has("measured");
  excitation_cycles = prm.get_integer("excitation cycles");
  for (const double x : get_doubles(prm, "time series speeds"))
    sweep.series_speeds.push_back(from_rpm(x));
  sweep.spectrum_orders = prm.get_integer("spectrum orders");
  sweep_blocks          = prm.get_integer("sweep blocks");
  warmup_speeds         = prm.get_integer("warm-up speeds");
}

namespace
{
std::string
list_text(const std::vector<double> &values, double unit)
{
  std::string text;
  for (const double v : values)
    text += (text.empty() ? "" : ", ") + plausible_number(v / unit);
  return text;
}

// What the geometry says about one member: its mass properties (involute members; a spiral
// bevel member's blank is not computed) and its size (tip diameter or face width, the larger;
// a bevel member: its outer cone distance, the scale of positions from its apex).
struct MemberSize
{
  bool           has_mass = false;
  MassProperties mass;
  double         size = 0;
  std::string    size_text;
};

// The model's masses, inertias and bearing positions against the member's geometry. A body is
// the gear with its hub and the shaft between its bearings: a few times the gear's own mass is
// a real design, a factor 10 warns, 300 is no design (a g/kg slip is 1000). The shaft adds
// little to the axial inertia (its radius is small; a hub or a coupling more): warned beyond
// 30 times the gear's, refused beyond 1e4 (kg mm^2 typed as kg m^2 is 1e6). The transverse
// inertia about the body point grows with the shaft's length squared: a 300 mm shaft under a
// 40 mm pinion gives some 400 times the gear's own; warned beyond 1000, refused beyond 1e5.
void
check_body(const BodyParameters &b, const MemberSize &m, const std::string &where,
           const std::string &member, std::vector<std::string> &warnings)
{
  if (m.has_mass && b.mass > 0)
    check_plausible(where + member + " mass = " + plausible_number(b.mass) + " kg",
                    b.mass / m.mass.mass,
                    "its ratio to the gear's mass from its geometry (" +
                        plausible_number(m.mass.mass) + " kg, Flanks section)",
                    0.1, 10, 1.0 / 300, 300,
                    {{1e-3, "grams typed in a kg field (" + plausible_number(b.mass) +
                                " g = " + plausible_number(b.mass / 1000) + " kg)"}},
                    warnings);
  for (const auto &[key, value, implied, high, highest] :
       {std::tuple{" axial inertia", b.axial_inertia, m.mass.polar_inertia, 30.0, 1e4},
        std::tuple{" transverse inertia", b.transverse_inertia, m.mass.diametral_inertia, 1e3,
                   1e5}})
    if (m.has_mass && value > 0)
      check_plausible(where + member + key + " = " + plausible_number(value) + " kg m^2",
                      value / implied,
                      "its ratio to the gear's inertia from its geometry (" +
                          plausible_number(implied) + " kg m^2)",
                      0.1, high, 1.0 / 300, highest,
                      {{1e-6, "kg mm^2 typed in a kg m^2 field (" + plausible_number(value) +
                                  " kg mm^2 = " + plausible_number(value * 1e-6) + " kg m^2)"},
                       {1e-7, "g cm^2 typed in a kg m^2 field (" + plausible_number(value) +
                                  " g cm^2 = " + plausible_number(value * 1e-7) + " kg m^2)"},
                       {1e-4, "kg cm^2 typed in a kg m^2 field (" + plausible_number(value) +
                                  " kg cm^2 = " + plausible_number(value * 1e-4) + " kg m^2)"}},
                      warnings);
  // Bearing positions: the bearings of a body stand at least about a tenth of its size apart
  // (a double-row bearing, an overhung pinion) and at most some 50 sizes (a long shaft);
  // closer than a hundredth of the size they hold nothing (bearings 0.09 mm apart under an
  // 83 mm gear: positions in metres), and 1e4 sizes is no gearbox.
  double              lo = 0, hi = 0;
  std::vector<double> x;
  for (const RadialBearing &r : b.bearings)
    x.push_back(r.position);
  if (x.size() >= 2)
    {
      lo = *std::min_element(x.begin(), x.end()), hi = *std::max_element(x.begin(), x.end());
      check_plausible(where + member + " bearing positions = " + list_text(x, mm) + " mm",
                      (hi - lo) / m.size,
                      "the bearings' span (" + plausible_number((hi - lo) / mm) +
                          " mm) over the member's size (" + m.size_text + ")",
                      0.1, 50, 0.01, 1e4,
                      {{1000, "metres typed in a mm field (" + list_text(x, mm) +
                                  " m = " + list_text(x, 1e-6) + " mm)"}},
                      warnings);
    }
}

// A stiffness [N/um] against its plausible range; the slips are N/m and N/mm typed in the
// N/um field.
void
check_stiffness(const std::string &parameter, double k, double scale, const std::string &what,
                double low, double high, double lowest, double highest,
                std::vector<std::string> &warnings)
{
  const double v = k / N_per_um;
  check_plausible(parameter + " = " + plausible_number(v) + " N/um", v / scale, what, low, high,
                  lowest, highest,
                  {{1e-6, "N/m typed in a N/um field (" + plausible_number(v) +
                              " N/m = " + plausible_number(v * 1e-6) + " N/um)"},
                   {1e-3, "N/mm typed in a N/um field (" + plausible_number(v) +
                              " N/mm = " + plausible_number(v * 1e-3) + " N/um)"}},
                  warnings);
}
} // namespace

void
DynamicsScene::check(const PairScene &pair, const TcaScene &tca, bool run,
                     std::vector<std::string> &warnings) const
{
  const std::string where = "Dynamics/" + pair.name + "/";
  if (!theoretical && !measured)
    throw InputError(where + "excitations: none chosen; choose theoretical, measured or both");
  const int steps = sweep.run.steps_per_cycle;
  if (steps > 32 && steps % 32 != 0)
    throw InputError(where + "steps per mesh cycle: " + std::to_string(steps) +
                     " is not a multiple of 32 (the samples recorded per mesh cycle); use " +
                     std::to_string(32 * (steps / 32)) + " or " +
                     std::to_string(32 * (steps / 32 + 1)));
  if (measured && !tca.measured)
    throw InputError(where + "excitations: measured needs the measured flanks' TCA (set TCA/" +
                     pair.name + "/measured flanks = true)");
  if (measured && excitation_cycles > tca.options.mesh_cycles)
    throw InputError(where + "excitation cycles: " + std::to_string(excitation_cycles) +
                     " is more than the " + std::to_string(tca.options.mesh_cycles) +
                     " mesh cycles the TCA computes (TCA/" + pair.name + "/mesh cycles)");
  if (!(speed_to >= speed_from))
    throw InputError(where + "speed to: " + std::to_string(speed_to / from_rpm(1)) +
                     " rpm is below speed from (" + std::to_string(speed_from / from_rpm(1)) +
                     " rpm)");
  if (run)
    check_plausibility(pair, warnings);
}

// The model against the pair's geometry: what a unit slip gives is refused by its parameter,
// an unusual but real design warned.
void
DynamicsScene::check_plausibility(const PairScene &pair, std::vector<std::string> &warnings) const
{
  const std::string                   where = "Dynamics/" + pair.name + "/";
  MemberSize                          sizes[2];
  double                              pinion_radius = 0, face_width = 0;
  std::shared_ptr<const InvoluteGear> p, g;
  if (pair.type == PairType::involute)
    {
      std::tie(p, g) = pair.involute_members();
      int i          = 0;
      for (const auto &member : {p, g})
        {
          MemberSize &m = sizes[i++];
          m.has_mass    = true;
          m.mass        = member->mass_properties();
          m.size        = std::max(2 * member->tip_radius, member->data().face_width);
          m.size_text   = "tip diameter " + plausible_number(2 * member->tip_radius / mm) +
                        " mm, face width " + plausible_number(member->data().face_width / mm) +
                        " mm";
        }
      pinion_radius = p->reference_radius;
      face_width    = std::min(pair.pinion.face_width, pair.gear.face_width);
    }
  else
    {
      const BevelPairGeometry b = bevel_geometry(pair.bevel);
      for (MemberSize &m : sizes)
        m.size      = b.outer_cone_distance,
        m.size_text = "outer cone distance " + plausible_number(b.outer_cone_distance / mm) + " mm";
      pinion_radius = b.mean_cone_distance * std::sin(b.pitch_angle_pinion);
      face_width    = pair.bevel.face_width;
    }
  check_body(model.pinion, sizes[0], where, "pinion", warnings);
  check_body(model.gear, sizes[1], where, "gear", warnings);

  // Mesh stiffness per face width: steel pairs 10..25 N/(mm um) (ISO 6336-1: c_gamma about
  // 20), polymer pairs down to about 1; beyond 1000 (50 times steel's) or below 1e-3 nothing
  // meshes so. 3e8 "N/um" on 20 mm is N/m.
  // With K_m from the finite elements the value is not used: what would be refused warns.
  if (mesh_stiffness > 0)
    try
      {
        std::vector<std::string> found;
        check_stiffness(where + "mesh stiffness", mesh_stiffness, face_width / mm,
                        "the mesh stiffness per face width [N/(mm um)] on " +
                            plausible_number(face_width / mm) + " mm",
                        1, 50, 1e-3, 1000, found);
        if (!fe_stiffness)
          warnings.insert(warnings.end(), found.begin(), found.end());
      }
    catch (const InputError &e)
      {
        if (!fe_stiffness)
          throw;
        std::string text = e.what();
        if (const auto k = text.find(" is not allowed: "); k != std::string::npos)
          text.replace(k, 17, " would not be allowed: ");
        warnings.push_back(text + "; it is not used (mesh stiffness source = finite elements), "
                                  "so the run goes on");
      }
  // Bearings: rolling and journal bearings 50..2000 N/um, elastic mounts from about 1; "rigid"
  // modelled as up to 1e5. Beyond 1e7 N/um (a solid steel block of the gear's size is about
  // 1e4) it is no support but a slip.
  if (!model.pinion.bearings.empty() && model.pinion.bearings[0].stiffness > 0)
    check_stiffness(where + "bearing stiffness", model.pinion.bearings[0].stiffness, 1,
                    "the bearing stiffness [N/um]", 1, 1e5, 1e-3, 1e7, warnings);
  if (model.pinion.axial_stiffness > 0)
    check_stiffness(where + "axial stiffness", model.pinion.axial_stiffness, 1,
                    "the axial stiffness [N/um]", 1, 1e5, 1e-3, 1e7, warnings);

  check_torque(where + "pinion torque", torque, pair, warnings);
  // Half backlash: j_t of 0.02 to 0.3 mm for modules of 1 to 10 mm; below 1 um (but not 0, a
  // zero-backlash model) it is mm typed in the um field: warned. Beyond 0.8 m_n the teeth
  // would be thinned to nothing (a tooth is about 1.57 m_n thick): refused.
  const PairScale   scale = pair_scale(pair);
  const double      bc    = model.half_backlash;
  const std::string half  = where + "half backlash = " + plausible_number(bc / um) + " um";
  if (bc > 0.8 * scale.module)
    throw InputError(half + " is not allowed: " + plausible_number(bc / scale.module) +
                     " normal modules (m_n " + plausible_number(scale.module / mm) +
                     " mm), where a tooth is about 1.57 m_n thick: real designs have up to "
                     "about 0.1 m_n; expected a half backlash below 0.8 m_n (" +
                     plausible_number(0.8 * scale.module / um) + " um)");
  if (bc > 0 && bc < 1 * um)
    warnings.push_back(half +
                       " is unusual: real designs have 10 to 300 um; it looks like mm "
                       "typed in a um field (" +
                       plausible_number(bc / um) + " mm = " + plausible_number(bc / um * 1000) +
                       " um); the run goes on with the value as given");
  // Motor and load inertias against the pinion's and gear's own: a motor rotor or a brake
  // drum is tens to thousands of times a small pinion's (the default 0.05 kg m^2 is 160 times
  // the FZG pinion's): warned beyond 1e4 times, refused beyond 1e6 (kg mm^2 typed as kg m^2).
  if (p)
    {
      for (const auto &[key, value, implied] :
           {std::tuple{"motor inertia", model.motor_inertia, p->mass_properties().polar_inertia},
            std::tuple{"load inertia", model.load_inertia, g->mass_properties().polar_inertia}})
        if (value > 0)
          check_plausible(where + key + " = " + plausible_number(value) + " kg m^2",
                          value / implied,
                          std::string("its ratio to the polar inertia of the ") +
                              (key[0] == 'm' ? "pinion" : "gear") + " from its geometry (" +
                              plausible_number(implied) + " kg m^2)",
                          0, 1e4, 0, 1e6,
                          {{1e-6, "kg mm^2 typed in a kg m^2 field (" + plausible_number(value) +
                                      " kg mm^2 = " + plausible_number(value * 1e-6) + " kg m^2)"}},
                          warnings);
    }

  // Speeds: the pitch-line velocity of the fastest turbo gears is about 200 m/s (warned
  // beyond); at 500 m/s the rim's hoop stress rho v^2 is 2 GPa in steel, beyond its strength:
  // refused. A mesh frequency beyond 50 kHz reaches the teeth's own bending modes, which this
  // lumped model (rigid teeth on a mesh spring) does not have: warned.
  const double      v     = speed_to * pinion_radius;
  const double      rpm   = speed_to / from_rpm(1);
  const int         z1    = pair_teeth(pair).first;
  const double      f     = z1 * speed_to / (2 * pi);
  const std::string speed = where + "speed to = " + plausible_number(rpm) + " rpm";
  check_plausible(speed, v,
                  "the pinion's pitch-line velocity [m/s] (pitch radius " +
                      plausible_number(pinion_radius / mm) + " mm)",
                  0, 200, 0, 500, {}, warnings);
  check_plausible(speed, f / 1000,
                  "the mesh frequency [kHz] (" + std::to_string(z1) +
                      " pinion teeth), which a lumped mesh model resolves below the teeth's own "
                      "modes,",
                  0, 50, 0, 1e300, {}, warnings);
}
} // namespace gearkit

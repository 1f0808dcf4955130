// Section Train/<train>: a gear train's impact dynamics (seeds 001 and 002) - its bodies (rigid
// rotors with their inertias, initial speeds, drives, torque laws and crank-sliders), its meshes
// (involute pairs of the Flanks section between two bodies, with their backlash), the IMPACT
// contact law, the run and the spectra - declared, read and checked side by side. Units are
// converted here, at the edge; the TrainScene holds SI.
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

namespace gearkit
{
namespace
{
std::string
number_text(double x)
{
  std::ostringstream s;
  s.precision(9);
  s << x;
  return s.str();
}

/// A parameter that is either `word` or a finite number: false for the word, the number in
/// value otherwise. Anything else is refused naming where, the text and what is allowed.
bool
number_or_word(const std::string &text, const std::string &word, double &value,
               const std::string &where, const std::string &allowed)
{
  const auto        b       = text.find_first_not_of(" \t");
  const auto        e       = text.find_last_not_of(" \t");
  const std::string trimmed = b == std::string::npos ? "" : text.substr(b, e - b + 1);
  if (trimmed == word)
    return false;
  char *end = nullptr;
  value     = std::strtod(trimmed.c_str(), &end);
  if (trimmed.empty() || *end != '\0' || !std::isfinite(value))
    throw InputError(where + ": '" + trimmed.substr(0, 40) + "' is not allowed; expected " +
                     allowed);
  return true;
}

void
declare_body(ParameterHandler &prm)
{
  prm.declare_entry("inertia", "auto", Patterns::Anything(),
                    "[kg m^2] Moment of inertia about the body's axis, its gears and shaft "
                    "included; auto: the polar inertias of its gears from their geometry (the "
                    "Flanks section: face width, bore, density, chipped teeth) plus shaft inertia. "
                    "A gear in two meshes (an idler) counts twice with auto: give a number.");
  prm.declare_entry("shaft inertia", "0", Patterns::Double(0),
                    "[kg m^2] Added to the gears' inertia when inertia = auto (shaft, coupling, "
                    "crank, flywheel).");
  prm.declare_entry("initial speed", "kinematic", Patterns::Anything(),
                    "[rad/s] Speed at t = 0 in the sense the train turns it running forward; "
                    "kinematic: from the first body with a number, through the tooth ratios.");
  prm.declare_entry("initial angle", "0", Patterns::Double(-360, 360), "[deg] Angle at t = 0.");
  prm.declare_entry("drive", "free", Patterns::Selection("free|constant speed"),
                    "free: the torque law below acts; constant speed: held at its initial speed "
                    "by whatever torque that takes (the torque law is then ignored).");
  prm.declare_entry("torque unit", "N m", Patterns::Selection("N m|lbf in"),
                    "Unit of torque and torque step.");
  prm.declare_entry("torque", "0", Patterns::Double(-1e9, 1e9),
                    "Constant torque on the body (positive drives it forward).");
  prm.declare_entry("torque step", "0", Patterns::Double(-1e9, 1e9),
                    "T_s of the step T_s (1 - exp(-t / tau)) added to the torque.");
  prm.declare_entry("torque time constant", "0", Patterns::Double(0, 1e9),
                    "[ms] tau of the torque step; 0: the step at once.");
  prm.declare_entry("viscous damping", "0", Patterns::Double(0, 1e9),
                    "[N m s/rad] A torque -c w opposing the body's speed (bearings, fluid).");
  prm.declare_entry("axis position", "", Patterns::List(Patterns::Double(-1e6, 1e6), 0, 2),
                    "[mm] x, y of the body's axis (optional): with both bodies of a mesh placed, "
                    "the mesh's centre distance must be their distance within 1 um.");
  prm.declare_entry("shaft to", "", Patterns::Anything(),
                    "A body joined to this one by a torsional shaft (both on one axis, turning "
                    "together); empty: none. Its torque k (theta_other - theta) + c (w_other - "
                    "w) acts on this body, the opposite on the other.");
  prm.declare_entry("shaft stiffness", "0", Patterns::Double(0, 1e15),
                    "[N m/rad] Torsional stiffness of that shaft (> 0 with shaft to).");
  prm.declare_entry("shaft damping", "0", Patterns::Double(0, 1e15),
                    "[N m s/rad] Torsional damping of that shaft.");
  in_subsection(prm, {"Crank slider"}, [&] {
    prm.declare_entry("crank radius", "0", Patterns::Double(0, 1e5),
                      "[mm] r; 0: the body drives no crank-slider.");
    prm.declare_entry("rod length", "0", Patterns::Double(0, 1e5),
                      "[mm] l of the connecting rod (> r).");
    prm.declare_entry("rod centre", "0", Patterns::Double(0, 1e5),
                      "[mm] Centre of mass of the rod from the crank pin (at most l).");
    prm.declare_entry("rod mass", "0", Patterns::Double(0, 1e6), "[kg]");
    prm.declare_entry("rod inertia", "0", Patterns::Double(0, 1e6),
                      "[kg m^2] About the rod's centre of mass.");
    prm.declare_entry("piston mass", "0", Patterns::Double(0, 1e6), "[kg]");
    prm.declare_entry("piston force", "0", Patterns::Double(-1e9, 1e9),
                      "[N] Constant force on the piston (> 0 pushes it toward the crank axis).");
    prm.declare_entry("crank angle", "0", Patterns::Double(-360, 360),
                      "[deg] Crank angle at body angle 0 (0: top dead centre).");
  });
}

void
declare_mesh(ParameterHandler &prm)
{
  prm.declare_entry("pair", "", Patterns::Anything(),
                    "Name of an involute (spur or helical) pair of Scene/pairs: its Flanks "
                    "section gives the teeth (deviations, chipped teeth included), its TCA "
                    "section the centre distance and misalignments.");
  prm.declare_entry("pinion body", "", Patterns::Anything(),
                    "Body that carries the pair's pinion (the driver of the mesh).");
  prm.declare_entry("gear body", "", Patterns::Anything(),
                    "Body that carries the pair's gear (driven).");
  prm.declare_entry("backlash", "0", Patterns::Double(0, 1e3),
                    "[mm] Circumferential backlash j_t of the nominal teeth on the operating "
                    "pitch circles; the centre distance is opened until they have it (exactly: "
                    "j_t = 2 a (inv alpha'_t - inv alpha_wt), a = a_w + j_t / (2 tan alpha_wt) "
                    "to first order). 0: the pair's TCA centre distance as it is (which must be "
                    "0, the zero-backlash one, when a backlash is given).");
  prm.declare_entry("pinion angle", "0", Patterns::Double(-360, 360),
                    "[deg] Angle of the pinion on its body (0: its tooth 0 on the line of "
                    "centres at body angle 0).");
  prm.declare_entry("stiffness", "impact", Patterns::Selection("impact|finite elements"),
                    "impact: every touching tooth pair carries the IMPACT force of the Contact "
                    "section; finite elements: the mesh stiffness K_m over the mesh cycle from "
                    "the stiffness stage (Loaded contact/<pair>) acts on each side's deepest "
                    "pair, K_m d_max in place of K d^e (by K_m's definition its deflection "
                    "lambda (e_L - e_0) is that pair's penetration); the Contact section's "
                    "damping stays (dynamics/train.h).");
  prm.declare_entry("stiffness torque", "0", Patterns::Double(0),
                    "[N m] With stiffness = finite elements: the K_m of the loaded-contact "
                    "torque nearest this (K_m is the secant stiffness at one load); 0: the "
                    "largest torque.");
  prm.declare_entry("initial contact", "centre", Patterns::Selection("centre|drive|coast"),
                    "Where the gear starts: in the middle of the backlash (centre), or with the "
                    "drive or coast flanks of the pairing at the line of centres touching.");
}

TorqueLaw
get_torque(ParameterHandler &prm)
{
  const double unit = prm.get("torque unit") == "N m" ? 1.0 : lbf * inch;
  TorqueLaw    t;
  t.constant      = prm.get_double("torque") * unit;
  t.step          = prm.get_double("torque step") * unit;
  t.time_constant = prm.get_double("torque time constant") * ms;
  t.viscous       = prm.get_double("viscous damping");
  return t;
}
} // namespace

void
TrainScene::declare(ParameterHandler &prm, const std::vector<std::string> &bodies,
                    const std::vector<std::string> &meshes)
{
  prm.declare_entry("bodies", "", Patterns::List(Patterns::Anything(), 0),
                    "Names of the train's bodies (rigid rotors: a shaft with its gears), each "
                    "with a subsection in Bodies (letters, digits, _ and -).");
  prm.declare_entry("meshes", "", Patterns::List(Patterns::Anything(), 0),
                    "Names of the train's meshes, each with a subsection in Meshes.");
  prm.declare_entry("reference body", "", Patterns::Anything(),
                    "Body whose mean speed over the spectrum interval sets the kinematic "
                    "frequencies (shaft speeds, GMF); empty: the first constant-speed body, "
                    "else the first body.");
  in_subsection(prm, {"Contact"}, [&] {
    prm.declare_entry("stiffness", "2e7", Patterns::Double(0, 1e300),
                      "K of the MSC ADAMS IMPACT force F = K d^e - STEP(d, 0, 0, d_max, c_max) "
                      "x' (per tooth pair), in the stiffness unit: force / length^e.");
    prm.declare_entry("stiffness unit", "N/mm", Patterns::Selection("N/mm|lbf/in"),
                      "N/mm: K in N / mm^e (ADAMS model units N, mm); lbf/in: lbf / in^e.");
    prm.declare_entry("exponent", "2.2", Patterns::Double(1, 10), "e of the IMPACT force.");
    prm.declare_entry("damping", "0", Patterns::Double(0, 1e300),
                      "c_max, the damping reached at penetration depth d_max, in the damping "
                      "unit.");
    prm.declare_entry(
        "damping unit", "% of stiffness", Patterns::Selection("% of stiffness|N s/mm|lbf s/in"),
        "% of stiffness: c_max = damping / 100 x K taken as a number in the stiffness unit's "
        "force s / length (the seeds' '2e-2 % of stiffness' with K = 2e7 N/mm^e: 4000 N s/mm); "
        "N s/mm or lbf s/in: c_max itself.");
    prm.declare_entry("penetration depth", "1e-7", Patterns::Double(0, 1e3),
                      "d_max, where the damping is complete (the cubic STEP from 0 at d = 0).");
    prm.declare_entry("penetration depth unit", "mm", Patterns::Selection("mm|in"),
                      "Unit of the penetration depth.");
    prm.declare_entry("tooth pair recess", "100", Patterns::Double(1, 1e5),
                      "[um] How far beyond the conjugate touch the tooth pair curves reach, along "
                      "the normal (tca/tooth_pairs.h): at least the deepest penetration of a "
                      "pair, or pairs leave their curves still touching (the run warns; soft "
                      "contacts penetrate hundreds of um).");
    prm.declare_entry("curve samples per mesh cycle", "64", Patterns::Integer(8, 100000),
                      "Samples of the tooth pair curves per pinion mesh cycle.");
  });
  in_subsection(prm, {"Run"}, [&] {
    prm.declare_entry("duration", "0.1", Patterns::Double(0, 1000), "[s] Simulated time.");
    prm.declare_entry("sample rate", "20000", Patterns::Double(1, 1e8),
                      "[Hz] Output samples per second (time series, spectra).");
    prm.declare_entry("anti-alias", "true", Patterns::Bool(),
                      "Record the angles, speeds and mesh forces without aliasing (averages of "
                      "the solution around 8 points per sample, decimated through a 70 dB "
                      "low-pass: true to 0.4 times the sample rate, nothing folds back from "
                      "above half of it; the samples end on the last whole output interval); "
                      "false: the solution's values at the sample times (they alias).");
    prm.declare_entry("integrator", "auto", Patterns::Selection("auto|bdf|adams"),
                      "CVODE method: adams (orders up to 12, no Jacobian: for contacts whose "
                      "damping acts slower than 10 us), bdf (stiff: IMPACT damping acting within "
                      "microseconds), or auto: bdf where a mesh's damping time constant m_e / "
                      "c_max (or a shaft's J / c) is below 10 us, adams otherwise (the log "
                      "and results.h5 say which ran).");
    prm.declare_entry("relative tolerance", "7e-9", Patterns::Double(1e-15, 1e-2),
                      "CVODE relative tolerance (also of the energy balance's quadratures).");
    prm.declare_entry("absolute tolerance", "1e-6", Patterns::Double(1e-12, 1e3),
                      "[um] Absolute tolerance as a length along the contact normals.");
    prm.declare_entry("energy tolerance", "0", Patterns::Double(0, 0.1),
                      "Error test of the energy balance's quadratures (work, dissipated energy), "
                      "relative and as a share of the initial kinetic energy; 0: the relative "
                      "tolerance. Long runs whose work is large against their energies need it "
                      "smaller.");
    prm.declare_entry("max steps", "20000000", Patterns::Integer(1),
                      "CVODE steps allowed in the whole run (beyond: a clear failure).");
    prm.declare_entry("pairings each side", "3", Patterns::Integer(1, 50),
                      "Tooth pairings examined on each side of the one at the line of centres.");
    prm.declare_entry(
        "maximum estimated cost", "600", Patterns::Double(0, 1e9),
        "[s] The run is refused before any stage when its estimated run time is beyond this "
        "(CVODE steps: about 60 (1e-6 / relative tolerance)^0.19 per mesh cycle of each mesh at "
        "the initial speeds, plus one per sample; 2 + 0.3 per tooth pair examined us a step, "
        "the 2-core machine of bench/README.md); raise it for a long run you mean to wait for. "
        "A run-up from rest is estimated at its initial speeds, so below its cost.");
  });
  in_subsection(prm, {"Spectrum"}, [&] {
    prm.declare_entry("start", "0", Patterns::Double(0, 1000),
                      "[s] The mesh forces' spectra are taken from this time to the end; 0: "
                      "the second half of the run.");
    prm.declare_entry("harmonics", "4", Patterns::Integer(1, 100),
                      "GMF harmonics looked for in each mesh's force spectrum.");
    prm.declare_entry("sidebands", "2", Patterns::Integer(0, 20),
                      "Sideband orders looked for around each harmonic, for every shaft "
                      "frequency of the train.");
    prm.declare_entry("max frequency", "0", Patterns::Double(0, 1e8),
                      "[Hz] Spectrum bins stored up to this; 0: all (to the Nyquist frequency).");
    prm.declare_entry("spectrogram window", "50", Patterns::Double(0, 1e6),
                      "[ms] Window of the first mesh's force spectrogram (Hamming); 0: none.");
    prm.declare_entry("spectrogram overlap", "0.8", Patterns::Double(0, 0.99),
                      "Share of each window the next one overlaps.");
    prm.declare_entry("spectrogram max frequency", "0", Patterns::Double(0, 1e8),
                      "[Hz] Top of the spectrogram; 0: the Nyquist frequency.");
  });
  for (const std::string &b : bodies)
    in_subsection(prm, {"Bodies", b}, [&] { declare_body(prm); });
  for (const std::string &m : meshes)
    in_subsection(prm, {"Meshes", m}, [&] { declare_mesh(prm); });
}

void
TrainScene::parse(ParameterHandler &prm)
{
  const std::string where = "Train/" + name;
  reference_body          = prm.get("reference body");
  for (const std::string &b : split_list(prm.get("bodies")))
    {
      TrainBodyScene body;
      body.name = b;
      in_subsection(prm, {"Bodies", b}, [&] {
        const std::string here = where + "/Bodies/" + b;
        body.inertia_auto      = !number_or_word(prm.get("inertia"), "auto", body.inertia,
                                                 here + "/inertia", "a number [kg m^2] or auto");
        body.shaft_inertia     = prm.get_double("shaft inertia");
        body.kinematic_speed =
            !number_or_word(prm.get("initial speed"), "kinematic", body.initial_speed,
                            here + "/initial speed", "a number [rad/s] or kinematic");
        body.initial_angle             = prm.get_double("initial angle") * deg;
        body.constant_speed            = prm.get("drive") == "constant speed";
        body.torque                    = get_torque(prm);
        const std::vector<double> axis = get_doubles(prm, "axis position", mm);
        if (axis.size() == 1)
          throw InputError(here + "/axis position: one number is not allowed; expected x, y "
                                  "[mm] or nothing");
        body.placed          = axis.size() == 2;
        body.shaft_to        = prm.get("shaft to");
        body.shaft_stiffness = prm.get_double("shaft stiffness");
        body.shaft_damping   = prm.get_double("shaft damping");
        if (body.placed)
          body.x = axis[0], body.y = axis[1];
        in_subsection(prm, {"Crank slider"}, [&] {
          CrankSlider &k  = body.crank;
          k.crank_radius  = prm.get_double("crank radius") * mm;
          k.rod_length    = prm.get_double("rod length") * mm;
          k.rod_centre    = prm.get_double("rod centre") * mm;
          k.rod_mass      = prm.get_double("rod mass");
          k.rod_inertia   = prm.get_double("rod inertia");
          k.piston_mass   = prm.get_double("piston mass");
          k.piston_force  = prm.get_double("piston force");
          k.crank_angle_0 = prm.get_double("crank angle") * deg;
          body.has_crank  = k.crank_radius > 0;
        });
      });
      bodies.push_back(body);
    }
  for (const std::string &m : split_list(prm.get("meshes")))
    {
      TrainMeshScene mesh;
      mesh.name = m;
      in_subsection(prm, {"Meshes", m}, [&] {
        mesh.pair              = prm.get("pair");
        mesh.pinion_body       = prm.get("pinion body");
        mesh.gear_body         = prm.get("gear body");
        mesh.backlash          = prm.get_double("backlash") * mm;
        mesh.pinion_angle      = prm.get_double("pinion angle") * deg;
        mesh.fe_stiffness      = prm.get("stiffness") == "finite elements";
        mesh.stiffness_torque  = prm.get_double("stiffness torque");
        const std::string from = prm.get("initial contact");
        mesh.start             = from == "centre"  ? MeshStart::centre
                                 : from == "drive" ? MeshStart::drive
                                                   : MeshStart::coast;
      });
      meshes.push_back(mesh);
    }
  in_subsection(prm, {"Contact"}, [&] {
    const bool   imperial = prm.get("stiffness unit") == "lbf/in";
    const double force = imperial ? lbf : 1.0, length = imperial ? inch : mm;
    law.exponent            = prm.get_double("exponent");
    const double K          = prm.get_double("stiffness");
    law.stiffness           = impact_stiffness_si(K, law.exponent, length) * force;
    const std::string unit  = prm.get("damping unit");
    const double      c     = prm.get_double("damping");
    law.damping             = unit == "% of stiffness" ? c / 100 * K * force / length
                              : unit == "N s/mm"       ? c / mm
                                                       : c * lbf / inch;
    curves.recess           = prm.get_double("tooth pair recess") * um;
    curves.samples_per_mesh = prm.get_integer("curve samples per mesh cycle");
    law.depth               = prm.get_double("penetration depth") *
                (prm.get("penetration depth unit") == "mm" ? mm : inch);
  });
  in_subsection(prm, {"Run"}, [&] {
    run.duration             = prm.get_double("duration");
    run.sample_rate          = prm.get_double("sample rate");
    run.anti_alias           = prm.get_bool("anti-alias");
    const std::string method = prm.get("integrator");
    run.method               = method == "bdf"     ? TrainIntegrator::bdf
                               : method == "adams" ? TrainIntegrator::adams
                                                   : TrainIntegrator::automatic;
    run.relative_tolerance   = prm.get_double("relative tolerance");
    run.absolute_tolerance   = prm.get_double("absolute tolerance") * um;
    run.energy_tolerance     = prm.get_double("energy tolerance");
    run.max_steps            = prm.get_integer("max steps");
    run.pairings_each_side   = prm.get_integer("pairings each side");
    maximum_cost             = prm.get_double("maximum estimated cost");
  });
  in_subsection(prm, {"Spectrum"}, [&] {
    spectrum_start            = prm.get_double("start");
    harmonics                 = prm.get_integer("harmonics");
    sidebands                 = prm.get_integer("sidebands");
    spectrum_max_frequency    = prm.get_double("max frequency");
    spectrogram_window        = prm.get_double("spectrogram window") * ms;
    spectrogram_overlap       = prm.get_double("spectrogram overlap");
    spectrogram_max_frequency = prm.get_double("spectrogram max frequency");
  });
}

int
TrainScene::body_index(const std::string &body) const
{
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == body)
      return int(i);
  return -1;
}

int
TrainScene::reference() const
{
  if (!reference_body.empty())
    return body_index(reference_body);
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].constant_speed)
      return int(i);
  return 0;
}

const PairScene &
Scene::pair(const std::string &p) const
{
  for (const PairScene &s : pairs)
    if (s.name == p)
      return s;
  std::string names;
  for (const PairScene &s : pairs)
    names += (names.empty() ? "" : ", ") + s.name;
  throw InputError(file + ": pair '" + p + "' is not in Scene/pairs (" + names + ")");
}

double
train_mesh_centre_distance(const Scene &scene, const TrainMeshScene &mesh)
{
  const PairScene &pair     = scene.pair(mesh.pair);
  const TcaScene  &tca      = scene.tca.at(mesh.pair);
  const auto [pinion, gear] = pair.involute_members();
  if (mesh.backlash > 0)
    return centre_distance_for_backlash(*pinion, *gear, mesh.backlash);
  return tca.centre_distance > 0 ? tca.centre_distance : working_centre_distance(*pinion, *gear);
}

TrainModel
TrainScene::model(const Scene &scene) const
{
  TrainModel m;
  for (const TrainBodyScene &b : bodies)
    {
      TrainBody body;
      body.name           = b.name;
      body.inertia        = b.inertia;
      body.initial_angle  = b.initial_angle;
      body.initial_speed  = b.initial_speed;
      body.constant_speed = b.constant_speed;
      body.torque         = b.torque;
      body.has_crank      = b.has_crank;
      body.crank          = b.crank;
      if (b.inertia_auto)
        body.inertia = b.shaft_inertia;
      m.bodies.push_back(body);
    }
  for (const TrainMeshScene &s : meshes)
    {
      TrainMesh mesh;
      mesh.name                 = s.name;
      mesh.driver               = body_index(s.pinion_body);
      mesh.driven               = body_index(s.gear_body);
      const PairScene &pair     = scene.pair(s.pair);
      const auto [pinion, gear] = pair.involute_members();
      mesh.teeth.pinion_teeth   = pinion->teeth();
      mesh.teeth.gear_teeth     = gear->teeth();
      mesh.pinion_base_radius   = pinion->base_radius;
      mesh.gear_base_radius     = gear->base_radius;
      mesh.pinion_angle_0       = s.pinion_angle;
      mesh.law                  = law;
      // the gears' inertias on their bodies
      if (bodies[std::size_t(mesh.driver)].inertia_auto)
        m.bodies[std::size_t(mesh.driver)].inertia += pinion->mass_properties().polar_inertia;
      if (bodies[std::size_t(mesh.driven)].inertia_auto)
        m.bodies[std::size_t(mesh.driven)].inertia += gear->mass_properties().polar_inertia;
      m.meshes.push_back(mesh);
    }
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!bodies[i].shaft_to.empty())
      m.shafts.push_back({int(i), body_index(bodies[i].shaft_to), bodies[i].shaft_stiffness,
                          bodies[i].shaft_damping});
  // kinematic initial speeds from the first body with a number
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!bodies[i].kinematic_speed)
      {
        const std::vector<double> w = train_speeds(m, int(i), bodies[i].initial_speed);
        for (std::size_t j = 0; j < bodies.size(); ++j)
          if (bodies[j].kinematic_speed)
            m.bodies[j].initial_speed = w[j];
        break;
      }
  return m;
}

TrainCost
train_cost_estimate(const TrainScene &train, const TrainModel &model)
{
  // Fit to bench_train_startup (bench/HISTORY.md, its 2026-11-24 table, 2-core Xeon: seed 002's
  // two meshes, 3 pairings each side): BDF at relative tolerance 1e-6, 1e-8, 1e-10 took 60, 167
  // and 335 CVODE steps per mesh cycle (summed over the meshes; the steady sweep of stage 1
  // alike: 336 at 1e-10), 6.2 us a step for its 28 tooth pairs (2 flank sides x 7 pairings x 2
  // meshes) on the idle machine. Measured again with two other builds running (the test's small
  // train, 0.5 s at 1e-10): 130k steps where this estimates 90k, 13.6 us a step. The estimate
  // takes 2 us + 0.3 us per tooth pair (10.4 us for 28): between the idle and the loaded
  // machine, so that a refusal is never far off. Adams takes about half the steps: the estimate
  // is BDF's. Each output sample costs at least a step's work (the root functions and the
  // record).
  TrainCost c;
  for (const TrainMesh &m : model.meshes)
    c.mesh_cycles += std::abs(model.bodies[std::size_t(m.driver)].initial_speed) *
                     m.teeth.pinion_teeth / (2 * pi) * train.run.duration;
  const double per_cycle = 60 * std::pow(1e-6 / train.run.relative_tolerance, 0.19);
  const double samples   = train.run.duration * train.run.sample_rate;
  c.steps                = per_cycle * c.mesh_cycles + samples;
  const double pairs     = double(model.meshes.size()) * 2 * (2 * train.run.pairings_each_side + 1);
  c.seconds              = c.steps * (2 + 0.3 * pairs) * 1e-6;
  return c;
}

namespace
{
// Constant-speed bodies are held at their speeds for the whole run: two of them joined through
// meshes or shafts whose ratio their speeds contradict drive the teeth into each other without
// end (penetrations of many mm, forces of 1e8 N). Refused naming both, where the teeth would
// drift by more than 1 um over the run (at the largest base radius on the second body): speeds
// rounded to 8 digits pass, a ratio rounded to 4 only in a short run (the message gives the
// speed to 9 digits).
void
check_constant_speeds(const TrainScene &train, const TrainModel &m)
{
  for (std::size_t i = 0; i < train.bodies.size(); ++i)
    {
      const TrainBodyScene &a = train.bodies[i];
      if (!a.constant_speed)
        continue;
      const double              wa = m.bodies[i].initial_speed;
      const std::vector<double> w  = train_speeds(m, int(i), wa);
      for (std::size_t j = i + 1; j < train.bodies.size(); ++j)
        {
          const TrainBodyScene &b      = train.bodies[j];
          const double          held   = m.bodies[j].initial_speed;
          double                radius = 0;
          for (const TrainMesh &mesh : m.meshes)
            {
              if (mesh.driver == int(j))
                radius = std::max(radius, mesh.pinion_base_radius);
              if (mesh.driven == int(j))
                radius = std::max(radius, mesh.gear_base_radius);
            }
          if (radius == 0) // a body on shafts only: a gear's size
            radius = 0.05;
          const double drift = std::abs(held - w[j]) * train.run.duration * radius;
          if (!b.constant_speed || !std::isfinite(w[j]) || !(drift > 1e-6))
            continue;
          auto speed_text = [&](const TrainBodyScene &x, double speed) {
            return "Train/" + train.name + "/Bodies/" + x.name + "/initial speed = " +
                   (x.kinematic_speed ? "kinematic (" + plausible_number(speed) + " rad/s)"
                                      : plausible_number(speed) + " rad/s");
          };
          throw InputError(
              speed_text(a, wa) + " and " + speed_text(b, held) +
              ", both with drive = constant speed, are not allowed: the tooth ratio between "
              "them (speed of " +
              b.name + " / speed of " + a.name + " = " +
              (wa != 0 ? plausible_number(w[j] / wa) : std::string("that of the meshes")) +
              " through the meshes) turns " + b.name + " at " + number_text(w[j]) + " rad/s when " +
              a.name + " turns at " + plausible_number(wa) + " rad/s: its teeth would run " +
              plausible_number(drift / mm) +
              " mm into their mates' over the run; hold one of them (the other drive = free), "
              "or give speeds in that ratio");
        }
    }
}

// The run's estimated cost (train_cost_estimate) within the user's limit: a 1000 s run at
// 20 kHz ran on without an estimate of its cost (issue 35).
void
check_cost(const TrainScene &train, const TrainModel &m)
{
  const TrainRunOptions &run   = train.run;
  const std::string      where = "Train/" + train.name;
  const TrainCost        c     = train_cost_estimate(train, m);
  if (c.seconds <= train.maximum_cost)
    return;
  const auto n = [](double x) { return plausible_number(std::round(x)); };
  throw InputError(
      where + "/Run/duration = " + plausible_number(run.duration) +
      " s at sample rate = " + plausible_number(run.sample_rate) +
      " Hz is not allowed: it is estimated to take " + plausible_number(c.seconds) + " s (" +
      plausible_number(c.steps) + " integrator steps: " + plausible_number(c.mesh_cycles) +
      " mesh cycles at the initial speeds, about " +
      n(60 * std::pow(1e-6 / run.relative_tolerance, 0.19)) + " steps each at relative tolerance " +
      plausible_number(run.relative_tolerance) + ", and " +
      plausible_number(run.duration * run.sample_rate) +
      " samples), more than maximum estimated cost = " + plausible_number(train.maximum_cost) +
      " s; shorten the duration, loosen the relative tolerance, or raise " + where +
      "/Run/maximum estimated cost if you mean to wait for it");
}

// Names: pairs, bodies and shafts that exist, every body in a mesh or on a shaft, given
// inertias, crank geometry, no name twice.
void
check_train_names(const TrainScene &t, const Scene &scene)
{
  const std::string where      = "Train/" + t.name;
  auto              fail       = [&](const std::string &what) { throw InputError(where + what); };
  const auto       &bodies     = t.bodies;
  const auto       &meshes     = t.meshes;
  auto              body_index = [&](const std::string &b) { return t.body_index(b); };
  if (bodies.size() < 2 || bodies.size() > 50)
    fail("/bodies: " + std::to_string(bodies.size()) +
         " bodies is not allowed; name 2 to 50 bodies (each with a subsection in Bodies)");
  if (meshes.empty() || meshes.size() > 50)
    fail("/meshes: " + std::to_string(meshes.size()) +
         " meshes is not allowed; name 1 to 50 meshes (each with a subsection in Meshes)");
  std::set<std::string> in_a_mesh;
  for (const TrainMeshScene &m : meshes)
    {
      const std::string here       = "/Meshes/" + m.name;
      bool              known_pair = false;
      std::string       pair_names;
      for (const PairScene &p : scene.pairs)
        {
          known_pair = known_pair || p.name == m.pair;
          pair_names += (pair_names.empty() ? "" : ", ") + p.name;
        }
      if (!known_pair)
        fail(here + "/pair: '" + m.pair + "' is not allowed; expected a pair of Scene/pairs (" +
             pair_names + ")");
      if (scene.pair(m.pair).type != PairType::involute)
        fail(here + "/pair: '" + m.pair +
             "' is a spiral bevel pair, which is not allowed; a train meshes involute (spur or "
             "helical) pairs on parallel axes");
      for (const auto &[what, body] :
           {std::pair{"pinion body", m.pinion_body}, std::pair{"gear body", m.gear_body}})
        if (body_index(body) < 0)
          {
            std::string names;
            for (const TrainBodyScene &b : bodies)
              names += (names.empty() ? "" : ", ") + b.name;
            fail(here + "/" + what + ": '" + body + "' is not allowed; expected a body of " +
                 where + "/bodies (" + names + ")");
          }
      if (m.pinion_body == m.gear_body)
        fail(here + "/gear body: '" + m.gear_body +
             "' is the pinion body too, which is not allowed; a mesh joins two different bodies");
      in_a_mesh.insert(m.pinion_body);
      in_a_mesh.insert(m.gear_body);
      if (m.backlash > 0 && scene.tca.at(m.pair).centre_distance > 0)
        fail(here + "/backlash: " + number_text(m.backlash / mm) + " mm with TCA/" + m.pair +
             "/centre distance = " + number_text(scene.tca.at(m.pair).centre_distance / mm) +
             " mm is not allowed; give the backlash or the centre distance, not both");
    }
  for (const TrainBodyScene &b : bodies)
    {
      const std::string here = "/Bodies/" + b.name;
      if (b.shaft_to.empty())
        continue;
      if (body_index(b.shaft_to) < 0 || b.shaft_to == b.name)
        {
          std::string names;
          for (const TrainBodyScene &o : bodies)
            if (o.name != b.name)
              names += (names.empty() ? "" : ", ") + o.name;
          fail(here + "/shaft to: '" + b.shaft_to + "' is not allowed; expected another body of " +
               where + "/bodies (" + names + ") or nothing");
        }
      if (!(b.shaft_stiffness > 0))
        fail(here + "/shaft stiffness: " + number_text(b.shaft_stiffness) +
             " N m/rad is not allowed with shaft to = " + b.shaft_to +
             "; expected > 0 (a rigid shaft: one body)");
      in_a_mesh.insert(b.name);
      in_a_mesh.insert(b.shaft_to);
    }
  for (const TrainBodyScene &b : bodies)
    {
      const std::string here = "/Bodies/" + b.name;
      if (!in_a_mesh.count(b.name))
        fail("/bodies: '" + b.name +
             "' is in no mesh and on no shaft, which is not allowed; every body meshes with "
             "another or is joined to one by a shaft");
      if (!b.inertia_auto && !(b.inertia > 0))
        fail(here + "/inertia: " + number_text(b.inertia) +
             " kg m^2 is not allowed; expected a number > 0 or auto");
      if (!b.inertia_auto && b.shaft_inertia > 0)
        fail(here + "/shaft inertia: " + number_text(b.shaft_inertia) +
             " kg m^2 with a given inertia is not allowed; it is added only with inertia = auto "
             "(include it in the inertia)");
      if (b.has_crank)
        {
          const CrankSlider &k = b.crank;
          if (!(k.rod_length > k.crank_radius))
            fail(here + "/Crank slider/rod length: " + number_text(k.rod_length / mm) +
                 " mm is not allowed; expected more than the crank radius " +
                 number_text(k.crank_radius / mm) + " mm");
          if (k.rod_centre > k.rod_length)
            fail(here + "/Crank slider/rod centre: " + number_text(k.rod_centre / mm) +
                 " mm is not allowed; expected at most the rod length " +
                 number_text(k.rod_length / mm) + " mm");
        }
    }
  std::set<std::string> body_names, mesh_names;
  for (const TrainBodyScene &b : bodies)
    if (!body_names.insert(b.name).second)
      fail("/bodies: '" + b.name + "' appears twice; each body needs its own name");
  for (const TrainMeshScene &m : meshes)
    if (!mesh_names.insert(m.name).second)
      fail("/meshes: '" + m.name + "' appears twice; each mesh needs its own name");
  if (!t.reference_body.empty() && body_index(t.reference_body) < 0)
    fail("/reference body: '" + t.reference_body + "' is not allowed; expected a body of " + where +
         "/bodies or nothing");
}

// Centre distances: the teeth reach each other; placed axes agree with them.
void
check_train_centre_distances(const TrainScene &t, const Scene &scene)
{
  const std::string where  = "Train/" + t.name;
  auto              fail   = [&](const std::string &what) { throw InputError(where + what); };
  const auto       &bodies = t.bodies;
  for (const TrainMeshScene &s : t.meshes)
    {
      const std::string here    = "/Meshes/" + s.name;
      const auto [pinion, gear] = scene.pair(s.pair).involute_members();
      const double a            = train_mesh_centre_distance(scene, s);
      const double a_actual     = a + scene.tca.at(s.pair).misalignment.centre_distance_error;
      if (contact_ratios(*pinion, *gear, a_actual).transverse <= 0)
        fail(here + "/backlash: " + number_text(s.backlash / mm) + " mm (centre distance " +
             number_text(a_actual / mm) +
             " mm) is not allowed; the teeth no longer reach each other there (the path of "
             "contact would be empty)");
      const TrainBodyScene &p = bodies[std::size_t(t.body_index(s.pinion_body))];
      const TrainBodyScene &g = bodies[std::size_t(t.body_index(s.gear_body))];
      if (p.placed && g.placed)
        {
          const double axes = std::hypot(g.x - p.x, g.y - p.y);
          if (std::abs(axes - a) > 1e-6)
            fail(here + ": the axes of " + p.name + " and " + g.name + " are " +
                 number_text(axes / mm) + " mm apart (Bodies/<body>/axis position), which is " +
                 "not allowed; the mesh's centre distance is " + number_text(a / mm) +
                 " mm (pair " + s.pair + ", backlash " + number_text(s.backlash / mm) +
                 " mm): expected the same within 1 um");
        }
    }
}

// The run and its spectra: a duration, samples within bounds, a penetration depth with damping,
// a spectrum and a spectrogram window within the run.
void
check_train_run(const TrainScene &t)
{
  const std::string where = "Train/" + t.name;
  auto              fail  = [&](const std::string &what) { throw InputError(where + what); };
  const auto       &run   = t.run;
  if (!(run.duration > 0))
    fail("/Run/duration = " + number_text(run.duration) +
         " s is not allowed; expected a simulated time > 0 s");
  if (run.duration * run.sample_rate > 5e7)
    fail("/Run/sample rate: " + number_text(run.sample_rate) + " Hz over " +
         number_text(run.duration) + " s is not allowed; at most 5e7 samples in a run");
  if (run.anti_alias && run.duration * run.sample_rate < 1 - 1e-9)
    fail("/Run/duration = " + number_text(run.duration) +
         " s is not allowed with anti-alias = true; expected at least one output interval (" +
         number_text(1 / run.sample_rate) + " s at sample rate = " + number_text(run.sample_rate) +
         " Hz)");
  if (t.law.damping > 0 && !(t.law.depth > 0))
    fail("/Contact/penetration depth: 0 with damping is not allowed; expected > 0");
  const double start = t.spectrum_start > 0 ? t.spectrum_start : run.duration / 2;
  if ((run.duration - start) * run.sample_rate < 16)
    fail("/Spectrum/start: " + number_text(t.spectrum_start) +
         " s is not allowed; expected a "
         "time that leaves at least 16 samples before the end of the run (" +
         number_text(run.duration) + " s)");
  if (t.spectrogram_window > 0 &&
      (t.spectrogram_window > run.duration || t.spectrogram_window * run.sample_rate < 4))
    fail("/Spectrum/spectrogram window: " + number_text(t.spectrogram_window / ms) +
         " ms is not allowed; expected at least 4 samples and at most the run (" +
         number_text(run.duration / ms) + " ms), or 0 for none");
}
} // namespace

void
TrainScene::check(const Scene &scene, bool run_wanted, std::vector<std::string> &warnings) const
{
  const std::string where = "Train/" + name;
  auto              fail  = [&](const std::string &what) { throw InputError(where + what); };
  check_train_names(*this, scene);

  // ratios that close, and a speed to start from
  bool numbered = false;
  for (const TrainBodyScene &b : bodies)
    numbered = numbered || !b.kinematic_speed;
  if (!numbered)
    fail("/Bodies: every initial speed is kinematic, which is not allowed; give at least one "
         "body a number (the others follow through the ratios)");
  TrainModel m;
  try
    {
      m = model(scene);
    }
  catch (const InputError &e)
    {
      fail("/meshes: the tooth ratios do not close - " + std::string(e.what()));
    }
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!std::isfinite(m.bodies[i].initial_speed))
      fail("/Bodies/" + bodies[i].name +
           "/initial speed: kinematic is not allowed here; the body is not joined by meshes to "
           "a body with a number (the train falls apart into separate trains)");
  for (const TrainBody &b : m.bodies)
    if (!(b.inertia > 0))
      fail("/Bodies/" + b.name + "/inertia: auto gives " + number_text(b.inertia) +
           " kg m^2, which is not allowed; expected > 0");
  check_constant_speeds(*this, m);
  check_plausibility(scene, m, warnings);
  check_train_centre_distances(*this, scene);
  check_train_run(*this);

  // what the run will cost, before it runs
  if (run_wanted)
    check_cost(*this, m);
}

// Speeds a train's gears cannot run at: the pitch-line velocity at the initial speeds (a
// constant-speed body's for the whole run), and mesh frequencies the samples cannot show.
void
TrainScene::check_plausibility(const Scene &scene, const TrainModel &m,
                               std::vector<std::string> &warnings) const
{
  const std::string where = "Train/" + name;
  // the body whose number the kinematic speeds follow from
  int source = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (!bodies[i].kinematic_speed)
      {
        source = int(i);
        break;
      }
  std::vector<double> gears(bodies.size(), 0); // polar inertia of each body's gears
  for (std::size_t k = 0; k < meshes.size(); ++k)
    {
      const TrainMeshScene &s      = meshes[k];
      const TrainMesh      &mesh   = m.meshes[k];
      const int             driver = mesh.driver;
      const int             named  = bodies[std::size_t(driver)].kinematic_speed ? source : driver;
      const double          w      = std::abs(m.bodies[std::size_t(driver)].initial_speed);
      const auto [pinion, gear]    = scene.pair(s.pair).involute_members();
      gears[std::size_t(driver)] += pinion->mass_properties().polar_inertia;
      gears[std::size_t(mesh.driven)] += gear->mass_properties().polar_inertia;
      const double v     = w * pinion->reference_radius;
      const double given = bodies[std::size_t(named)].initial_speed;
      // As in Dynamics/<pair>/speed to: 200 m/s (turbo gears) warns, 500 m/s (hoop stress
      // rho v^2 = 2 GPa in steel) is refused. rpm typed in the rad/s field is 9.5 times fast.
      check_plausible(
          where + "/Bodies/" + bodies[std::size_t(named)].name +
              "/initial speed = " + number_text(given) + " rad/s",
          v,
          "the pitch-line velocity [m/s] of mesh " + s.name + " (pinion pitch radius " +
              plausible_number(pinion->reference_radius / mm) + " mm, " + plausible_number(w) +
              " rad/s)",
          0, 200, 0, 500,
          {{2 * pi / 60, "rpm typed in a rad/s field (" + number_text(given) +
                             " rpm = " + plausible_number(from_rpm(given)) + " rad/s)"}},
          warnings);
      const double f = mesh.teeth.pinion_teeth * w / (2 * pi);
      if (f > run.sample_rate / 2)
        warnings.push_back(where + "/Run/sample rate = " + number_text(run.sample_rate) +
                           " Hz is unusual: the mesh frequency of mesh " + s.name + " is " +
                           plausible_number(f) + " Hz at the initial speeds, above the " +
                           "Nyquist frequency " + plausible_number(run.sample_rate / 2) +
                           " Hz, so the mesh force spectra cannot show it (" +
                           (run.anti_alias ? "filtered out" : "aliased") +
                           "); plausible: "
                           "a sample rate above " +
                           plausible_number(2 * f * harmonics) + " Hz (" +
                           std::to_string(harmonics) +
                           " harmonics); the run goes on with the value as given");
    }

  // A given inertia against its gears' own (their geometry, as inertia = auto takes it): the
  // body adds its shaft, couplings, a flywheel or a crank, so tens of times the gears' is a
  // real design and a thousand times warns (seed 002's output body: its gear and a shaft
  // inertia of 64 times that, the crank and flywheel); below a third of them the gears alone
  // would be heavier (lightening holes take less); 1e5 times or below 1/300 no design (kg mm^2
  // typed as kg m^2 is 1e6). A shaft inertia (added with auto) likewise, from 0.
  for (std::size_t i = 0; i < bodies.size(); ++i)
    {
      const TrainBodyScene &b      = bodies[i];
      const bool            given  = !b.inertia_auto;
      const double          value  = given ? b.inertia : b.shaft_inertia;
      const std::string     key    = given ? "/inertia = " : "/shaft inertia = ";
      const double          lowest = given ? 1.0 / 300 : 0;
      if (gears[i] > 0 && (given || value > 0))
        check_plausible(where + "/Bodies/" + b.name + key + plausible_number(value) + " kg m^2",
                        value / gears[i],
                        "its ratio to the polar inertia of its gears from their geometry (" +
                            plausible_number(gears[i]) + " kg m^2, Flanks section)",
                        given ? 0.3 : 0, 1000, lowest, 1e5,
                        {{1e-6, "kg mm^2 typed in a kg m^2 field (" + plausible_number(value) +
                                    " kg mm^2 = " + plausible_number(value * 1e-6) + " kg m^2)"},
                         {1e-4, "kg cm^2 typed in a kg m^2 field (" + plausible_number(value) +
                                    " kg cm^2 = " + plausible_number(value * 1e-4) + " kg m^2)"}},
                        warnings);
    }
}
} // namespace gearkit

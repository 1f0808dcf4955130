#include "driver/scene.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <regex>
#include <sstream>

namespace gearkit
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;
namespace fs       = std::filesystem;

namespace
{
constexpr double mm = 1e-3, um = 1e-6, deg = pi / 180;

const char *output_names = "flanks|measured|ste|stiffness|dynamics";

// --- declarations ----------------------------------------------------------------------------

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
                    "[um] C_alpha, parabolic removal at both ends of the active profile.");
  prm.declare_entry("profile slope deviation", "0", Patterns::Double(),
                    "[um] f_Halpha over the active profile; positive adds material at the tip.");
  prm.declare_entry("helix slope deviation", "0", Patterns::Double(),
                    "[um] f_Hbeta over the face width; positive adds material at the +z end.");
  prm.declare_entry("waviness amplitude", "0", Patterns::Double(0),
                    "[um] Amplitude of a sinusoidal profile waviness.");
  prm.declare_entry("waviness wavelength", "0", Patterns::Double(0),
                    "[mm] Wavelength of the profile waviness along the roll length; 0 = none.");
  prm.declare_entry("waviness phase", "0", Patterns::Double(-360, 360),
                    "[deg] Phase of the waviness at the form circle.");
}

void
declare_member(ParameterHandler &prm, const std::string &defaults_teeth)
{
  prm.declare_entry("number of teeth", defaults_teeth, Patterns::Integer(3, 100000),
                    "Number of teeth z.");
  prm.declare_entry("normal module", "3", Patterns::Double(0), "[mm] Normal module m_n.");
  prm.declare_entry("normal pressure angle", "20", Patterns::Double(0, 45),
                    "[deg] Normal pressure angle alpha_n of the basic rack.");
  prm.declare_entry("helix angle", "0", Patterns::Double(0, 60),
                    "[deg] Helix angle beta at the reference circle (0 = spur).");
  prm.declare_entry("hand", "right", Patterns::Selection("right|left"),
                    "Hand of the helix (a pair of external helical gears has opposite hands).");
  prm.declare_entry("profile shift coefficient", "0", Patterns::Double(-3, 3),
                    "Profile shift coefficient x.");
  prm.declare_entry("face width", "20", Patterns::Double(0), "[mm] Face width b.");
  prm.declare_entry("addendum factor", "1", Patterns::Double(0, 3),
                    "h_aP*: tip radius r_a = r + (h_aP* + x) m_n.");
  prm.declare_entry("dedendum factor", "1.25", Patterns::Double(0, 3),
                    "h_fP*: root radius r_f = r - (h_fP* - x) m_n.");
  prm.declare_entry("root radius factor", "0.38", Patterns::Double(0, 1),
                    "rho_fP*: tip radius of the generating rack cutter / m_n; it forms the "
                    "trochoidal root fillet.");
  prm.declare_entry("bore diameter", "0", Patterns::Double(0), "[mm] Bore diameter (0 = solid).");
  prm.declare_entry("density", "7850", Patterns::Double(0), "[kg/m^3] Density of the gear body.");
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

void
declare_measured(ParameterHandler &prm)
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
declare_bevel(ParameterHandler &prm)
{
  prm.declare_entry("pinion teeth", "12", Patterns::Integer(3, 10000), "Pinion teeth z1.");
  prm.declare_entry("gear teeth", "36", Patterns::Integer(3, 10000), "Gear teeth z2.");
  prm.declare_entry("shaft angle", "90", Patterns::Double(1, 179), "[deg] Shaft angle Sigma.");
  prm.declare_entry("module", "6", Patterns::Double(0), "[mm] Module (see module type).");
  prm.declare_entry("module type", "outer transverse",
                    Patterns::Selection("outer transverse|mean normal"),
                    "outer transverse: m_et at the heel; mean normal: m_mn at the mean point.");
  prm.declare_entry("face width", "25.4", Patterns::Double(0), "[mm] Face width F.");
  prm.declare_entry("mean spiral angle", "35", Patterns::Double(0, 60),
                    "[deg] Mean spiral angle beta_m.");
  prm.declare_entry("pressure angle", "20", Patterns::Double(0, 45),
                    "[deg] Normal pressure angle of both sides (blade angle).");
  prm.declare_entry("pinion hand", "left", Patterns::Selection("right|left"),
                    "Hand of spiral of the pinion; the gear has the other.");
  prm.declare_entry("cutter radius", "76.2", Patterns::Double(0),
                    "[mm] Mean radius r_c of the head cutter.");
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
                    "Modified roll 2C of the pinion (used when transmission error amplitude "
                    "is 0).");
  prm.declare_entry("pinion modified roll 6D", "0", Patterns::Double(),
                    "Modified roll 6D of the pinion.");
  prm.declare_entry("transmission error amplitude", "0", Patterns::Double(0),
                    "[urad] Predesigned parabolic transmission error (peak-to-peak over a mesh "
                    "cycle) the pinion's modified roll 2C is synthesised for; 0 = none.");
}

void
declare_tca(ParameterHandler &prm)
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
declare_fe(ParameterHandler &prm)
{
  prm.declare_entry("segment teeth", "7", Patterns::Integer(3, 15),
                    "Teeth in each member's finite-element segment (odd, at least the teeth that "
                    "carry load over the mesh cycle; bore and radial cuts held). Held cuts near "
                    "the loaded teeth stiffen them: 3 teeth overestimate K_m by ~30 %, 5 by "
                    "~10 %, 7 by ~5 % (bench/README.md).");
  prm.declare_entry("hold cuts", "true", Patterns::Bool(),
                    "Hold the segment's radial cut faces (true) or leave them free (false: "
                    "softer than the whole gear; held and free bracket it).");
  prm.declare_entry("flank element size", "0.25", Patterns::Double(0.02, 2),
                    "Element size at the flanks and fillets / m_n.");
  prm.declare_entry("far element size", "1", Patterns::Double(0.05, 10),
                    "Element size toward the bore / m_n.");
  prm.declare_entry("degree", "2", Patterns::Integer(1, 2), "Finite-element degree (FE_Q).");
  prm.declare_entry("other element size", "0", Patterns::Double(0, 2),
                    "[m_n] Element size at the fillets and the flanks of the unloaded side; 0 = "
                    "the flank element size. Only the loaded flanks need fine elements: e.g. "
                    "flank 0.1, other 0.3, response depth 2 is within 1.7 % of the reference "
                    "mode (bench/README.md).");
  prm.declare_entry("response depth", "3", Patterns::Double(1, 20),
                    "Depth below the flank, in flank element sizes, where the finite elements "
                    "are read (they resolve the Boussinesq field there); the half-space part "
                    "above it is analytic.");
  prm.declare_entry("profile grid points", "9", Patterns::Integer(2, 100),
                    "Unit-load points over the profile of each loaded flank.");
  prm.declare_entry("face grid points", "7", Patterns::Integer(2, 100),
                    "Unit-load points over the face of each loaded flank.");
  prm.declare_entry("Young's modulus", "206", Patterns::Double(1),
                    "[GPa] Young's modulus of both members.");
  prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(-0.99, 0.499),
                    "Poisson's ratio of both members.");
}

void
declare_loaded(ParameterHandler &prm)
{
  prm.declare_entry("torques", "100", Patterns::List(Patterns::Double(0), 1),
                    "[N m] Pinion torques (one loaded analysis per torque; the compliances are "
                    "computed once).");
  prm.declare_entry("positions per mesh cycle", "20", Patterns::Integer(1, 10000),
                    "Pinion positions over one mesh cycle.");
  prm.declare_entry("cells across", "17", Patterns::Integer(1, 201),
                    "Contact cells across each contact line (odd: a row on the line).");
  prm.declare_entry("cells along", "24", Patterns::Integer(1, 1000),
                    "Contact cells along each contact line.");
  prm.declare_entry("gap band", "10", Patterns::Double(0.01),
                    "[um] The contact zone reaches where the unloaded gap opens to this; above "
                    "the largest elastic approach.");
  prm.declare_entry("reference positions", "", Patterns::List(Patterns::Integer(0), 0, 1000),
                    "Positions of the mesh cycle (0 = the first) solved again in reference mode "
                    "(spur pairs: both members meshed for the position, finite elements alone, "
                    "minutes per position), with VTU files of displacement and stress in "
                    "<output>/vtu/.");
  prm.declare_entry("reference elements per cell", "0.5", Patterns::Double(0.1, 4),
                    "Reference mode: element size at the contact = cell width / this.");
  prm.declare_entry("measured flanks", "false", Patterns::Bool(),
                    "Also the loaded contact of the measured flanks (Measured flanks section), "
                    "with the theoretical pair's compliances.");
}

void
declare_dynamics(ParameterHandler &prm)
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
  prm.declare_entry("settle cycles", "200", Patterns::Integer(0),
                    "Most mesh cycles to settle at each speed (less when the motion repeats).");
  prm.declare_entry("record cycles", "50", Patterns::Integer(1), "Mesh cycles recorded per speed.");
  prm.declare_entry("steady tolerance", "1e-4", Patterns::Double(0),
                    "Settled when the states at whole excitation periods repeat within this, "
                    "relative to the static mesh deflection; 0: always settle cycles.");
  prm.declare_entry(
      "integrator", "newmark", Patterns::Selection("newmark|cvode bdf|cvode adams"),
      "newmark: fixed steps (the fast path); cvode: adaptive, events at the backlash.");
  prm.declare_entry("steps per mesh cycle", "64", Patterns::Integer(8, 100000), "Newmark.");
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
  prm.declare_entry("spectrum orders", "10", Patterns::Integer(1, 1000),
                    "DTE spectrum per speed up to this mesh order.");
  prm.declare_entry("sweep blocks", "1", Patterns::Integer(1, 100000),
                    "Each sweep in this many blocks of consecutive speeds, run in parallel "
                    "(threads, and MPI processes under mpirun); 1: one continuation.");
  prm.declare_entry("warm-up speeds", "3", Patterns::Integer(0),
                    "Speeds each block but the first starts early to regain the continuation.");
}

void
declare_scene(ParameterHandler &prm)
{
  prm.enter_subsection("Scene");
  prm.declare_entry("name", "", Patterns::Anything(),
                    "Name of the scene; results go to <output root>/<name>/. Empty = the scene "
                    "file name without extension.");
  prm.declare_entry("outputs", "flanks", Patterns::MultipleSelection(output_names),
                    "What to compute; the driver runs only the stages these need.");
  prm.declare_entry("pairs", "pair", Patterns::List(Patterns::Anything(), 1),
                    "Names of the gear pairs in this scene; each has a subsection of that name "
                    "in every stage subsection (letters, digits, _ and -).");
  prm.leave_subsection();
}

void
declare_all(ParameterHandler &prm, const std::vector<std::string> &pairs)
{
  declare_scene(prm);
  prm.enter_subsection("Flanks");
  for (const std::string &pair : pairs)
    {
      prm.enter_subsection(pair);
      prm.declare_entry("grid profile points", "9", Patterns::Integer(2, 10000),
                        "Profile points per flank in the stored flank grids (/flanks).");
      prm.declare_entry("grid face points", "29", Patterns::Integer(2, 10000),
                        "Face points per flank in the stored flank grids (/flanks).");
      prm.declare_entry("type", "involute", Patterns::Selection("involute|spiral bevel"),
                        "involute: spur or helical pair (subsections Pinion, Gear); spiral "
                        "bevel: face-milled spiral bevel pair (subsection Spiral bevel).");
      prm.enter_subsection("Pinion");
      declare_member(prm, "20");
      prm.leave_subsection();
      prm.enter_subsection("Gear");
      declare_member(prm, "40");
      prm.leave_subsection();
      prm.enter_subsection("Spiral bevel");
      declare_bevel(prm);
      prm.leave_subsection();
      prm.leave_subsection();
    }
  prm.leave_subsection();
  prm.enter_subsection("Measured flanks");
  for (const std::string &pair : pairs)
    {
      prm.enter_subsection(pair);
      declare_measured(prm);
      prm.leave_subsection();
    }
  prm.leave_subsection();
  prm.enter_subsection("TCA");
  for (const std::string &pair : pairs)
    {
      prm.enter_subsection(pair);
      declare_tca(prm);
      prm.leave_subsection();
    }
  prm.leave_subsection();
  prm.enter_subsection("Finite elements");
  for (const std::string &pair : pairs)
    {
      prm.enter_subsection(pair);
      declare_fe(prm);
      prm.leave_subsection();
    }
  prm.leave_subsection();
  prm.enter_subsection("Loaded contact");
  for (const std::string &pair : pairs)
    {
      prm.enter_subsection(pair);
      declare_loaded(prm);
      prm.leave_subsection();
    }
  prm.leave_subsection();
  prm.enter_subsection("Dynamics");
  for (const std::string &pair : pairs)
    {
      prm.enter_subsection(pair);
      declare_dynamics(prm);
      prm.leave_subsection();
    }
  prm.leave_subsection();
}

// --- reading ---------------------------------------------------------------------------------

std::vector<std::string>
split_list(const std::string &text)
{
  std::vector<std::string> items;
  std::stringstream        s(text);
  std::string              item;
  while (std::getline(s, item, ','))
    {
      const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
      if (b != std::string::npos)
        items.push_back(item.substr(b, e - b + 1));
    }
  return items;
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
  for (const std::string &v : split_list(prm.get("single pitch deviations")))
    d.single_pitch_deviations.push_back(std::stod(v) * um);
  d.runout = {prm.get_double("runout") * um, prm.get_double("runout phase") * deg};
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

MeasuredScene
get_measured(ParameterHandler &prm, const fs::path &scene_dir, const std::string &pair)
{
  static const std::map<std::string, MeasuredSource> sources = {
      {"none", MeasuredSource::none},
      {"virtual cmm", MeasuredSource::virtual_cmm},
      {"synthesised", MeasuredSource::synthesised},
      {"cmm files", MeasuredSource::cmm_files},
      {"topography files", MeasuredSource::topography_files}};
  MeasuredScene m;
  m.source  = sources.at(prm.get("source"));
  auto path = [&](const char *key) {
    const std::string f = prm.get(key);
    return f.empty() ? f : (scene_dir / f).lexically_normal().string();
  };
  m.pinion_file = path("pinion file");
  m.gear_file   = path("gear file");
  if (m.source == MeasuredSource::cmm_files || m.source == MeasuredSource::topography_files)
    for (const auto &[key, f] :
         {std::pair{"pinion file", m.pinion_file}, {"gear file", m.gear_file}})
      if (f.empty() || !fs::is_regular_file(f))
        throw InputError("Measured flanks/" + pair + ": " + std::string(key) + " = '" + f +
                         "' does not name a readable file (source = " + prm.get("source") + ")");
  m.profile_points = prm.get_integer("profile points");
  m.face_points    = prm.get_integer("face points");
  m.edge_margin    = prm.get_double("edge margin");
  for (const std::string &v : split_list(prm.get("pinion teeth")))
    m.pinion_teeth.push_back(std::stoi(v));
  for (const std::string &v : split_list(prm.get("gear teeth")))
    m.gear_teeth.push_back(std::stoi(v));
  prm.enter_subsection("Synthesis");
  m.seed                = prm.get_integer("seed");
  m.form_error          = prm.get_double("form error") * um;
  m.waviness_amplitude  = prm.get_double("waviness amplitude") * um;
  m.waviness_wavelength = prm.get_double("waviness wavelength") * mm;
  m.roughness           = prm.get_double("roughness") * um;
  m.noise               = prm.get_double("noise") * um;
  m.pitch_error         = prm.get_double("pitch error") * um;
  prm.leave_subsection();
  return m;
}

TcaScene
get_tca(ParameterHandler &prm)
{
  TcaScene t;
  t.options.side = prm.get("working flanks") == "drive" ? FlankSide::drive : FlankSide::coast;
  t.options.positions_per_mesh         = prm.get_integer("positions per mesh cycle");
  t.options.mesh_cycles                = prm.get_integer("mesh cycles");
  t.options.start_angle                = prm.get_double("start angle") * deg;
  t.centre_distance                    = prm.get_double("centre distance") * mm;
  t.misalignment.centre_distance_error = prm.get_double("centre distance error") * um;
  t.misalignment.crossing_angle        = prm.get_double("crossing angle") * 1e-3;
  t.misalignment.intersecting_angle    = prm.get_double("intersecting angle") * 1e-3;
  t.misalignment.pinion_axial_shift    = prm.get_double("pinion axial shift") * mm;
  t.misalignment.gear_axial_shift      = prm.get_double("gear axial shift") * mm;
  t.misalignment.offset                = prm.get_double("offset") * um;
  t.harmonics                          = prm.get_integer("harmonics");
  t.elastic_approach                   = prm.get_double("elastic approach") * um;
  t.measured                           = prm.get_bool("measured flanks");
  t.hunting                            = prm.get_bool("hunting cycle");
  t.paper_mode                         = prm.get("discrete-point method") == "paper";
  t.paper.spacing                      = prm.get_double("paper spacing") * um;
  t.paper.rotation_step                = prm.get_double("paper rotation step") * 1e-6;
  t.paper.tolerance                    = prm.get_double("paper tolerance") * um;
  return t;
}

PairScene
get_bevel(ParameterHandler &prm, PairScene pair)
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
  return pair;
}

// Both members must build (InvoluteGear checks every parameter) and mesh with each other.
void
check_pair(const PairScene &p)
{
  if (p.type == PairType::spiral_bevel)
    {
      try
        {
          bevel_geometry(p.bevel);
        }
      catch (const InputError &e)
        {
          throw InputError("Flanks/" + p.name + "/Spiral bevel: " + e.what());
        }
      return;
    }
  InvoluteGear::create(p.pinion);
  InvoluteGear::create(p.gear);
  const InvoluteGearData &a = p.pinion, &b = p.gear;
  auto                    fail = [&](const std::string &what) {
    throw InputError("Flanks/" + p.name + ": pinion and gear " + what);
  };
  if (std::abs(a.normal_module - b.normal_module) > 1e-12)
    fail("must have the same normal module (" + std::to_string(a.normal_module / mm) + " and " +
         std::to_string(b.normal_module / mm) + " mm)");
  if (std::abs(a.normal_pressure_angle - b.normal_pressure_angle) > 1e-12)
    fail("must have the same normal pressure angle");
  if (std::abs(a.helix_angle - b.helix_angle) > 1e-12)
    fail("must have the same helix angle (external parallel-axis pair)");
  if (a.helix_angle > 0 && a.hand == b.hand)
    fail("must have opposite hands (external helical pair); both are " +
         std::string(a.hand == Hand::right ? "right" : "left"));
}

// deal.II exceptions carry a long report; the user needs the "Additional information" part,
// which names the file, the line and the pattern.
std::string
brief(const dealii::ExceptionBase &e)
{
  std::string       text = e.what();
  const std::string key  = "Additional information:";
  if (const auto p = text.find(key); p != std::string::npos)
    text = text.substr(p + key.size());
  if (const auto p = text.find("Stacktrace:"); p != std::string::npos)
    text = text.substr(0, p);
  std::string out;
  for (char c : text) // collapse whitespace and line breaks
    if (!std::isspace(static_cast<unsigned char>(c)) || (!out.empty() && out.back() != ' '))
      out += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
  while (!out.empty() && (out.back() == ' ' || out.back() == '-'))
    out.pop_back();
  return out;
}

// Top-level "subsection X ... end" blocks of a ShortPRM print, keyed by X.
std::map<std::string, std::string>
section_blocks(const std::string &prm_text)
{
  std::map<std::string, std::string> blocks;
  std::istringstream                 in(prm_text);
  std::string                        line, current, body;
  int                                depth = 0;
  while (std::getline(in, line))
    {
      const auto        b       = line.find_first_not_of(" \t");
      const std::string trimmed = b == std::string::npos ? "" : line.substr(b);
      if (trimmed.rfind("subsection ", 0) == 0)
        {
          if (depth++ == 0)
            {
              current = trimmed.substr(11);
              body.clear();
              continue;
            }
        }
      else if (trimmed == "end" && --depth == 0)
        {
          blocks[current] = body;
          continue;
        }
      if (depth > 0 && !trimmed.empty())
        body += trimmed + "\n";
    }
  return blocks;
}
} // namespace

Scene
read_scene(const std::string &file)
{
  if (!fs::is_regular_file(file))
    throw InputError("scene file " + file + " does not exist or is not a file");
  Scene scene;
  scene.file = file;
  try
    {
      // Pass 1: the scene header only, to learn the pair names that the other sections use.
      ParameterHandler header;
      declare_scene(header);
      header.parse_input(file, "", true);
      header.enter_subsection("Scene");
      std::vector<std::string> pairs = split_list(header.get("pairs"));
      header.leave_subsection();
      static const std::regex identifier("[A-Za-z0-9_-]+");
      for (const std::string &p : pairs)
        if (!std::regex_match(p, identifier))
          throw InputError(file + ": Scene/pairs: the pair name '" + p +
                           "' is not allowed; use letters, digits, _ and -");

      // Pass 2: everything, strictly (unknown entries and bad values are errors).
      ParameterHandler prm;
      declare_all(prm, pairs);
      prm.parse_input(file);

      prm.enter_subsection("Scene");
      scene.name    = prm.get("name");
      scene.outputs = split_list(prm.get("outputs"));
      prm.leave_subsection();
      if (scene.name.empty())
        scene.name = fs::path(file).stem().string();
      if (!std::regex_match(scene.name, identifier))
        throw InputError(file + ": Scene/name: '" + scene.name +
                         "' is not allowed; use letters, digits, _ and -");

      const fs::path dir = fs::path(file).parent_path();
      for (const std::string &p : pairs)
        {
          PairScene pair;
          pair.name = p;
          prm.enter_subsection("Flanks");
          prm.enter_subsection(p);
          pair.grid_profile_points = prm.get_integer("grid profile points");
          pair.grid_face_points    = prm.get_integer("grid face points");
          pair.type =
              prm.get("type") == "spiral bevel" ? PairType::spiral_bevel : PairType::involute;
          prm.enter_subsection("Pinion");
          pair.pinion = get_member(prm, "Flanks/" + p + "/Pinion");
          prm.leave_subsection();
          prm.enter_subsection("Gear");
          pair.gear = get_member(prm, "Flanks/" + p + "/Gear");
          prm.leave_subsection();
          prm.enter_subsection("Spiral bevel");
          pair = get_bevel(prm, pair);
          prm.leave_subsection();
          prm.leave_subsection();
          prm.leave_subsection();
          prm.enter_subsection("Measured flanks");
          prm.enter_subsection(p);
          scene.measured[p] = get_measured(prm, dir, p);
          prm.leave_subsection();
          prm.leave_subsection();
          prm.enter_subsection("TCA");
          prm.enter_subsection(p);
          scene.tca[p] = get_tca(prm);
          TcaScene &t  = scene.tca[p];
          if (t.hunting)
            t.options.mesh_cycles = std::lcm(pair_teeth(pair).first,
                                             pair_teeth(pair).second); // a hunting period
          t.paper.side               = t.options.side;
          t.paper.positions_per_mesh = t.options.positions_per_mesh;
          t.paper.mesh_cycles        = t.options.mesh_cycles;
          t.paper.start_angle        = t.options.start_angle;
          prm.leave_subsection();
          prm.leave_subsection();
          prm.enter_subsection("Finite elements");
          prm.enter_subsection(p);
          FeScene &fe      = scene.fe[p];
          fe.segment_teeth = prm.get_integer("segment teeth");
          if (fe.segment_teeth % 2 == 0)
            throw InputError("Finite elements/" + p +
                             "/segment teeth = " + std::to_string(fe.segment_teeth) +
                             " is not allowed; expected an odd number");
          fe.hold_cuts  = prm.get_bool("hold cuts");
          fe.flank_size = prm.get_double("flank element size");
          fe.far_size   = prm.get_double("far element size");
          fe.other_size = prm.get_double("other element size");
          fe.degree     = unsigned(prm.get_integer("degree"));
          fe.depth      = prm.get_double("response depth");
          fe.n_u        = prm.get_integer("profile grid points");
          fe.n_v        = prm.get_integer("face grid points");
          fe.material   = {prm.get_double("Young's modulus") * 1e9,
                           prm.get_double("Poisson's ratio")};
          prm.leave_subsection();
          prm.leave_subsection();
          prm.enter_subsection("Loaded contact");
          prm.enter_subsection(p);
          LoadedScene &lc = scene.loaded[p];
          lc.torques.clear();
          for (const std::string &t : split_list(prm.get("torques")))
            lc.torques.push_back(std::stod(t));
          lc.positions          = prm.get_integer("positions per mesh cycle");
          lc.cells.cells_across = prm.get_integer("cells across");
          lc.cells.cells_along  = prm.get_integer("cells along");
          lc.cells.gap_band     = prm.get_double("gap band") * 1e-6;
          lc.measured           = prm.get_bool("measured flanks");
          for (const std::string &i : split_list(prm.get("reference positions")))
            {
              lc.reference_positions.push_back(std::stoi(i));
              if (lc.reference_positions.back() >= lc.positions)
                throw InputError("Loaded contact/" + p + "/reference positions: " + i +
                                 " is not a position of the mesh cycle (allowed: 0 to " +
                                 std::to_string(lc.positions - 1) + ")");
            }
          lc.reference_elements_per_cell = prm.get_double("reference elements per cell");
          prm.leave_subsection();
          prm.leave_subsection();
          prm.enter_subsection("Dynamics");
          prm.enter_subsection(p);
          DynamicsScene &d               = scene.dynamics[p];
          d.fe_stiffness                 = prm.get("mesh stiffness source") == "finite elements";
          d.mesh_stiffness               = prm.get_double("mesh stiffness") * 1e6;
          d.stiffness_variation          = prm.get_double("mesh stiffness variation");
          d.torque                       = prm.get_double("pinion torque");
          d.tca_transmission_error       = prm.get("transmission error source") == "tca";
          d.transmission_error_amplitude = prm.get_double("transmission error amplitude") * 1e-6;
          PairModelParameters &mp        = d.model;
          mp.motor_inertia               = prm.get_double("motor inertia");
          mp.speed_controlled_motor      = prm.get("motor") == "speed controlled";
          mp.load_inertia                = prm.get_double("load inertia");
          const double shaft_c           = prm.get_double("shaft damping");
          mp.motor_shaft                 = {prm.get_double("motor shaft stiffness"), shaft_c};
          mp.load_shaft                  = {prm.get_double("load shaft stiffness"), shaft_c};
          const double kb                = prm.get_double("bearing stiffness") * 1e6,
                       cb                = prm.get_double("bearing damping");
          for (const char *member : {"pinion", "gear"})
            {
              BodyParameters   &b  = std::string(member) == "pinion" ? mp.pinion : mp.gear;
              const std::string m  = member;
              b.mass               = prm.get_double(m + " mass");
              b.axial_inertia      = prm.get_double(m + " axial inertia");
              b.transverse_inertia = prm.get_double(m + " transverse inertia");
              b.bearings.clear();
              for (const std::string &x : split_list(prm.get(m + " bearing positions")))
                b.bearings.push_back({std::stod(x) * 1e-3, kb, cb});
              b.axial_stiffness = prm.get_double("axial stiffness") * 1e6;
              b.axial_damping   = cb;
            }
          mp.half_backlash        = prm.get_double("half backlash") * 1e-6;
          mp.mesh_damping_ratio   = prm.get_double("mesh damping ratio");
          d.speed_from            = prm.get_double("speed from") * 2 * pi / 60;
          d.speed_to              = prm.get_double("speed to") * 2 * pi / 60;
          d.speeds                = prm.get_integer("speeds");
          d.settle_cycles         = prm.get_integer("settle cycles");
          d.record_cycles         = prm.get_integer("record cycles");
          d.steady_tolerance      = prm.get_double("steady tolerance");
          const std::string integ = prm.get("integrator");
          d.integrator            = integ == "newmark"     ? Integrator::newmark
                                    : integ == "cvode bdf" ? Integrator::cvode_bdf
                                                           : Integrator::cvode_adams;
          d.steps_per_cycle       = prm.get_integer("steps per mesh cycle");
          const auto excitations  = split_list(prm.get("excitations"));
          auto       has          = [&](const char *what) {
            return std::find(excitations.begin(), excitations.end(), what) != excitations.end();
          };
          d.theoretical       = has("theoretical");
          d.measured          = has("measured");
          d.excitation_cycles = prm.get_integer("excitation cycles");
          for (const std::string &x : split_list(prm.get("time series speeds")))
            d.series_speeds.push_back(std::stod(x) * 2 * pi / 60);
          d.spectrum_orders = prm.get_integer("spectrum orders");
          d.sweep_blocks    = prm.get_integer("sweep blocks");
          d.warmup_speeds   = prm.get_integer("warm-up speeds");
          if (d.measured && !scene.tca[p].measured)
            throw InputError("Dynamics/" + p +
                             "/excitations: measured needs the measured "
                             "flanks' TCA (set TCA/" +
                             p + "/measured flanks = true)");
          if (d.measured && d.excitation_cycles > scene.tca[p].options.mesh_cycles)
            throw InputError(
                "Dynamics/" + p + "/excitation cycles: " + std::to_string(d.excitation_cycles) +
                " is more than the " + std::to_string(scene.tca[p].options.mesh_cycles) +
                " mesh cycles the TCA computes (TCA/" + p + "/mesh cycles)");
          if (!(d.speed_to >= d.speed_from))
            throw InputError("Dynamics/" + p + "/speed to: " + prm.get("speed to") +
                             " rpm is below speed from (" + prm.get("speed from") + " rpm)");
          prm.leave_subsection();
          prm.leave_subsection();
          check_pair(pair);
          scene.pairs.push_back(pair);
        }

      std::ostringstream text;
      prm.print_parameters(text, ParameterHandler::ShortPRM);
      scene.sections = section_blocks(text.str());
    }
  catch (const dealii::ExceptionBase &e)
    {
      throw InputError("scene " + file + ": " + brief(e));
    }
  catch (const InputError &e)
    {
      const std::string what = e.what();
      throw InputError(what.rfind(file, 0) == 0 ? what : "scene " + file + ": " + what);
    }
  return scene;
}

void
print_parameters(std::ostream &out, const std::vector<std::string> &pairs)
{
  // deal.II's PRM listing omits the allowed values and its Description listing the defaults;
  // this one has both and is itself a valid scene file.
  ParameterHandler prm;
  declare_all(prm, pairs);
  std::stringstream json;
  prm.print_parameters(json, ParameterHandler::JSON);
  boost::property_tree::ptree tree;
  boost::property_tree::read_json(json, tree);

  std::function<void(const boost::property_tree::ptree &, int)> print =
      [&](const boost::property_tree::ptree &node, int depth) {
        const std::string indent(2 * depth, ' ');
        for (const auto &[name, child] : node) // entries first, then subsections
          if (child.count("value"))
            out << indent << "# " << child.get<std::string>("documentation") << "\n"
                << indent << "# allowed: " << child.get<std::string>("pattern_description") << "\n"
                << indent << "set " << name << " = " << child.get<std::string>("default_value")
                << "\n\n";
        for (const auto &[name, child] : node)
          if (!child.count("value"))
            {
              out << indent << "subsection " << name << "\n";
              print(child, depth + 1);
              out << indent << "end\n\n";
            }
      };
  out << "# gearkit scene parameters: every entry with its help text, allowed values and default.\n"
      << "# Pair subsections repeat for every name in Scene/pairs (here: the example pair "
         "names).\n\n";
  boost::property_tree::ptree scene_first;
  scene_first.add_child("Scene", tree.get_child("Scene"));
  for (const auto &[name, child] : tree)
    if (name != "Scene")
      scene_first.add_child(name, child);
  print(scene_first, 0);
}
} // namespace gearkit

#include "driver/results_schema.h"

#include "dynamics/sweep.h"
#include "study/misalignment_study.h"
#include "study/modification_grid.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <ostream>
#include <stdexcept>
#include <utility>

namespace gearkit
{
namespace
{
/// A dataset of a group (the group given where the entries are added).
struct Entry
{
  const char *name, *shape, *units;
  std::string description;
};

/// The tables of an unloaded TCA (pair_tca.cc write_tca_tables): ste/<pair>, its measured/, and
/// the dynamics' TCA at the deflected position.
std::vector<Entry>
tca_tables()
{
  return {
      {"centre_distance", "scalar", "m",
       "centre distance of the analysis (with its error added and the offset: the axes' distance "
       "in the face's middle section)"},
      {"pitch_radius", "scalar", "m",
       "pinion radius of transmission_error_pitch: operating pitch radius (parallel axes) or mean "
       "pitch radius (bevel)"},
      {"pinion_angle", "positions", "rad", "pinion rotation phi (counter-clockwise)"},
      {"gear_angle", "positions", "rad", "gear rotation psi in its driven sense"},
      {"transmission_error", "positions", "rad",
       "unloaded static transmission error e_0 = phi - (z2/z1) psi, pinion radians (zero for "
       "perfect involutes at zero backlash)"},
      {"transmission_error_pitch", "positions", "m",
       "e_0 as displacement at the pitch point, e_0 times pitch_radius"},
      {"peak_to_peak", "scalar", "rad", "peak-to-peak of e_0"},
      {"harmonics", "mesh orders (0 .. harmonics)", "m",
       "amplitudes of mesh orders 0..N of e_0 at the pitch point (order 0: mean)"},
      {"shaft_order", "shaft orders", "1",
       "pinion shaft orders of shaft_order_spectrum, k / (pinion revolutions in the hunting "
       "cycle): mesh order m is pinion order m z1, gear order n is pinion order n z1 / z2"},
      {"shaft_order_spectrum", "shaft orders", "m",
       "amplitudes of e_0 at the pitch point over the hunting cycle at the pinion shaft orders in "
       "shaft_order (0 .. z1 x harmonics)"},
      {"pairs_in_contact", "positions, integers", "1", "tooth pairs within the contact tolerance"},
      {"mean_pairs_in_contact", "scalar", "1",
       "mean number of touching pairs (the contact ratio for conjugate flanks)"},
      {"leading", "positions, integers", "1", "pair slot that carries the contact"},
      {"pinion_tooth", "positions x pair slots, integers", "1",
       "pinion tooth of each pair slot (-1: empty)"},
      {"gear_tooth", "positions x pair slots, integers", "1",
       "gear tooth of each pair slot (-1: empty)"},
      {"edge_contact", "positions x pair slots, integers", "1",
       "1 where the closest point lies on a flank edge"},
      {"separation", "positions x pair slots", "m",
       "normal gap of each pair at the gear's position (0 for touching pairs)"},
      {"pinion_u", "positions x pair slots", "1", "pinion flank profile parameter"},
      {"pinion_v", "positions x pair slots", "1", "pinion flank face parameter"},
      {"gear_u", "positions x pair slots", "1", "gear flank profile parameter"},
      {"gear_v", "positions x pair slots", "1", "gear flank face parameter"},
      {"contact_point", "positions x pair slots x 3 (xyz)", "m",
       "contact (closest) point, global frame"},
      {"normal_pinion", "positions x pair slots x 3 (xyz)", "1",
       "n_p: pinion flank outward normal, global"},
      {"normal_gear", "positions x pair slots x 3 (xyz)", "1",
       "n_g: gear flank outward normal, global"},
      {"lambda_pinion", "positions x pair slots x 3 (xyz)", "m",
       "lambda_p = r_p x n_p about the pinion centre"},
      {"lambda_gear", "positions x pair slots x 3 (xyz)", "m",
       "lambda_g = r_g x n_g about the gear centre"},
      {"relative_curvature_min", "positions x pair slots", "1/m",
       "smaller principal relative curvature of the flanks at the contact (0: line contact)"},
      {"relative_curvature_max", "positions x pair slots", "1/m",
       "larger principal relative curvature of the flanks at the contact"},
      {"contact_ellipse_direction", "positions x pair slots x 3 (xyz)", "1",
       "direction of the contact ellipse's major axis (smaller relative curvature), global"},
      {"contact_ellipse_axes", "positions x pair slots x 2 (major, minor)", "m",
       "semi-axes (major, minor) of the contact ellipse at the elastic approach elastic_approach, "
       "sqrt(2 delta / k); 1 m where the contact is a line"},
      {"contact_in_gear_frame", "positions x pair slots x 3 (point, major, minor) x 3 (xyz)", "m",
       "contact point and the contact ellipse's major and minor semi-axis vectors in the gear "
       "member's own frame (axis z), for the contact pattern on the gear flank"},
      {"elastic_approach", "scalar", "m", "elastic approach delta of the contact ellipses"},
  };
}

/// A finite-element compliance table of a member (stage_stiffness.cc run_compliance_stage):
/// compliance/<pair>/<member> and the error estimate's coarse/<member>.
std::vector<Entry>
compliance_table()
{
  return {
      // variant 0: the analytic near field, 1: near field = response depth
      {"compliance", "load points x grid points", "m/N",
       "structural compliance S(i, j) (column-major: load j on the load points, response i on the "
       "grid), {the point-force half-space displacement of the same tooth removed|half-space part "
       "below the response depth removed}"},
      {"teeth", "loaded teeth, integers", "1", "member teeth that can carry load"},
      {"grid_teeth", "teeth with grid points, integers", "1",
       "member teeth with grid points (responses; the compliance's rows)"},
      {"cyclic_tooth", "scalar", "1",
       "-1: unit loads on every tooth that can carry load; else the tooth that alone carries them, "
       "read for every tooth turned"},
      {"cyclic_reach", "scalar", "1",
       "with a cyclic tooth: the teeth either side of it with responses"},
      {"central_tooth", "scalar", "1", "tooth in the middle of the segment"},
      {"hexahedra", "scalar", "1", "elements of the segment mesh"},
      {"dofs", "scalar", "1", "degrees of freedom"},
      {"min_near_field_radius", "scalar", "m",
       "smallest radius within which a unit load's field is analytic"},
      {"response_depth", "scalar", "m", "depth of the finite-element responses"},
      {"shallow_points", "scalar", "1",
       "grid points read at half the chord through the tooth (thinner than twice the response "
       "depth there)"},
      {"min_response_depth", "scalar", "m", "smallest response depth used"},
      {"seconds", "scalar", "s", "mesh, assembly, factorisation and unit-load solves"},
  };
}

/// The loaded contact over one mesh cycle (results_stiffness.cc write_mesh_cycle):
/// stiffness/<pair> and its measured/.
std::vector<Entry>
mesh_cycle()
{
  return {
      {"torque", "torques", "N m", "pinion torques (those solved)"},
      {"refused_torque", "refused torques", "N m",
       "torques of the scene the loaded contact could not solve (attribute "
       "stiffness/<pair>/warnings: why)"},
      {"pinion_angle", "positions", "rad", "pinion rotation phi"},
      {"transmission_error_unloaded", "positions", "rad", "e_0 (pinion radians)"},
      {"transmission_error_loaded", "torques x positions", "rad",
       "e_L per torque and position (pinion radians, gear held)"},
      {"mesh_stiffness", "torques x positions", "N/m", "K_m = F / (lambda (e_L - e_0))"},
      {"normal_force", "torques x positions", "N", "total normal force F"},
      {"lever", "torques x positions", "m", "lambda = torque / F (pinion base radius for spur)"},
      {"pair_force", "torques x positions x pair slots", "N",
       "normal force per pair slot of the unloaded TCA at the same position"},
      {"pinion_tooth", "positions x pair slots, integers", "1",
       "pinion tooth of each pair slot (-1: empty)"},
      {"peak_pressure", "torques x positions", "Pa", "largest cell pressure"},
      {"interior_peak_pressure", "torques x positions", "Pa",
       "largest pressure on cells off the flanks' edges (Hertz's where the flanks are smooth)"},
      {"edge_load_share", "torques x positions", "1",
       "edge contact: force on cells at an edge of either flank (tip, face end, start of the "
       "working flank) / F"},
      {"edge_position", "torques x positions x 2 (radius, axial)", "m",
       "the most loaded edge cell's pinion point: radius, axial position (0: none)"},
      {"gap_band", "torques x positions", "m",
       "the contact zone's band fitted to the load (the zone reaches where the unloaded gap opens "
       "to this)"},
      {"contact_cells", "torques x positions x cells x 4 (tooth, u, v, pressure)", "mixed",
       "per cell: pinion tooth (-1: unused slot), pinion flank u, v, pressure [Pa]"},
      {"mean_pairs_in_contact", "scalar", "1",
       "unloaded contact ratio (eps_gamma for conjugate flanks)"},
  };
}

/// A speed sweep of the pair dynamics (stage_dynamics.cc write_sweep).
std::vector<Entry>
sweep()
{
  // a diverged speed has no results: zeros there, which `status` (or `diverged`) masks
  const std::string none = " (0 where status is 2: diverged, no result)";
  return {
      {"speed", "speeds", "rpm", "pinion speed, in the order swept"},
      {"status", "speeds, integers", "1",
       "per speed: 0 steady (the motion repeats: period), 1 not steady within the settle cycles "
       "(or not checked), 2 diverged (|delta_D - E_t| past " +
           std::to_string(int(SweepOptions().divergence_factor)) +
           " times the static deflection, half backlash and E_t peak-to-peak together, or not "
           "finite: the results at that speed are 0 and no maximum or mean may take them; the next "
           "speed started from the static equilibrium)"},
      {"dte_peak_to_peak", "speeds", "m", "DTE delta_D peak-to-peak" + none},
      {"dte_rms", "speeds", "m", "RMS of delta_D about its mean" + none},
      {"relative_peak_to_peak", "speeds", "m",
       "delta_D - E_t peak-to-peak (the mesh deflection)" + none},
      {"max_mesh_force", "speeds", "N", "largest F_m" + none},
      {"dynamic_load_factor", "speeds", "1", "largest F_m over the static mesh force" + none},
      {"contact_loss", "speeds", "1", "share of the recorded time out of contact" + none},
      {"period", "speeds, integers", "mesh cycles",
       "the motion repeats after (0: not steady, or diverged)"},
      {"settled_cycles", "speeds, integers", "mesh cycles",
       "spent settling (diverged: until then)"},
      {"diverged", "speeds, integers", "1", "1: the response diverged (status 2)"},
      {"diverged_time", "speeds", "s",
       "time run at that speed (settling, records) when the response passed the divergence bound "
       "(0: not diverged)"},
      {"steps_per_cycle", "speeds, integers", "1", "Newmark steps per mesh cycle"},
      {"error_estimate", "speeds", "1",
       "estimated RMS error of delta_D over its RMS (dynamics/newmark_error.h: the larger of the "
       "tables' forcing's and the recorded harmonics')" +
           none},
      {"spectrum_order", "mesh order bins", "1",
       "mesh orders of dte_spectrum (resolution 1 / recorded mesh cycles)"},
      {"dte_spectrum", "speeds x mesh order bins", "m",
       "amplitude of delta_D at each speed and mesh order (order 0: the mean)" + none},
  };
}

/// The schema gathers the groups stage by stage: add(group pattern, its datasets).
using Add = std::function<void(const std::string &, const std::vector<Entry> &)>;

/// Stage flanks (stage_flanks.cc): involute pairs
void
add_flanks(const Add &add)
{
  add("flanks/<involute pair>",
      {
          {"working_pressure_angle", "scalar", "rad",
           "transverse working pressure angle for zero backlash"},
          {"working_centre_distance", "scalar", "m",
           "centre distance for zero backlash, a_w = (r_b1 + r_b2) / cos alpha_wt"},
          {"operating_centre_distance", "scalar", "m",
           "centre distance the pair runs at (TCA: centre distance, or a_w, plus the centre "
           "distance error, with the offset): the active profiles refer to it"},
          {"operating_pressure_angle", "scalar", "rad",
           "transverse pressure angle at the operating centre distance, cos alpha'_t = (r_b1 + "
           "r_b2) / a"},
          {"transverse_contact_ratio", "scalar", "1", "eps_alpha at the operating centre distance"},
          {"overlap_ratio", "scalar", "1", "eps_beta = b sin(beta) / (pi m_n)"},
      });
  add("flanks/<involute pair>/<member>",
      {
          {"number_of_teeth", "scalar, integer", "1", "number of teeth z"},
          {"normal_module", "scalar", "m", "normal module m_n"},
          {"normal_pressure_angle", "scalar", "rad", "normal pressure angle"},
          {"helix_angle", "scalar", "rad",
           "helix angle at the reference circle, positive for a right hand"},
          {"profile_shift", "scalar", "1", "profile shift coefficient x"},
          {"face_width", "scalar", "m", "face width b"},
          {"bore_radius", "scalar", "m", "bore radius (0 = solid)"},
          {"transverse_pressure_angle", "scalar", "rad", "alpha_t"},
          {"reference_radius", "scalar", "m", "r = z m_t / 2"},
          {"base_radius", "scalar", "m", "r_b = r cos alpha_t"},
          {"tip_radius", "scalar", "m", "r_a = r + (h_aP* + x) m_n"},
          {"root_radius", "scalar", "m", "r_f = r - (h_fP* - x) m_n"},
          {"form_radius", "scalar", "m",
           "start of the involute, end of the rack-generated root fillet"},
          {"active_profile_start_radius", "scalar", "m",
           "start of active profile (SAP): the mate's tip circle on the line of action at the "
           "operating centre distance (the form radius where the mate reaches below it)"},
          {"profile_evaluation_range", "2 (start, end)", "m",
           "ISO 1328-1 profile evaluation range of f_Halpha as roll lengths from the base circle: "
           "from the start of active profile over 92 % of the active length"},
          {"base_helix_angle", "scalar", "rad", "beta_b"},
          {"lead", "scalar", "m", "helix lead p_z = 2 pi r / tan beta (0 for spur gears)"},
          {"tooth_thickness_reference", "scalar", "m",
           "transverse arc tooth thickness on the reference circle s_t"},
          {"tip_thickness_normal", "scalar", "m", "normal tooth thickness at the tip s_an"},
          {"undercut", "scalar, integer", "1", "1 if the rack cutter undercuts the involute"},
          {"mass", "scalar", "kg", "mass of the gear body (nominal section minus bore, chips)"},
          {"polar_inertia", "scalar", "kg m^2", "moment of inertia about the axis"},
          {"diametral_inertia", "scalar", "kg m^2",
           "moment of inertia about a diameter through the centre of mass"},
          {"transverse_outline", "outline points x 2 (x, y)", "m",
           "closed nominal transverse outline (x, y) of the whole gear at z = 0, "
           "counter-clockwise, tooth 0 on +x"},
          {"drive_half_profile", "profile points x 2 (x, y)", "m",
           "drive side of tooth 0 at z = 0 from the middle of the root land: root land, fillet, "
           "involute, tip land"},
      });
  add("flanks/<involute pair>/<member>/<side>",
      {
          {"points", "teeth x profile x face x 3 (xyz)", "m",
           "flank points [tooth][profile][face][xyz] in the member frame, with all modifications "
           "and deviations"},
          {"normals", "teeth x profile x face x 3 (xyz)", "1",
           "unit outward normals [tooth][profile][face][xyz]"},
          {"deviation", "teeth x profile x face", "m",
           "flank topography [tooth][profile][face]: modifications and deviations along the "
           "nominal outward normal (positive = material added; runout and pitch included)"},
          {"roll_angle", "profile", "rad", "profile parameter xi of the grid rows"},
          {"z", "face", "m", "axial position of the grid columns"},
      });
  // spiral bevel pairs
  add("flanks/<bevel pair>", {
                                 {"pinion_modified_roll_2c", "scalar", "1",
                                  "the pinion's modified roll 2C (synthesised when a transmission "
                                  "error amplitude is given)"},
                                 {"pitch_angle_pinion", "scalar", "rad", "gamma_1"},
                                 {"pitch_angle_gear", "scalar", "rad", "gamma_2"},
                                 {"shaft_angle", "scalar", "rad", "Sigma"},
                                 {"outer_cone_distance", "scalar", "m", "A_0"},
                                 {"mean_cone_distance", "scalar", "m", "A_m"},
                                 {"outer_transverse_module", "scalar", "m", "m_et"},
                                 {"mean_normal_module", "scalar", "m", "m_mn"},
                                 {"mean_spiral_angle", "scalar", "rad", "beta_m"},
                                 {"nominal_radial_setting", "scalar", "m",
                                  "S_r = sqrt(A_m^2 + r_c^2 - 2 A_m r_c sin beta_m)"},
                                 {"nominal_cradle_angle", "scalar", "rad",
                                  "q = atan(r_c cos beta_m / (A_m - r_c sin beta_m))"},
                             });
  add("flanks/<bevel pair>/<member>",
      {
          {"number_of_teeth", "scalar, integer", "1", "number of teeth"},
          {"pitch_angle", "scalar", "rad", "pitch cone angle"},
          {"face_width", "scalar", "m", "face width F"},
          {"addendum", "scalar", "m", "mean addendum"},
          {"dedendum", "scalar", "m", "mean dedendum"},
          {"mean_pitch_radius", "scalar", "m", "R_m = A_m sin gamma"},
      });
  add("flanks/<bevel pair>/<member>/<side>",
      {
          {"form_height", "scalar", "m",
           "lowest h of the working flank (blade tip or undercut limit)"},
          {"undercut", "scalar, integer", "1",
           "1 if the envelope's edge of regression limits the flank (undercut)"},
          {"points", "teeth x profile x face x 3 (xyz)", "m",
           "flank points [tooth][profile][face][xyz] in the member frame"},
          {"normals", "teeth x profile x face x 3 (xyz)", "1",
           "unit outward normals [tooth][profile][face][xyz]"},
          {"h", "profile", "m", "profile coordinate of the grid rows: height above the pitch cone"},
          {"face", "face", "m", "face coordinate of the grid columns: cone distance minus A_m"},
      });
  add("flanks/<bevel pair>/<member>/<side>/machine",
      {
          {"blade_pitch_radius", "scalar", "m", "blade radius at the pitch plane"},
          {"blade_angle", "scalar", "rad", "blade angle to the cutter axis"},
          {"blade_slope", "scalar", "1", "+1 outside blade, -1 inside blade"},
          {"blade_curvature", "scalar", "1/m", "parabolic blade curvature"},
          {"radial_setting", "scalar", "m", "S_r"},
          {"cradle_angle", "scalar", "rad", "q"},
          {"machine_root_angle", "scalar", "rad", "gamma_m"},
          {"sliding_base", "scalar", "m", "Delta X_B"},
          {"machine_centre_to_back", "scalar", "m", "Delta X_D"},
          {"blank_offset", "scalar", "m", "E_m"},
          {"ratio_of_roll", "scalar", "1", "R_a"},
          {"modified_roll_2c", "scalar", "1", "2C"},
          {"modified_roll_6d", "scalar", "1", "6D"},
      });
}

/// Stage measured (stage_measured.cc)
void
add_measured(const Add &add)
{
  add("measured/<pair>/<member>",
      {
          {"number_of_teeth", "scalar, integer", "1", "number of teeth z"},
      });
  add("measured/<pair>/<member>/tooth_<k>_<side>",
      {
          {"tooth", "scalar, integer", "1", "tooth index"},
          {"points", "profile x face x 3 (xyz)", "m",
           "measured points [profile][face][xyz] in the member frame (axis z; bevel: cone apex at "
           "the origin), profile root to tip, face -z end to +z end (bevel: toe to heel)"},
          {"normals", "profile x face x 3 (xyz)", "1", "unit outward normals (probe directions)"},
          {"deviation", "profile x face", "m",
           "measured minus theoretical flank along the theoretical outward normal (positive = "
           "material added)"},
      });
}

/// Stage ste (stage_ste.cc, pair_tca.cc)
void
add_ste(const Add &add)
{
  add("ste/<pair>", tca_tables());
  add("ste/<pair>/measured", tca_tables());
  add("ste/<pair>/measured",
      {
          {"paper_tolerance", "scalar", "m",
           "contact tolerance E = sqrt((a/2)^2 + (b/2)^2 + (r theta)^2)"},
          {"paper_points", "scalar", "1", "points in all clouds"},
          {"seed_ste", "positions", "rad", "the seed's STE, relative to the first position"},
      });
}

/// Stage compliance (stage_stiffness.cc)
void
add_compliance(const Add &add)
{
  add("compliance/<pair>/<member>", compliance_table());
  add("compliance/<pair>/coarse",
      {
          {"coarsening", "scalar", "1", "element sizes of the coarse mesh / the scene's"},
      });
  add("compliance/<pair>/coarse/<member>", compliance_table());
}

/// Stage stiffness (stage_stiffness.cc)
void
add_stiffness(const Add &add)
{
  add("stiffness/<pair>", mesh_cycle());
  add("stiffness/<pair>",
      {
          {"transverse_contact_ratio", "scalar", "1", "eps_alpha of the geometry"},
          {"overlap_ratio", "scalar", "1", "eps_beta of the geometry"},
          {"iso_c_prime", "scalar", "N/m",
           "ISO 6336-1 method B single stiffness c' times the face width"},
          {"iso_c_gamma_alpha", "scalar", "N/m",
           "ISO 6336-1 method B mesh stiffness c_gamma_alpha times the face width"},
          {"iso_c_th", "scalar", "N/m",
           "ISO 6336-1 theoretical single stiffness c'_th times the face width"},
      });
  add("stiffness/<pair>/error_estimate",
      {
          {"mesh_stiffness", "torques x positions", "N/m", "estimated error of K_m"},
          {"mesh_stiffness_elements", "torques x positions", "N/m", "|K(h) - K(c h)| / (c - 1)"},
          {"mesh_stiffness_cells", "torques x positions", "N/m", "|K(cells) - K(cells / 2)|"},
          {"transmission_error_loaded", "torques x positions", "rad",
           "estimated error of e_L (the same two changes)"},
      });
  add("stiffness/<pair>/reference",
      {
          {"position", "reference positions, integers", "1",
           "index of the position in the mesh cycle"},
          {"pinion_angle", "reference positions", "rad", "pinion rotation phi"},
          {"transmission_error_loaded", "torques x reference positions", "rad",
           "e_L per torque and position (pinion radians, gear held)"},
          {"mesh_stiffness", "torques x reference positions", "N/m",
           "K_m = F / (lambda (e_L - e_0))"},
          {"normal_force", "torques x reference positions", "N", "total normal force F"},
          {"dofs", "reference positions", "1", "degrees of freedom of both members"},
          {"seconds", "reference positions", "s", "mesh, assembly, factorisation, solves"},
      });
  add("stiffness/<pair>/measured", mesh_cycle());
}

/// Stage dynamics (stage_dynamics.cc)
void
add_dynamics(const Add &add)
{
  add("dynamics/<pair>",
      {
          // variant: the first excitation's
          {"mode_frequency", "modes", "Hz",
           "linear modes of the free DOFs at the mean mesh of the {theoretical|measured} "
           "excitation (a torque-driven train: the first is its rigid rotation)"},
          {"mode_mesh_energy", "modes", "1", "share of each mode's strain energy in the mesh"},
          {"pinion_teeth", "scalar", "1", "mesh orders: z_p per pinion turn"},
          {"resonance_speed", "3 (mesh orders 1, 2, 3) x modes", "rpm",
           "pinion speed at which mesh order 1, 2, 3 meets each mode"},
      });
  add("dynamics/<pair>/<excitation>",
      {
          {"static_mesh_force", "scalar", "N", "F_m in the static equilibrium"},
          {"static_deflection", "scalar", "m", "delta_D - E_t - b_c, static"},
          {"load_torque", "scalar", "N m", "T_L balancing the pinion torque"},
          {"excitation_cycles", "scalar", "mesh cycles", "period of the tables"},
          {"wrap_step", "scalar", "m",
           "E_t(period start) - E_t(last sample): the step where the tables wrap"},
      });
  const std::string added =
      "the misalignment the deflection adds to the scene's (TCA/<pair>), as assembly.h defines it";
  add("dynamics/<pair>/<excitation>/deflection",
      {
          {"iterations", "scalar", "1", "TCA runs at a deflected position"},
          {"converged", "scalar", "1",
           "1: the static motion changed by less than 1e-3 of its size in the last iteration"},
          {"change", "iterations", "m",
           "per iteration, the change of the gear's motion: at its body point plus its rotation "
           "times the largest mean moment arm"},
          {"gear_translation", "3 (xyz)", "m",
           "static motion of the gear relative to the pinion: of its point at the global origin"},
          {"gear_rotation", "3 (xyz)", "rad", "static rotation of the gear relative to the pinion"},
          {"offset", "scalar", "m", added},
          {"centre_distance_error", "scalar", "m", added},
          {"crossing_angle", "scalar", "rad", added},
          {"intersecting_angle", "scalar", "rad", added},
          {"pinion_axial_shift", "scalar", "m", added},
          {"gear_axial_shift", "scalar", "m", added},
          {"pattern_shift", "2 (radial, axial)", "m",
           "shift of the mean contact point of the leading pairs on the gear flank, (radial, "
           "axial) in the gear's frame, deflected minus as assembled"},
          {"transmission_error_mean_shift", "scalar", "rad",
           "mean e_0 deflected minus as assembled"},
      });
  add("dynamics/<pair>/<excitation>/deflection/tca", tca_tables());
  add("dynamics/<pair>/<excitation>/stability",
      {
          {"speed", "speeds", "rpm", "pinion speed"},
          {"spectral_radius", "speeds", "1",
           "largest Floquet multiplier modulus of the mesh in contact over one period of the "
           "tables, with Newmark on the steps per mesh cycle the sweeps took at that speed (> 1: "
           "parametric resonance, vibrations grow until contact is lost)"},
          {"unstable", "speeds, integers", "1",
           "1: spectral radius above 1 by more than 1e-6 (undamped, the stable multipliers lie on "
           "the unit circle, and a torque-driven train's rigid rotation gives 1: 1 to rounding; "
           "dynamics/modes.h)"},
      });
  add("dynamics/<pair>/<excitation>/<sweep>", sweep());
  add("dynamics/<pair>/<excitation>/<sweep>/time_series/<k>",
      {
          {"speed", "scalar", "rpm", "pinion speed"},
          {"time", "samples", "s", "from the start of the record (mesh phase 0)"},
          {"dte", "samples", "m", "delta_D"},
          {"transmission_error", "samples", "m", "E_t"},
          {"mesh_force", "samples", "N", "F_m"},
      });
}

/// Stage train (stage_train.cc)
void
add_train(const Add &add)
{
  add("train/<train>",
      {
          {"time", "samples", "s", "sample times"},
          {"inertia", "bodies", "kg m^2",
           "each body's inertia about its axis (a crank-slider's varying part not included)"},
          {"initial_speed", "bodies", "rad/s", "each body's speed at t = 0"},
          {"angle", "bodies x samples", "rad", "body angles (in the sense the train runs forward)"},
          {"speed", "bodies x samples", "rad/s", "body speeds"},
          {"work", "samples", "J",
           "work of the torques (constant-speed drives included) and of a finite-element K_m's "
           "variation"},
          {"kinetic", "samples", "J", "kinetic energy"},
          {"potential", "samples", "J", "elastic energy stored in the contacts"},
          {"dissipated", "samples", "J", "energy dissipated by the contact damping"},
          {"energy_error", "scalar", "1",
           "max |work - kinetic change - potential change - dissipated| over the run, relative to "
           "the largest of the terms"},
          {"steps", "scalar", "1", "CVODE steps"},
          {"events", "scalar", "1",
           "contact changes located (a side's or a tooth pair's touch and separation)"},
          {"seconds", "scalar", "s", "wall time of the run"},
          {"anti_alias", "scalar", "1",
           "1: angles, speeds, S and forces recorded without aliasing (B-spline averages decimated "
           "through a 70 dB low-pass: flat to 0.4 x the sample rate, nothing folds back from above "
           "half of it); 0: the solution's values at the sample times"},
      });
  add("train/<train>/kinematics",
      {
          {"reference_body", "scalar", "1", "index of the body whose speed sets them"},
          {"reference_speed", "scalar", "rad/s", "its mean speed over the spectrum interval"},
          {"shaft_frequency", "bodies", "Hz", "every body's rotation frequency"},
          {"mesh_frequency", "meshes", "Hz",
           "every mesh's tooth mesh frequency (GMF): pinion teeth x its shaft frequency"},
      });
  add("train/<train>/meshes/<mesh>",
      {
          {"centre_distance", "scalar", "m",
           "nominal centre distance (the TCA's centre distance error comes on top)"},
          {"circumferential_backlash", "scalar", "m",
           "of the nominal teeth on the operating pitch circles at that centre distance"},
          {"band_half_width", "scalar", "m",
           "S at drive contact of pairing 0 (minus it at coast contact): half the normal backlash "
           "for perfect flanks"},
          {"pinion_base_radius", "scalar", "m", "r_b1"},
          {"gear_base_radius", "scalar", "m", "r_b2"},
          {"pinion_angle_0", "scalar", "rad", "pinion angle on its body"},
          {"gear_angle_0", "scalar", "rad", "gear angle on its body"},
          {"mesh_stiffness", "positions (one mesh cycle)", "N/m",
           "the stiffness stage's K_m on each side's deepest pair (stiffness = finite elements), "
           "over one mesh cycle"},
          {"mesh_stiffness_pinion_angle", "positions (one mesh cycle)", "rad",
           "its pinion angles phi"},
          {"relative", "samples", "m",
           "S = r_b2 ((z1/z2) phi + c - psi) along the line of action (> 0: pinion ahead; drive "
           "contact at +band_half_width, coast at -band_half_width)"},
          {"force", "samples", "N", "normal force, drive flanks + and coast -"},
          {"force_magnitude", "samples", "N", "drive + coast flanks' force (the spectra's signal)"},
          {"pairs", "samples, integers", "1", "tooth pairs touching"},
          {"impacts", "scalar", "1", "first touches of a side after separation"},
          {"drive_impacts", "scalar", "1", "of them on the drive flanks"},
          {"coast_impacts", "scalar", "1", "of them on the coast flanks"},
          {"first_contact", "scalar", "s", "time of the first touch (-1: none)"},
          {"max_force", "scalar", "N",
           "largest force of a flank side over the continuous solution (at every integrator step's "
           "end and every located root of its rate dF/dt)"},
          {"max_force_time", "scalar", "s", "its time"},
          {"max_penetration", "scalar", "m",
           "deepest penetration of a tooth pair (the curves reach tooth pair recess beyond the "
           "conjugate touch)"},
          {"gmf", "scalar", "Hz", "tooth mesh frequency (kinematics)"},
      });
  add("train/<train>/meshes/<mesh>/contacts",
      {
          {"side", "contacts", "1", "+1 drive flanks, -1 coast flanks"},
          {"touch", "contacts", "s", "located first touch"},
          {"separation", "contacts", "s", "located separation (-1: touching at the end)"},
          {"peak", "contacts", "N", "the side's largest force in the contact (located)"},
          {"peak_time", "contacts", "s", "its time"},
          {"impulse", "contacts", "N s",
           "integral of the side's force over the contact (Simpson's rule on every step piece)"},
      });
  add("train/<train>/meshes/<mesh>/spectrum",
      {
          {"start", "scalar", "s", "the spectrum's record starts here (to the end)"},
          {"resolution", "scalar", "Hz", "bin spacing"},
          {"gmf_sweep", "scalar", "Hz",
           "how far the highest harmonic looked for moves over the record (at most 2 bins: a "
           "spectrum is written only then)"},
          {"amplitude", "bins", "N",
           "single-sided amplitude of the force magnitude (drive + coast flanks, recorded as its "
           "own channel: without aliasing when anti-alias = true; Hann window, mean removed), bins "
           "0, resolution, 2 resolution, ..."},
      });
  add("train/<train>/meshes/<mesh>/spectrum/lines",
      {
          {"expected", "lines", "Hz",
           "where a line is looked for: harmonic x GMF + sideband x the shaft's frequency "
           "(harmonic 0: the shaft's own orders)"},
          {"frequency", "lines", "Hz",
           "the largest bin's frequency within the band around it, interpolated (spectral_peak)"},
          {"amplitude", "lines", "N", "its amplitude"},
          {"floor", "lines", "N", "median amplitude within 10 band widths (the local floor)"},
          {"found", "lines, integers", "1",
           "1: a local maximum inside the band, 4 times above the floor (base/spectrum.h "
           "spectral_line_near)"},
          {"harmonic", "lines, integers", "1", "GMF harmonic (0: shaft orders)"},
          {"sideband", "lines, integers", "1", "sideband order (signed), or the shaft order"},
          {"shaft", "lines, integers", "1", "body index of the shaft frequency (-1: none)"},
      });
  add("train/<train>/spectrogram",
      {
          {"time", "windows", "s", "window centres"},
          {"frequency", "bins", "Hz", "bins"},
          {"amplitude", "windows x bins", "N",
           "amplitude of the first mesh's force magnitude per window (Hamming) and frequency"},
      });
}

/// Stage study (stage_study.cc): the micro-geometry map
void
add_study(const Add &add)
{
  add("study/<pair>",
      {
          {"torques", "torques", "N m", "pinion torques of the map, ascending"},
          {"design_torque", "scalar", "N m", "the torque the design is for (0: none)"},
          {"pitch_radius", "scalar", "m",
           "operating pitch radius of the pinion: TE [rad] times it is the TE at the pitch circle"},
          {"shape", "parameters, integers", "1", "values of each axis of the grid, in order"},
          {"grid", "variants x parameters", "m",
           "each variant's parameter values (the first axis slowest; misalignment angles in "
           "rad)"},
          {"te_peak_to_peak", "variants x torques", "rad",
           "loaded TE e_L peak-to-peak over the positions (pinion radians)"},
          {"unloaded_te_peak_to_peak", "variants", "rad", "unloaded TE e_0 peak-to-peak"},
          {"te_harmonics", "variants x torques x harmonics", "rad",
           "amplitudes of mesh orders 1..H of e_L"},
          {"stiffness_mean", "variants x torques", "N/m", "K_m mean over the mesh cycle"},
          {"stiffness_range", "variants x torques", "N/m", "K_m max - min over the mesh cycle"},
          {"max_pressure", "variants x torques", "Pa", "largest cell pressure over the cycle"},
          {"max_interior_pressure", "variants x torques", "Pa",
           "largest pressure on cells off the flanks' edges over the cycle (Hertz's where the "
           "flanks are smooth; at a flank edge the cell pressure depends on the cells' layout)"},
          {"max_edge_share", "variants x torques", "1",
           "largest share of the load on cells at a flank edge (edge contact)"},
          {"zone_edge", "variants x torques, integers", "1",
           "1 where a contact reached the edge of its fixed zone at some position (too narrow: "
           "the variant's results at that torque are not valid)"},
          {"pinion_angle", "positions", "rad", "pinion rotation phi of each position"},
          {"unloaded_te", "variants x positions", "rad", "e_0 of each variant"},
          {"loaded_te", "variants x torques x positions", "rad", "e_L of each variant"},
          {"mesh_stiffness", "variants x torques x positions", "N/m",
           "K_m = F / (lambda (e_L - e_0)) of each variant"},
          {"best_variant", "torques, integers", "1",
           "the valid variant of least TE peak-to-peak at each torque (-1: none)"},
          {"unmodified_variant", "scalar, integer", "1",
           "the variant without modifications on either member (-1: none in the grid)"},
          {"iso_c_gamma_alpha", "scalar", "N/m",
           "ISO 6336-1 method B mesh stiffness c_gamma_alpha times the face width"},
          {"classical_relief_iso", "scalar", "m",
           "the classical tip relief F_bt / (b c_gamma_alpha) at the design torque (ISO 6336-1)"},
          {"mesh_deflection_design", "scalar", "m",
           "F_bt / K_m mean of the grid's variant without modifications at the design torque"},
          {"best_relief_design", "scalar", "m",
           "the relief of least TE peak-to-peak at the design torque: a parabola through the "
           "grid's best value and its neighbours"},
      });
  // the tolerance Monte Carlo (kind tolerances): its variants are the samples
  add("study/<pair>",
      {
          {"features", "variants x features", "m",
           "each sample's deviations summed up per member (attribute features: their names)"},
          {"percentile_levels", "levels", "%", "the percentiles reported (5, 50, 95)"},
          {"convergence_samples", "counts", "1",
           "the sample counts the percentiles' convergence is shown at (the first n samples)"},
      });
  std::vector<Entry> nominal, percentiles, convergence;
  for (const auto &[name, units] : {std::pair{"te_peak_to_peak", "rad"},
                                    {"stiffness_mean", "N/m"},
                                    {"stiffness_range", "N/m"},
                                    {"max_pressure", "Pa"},
                                    {"max_interior_pressure", "Pa"},
                                    {"max_edge_share", "1"}})
    {
      nominal.push_back(
          {name, "torques", units, std::string(name) + " of the design without deviations"});
      percentiles.push_back(
          {name, "torques x levels", units, std::string("the samples' percentiles of ") + name});
      convergence.push_back({name, "torques x counts x levels", units,
                             std::string("the percentiles of the first n samples of ") + name});
    }
  add("study/<pair>/nominal", nominal);
  add("study/<pair>/percentiles", percentiles);
  add("study/<pair>/convergence", convergence);
  add("study/<pair>/sensitivity/<output>",
      {
          {"coefficient", "torques x features", "1",
           "standardized regression coefficient of the output on each feature"},
          {"low", "torques x features", "1", "its 95 % bootstrap interval's lower end"},
          {"high", "torques x features", "1", "its 95 % bootstrap interval's upper end"},
          {"r2", "torques", "1", "the linear model's coefficient of determination"},
      });
  // the misalignment (V-H) check (kind misalignments): its variants are the grid's assemblies
  add("study/<pair>",
      {
          {"tca_pinion_angle", "tca positions", "rad",
           "pinion rotation of the unloaded TCA's positions (the TCA section's)"},
          {"tca_unloaded_te", "variants x tca positions", "rad", "e_0 at the TCA's positions"},
          {"contact_path", "variants x tca positions x 2", "m",
           "the leading pair's unloaded contact point on the gear flank: (profile, face) lengths "
           "(spiral bevel: height above the pitch cone, cone distance - A_m; involute: roll "
           "length, z)"},
          {"path_centre", "variants x 2", "m", "the contact path's mean point (profile, face)"},
          {"pattern", "variants x torques x profile bins x face bins", "Pa",
           "the loaded contact pattern: the largest cell pressure over the mesh cycle in each bin "
           "of the gear flank"},
          {"pattern_profile_range", "2", "m", "the raster's extent along the profile"},
          {"pattern_face_range", "2", "m", "the raster's extent along the face"},
          {"pattern_centre", "variants x torques x 2", "m",
           "the pressure-weighted centre of the loaded cells (profile, face)"},
          {"pattern_extent", "variants x torques x 4", "m",
           "the loaded cells' extent: profile min, max, face min, max"},
      });
  std::vector<Entry> axes;
  for (const std::string &field : modification_field_names())
    axes.push_back({field.c_str(), "values", "m", "the values of this axis of the grid"});
  for (const std::string &field : misalignment_field_names())
    axes.push_back({field.c_str(), "values", field.find("angle") != std::string::npos ? "rad" : "m",
                    "the values of this misalignment axis of the grid"});
  add("study/<pair>/axes", axes);
}

std::vector<ResultDataset>
schema()
{
  std::vector<ResultDataset> all;
  const Add add = [&all](const std::string &group, const std::vector<Entry> &entries) {
    for (const Entry &e : entries)
      all.push_back({group, e.name, e.shape, e.units, e.description});
  };
  add_flanks(add);
  add_measured(add);
  add_ste(add);
  add_compliance(add);
  add_stiffness(add);
  add_dynamics(add);
  add_train(add);
  add_study(add);
  return all;
}
} // namespace

const std::vector<ResultDataset> &
results_schema()
{
  static const std::vector<ResultDataset> all = schema();
  return all;
}

const ResultDataset &
result_dataset(const std::string &group, const std::string &name)
{
  static const std::map<std::pair<std::string, std::string>, const ResultDataset *> index = [] {
    std::map<std::pair<std::string, std::string>, const ResultDataset *> i;
    for (const ResultDataset &d : results_schema())
      i.emplace(std::pair{d.group, d.name}, &d);
    return i;
  }();
  if (const auto found = index.find({group, name}); found != index.end())
    return *found->second;
  throw std::logic_error("results schema: no dataset '" + name + "' in group '" + group +
                         "' (every dataset written needs its entry in driver/results_schema.cc)");
}

std::size_t
result_rank(const ResultDataset &d)
{
  if (d.shape.rfind("scalar", 0) == 0)
    return 0;
  std::size_t rank = 1;
  for (std::size_t at = d.shape.find(" x "); at != std::string::npos;
       at             = d.shape.find(" x ", at + 3))
    ++rank;
  return rank;
}

bool
result_integers(const ResultDataset &d)
{
  for (const std::string end : {", integer", ", integers"})
    if (d.shape.size() >= end.size() &&
        d.shape.compare(d.shape.size() - end.size(), end.size(), end) == 0)
      return true;
  return false;
}

std::string
result_description(const ResultDataset &d, int variant)
{
  const std::string &text = d.description;
  const auto         open = text.find('{'), close = text.find('}');
  const std::string  where = "results schema: " + d.group + "/" + d.name + ": ";
  if (open == std::string::npos)
    {
      if (variant != -1)
        throw std::logic_error(where + "written with variant " + std::to_string(variant) +
                               ", but its description offers no choice");
      return text;
    }
  std::vector<std::string> alternatives(1);
  for (std::size_t i = open + 1; i < close; ++i)
    if (text[i] == '|')
      alternatives.emplace_back();
    else
      alternatives.back() += text[i];
  if (variant < 0 || std::size_t(variant) >= alternatives.size())
    throw std::logic_error(where + "written with variant " + std::to_string(variant) +
                           ", but its description offers " + std::to_string(alternatives.size()) +
                           " alternatives");
  return text.substr(0, open) + alternatives[std::size_t(variant)] + text.substr(close + 1);
}

std::vector<std::string>
result_descriptions(const ResultDataset &d)
{
  if (d.description.find('{') == std::string::npos)
    return {d.description};
  std::vector<std::string> all;
  const auto               close = d.description.find('}');
  for (int v = 0;
       v <= int(std::count(d.description.begin(), d.description.begin() + long(close), '|')); ++v)
    all.push_back(result_description(d, v));
  return all;
}

namespace
{
std::string
json_string(const std::string &s)
{
  std::string out = "\"";
  for (const char c : s)
    if (c == '"' || c == '\\')
      out += std::string("\\") + c;
    else if (static_cast<unsigned char>(c) < 0x20)
      {
        char code[8];
        std::snprintf(code, sizeof code, "\\u%04x", c);
        out += code;
      }
    else
      out += c;
  return out + "\"";
}
} // namespace

void
print_results_schema(std::ostream &out, const std::string &format)
{
  const std::vector<ResultDataset> &all = results_schema();
  if (format == "json")
    {
      out << "[\n";
      for (std::size_t i = 0; i < all.size(); ++i)
        {
          const ResultDataset &d = all[i];
          out << "  {\"group\": " << json_string(d.group)
              << ", \"dataset\": " << json_string(d.name) << ", \"shape\": " << json_string(d.shape)
              << ", \"units\": " << json_string(d.units)
              << ", \"description\": " << json_string(d.description) << "}"
              << (i + 1 < all.size() ? "," : "") << "\n";
        }
      out << "]\n";
      return;
    }
  if (format != "table")
    throw std::invalid_argument("results schema: format '" + format +
                                "' is not known; expected table or json");
  std::size_t widths[4] = {5, 7, 5, 5}; // the headings' lengths
  for (const ResultDataset &d : all)
    for (const auto &[k, text] :
         {std::pair{0, &d.group}, {1, &d.name}, {2, &d.shape}, {3, &d.units}})
      widths[k] = std::max(widths[k], text->size());
  const auto row = [&](const std::string &group, const std::string &name, const std::string &shape,
                       const std::string &units, const std::string &description) {
    const std::string *cells[4] = {&group, &name, &shape, &units};
    for (int k = 0; k < 4; ++k)
      out << *cells[k] << std::string(widths[k] + 2 - cells[k]->size(), ' ');
    out << description << "\n";
  };
  row("group", "dataset", "shape", "units", "description");
  for (const ResultDataset &d : all)
    row(d.group, d.name, d.shape, d.units, d.description);
}
} // namespace gearkit

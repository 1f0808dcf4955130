// Stage "flanks": the nominal geometry of every member, its transverse outline, flank grids of
// every tooth and side (with modifications and deviations), and mass properties.
#include "driver/stages.h"
#include "tca/bevel_synthesis.h"

#include <cmath>
#include <ostream>

namespace gearkit
{
namespace
{
std::vector<double>
flatten(const std::vector<Vec2> &points)
{
  std::vector<double> v;
  for (const Vec2 &p : points)
    v.insert(v.end(), {p.x(), p.y()});
  return v;
}

void
write_member(const InvoluteGear &g, int n_u, int n_v, const H5Group &out, std::ostream &log,
             Progress &progress)
{
  const InvoluteGearData &d = g.data();
  out.write("number_of_teeth", std::vector<int>{d.teeth}, {}, "1", "number of teeth z");
  out.write("normal_module", d.normal_module, "m", "normal module m_n");
  out.write("normal_pressure_angle", d.normal_pressure_angle, "rad", "normal pressure angle");
  out.write("helix_angle", g.helix_sign * d.helix_angle, "rad",
            "helix angle at the reference circle, positive for a right hand");
  out.write("profile_shift", d.profile_shift, "1", "profile shift coefficient x");
  out.write("face_width", d.face_width, "m", "face width b");
  out.write("bore_radius", d.bore_diameter / 2, "m", "bore radius (0 = solid)");
  out.write("transverse_pressure_angle", g.transverse_pressure_angle, "rad", "alpha_t");
  out.write("reference_radius", g.reference_radius, "m", "r = z m_t / 2");
  out.write("base_radius", g.base_radius, "m", "r_b = r cos alpha_t");
  out.write("tip_radius", g.tip_radius, "m", "r_a = r + (h_aP* + x) m_n");
  out.write("root_radius", g.root_radius, "m", "r_f = r - (h_fP* - x) m_n");
  out.write("form_radius", g.form_radius, "m",
            "start of the involute, end of the rack-generated root fillet");
  out.write("active_profile_start_radius", d.active_profile_start_radius, "m",
            "start of active profile (SAP): the mate's tip circle on the line of action at the "
            "operating centre distance (the form radius where the mate reaches below it)");
  const auto [L0, L1] = profile_evaluation_range(g.modification_frame());
  out.write("profile_evaluation_range", std::vector<double>{L0, L1}, {2}, "m",
            "ISO 1328-1 profile evaluation range of f_Halpha as roll lengths from the base "
            "circle: from the start of active profile over 92 % of the active length");
  out.write("base_helix_angle", g.base_helix_angle, "rad", "beta_b");
  out.write("lead", g.lead, "m", "helix lead p_z = 2 pi r / tan beta (0 for spur gears)");
  out.write("tooth_thickness_reference", g.tooth_thickness_reference, "m",
            "transverse arc tooth thickness on the reference circle s_t");
  out.write("tip_thickness_normal", g.checks().tip_thickness_normal, "m",
            "normal tooth thickness at the tip s_an");
  out.write("undercut", std::vector<int>{g.checks().undercut ? 1 : 0}, {}, "1",
            "1 if the rack cutter undercuts the involute");
  std::string warnings;
  for (const std::string &w : g.checks().warnings)
    {
      log << "  warning: " << w << "\n";
      warnings += w + "\n";
    }
  out.attribute("warnings", warnings);

  const MassProperties mp = g.mass_properties();
  out.write("mass", mp.mass, "kg", "mass of the gear body (nominal section minus bore, chips)");
  out.write("polar_inertia", mp.polar_inertia, "kg m^2", "moment of inertia about the axis");
  out.write("diametral_inertia", mp.diametral_inertia, "kg m^2",
            "moment of inertia about a diameter through the centre of mass");

  const std::vector<Vec2> outline = g.transverse_outline(40);
  out.write("transverse_outline", flatten(outline), {outline.size(), 2}, "m",
            "closed nominal transverse outline (x, y) of the whole gear at z = 0, "
            "counter-clockwise, tooth 0 on +x");
  const std::vector<Vec2> half = g.half_tooth_profile(40);
  out.write("drive_half_profile", flatten(half), {half.size(), 2}, "m",
            "drive side of tooth 0 at z = 0 from the middle of the root land: root land, "
            "fillet, involute, tip land");

  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      const H5Group       s = out.group(to_string(side));
      std::vector<double> points, normals, deviation, u, v;
      for (int k = 0; k < d.teeth; ++k)
        {
          const InvoluteFlank flank = g.flank(k, side);
          const FlankGrid     grid  = sample_flank(flank, n_u, n_v);
          for (std::size_t i = 0; i < grid.positions.size(); ++i)
            {
              points.insert(points.end(), grid.positions[i].data(), grid.positions[i].data() + 3);
              normals.insert(normals.end(), grid.normals[i].data(), grid.normals[i].data() + 3);
              const FlankPoint nominal = flank.nominal(grid.u[i / n_v], grid.v[i % n_v]);
              deviation.push_back((grid.positions[i] - nominal.position).dot(nominal.normal));
            }
          u = grid.u;
          v = grid.v;
          progress.advance();
        }
      const std::vector<hsize_t> shape = {hsize_t(d.teeth), hsize_t(n_u), hsize_t(n_v), 3};
      s.write("points", points, shape, "m",
              "flank points [tooth][profile][face][xyz] in the member frame, with all "
              "modifications and deviations");
      s.write("normals", normals, shape, "1", "unit outward normals [tooth][profile][face][xyz]");
      s.write("deviation", deviation, {shape[0], shape[1], shape[2]}, "m",
              "flank topography [tooth][profile][face]: modifications and deviations along the "
              "nominal outward normal (positive = material added; runout and pitch included)");
      s.write("roll_angle", u, {u.size()}, "rad", "profile parameter xi of the grid rows");
      s.write("z", v, {v.size()}, "m", "axial position of the grid columns");
    }
}

/// Flank grids [tooth][profile][face] of every tooth and side of a member, with the grid axes.
void
write_grids(const MemberFlanks &m, int n_u, int n_v, const H5Group &out, const char *u_name,
            const char *u_unit, const char *u_text, const char *v_name, const char *v_text,
            Progress &progress)
{
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      const H5Group       s = out.group(to_string(side));
      std::vector<double> points, normals, u, v;
      for (int k = 0; k < m.teeth(); ++k)
        {
          const FlankGrid grid = sample_flank(m.flank(k, side), n_u, n_v);
          for (std::size_t i = 0; i < grid.positions.size(); ++i)
            {
              points.insert(points.end(), grid.positions[i].data(), grid.positions[i].data() + 3);
              normals.insert(normals.end(), grid.normals[i].data(), grid.normals[i].data() + 3);
            }
          u = grid.u, v = grid.v;
          progress.advance();
        }
      const std::vector<hsize_t> shape = {hsize_t(m.teeth()), hsize_t(n_u), hsize_t(n_v), 3};
      s.write("points", points, shape, "m",
              "flank points [tooth][profile][face][xyz] in the member frame");
      s.write("normals", normals, shape, "1", "unit outward normals [tooth][profile][face][xyz]");
      s.write(u_name, u, {u.size()}, u_unit, u_text);
      s.write(v_name, v, {v.size()}, "m", v_text);
    }
}

void
write_machine(const Blade &b, const MachineSettings &m, const H5Group &g)
{
  g.write("blade_pitch_radius", b.pitch_radius, "m", "blade radius at the pitch plane");
  g.write("blade_angle", b.angle, "rad", "blade angle to the cutter axis");
  g.write("blade_slope", double(b.slope), "1", "+1 outside blade, -1 inside blade");
  g.write("blade_curvature", b.curvature, "1/m", "parabolic blade curvature");
  g.write("radial_setting", m.radial_setting, "m", "S_r");
  g.write("cradle_angle", m.cradle_angle, "rad", "q");
  g.write("machine_root_angle", m.root_angle, "rad", "gamma_m");
  g.write("sliding_base", m.sliding_base, "m", "Delta X_B");
  g.write("machine_centre_to_back", m.machine_centre_to_back, "m", "Delta X_D");
  g.write("blank_offset", m.blank_offset, "m", "E_m");
  g.write("ratio_of_roll", m.ratio_of_roll, "1", "R_a");
  g.write("modified_roll_2c", m.modified_roll_2c, "1", "2C");
  g.write("modified_roll_6d", m.modified_roll_6d, "1", "6D");
}

void
write_bevel_pair(const PairScene &pair, const H5Group &pg, std::ostream &log, Progress &progress)
{
  const BevelPairDesign  &d = pair.bevel;
  const BevelPairGeometry g = bevel_geometry(d);
  const NominalSettings   n = nominal_settings(d);
  PinionMismatch          m = pair.mismatch;
  if (pair.transmission_error_amplitude > 0)
    {
      m = synthesise_modified_roll(d, m, pair.transmission_error_amplitude);
      log << "  " << pair.name << ": modified roll 2C = " << m.modified_roll_2c
          << " for a transmission error of " << pair.transmission_error_amplitude * 1e6
          << " urad\n";
    }
  pg.attribute("type", "spiral bevel");
  pg.write("pinion_modified_roll_2c", m.modified_roll_2c, "1",
           "the pinion's modified roll 2C (synthesised when a transmission error amplitude is "
           "given)");
  pg.write("pitch_angle_pinion", g.pitch_angle_pinion, "rad", "gamma_1");
  pg.write("pitch_angle_gear", g.pitch_angle_gear, "rad", "gamma_2");
  pg.write("shaft_angle", d.shaft_angle, "rad", "Sigma");
  pg.write("outer_cone_distance", g.outer_cone_distance, "m", "A_0");
  pg.write("mean_cone_distance", g.mean_cone_distance, "m", "A_m");
  pg.write("outer_transverse_module", g.outer_transverse_module, "m", "m_et");
  pg.write("mean_normal_module", g.mean_normal_module, "m", "m_mn");
  pg.write("mean_spiral_angle", d.mean_spiral_angle, "rad", "beta_m");
  pg.write("nominal_radial_setting", n.radial_setting, "m",
           "S_r = sqrt(A_m^2 + r_c^2 - 2 A_m r_c sin beta_m)");
  pg.write("nominal_cradle_angle", n.cradle_angle, "rad",
           "q = atan(r_c cos beta_m / (A_m - r_c sin beta_m))");
  const auto [pc, gc] = mismatched_cuts(d, m);
  for (const auto &[name, cut] : {std::pair{"pinion", pc}, {"gear", gc}})
    {
      const H5Group           mg = pg.group(name);
      const BevelMemberFlanks flanks(cut);
      mg.write("number_of_teeth", std::vector<int>{cut.blank.teeth}, {}, "1", "number of teeth");
      mg.write("pitch_angle", cut.blank.pitch_angle, "rad", "pitch cone angle");
      mg.write("face_width", cut.blank.face_width, "m", "face width F");
      mg.write("addendum", cut.blank.addendum, "m", "mean addendum");
      mg.write("dedendum", cut.blank.dedendum, "m", "mean dedendum");
      mg.write("mean_pitch_radius", cut.blank.mean_cone_distance * std::sin(cut.blank.pitch_angle),
               "m", "R_m = A_m sin gamma");
      mg.attribute("drive_flank", flanks.concave_drives() ? "concave" : "convex");
      for (FlankSide side : {FlankSide::drive, FlankSide::coast})
        {
          const bool    outside = (side == FlankSide::drive) == flanks.concave_drives();
          const H5Group sg      = mg.group(to_string(side));
          write_machine(outside ? cut.outside_blade : cut.inside_blade,
                        outside ? cut.outside_machine : cut.inside_machine, sg.group("machine"));
          const GeneratedFlank &f = flanks.tooth_flank(side);
          sg.write("form_height", f.domain().u_min, "m",
                   "lowest h of the working flank (blade tip or undercut limit)");
          sg.write("undercut", std::vector<int>{f.undercut_found() ? 1 : 0}, {}, "1",
                   "1 if the envelope's edge of regression limits the flank (undercut)");
          if (f.undercut_found())
            log << "  warning: " << pair.name << " " << name << " " << to_string(side)
                << " flank is undercut; the working flank starts at h = " << f.domain().u_min * 1e3
                << " mm\n";
        }
      write_grids(flanks, pair.grid_profile_points, pair.grid_face_points, mg, "h", "m",
                  "profile coordinate of the grid rows: height above the pitch cone", "face",
                  "face coordinate of the grid columns: cone distance minus A_m", progress);
    }
}
} // namespace

void
run_flanks_stage(const Scene &scene, const Upstream &, const H5Group &out, std::ostream &log)
{
  std::size_t total = 0;
  for (const PairScene &pair : scene.pairs)
    total += 2 * (pair_teeth(pair).first + pair_teeth(pair).second);
  Progress progress("flanks", total);
  for (const PairScene &pair : scene.pairs)
    {
      const H5Group pg = out.group(pair.name);
      if (pair.type == PairType::spiral_bevel)
        {
          try // (the modified roll's synthesis runs the TCA; its errors name the pair)
            {
              write_bevel_pair(pair, pg, log, progress);
            }
          catch (const InputError &e)
            {
              throw InputError("Flanks/" + pair.name + "/Spiral bevel: " + e.what());
            }
          continue;
        }
      pg.attribute("type", "involute");
      // The flanks as the pair runs: what is defined on the active profile (the start of active
      // profile, f_Halpha's evaluation range) at the centre distance of its contact analysis.
      // The stages after this one build the members with the starts stored here
      // (theoretical_members).
      const double a            = pair.operating_centre_distance(scene.tca.at(pair.name));
      const auto [pinion, gear] = pair.involute_members(a);
      write_member(*pinion, pair.grid_profile_points, pair.grid_face_points, pg.group("pinion"),
                   log, progress);
      write_member(*gear, pair.grid_profile_points, pair.grid_face_points, pg.group("gear"), log,
                   progress);
      pg.write("working_pressure_angle", working_pressure_angle(*pinion, *gear), "rad",
               "transverse working pressure angle for zero backlash");
      pg.write("working_centre_distance", working_centre_distance(*pinion, *gear), "m",
               "centre distance for zero backlash, a_w = (r_b1 + r_b2) / cos alpha_wt");
      pg.write("operating_centre_distance", a, "m",
               "centre distance the pair runs at (TCA: centre distance, or a_w, plus the centre "
               "distance error, with the offset): the active profiles refer to it");
      pg.write("operating_pressure_angle", std::acos((pinion->base_radius + gear->base_radius) / a),
               "rad",
               "transverse pressure angle at the operating centre distance, cos alpha'_t = (r_b1 "
               "+ r_b2) / a");
      const ContactRatios eps = contact_ratios(*pinion, *gear, a);
      pg.write("transverse_contact_ratio", eps.transverse, "1",
               "eps_alpha at the operating centre distance");
      pg.write("overlap_ratio", eps.overlap, "1", "eps_beta = b sin(beta) / (pi m_n)");
    }
}
} // namespace gearkit

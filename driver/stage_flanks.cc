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
  out.write("number_of_teeth", std::vector<int>{d.teeth}, {});
  out.write("normal_module", d.normal_module);
  out.write("normal_pressure_angle", d.normal_pressure_angle);
  out.write("helix_angle", g.helix_sign * d.helix_angle);
  out.write("profile_shift", d.profile_shift);
  out.write("face_width", d.face_width);
  out.write("bore_radius", d.bore_diameter / 2);
  out.write("transverse_pressure_angle", g.transverse_pressure_angle);
  out.write("reference_radius", g.reference_radius);
  out.write("base_radius", g.base_radius);
  out.write("tip_radius", g.tip_radius);
  out.write("root_radius", g.root_radius);
  out.write("form_radius", g.form_radius);
  out.write("active_profile_start_radius", d.active_profile_start_radius);
  const auto [L0, L1] = profile_evaluation_range(g.modification_frame());
  out.write("profile_evaluation_range", std::vector<double>{L0, L1}, {2});
  out.write("base_helix_angle", g.base_helix_angle);
  out.write("lead", g.lead);
  out.write("tooth_thickness_reference", g.tooth_thickness_reference);
  out.write("tip_thickness_normal", g.checks().tip_thickness_normal);
  out.write("undercut", std::vector<int>{g.checks().undercut ? 1 : 0}, {});
  std::string warnings;
  for (const std::string &w : g.checks().warnings)
    {
      log << "  warning: " << w << "\n";
      warnings += w + "\n";
    }
  out.attribute("warnings", warnings);

  const MassProperties mp = g.mass_properties();
  out.write("mass", mp.mass);
  out.write("polar_inertia", mp.polar_inertia);
  out.write("diametral_inertia", mp.diametral_inertia);

  const std::vector<Vec2> outline = g.transverse_outline(40);
  out.write("transverse_outline", flatten(outline), {outline.size(), 2});
  const std::vector<Vec2> half = g.half_tooth_profile(40);
  out.write("drive_half_profile", flatten(half), {half.size(), 2});

  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      const H5Group       s = out.group(to_string(side), "<side>");
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
      s.write("points", points, shape);
      s.write("normals", normals, shape);
      s.write("deviation", deviation, {shape[0], shape[1], shape[2]});
      s.write("roll_angle", u, {u.size()});
      s.write("z", v, {v.size()});
    }
}

/// Flank grids [tooth][profile][face] of every tooth and side of a spiral bevel member, with the
/// grid axes h and face.
void
write_grids(const MemberFlanks &m, int n_u, int n_v, const H5Group &out, Progress &progress)
{
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      const H5Group       s = out.group(to_string(side), "<side>");
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
      s.write("points", points, shape);
      s.write("normals", normals, shape);
      s.write("h", u, {u.size()});
      s.write("face", v, {v.size()});
    }
}

void
write_machine(const Blade &b, const MachineSettings &m, const H5Group &g)
{
  g.write("blade_pitch_radius", b.pitch_radius);
  g.write("blade_angle", b.angle);
  g.write("blade_slope", double(b.slope));
  g.write("blade_curvature", b.curvature);
  g.write("radial_setting", m.radial_setting);
  g.write("cradle_angle", m.cradle_angle);
  g.write("machine_root_angle", m.root_angle);
  g.write("sliding_base", m.sliding_base);
  g.write("machine_centre_to_back", m.machine_centre_to_back);
  g.write("blank_offset", m.blank_offset);
  g.write("ratio_of_roll", m.ratio_of_roll);
  g.write("modified_roll_2c", m.modified_roll_2c);
  g.write("modified_roll_6d", m.modified_roll_6d);
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
  pg.write("pinion_modified_roll_2c", m.modified_roll_2c);
  pg.write("pitch_angle_pinion", g.pitch_angle_pinion);
  pg.write("pitch_angle_gear", g.pitch_angle_gear);
  pg.write("shaft_angle", d.shaft_angle);
  pg.write("outer_cone_distance", g.outer_cone_distance);
  pg.write("mean_cone_distance", g.mean_cone_distance);
  pg.write("outer_transverse_module", g.outer_transverse_module);
  pg.write("mean_normal_module", g.mean_normal_module);
  pg.write("mean_spiral_angle", d.mean_spiral_angle);
  pg.write("nominal_radial_setting", n.radial_setting);
  pg.write("nominal_cradle_angle", n.cradle_angle);
  const auto [pc, gc] = mismatched_cuts(d, m);
  for (const auto &[name, cut] : {std::pair{"pinion", pc}, {"gear", gc}})
    {
      const H5Group           mg = pg.group(name, "<member>");
      const BevelMemberFlanks flanks(cut);
      mg.write("number_of_teeth", std::vector<int>{cut.blank.teeth}, {});
      mg.write("pitch_angle", cut.blank.pitch_angle);
      mg.write("face_width", cut.blank.face_width);
      mg.write("addendum", cut.blank.addendum);
      mg.write("dedendum", cut.blank.dedendum);
      mg.write("mean_pitch_radius", cut.blank.mean_cone_distance * std::sin(cut.blank.pitch_angle));
      mg.attribute("drive_flank", flanks.concave_drives() ? "concave" : "convex");
      for (FlankSide side : {FlankSide::drive, FlankSide::coast})
        {
          const bool    outside = (side == FlankSide::drive) == flanks.concave_drives();
          const H5Group sg      = mg.group(to_string(side), "<side>");
          write_machine(outside ? cut.outside_blade : cut.inside_blade,
                        outside ? cut.outside_machine : cut.inside_machine, sg.group("machine"));
          const GeneratedFlank &f = flanks.tooth_flank(side);
          sg.write("form_height", f.domain().u_min);
          sg.write("undercut", std::vector<int>{f.undercut_found() ? 1 : 0}, {});
          if (f.undercut_found())
            log << "  warning: " << pair.name << " " << name << " " << to_string(side)
                << " flank is undercut; the working flank starts at h = " << f.domain().u_min * 1e3
                << " mm\n";
        }
      write_grids(flanks, pair.grid_profile_points, pair.grid_face_points, mg, progress);
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
      const H5Group pg = out.group(
          pair.name, pair.type == PairType::spiral_bevel ? "<bevel pair>" : "<involute pair>");
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
      write_member(*pinion, pair.grid_profile_points, pair.grid_face_points,
                   pg.group("pinion", "<member>"), log, progress);
      write_member(*gear, pair.grid_profile_points, pair.grid_face_points,
                   pg.group("gear", "<member>"), log, progress);
      pg.write("working_pressure_angle", working_pressure_angle(*pinion, *gear));
      pg.write("working_centre_distance", working_centre_distance(*pinion, *gear));
      pg.write("operating_centre_distance", a);
      pg.write("operating_pressure_angle",
               std::acos((pinion->base_radius + gear->base_radius) / a));
      const ContactRatios eps = contact_ratios(*pinion, *gear, a);
      pg.write("transverse_contact_ratio", eps.transverse);
      pg.write("overlap_ratio", eps.overlap);
    }
}
} // namespace gearkit

// Stage "measured": measured flank point sets per pair and member — sampled from the
// theoretical flanks (virtual CMM), synthesised with realistic errors, or read from CMM or
// topography files — with their deviation from the theoretical flank where it is known.
#include "driver/pair_members.h"
#include "driver/stages.h"
#include "geometry/flank_distance.h"
#include "geometry/measured_flank.h"

#include <algorithm>
#include <filesystem>
#include <ostream>

namespace gearkit
{
namespace
{
const char *
source_name(MeasuredSource s)
{
  switch (s)
    {
    case MeasuredSource::none:
      return "none";
    case MeasuredSource::virtual_cmm:
      return "virtual cmm";
    case MeasuredSource::synthesised:
      return "synthesised";
    case MeasuredSource::cmm_files:
      return "cmm files";
    case MeasuredSource::topography_files:
      return "topography files";
    }
  return "?";
}

std::string
flank_group_name(const MeasuredFlank &f)
{
  return "tooth_" + std::to_string(f.tooth) + "_" + to_string(f.side);
}

/// Writes the flanks; `deviation` (one vector per flank, along the theoretical normal) may be
/// empty where the theoretical counterpart of the points is unknown.
void
write_measured(const MeasuredMember &m, const std::vector<std::vector<double>> &deviation,
               const H5Group &out)
{
  out.write("number_of_teeth", std::vector<int>{m.teeth}, {});
  for (std::size_t i = 0; i < m.flanks.size(); ++i)
    {
      const MeasuredFlank &f = m.flanks[i];
      const H5Group        g = out.group(flank_group_name(f), "tooth_<k>_<side>");
      g.write("tooth", std::vector<int>{f.tooth}, {});
      g.attribute("side", to_string(f.side));
      const std::vector<hsize_t> shape = {hsize_t(f.n_profile), hsize_t(f.n_face), 3};
      std::vector<double>        p, n;
      for (const Vec3 &q : f.points)
        p.insert(p.end(), q.data(), q.data() + 3);
      for (const Vec3 &q : f.normals)
        n.insert(n.end(), q.data(), q.data() + 3);
      g.write("points", p, shape);
      if (!n.empty())
        g.write("normals", n, shape);
      if (!deviation.empty() && !deviation[i].empty())
        g.write("deviation", deviation[i], {shape[0], shape[1]});
    }
}

/// (measured - theoretical) . n on the same grid.
std::vector<std::vector<double>>
deviation_from(const MeasuredMember &measured, const MeasuredMember &theory)
{
  std::vector<std::vector<double>> d;
  for (std::size_t i = 0; i < measured.flanks.size(); ++i)
    {
      const MeasuredFlank &a = measured.flanks[i], &b = theory.flanks[i];
      d.emplace_back();
      for (std::size_t k = 0; k < a.points.size(); ++k)
        d.back().push_back((a.points[k] - b.points[k]).dot(b.normals[k]));
    }
  return d;
}
} // namespace

void
run_measured_stage(const Scene &scene, const Upstream &upstream, const H5Group &out,
                   std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      const MeasuredScene &m  = scene.measured.at(pair.name);
      const H5Group        pg = out.group(pair.name, "<pair>");
      pg.attribute("source", source_name(m.source));
      if (m.source == MeasuredSource::none)
        continue;
      const PairMembers theory_members =
          theoretical_members(pair, TcaScene{}, upstream.at("flanks")->group(pair.name));
      struct Member
      {
        const char             *name;
        const MemberFlanks     &flanks;
        const std::string      &file;
        const std::vector<int> &teeth;
      };
      for (const Member &member :
           {Member{"pinion", *theory_members.pinion, m.pinion_file, m.pinion_teeth},
            Member{"gear", *theory_members.gear, m.gear_file, m.gear_teeth}})
        {
          const int      z = member.flanks.teeth(); // tooth indices: checked at read time
          MeasuredMember measured;
          std::vector<std::vector<double>> deviation;
          switch (m.source)
            {
            case MeasuredSource::virtual_cmm:
            case MeasuredSource::synthesised:
              {
                const MeasuredMember theory =
                    virtual_cmm(member.flanks, member.name, m.profile_points, m.face_points,
                                m.edge_margin, member.teeth);
                measured = theory; // a perfect virtual CMM
                if (m.source == MeasuredSource::synthesised)
                  measured = synthesise_measured(theory, {m.seed + (member.name[0] == 'g' ? 1 : 0),
                                                          m.form_error, m.waviness_amplitude,
                                                          m.waviness_wavelength, m.roughness,
                                                          m.noise, m.pitch_error});
                deviation = deviation_from(measured, theory);
                break;
              }
            case MeasuredSource::cmm_files:
              measured = read_cmm_file(member.file);
              if (measured.teeth != z)
                throw InputError(member.file + ": teeth = " + std::to_string(measured.teeth) +
                                 ", but Flanks/" + pair.name + "/" + member.name + " has " +
                                 std::to_string(z) + " teeth");
              check_measurement(measured, member.flanks, m.nominal_tolerance, member.file,
                                "Measured flanks/" + pair.name + "/nominal tolerance");
              break;
            case MeasuredSource::topography_files:
              {
                const TopographyMember t = read_topography_file(member.file);
                measured                 = topography_to_points(involute(member.flanks), t);
                check_measurement(measured, member.flanks, m.nominal_tolerance, member.file,
                                  "Measured flanks/" + pair.name + "/nominal tolerance");
                for (const FlankTopography &f : t.flanks)
                  deviation.push_back(f.deviations);
                break;
              }
            case MeasuredSource::none:
              break;
            }
          log << "  " << pair.name << " " << member.name << ": " << measured.flanks.size()
              << " flanks (" << source_name(m.source) << ")\n";
          write_measured(measured, deviation, pg.group(member.name, "<member>"));
        }
    }
}

MeasuredMember
read_measured(const H5Group &group, const std::string &member)
{
  MeasuredMember m;
  m.member = member;
  m.teeth  = group.read_ints("number_of_teeth").at(0);
  for (const std::string &name : group.children())
    {
      if (name.rfind("tooth_", 0) != 0)
        continue;
      const H5Group        g = group.group(name);
      MeasuredFlank        f;
      std::vector<hsize_t> shape;
      const auto           p = g.read_doubles("points", &shape);
      f.tooth                = g.read_ints("tooth").at(0);
      f.side      = g.read_attribute("side") == "drive" ? FlankSide::drive : FlankSide::coast;
      f.n_profile = int(shape.at(0));
      f.n_face    = int(shape.at(1));
      for (std::size_t k = 0; k < p.size(); k += 3)
        f.points.emplace_back(p[k], p[k + 1], p[k + 2]);
      if (g.has("normals"))
        {
          const auto n = g.read_doubles("normals");
          for (std::size_t k = 0; k < n.size(); k += 3)
            f.normals.emplace_back(n[k], n[k + 1], n[k + 2]);
        }
      m.flanks.push_back(std::move(f));
    }
  // creation order is lost in the name index: restore tooth, side order
  std::sort(m.flanks.begin(), m.flanks.end(), [](const MeasuredFlank &a, const MeasuredFlank &b) {
    return std::pair(a.tooth, int(a.side)) < std::pair(b.tooth, int(b.side));
  });
  return m;
}
} // namespace gearkit

namespace gearkit
{
void
export_measured_cmm(const Scene &scene, const H5Group &measured, const std::string &dir,
                    std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      const MeasuredSource s = scene.measured.at(pair.name).source;
      if (s != MeasuredSource::virtual_cmm && s != MeasuredSource::synthesised)
        continue;
      std::filesystem::create_directories(dir);
      for (const char *member : {"pinion", "gear"})
        {
          const std::string path = dir + "/" + pair.name + "_" + member + ".cmm";
          write_cmm_file(path, read_measured(measured.group(pair.name).group(member), member));
          log << "cmm file: " << path << "\n";
        }
    }
}
} // namespace gearkit

#include "member_compliance.h"

#include "elastic_segment.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>

namespace gearkit
{
namespace
{
double
seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

std::pair<SegmentChoice, SegmentChoice>
loaded_segments(const std::vector<TcaPosition> &positions, int z1, int z2, double gap_band)
{
  auto choose = [&](bool pinion, int z) {
    int first = -1, lo = 0, hi = 0;
    for (const TcaPosition &p : positions)
      for (const PairContact &c : p.pairs)
        if (c.found && c.separation <= gap_band)
          {
            const int t = pinion ? c.pinion_tooth : c.gear_tooth;
            if (first < 0)
              first = t;
            const int d = ((t - first) % z + z + z / 2) % z - z / 2; // signed offset
            lo = std::min(lo, d), hi = std::max(hi, d);
          }
    if (first < 0)
      throw InputError("member compliance: no tooth pair comes within the gap band at the "
                       "positions analysed");
    SegmentChoice s;
    s.central = ((first + (lo + hi) / 2) % z + z) % z;
    s.teeth   = hi - lo + 1;
    if (s.teeth % 2 == 0)
      ++s.teeth; // segments are odd: one tooth more on one side
    return s;
  };
  return {choose(true, z1), choose(false, z2)};
}

FlankCompliance
involute_member_compliance(const InvoluteGear &gear, const MemberFlanks &flanks,
                           const MemberComplianceOptions &o, MemberComplianceInfo *info)
{
  MemberComplianceInfo  local;
  MemberComplianceInfo &out = info ? *info : local;
  if (o.work_directory.empty() || !std::filesystem::is_directory(o.work_directory))
    throw InputError("member compliance: the work directory '" + o.work_directory +
                     "' does not exist");
  if (!(o.depth_elements > 0 && o.patch_elements > 0))
    throw InputError("member compliance: depth and patch radius (in element sizes) must be > 0");
  auto        t0   = std::chrono::steady_clock::now();
  std::string name = gear.data().name + "_segment";
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  const std::string mesh_file =
      (std::filesystem::path(o.work_directory) / (name + ".msh")).string();
  SegmentMeshOptions mesh       = o.mesh;
  mesh.fine_side                = o.side; // the loaded flanks get the flank element size
  const SegmentMeshInfo segment = write_tooth_segment_mesh(gear, mesh, mesh_file);
  out.hexahedra                 = segment.hexahedra;
  out.mesh_seconds              = seconds_since(t0);

  const double h   = o.mesh.flank_size > 0 ? o.mesh.flank_size : gear.data().normal_module / 5;
  out.depth        = o.depth_elements * h;
  out.patch_radius = o.patch_elements * h;
  FlankGridSpec spec;
  spec.teeth = o.loaded_teeth.empty() ? segment.member_teeth : o.loaded_teeth;
  spec.side  = o.side;
  spec.n_u = o.n_u, spec.n_v = o.n_v;
  for (int t : spec.teeth)
    if (std::find(segment.member_teeth.begin(), segment.member_teeth.end(), t) ==
        segment.member_teeth.end())
      throw InputError("member compliance: loaded tooth " + std::to_string(t) +
                       " is not in the finite-element segment of " + gear.data().name);
  FlankCompliance table(flanks, spec);

  t0 = std::chrono::steady_clock::now();
  ElasticSegmentOptions eo;
  eo.degree   = o.degree;
  eo.material = o.material;
  eo.clamped  = {boundary::bore};
  if (o.hold_cuts)
    eo.clamped.insert({boundary::cut_start, boundary::cut_end});
  const ElasticSegment body(mesh_file, eo);
  out.dofs          = body.dofs();
  out.setup_seconds = seconds_since(t0);

  t0                          = std::chrono::steady_clock::now();
  const ElasticResponse solve = [&](const std::vector<FlankLoad>             &loads,
                                    const std::vector<std::pair<Vec3, Vec3>> &responses) {
    std::vector<PatchLoad> patches;
    for (const FlankLoad &l : loads)
      {
        const int i =
            int(std::find(segment.member_teeth.begin(), segment.member_teeth.end(), l.tooth) -
                segment.member_teeth.begin());
        patches.push_back({l.point, l.direction, out.patch_radius, {boundary::flank(i, o.side)}});
      }
    std::vector<Probe> probes;
    for (const auto &[x, d] : responses)
      probes.push_back({x, d});
    return body.response(patches, probes);
  };
  fill_structural_compliance(table, solve, out.depth, o.material, out.patch_radius);
  out.solve_seconds = seconds_since(t0);
  return table;
}
} // namespace gearkit

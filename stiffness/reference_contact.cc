#include "stiffness/reference_contact.h"

#include "stiffness/elastic_segment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

namespace gearkit
{
namespace
{
double
seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Where a cell sits on one member's flank (member frame) and the box its traction covers.
struct MemberCell
{
  int             tooth = 0;
  Vec3            position, normal; ///< normal out of the material
  Eigen::Matrix3d axes;             ///< rows: across (s), along (t), normal
  Vec3            half_size;
};

MemberCell
member_cell(const MemberFlanks &flanks, FlankSide side, int tooth, double u, double v,
            const ContactCell &c)
{
  const FlankPoint q = flanks.flank(tooth, side).evaluate(u, v);
  MemberCell       m;
  m.tooth          = tooth;
  m.position       = q.position;
  m.normal         = q.normal.normalized();
  const Vec3 along = (q.d_dv - q.d_dv.dot(m.normal) * m.normal).normalized();
  m.axes.row(0)    = m.normal.cross(along).transpose();
  m.axes.row(1)    = along.transpose();
  m.axes.row(2)    = m.normal.transpose();
  // the box reaches a whole cell width off the flank: the flank curves away from its tangent
  // plane by far less than that over a cell
  m.half_size = Vec3(c.ds / 2, c.dt / 2, c.ds);
  return m;
}

/// The segment around the pairs of this position (or the one asked for).
SegmentChoice
segment_for(const SegmentChoice &asked, const SegmentChoice &near, int min_teeth)
{
  if (asked.teeth > 0)
    return asked;
  SegmentChoice s = near;
  s.teeth         = std::max(s.teeth, min_teeth);
  if (s.teeth % 2 == 0)
    ++s.teeth; // the mesher checks that it fits the gear
  return s;
}

/// Refuses (InputError) a missing work directory, bad sizes and bad torques.
void
check_reference_input(const ReferenceContactOptions &o, const std::vector<double> &torques)
{
  if (o.work_directory.empty() || !std::filesystem::is_directory(o.work_directory))
    throw InputError("reference contact: the work directory '" + o.work_directory +
                     "' does not exist");
  if (!(o.elements_per_cell > 0) || o.layers_per_cell < 1 || o.min_segment_teeth < 1)
    throw InputError("reference contact: elements per cell must be > 0, layers per cell and "
                     "segment teeth >= 1");
  for (double T : torques)
    if (!(T >= 0) || !std::isfinite(T))
      throw InputError("reference contact: torques must be finite and >= 0 (got " +
                       std::to_string(T) + " N m)");
}

/// How a member's segment is refined about the cells.
struct Refinement
{
  double flank_size = 0; ///< the flank elements' size
  double contact    = 0; ///< the elements' size at the cells
  /// gmsh grades the segment's transverse section to straight contact lines; else deal.II
  /// refines the body about the cells
  bool graded_lines = false;
};

/// The member's segment mesh (`seg`; `loaded`: the segment about this position's pairs) and
/// its refinement about the cells (mc: the cells on the member's flanks).
SegmentMeshOptions
segment_options(const ReferenceMember &m, bool is_pinion, const SegmentChoice &seg,
                const SegmentChoice &loaded, FlankSide side, const ReferenceContactOptions &o,
                const std::vector<ContactCell> &cells, const std::vector<MemberCell> &mc,
                Refinement &r)
{
  const Eigen::Index n = Eigen::Index(cells.size());
  SegmentMeshOptions mesh;
  mesh.teeth         = seg.teeth;
  mesh.central_tooth = seg.central;
  mesh.whole_rim     = is_pinion ? o.pinion_whole_rim : o.gear_whole_rim;
  mesh.flank_size    = o.flank_size;
  mesh.far_size      = o.far_size;
  mesh.fine_side     = side;
  if (seg.teeth == m.flanks->teeth()) // the whole gear: fine about this position's pairs
    {
      mesh.central_tooth = loaded.central, mesh.fine_teeth = loaded.teeth;
    }
  // the cells' widths across and along: the smallest (the graded section resolves every
  // cell) and the median (cells cut at a tip's edge are narrower)
  double              ds = HUGE_VAL, dt = HUGE_VAL, reach = 0;
  std::vector<double> widths;
  for (const ContactCell &c : cells)
    {
      ds = std::min(ds, c.ds), dt = std::min(dt, c.dt);
      reach = std::max(reach, std::abs(c.s) + c.ds);
      widths.push_back(c.ds);
    }
  std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
  const double median_ds = widths[widths.size() / 2];
  // never coarser than the flank elements around it (a coarser "refinement" folds the
  // graded quadrilaterals at the root)
  r.flank_size   = o.flank_size > 0 ? o.flank_size : m.module / 5;
  r.graded_lines = m.straight_lines && !o.local_refinement;
  r.contact      = std::min((r.graded_lines ? ds : median_ds) / o.elements_per_cell, r.flank_size);
  if (r.graded_lines)
    {
      // Refinement about each pair's contact line: the cell nearest the line (smallest
      // |s|) marks it, the cells' reach across sets the radius.
      std::map<int, std::pair<double, Vec2>> line; // pair -> (|s|, section point)
      for (Eigen::Index i = 0; i < n; ++i)
        {
          auto it = line.find(cells[i].pair);
          if (it == line.end() || std::abs(cells[i].s) < it->second.first)
            line[cells[i].pair] = {std::abs(cells[i].s), mc[i].position.head<2>()};
        }
      for (const auto &[pair, l] : line)
        mesh.refine_points.push_back(l.second);
      mesh.refine_size   = r.contact;
      mesh.refine_radius = reach;
      mesh.face_layers   = std::max(2, int(std::lround(m.face_width / dt)) * o.layers_per_cell);
    }
  return mesh;
}

/// The boundary id of a tooth's loaded flank in the member's segment.
int
flank_boundary(const SegmentMeshInfo &segment, FlankSide side, int tooth)
{
  const auto at = std::find(segment.member_teeth.begin(), segment.member_teeth.end(), tooth);
  return boundary::flank(int(at - segment.member_teeth.begin()), side);
}

/// The member's body on its segment: held at the bore (and the cuts if asked), refined about
/// the cells by deal.II where gmsh has not graded the segment to them.
ElasticSegmentOptions
body_options(const ReferenceMember &m, bool is_pinion, FlankSide side,
             const ReferenceContactOptions &o, const SegmentMeshInfo &segment,
             const std::vector<MemberCell> &mc, const Refinement &r)
{
  const double          flank_size = r.flank_size, contact = r.contact;
  ElasticSegmentOptions eo;
  eo.degree       = o.degree;
  eo.communicator = o.communicator;
  eo.material     = is_pinion ? o.cells.pinion_material : o.cells.gear_material;
  eo.clamped      = {boundary::bore};
  if (o.hold_cuts && !segment.whole)
    eo.clamped.insert({boundary::cut_start, boundary::cut_end});
  if (!r.graded_lines)
    {
      // deal.II halves the elements about the cells until they are the contact size: pass j
      // within flank_size / 2^j of the flank within the cells (and a contact element
      // around them)
      eo.local_refinements =
          unsigned(std::max(1.0, std::ceil(std::log2(flank_size / contact) - 1e-9)));
      eo.refine_distance       = flank_size;
      eo.halve_refine_distance = true;
      for (const MemberCell &c : mc)
        {
          eo.refine_boundaries.insert(flank_boundary(segment, side, c.tooth));
          // the cell and one contact element around it, up to a flank element off the flank
          eo.refine_boxes.push_back(
              {c.position, Vec3(c.half_size.x() + contact, c.half_size.y() + contact, flank_size),
               c.axes});
        }
      eo.surface_boundaries = eo.refine_boundaries;
      eo.boundary_surface   = flank_surface(*m.flanks, segment.member_teeth, side);
    }
  return eo;
}

/// One unit patch load per cell on the member's flank, pressing into the material.
std::vector<PatchLoad>
patch_loads(const std::vector<MemberCell> &mc, const SegmentMeshInfo &segment, FlankSide side,
            const Refinement &r)
{
  const bool             graded_lines = r.graded_lines;
  const double           contact      = r.contact;
  std::vector<PatchLoad> loads;
  for (const MemberCell &c : mc)
    {
      PatchLoad l;
      l.point      = c.position;
      l.force      = -c.normal; // a unit force pressing into the material
      l.boundaries = {flank_boundary(segment, side, c.tooth)};
      // refined about the cells: a cell narrower than the contact elements (cut at a tip's
      // edge) spreads its traction over one element, so that it meets the quadrature
      l.half_size = graded_lines ? c.half_size
                                 : c.half_size.cwiseMax(Vec3(contact / 2, contact / 2, contact));
      l.axes      = c.axes;
      loads.push_back(l);
    }
  return loads;
}

/// One member's part: its segment meshed about the cells, its body, the cells' patch loads on
/// it (into `loads`), and their compliance (the approach of each cell = its mean normal
/// displacement, the cells' load work) added to C.
std::unique_ptr<ElasticSegment>
reference_body(bool is_pinion, const ReferenceMember &m, const std::vector<ContactCell> &cells,
               const std::pair<SegmentChoice, SegmentChoice> &near, FlankSide side,
               const ReferenceContactOptions &o, std::vector<PatchLoad> &loads, Eigen::MatrixXd &C,
               ReferenceContactInfo &out)
{
  std::vector<MemberCell> mc;
  for (const ContactCell &c : cells)
    mc.push_back(is_pinion ? member_cell(*m.flanks, side, c.pinion_tooth, c.u1, c.v1, c)
                           : member_cell(*m.flanks, side, c.gear_tooth, c.u2, c.v2, c));
  Refinement               r;
  const SegmentMeshOptions mesh =
      segment_options(m, is_pinion, is_pinion ? out.pinion_segment : out.gear_segment,
                      is_pinion ? near.first : near.second, side, o, cells, mc, r);
  const std::string file =
      (std::filesystem::path(o.work_directory) /
       (std::string(is_pinion ? "reference_pinion" : "reference_gear") + ".msh"))
          .string();
  auto                  t0      = std::chrono::steady_clock::now();
  const SegmentMeshInfo segment = segment_mesh_on_first_process(
      [&](const std::string &path) { return m.mesher(mesh, path); }, file, o.communicator);
  out.mesh_seconds += seconds_since(t0);

  t0                             = std::chrono::steady_clock::now();
  const ElasticSegmentOptions eo = body_options(m, is_pinion, side, o, segment, mc, r);
  if (!r.graded_lines)
    out.local_refinements = eo.local_refinements;
  auto body = std::make_unique<ElasticSegment>(file, eo);
  out.hexahedra += body->cells();
  out.dofs += body->dofs();
  loads = patch_loads(mc, segment, side, r);
  C += body->patch_response(loads, loads);
  out.solve_seconds += seconds_since(t0);
  return body;
}
} // namespace

ReferenceMember
involute_reference_member(const InvoluteGear &gear, const MemberFlanks &flanks)
{
  ReferenceMember m;
  m.flanks = &flanks;
  m.mesher = [&gear](const SegmentMeshOptions &o, const std::string &path) {
    return write_tooth_segment_mesh(gear, o, path);
  };
  m.module         = gear.data().normal_module;
  m.face_width     = gear.data().face_width;
  m.straight_lines = gear.data().helix_angle == 0;
  return m;
}

ReferenceMember
bevel_reference_member(const BevelMemberFlanks &flanks, double module)
{
  ReferenceMember m;
  m.flanks = &flanks;
  m.mesher = [&flanks, module](const SegmentMeshOptions &o, const std::string &path) {
    return write_bevel_segment_mesh(flanks, module, o, path);
  };
  m.module = module;
  return m;
}

std::vector<LoadedPosition>
reference_contact(const InvoluteGear &pinion, const InvoluteGear &gear, const UnloadedTca &tca,
                  const TcaPosition &position, const std::vector<double> &torques,
                  const ReferenceContactOptions &o, ReferenceContactInfo *info)
{
  return reference_contact(involute_reference_member(pinion, tca.pinion_flanks()),
                           involute_reference_member(gear, tca.gear_flanks()), tca, position,
                           torques, o, info);
}

std::vector<LoadedPosition>
reference_contact(const ReferenceMember &pinion, const ReferenceMember &gear,
                  const UnloadedTca &tca, const TcaPosition &position,
                  const std::vector<double> &torques, const ReferenceContactOptions &o,
                  ReferenceContactInfo *info)
{
  ReferenceContactInfo  local;
  ReferenceContactInfo &out = info ? *info : local;
  out                       = ReferenceContactInfo{};
  check_reference_input(o, torques);

  const FlankSide side = tca.options_data().side;
  const int       z1 = pinion.flanks->teeth(), z2 = gear.flanks->teeth();
  const auto      near = loaded_segments({position}, z1, z2, o.cells.cells.gap_band);
  out.pinion_segment   = segment_for(o.pinion_segment, near.first, o.min_segment_teeth);
  out.gear_segment     = segment_for(o.gear_segment, near.second, o.min_segment_teeth);

  // The segments carry every cell: pairs outside them are refused when they touch.
  auto in_segment = [](const SegmentChoice &s, int z, int tooth) {
    const int d = ((tooth - s.central) % z + z + z / 2) % z - z / 2;
    return std::abs(d) <= (s.teeth - 1) / 2;
  };
  LoadedContactOptions lo = o.cells;
  lo.covered              = [&](int p, int g) {
    return in_segment(out.pinion_segment, z1, p) && in_segment(out.gear_segment, z2, g);
  };
  lo.table_parameters = nullptr;
  // Uniform columns along: the members' face layers are uniform, and graded columns would ask
  // for layers of the narrowest (ten times the elements at 24 columns).
  lo.cells.along_grading         = 0;
  std::vector<ContactCell> cells = loaded_cells(tca, position, lo);
  const Eigen::Index       n     = Eigen::Index(cells.size());
  if (n == 0)
    throw InputError("reference contact: no flank pair comes within the gap band (" +
                     std::to_string(o.cells.cells.gap_band * 1e6) + " um) at this position");

  Eigen::MatrixXd                              C = Eigen::MatrixXd::Zero(n, n);
  std::vector<std::vector<PatchLoad>>          member_loads(2);
  std::vector<std::unique_ptr<ElasticSegment>> bodies;
  for (int member = 0; member < 2; ++member)
    bodies.push_back(reference_body(member == 0, member == 0 ? pinion : gear, cells, near, side, o,
                                    member_loads[member], C, out));

  const auto                  t0 = std::chrono::steady_clock::now();
  std::vector<LoadedPosition> results;
  for (std::size_t k = 0; k < torques.size(); ++k)
    {
      results.push_back(solve_loaded_contact(tca, position, torques[k], cells, C));
      results.back().gap_band = o.cells.cells.gap_band;
      if (results.back().zone_edge_reached)
        throw InputError("reference contact: at " + std::to_string(torques[k]) +
                         " N m the contact reaches the edge of the cell zone; raise the gap band "
                         "(now " +
                         std::to_string(o.cells.cells.gap_band * 1e6) + " um)");
      if (!o.vtu_prefix.empty())
        for (int member = 0; member < 2; ++member)
          {
            std::vector<PatchLoad> loads = member_loads[member];
            for (Eigen::Index i = 0; i < n; ++i)
              loads[i].force *= results.back().force[i];
            bodies[member]->write_vtu(loads, o.vtu_prefix + "_torque" + std::to_string(k) +
                                                 (member == 0 ? "_pinion.vtu" : "_gear.vtu"));
          }
    }
  out.contact_seconds = seconds_since(t0);
  return results;
}
} // namespace gearkit

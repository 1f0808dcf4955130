#include "meshes/tooth_segment.h"

#include "geometry/mass_properties.h"
#include "meshes/gmsh_session.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

namespace gearkit
{
namespace
{
Vec2
polar(double r, double a)
{
  return {r * std::cos(a), r * std::sin(a)};
}

Vec2
rotate(const Vec2 &p, double a)
{
  const double c = std::cos(a), s = std::sin(a);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

void
check(bool ok, const std::string &parameter, double value, const std::string &allowed)
{
  require_value(ok, "tooth segment mesh", parameter, value, allowed);
}

/// Builds the section curves in the geo kernel; remembers which group each curve's extrusion
/// belongs to and which curves attract the fine elements.
class SectionBuilder
{
public:
  explicit SectionBuilder(double z0)
      : z0(z0)
      , centre(gmsh::model::geo::addPoint(0, 0, z0))
  {
  }

  int
  point(const Vec2 &p)
  {
    return gmsh::model::geo::addPoint(p.x(), p.y(), z0);
  }
  /// Circle arc about the axis from point a to point b (split below 60 deg per piece): the
  /// shorter way, or counter-clockwise however far that is.
  void
  arc(int a, const Vec2 &pa, int b, const Vec2 &pb, int group, bool counter_clockwise = false)
  {
    const double a0 = std::atan2(pa.y(), pa.x());
    double       da = std::atan2(pb.y(), pb.x()) - a0;
    da = counter_clockwise ? da - 2 * pi * std::floor(da / (2 * pi)) : std::remainder(da, 2 * pi);
    const int    pieces = int(std::ceil(std::abs(da) / (pi / 3)));
    const double r      = pa.norm();
    int          from   = a;
    for (int k = 1; k <= pieces; ++k)
      {
        const int to = k == pieces ? b : point(polar(r, a0 + da * k / pieces));
        add(gmsh::model::geo::addCircleArc(from, centre, to), group, false);
        from = to;
      }
  }
  void
  line(int a, int b, int group)
  {
    add(gmsh::model::geo::addLine(a, b), group, false);
  }
  /// Spline through the points (first and last given as tags, shared with the neighbours).
  void
  spline(int first, const std::vector<Vec2> &inner, int last, int group)
  {
    std::vector<int> tags{first};
    for (const Vec2 &p : inner)
      tags.push_back(point(p));
    tags.push_back(last);
    add(gmsh::model::geo::addSpline(tags), group, true);
  }

  /// Curves in order, their groups, and the fine ones (flanks and fillets) with their segment
  /// tooth (set `tooth` before adding a tooth's curves).
  std::vector<int> curves, groups, fine, fine_tooth;
  int              tooth = -1;

private:
  void
  add(int curve, int group, bool is_fine)
  {
    curves.push_back(curve);
    groups.push_back(group);
    if (is_fine)
      fine.push_back(curve), fine_tooth.push_back(tooth);
  }
  double z0;
  int    centre;
};

/// A curve's points mirrored in y (the coast half of a tooth from the drive half).
std::vector<Vec2>
mirror(std::vector<Vec2> c)
{
  for (Vec2 &p : c)
    p.y() = -p.y();
  return c;
}

/// A curve's inner points (without its ends), turned by `angle`, in reverse if `reversed`.
std::vector<Vec2>
inner(const std::vector<Vec2> &c, double angle, bool reversed)
{
  std::vector<Vec2> out;
  for (std::size_t i = 1; i + 1 < c.size(); ++i)
    out.push_back(rotate(c[reversed ? c.size() - 1 - i : i], angle));
  return out;
}

/// The segment's tooth profile and its place on the gear: what build_and_write's phases
/// share.
struct SegmentLayout
{
  SegmentLayout(const InvoluteGear &gear, const SegmentMeshOptions &o, const SegmentMeshInfo &info)
      : gear(gear)
      , o(o)
      , d(gear.data())
      , z(d.teeth)
      , mn(d.normal_module)
      , b(d.face_width)
      , n(o.curve_points)
      , dphi(gear.helix_sign * std::tan(d.helix_angle) / gear.reference_radius)
      , phi0(-dphi * b / 2)
      , pitch(2 * pi / z)
      , whole(o.teeth == z)
      , round(whole || o.whole_rim)
      , half_n(whole ? z / 2 : (o.teeth - 1) / 2)
      , a_start(phi0 + pitch * (o.central_tooth - half_n) - pitch / 2)
      , a_end(a_start + pitch * o.teeth)
      , ri(info.rim_inner_radius)
      , rf(gear.root_radius)
  {
    // Drive half of tooth 0 from gear.half_tooth_profile: root land [0, n), fillet [n, 2n),
    // involute [2n, 3n] (form point to tip corner), tip land. The coast half is its mirror in y.
    const std::vector<Vec2> half = gear.half_tooth_profile(n);
    fillet.assign(half.begin() + n, half.begin() + 2 * n + 1); // to the form point
    involute.assign(half.begin() + 2 * n, half.begin() + 3 * n + 1);
  }

  const InvoluteGear       &gear;
  const SegmentMeshOptions &o;
  const InvoluteGearData   &d;
  const int                 z;
  const double              mn, b;
  const int                 n;                ///< spline points per fillet and per involute
  std::vector<Vec2>         fillet, involute; ///< of tooth 0's drive half
  const double              dphi;             ///< the helix's turn per length [rad/m]
  const double              phi0;             ///< the section at z = -b/2
  const double              pitch;
  const bool                whole;
  const bool                round; ///< rim and bore all round, no cuts
  const int                 half_n;
  const double              a_start, a_end; ///< the segment's cuts (the section's angles)
  const double              ri, rf;         ///< rim inner and root radius
};

/// The transverse section at z = -b/2 in the geo kernel, its curves in `s` and the fillets
/// (curve, segment tooth) in `fillets`; returns its plane surface.
int
build_section(const SegmentLayout &l, SegmentMeshInfo &info, SectionBuilder &s,
              std::vector<std::pair<int, int>> &fillets)
{
  const SegmentMeshOptions &o = l.o;
  info.whole                  = l.round;
  // Counter-clockwise: cut at the start, root arcs and teeth, cut at the end, bore back. The
  // whole gear: the teeth all round, then the bore as a hole; the whole rim: the segment's
  // teeth, the root circle round to the first, then the bore as a hole.
  const Vec2 bore_start = polar(l.ri, l.a_start), root_start = polar(l.rf, l.a_start);
  const Vec2 root_end = polar(l.rf, l.a_end), bore_end = polar(l.ri, l.a_end);
  const int  p_root_start = s.point(root_start);
  const int  p_bore_start = l.round ? 0 : s.point(bore_start);
  if (!l.round)
    s.line(p_bore_start, p_root_start, boundary::cut_start);
  int  previous    = p_root_start;
  Vec2 previous_xy = root_start;
  for (int i = 0; i < o.teeth; ++i)
    {
      const int    k = ((o.central_tooth - l.half_n + i) % l.z + l.z) % l.z;
      const double a = l.phi0 + l.pitch * (o.central_tooth - l.half_n + i);
      info.member_teeth.push_back(k);
      s.tooth                              = i;
      const std::vector<Vec2> coast_fillet = mirror(l.fillet), coast_involute = mirror(l.involute);
      const Vec2 c0 = rotate(coast_fillet.front(), a), c1 = rotate(coast_fillet.back(), a);
      const Vec2 c2 = rotate(coast_involute.back(), a);
      const Vec2 d2 = rotate(l.involute.back(), a), d1 = rotate(l.fillet.back(), a);
      const Vec2 d0  = rotate(l.fillet.front(), a);
      const int  pc0 = s.point(c0), pc1 = s.point(c1), pc2 = s.point(c2);
      const int  pd2 = s.point(d2), pd1 = s.point(d1), pd0 = s.point(d0);
      s.arc(previous, previous_xy, pc0, c0, boundary::free);
      s.spline(pc0, inner(coast_fillet, a, false), pc1, boundary::free);
      fillets.emplace_back(s.curves.back(), i);
      s.spline(pc1, inner(coast_involute, a, false), pc2, boundary::flank(i, FlankSide::coast));
      s.arc(pc2, c2, pd2, d2, boundary::free);
      s.spline(pd2, inner(l.involute, a, true), pd1, boundary::flank(i, FlankSide::drive));
      s.spline(pd1, inner(l.fillet, a, true), pd0, boundary::free);
      fillets.emplace_back(s.curves.back(), i);
      previous = pd0, previous_xy = d0;
    }
  s.tooth = -1;
  std::vector<int> loops;
  if (l.round)
    {
      s.arc(previous, previous_xy, p_root_start, root_start, boundary::free, true);
      loops.push_back(gmsh::model::geo::addCurveLoop(s.curves));
      // the bore: three arcs of 120 degrees
      const std::size_t outer = s.curves.size();
      std::vector<int>  p;
      std::vector<Vec2> xy;
      for (int k = 0; k < 3; ++k)
        xy.push_back(polar(l.ri, l.a_start + 2 * pi * k / 3)), p.push_back(s.point(xy.back()));
      for (int k = 0; k < 3; ++k)
        s.arc(p[k], xy[k], p[(k + 1) % 3], xy[(k + 1) % 3], boundary::bore);
      loops.push_back(gmsh::model::geo::addCurveLoop(
          std::vector<int>(s.curves.begin() + std::ptrdiff_t(outer), s.curves.end())));
    }
  else
    {
      const int p_root_end = s.point(root_end), p_bore_end = s.point(bore_end);
      s.arc(previous, previous_xy, p_root_end, root_end, boundary::free);
      s.line(p_root_end, p_bore_end, boundary::cut_end);
      s.arc(p_bore_end, bore_end, p_bore_start, bore_start, boundary::bore);
      loops.push_back(gmsh::model::geo::addCurveLoop(s.curves));
    }
  const int section = gmsh::model::geo::addPlaneSurface(loops);
  gmsh::model::geo::synchronize();
  return section;
}

/// The element sizes as gmsh's background field, and the meshing options (the section
/// recombined into quadrilaterals, everything subdivided into hexahedra).
void
set_sizes(const SegmentLayout &l, const SectionBuilder &s,
          const std::vector<std::pair<int, int>> &fillets, int section, double flank_size,
          double far_size)
{
  const SegmentMeshOptions &o = l.o;
  // Fine at the flanks and fillets, coarse toward the bore: distance threshold fields, the
  // loaded side's flanks at the flank size, the other flanks and the fillets at theirs.
  const double        other_size = o.other_size > 0 ? o.other_size : flank_size;
  std::vector<double> loaded, others;
  const int           fine_half = o.fine_teeth > 0 ? (o.fine_teeth - 1) / 2 : o.teeth;
  std::vector<double> away; // the flanks and fillets of the teeth away from the loaded ones
  for (std::size_t c = 0; c < s.curves.size(); ++c)
    if (const auto f = std::find(s.fine.begin(), s.fine.end(), s.curves[c]); f != s.fine.end())
      {
        if (std::abs(s.fine_tooth[std::size_t(f - s.fine.begin())] - l.half_n) > fine_half)
          {
            away.push_back(s.curves[c]);
            continue;
          }
        bool on_loaded = false;
        for (int i = 0; i < o.teeth; ++i)
          on_loaded = on_loaded || s.groups[c] == boundary::flank(i, o.fine_side);
        (on_loaded || other_size == flank_size ? loaded : others).push_back(s.curves[c]);
      }
  std::vector<double> fields;
  auto                threshold_about = [&](const std::vector<double> &curves, double size) {
    const int distance = gmsh::model::mesh::field::add("Distance");
    gmsh::model::mesh::field::setNumbers(distance, "CurvesList", curves);
    gmsh::model::mesh::field::setNumber(distance, "NumPointsPerCurve", 4 * l.n);
    const int threshold = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMin", 2 * size);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMax", 2 * far_size);
    gmsh::model::mesh::field::setNumber(threshold, "DistMin", size);
    gmsh::model::mesh::field::setNumber(threshold, "DistMax", 2 * l.mn);
    fields.push_back(threshold);
  };
  threshold_about(loaded, flank_size);
  if (o.fillet_size > 0)
    {
      std::vector<double> fine_fillets; // of the teeth with fine elements
      for (const auto &[curve, tooth] : fillets)
        if (std::abs(tooth - l.half_n) <= fine_half)
          fine_fillets.push_back(curve);
      threshold_about(fine_fillets, o.fillet_size);
    }
  if (!others.empty())
    threshold_about(others, other_size);
  // a tooth needs a few elements across (coarser ones fold at the fillets)
  if (!away.empty())
    threshold_about(away, std::max(other_size, std::min(far_size, l.mn / 2)));
  for (const Vec2 &c : o.refine_points)
    {
      std::ostringstream distance_to;
      distance_to.precision(17);
      distance_to << "Sqrt((x - (" << c.x() << "))^2 + (y - (" << c.y() << "))^2)";
      const int d = gmsh::model::mesh::field::add("MathEval");
      gmsh::model::mesh::field::setString(d, "F", distance_to.str());
      const int t = gmsh::model::mesh::field::add("Threshold");
      gmsh::model::mesh::field::setNumber(t, "InField", d);
      gmsh::model::mesh::field::setNumber(t, "SizeMin", 2 * o.refine_size);
      gmsh::model::mesh::field::setNumber(t, "SizeMax", 2 * flank_size);
      gmsh::model::mesh::field::setNumber(t, "DistMin", o.refine_radius);
      gmsh::model::mesh::field::setNumber(t, "DistMax",
                                          o.refine_radius + 4 * (flank_size - o.refine_size));
      fields.push_back(t);
    }
  const int background = gmsh::model::mesh::field::add("Min");
  gmsh::model::mesh::field::setNumbers(background, "FieldsList", fields);
  gmsh::model::mesh::field::setAsBackgroundMesh(background);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1); // blossom
  // Every element is split into hexahedra at the end (the prisms the recombination's left-over
  // triangles extrude into as well): all-hexahedral. The sizes and layers given to gmsh are
  // halved to compensate.
  gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 2);
  gmsh::model::geo::mesh::setRecombine(2, section);
}

/// The section extruded over the face along the helix, and the physical groups: returns the
/// surfaces per boundary id.
std::map<int, std::vector<int>>
extrude_section(const SegmentLayout &l, const SectionBuilder &s, int section, int layers)
{
  gmsh::vectorpair out;
  if (l.dphi == 0)
    gmsh::model::geo::extrude({{2, section}}, 0, 0, l.b, out, {(layers + 1) / 2}, {}, true);
  else
    gmsh::model::geo::twist({{2, section}}, 0, 0, 0, 0, 0, l.b, 0, 0, 1, l.dphi * l.b, out,
                            {(layers + 1) / 2}, {}, true);
  gmsh::model::geo::synchronize();
  const int top = out[0].second, volume = out[1].second;

  std::map<int, std::vector<int>> groups{{boundary::end_front, {section}},
                                         {boundary::end_back, {top}}};
  for (std::size_t c = 0; c < s.curves.size(); ++c)
    groups[s.groups[c]].push_back(out[2 + c].second);
  for (const auto &[id, surfaces] : groups)
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, surfaces, id),
                                 boundary::name(id));
  gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {volume}, 1), "body");
  return groups;
}

/// Flank nodes onto the exact involute (splines and the subdivision's new nodes are off by up
/// to a few micrometres; contact gaps are micrometres): at the node's radius and z, the polar
/// angle of the involute, theta_b - inv(alpha_r) from the tooth's centre line turned by the
/// helix.
void
onto_involutes(const SegmentLayout &l)
{
  const InvoluteGear &gear    = l.gear;
  const double        theta_b = std::atan2(l.involute.front().y(), l.involute.front().x()) +
                         gear.roll_angle_form - std::atan(gear.roll_angle_form);
  for (int i = 0; i < l.o.teeth; ++i)
    for (FlankSide side : {FlankSide::drive, FlankSide::coast})
      {
        const double             sign = side == FlankSide::drive ? 1 : -1;
        const double             a    = l.phi0 + l.pitch * (l.o.central_tooth - l.half_n + i);
        std::vector<std::size_t> flank_nodes;
        std::vector<double>      xyz;
        gmsh::model::mesh::getNodesForPhysicalGroup(2, boundary::flank(i, side), flank_nodes, xyz);
        for (std::size_t k = 0; k < flank_nodes.size(); ++k)
          {
            const double r = std::hypot(xyz[3 * k], xyz[3 * k + 1]), zk = xyz[3 * k + 2];
            const double xi =
                std::sqrt(std::max(0.0, r * r / (gear.base_radius * gear.base_radius) - 1));
            const double angle =
                a + l.dphi * (zk + l.b / 2) + sign * (theta_b - (xi - std::atan(xi)));
            gmsh::model::mesh::setNode(flank_nodes[k],
                                       {r * std::cos(angle), r * std::sin(angle), zk}, {});
          }
      }
}

/// The mesh by gmsh's 2-D algorithms in turn until the worst element is acceptable (the best
/// one if none is): at some sizes one of them leaves a sliver at a root land or fillet whose
/// subdivision folds (bench/README.md, "Mesh quality"); the first is the one every earlier mesh
/// used. (8, frontal-Delaunay for quadrilaterals, crashes with a background field in gmsh 4.8.)
void
generate_mesh(const SegmentLayout &l, SegmentMeshInfo &info, double flank_size, double far_size)
{
  const int algorithms[] = {6, 5, 1}; // frontal-Delaunay, Delaunay, MeshAdapt
  int       best         = 0;
  double    best_quality = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i <= std::size(algorithms); ++i)
    {
      const int algorithm = i < std::size(algorithms) ? algorithms[i] : best;
      if (i == std::size(algorithms) && algorithm == info.mesh_algorithm)
        break; // the last one tried was the best
      gmsh::model::mesh::clear();
      gmsh::option::setNumber("Mesh.Algorithm", algorithm);
      gmsh::model::mesh::generate(3);
      std::tie(info.hexahedra, info.nodes) = require_hexahedra("tooth segment mesh");
      onto_involutes(l);
      info.mesh_algorithm        = algorithm;
      info.worst_corner_jacobian = worst_corner_jacobian();
      if (info.worst_corner_jacobian >= SegmentMeshInfo::acceptable_corner_jacobian)
        break;
      if (info.worst_corner_jacobian > best_quality)
        best_quality = info.worst_corner_jacobian, best = algorithm;
    }
  if (!(info.worst_corner_jacobian > 0))
    {
      std::ostringstream msg;
      msg << "tooth segment mesh of " << l.d.name << ": gmsh folds an element with every 2-D "
          << "algorithm at these sizes (flank " << flank_size * 1e3 << " mm, far " << far_size * 1e3
          << " mm; worst corner Jacobian " << best_quality
          << " of its mean); allowed: positive at every corner. Try other element sizes";
      throw InputError(msg.str());
    }
}

/// The gmsh model, mesh and files (inside a GmshSession; options already checked).
void
build_and_write(const InvoluteGear &gear, const SegmentMeshOptions &o, const std::string &path,
                SegmentMeshInfo &info, double flank_size, double far_size, int layers)
{
  gmsh::model::add("tooth_segment");
  const SegmentLayout              l(gear, o, info);
  SectionBuilder                   s(-l.b / 2);
  std::vector<std::pair<int, int>> fillets; // (curve, segment tooth)
  const int                        section = build_section(l, info, s, fillets);
  set_sizes(l, s, fillets, section, flank_size, far_size);
  const std::map<int, std::vector<int>> groups = extrude_section(l, s, section, layers);
  generate_mesh(l, info, flank_size, far_size);

  // Analytic volume: N/z of the gear's nominal section minus the rim's inner disc, times b (the
  // whole rim: the rest of the root disc too).
  const double outline_area = polygon_moments(gear.transverse_outline(400)).area;
  const double toothed      = double(o.teeth) / l.z;
  const double ri = l.ri, rf = l.rf;
  info.analytic_volume = l.b * (toothed * (outline_area - pi * ri * ri) +
                                (l.round ? (1 - toothed) * pi * (rf * rf - ri * ri) : 0));

  write_mesh_atomically(path);

  std::vector<int> ids;
  for (const auto &g : groups)
    ids.push_back(g.first);
  write_text_atomically(path + ".json", segment_sidecar(l.d.name, info, ids));
}
} // namespace

std::string
boundary::name(int id)
{
  switch (id)
    {
    case bore:
      return "bore";
    case cut_start:
      return "cut_start";
    case cut_end:
      return "cut_end";
    case end_front:
      return "end_front";
    case end_back:
      return "end_back";
    case free:
      return "free";
    default:
      return "tooth" + std::to_string((id - 10) / 2) + ((id - 10) % 2 ? "_coast" : "_drive");
    }
}

std::string
segment_sidecar(const std::string &member, const SegmentMeshInfo &info,
                const std::vector<int> &boundary_ids)
{
  std::ostringstream json;
  json.precision(12);
  json << "{\n  \"gear\": \"" << member << "\",\n  \"analytic_volume\": " << info.analytic_volume
       << ",\n  \"hexahedra\": " << info.hexahedra << ",\n  \"nodes\": " << info.nodes
       << ",\n  \"rim_inner_radius\": " << info.rim_inner_radius
       << ",\n  \"worst_corner_jacobian\": " << info.worst_corner_jacobian
       << ",\n  \"gmsh_2d_algorithm\": " << info.mesh_algorithm << ",\n  \"member_teeth\": [";
  for (std::size_t i = 0; i < info.member_teeth.size(); ++i)
    json << (i ? ", " : "") << info.member_teeth[i];
  json << "],\n  \"physical_surfaces\": {";
  for (std::size_t i = 0; i < boundary_ids.size(); ++i)
    json << (i ? "," : "") << "\n    \"" << boundary::name(boundary_ids[i])
         << "\": " << boundary_ids[i];
  json << "\n  },\n  \"physical_volumes\": {\"body\": 1}\n}\n";
  return json.str();
}

SegmentMeshInfo
write_tooth_segment_mesh(const InvoluteGear &gear, const SegmentMeshOptions &o,
                         const std::string &path)
{
  const InvoluteGearData &d  = gear.data();
  const int               z  = d.teeth;
  const double            mn = d.normal_module, b = d.face_width;
  check(o.teeth == z || (o.teeth >= 1 && o.teeth % 2 == 1 && o.teeth < z &&
                         (o.whole_rim || 2 * pi * o.teeth / z <= pi + 1e-12)),
        "teeth in the segment", o.teeth,
        "an odd number >= 1 spanning at most half the gear (any on the whole rim), or all " +
            std::to_string(z) + " (the whole gear)");
  check(o.fine_teeth == 0 || (o.fine_teeth % 2 == 1 && o.fine_teeth <= o.teeth), "fine teeth",
        o.fine_teeth, "0 (all) or an odd number up to the segment's teeth");
  check(o.central_tooth >= 0 && o.central_tooth < z, "central tooth", o.central_tooth,
        "a tooth index in [0, z - 1]");
  check(o.flank_size >= 0 && o.far_size >= 0 && o.face_layers >= 0, "element size / layers",
        std::min({o.flank_size, o.far_size, double(o.face_layers)}), "values >= 0 (0 = default)");
  check(o.curve_points >= 4, "curve points", o.curve_points, ">= 4");
  check(o.other_size >= 0, "other element size", o.other_size, ">= 0 (0 = the flank size)");
  check(o.fillet_size >= 0, "fillet element size", o.fillet_size,
        ">= 0 (0 = the flank or other size)");
  if (!o.refine_points.empty())
    {
      check(d.helix_angle == 0, "refinement points (helix angle)", d.helix_angle,
            "a spur gear (local refinement follows straight contact lines)");
      const double h = o.flank_size > 0 ? o.flank_size : mn / 5;
      check(o.refine_size > 0 && o.refine_size < h && o.refine_radius > 0,
            "refinement size / radius", o.refine_size,
            "0 < size < the flank size, and a radius > 0");
    }
  check(d.chipped_teeth.empty(), "chipped teeth", double(d.chipped_teeth.size()),
        "none (the mesh is built from the nominal section)");

  SegmentMeshInfo info;
  info.rim_inner_radius = o.rim_inner_radius > 0 ? o.rim_inner_radius
                          : d.bore_diameter > 0  ? d.bore_diameter / 2
                                                 : gear.root_radius - 3.5 * mn;
  check(info.rim_inner_radius > 0 && info.rim_inner_radius < gear.root_radius - 0.5 * mn,
        "rim inner radius [mm]", info.rim_inner_radius * 1e3,
        "a radius in (0, root radius - m_n/2 = " +
            std::to_string((gear.root_radius - 0.5 * mn) * 1e3) + " mm)");
  const double flank_size = o.flank_size > 0 ? o.flank_size : mn / 5;
  // the body between the bore and the root circle at least three elements thick
  const double rim_thickness = gear.root_radius - info.rim_inner_radius;
  const double far_size =
      std::max(flank_size, std::min(o.far_size > 0 ? o.far_size : mn, rim_thickness / 3));
  const int layers =
      o.face_layers > 0 ? o.face_layers : std::max(2, int(std::lround(b / (2 * flank_size))));

  with_gmsh("tooth segment mesh",
            [&] { build_and_write(gear, o, path, info, flank_size, far_size, layers); });
  return info;
}

} // namespace gearkit

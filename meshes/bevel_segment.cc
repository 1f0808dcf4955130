#include "meshes/bevel_segment.h"

#include "meshes/gmsh_session.h"

#include <gmsh.h>

#include <array>
#include <cmath>
#include <map>
#include <sstream>

namespace gearkit
{
namespace
{
void
check(bool ok, const std::string &parameter, double value, const std::string &allowed)
{
  require_value(ok, "bevel segment mesh", parameter, value, allowed);
}

/// n + 1 fractions from 0 to 1 whose steps grow linearly from proportional to s0 to s1.
std::vector<double>
graded(int n, double s0, double s1)
{
  std::vector<double> x{0};
  for (int k = 0; k < n; ++k)
    x.push_back(x.back() + s0 + (s1 - s0) * (k + 0.5) / n);
  for (double &xi : x)
    xi /= x.back();
  return x;
}

/// Cells for a length with sizes growing from s0 to s1 (at least `least`).
int
cells(double length, double s0, double s1, int least = 1)
{
  return std::max(least, int(std::ceil(2 * length / (s0 + s1) - 1e-9)));
}

/// A point of a section A = const: polar angle and height above the pitch cone.
struct SectionPoint
{
  double theta = 0, h = 0;
};

/// One side of a tooth at one section: the lower fillet half from the root cone up (t 1 to
/// 1/2), and the tooth block's side from the fillet's middle up the upper half and the working
/// flank to the tip.
struct ToothSide
{
  std::vector<SectionPoint> lower, upper;
};

SectionPoint
section_point(const Vec3 &x, double h, double turn)
{
  return {std::atan2(x.y(), x.x()) + turn, h};
}

/// Element counts, the same for every section (taken at the mean section).
struct Counts
{
  int fillet_lower = 1, fillet_upper = 1, flank = 2, across = 2, land = 2, rim = 2, face = 2;
  std::vector<double> across_fractions, rim_fractions;
};

/// A section's nodes (theta, h) and their index structure: BevelSegmentBuilder::section's
/// phases fill it in turn (the rim's top row, then the rim's columns and the teeth's rows).
struct SectionGrid
{
  std::vector<SectionPoint> nodes;
  std::vector<int>          top; ///< the rim's top row, left to right
  std::vector<int> top_kind;     ///< per top edge: -1 free, else the tooth whose block stands on it
  std::vector<std::vector<int>> chord; ///< per tooth: the top nodes under its block
  std::vector<std::vector<int>> rim;   ///< per top node: its column from the inner cone up
  std::vector<std::vector<std::vector<int>>> tooth; ///< per tooth: rows across, nodes up

  int
  add(SectionPoint p)
  {
    nodes.push_back(p);
    return int(nodes.size()) - 1;
  }
  /// A land on the top row from a to b in n steps (from a itself if `first_node`).
  void
  land(SectionPoint a, SectionPoint b, int n, bool first_node)
  {
    for (int k = first_node ? 0 : 1; k <= n; ++k)
      {
        top.push_back(add({a.theta + (b.theta - a.theta) * k / n, a.h + (b.h - a.h) * k / n}));
        if (top.size() > 1)
          top_kind.push_back(-1);
      }
  }
};

class BevelSegmentBuilder
{
public:
  BevelSegmentBuilder(const BevelMemberFlanks &member, const SegmentMeshOptions &o, double module)
      : member(member)
      , o(o)
      , blank(member.tooth_flank(FlankSide::drive).blank_data())
      , z(member.teeth())
      , flank_size(o.flank_size > 0 ? o.flank_size : module / 5)
      , other_size(o.other_size > 0 ? o.other_size : flank_size)
      , far_size(std::max(flank_size, o.far_size > 0 ? o.far_size : module))
      , rim_thickness(o.rim_thickness > 0 ? o.rim_thickness : 3.5 * module)
  {
    check(module > 0, "module [mm]", module * 1e3, "> 0");
    check(o.teeth >= 1 && o.teeth % 2 == 1 && o.teeth < z && 2 * pi * o.teeth / z <= pi + 1e-12,
          "teeth in the segment", o.teeth, "an odd number >= 1 spanning at most half the gear");
    check(o.central_tooth >= 0 && o.central_tooth < z, "central tooth", o.central_tooth,
          "a tooth index in [0, z - 1]");
    check(o.flank_size >= 0 && o.far_size >= 0 && o.other_size >= 0 && o.face_layers >= 0,
          "element size / layers",
          std::min({o.flank_size, o.far_size, o.other_size, double(o.face_layers)}),
          "values >= 0 (0 = default)");
    check(o.rim_thickness >= 0, "rim thickness [mm]", o.rim_thickness * 1e3, ">= 0 (0 = 3.5 m)");
    check(o.refine_points.empty(), "refinement points", double(o.refine_points.size()),
          "none (spur segments only)");
    for (FlankSide side : {FlankSide::drive, FlankSide::coast})
      check(member.tooth_flank(side).blank_data().teeth == z, "blank teeth", z, "one blank");
    h_rim = -blank.dedendum - rim_thickness;
    check(blank.axial_plane(blank.mean_cone_distance - blank.face_width / 2, h_rim).y() > 0,
          "rim thickness [mm]", rim_thickness * 1e3, "a rim that stays off the axis at the toe");
    for (int i = 0; i < o.teeth; ++i)
      member_teeth.push_back(mod(o.central_tooth - (o.teeth - 1) / 2 + i, z));
    choose_counts();
  }

  /// Tooth 0's sides at the section v = A - A_m, turned by `turn`.
  ToothSide
  side(FlankSide s, double v, double turn, int n_lower, int n_upper, int n_flank) const;

  /// Nodes (theta, h) of the section at v = A - A_m, and (first call) its topology.
  std::vector<SectionPoint>
  section(double v);

  Vec3
  position(double A, const SectionPoint &p) const
  {
    const Vec2 ar = blank.axial_plane(A, p.h);
    return {ar.y() * std::cos(p.theta), ar.y() * std::sin(p.theta), ar.x()};
  }

  /// The gmsh model and files (inside a GmshSession).
  void
  write(const std::string &path, SegmentMeshInfo &info);

  /// The volume by Green's theorem per section (integral of r dtheta dh = closed integral of
  /// -(A sin gamma h + cos gamma h^2 / 2) dtheta, counter-clockwise) along boundaries sampled
  /// `samples` times per fillet half and flank; Gauss-Legendre (8 points) over A.
  double
  volume(int samples) const;

  std::vector<int> member_teeth;

private:
  void
  choose_counts();
  /// section's phases: the top row (lands, fillets and the chords under the teeth), the rim's
  /// columns and the teeth's rows, the quadrilaterals and boundary edges.
  void
  section_top(SectionGrid &g, const std::vector<ToothSide> &coast,
              const std::vector<ToothSide> &drive) const;
  void
  section_body(SectionGrid &g, const std::vector<ToothSide> &coast,
               const std::vector<ToothSide> &drive) const;
  void
  section_topology(const SectionGrid &g);

  const BevelMemberFlanks               &member;
  const SegmentMeshOptions              &o;
  const BevelBlank                       blank;
  const int                              z;
  const double                           flank_size, other_size, far_size, rim_thickness;
  double                                 h_rim = 0;
  Counts                                 counts;
  int                                    n_section = 0, orientation = 0;
  std::vector<std::array<int, 4>>        quads;
  std::vector<std::tuple<int, int, int>> edges;
};

ToothSide
BevelSegmentBuilder::side(FlankSide s, double v, double turn, int n_lower, int n_upper,
                          int n_flank) const
{
  const GeneratedFlank &f = member.tooth_flank(s);
  const FlankDomain     d = f.domain();
  ToothSide             out;
  for (int j = 0; j <= n_lower; ++j)
    {
      const auto p = f.fillet_point(1 - 0.5 * j / n_lower, v);
      out.lower.push_back(section_point(p.position, p.height, turn));
    }
  for (int j = 0; j <= n_upper; ++j)
    {
      const auto p = f.fillet_point(0.5 * (1 - double(j) / n_upper), v);
      out.upper.push_back(section_point(p.position, p.height, turn));
    }
  for (int j = 1; j <= n_flank; ++j)
    {
      const double u = d.u_min + (d.u_max - d.u_min) * j / n_flank;
      out.upper.push_back(section_point(f.evaluate(u, v).position, u, turn));
    }
  return out;
}

std::vector<SectionPoint>
BevelSegmentBuilder::section(double v)
{
  const bool             topology = quads.empty();
  const double           pitch    = 2 * pi / z;
  const Counts          &c        = counts;
  std::vector<ToothSide> coast, drive;
  for (int i = -1; i <= o.teeth; ++i) // the neighbours outside place the cuts
    {
      const double turn = pitch * (o.central_tooth - (o.teeth - 1) / 2 + i);
      const bool   in   = i >= 0 && i < o.teeth;
      coast.push_back(side(FlankSide::coast, v, turn, in ? c.fillet_lower : 1,
                           in ? c.fillet_upper : 1, in ? c.flank : 1));
      drive.push_back(side(FlankSide::drive, v, turn, in ? c.fillet_lower : 1,
                           in ? c.fillet_upper : 1, in ? c.flank : 1));
    }
  SectionGrid g;
  section_top(g, coast, drive);
  section_body(g, coast, drive);
  if (topology)
    section_topology(g);
  return g.nodes;
}

// The rim's top, left to right: half land, then per tooth the coast lower fillet, the chord
// under the tooth, the drive lower fillet and a land (the last a half land).
void
BevelSegmentBuilder::section_top(SectionGrid &g, const std::vector<ToothSide> &coast,
                                 const std::vector<ToothSide> &drive) const
{
  const Counts &c = counts;
  g.chord.resize(o.teeth);
  const SectionPoint cut_start{(drive[0].lower[0].theta + coast[1].lower[0].theta) / 2,
                               coast[1].lower[0].h};
  g.land(cut_start, coast[1].lower[0], c.land / 2, true);
  for (int i = 0; i < o.teeth; ++i)
    {
      const ToothSide &cs = coast[i + 1], &ds = drive[i + 1];
      for (int j = 1; j <= c.fillet_lower; ++j)
        {
          g.top.push_back(g.add(cs.lower[j]));
          g.top_kind.push_back(-1);
        }
      g.chord[i].push_back(g.top.back());
      for (int a = 1; a <= c.across; ++a)
        {
          const double x = c.across_fractions[a];
          if (a < c.across)
            g.top.push_back(g.add({cs.upper[0].theta + (ds.upper[0].theta - cs.upper[0].theta) * x,
                                   cs.upper[0].h + (ds.upper[0].h - cs.upper[0].h) * x}));
          else
            g.top.push_back(g.add(ds.lower[c.fillet_lower]));
          g.top_kind.push_back(i);
          g.chord[i].push_back(g.top.back());
        }
      for (int j = c.fillet_lower - 1; j >= 0; --j)
        {
          g.top.push_back(g.add(ds.lower[j]));
          g.top_kind.push_back(-1);
        }
      if (i + 1 < o.teeth)
        g.land(ds.lower[0], coast[i + 2].lower[0], c.land, false);
    }
  const ToothSide   &last = drive[o.teeth];
  const SectionPoint cut_end{(last.lower[0].theta + coast[o.teeth + 1].lower[0].theta) / 2,
                             last.lower[0].h};
  g.land(last.lower[0], cut_end, c.land / 2, false);
}

void
BevelSegmentBuilder::section_body(SectionGrid &g, const std::vector<ToothSide> &coast,
                                  const std::vector<ToothSide> &drive) const
{
  const Counts &c = counts;
  // Rim: columns under the top nodes down to the inner cone.
  const int n_top = int(g.top.size());
  g.rim.assign(n_top, std::vector<int>(c.rim + 1));
  for (int k = 0; k < n_top; ++k)
    {
      const SectionPoint t = g.nodes[g.top[k]];
      for (int l = 0; l < c.rim; ++l)
        g.rim[k][l] = g.add({t.theta, h_rim + (t.h - h_rim) * c.rim_fractions[l]});
      g.rim[k][c.rim] = g.top[k];
    }
  // Teeth: between the sides, rows at the sides' points, graded across.
  const int n_up = c.fillet_upper + c.flank;
  g.tooth.resize(o.teeth);
  for (int i = 0; i < o.teeth; ++i)
    {
      const ToothSide &cs = coast[i + 1], &ds = drive[i + 1];
      g.tooth[i].assign(c.across + 1, std::vector<int>(n_up + 1));
      for (int a = 0; a <= c.across; ++a)
        {
          g.tooth[i][a][0] = g.chord[i][a];
          const double x   = c.across_fractions[a];
          for (int b = 1; b <= n_up; ++b)
            g.tooth[i][a][b] =
                g.add({cs.upper[b].theta + (ds.upper[b].theta - cs.upper[b].theta) * x,
                       cs.upper[b].h + (ds.upper[b].h - cs.upper[b].h) * x});
        }
    }
}

void
BevelSegmentBuilder::section_topology(const SectionGrid &g)
{
  const Counts &c     = counts;
  const int     n_top = int(g.top.size());
  const int     n_up  = c.fillet_upper + c.flank;
  const auto   &rim   = g.rim;
  n_section           = int(g.nodes.size());
  auto quad           = [&](int a, int b, int cc, int d) { quads.push_back({a, b, cc, d}); };
  auto edge           = [&](int a, int b, int id) { edges.push_back({a, b, id}); };
  for (int k = 0; k + 1 < n_top; ++k)
    {
      for (int l = 0; l < c.rim; ++l)
        quad(rim[k][l], rim[k + 1][l], rim[k + 1][l + 1], rim[k][l + 1]);
      edge(rim[k][0], rim[k + 1][0], boundary::bore);
      if (g.top_kind[k] < 0)
        edge(g.top[k], g.top[k + 1], boundary::free);
    }
  for (int l = 0; l < c.rim; ++l)
    {
      edge(rim[0][l], rim[0][l + 1], boundary::cut_start);
      edge(rim[n_top - 1][l], rim[n_top - 1][l + 1], boundary::cut_end);
    }
  for (int i = 0; i < o.teeth; ++i)
    {
      const auto &t = g.tooth[i];
      for (int a = 0; a < c.across; ++a)
        {
          for (int b = 0; b < n_up; ++b)
            quad(t[a][b], t[a + 1][b], t[a + 1][b + 1], t[a][b + 1]);
          edge(t[a][n_up], t[a + 1][n_up], boundary::free);
        }
      for (int b = 0; b < n_up; ++b)
        {
          const bool flank = b >= c.fillet_upper;
          edge(t[0][b], t[0][b + 1], flank ? boundary::flank(i, FlankSide::coast) : boundary::free);
          edge(t[c.across][b], t[c.across][b + 1],
               flank ? boundary::flank(i, FlankSide::drive) : boundary::free);
        }
    }
}

void
BevelSegmentBuilder::write(const std::string &path, SegmentMeshInfo &info)
{
  const int           n_face = counts.face;
  std::vector<double> xyz;
  for (int k = 0; k <= n_face; ++k)
    {
      const double v = blank.face_width * (double(k) / n_face - 0.5);
      const auto   s = section(v);
      for (const SectionPoint &p : s)
        {
          const Vec3 x = position(blank.mean_cone_distance + v, p);
          xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
        }
    }
  const auto node = [&](int k, int i) { return std::size_t(k) * n_section + i + 1; };
  auto       X    = [&](std::size_t tag) {
    return Vec3(xyz[3 * (tag - 1)], xyz[3 * (tag - 1) + 1], xyz[3 * (tag - 1) + 2]);
  };
  // Hexahedra, oriented so that the Jacobian is positive; every corner checked.
  std::vector<std::size_t> hex;
  for (int k = 0; k < n_face; ++k)
    for (const auto &q : quads)
      {
        std::array<std::size_t, 8> h{node(k, q[0]),     node(k, q[1]),     node(k, q[2]),
                                     node(k, q[3]),     node(k + 1, q[0]), node(k + 1, q[1]),
                                     node(k + 1, q[2]), node(k + 1, q[3])};
        Vec3                       x[8];
        for (int c = 0; c < 8; ++c)
          x[c] = X(h[std::size_t(c)]);
        if (orientation == 0)
          orientation = hexahedron_corner_jacobian(x, 0) > 0 ? 1 : -1;
        if (orientation < 0)
          {
            std::swap_ranges(h.begin(), h.begin() + 4, h.begin() + 4);
            std::swap_ranges(x, x + 4, x + 4);
          }
        for (int corner = 0; corner < 8; ++corner)
          if (!(hexahedron_corner_jacobian(x, corner) > 0))
            {
              std::ostringstream msg;
              msg << "bevel segment mesh: a folded element at (" << X(h[corner]).transpose() * 1e3
                  << ") mm; try other element sizes";
              throw InputError(msg.str());
            }
        hex.insert(hex.end(), h.begin(), h.end());
      }
  std::map<int, std::vector<std::size_t>> faces;
  for (int k = 0; k < n_face; ++k)
    for (const auto &[a, b, id] : edges)
      faces[id].insert(faces[id].end(), {node(k, a), node(k, b), node(k + 1, b), node(k + 1, a)});
  for (const auto &q : quads)
    for (const auto &[k, id] : {std::pair{0, boundary::end_front}, {n_face, boundary::end_back}})
      faces[id].insert(faces[id].end(),
                       {node(k, q[0]), node(k, q[1]), node(k, q[2]), node(k, q[3])});

  gmsh::model::add("bevel_segment");
  gmsh::model::addDiscreteEntity(3, 1);
  std::vector<std::size_t> tags(xyz.size() / 3);
  for (std::size_t i = 0; i < tags.size(); ++i)
    tags[i] = i + 1;
  gmsh::model::mesh::addNodes(3, 1, tags, xyz);
  gmsh::model::mesh::addElementsByType(1, 5, {}, hex);
  std::vector<int> ids;
  for (const auto &[id, q] : faces)
    {
      gmsh::model::addDiscreteEntity(2, id);
      gmsh::model::mesh::addElementsByType(id, 3, {}, q);
      gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {id}, id),
                                   boundary::name(id));
      ids.push_back(id);
    }
  gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {1}, 1), "body");
  std::tie(info.hexahedra, info.nodes) = require_hexahedra("bevel segment mesh");
  info.member_teeth                    = member_teeth;
  write_mesh_atomically(path);
  write_text_atomically(
      path + ".json", segment_sidecar("bevel member, " + std::to_string(z) + " teeth", info, ids));
}

double
BevelSegmentBuilder::volume(int samples) const
{
  const double sg = std::sin(blank.pitch_angle), cg = std::cos(blank.pitch_angle);
  const double xg[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                        0.9602898564975363};
  const double wg[4] = {0.3626837833783620, 0.3137066115375184, 0.2223810344533745,
                        0.1012285362903763};
  const double pitch = 2 * pi / z;
  double       total = 0;
  for (int g = 0; g < 8; ++g)
    {
      const double v = blank.face_width / 2 * (g < 4 ? -xg[g] : xg[g - 4]);
      const double A = blank.mean_cone_distance + v;
      auto         P = [&](double h) { return -(A * sg * h + cg * h * h / 2); };
      // the boundary's top part from right to left (cut_end to cut_start), then the bore
      std::vector<SectionPoint> path;
      std::vector<ToothSide>    coast, drive;
      for (int i = -1; i <= o.teeth; ++i)
        {
          const double turn = pitch * (o.central_tooth - (o.teeth - 1) / 2 + i);
          coast.push_back(side(FlankSide::coast, v, turn, samples, samples, samples));
          drive.push_back(side(FlankSide::drive, v, turn, samples, samples, samples));
        }
      path.push_back({(drive[o.teeth].lower[0].theta + coast[o.teeth + 1].lower[0].theta) / 2,
                      -blank.dedendum});
      for (int i = o.teeth; i >= 1; --i)
        {
          // up the drive side, along the tip land, down the coast side
          const ToothSide &d = drive[i], &c = coast[i];
          path.insert(path.end(), d.lower.begin(), d.lower.end());
          path.insert(path.end(), d.upper.begin() + 1, d.upper.end());
          path.insert(path.end(), c.upper.rbegin(), c.upper.rend() - 1);
          path.insert(path.end(), c.lower.rbegin(), c.lower.rend());
        }
      path.push_back({(drive[0].lower[0].theta + coast[1].lower[0].theta) / 2, -blank.dedendum});
      double section = 0;
      for (std::size_t k = 0; k + 1 < path.size(); ++k) // Simpson along each straight piece
        section += (path[k + 1].theta - path[k].theta) *
                   (P(path[k].h) + 4 * P((path[k].h + path[k + 1].h) / 2) + P(path[k + 1].h)) / 6;
      // down cut_start (no dtheta), along the bore to the right, up cut_end (none)
      section += (path.front().theta - path.back().theta) * P(h_rim);
      total += wg[g % 4] * blank.face_width / 2 * section;
    }
  return total;
}

void
BevelSegmentBuilder::choose_counts()
{
  Counts &c = counts;
  // sizes at the mean section
  const ToothSide cs  = side(FlankSide::coast, 0, 0, 1, 1, 1);
  const ToothSide ds  = side(FlankSide::drive, 0, 0, 1, 1, 1);
  const double    r   = blank.axial_plane(blank.mean_cone_distance, -blank.dedendum).y();
  auto            arc = [&](const SectionPoint &a, const SectionPoint &b) {
    return std::hypot(r * (a.theta - b.theta), a.h - b.h);
  };
  c.fillet_lower = cells(std::max(arc(cs.lower[0], cs.lower[1]), arc(ds.lower[0], ds.lower[1])),
                         flank_size, flank_size);
  c.fillet_upper = cells(std::max(arc(cs.upper[0], cs.upper[1]), arc(ds.upper[0], ds.upper[1])),
                         flank_size, flank_size);
  c.flank = cells(blank.addendum - std::min(member.tooth_flank(FlankSide::coast).domain().u_min,
                                            member.tooth_flank(FlankSide::drive).domain().u_min),
                  flank_size, flank_size, 2);
  // across the tooth at the fillets' middle: from the other flank's size to the loaded one's
  const double width = r * (ds.upper[0].theta - cs.upper[0].theta);
  check(width > 0, "tooth width at the root [mm]", width * 1e3, "> 0");
  const bool drive_fine = o.fine_side == FlankSide::drive;
  c.across              = cells(width, flank_size, other_size, 2);
  c.across_fractions    = drive_fine ? graded(c.across, other_size, flank_size)
                                     : graded(c.across, flank_size, other_size);
  const double land     = r * (cs.lower[0].theta + 2 * pi / z - ds.lower[0].theta);
  check(land > 0, "root land width [mm]", land * 1e3, "> 0 (teeth do not overlap at the root)");
  c.land          = 2 * cells(land / 2, other_size, other_size);
  c.rim           = cells(rim_thickness, far_size, other_size, 2);
  c.rim_fractions = graded(c.rim, far_size, other_size);
  c.face          = o.face_layers > 0 ? o.face_layers
                                      : std::max(2, int(std::lround(blank.face_width / (2 * flank_size))));
}

} // namespace

SegmentMeshInfo
write_bevel_segment_mesh(const BevelMemberFlanks &member, double module,
                         const SegmentMeshOptions &o, const std::string &path)
{
  BevelSegmentBuilder b(member, o, module);
  SegmentMeshInfo     info;
  info.analytic_volume = b.volume(96);
  with_gmsh("bevel segment mesh", [&] { b.write(path, info); });
  return info;
}

double
bevel_segment_volume(const BevelMemberFlanks &member, const SegmentMeshOptions &o, double module,
                     int samples)
{
  return BevelSegmentBuilder(member, o, module).volume(samples);
}
} // namespace gearkit

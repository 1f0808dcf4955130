#include "tca/paper_mode.h"

#include "base/tooth_pairs.h"
#include "geometry/point_cloud.h"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <memory>
#include <sstream>

namespace gearkit
{
namespace
{
/// A flank sampled at (about) the requested spacing: points in the member frame, with the flank
/// parameters of each point (for the normals of the contact tables).
struct Cloud
{
  const Flank      *flank = nullptr;
  PointCloud<3>     points;
  std::vector<Vec2> uv;
};

std::unique_ptr<Cloud>
sample(const Flank &flank, double spacing, bool with_tree, double &a, double &b)
{
  // Grid counts from the flank's extent through its middle; a and b are the spacings reached.
  const FlankDomain d  = flank.domain();
  const double      um = 0.5 * (d.u_min + d.u_max), vm = 0.5 * (d.v_min + d.v_max);
  const double      len_u =
      (flank.evaluate(d.u_max, vm).position - flank.evaluate(d.u_min, vm).position).norm();
  const double len_v =
      (flank.evaluate(um, d.v_max).position - flank.evaluate(um, d.v_min).position).norm();
  const int nu = std::max(2, int(std::ceil(len_u / spacing)) + 1);
  const int nv = std::max(2, int(std::ceil(len_v / spacing)) + 1);
  a            = std::max(a, len_u / (nu - 1));
  b            = std::max(b, len_v / (nv - 1));
  auto cloud   = std::make_unique<Cloud>();
  cloud->flank = &flank;
  cloud->points.points.reserve(std::size_t(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      {
        const double u = d.u_min + (d.u_max - d.u_min) * i / (nu - 1);
        const double v = d.v_min + (d.v_max - d.v_min) * j / (nv - 1);
        if (flank.contains(u, v))
          {
            cloud->points.points.push_back(flank.evaluate(u, v).position);
            cloud->uv.emplace_back(u, v);
          }
      }
  if (with_tree)
    cloud->points.build();
  return cloud;
}

bool
on_edge(const Flank &flank, const Vec2 &uv)
{
  const FlankDomain d   = flank.domain();
  const double      tol = 1e-9;
  return uv.x() - d.u_min < tol * (d.u_max - d.u_min) ||
         d.u_max - uv.x() < tol * (d.u_max - d.u_min) ||
         uv.y() - d.v_min < tol * (d.v_max - d.v_min) ||
         d.v_max - uv.y() < tol * (d.v_max - d.v_min);
}

/// One tooth pair in mesh: the pinion cloud, its points in the gear's unrotated frame, the gear
/// cloud.
struct MeshingPair
{
  int               pinion_tooth, gear_tooth;
  const Cloud      *pinion, *gear;
  std::vector<Vec3> q;
};

/// Closest points of a pair with the gear turned by psi: squared distance, pinion and gear
/// point indices.
struct Closest
{
  double      d2     = HUGE_VAL;
  std::size_t pinion = 0, gear = 0;
};

Closest
closest(const MeshingPair &pair, const Eigen::Matrix3d &R, std::size_t &queries)
{
  Closest c;
  for (std::size_t i = 0; i < pair.q.size(); ++i)
    {
      const auto [j, d2] = pair.gear->points.nearest(R * pair.q[i]);
      ++queries;
      if (d2 < c.d2)
        c = {d2, i, j};
    }
  return c;
}
} // namespace

PaperModeResult
paper_mode_ste(const MemberFlanks &pinion, const MemberFlanks &gear, double a_w,
               const Misalignment &m, const PaperModeOptions &o)
{
  return paper_mode_ste(pinion, gear, Assembly(a_w, gear.teeth(), m), o);
}

PaperModeResult
paper_mode_ste(const MemberFlanks &pinion, const MemberFlanks &gear, const Assembly &assembly,
               const PaperModeOptions &o)
{
  if (o.spacing <= 0 || o.rotation_step <= 0 || o.positions_per_mesh < 1 || o.mesh_cycles < 1)
    throw InputError("paper mode: spacing, rotation step, positions and cycles must be > 0");
  const int    z1 = pinion.teeth(), z2 = gear.teeth();
  const double ratio = double(z1) / z2;
  const bool   drive = o.side == FlankSide::drive;

  PaperModeResult result;
  result.tca.mesh_angle = 2 * pi / z1;
  double a = 0, b = 0;
  double r_max = 0; // largest driven-flank radius: the r of l = r theta in the tolerance
  std::map<int, std::unique_ptr<Cloud>> pinion_clouds, gear_clouds;
  auto cloud = [&](std::map<int, std::unique_ptr<Cloud>> &clouds, const MemberFlanks &member,
                   int tooth, bool tree) -> const Cloud * {
    if (!member.has(tooth, o.side))
      return nullptr;
    auto &c = clouds[tooth];
    if (!c)
      {
        c = sample(member.flank(tooth, o.side), o.spacing, tree, a, b);
        result.points += c->uv.size();
        if (tree)
          for (const Vec3 &x : c->points.points)
            r_max = std::max(r_max, x.head<2>().norm());
      }
    return c.get();
  };

  double       previous = NAN;
  const double s        = drive ? 1.0 : -1.0;
  const int    n        = o.positions_per_mesh * o.mesh_cycles;
  for (int i = 0; i < n; ++i)
    {
      const double phi = o.start_angle + result.tca.mesh_angle * i / o.positions_per_mesh;
      const int    k0  = int(std::lround(phi * z1 / (2 * pi)));
      std::vector<MeshingPair> pairs;
      for (int k = k0 - 2; k <= k0 + 2; ++k)
        {
          const int    tp = mod(-k, z1), tg = mod(drive ? k - 1 : k, z2);
          const Cloud *p = cloud(pinion_clouds, pinion, tp, false);
          const Cloud *g = cloud(gear_clouds, gear, tg, true);
          if (!p || !g)
            continue;
          MeshingPair pair{tp, tg, p, g, {}};
          pair.q.reserve(p->uv.size());
          for (const Vec3 &x : p->points.points)
            pair.q.push_back(assembly.global_to_gear_unrotated(assembly.pinion_to_global(x, phi)));
          pairs.push_back(std::move(pair));
        }
      if (pairs.empty())
        throw InputError("paper mode: no measured tooth pair in mesh at pinion angle " +
                         std::to_string(phi));
      const double l        = r_max * o.rotation_step;
      const double smallest = std::sqrt(a * a / 4 + b * b / 4 + l * l);
      if (o.tolerance > 0 && o.tolerance < smallest)
        {
          std::ostringstream m;
          m << "paper mode: tolerance E = " << o.tolerance * 1e6 << " um is below sqrt((a/2)^2 + "
            << "(b/2)^2 + (r theta)^2) = " << smallest * 1e6 << " um (a = " << a * 1e6
            << " um, b = " << b * 1e6 << " um, r theta = " << l * 1e6
            << " um); expected E >= that, or 0 for it";
          throw InputError(m.str());
        }
      result.tolerance = std::max(o.tolerance, smallest);
      const double E   = result.tolerance;

      auto min_distance = [&](double psi) {
        const Eigen::Matrix3d R    = Eigen::AngleAxisd(psi, Vec3::UnitZ()).toRotationMatrix();
        double                best = HUGE_VAL;
        for (const MeshingPair &pair : pairs)
          for (const Vec3 &x : pair.q)
            {
              best = std::min(best, pair.gear->points.nearest(R * x).second);
              ++result.queries;
            }
        return std::sqrt(best);
      };
      // The seed steps the driven member by theta until the clouds come within E. The same
      // first step is found here by bisection over the step count (the distance falls
      // monotonically as the members approach), after bracketing from the previous solution:
      // log2 of the steps instead of all of them, with the identical result.
      double apart = std::isnan(previous)
                         ? ratio * phi
                         : previous + ratio * result.tca.mesh_angle / o.positions_per_mesh;
      for (double step = o.rotation_step; min_distance(apart) <= E; step *= 2)
        apart += s * step;
      double touching = apart;
      for (double step = o.rotation_step; min_distance(touching) > E; step *= 2)
        touching -= s * step;
      long lo = 0, hi = long(std::ceil(std::abs(apart - touching) / o.rotation_step));
      while (hi - lo > 1)
        {
          const long mid                                                   = (lo + hi) / 2;
          (min_distance(apart - s * mid * o.rotation_step) <= E ? hi : lo) = mid;
        }
      const double psi = apart - s * hi * o.rotation_step;
      previous         = psi;

      // The tables at the position found: closest points of every pair.
      TcaPosition pos;
      pos.pinion_angle           = phi;
      pos.gear_angle             = psi;
      pos.transmission_error     = phi - psi / ratio;
      const Eigen::Matrix3d R    = Eigen::AngleAxisd(psi, Vec3::UnitZ()).toRotationMatrix();
      const Vec3            axis = assembly.gear_axis();
      for (const MeshingPair &pair : pairs)
        {
          const Closest cl = closest(pair, R, result.queries);
          PairContact   c;
          c.pinion_tooth  = pair.pinion_tooth;
          c.gear_tooth    = pair.gear_tooth;
          c.found         = true;
          const Vec2 &uv1 = pair.pinion->uv[cl.pinion];
          const Vec2 &uv2 = pair.gear->uv[cl.gear];
          c.u1 = uv1.x(), c.v1 = uv1.y(), c.u2 = uv2.x(), c.v2 = uv2.y();
          c.edge       = on_edge(*pair.pinion->flank, uv1) || on_edge(*pair.gear->flank, uv2);
          c.separation = std::sqrt(cl.d2);
          set_contact_geometry(c, assembly, *pair.pinion->flank, *pair.gear->flank, phi, psi);
          // The gear rotation that would close this pair's gap (as in classical TCA).
          const double arm =
              std::abs(axis.cross(c.position - assembly.gear_centre()).dot(c.normal_gear));
          c.touch_angle = psi - s * c.separation / arm;
          if (c.separation <= E)
            ++pos.touching;
          if (pos.leading < 0 || c.separation < pos.pairs[pos.leading].separation)
            pos.leading = int(pos.pairs.size());
          pos.pairs.push_back(c);
        }
      result.tca.positions.push_back(std::move(pos));
      if (o.on_position)
        o.on_position();
    }
  summarise(result.tca);
  const TcaPosition &first = result.tca.positions.front();
  for (const TcaPosition &p : result.tca.positions)
    result.seed_ste.push_back((p.pinion_angle - first.pinion_angle) -
                              (p.gear_angle - first.gear_angle) / ratio);
  return result;
}
} // namespace gearkit

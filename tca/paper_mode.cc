#include "paper_mode.h"

#include "point_cloud.h"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <memory>

namespace gearkit
{
namespace
{
int
mod(int a, int n)
{
  return ((a % n) + n) % n;
}

/// A flank sampled at (about) the requested spacing: points in the member frame.
using Cloud = PointCloud<3>;

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
  cloud->points.reserve(std::size_t(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      {
        const double u = d.u_min + (d.u_max - d.u_min) * i / (nu - 1);
        const double v = d.v_min + (d.v_max - d.v_min) * j / (nv - 1);
        if (flank.contains(u, v))
          cloud->points.push_back(flank.evaluate(u, v).position);
      }
  if (with_tree)
    cloud->build();
  return cloud;
}
} // namespace

PaperModeResult
paper_mode_ste(const MemberFlanks &pinion, const MemberFlanks &gear, double a_w,
               const Misalignment &m, const PaperModeOptions &o)
{
  if (o.spacing <= 0 || o.rotation_step <= 0 || o.positions_per_mesh < 1 || o.mesh_cycles < 1)
    throw InputError("paper mode: spacing, rotation step, positions and cycles must be > 0");
  const Assembly assembly(a_w, gear.teeth(), m);
  const int      z1 = pinion.teeth(), z2 = gear.teeth();
  const double   ratio = double(z1) / z2;
  const bool     drive = o.side == FlankSide::drive;

  PaperModeResult result;
  double          a = 0, b = 0;
  double          r_max = 0; // largest driven-flank radius: the r of l = r theta in the tolerance
  std::map<int, std::unique_ptr<Cloud>> pinion_clouds, gear_clouds;
  auto cloud = [&](std::map<int, std::unique_ptr<Cloud>> &clouds, const MemberFlanks &member,
                   int tooth, bool tree) -> const Cloud * {
    if (!member.has(tooth, o.side))
      return nullptr;
    auto &c = clouds[tooth];
    if (!c)
      {
        c = sample(member.flank(tooth, o.side), o.spacing, tree, a, b);
        result.points += c->points.size();
        if (tree)
          for (const Vec3 &x : c->points)
            r_max = std::max(r_max, x.head<2>().norm());
      }
    return c.get();
  };

  double    previous = NAN;
  const int n        = o.positions_per_mesh * o.mesh_cycles;
  for (int i = 0; i < n; ++i)
    {
      const double phi = o.start_angle + 2 * pi / z1 * i / o.positions_per_mesh;
      const int    k0  = int(std::lround(phi * z1 / (2 * pi)));
      // Pinion points of the pairs in mesh, in the gear's unrotated frame (Q), with their gear.
      std::vector<std::pair<const Cloud *, std::vector<Vec3>>> pairs;
      for (int k = k0 - 2; k <= k0 + 2; ++k)
        {
          const Cloud *p = cloud(pinion_clouds, pinion, mod(-k, z1), false);
          const Cloud *g = cloud(gear_clouds, gear, mod(drive ? k - 1 : k, z2), true);
          if (!p || !g)
            continue;
          std::vector<Vec3> q;
          q.reserve(p->points.size());
          for (const Vec3 &x : p->points)
            q.push_back(assembly.global_to_gear_unrotated(assembly.pinion_to_global(x, phi)));
          pairs.emplace_back(g, std::move(q));
        }
      if (pairs.empty())
        throw InputError("paper mode: no measured tooth pair in mesh at pinion angle " +
                         std::to_string(phi));
      const double l   = r_max * o.rotation_step;
      result.tolerance = std::sqrt(a * a / 4 + b * b / 4 + l * l);
      const double E   = result.tolerance;

      auto min_distance = [&](double psi) {
        const Eigen::Matrix3d R    = Eigen::AngleAxisd(psi, Vec3::UnitZ()).toRotationMatrix();
        double                best = HUGE_VAL;
        for (const auto &[g, q] : pairs)
          for (const Vec3 &x : q)
            {
              best = std::min(best, g->nearest(R * x).second);
              ++result.queries;
            }
        return std::sqrt(best);
      };
      // The seed steps the driven member by theta until the clouds come within E. The same
      // first step is found here by bisection over the step count (the distance falls
      // monotonically as the members approach), after bracketing from the previous solution:
      // log2 of the steps instead of all of them, with the identical result.
      const double s     = drive ? 1.0 : -1.0;
      double       apart = std::isnan(previous) ? ratio * phi
                                                : previous + ratio * 2 * pi / z1 / o.positions_per_mesh;
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
      result.pinion_angle.push_back(phi);
      result.gear_angle.push_back(psi);
    }
  for (int i = 0; i < n; ++i)
    result.transmission_error.push_back((result.pinion_angle[i] - result.pinion_angle[0]) -
                                        (result.gear_angle[i] - result.gear_angle[0]) / ratio);
  return result;
}
} // namespace gearkit

#include "stiffness/flank_compliance.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace gearkit
{
int
face_grid_points(double face_width, double module)
{
  if (!(face_width > 0 && module > 0))
    throw InputError("face grid points: face width and module must be > 0");
  return std::clamp(1 + int(std::ceil(2 * face_width / module - 1e-9)), 7, 25);
}

FlankCompliance::FlankCompliance(const MemberFlanks &flanks, const FlankGridSpec &s)
    : spec(s)
    , member_teeth(flanks.teeth())
{
  if (spec.teeth.empty() || spec.n_u < 2 || spec.n_v < 2 || !(spec.margin >= 0) ||
      !(spec.margin < 0.5))
    throw InputError("flank compliance grid: needs at least one tooth, n_u and n_v >= 2 and a "
                     "margin in [0, 0.5)");
  if (spec.cyclic_tooth < 0)
    with_grid = spec.teeth;
  else
    {
      if (spec.cyclic_tooth >= member_teeth || spec.cyclic_reach < 0 ||
          2 * spec.cyclic_reach + 1 > member_teeth)
        throw InputError("flank compliance grid: a cyclic tooth in [0, z) and a reach in [0, "
                         "(z - 1) / 2] expected");
      for (int k = -spec.cyclic_reach; k <= spec.cyclic_reach; ++k)
        with_grid.push_back(((spec.cyclic_tooth + k) % member_teeth + member_teeth) % member_teeth);
    }
  auto nodes = [&](int n) {
    std::vector<double> x(std::size_t(n), 0.0);
    for (int i = 0; i < n; ++i)
      x[std::size_t(i)] = spec.graded ? (1 - std::cos(pi * i / (n - 1))) / 2 : double(i) / (n - 1);
    x.back() = 1;
    return x;
  };
  u_nodes = nodes(spec.n_u), v_nodes = nodes(spec.n_v);
  for (int tooth : with_grid)
    {
      const Flank      &f  = flanks.flank(tooth, spec.side);
      const FlankDomain d  = f.domain();
      const double      du = d.u_max - d.u_min, dv = d.v_max - d.v_min;
      u_range.emplace_back(d.u_min + spec.margin * du, d.u_max - spec.margin * du);
      v_range.emplace_back(d.v_min + spec.margin * dv, d.v_max - spec.margin * dv);
      for (int i = 0; i < spec.n_u; ++i)
        for (int j = 0; j < spec.n_v; ++j)
          {
            Point p;
            p.tooth = tooth;
            p.u     = u_range.back().first +
                  (u_range.back().second - u_range.back().first) * u_nodes[std::size_t(i)];
            p.v = v_range.back().first +
                  (v_range.back().second - v_range.back().first) * v_nodes[std::size_t(j)];
            const FlankPoint q = f.evaluate(p.u, p.v);
            p.position = q.position, p.normal = q.normal;
            p.face_direction = flanks.face_direction(q.position);
            if (spec.cyclic_tooth < 0 || tooth == spec.cyclic_tooth)
              loaded.push_back(grid.size());
            grid.push_back(p);
          }
    }
  load_base = int(loaded.front());
}

void
FlankCompliance::set(const Eigen::MatrixXd &compliance)
{
  const Eigen::Index n = Eigen::Index(grid.size()), m = Eigen::Index(loaded.size());
  if (compliance.rows() != n || compliance.cols() != m || !compliance.allFinite())
    throw InputError("flank compliance: the matrix must be finite and " + std::to_string(n) +
                     " x " + std::to_string(m));
  S = compliance;
}

bool
FlankCompliance::covers(int tooth) const
{
  return std::find(spec.teeth.begin(), spec.teeth.end(), tooth) != spec.teeth.end();
}

FlankCompliance::Weights
FlankCompliance::weights(int tooth, double u, double v) const
{
  const auto it = std::find(with_grid.begin(), with_grid.end(), tooth);
  if (it == with_grid.end())
    throw InputError("flank compliance: tooth " + std::to_string(tooth) +
                     " carries load but lies outside the finite-element segment's loaded teeth");
  const int t = int(it - with_grid.begin());
  // the interval of the nodes x lies in, and the fraction along it
  auto frac = [](double x, double lo, double hi, const std::vector<double> &nodes, int &i0) {
    const double f = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    i0 = std::clamp(int(std::upper_bound(nodes.begin(), nodes.end(), f) - nodes.begin()) - 1, 0,
                    int(nodes.size()) - 2);
    return (f - nodes[std::size_t(i0)]) / (nodes[std::size_t(i0) + 1] - nodes[std::size_t(i0)]);
  };
  int          iu, iv;
  const double fu   = frac(u, u_range[t].first, u_range[t].second, u_nodes, iu);
  const double fv   = frac(v, v_range[t].first, v_range[t].second, v_nodes, iv);
  const int    base = t * spec.n_u * spec.n_v;
  Weights      w;
  int          k = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b, ++k)
      {
        w.index[k]  = base + (iu + a) * spec.n_v + iv + b;
        w.weight[k] = (a ? fu : 1 - fu) * (b ? fv : 1 - fv);
        w.u[k]      = u_range[t].first +
                 u_nodes[std::size_t(iu + a)] * (u_range[t].second - u_range[t].first);
        w.v[k] = v_range[t].first +
                 v_nodes[std::size_t(iv + b)] * (v_range[t].second - v_range[t].first);
      }
  return w;
}

double
FlankCompliance::operator()(int tooth_i, double u_i, double v_i, int tooth_j, double u_j,
                            double v_j) const
{
  if (S.size() == 0)
    throw InputError("flank compliance: the table has not been filled");
  if (spec.cyclic_tooth >= 0)
    {
      // the load moved onto the cyclic tooth, the response turned with it
      const int offset = tooth_offset(tooth_i, tooth_j);
      if (std::abs(offset) > spec.cyclic_reach)
        throw InputError("flank compliance: teeth " + std::to_string(tooth_i) + " and " +
                         std::to_string(tooth_j) + " in contact at once lie " +
                         std::to_string(std::abs(offset)) +
                         " teeth apart, further than the middle tooth's responses reach (" +
                         std::to_string(spec.cyclic_reach) + ")");
      tooth_i = spec.cyclic_tooth, tooth_j = cyclic_turned(offset);
    }
  const bool    follow = spec.follow_load && tooth_i == tooth_j;
  const Weights wj     = weights(tooth_j, u_j, v_j);
  const Weights fixed  = follow ? Weights{} : weights(tooth_i, u_i, v_i);
  if (!follow)
    return interpolate(fixed, wj);
  double c = 0;
  for (int b = 0; b < 4; ++b)
    {
      // following the load: the response at the same offset from each of the load's corners
      const Weights wi = weights(tooth_i, u_i + wj.u[b] - u_j, v_i + wj.v[b] - v_j);
      for (int a = 0; a < 4; ++a)
        c += wi.weight[a] * wj.weight[b] * S(wj.index[b], wi.index[a] - load_base);
    }
  return c;
}

int
FlankCompliance::tooth_offset(int from, int to) const
{
  // signed: the nearer way round
  return ((to - from) % member_teeth + member_teeth + member_teeth / 2) % member_teeth -
         member_teeth / 2;
}

int
FlankCompliance::cyclic_turned(int offset) const
{
  return ((spec.cyclic_tooth + offset) % member_teeth + member_teeth) % member_teeth;
}

double
FlankCompliance::interpolate(const Weights &wi, const Weights &wj) const
{
  double c = 0;
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a)
      c += wi.weight[a] * wj.weight[b] * S(wj.index[b], wi.index[a] - load_base);
  return c;
}

Eigen::MatrixXd
FlankCompliance::matrix(const std::vector<Location> &at) const
{
  const Eigen::Index n = Eigen::Index(at.size());
  Eigen::MatrixXd    M(n, n);
  if (spec.follow_load)
    {
      // the load's weights depend on the response's corners: pair by pair
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j)
          M(j, i) = (*this)(at[i].tooth, at[i].u, at[i].v, at[j].tooth, at[j].u, at[j].v);
      return M;
    }
  if (S.size() == 0)
    throw InputError("flank compliance: the table has not been filled");
  // Without a cyclic tooth each point is read on its own tooth (offset 0). With one, a load is
  // read on the cyclic tooth and a response on the tooth as far from it as the response's tooth
  // from the load's: the weights of each point at each such offset, found once.
  const bool                                       cyclic = spec.cyclic_tooth >= 0;
  const int                                        reach  = cyclic ? spec.cyclic_reach : 0;
  std::vector<std::vector<std::optional<Weights>>> cache(
      std::size_t(2 * reach + 1), std::vector<std::optional<Weights>>(at.size()));
  auto weights_at = [&](std::size_t k, int offset) -> const Weights & {
    std::optional<Weights> &w = cache[std::size_t(offset + reach)][k];
    if (!w)
      w = weights(cyclic ? cyclic_turned(offset) : at[k].tooth, at[k].u, at[k].v);
    return *w;
  };
  for (Eigen::Index i = 0; i < n; ++i)
    {
      const Weights &wi = weights_at(std::size_t(i), 0);
      for (Eigen::Index j = 0; j < n; ++j)
        {
          const int offset = cyclic ? tooth_offset(at[i].tooth, at[j].tooth) : 0;
          if (std::abs(offset) > reach) // refused, with operator()'s message
            (*this)(at[i].tooth, at[i].u, at[i].v, at[j].tooth, at[j].u, at[j].v);
          M(j, i) = interpolate(wi, weights_at(std::size_t(j), offset));
        }
    }
  return M;
}

double
disk_load_displacement(double r, double z, double radius, const Material &material)
{
  if (radius == 0)
    return point_load_displacement(r, z, 1.0, material);
  // Equal-area rings (midpoints in rho^2) times equally spaced angles: the point solution
  // averaged over the disk; smooth there, since the response lies well below the surface.
  constexpr int rings = 6, angles = 24;
  double        sum = 0;
  for (int i = 0; i < rings; ++i)
    {
      const double rho = radius * std::sqrt((i + 0.5) / rings);
      for (int k = 0; k < angles; ++k)
        {
          const double a = 2 * pi * (k + 0.5) / angles;
          sum += point_load_displacement(std::hypot(r - rho * std::cos(a), rho * std::sin(a)), z,
                                         1.0, material);
        }
    }
  return sum / (rings * angles);
}

Vec3
response_offset(const FlankCompliance::Point &point)
{
  const Vec3 across = point.normal - point.normal.dot(point.face_direction) * point.face_direction;
  return -across / across.squaredNorm();
}

void
fill_structural_compliance(FlankCompliance &table, const ElasticResponse &solve,
                           const std::vector<double> &depths, const Material &material,
                           double patch_radius)
{
  const auto                        &points = table.points();
  const auto                        &loaded = table.load_points();
  std::vector<FlankLoad>             loads;
  std::vector<std::pair<Vec3, Vec3>> responses;
  if (depths.size() != points.size())
    throw InputError("flank compliance: " + std::to_string(depths.size()) +
                     " response depths for " + std::to_string(points.size()) + " grid points");
  for (std::size_t i : loaded)
    loads.push_back({points[i].tooth, points[i].position, -points[i].normal});
  for (std::size_t j = 0; j < points.size(); ++j)
    responses.emplace_back(points[j].position + depths[j] * response_offset(points[j]),
                           -points[j].normal);
  Eigen::MatrixXd D = solve(loads, responses);
  for (std::size_t k = 0; k < loaded.size(); ++k)
    for (std::size_t j = 0; j < points.size(); ++j)
      if (points[loaded[k]].tooth == points[j].tooth)
        {
          const FlankCompliance::Point &p = points[loaded[k]];
          const Vec3                    d = responses[j].first - p.position;
          const double z = -d.dot(p.normal); // depth below the load's tangent plane
          const double r = (d + z * p.normal).norm();
          D(Eigen::Index(j), Eigen::Index(k)) -=
              disk_load_displacement(r, std::max(z, 0.0), patch_radius, material);
        }
  table.set(D);
}
} // namespace gearkit

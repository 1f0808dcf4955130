#include "driver/results_ste.h"

#include "base/spectrum.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace gearkit
{
std::pair<double, double>
write_tca_tables(const TcaResult &r, const TcaScene &t, const PairMembers &members,
                 const H5Group &g)
{
  const int n = int(r.positions.size()), z1 = members.pinion->teeth();

  // Per-position tables; pair slots padded to the most pairs met at any position.
  std::size_t slots = 0;
  for (const TcaPosition &p : r.positions)
    slots = std::max(slots, p.pairs.size());
  std::vector<double> phi, psi, te, sep, u1, v1, u2, v2, X, np, ng, lp, lg, kmin, kmax, major, axes,
      ellipse_gear;
  std::vector<int> touching, leading, ptooth, gtooth, edge;
  double           te_min = HUGE_VAL, te_max = -HUGE_VAL, pairs_sum = 0;
  for (const TcaPosition &p : r.positions)
    {
      phi.push_back(p.pinion_angle);
      psi.push_back(p.gear_angle);
      te.push_back(p.transmission_error);
      te_min = std::min(te_min, p.transmission_error);
      te_max = std::max(te_max, p.transmission_error);
      touching.push_back(p.touching);
      leading.push_back(p.leading);
      pairs_sum += p.touching;
      for (std::size_t k = 0; k < slots; ++k)
        {
          const bool         used = k < p.pairs.size();
          const PairContact  none;
          const PairContact &c = used ? p.pairs[k] : none;
          ptooth.push_back(used ? c.pinion_tooth : -1);
          gtooth.push_back(used ? c.gear_tooth : -1);
          edge.push_back(c.edge ? 1 : 0);
          sep.push_back(c.separation);
          u1.push_back(c.u1), v1.push_back(c.v1), u2.push_back(c.u2), v2.push_back(c.v2);
          kmin.push_back(c.curvature_min), kmax.push_back(c.curvature_max);
          const auto [a, b] = used ? contact_ellipse(c, t.elastic_approach) : std::pair{0.0, 0.0};
          axes.insert(axes.end(), {a, b});
          // contact point and ellipse semi-axis vectors in the gear's own frame (contact
          // pattern on the gear flank)
          const Eigen::Matrix3d turn    = Eigen::AngleAxisd(p.gear_angle, Vec3::UnitZ()).matrix();
          const Vec3            minor   = c.normal_pinion.cross(c.major_direction);
          const auto            to_gear = [&](const Vec3 &v) {
            return Vec3(turn * members.assembly.global_to_gear_unrotated_vector(v));
          };
          const Vec3 Xg = used ? Vec3(turn * members.assembly.global_to_gear_unrotated(c.position))
                               : Vec3::Zero();
          const Vec3 A  = used ? to_gear(a * c.major_direction) : Vec3::Zero();
          const Vec3 B  = used ? to_gear(b * minor) : Vec3::Zero();
          for (const Vec3 *v : {&Xg, &A, &B})
            ellipse_gear.insert(ellipse_gear.end(), v->data(), v->data() + 3);
          for (auto [v, dest] : {std::pair{&c.position, &X},
                                 {&c.normal_pinion, &np},
                                 {&c.normal_gear, &ng},
                                 {&c.lambda_pinion, &lp},
                                 {&c.lambda_gear, &lg},
                                 {&c.major_direction, &major}})
            dest->insert(dest->end(), v->data(), v->data() + 3);
        }
    }
  const hsize_t       N = n, S = slots;
  const double        r_p = members.pitch_radius;
  std::vector<double> te_pitch(te.size());
  std::transform(te.begin(), te.end(), te_pitch.begin(), [&](double e) { return e * r_p; });

  if (members.centre_distance > 0)
    g.write("centre_distance", members.centre_distance);
  g.write("pitch_radius", r_p);
  g.write("pinion_angle", phi, {N});
  g.write("gear_angle", psi, {N});
  g.write("transmission_error", te, {N});
  g.write("transmission_error_pitch", te_pitch, {N});
  g.write("peak_to_peak", te_max - te_min);
  const std::vector<double> h = mesh_order_amplitudes(te_pitch, t.options.mesh_cycles, t.harmonics);
  g.write("harmonics", h, {h.size()});
  if (t.hunting)
    {
      // The signal repeats after the hunting cycle: its fundamental is 1 / revolutions pinion
      // orders, so gear-tooth errors (gear order 1 = pinion order z1 / z2) land on lines too.
      const int                 revolutions = t.options.mesh_cycles / z1;
      const std::vector<double> amplitude =
          mesh_order_amplitudes(te_pitch, 1, revolutions * z1 * t.harmonics);
      std::vector<double> order(amplitude.size());
      for (std::size_t k = 0; k < order.size(); ++k)
        order[k] = double(k) / revolutions;
      g.write("shaft_order", order, {order.size()});
      g.write("shaft_order_spectrum", amplitude, {amplitude.size()});
    }
  g.write("pairs_in_contact", touching, {N});
  g.write("mean_pairs_in_contact", pairs_sum / n);
  g.write("leading", leading, {N});
  g.write("pinion_tooth", ptooth, {N, S});
  g.write("gear_tooth", gtooth, {N, S});
  g.write("edge_contact", edge, {N, S});
  g.write("separation", sep, {N, S});
  g.write("pinion_u", u1, {N, S});
  g.write("pinion_v", v1, {N, S});
  g.write("gear_u", u2, {N, S});
  g.write("gear_v", v2, {N, S});
  g.write("contact_point", X, {N, S, 3});
  g.write("normal_pinion", np, {N, S, 3});
  g.write("normal_gear", ng, {N, S, 3});
  g.write("lambda_pinion", lp, {N, S, 3});
  g.write("lambda_gear", lg, {N, S, 3});
  g.write("relative_curvature_min", kmin, {N, S});
  g.write("relative_curvature_max", kmax, {N, S});
  g.write("contact_ellipse_direction", major, {N, S, 3});
  g.write("contact_ellipse_axes", axes, {N, S, 2});
  g.write("contact_in_gear_frame", ellipse_gear, {N, S, 3, 3});
  g.write("elastic_approach", t.elastic_approach);
  return {te_max - te_min, pairs_sum / n};
}

ContactTables
contact_tables(const TcaResult &r)
{
  ContactTables t;
  t.positions = r.positions.size();
  for (const TcaPosition &p : r.positions)
    t.slots = std::max(t.slots, p.pairs.size());
  for (const TcaPosition &p : r.positions)
    {
      t.transmission_error.push_back(p.transmission_error);
      t.leading.push_back(p.leading);
      for (std::size_t k = 0; k < t.slots; ++k)
        {
          const PairContact none, &c = k < p.pairs.size() ? p.pairs[k] : none;
          for (auto [v, dest] : {std::pair{&c.normal_pinion, &t.normal_pinion},
                                 {&c.lambda_pinion, &t.lambda_pinion},
                                 {&c.lambda_gear, &t.lambda_gear}})
            dest->insert(dest->end(), v->data(), v->data() + 3);
        }
    }
  return t;
}

ContactTables
contact_tables(const H5Group &ste)
{
  ContactTables        t;
  std::vector<hsize_t> shape;
  t.normal_pinion      = ste.read_doubles("normal_pinion", &shape);
  t.lambda_pinion      = ste.read_doubles("lambda_pinion");
  t.lambda_gear        = ste.read_doubles("lambda_gear");
  t.transmission_error = ste.read_doubles("transmission_error");
  t.leading            = ste.read_ints("leading");
  t.positions = shape[0], t.slots = shape[1];
  return t;
}

Vec2
contact_pattern_centre(const H5Group &tables)
{
  std::vector<hsize_t> shape;
  const auto           X    = tables.read_doubles("contact_in_gear_frame", &shape);
  const auto           lead = tables.read_ints("leading");
  Vec2                 c    = Vec2::Zero();
  for (std::size_t i = 0; i < shape[0]; ++i)
    {
      const std::size_t at = ((i * shape[1] + std::size_t(std::max(lead[i], 0))) * 3) * 3;
      c += Vec2(std::hypot(X[at], X[at + 1]), X[at + 2]);
    }
  return c / double(shape[0]);
}
} // namespace gearkit

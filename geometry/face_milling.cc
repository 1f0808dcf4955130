#include "geometry/face_milling.h"

#include <Eigen/LU>

#include <cmath>
#include <sstream>
#include <unsupported/Eigen/AutoDiff>

namespace gearkit
{
namespace
{
using AD                    = Eigen::AutoDiffScalar<Eigen::Vector3d>;
template <class T> using V3 = Eigen::Matrix<T, 3, 1>;

/// Everything the generation chain gives at one (s, theta, psi_c).
template <class T> struct ChainValues
{
  V3<T> position; ///< flank frame
  V3<T> normal;   ///< work outward normal, flank frame
  T     meshing;  ///< n . v (generated) or psi_c A_m (formate)
  T     axial;    ///< coordinate along the blank axis
  T     radius;   ///< distance from the blank axis
};

template <class T>
V3<T>
rotate_z(const V3<T> &x, const T &c, const T &s)
{
  return V3<T>(c * x.x() - s * x.y(), s * x.x() + c * x.y(), x.z());
}
} // namespace

/// Axes of the cutter frame in the cradle frame (columns): z along the cutter axis, x the cradle
/// x axis made perpendicular to it (identity without tilt).
Eigen::Matrix3d
cutter_frame(const MachineSettings &m)
{
  const double d = m.cradle_angle + m.swivel;
  const Vec3   k(std::sin(m.tilt) * std::cos(d), std::sin(m.tilt) * std::sin(d), std::cos(m.tilt));
  const Vec3   x = (Vec3::UnitX() - Vec3::UnitX().dot(k) * k).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x, R.col(1) = k.cross(x), R.col(2) = k;
  return R;
}

// Blade meridian at s: radius rho, height z above the pitch plane and the unit normal (n_rho,
// n_z) into the work. Straight plus a parabolic displacement kappa (s - s0)^2 along the straight
// blade's normal n0 = (sigma cos a, sin a); beyond s_round (edge radius r_e > 0) the tip rounding:
// an arc of radius r_e tangent to the blade there, s its arc length, turning the normal toward
// the cutter axis (the tip plane), reached at s_round + r_e (pi/2 - a_j).
template <class T>
void
blade_meridian(const Blade &blade, double s_round, const T &s, T &rho, T &z, T &n_rho, T &n_z)
{
  using std::cos;
  using std::sin;
  using std::sqrt;
  const double sa = std::sin(blade.angle), ca = std::cos(blade.angle);
  const double sigma   = blade.slope;
  auto         profile = [&](const auto &s_, auto &rho_, auto &z_, auto &nr_, auto &nz_) {
    const auto ds     = s_ - blade.parabola_apex;
    const auto bulge  = blade.curvature * ds * ds;
    const auto dbulge = 2 * blade.curvature * ds;
    rho_              = blade.pitch_radius - sigma * sa * s_ + sigma * ca * bulge;
    z_                = ca * s_ + sa * bulge;
    const auto drho   = -sigma * sa + sigma * ca * dbulge;
    const auto dz     = ca + sa * dbulge;
    const auto len    = sqrt(drho * drho + dz * dz);
    nr_ = sigma * dz / len, nz_ = -sigma * drho / len;
  };
  if (!(blade.edge_radius > 0 && s > s_round))
    return profile(s, rho, z, n_rho, n_z);
  double rj, zj, nrj, nzj;
  profile(s_round, rj, zj, nrj, nzj);
  const double r   = blade.edge_radius;
  const double aj  = std::atan2(nzj, sigma * nrj); // n_j = (sigma cos a_j, sin a_j)
  const T      phi = aj + (s - s_round) / r;
  n_rho = sigma * cos(phi), n_z = sin(phi);
  rho = rj - r * nrj + r * n_rho;
  z   = zj - r * nzj + r * n_z;
}

// The generation chain, shared by the value and derivative evaluations (T = double or AD).
template <class T>
ChainValues<T>
generation_chain(const Blade &blade, double s_round, const MachineSettings &m,
                 const Eigen::Matrix3d &to_blank, const Vec3 &apex, double rotation,
                 double mean_cone_distance, const T &s, const T &theta, const T &psi)
{
  using std::cos;
  using std::sin;
  using std::sqrt;
  T rho, z, n_rho, n_z;
  blade_meridian(blade, s_round, s, rho, z, n_rho, n_z);

  const T               ct = cos(theta), st = sin(theta);
  const Eigen::Matrix3d cutter = cutter_frame(m);
  const V3<T>           r_c    = Vec3(m.radial_setting * std::cos(m.cradle_angle),
                                      m.radial_setting * std::sin(m.cradle_angle), 0)
                        .cast<T>() +
                    cutter.cast<T>() * V3<T>(rho * ct, rho * st, z);
  const V3<T> n_c = cutter.cast<T>() * V3<T>(n_rho * ct, n_rho * st, n_z);
  const T     cp = cos(psi), sp = sin(psi);
  const V3<T> r_m = rotate_z<T>(r_c, cp, sp);
  const V3<T> n_m = rotate_z<T>(n_c, cp, sp);
  const V3<T> v_m(-r_m.y(), r_m.x(), T(0)); // blade velocity per unit cradle rotation

  const V3<T> r_b = to_blank.cast<T>() * (r_m - apex.cast<T>());
  const V3<T> n_b = to_blank.cast<T>() * n_m;
  const V3<T> v_b = to_blank.cast<T>() * v_m;

  ChainValues<T> out;
  T              psi_1 = T(0);
  if (m.generated)
    {
      const double C = m.modified_roll_2c / 2, D = m.modified_roll_6d / 6;
      const T      dp    = psi - m.modified_roll_centre;
      psi_1              = m.ratio_of_roll * (psi - C * dp * dp - D * dp * dp * dp);
      const T     dpsi_1 = m.ratio_of_roll * (1 - 2 * C * dp - 3 * D * dp * dp);
      const V3<T> v_1(-dpsi_1 * r_b.y(), dpsi_1 * r_b.x(), T(0)); // blank material velocity
      out.meshing = n_b.dot(v_b - v_1);
    }
  else
    out.meshing = psi * mean_cone_distance;
  out.axial     = r_b.z();
  out.radius    = sqrt(r_b.x() * r_b.x() + r_b.y() * r_b.y());
  const T angle = rotation - psi_1;
  const T ca1 = cos(angle), sa1 = sin(angle);
  out.position = rotate_z<T>(r_b, ca1, sa1);
  out.normal   = -rotate_z<T>(n_b, ca1, sa1);
  return out;
}

namespace
{
AD
variable(double value, int index)
{
  return AD(value, 3, index);
}
} // namespace

GeneratedFlank::GeneratedFlank(const BevelBlank &b, const Blade &bl, const MachineSettings &m,
                               double rot)
    : blank(b)
    , blade(bl)
    , machine(m)
    , rotation(rot)
{
  if (!(blank.teeth >= 1 && blank.pitch_angle > 0 && blank.pitch_angle < pi &&
        blank.mean_cone_distance > 0 && blank.face_width > 0 &&
        blank.face_width < 2 * blank.mean_cone_distance && blank.addendum >= 0 &&
        blank.dedendum > 0))
    throw InputError("generated bevel flank: the blank needs teeth >= 1, a pitch angle in (0, "
                     "180) deg, positive cone distance, face width below twice it, addendum >= 0 "
                     "and dedendum > 0");
  if (!(blade.pitch_radius > 0 && std::abs(blade.slope) == 1 && blade.angle > -pi / 2 &&
        blade.angle < pi / 2))
    throw InputError("generated bevel flank: a blade needs a positive radius, slope +1 or -1 and "
                     "an angle in (-90, 90) deg");
  const double g          = machine.root_angle;
  machine_to_blank.row(0) = Vec3(std::sin(g), 0, -std::cos(g));
  machine_to_blank.row(1) = Vec3(0, 1, 0);
  machine_to_blank.row(2) = Vec3(std::cos(g), 0, std::sin(g));
  apex = machine.blank_offset * Vec3::UnitY() - machine.sliding_base * Vec3::UnitZ() -
         machine.machine_centre_to_back * machine_to_blank.row(2).transpose();

  // The blade tips lie at the work's dedendum above the pitch plane; with an edge radius r_e
  // the straight part ends at (h_f - r_e (1 - sin alpha)) / cos alpha along the blade.
  if (!(blade.edge_radius >= 0 && blade.edge_radius < blank.dedendum))
    throw InputError("generated bevel flank: the blade edge radius must lie in [0, dedendum)");
  s_round =
      (blank.dedendum - blade.edge_radius * (1 - std::sin(blade.angle))) / std::cos(blade.angle);

  // First guess at the mean point of the pitch cone (blank frame: polar angle 0, radius
  // A_m sin gamma, axial A_m cos gamma), in the machine at cradle angle 0: the blade point
  // nearest to it.
  const double Am = blank.mean_cone_distance;
  const Vec3   P  = apex + machine_to_blank.transpose() * Vec3(Am * std::sin(blank.pitch_angle), 0,
                                                               Am * std::cos(blank.pitch_angle));
  const Vec3   Pc = cutter_frame(machine).transpose() *
                  (P - Vec3(machine.radial_setting * std::cos(machine.cradle_angle),
                            machine.radial_setting * std::sin(machine.cradle_angle), 0));
  const double    ca = std::cos(blade.angle), sa = std::sin(blade.angle);
  Eigen::Vector3d q0(ca * Pc.z() - blade.slope * sa * (Pc.head<2>().norm() - blade.pitch_radius),
                     std::atan2(Pc.y(), Pc.x()), 0);
  int             it;
  q0 = solve(0, 0, q0, it);

  // Form limit: toward the root the straight blade generates the flank only down to where its
  // tip (s_tip = h_f / cos alpha) or the envelope's edge of regression (undercut) is reached;
  // below lies the fillet. The working flank's domain starts at the highest such h along the
  // face (sampled at 9 face positions, 2 % of the depth kept as margin).
  const double s_tip = s_round;
  const double depth = blank.addendum + blank.dedendum;
  form_height        = -blank.dedendum;
  for (int j = 0; j < 9; ++j)
    {
      const double    v = -blank.face_width / 2 + blank.face_width * j / 8;
      Eigen::Vector3d q = q0;
      if (!follow(0, 0, q0, 0, v, q))
        solve(0, v, q, it); // throws: the pitch line itself is not generated
      double          good = 0, bad = NAN;
      Eigen::Vector3d qg = q;
      for (int k = 1; k <= 32 && std::isnan(bad); ++k)
        {
          const double h = -blank.dedendum * k / 32;
          if (follow(good, v, qg, h, v, q) && q[0] <= s_tip)
            good = h, qg = q;
          else
            bad = h;
        }
      if (std::isnan(bad))
        continue; // generated down to the root
      for (int b = 0; b < 30; ++b)
        {
          const double h = (good + bad) / 2;
          if (follow(good, v, qg, h, v, q) && q[0] <= s_tip)
            good = h, qg = q;
          else
            bad = h;
        }
      if (qg[0] < s_tip - 1e-6 * s_tip)
        undercut = true; // stopped by the edge of regression, not by the blade tip
      form_height = std::max(form_height, good + 0.02 * depth);
    }
  if (form_height >= blank.addendum - 0.1 * depth)
    throw InputError("generated bevel flank: the blade generates only the top of the tooth "
                     "(undercut or a blade too short); expected a working flank down to at least "
                     "10 % of the depth below the tip");

  // First guesses: a grid over the domain, by continuation from the mean point.
  const FlankDomain d = domain();
  guess_nu = 9, guess_nv = 9;
  guesses.resize(guess_nu * guess_nv);
  auto at = [&](int i, int j) -> Guess & { return guesses[i * guess_nv + j]; };
  auto uv = [&](int i, int j) {
    return Vec2(d.u_min + (d.u_max - d.u_min) * i / (guess_nu - 1),
                d.v_min + (d.v_max - d.v_min) * j / (guess_nv - 1));
  };
  const int jm    = guess_nv / 2;
  auto      reach = [&](const Guess &from, const Vec2 &p) {
    Eigen::Vector3d q = from.q;
    if (!follow(from.u, from.v, from.q, p.x(), p.y(), q))
      solve(p.x(), p.y(), q, it); // throws with the place
    return Guess{p.x(), p.y(), q};
  };
  for (int i = 0; i < guess_nu; ++i)
    at(i, jm) = reach({0, 0, q0}, uv(i, jm));
  for (int i = 0; i < guess_nu; ++i)
    for (int dir : {-1, 1})
      for (int j = jm + dir; j >= 0 && j < guess_nv; j += dir)
        at(i, j) = reach(at(i, j - dir), uv(i, j));
}

FlankDomain
GeneratedFlank::domain() const
{
  return {form_height, blank.addendum, -blank.face_width / 2, blank.face_width / 2};
}

Eigen::Vector3d
GeneratedFlank::solve(double u, double v, Eigen::Vector3d q, int &iterations) const
{
  if (!newton(u, v, q, iterations))
    {
      std::ostringstream msg;
      msg << "generated bevel flank: the equation of meshing has no solution at h = " << u * 1e3
          << " mm, A - A_m = " << v * 1e3
          << " mm; the machine settings do not generate this part of the blank";
      throw InputError(msg.str());
    }
  return q;
}

bool
GeneratedFlank::follow(double u0, double v0, const Eigen::Vector3d &q0, double u, double v,
                       Eigen::Vector3d &q, int depth) const
{
  // Newton from the solution at (u0, v0); where that fails, halve the path.
  int it;
  q = q0;
  if (newton(u, v, q, it))
    return true;
  if (depth >= 10)
    return false;
  const double    um = (u0 + u) / 2, vm = (v0 + v) / 2;
  Eigen::Vector3d qm;
  return follow(u0, v0, q0, um, vm, qm, depth + 1) && follow(um, vm, qm, u, v, q, depth + 1);
}

bool
GeneratedFlank::newton(double u, double v, Eigen::Vector3d &q, int &iterations) const
{
  const Vec2 target = blank.axial_plane(blank.mean_cone_distance + v, u);
  double     norm   = HUGE_VAL;
  for (iterations = 0; iterations < 40; ++iterations)
    {
      const ChainValues<AD> c = generation_chain<AD>(
          blade, s_round, machine, machine_to_blank, apex, rotation, blank.mean_cone_distance,
          variable(q[0], 0), variable(q[1], 1), variable(q[2], 2));
      const Eigen::Vector3d F(c.meshing.value(), c.axial.value() - target.x(),
                              c.radius.value() - target.y());
      Eigen::Matrix3d       J;
      J.row(0) = c.meshing.derivatives().transpose();
      J.row(1) = c.axial.derivatives().transpose();
      J.row(2) = c.radius.derivatives().transpose();
      norm     = F.norm();
      if (norm < 1e-15 * blank.mean_cone_distance)
        return true;
      const Eigen::Vector3d step = J.partialPivLu().solve(F);
      // damped for the first, far steps: at most 0.3 rad in angles
      const double scale = std::min(1.0, 0.3 / std::max(std::abs(step[1]), std::abs(step[2])));
      q -= scale * step;
      if (step.norm() < 1e-15 && scale == 1)
        return true;
      if (iterations > 6 && norm > 1e-3 * blank.mean_cone_distance)
        return false; // far off after the first steps: give up, the caller shortens the path
    }
  return norm < 1e-11 * blank.mean_cone_distance;
}

GeneratedFlank::Generation
GeneratedFlank::generation(double u, double v) const
{
  // nearest solved guess
  std::size_t       best = 0;
  double            d2   = HUGE_VAL;
  const FlankDomain d    = domain();
  for (std::size_t k = 0; k < guesses.size(); ++k)
    {
      const double du = (guesses[k].u - u) / (d.u_max - d.u_min),
                   dv = (guesses[k].v - v) / (d.v_max - d.v_min);
      if (du * du + dv * dv < d2)
        d2 = du * du + dv * dv, best = k;
    }
  Generation            g;
  const Eigen::Vector3d q = solve(u, v, guesses[best].q, g.iterations);
  g.s = q[0], g.theta = q[1], g.psi_c = q[2];
  g.meshing_residual =
      generation_chain<double>(blade, s_round, machine, machine_to_blank, apex, rotation,
                               blank.mean_cone_distance, q[0], q[1], q[2])
          .meshing;
  return g;
}

FlankPoint
GeneratedFlank::evaluate(double u, double v) const
{
  const Generation      g = generation(u, v);
  const ChainValues<AD> c = generation_chain<AD>(
      blade, s_round, machine, machine_to_blank, apex, rotation, blank.mean_cone_distance,
      variable(g.s, 0), variable(g.theta, 1), variable(g.psi_c, 2));
  Eigen::Matrix3d J, dr;
  J.row(0) = c.meshing.derivatives().transpose();
  J.row(1) = c.axial.derivatives().transpose();
  J.row(2) = c.radius.derivatives().transpose();
  for (int k = 0; k < 3; ++k)
    dr.row(k) = c.position[k].derivatives().transpose();
  // Implicit function theorem: J dq = (0, dx, dR); (x, R) = A (cos g, sin g) + h (-sin g, cos g).
  const auto            lu = J.partialPivLu();
  const double          sg = std::sin(blank.pitch_angle), cg = std::cos(blank.pitch_angle);
  const Eigen::Vector3d dq_du = lu.solve(Eigen::Vector3d(0, -sg, cg));
  const Eigen::Vector3d dq_dv = lu.solve(Eigen::Vector3d(0, cg, sg));
  FlankPoint            p;
  for (int k = 0; k < 3; ++k)
    {
      p.position[k] = c.position[k].value();
      p.normal[k]   = c.normal[k].value();
    }
  p.d_du = dr * dq_du;
  p.d_dv = dr * dq_dv;
  return p;
}

FlankPoint
GeneratedFlank::blade_point(double s, double theta, double psi_c, double *meshing) const
{
  const ChainValues<double> c =
      generation_chain<double>(blade, s_round, machine, machine_to_blank, apex, rotation,
                               blank.mean_cone_distance, s, theta, psi_c);
  if (meshing)
    *meshing = c.meshing;
  FlankPoint p;
  p.position = c.position;
  p.normal   = c.normal;
  p.d_du = p.d_dv = Vec3::Zero();
  return p;
}

GeneratedFlank::FilletPoint
GeneratedFlank::fillet_point(double t, double v) const
{
  if (!(blade.edge_radius > 0))
    throw InputError("generated bevel flank: a root fillet needs a blade edge radius > 0");
  if (!(t >= 0 && t <= 1 && v >= -blank.face_width / 2 && v <= blank.face_width / 2))
    throw InputError("generated bevel flank: fillet point outside t in [0, 1], |A - A_m| <= F/2");
  // Start at the working flank's lower edge and march along the blade: (theta, psi_c) solve the
  // equation of meshing and the cone distance A = A_m + v at the blade parameter s(t).
  const Generation g0 = generation(domain().u_min, v);
  double rj, zj, nrj, nzj; // the rounding turns the normal from the blade's at s_round to the axis
  blade_meridian<double>(blade, s_round, s_round, rj, zj, nrj, nzj);
  const double s_end = s_round + blade.edge_radius * (pi / 2 - std::atan2(nzj, blade.slope * nrj));
  const double cg = std::cos(blank.pitch_angle), sg = std::sin(blank.pitch_angle);
  const double A = blank.mean_cone_distance + v;
  Eigen::Vector2d q(g0.theta, g0.psi_c);
  const int       steps = std::max(1, int(std::ceil(t * 16)));
  FilletPoint     out;
  for (int k = 1; k <= steps; ++k)
    {
      out.s          = g0.s + (s_end - g0.s) * t * k / steps;
      bool converged = false;
      for (int it = 0; it < 30 && !converged; ++it)
        {
          const ChainValues<AD> c = generation_chain<AD>(
              blade, s_round, machine, machine_to_blank, apex, rotation, blank.mean_cone_distance,
              AD(out.s, Eigen::Vector3d::Zero()), variable(q[0], 1), variable(q[1], 2));
          const AD        a = c.axial * cg + c.radius * sg;
          Eigen::Vector2d F(c.meshing.value(), a.value() - A);
          Eigen::Matrix2d J;
          J << c.meshing.derivatives()[1], c.meshing.derivatives()[2], a.derivatives()[1],
              a.derivatives()[2];
          const Eigen::Vector2d step = J.partialPivLu().solve(F);
          q -= step;
          converged = step.norm() < 1e-14 && F.norm() < 1e-12 * A;
        }
      if (!converged)
        {
          std::ostringstream msg;
          msg << "generated bevel flank: the root fillet is not generated at t = " << t
              << ", A - A_m = " << v * 1e3 << " mm (blade parameter " << out.s * 1e3 << " mm)";
          throw InputError(msg.str());
        }
    }
  const ChainValues<double> c =
      generation_chain<double>(blade, s_round, machine, machine_to_blank, apex, rotation,
                               blank.mean_cone_distance, out.s, q[0], q[1]);
  out.position         = c.position;
  out.normal           = c.normal;
  out.meshing_residual = c.meshing;
  out.height           = -c.axial * sg + c.radius * cg;
  return out;
}

GeneratedFlank
GeneratedFlank::rotated(double angle) const
{
  GeneratedFlank copy = *this;
  copy.rotation += angle;
  return copy;
}
} // namespace gearkit

#include "dynamics/train.h"

#include "base/decimator.h"
#include "base/progress.h"
#include "base/types.h"
#include "dynamics/cvode_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

namespace gearkit
{
namespace
{
/// IMPACT's damping coefficient STEP(d, 0, 0, d_max, c_max) at penetration d > 0, and its
/// derivative by d.
std::pair<double, double>
impact_damping(const ImpactLaw &law, double d)
{
  if (!(d < law.depth))
    return {law.damping, 0.0};
  const double x = d / law.depth;
  return {law.damping * x * x * (3 - 2 * x), law.damping * 6 * x * (1 - x) / law.depth};
}

/// IMPACT's force from its elastic part K d^e (given: the caller has it).
double
damped_impact_force(const ImpactLaw &law, double d, double d_rate, double elastic)
{
  if (!(d > 0))
    return 0;
  return std::max(0.0, elastic + impact_damping(law, d).first * d_rate);
}
} // namespace

double
impact_force(const ImpactLaw &law, double d, double d_rate)
{
  return damped_impact_force(law, d, d_rate, law.stiffness * std::pow(d, law.exponent));
}

double
impact_energy(const ImpactLaw &law, double d)
{
  return d > 0 ? law.stiffness * std::pow(d, law.exponent + 1) / (law.exponent + 1) : 0.0;
}

double
impact_stiffness_si(double stiffness, double exponent, double length_unit)
{
  return stiffness / std::pow(length_unit, exponent);
}

namespace
{
/// Cubic Hermite interpolation of a curve's samples (slopes by central differences): where x
/// falls and the value basis there, shared by the curve's offsets and arms (the derivatives'
/// bases only where asked: hermite).
struct Hermite
{
  int    n = 0, i = 0;
  double u        = 0;  ///< position within the interval [i, i + 1]
  double value[4] = {}; ///< weights of y_i, m_i, y_i+1, m_i+1
};

/// false outside the samples
bool
hermite_at(const ToothPairCurve &c, double x, Hermite &h)
{
  h.n = int(c.offset.size());
  if (h.n < 2)
    return false;
  const double s = (x - c.start) / c.step;
  if (!(s >= 0) || s > h.n - 1)
    return false;
  h.i            = std::min(int(s), h.n - 2);
  const double u = h.u = s - h.i, u2 = u * u, u3 = u2 * u;
  h.value[0] = 2 * u3 - 3 * u2 + 1;
  h.value[1] = u3 - 2 * u2 + u;
  h.value[2] = -2 * u3 + 3 * u2;
  h.value[3] = u3 - u2;
  return true;
}

/// The Hermite weights of samples y at h: y_i, its slope m_i, y_i+1, m_i+1 (central
/// differences, one-sided at the ends).
std::array<double, 4>
hermite_weights(const Hermite &h, const std::vector<double> &y)
{
  const int n = h.n;
  auto      m = [&](int j) {
    if (j == 0)
      return y[1] - y[0];
    if (j == n - 1)
      return y[n - 1] - y[n - 2];
    return (y[j + 1] - y[j - 1]) / 2;
  };
  return {y[h.i], m(h.i), y[h.i + 1], m(h.i + 1)};
}

/// The interpolated value at h of the samples whose weights are w (hermite_weights).
double
hermite_value(const Hermite &h, const std::array<double, 4> &w)
{
  return h.value[0] * w[0] + h.value[1] * w[1] + h.value[2] * w[2] + h.value[3] * w[3];
}

/// The interpolant's derivative by x at h and, if asked, its second derivative, from the
/// samples' weights w (hermite_weights).
void
hermite_derivatives(const Hermite &h, const std::array<double, 4> &w, double step, double &slope,
                    double *curvature = nullptr)
{
  const double u = h.u, u2 = u * u;
  const double slope_basis[4]     = {6 * u2 - 6 * u, 3 * u2 - 4 * u + 1, -6 * u2 + 6 * u,
                                     3 * u2 - 2 * u};
  const double curvature_basis[4] = {12 * u - 6, 6 * u - 4, -12 * u + 6, 6 * u - 2};
  slope = (slope_basis[0] * w[0] + slope_basis[1] * w[1] + slope_basis[2] * w[2] +
           slope_basis[3] * w[3]) /
          step;
  if (curvature)
    *curvature = (curvature_basis[0] * w[0] + curvature_basis[1] * w[1] +
                  curvature_basis[2] * w[2] + curvature_basis[3] * w[3]) /
                 (step * step);
}

/// The curve's offset at x with its slope; false outside the samples.
bool
interpolate_offset(const ToothPairCurve &c, double x, double &value, double &slope)
{
  Hermite h;
  if (!hermite_at(c, x, h))
    return false;
  const std::array<double, 4> w = hermite_weights(h, c.offset);
  value                         = hermite_value(h, w);
  hermite_derivatives(h, w, c.step, slope);
  return true;
}

} // namespace

std::pair<double, double>
band_edges(const ToothPairTables &t)
{
  // the most common class of a member; -1 when none is more common than every other
  auto nominal = [](const std::vector<int> &classes, int count) {
    std::vector<int> n(std::size_t(std::max(count, 0)), 0);
    for (int c : classes)
      if (c >= 0 && c < count)
        ++n[std::size_t(c)];
    int best = -1, most = 0, ties = 0;
    for (int c = 0; c < count; ++c)
      if (n[std::size_t(c)] > most)
        best = c, most = n[std::size_t(c)], ties = 0;
      else if (n[std::size_t(c)] == most)
        ++ties;
    return ties > 0 ? -1 : best;
  };
  const int             p = nominal(t.pinion_class, t.pinion_classes);
  const int             g = nominal(t.gear_class, t.gear_classes);
  const ToothPairCurve *d = &t.curve(drive_side, 0, mod(-1, t.gear_teeth));
  const ToothPairCurve *c = &t.curve(coast_side, 0, 0);
  if (p >= 0 && g >= 0 &&
      !t.curves[drive_side][std::size_t(p * t.gear_classes + g)].offset.empty() &&
      !t.curves[coast_side][std::size_t(p * t.gear_classes + g)].offset.empty())
    {
      d = &t.curves[drive_side][std::size_t(p * t.gear_classes + g)];
      c = &t.curves[coast_side][std::size_t(p * t.gear_classes + g)];
    }
  double v[2] = {0, 0}, slope = 0;
  if (!interpolate_offset(*d, 0.0, v[0], slope) || !interpolate_offset(*c, 0.0, v[1], slope))
    require_value(false, "Train mesh", "tooth pair curves at the pitch point", 0,
                  "curves that cover the pairing's centre (local angle 0)");
  return {v[0], v[1]};
}

double
band_centre(const ToothPairTables &t)
{
  const auto [drive, coast] = band_edges(t);
  return (drive + coast) / 2;
}

namespace
{

/// One mesh at one state: forces on its bodies, energies, root functions, outputs.
struct MeshEval
{
  double torque_driver = 0, torque_driven = 0; ///< generalised forces on the two angles
  double force[2] = {0, 0};                    ///< normal force per side [N]
  double energy = 0, dissipation_rate = 0;
  double max_penetration[2] = {-HUGE_VAL, -HUGE_VAL};
  /// The second and third deepest penetrations per side [m] (pairs entering and leaving while
  /// another touches)
  double next_penetration[2][2] = {{-HUGE_VAL, -HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL}};
  /// The k-th deepest penetration of a side (k = 0, 1, 2)
  double
  penetration(int side, int k) const
  {
    return k == 0 ? max_penetration[side] : next_penetration[side][k - 1];
  }
  /// dF/dt per side, linear in the two bodies' accelerations: its part without them and their
  /// coefficients (force_rate)
  double rate_fixed[2] = {0, 0}, rate_driver[2] = {0, 0}, rate_driven[2] = {0, 0};
  /// dF/dt of a side [N/s] at the driver's and driven body's accelerations: zero where the
  /// side's force peaks
  double
  force_rate(int side, double alpha_driver, double alpha_driven) const
  {
    return rate_fixed[side] + rate_driver[side] * alpha_driver + rate_driven[side] * alpha_driven;
  }
  /// The penetration rates of the touching pairs, weighted by their elastic force over d: zero
  /// where the deepest penetration peaks (a finite number at first touch)
  double penetration_rate = 0, penetration_weight = 0;
  int    pairs            = 0;
  double parametric_power = 0; ///< of a finite-element K_m's variation [W]
};

/// A finite-element mesh stiffness at pinion angle phi and its derivative by phi (periodic over
/// the mesh cycle, linear between the samples).
std::pair<double, double>
mesh_stiffness_at(const TrainMesh &m, double phi)
{
  const std::vector<double> &K    = m.mesh_stiffness;
  const int                  n    = int(K.size());
  const double               step = 2 * pi / m.teeth.pinion_teeth / n;
  const double               s    = (phi - m.mesh_stiffness_start) / step;
  const double               f    = std::floor(s);
  const int                  i    = mod(int(std::fmod(f, double(n))), n);
  const double               u    = s - f;
  const double               a = K[std::size_t(i)], b = K[std::size_t((i + 1) % n)];
  return {a + u * (b - a), (b - a) / step};
}

class TrainSystem
{
public:
  TrainSystem(const TrainModel &m, const TrainRunOptions &o)
      : model(m)
      , options(o)
  {
    n = int(model.bodies.size());
    for (const TrainMesh &mesh : model.meshes)
      centre.push_back(band_centre(mesh.teeth));
  }

  /// One mesh at (theta, omega).
  MeshEval
  mesh(int index, const double *theta, const double *omega) const
  {
    const TrainMesh       &m   = model.meshes[index];
    const ToothPairTables &t   = m.teeth;
    const double           phi = theta[m.driver] + m.pinion_angle_0;
    const double           psi = theta[m.driven] + m.gear_angle_0;
    const double           w_p = omega[m.driver], w_g = omega[m.driven];
    const double           ratio = double(t.pinion_teeth) / t.gear_teeth;
    MeshEval               e;
    const int              k0 = int(std::lround(phi * t.pinion_teeth / (2 * pi)));
    const bool             fe = !m.mesh_stiffness.empty();
    /// the deepest touching pair of each side (finite-element K_m)
    struct Deepest
    {
      double d = 0, dd_dphi = 0, dd_dpsi = 0, rate = 0, curvature = 0;
    } deepest[2];
    for (int k = k0 - options.pairings_each_side; k <= k0 + options.pairings_each_side; ++k)
      {
        const double phi_k = phi - 2 * pi * k / t.pinion_teeth;
        const int    i     = mod(-k, t.pinion_teeth);
        for (int side = 0; side < 2; ++side)
          {
            const int             j = mod(side == drive_side ? k - 1 : k, t.gear_teeth);
            const ToothPairCurve &c = t.curve(side, i, j);
            Hermite               h;
            if (!hermite_at(c, phi_k, h))
              continue;
            // d = s arm(phi_k) (psi_touch(phi_k) - psi); the derivatives only where it touches
            double                      o_slope, arm_slope, o_curvature, arm_curvature;
            const std::array<double, 4> w_o   = hermite_weights(h, c.offset);
            const std::array<double, 4> w_arm = hermite_weights(h, c.arm);
            const double                o     = hermite_value(h, w_o);
            const double                arm   = hermite_value(h, w_arm);
            const double                gap   = 2 * pi * k / t.gear_teeth + ratio * phi_k + o - psi;
            const double                s     = side == drive_side ? 1.0 : -1.0;
            const double                d     = s * arm * gap;
            double &p1 = e.max_penetration[side], &p2 = e.next_penetration[side][0],
                   &p3 = e.next_penetration[side][1];
            if (d > p1)
              p3 = p2, p2 = p1, p1 = d;
            else if (d > p2)
              p3 = p2, p2 = d;
            else
              p3 = std::max(p3, d);
            if (!(d > 0))
              continue;
            hermite_derivatives(h, w_o, c.step, o_slope, &o_curvature);
            hermite_derivatives(h, w_arm, c.step, arm_slope, &arm_curvature);
            const double dd_dphi = s * (arm_slope * gap + arm * (ratio + o_slope));
            const double dd_dpsi = -s * arm;
            const double d_rate  = dd_dphi * w_p + dd_dpsi * w_g;
            // d'' = d_phi phi'' + d_psi psi'' + curvature, curvature = d_phiphi phi'^2 +
            // 2 d_phipsi phi' psi'
            const double curvature =
                s * (arm_curvature * gap + 2 * arm_slope * (ratio + o_slope) + arm * o_curvature) *
                    w_p * w_p -
                2 * s * arm_slope * w_p * w_g;
            ++e.pairs;
            if (fe)
              {
                if (d > deepest[side].d)
                  deepest[side] = {d, dd_dphi, dd_dpsi, d_rate, curvature};
                continue;
              }
            const double elastic = m.law.stiffness * std::pow(d, m.law.exponent);
            const double F       = damped_impact_force(m.law, d, d_rate, elastic);
            e.torque_driver -= F * dd_dphi;
            e.torque_driven -= F * dd_dpsi;
            e.force[side] += F;
            e.energy += elastic * d / (m.law.exponent + 1); // impact_energy
            e.dissipation_rate += (F - elastic) * d_rate;
            e.penetration_rate += elastic / d * d_rate;
            e.penetration_weight += elastic / d;
            if (F > 0)
              {
                const auto [c, dc_dd] = impact_damping(m.law, d);
                e.rate_fixed[side] +=
                    m.law.exponent * elastic / d * d_rate + dc_dd * d_rate * d_rate + c * curvature;
                e.rate_driver[side] += c * dd_dphi;
                e.rate_driven[side] += c * dd_dpsi;
              }
          }
      }
    if (fe)
      {
        const auto [K, dK_dphi] = mesh_stiffness_at(m, phi);
        const ImpactLaw linear{K, 1.0, m.law.damping, m.law.depth};
        for (int side = 0; side < 2; ++side)
          {
            const Deepest &p = deepest[side];
            if (!(p.d > 0))
              continue;
            const double F = impact_force(linear, p.d, p.rate);
            e.torque_driver -= F * p.dd_dphi;
            e.torque_driven -= F * p.dd_dpsi;
            e.force[side] += F;
            e.energy += K * p.d * p.d / 2;
            e.dissipation_rate += (F - K * p.d) * p.rate;
            e.parametric_power += dK_dphi * w_p * p.d * p.d / 2;
            e.penetration_rate += K * p.rate;
            e.penetration_weight += K;
            if (F > 0)
              {
                const auto [c, dc_dd] = impact_damping(linear, p.d);
                e.rate_fixed[side] +=
                    dK_dphi * w_p * p.d + K * p.rate + dc_dd * p.rate * p.rate + c * p.curvature;
                e.rate_driver[side] += c * p.dd_dphi;
                e.rate_driven[side] += c * p.dd_dpsi;
              }
          }
      }
    return e;
  }

  /// S of a mesh [m].
  double
  relative(int index, const double *theta) const
  {
    const TrainMesh &m     = model.meshes[index];
    const double     ratio = double(m.teeth.pinion_teeth) / m.teeth.gear_teeth;
    const double phi = theta[m.driver] + m.pinion_angle_0, psi = theta[m.driven] + m.gear_angle_0;
    return m.gear_base_radius * (ratio * phi + centre[index] - psi);
  }

  /// Accelerations, the power of the torques (and of a finite-element K_m's variation) and the
  /// dissipation rate at (t, theta, omega); the meshes as evaluated, if asked.
  void
  evaluate(double t, const double *theta, const double *omega, double *alpha, double &power,
           double &dissipation, std::vector<MeshEval> *evaluated = nullptr) const
  {
    std::vector<double> Q(n, 0.0);
    dissipation       = 0;
    double parametric = 0;
    if (evaluated)
      evaluated->resize(model.meshes.size());
    for (int i = 0; i < int(model.meshes.size()); ++i)
      {
        const MeshEval e = mesh(i, theta, omega);
        if (evaluated)
          (*evaluated)[std::size_t(i)] = e;
        Q[model.meshes[i].driver] += e.torque_driver;
        Q[model.meshes[i].driven] += e.torque_driven;
        dissipation += e.dissipation_rate;
        parametric += e.parametric_power;
      }
    for (const TrainShaft &s : model.shafts)
      {
        const double dw = omega[s.b] - omega[s.a];
        const double T  = s.stiffness * (theta[s.b] - theta[s.a]) + s.damping * dw;
        Q[s.a] += T;
        Q[s.b] -= T;
        dissipation += s.damping * dw * dw;
      }
    power = parametric;
    for (int i = 0; i < n; ++i)
      {
        const TrainBody &b = model.bodies[i];
        double           J = b.inertia, dJ = 0, external = 0;
        if (b.has_crank)
          {
            const auto [Jc, dJc] = b.crank.inertia(theta[i] + b.crank.crank_angle_0);
            J += Jc, dJ = dJc;
            external -=
                b.crank.piston_force * b.crank.piston(theta[i] + b.crank.crank_angle_0).second;
          }
        if (b.constant_speed)
          {
            alpha[i] = 0; // held by the torque that balances the rest
            power += (dJ * omega[i] * omega[i] / 2 - Q[i]) * omega[i];
            continue;
          }
        external += b.torque(t, omega[i]);
        power += external * omega[i];
        alpha[i] = (external + Q[i] - dJ * omega[i] * omega[i] / 2) / J;
      }
  }

  double
  kinetic(const double *theta, const double *omega) const
  {
    double E = 0;
    for (int i = 0; i < n; ++i)
      {
        const TrainBody &b = model.bodies[i];
        double           J = b.inertia;
        if (b.has_crank)
          J += b.crank.inertia(theta[i] + b.crank.crank_angle_0).first;
        E += J * omega[i] * omega[i] / 2;
      }
    return E;
  }

  double
  potential(const double *theta, const double *omega) const
  {
    double V = 0;
    for (int i = 0; i < int(model.meshes.size()); ++i)
      V += mesh(i, theta, omega).energy;
    for (const TrainShaft &s : model.shafts)
      V += s.stiffness * std::pow(theta[s.b] - theta[s.a], 2) / 2;
    return V;
  }

  int                 n;
  const TrainModel   &model;
  TrainRunOptions     options;
  std::vector<double> centre; ///< band centre per mesh [rad]
};
} // namespace

namespace
{
/// Root functions per mesh: either side's deepest penetration (touch and separation), and either
/// side's second and third deepest penetrations (a pair entering or leaving while another
/// touches: the force law's kink there, and the damping spike of a pair entering at its tip
/// edge, which the steps would otherwise stride over). The forces' and penetrations' peaks are
/// located inside the steps without stopping the method (cubic_peak).
constexpr int roots_per_mesh  = 6;
constexpr int ranked_contacts = 3; ///< pairs per side followed (contact ratios below 3)

/// The root function's index (within its mesh) of the k-th deepest penetration of a side.
int
rank_root(int side, int k)
{
  return 2 * k + side;
}

/// The touch function of the k-th deepest penetration of a side (at least -1 m: no pairing
/// within reach), shifted by a hysteresis towards the side's present count of touching pairs.
double
touch_value(const MeshEval &e, int side, int k, int touching_pairs, double hysteresis)
{
  return std::max(e.penetration(side, k), -1.0) + (touching_pairs > k ? hysteresis : -hysteresis);
}

/// Pairs touching per side (0 ... ranked_contacts) in a mesh eval.
int
touching_pairs(const MeshEval &e, int side)
{
  int count = 0;
  for (int k = 0; k < ranked_contacts; ++k)
    count += e.penetration(side, k) > 0;
  return count;
}

/// The touch functions' hysteresis [m]: a thousandth of the absolute tolerance, so that a root
/// never stays exactly zero on rounding-quantised penetrations (which CVODE refuses as a root
/// "at and very near" the last).
double
touch_hysteresis(const TrainRunOptions &o)
{
  return 1e-3 * o.absolute_tolerance;
}

/// The train as last evaluated at a step's end: CVODE evaluates the quadratures there, then the
/// root functions (both reuse one evaluation), and the recorder's extremes reuse it too.
struct LastEvaluation
{
  double                t = -1;
  std::vector<double>   state, alpha;
  double                power = 0, dissipation = 0;
  std::vector<MeshEval> meshes;
  /// Whether (time, y) was the last evaluation.
  bool
  at(double time, const std::vector<double> &y) const
  {
    return time == t && y == state;
  }
  /// The train at (time, y), evaluated unless it was the last evaluation.
  void
  evaluate(const TrainSystem &sys, double time, const double *y)
  {
    const int n = sys.n;
    if (time == t && std::equal(y, y + 2 * n, state.begin(), state.end()))
      return;
    alpha.resize(std::size_t(n));
    sys.evaluate(time, y, y + n, alpha.data(), power, dissipation, &meshes);
    t = time;
    state.assign(y, y + 2 * n);
  }
};

/// The train's CVODE problem: y = [theta; omega], quadratures [work; dissipated; the meshes'
/// force integrals]; the root
/// functions above. `touching` holds the count of touching pairs per mesh and side; `last`
/// holds the last evaluation (the quadratures' and root functions', at the step's end).
CvodeProblem
train_problem(const TrainSystem &sys, const TrainRunOptions &o, const std::vector<double> &y0,
              const std::vector<char> &touching, LastEvaluation &last)
{
  const int    n      = sys.n;
  const int    meshes = int(sys.model.meshes.size());
  CvodeProblem p;
  p.what = "gear train";
  p.hint = "try a smaller tolerance, a smaller contact stiffness, or check the inertias";
  p.size = 2 * n;
  p.bdf  = o.method == TrainIntegrator::bdf;
  p.rhs  = [&sys, n](double t, const double *y, double *ydot) {
    double power, dissipation;
    std::copy(y + n, y + 2 * n, ydot);
    sys.evaluate(t, y, y + n, ydot + n, power, dissipation);
    return 0;
  };
  // the work and the dissipated energy, then every mesh's force integrals (drive - coast,
  // drive + coast: the anti-alias recorder's forces from their derivatives, outside the error
  // test)
  p.quadratures = 2 + 2 * meshes;
  // the energies to the energy tolerance's share of the initial kinetic energy (at least a
  // microjoule), in every step: a relative test would let the local error grow with the work
  // done, which accumulates over a long run (a constant-speed drive against resistive torques)
  const double energy_tolerance =
      o.energy_tolerance > 0 ? o.energy_tolerance : o.relative_tolerance;
  p.quadrature_tolerance.assign(std::size_t(p.quadratures),
                                std::numeric_limits<double>::infinity());
  std::fill_n(p.quadrature_tolerance.begin(), 2,
              energy_tolerance * std::max(1e-6, sys.kinetic(y0.data(), y0.data() + n)));
  p.quadrature_relative_tolerance = energy_tolerance;
  p.quadrature_rhs                = [&sys, &last, meshes](double t, const double *y, double *q) {
    last.evaluate(sys, t, y);
    q[0] = last.power, q[1] = last.dissipation;
    for (int i = 0; i < meshes; ++i)
      {
        const MeshEval &e = last.meshes[std::size_t(i)];
        q[2 + i]          = e.force[drive_side] - e.force[coast_side];
        q[2 + meshes + i] = e.force[drive_side] + e.force[coast_side];
      }
    return 0;
  };
  const double hysteresis = touch_hysteresis(o);
  p.roots                 = roots_per_mesh * meshes;
  p.root_functions        = [&sys, &touching, &last, meshes, hysteresis](double t, const double *y,
                                                                  double *g) {
    last.evaluate(sys, t, y);
    for (int i = 0; i < meshes; ++i)
      {
        const MeshEval &e  = last.meshes[std::size_t(i)];
        double *const   gi = g + roots_per_mesh * i;
        for (int side = 0; side < 2; ++side)
          for (int k = 0; k < ranked_contacts; ++k)
            gi[rank_root(side, k)] =
                touch_value(e, side, k, touching[std::size_t(2 * i + side)], hysteresis);
      }
  };
  // tolerances along the contact normals: angles over the body's largest base radius, speeds
  // over a contact time scale of 0.1 ms
  std::vector<double> radius(std::size_t(n), 0.0);
  for (const TrainMesh &m : sys.model.meshes)
    {
      radius[m.driver] = std::max(radius[m.driver], m.pinion_base_radius);
      radius[m.driven] = std::max(radius[m.driven], m.gear_base_radius);
    }
  const double r_max   = *std::max_element(radius.begin(), radius.end());
  p.relative_tolerance = o.relative_tolerance;
  p.absolute_tolerance.resize(std::size_t(2 * n));
  for (int i = 0; i < n; ++i)
    {
      const double r              = radius[i] > 0 ? radius[i] : r_max;
      p.absolute_tolerance[i]     = o.absolute_tolerance / r;
      p.absolute_tolerance[n + i] = o.absolute_tolerance / r / 1e-4;
    }
  return p;
}

/// The first change of contact inside the piece (a, b) of the last step that the root test at
/// the step's ends cannot see: a side separating and touching again within one step (free
/// flight is a polynomial the method integrates exactly, so its steps grow across a brief
/// separation). The touch functions are checked at the piece's midpoint on the interpolant
/// (their signs at a are the sides' states `touching`) and a change is located by bisection;
/// returns its time (just past it: the new sign holds there) with `fired` set as CVODE sets
/// it, or b when there is none - `middle` then holds the meshes at the midpoint.
double
hidden_contact_change(const CvodeSolver &solver, const TrainSystem &sys,
                      const std::vector<char> &touching, double hysteresis, double a, double b,
                      std::vector<int> &fired, std::vector<MeshEval> &middle)
{
  const int           meshes = int(sys.model.meshes.size());
  std::vector<double> y;
  fired.assign(std::size_t(roots_per_mesh * meshes), 0);
  middle.resize(std::size_t(meshes));
  auto changed = [&](double t) {
    solver.interpolate(t, y);
    bool any = false;
    for (int i = 0; i < meshes; ++i)
      {
        const MeshEval &e = middle[std::size_t(i)] = sys.mesh(i, y.data(), y.data() + sys.n);
        for (int side = 0; side < 2; ++side)
          {
            const int  count = touching[std::size_t(2 * i + side)];
            const bool was   = count > 0; // the sign at a
            const bool now   = touch_value(e, side, 0, count, hysteresis) > 0;
            fired[std::size_t(roots_per_mesh * i + side)] = now == was ? 0 : (now ? 1 : -1);
            any                                           = any || now != was;
          }
      }
    return any;
  };
  double lo = a, hi = (a + b) / 2;
  if (!changed(hi))
    {
      fired.assign(fired.size(), 0);
      return b;
    }
  while (hi - lo > 8 * std::numeric_limits<double>::epsilon() * std::abs(hi))
    {
      const double mid = (lo + hi) / 2;
      if (mid <= lo || mid >= hi)
        break;
      (changed(mid) ? hi : lo) = mid;
    }
  changed(hi);
  return hi;
}

/// A side's force that peaks inside the piece (a, b) of the last step without a root of its
/// rate there (a sharp peak the step strides over: two sign changes within it): when the force
/// at the midpoint exceeds both ends', the peak located by golden-section search on the
/// interpolant; its time, or -1 when there is none.
double
interior_peak(const CvodeSolver &solver, const TrainSystem &sys, int mesh, int side, double a,
              double b, double f_a, double f_mid, double f_b)
{
  if (!(f_mid > f_a && f_mid > f_b))
    return -1;
  std::vector<double> y;
  auto                force = [&](double t) {
    solver.interpolate(t, y);
    return sys.mesh(mesh, y.data(), y.data() + sys.n).force[side];
  };
  const double r  = (std::sqrt(5.0) - 1) / 2;
  double       lo = a, hi = b;
  double       x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
  double       f1 = force(x1), f2 = force(x2);
  while (hi - lo > 1e-9 * (b - a) + 4 * std::numeric_limits<double>::epsilon() * std::abs(hi))
    if (f1 < f2)
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = force(x2);
    else
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = force(x1);
  return f1 > f2 ? x1 : x2;
}

/// The time in (a, b) where a quantity with values f_a, f_b and rates r_a > 0 > r_b at the ends
/// of a piece of a step peaks, from the cubic Hermite interpolant of those four numbers (the
/// root of its derivative, a quadratic, where the derivative falls); the method's polynomial is
/// that smooth inside a step, so the solution evaluated there gives the peak to second order in
/// the cubic's error of its time.
double
cubic_peak(double a, double b, double f_a, double f_b, double r_a, double r_b)
{
  const double h = b - a;
  // p(u) = f_a H00 + h r_a H10 + f_b H01 + h r_b H11, p'(u) = A u^2 + B u + C
  const double m0 = h * r_a, m1 = h * r_b, d = f_b - f_a;
  const double A = 3 * (m0 + m1) - 6 * d, B = 6 * d - 4 * m0 - 2 * m1, C = m0;
  double       u = 0.5;
  if (std::abs(A) <= 1e-12 * (std::abs(B) + std::abs(C)))
    u = B != 0 ? -C / B : 0.5;
  else
    {
      const double disc = std::max(0.0, B * B - 4 * A * C);
      const double q    = -(B + std::copysign(std::sqrt(disc), B)) / 2;
      const double u1 = q / A, u2 = q != 0 ? C / q : u1;
      u = 2 * A * u1 + B < 0 ? u1 : u2; // p' falls through zero at the peak
    }
  return a + h * std::clamp(u, 0.0, 1.0);
}

/// The meshes at the state y.
std::vector<MeshEval>
meshes_at(const TrainSystem &sys, const std::vector<double> &y)
{
  std::vector<MeshEval> e;
  for (int i = 0; i < int(sys.model.meshes.size()); ++i)
    e.push_back(sys.mesh(i, y.data(), y.data() + sys.n));
  return e;
}

/// The meshes and the accelerations at a point of the solution.
struct SolutionPoint
{
  std::vector<MeshEval> meshes;
  std::vector<double>   alpha;
};

/// The times inside the piece (a, b) of the last step where a side's force or a mesh's deepest
/// penetration peaks: a side loaded at both ends whose force rate falls through zero (the cubic
/// through the ends' forces and rates: cubic_peak), the deepest penetration likewise with its
/// weighted rate, and a sharp peak the piece strides over (two sign changes: the force at the
/// midpoint above both ends', golden-section search: interior_peak).
std::vector<double>
piece_peaks(const CvodeSolver &solver, const TrainSystem &sys, double a, double b,
            const SolutionPoint &start, const std::vector<MeshEval> &middle,
            const SolutionPoint &end)
{
  std::vector<double> peaks;
  for (int i = 0; i < int(sys.model.meshes.size()); ++i)
    {
      const TrainMesh &m  = sys.model.meshes[std::size_t(i)];
      const MeshEval  &ea = start.meshes[std::size_t(i)], &eb = end.meshes[std::size_t(i)];
      for (int side = 0; side < 2; ++side)
        {
          const double fa = ea.force[side], fb = eb.force[side];
          const double ra =
              fa > 0 ? ea.force_rate(side, start.alpha[m.driver], start.alpha[m.driven]) : 0;
          const double rb =
              fb > 0 ? eb.force_rate(side, end.alpha[m.driver], end.alpha[m.driven]) : 0;
          if (fa > 0 && fb > 0 && ra > 0 && rb < 0)
            peaks.push_back(cubic_peak(a, b, fa, fb, ra, rb));
          else if (const double x = interior_peak(solver, sys, i, side, a, b, fa,
                                                  middle[std::size_t(i)].force[side], fb);
                   x > 0)
            peaks.push_back(x);
        }
      if (ea.pairs > 0 && eb.pairs > 0)
        {
          const double ra = ea.penetration_rate / ea.penetration_weight;
          const double rb = eb.penetration_rate / eb.penetration_weight;
          if (ra > 0 && rb < 0)
            peaks.push_back(cubic_peak(a, b, std::max(ea.max_penetration[0], ea.max_penetration[1]),
                                       std::max(eb.max_penetration[0], eb.max_penetration[1]), ra,
                                       rb));
        }
    }
  return peaks;
}

/// What the run records: the samples (from the integrator's interpolant, at the output times),
/// and the extremes and impacts of the continuous solution - the forces and penetrations at
/// every step's end and at every located root (touch, separation, the forces' peaks), the
/// impulses integrated over every step.
class TrainRecorder
{
public:
  TrainRecorder(const TrainSystem &sys, const std::vector<double> &y0, const TrainRunOptions &o,
                long samples)
      : sys(sys)
      , n(sys.n)
      , meshes(int(sys.model.meshes.size()))
      , kinetic0(sys.kinetic(y0.data(), y0.data() + sys.n))
      , potential0(sys.potential(y0.data(), y0.data() + sys.n))
      , scale(std::max(kinetic0, 1e-300))
      , open(std::size_t(2 * meshes))
      , impulse(std::size_t(2 * meshes), 0.0)
  {
    out.angle.assign(std::size_t(n), {});
    out.speed.assign(std::size_t(n), {});
    out.meshes.assign(std::size_t(meshes), {});
    if (o.anti_alias) // channels: the angles, the speeds, the meshes' forces and magnitudes
      alias.emplace(o.sample_rate, samples, std::size_t(2 * n + 2 * meshes));
  }

  /// The solution over [a, b], a piece of the last step, for the anti-alias recorder: the
  /// states from the method's polynomial, the forces from their integrals' (the quadratures').
  void
  record(const CvodeSolver &solver, double a, double b)
  {
    if (!alias)
      return;
    alias->advance(a, b, [&](double t, double *v) {
      solver.interpolate(t, state);
      std::copy(state.begin(), state.end(), v);
      solver.interpolate_quadrature_rates(t, rates);
      std::copy(rates.begin() + 2, rates.end(), v + 2 * n);
    });
  }

  /// The output sample at time t.
  void
  sample(double t, const std::vector<double> &state, const std::vector<double> &q)
  {
    out.t.push_back(t);
    for (int i = 0; i < n; ++i)
      {
        out.angle[i].push_back(state[i]);
        out.speed[i].push_back(state[n + i]);
      }
    for (int i = 0; i < meshes; ++i)
      {
        const MeshEval e = sys.mesh(i, state.data(), state.data() + n);
        out.meshes[i].relative.push_back(sys.relative(i, state.data()));
        out.meshes[i].force.push_back(e.force[drive_side] - e.force[coast_side]);
        out.meshes[i].magnitude.push_back(e.force[drive_side] + e.force[coast_side]);
        out.meshes[i].pairs.push_back(e.pairs);
      }
    const double K = sys.kinetic(state.data(), state.data() + n);
    const double V = sys.potential(state.data(), state.data() + n);
    out.work.push_back(q[0]);
    out.kinetic.push_back(K);
    out.potential.push_back(V);
    out.dissipated.push_back(q[1]);
    scale = std::max({scale, std::abs(q[0]), K, V, std::abs(q[1])});
    out.energy_error =
        std::max(out.energy_error, std::abs(q[0] - (K - kinetic0) - (V - potential0) - q[1]));
  }

  /// The forces and penetrations at a point of the solution (a step's end, a root): the
  /// meshes evaluated there.
  void
  extremes(double t, const std::vector<MeshEval> &evaluated)
  {
    for (int i = 0; i < meshes; ++i)
      {
        const MeshEval &e  = evaluated[std::size_t(i)];
        MeshSeries     &ms = out.meshes[i];
        for (int side = 0; side < 2; ++side)
          {
            const double F = e.force[side];
            if (F > ms.max_force)
              ms.max_force = F, ms.max_force_time = t;
            ms.max_penetration            = std::max(ms.max_penetration, e.max_penetration[side]);
            std::optional<TrainImpact> &c = open[std::size_t(2 * i + side)];
            if (c && F > c->peak)
              c->peak = F, c->peak_time = t;
          }
      }
  }

  /// The forces' integrals over [a, b], a piece of the last step, from the meshes at a, at the
  /// midpoint and at b (Simpson's rule on the method's interpolant: its kinks - touch,
  /// separation - are roots, and end the pieces).
  void
  integrate(double a, double b, const std::vector<MeshEval> &at_a,
            const std::vector<MeshEval> &middle, const std::vector<MeshEval> &at_b)
  {
    for (int i = 0; i < meshes; ++i)
      for (int side = 0; side < 2; ++side)
        impulse[std::size_t(2 * i + side)] +=
            (b - a) / 6 *
            (at_a[std::size_t(i)].force[side] + 4 * middle[std::size_t(i)].force[side] +
             at_b[std::size_t(i)].force[side]);
  }

  /// A side of mesh i starts (touch) or stops touching at t; a contact at the start (t = 0)
  /// is recorded, but is no impact.
  void
  contact(int i, int side, bool touch, double t)
  {
    MeshSeries                 &ms = out.meshes[i];
    std::optional<TrainImpact> &c  = open[std::size_t(2 * i + side)];
    if (touch)
      {
        if (t > 0)
          {
            ++ms.impacts;
            ++(side == drive_side ? ms.drive_impacts : ms.coast_impacts);
          }
        if (ms.first_contact < 0)
          ms.first_contact = t;
        c.emplace();
        c->side = side, c->touch = t, c->peak_time = t;
        c->impulse = impulse[std::size_t(2 * i + side)]; // the integral so far; then the change
        return;
      }
    if (!c)
      return;
    c->separation = t;
    c->impulse    = impulse[std::size_t(2 * i + side)] - c->impulse;
    ms.contacts.push_back(*c);
    c.reset();
  }

  /// The result, with the contacts still open at the end (separation -1).
  TrainResult
  finish(const CvodeSolver &solver)
  {
    for (int i = 0; i < meshes; ++i)
      for (int side = 0; side < 2; ++side)
        if (std::optional<TrainImpact> &c = open[std::size_t(2 * i + side)])
          {
            c->impulse = impulse[std::size_t(2 * i + side)] - c->impulse;
            out.meshes[i].contacts.push_back(*c);
            c.reset();
          }
    for (MeshSeries &ms : out.meshes)
      std::sort(ms.contacts.begin(), ms.contacts.end(),
                [](const TrainImpact &a, const TrainImpact &b) { return a.touch < b.touch; });
    out.steps        = std::size_t(solver.steps());
    out.energy_error = out.energy_error / scale;
    if (alias) // the recorded series in place of the point samples
      {
        if (!alias->done() || alias->output(0).size() != out.t.size())
          throw std::logic_error("gear train: the anti-alias record does not cover the samples");
        for (int i = 0; i < n; ++i)
          {
            out.angle[i] = std::move(alias->output(std::size_t(i)));
            out.speed[i] = std::move(alias->output(std::size_t(n + i)));
          }
        std::vector<double> theta(static_cast<std::size_t>(n));
        for (int i = 0; i < meshes; ++i)
          {
            MeshSeries &ms = out.meshes[i];
            ms.force       = std::move(alias->output(std::size_t(2 * n + i)));
            ms.magnitude   = std::move(alias->output(std::size_t(2 * n + meshes + i)));
            for (std::size_t k = 0; k < out.t.size(); ++k)
              {
                for (int j = 0; j < n; ++j)
                  theta[j] = out.angle[j][k];
                ms.relative[k] = sys.relative(i, theta.data());
              }
          }
      }
    return std::move(out);
  }

  TrainResult out;

private:
  const TrainSystem                      &sys;
  int                                     n, meshes;
  double                                  kinetic0, potential0, scale;
  std::vector<std::optional<TrainImpact>> open;    ///< per mesh and side
  std::vector<double>                     impulse; ///< force integral since the start [N s]
  std::optional<AntiAliasRecorder>        alias;
  std::vector<double>                     state, rates; ///< record's interpolations
};
/// The run's options, each against what it allows (InputError naming it).
void
check_run_options(const TrainRunOptions &o)
{
  auto require = [](bool ok, const std::string &what, double value, const std::string &allowed) {
    require_value(ok, "Train run", what, value, allowed);
  };
  require(o.duration > 0 && std::isfinite(o.duration), "duration [s]", o.duration, "> 0");
  require(o.sample_rate > 0 && o.duration * o.sample_rate <= 5e7, "sample rate [1/s]",
          o.sample_rate, "> 0, at most 5e7 samples in the run");
  // the samples: at k / rate up to the duration, the last one at the duration itself; without
  // aliasing on whole output intervals only
  require(!o.anti_alias || o.duration * o.sample_rate >= 1 - 1e-9, "duration [s]", o.duration,
          "at least one output interval (1 / sample rate) when recorded without aliasing");
  require(o.relative_tolerance > 0 && o.absolute_tolerance > 0, "tolerance",
          std::min(o.relative_tolerance, o.absolute_tolerance), "> 0");
  require(o.max_steps > 0, "max steps", double(o.max_steps), "> 0");
  require(o.energy_tolerance >= 0 && o.energy_tolerance < 1, "energy tolerance", o.energy_tolerance,
          "in [0, 1)");
  require(o.pairings_each_side >= 1 && o.pairings_each_side <= 50, "pairings each side",
          o.pairings_each_side, "in [1, 50]");
}
} // namespace

TrainResult
simulate_train(const TrainModel &model, const TrainRunOptions &o)
{
  // 1. check
  model.check();
  check_run_options(o);
  const double intervals = o.duration * o.sample_rate;
  const long   samples   = std::max(1L, o.anti_alias ? long(std::floor(intervals + 1e-9))
                                                     : long(std::ceil(intervals - 1e-9)));

  // 2. the system and its CVODE problem
  const TrainSystem   sys(model, o);
  const int           n      = sys.n;
  const int           meshes = int(model.meshes.size());
  std::vector<double> y(2 * std::size_t(n));
  for (int i = 0; i < n; ++i)
    y[i] = model.bodies[i].initial_angle, y[n + i] = model.bodies[i].initial_speed;
  std::vector<char>  touching(2 * std::size_t(meshes), 0);
  LastEvaluation     last_evaluation;
  const CvodeProblem p = train_problem(sys, o, y, touching, last_evaluation);

  // 3. integrate step by step (the steps do not depend on the output rate), the samples
  // interpolated at the output times, the extremes and impacts from the steps and roots
  TrainRecorder rec(sys, y, o, samples);
  for (int i = 0; i < meshes; ++i) // the sides touching at the start
    {
      const MeshEval e = sys.mesh(i, y.data(), y.data() + n);
      for (int side = 0; side < 2; ++side)
        if ((touching[std::size_t(2 * i + side)] = char(touching_pairs(e, side))) > 0)
          rec.contact(i, side, true, 0);
    }
  CvodeSolver solver(p, 0.0, y);
  rec.sample(0, y, {0.0, 0.0});
  rec.extremes(0, meshes_at(sys, y));
  auto sample_time = [&](long k) { return std::min(o.duration, double(k) / o.sample_rate); };
  std::optional<Progress> line;
  if (!o.progress.empty())
    line.emplace(o.progress, std::size_t(samples));
  std::vector<int>      fired, hidden_fired;
  std::vector<MeshEval> middle;
  std::vector<double>   ys, qs, g(std::size_t(p.roots));
  // the meshes and accelerations at a piece's start and end (the end's from the quadratures'
  // and root functions' evaluation there, when it is theirs)
  auto point_at = [&](double time, const std::vector<double> &state, SolutionPoint &point) {
    if (last_evaluation.at(time, state))
      {
        point.meshes = last_evaluation.meshes, point.alpha = last_evaluation.alpha;
        return;
      }
    double power, dissipation;
    point.alpha.resize(std::size_t(n));
    sys.evaluate(time, state.data(), state.data() + n, point.alpha.data(), power, dissipation,
                 &point.meshes);
  };
  SolutionPoint start, end;
  point_at(0, y, start);
  long next = 1;
  // steps of at most 1/16 of the shortest tooth mesh period at the present speeds: a contact
  // that opens and closes within a step is looked for at its midpoint only (changes shorter
  // than 1/32 of a mesh period may pass unseen), and free flight would let the steps grow
  // across whole mesh periods
  auto max_step = [&](const std::vector<double> &state) {
    double fastest = 0; // tooth passes per second
    for (const TrainMesh &m : model.meshes)
      fastest = std::max(fastest, m.teeth.pinion_teeth * std::abs(state[n + m.driver]) / (2 * pi));
    return fastest > 0 ? 1 / (16 * fastest) : 0.0;
  };
  for (double t = 0, last = 0; t < o.duration; last = t)
    {
      solver.set_max_step(max_step(y));
      bool         root    = solver.step(o.duration, t, y, &fired);
      const double hidden  = hidden_contact_change(solver, sys, touching, touch_hysteresis(o), last,
                                                   t, hidden_fired, middle);
      const bool   restart = hidden < t; // the run goes on from there
      if (restart)
        {
          t = hidden, root = true;
          solver.interpolate(t, y);
          fired.swap(hidden_fired);
          solver.interpolate((last + t) / 2, ys);
          middle = meshes_at(sys, ys);
        }
      point_at(t, y, end);
      rec.integrate(last, t, start.meshes, middle, end.meshes);
      rec.record(solver, last, t);
      for (; next <= samples && sample_time(next) <= t; ++next)
        {
          solver.interpolate(sample_time(next), ys, &qs);
          rec.sample(sample_time(next), ys, qs);
          if (line)
            line->advance();
        }
      for (double v : y)
        if (!std::isfinite(v))
          throw InputError("gear train: the state is not finite at t = " + std::to_string(t) +
                           " s; check the inertias and the contact law");
      rec.extremes(t, end.meshes);
      for (const double x : piece_peaks(solver, sys, last, t, start, middle, end))
        {
          solver.interpolate(x, ys);
          rec.extremes(x, meshes_at(sys, ys));
        }
      std::swap(start, end);
      if (root)
        {
          ++rec.out.events;
          bool contact_change = false;
          for (int i = 0; i < meshes; ++i)
            for (int side = 0; side < 2; ++side)
              for (int k = 0; k < ranked_contacts; ++k)
                if (const int f = fired[std::size_t(roots_per_mesh * i + rank_root(side, k))])
                  {
                    char &count = touching[std::size_t(2 * i + side)];
                    count       = f > 0 ? std::max(count, char(k + 1)) : std::min(count, char(k));
                    if (k == 0)
                      rec.contact(i, side, f > 0, t);
                    contact_change = true;
                  }
          // restart the method at every touch and separation, of a side and of a pair (the
          // force law's derivatives jump there: BDF's history across the kink costs accuracy, the
          // energy balance of a damped driven run 1.6e-6 without the restarts against 1e-6 with
          // them), after a change found inside a step, and where a root function is exactly zero at
          // the root (rounding-quantised rates): CVODE would take it for a root "at and very near"
          // the last one, a restart sets it aside
          p.root_functions(t, y.data(), g.data());
          if (contact_change || restart || std::find(g.begin(), g.end(), 0.0) != g.end())
            solver.reinit(t, y);
        }
      if (solver.steps() > o.max_steps)
        {
          std::ostringstream m;
          m << "gear train: more than " << o.max_steps << " integrator steps by t = " << t
            << " s of " << o.duration
            << " s; the contact is too stiff for this duration (reduce the contact stiffness "
               "or the duration, or raise the step budget)";
          throw InputError(m.str());
        }
    }
  return rec.finish(solver);
}
} // namespace gearkit

#include "dynamics/train.h"

#include "base/decimator.h"
#include "base/progress.h"
#include "base/types.h"
#include "dynamics/cvode_solver.h"
#include "dynamics/train_system.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

namespace gearkit
{
using train_internal::MeshEval;
using train_internal::TrainSystem;

namespace
{
/// Root functions per mesh: either side's deepest penetration (touch and separation), and either
/// side's second and third deepest penetrations (a pair entering or leaving while another
/// touches: the force law's kink there, and the damping spike of a pair entering at its tip
/// edge, which the steps would otherwise stride over). The forces' and penetrations' peaks are
/// located inside the steps without stopping the method (cubic_range).
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

/// The kinks' root functions in order (after the contacts'): (mesh, kink index).
std::vector<std::pair<int, int>>
kink_root_list(const TrainSystem &sys)
{
  std::vector<std::pair<int, int>> r;
  for (int i = 0; i < int(sys.model.meshes.size()); ++i)
    for (int k = 0; k < int(sys.kinks(i).size()); ++k)
      r.emplace_back(i, k);
  return r;
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
    sys.evaluate(time, y, y + n, alpha.data(), power, dissipation, &meshes, true);
    t = time;
    state.assign(y, y + 2 * n);
  }
};

/// The train's CVODE problem: y = [theta; omega], quadratures [work; dissipated]; the root
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
  const TrainIntegrator method = resolve_integrator(sys.model, o.method);
  p.bdf                        = method == TrainIntegrator::bdf;
  // Adams for a contact that is not stiff: its natural iteration, no Jacobian
  p.functional_iteration = method == TrainIntegrator::adams;
  p.rhs                  = [&sys, n](double t, const double *y, double *ydot) {
    double power, dissipation;
    std::copy(y + n, y + 2 * n, ydot);
    sys.evaluate(t, y, y + n, ydot + n, power, dissipation);
    return 0;
  };
  // the work and the dissipated energy
  p.quadratures = 2;
  // the energies to the energy tolerance's share of the initial kinetic energy (at least a
  // microjoule), in every step: a relative test would let the local error grow with the work
  // done, which accumulates over a long run (a constant-speed drive against resistive torques)
  const double energy_tolerance =
      o.energy_tolerance > 0 ? o.energy_tolerance : o.relative_tolerance;
  p.quadrature_tolerance.assign(2, energy_tolerance *
                                       std::max(1e-6, sys.kinetic(y0.data(), y0.data() + n)));
  p.quadrature_relative_tolerance = energy_tolerance;
  p.quadrature_rhs                = [&sys, &last](double t, const double *y, double *q) {
    last.evaluate(sys, t, y);
    q[0] = last.power, q[1] = last.dissipation;
    return 0;
  };
  const double hysteresis = touch_hysteresis(o);
  // the contacts' root functions, then one per kink of the tooth pair curves (kink_root_list)
  p.roots          = roots_per_mesh * meshes + int(kink_root_list(sys).size());
  p.root_functions = [&sys, &touching, &last, meshes, hysteresis](double t, const double *y,
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
    double *gk = g + roots_per_mesh * meshes;
    for (int i = 0; i < meshes; ++i)
      {
        sys.kink_roots(i, y, gk);
        gk += sys.kinks(i).size();
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

/// The least and largest values over [a, b] (ends included) of the cubic Hermite interpolant
/// of values f_a, f_b and rates r_a, r_b at a and b, and where the largest is. With r_a > 0 > r_b
/// that is a peak inside, at the root of the cubic's rate (a quadratic) where it falls: the
/// method's polynomial is that smooth inside a step, so the solution evaluated there gives the
/// peak to second order in the cubic's error of its time.
struct CubicRange
{
  double min = 0, max = 0, max_time = 0;
};
CubicRange
cubic_range(double a, double b, double f_a, double f_b, double r_a, double r_b)
{
  const double h = b - a, m0 = h * r_a, m1 = h * r_b, d = f_b - f_a;
  CubicRange   r{std::min(f_a, f_b), std::max(f_a, f_b), f_a > f_b ? a : b};
  auto         consider = [&](double u) {
    if (!(u > 0 && u < 1))
      return;
    const double u2 = u * u, u3 = u2 * u;
    const double p = (2 * u3 - 3 * u2 + 1) * f_a + (u3 - 2 * u2 + u) * m0 +
                     (-2 * u3 + 3 * u2) * f_b + (u3 - u2) * m1;
    r.min = std::min(r.min, p);
    if (p > r.max)
      r.max = p, r.max_time = a + h * u;
  };
  // p'(u) = A u^2 + B u + C
  const double A = 3 * (m0 + m1) - 6 * d, B = 6 * d - 4 * m0 - 2 * m1, C = m0;
  if (std::abs(A) <= 1e-12 * (std::abs(B) + std::abs(C)))
    {
      if (B != 0)
        consider(-C / B);
    }
  else // a negative discriminant from rounding adds a point of the cubic, no harm
    {
      const double q = -(B + std::copysign(std::sqrt(std::max(0.0, B * B - 4 * A * C)), B)) / 2;
      consider(q / A);
      if (q != 0)
        consider(C / q);
    }
  return r;
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

/// The meshes, the accelerations and each side's force rate dF/dt at a point of the solution.
struct SolutionPoint
{
  std::vector<MeshEval>              meshes;
  std::vector<double>                alpha;
  std::vector<std::array<double, 2>> force_rate; ///< per mesh, drive and coast [N/s]
  /// force_rate from the meshes and accelerations
  void
  set_force_rates(const TrainSystem &sys)
  {
    force_rate.resize(meshes.size());
    for (std::size_t i = 0; i < meshes.size(); ++i)
      {
        const TrainMesh &m = sys.model.meshes[i];
        for (int side = 0; side < 2; ++side)
          force_rate[i][std::size_t(side)] = meshes[i].force_rate(
              side, alpha[std::size_t(m.driver)], alpha[std::size_t(m.driven)]);
      }
  }
};

/// The times inside the piece (a, b) of the last step where a side's force or a mesh's deepest
/// penetration peaks: a side loaded at both ends whose force rate falls through zero (the cubic
/// through the ends' forces and rates: cubic_range), the deepest penetration likewise with its
/// weighted rate, and a peak the piece strides over (two sign changes of the rate: the cubic's
/// interior maximum, or the force at the midpoint where it was evaluated, above both ends';
/// golden-section search: interior_peak).
std::vector<double>
piece_peaks(const CvodeSolver &solver, const TrainSystem &sys, double a, double b,
            const SolutionPoint &start, const std::vector<MeshEval> *middle,
            const SolutionPoint &end)
{
  std::vector<double> peaks;
  for (int i = 0; i < int(sys.model.meshes.size()); ++i)
    {
      const MeshEval &ea = start.meshes[std::size_t(i)], &eb = end.meshes[std::size_t(i)];
      for (int side = 0; side < 2; ++side)
        {
          const double     fa = ea.force[side], fb = eb.force[side];
          const double     ra = fa > 0 ? start.force_rate[std::size_t(i)][std::size_t(side)] : 0;
          const double     rb = fb > 0 ? end.force_rate[std::size_t(i)][std::size_t(side)] : 0;
          const CubicRange c  = cubic_range(a, b, fa, fb, ra, rb);
          if (fa > 0 && fb > 0 && ra > 0 && rb < 0)
            {
              peaks.push_back(c.max_time); // the root of the cubic's rate where it falls
              continue;
            }
          // a peak the cubic shows inside, or (where the midpoint was evaluated) the midpoint
          // above both ends
          const double f_mid = middle ? (*middle)[std::size_t(i)].force[side] : 0.0;
          const double guess = c.max > std::max(fa, fb) ? c.max : f_mid;
          if (const double x = interior_peak(solver, sys, i, side, a, b, fa, guess, fb); x > 0)
            peaks.push_back(x);
        }
      if (ea.pairs > 0 && eb.pairs > 0)
        {
          const double ra = ea.penetration_rate / ea.penetration_weight;
          const double rb = eb.penetration_rate / eb.penetration_weight;
          if (ra > 0 && rb < 0)
            peaks.push_back(
                cubic_range(a, b, std::max(ea.max_penetration[0], ea.max_penetration[1]),
                            std::max(eb.max_penetration[0], eb.max_penetration[1]), ra, rb)
                    .max_time);
        }
    }
  return peaks;
}

/// Whether a contact could change inside the piece (a, b) of the last step unseen by the root
/// test at its ends (hidden_contact_change then looks at its midpoint): a side's touch function
/// whose cubic through the ends' values and rates comes within a quarter of its own excursion
/// of zero on the piece (or a side without those rates).
bool
contact_may_change_inside(const SolutionPoint &start, const SolutionPoint &end,
                          const std::vector<char> &touching, double hysteresis, double a, double b)
{
  for (std::size_t i = 0; i < start.meshes.size(); ++i)
    for (int side = 0; side < 2; ++side)
      {
        const MeshEval &ea = start.meshes[i], &eb = end.meshes[i];
        const int       count = touching[2 * i + std::size_t(side)];
        const double    ga    = touch_value(ea, side, 0, count, hysteresis);
        const double    gb    = touch_value(eb, side, 0, count, hysteresis);
        if (ga <= -1 + hysteresis && gb <= -1 + hysteresis)
          continue; // no pairing within reach at either end
        const CubicRange c =
            cubic_range(a, b, ga, gb, ea.deepest_rate[side], eb.deepest_rate[side]);
        const double margin = (c.max - c.min) / 4;
        if (count > 0 ? c.min <= margin : c.max >= -margin)
          return true;
      }
  return false;
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

  /// The solution over [a, b], a piece of the last step, for the anti-alias recorder: every
  /// channel the cubic Hermite interpolant of its values and rates at the piece's ends (the
  /// angles from the speeds, the speeds from the accelerations, the forces from their rates),
  /// third-order accurate like the step and without the interpolations the method's own
  /// polynomial would cost at every quadrature point.
  void
  record(double a, double b, const std::vector<double> &y_a, const SolutionPoint &at_a,
         const std::vector<double> &y_b, const SolutionPoint &at_b);

  /// The output sample at time t.
  void
  sample(double t, const std::vector<double> &state, const std::vector<double> &q);

  /// The forces and penetrations at a point of the solution (a step's end, a root): the
  /// meshes evaluated there.
  void
  extremes(double t, const std::vector<MeshEval> &evaluated);

  /// The forces' integrals over [a, b], a piece of the last step, from the forces and their
  /// rates at a and b (the integral of their cubic Hermite interpolant, exact for cubics as
  /// Simpson's rule is: the force's kinks - touch, separation - are roots, and end the pieces).
  void
  integrate(double a, double b, const SolutionPoint &at_a, const SolutionPoint &at_b);

  /// A side of mesh i starts (touch) or stops touching at t; a contact at the start (t = 0)
  /// is recorded, but is no impact.
  void
  contact(int i, int side, bool touch, double t);

  /// The result, with the contacts still open at the end (separation -1).
  TrainResult
  finish(const CvodeSolver &solver);

  TrainResult out;

private:
  const TrainSystem                      &sys;
  int                                     n, meshes;
  double                                  kinetic0, potential0, scale;
  std::vector<std::optional<TrainImpact>> open;    ///< per mesh and side
  std::vector<double>                     impulse; ///< force integral since the start [N s]
  std::optional<AntiAliasRecorder>        alias;
  std::vector<double>                     ends; ///< record's values and rates at the ends
};

void
TrainRecorder::record(double a, double b, const std::vector<double> &y_a, const SolutionPoint &at_a,
                      const std::vector<double> &y_b, const SolutionPoint &at_b)
{
  if (!alias)
    return;
  const std::size_t channels = std::size_t(2 * n + 2 * meshes);
  ends.resize(4 * channels);
  double *const value_a = ends.data(), *const rate_a = value_a + channels,
                *const value_b = rate_a + channels, *const rate_b = value_b + channels;
  auto fill = [&](const std::vector<double> &y, const SolutionPoint &at, double *value,
                  double *rate) {
    for (int i = 0; i < n; ++i)
      {
        value[i] = y[std::size_t(i)], rate[i] = y[std::size_t(n + i)];
        value[n + i] = y[std::size_t(n + i)], rate[n + i] = at.alpha[std::size_t(i)];
      }
    for (int i = 0; i < meshes; ++i)
      {
        const MeshEval &e         = at.meshes[std::size_t(i)];
        const double    r_d       = at.force_rate[std::size_t(i)][drive_side],
                     r_c          = at.force_rate[std::size_t(i)][coast_side];
        value[2 * n + i]          = e.force[drive_side] - e.force[coast_side];
        rate[2 * n + i]           = r_d - r_c;
        value[2 * n + meshes + i] = e.force[drive_side] + e.force[coast_side];
        rate[2 * n + meshes + i]  = r_d + r_c;
      }
  };
  fill(y_a, at_a, value_a, rate_a);
  fill(y_b, at_b, value_b, rate_b);
  const double h = b - a;
  alias->advance(a, b, [&](double t, double *v) {
    const double u = (t - a) / h, u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = (u3 - 2 * u2 + u) * h, h01 = -2 * u3 + 3 * u2,
                 h11 = (u3 - u2) * h;
    for (std::size_t j = 0; j < channels; ++j)
      v[j] = h00 * value_a[j] + h10 * rate_a[j] + h01 * value_b[j] + h11 * rate_b[j];
  });
}

void
TrainRecorder::sample(double t, const std::vector<double> &state, const std::vector<double> &q)
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

void
TrainRecorder::extremes(double t, const std::vector<MeshEval> &evaluated)
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

void
TrainRecorder::integrate(double a, double b, const SolutionPoint &at_a, const SolutionPoint &at_b)
{
  const double h = b - a;
  for (std::size_t i = 0; i < std::size_t(meshes); ++i)
    for (std::size_t side = 0; side < 2; ++side)
      impulse[2 * i + side] += h / 2 * (at_a.meshes[i].force[side] + at_b.meshes[i].force[side]) +
                               h * h / 12 * (at_a.force_rate[i][side] - at_b.force_rate[i][side]);
}

void
TrainRecorder::contact(int i, int side, bool touch, double t)
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

TrainResult
TrainRecorder::finish(const CvodeSolver &solver)
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
/// Updates the touching counts from the contact roots that fired at t (CVODE's directions), the
/// recorder's contacts with them; whether any changed.
bool
record_contact_changes(const std::vector<int> &fired, int meshes, double t,
                       std::vector<char> &touching, TrainRecorder &rec)
{
  bool changed = false;
  for (int i = 0; i < meshes; ++i)
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < ranked_contacts; ++k)
        if (const int f = fired[std::size_t(roots_per_mesh * i + rank_root(side, k))])
          {
            char &count = touching[std::size_t(2 * i + side)];
            count       = f > 0 ? std::max(count, char(k + 1)) : std::min(count, char(k));
            if (k == 0)
              rec.contact(i, side, f > 0, t);
            changed = true;
          }
  return changed;
}

/// Whether a kink root that fired belongs to a pairing touching at its kink (`kinks`: the kink
/// roots after the contacts', kink_root_list).
bool
passes_touching_kink(const TrainSystem &sys, const std::vector<int> &fired,
                     const std::vector<std::pair<int, int>> &kinks, const std::vector<double> &y)
{
  const std::size_t first = std::size_t(roots_per_mesh) * sys.model.meshes.size();
  for (std::size_t r = first; r < fired.size(); ++r)
    if (fired[r] && sys.kink_touches(kinks[r - first].first, kinks[r - first].second, y.data()))
      return true;
  return false;
}
} // namespace

double
damping_time_constant(const TrainModel &model)
{
  auto mobility = [&](int body, double radius) { // r^2 / J, 0 for a body held at its speed
    const TrainBody &b = model.bodies[std::size_t(body)];
    return b.constant_speed || !(b.inertia > 0) ? 0.0 : radius * radius / b.inertia;
  };
  double shortest = HUGE_VAL;
  for (const TrainMesh &m : model.meshes)
    {
      const double per_mass = mobility(m.driver, m.pinion_base_radius) +
                              mobility(m.driven, m.gear_base_radius); // 1 / m_e
      if (m.law.damping > 0 && per_mass > 0)
        shortest = std::min(shortest, 1 / (m.law.damping * per_mass));
    }
  for (const TrainShaft &s : model.shafts)
    {
      const double per_inertia = mobility(s.a, 1) + mobility(s.b, 1);
      if (s.damping > 0 && per_inertia > 0)
        shortest = std::min(shortest, 1 / (s.damping * per_inertia));
    }
  return shortest;
}

TrainIntegrator
resolve_integrator(const TrainModel &model, TrainIntegrator method)
{
  if (method != TrainIntegrator::automatic)
    return method;
  return damping_time_constant(model) < stiff_time_constant ? TrainIntegrator::bdf
                                                            : TrainIntegrator::adams;
}

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
  std::vector<int>                       fired, hidden_fired;
  const std::vector<std::pair<int, int>> kinks = kink_root_list(sys);
  std::vector<MeshEval>                  middle;
  std::vector<double>                    ys, qs, g(std::size_t(p.roots));
  // the meshes and accelerations at a piece's start and end (the end's from the quadratures'
  // and root functions' evaluation there, when it is theirs)
  auto point_at = [&](double time, const std::vector<double> &state, SolutionPoint &point) {
    if (last_evaluation.at(time, state))
      point.meshes = last_evaluation.meshes, point.alpha = last_evaluation.alpha;
    else
      {
        double power, dissipation;
        point.alpha.resize(std::size_t(n));
        sys.evaluate(time, state.data(), state.data() + n, point.alpha.data(), power, dissipation,
                     &point.meshes, true);
      }
    point.set_force_rates(sys);
  };
  SolutionPoint       start, end;
  std::vector<double> y_last = y; // the state at the piece's start
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
      bool root = solver.step(o.duration, t, y, &fired);
      point_at(t, y, end);
      // a contact that changes and changes back inside the step, looked for at its midpoint
      // where the touch functions' cubics come near zero
      bool have_middle = false, restart = false;
      if (contact_may_change_inside(start, end, touching, touch_hysteresis(o), last, t))
        {
          have_middle         = true;
          const double hidden = hidden_contact_change(solver, sys, touching, touch_hysteresis(o),
                                                      last, t, hidden_fired, middle);
          restart             = hidden < t; // the run goes on from there
          if (restart)
            {
              t = hidden, root = true;
              solver.interpolate(t, y);
              fired.swap(hidden_fired);
              solver.interpolate((last + t) / 2, ys);
              middle = meshes_at(sys, ys);
              point_at(t, y, end);
            }
        }
      rec.integrate(last, t, start, end);
      rec.record(last, t, y_last, start, y, end);
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
      for (const double x :
           piece_peaks(solver, sys, last, t, start, have_middle ? &middle : nullptr, end))
        {
          solver.interpolate(x, ys);
          rec.extremes(x, meshes_at(sys, ys));
        }
      std::swap(start, end);
      y_last = y;
      if (root)
        {
          const bool contact_change = record_contact_changes(fired, meshes, t, touching, rec);
          const bool kink           = passes_touching_kink(sys, fired, kinks, y);
          // restart the method at every touch and separation, of a side and of a pair (the
          // force law's derivatives jump there: BDF's history across the kink costs accuracy, the
          // energy balance of a damped driven run 1.6e-6 without the restarts against 1e-6 with
          // them), where a touching pair passes a kink of its curve (its penetration's slope
          // jumps, and with it the damping force), after a change found inside a step, and where
          // a root function is exactly zero at the root (rounding-quantised rates): CVODE would
          // take it for a root "at and very near" the last one, a restart sets it aside
          if (contact_change)
            ++rec.out.events;
          p.root_functions(t, y.data(), g.data());
          if (contact_change || kink || restart || std::find(g.begin(), g.end(), 0.0) != g.end())
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
  TrainResult r = rec.finish(solver);
  r.method      = resolve_integrator(model, o.method);
  return r;
}
} // namespace gearkit

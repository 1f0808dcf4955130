#include "dynamics/integrators.h"

#include "dynamics/cvode_solver.h"

#include <Eigen/Dense>

#include <cmath>

namespace gearkit
{
namespace
{
/// The sample at time t: the state, delta_D, delta_D - E_t and F_m.
struct Sample
{
  double delta = 0, relative = 0, force = 0;
  /// finite and |delta_D - E_t| within the divergence bound
  bool within = true;
};

Sample
sample(const PairModel &model, const RunOptions &o, double t, const PairVector &q,
       const PairVector &v)
{
  const MeshState  m       = model.mesh().at(model.phase(t, o.omega));
  const PairVector g       = PairModel::mesh_gradient(m);
  const double     et_rate = m.det * model.parameters().pinion_teeth * o.omega / (2 * pi);
  Sample           s;
  s.delta    = g.dot(q);
  s.relative = s.delta - m.et;
  s.force    = model.mesh_force(m, s.delta, g.dot(v), et_rate);
  s.within   = q.allFinite() && v.allFinite() && std::isfinite(s.force) &&
             std::abs(s.relative) <= o.divergence_bound;
  return s;
}

/// A point of the solution (a sample, a located stationary point) in the trajectory's extremes.
void
extend(Trajectory &out, const Sample &s)
{
  out.dte_min      = std::min(out.dte_min, s.delta);
  out.dte_max      = std::max(out.dte_max, s.delta);
  out.relative_min = std::min(out.relative_min, s.relative);
  out.relative_max = std::max(out.relative_max, s.relative);
  out.force_max    = std::max(out.force_max, s.force);
}

/// Appends the sample at time t; where it is not within the divergence bound (or not finite),
/// marks the run diverged at t instead (the initial sample is kept all the same) and returns
/// false.
bool
record(const PairModel &model, const RunOptions &o, double t, const PairVector &q,
       const PairVector &v, Trajectory &out)
{
  const Sample s = sample(model, o, t, q, v);
  if (!s.within)
    {
      out.diverged = true, out.diverged_at = t;
      if (!out.t.empty())
        return false;
    }
  out.t.push_back(t);
  out.q.push_back(q);
  out.v.push_back(v);
  out.dte.push_back(s.delta);
  out.relative.push_back(s.relative);
  out.force.push_back(s.force);
  if (s.within)
    extend(out, s);
  return s.within;
}

Trajectory
run_cvode(const PairModel &model, const PairVector &q0, const PairVector &v0, const RunOptions &o)
{
  // y = [q; v] in SI, time tau in mesh cycles (the mesh phase): dy/dtau = T dy/dt
  Trajectory   out;
  const double period = 2 * pi / (model.parameters().pinion_teeth * o.omega);
  CvodeProblem p;
  p.what = "pair dynamics";
  p.hint = "try a smaller tolerance, the Newmark path, or check the model's stiffnesses";
  p.size = 2 * pair_dofs;
  p.bdf  = o.method != Integrator::cvode_adams;
  p.rhs  = [&](double tau, const double *y, double *ydot) {
    Eigen::Map<const PairVector> q(y), v(y + pair_dofs);
    Eigen::Map<PairVector>       dq(ydot), dv(ydot + pair_dofs);
    dq = period * v;
    dv = period * model.acceleration(tau * period, q, v, o.omega, o.motor_torque, o.load_torque);
    return 0;
  };
  // roots: the stationary points of delta_D and delta_D - E_t (extremes), then the backlash
  // boundaries delta_D - E_t = +-b, where the mesh force changes its law
  const bool   backlash          = model.parameters().half_backlash > 0;
  const double cycles_per_second = 1 / period;
  p.roots                        = backlash ? 4 : 2;
  p.root_functions               = [&, cycles_per_second](double tau, const double *y, double *g) {
    const MeshState  m    = model.mesh().at(tau);
    const PairVector grad = PairModel::mesh_gradient(m);
    const double     rate = grad.dot(Eigen::Map<const PairVector>(y + pair_dofs));
    g[0]                  = rate;
    g[1]                  = rate - m.det * cycles_per_second;
    if (backlash)
      {
        const double x = grad.dot(Eigen::Map<const PairVector>(y)) - m.et,
                     b = model.parameters().half_backlash;
        g[2]           = x - b;
        g[3]           = x + b;
      }
  };
  // scales: the static mesh deflection's, the half backlash, at least a micrometre
  const PairVector s   = model.dof_scale(std::max(model.parameters().half_backlash, 1e-6));
  p.relative_tolerance = o.relative_tolerance;
  p.absolute_tolerance.resize(p.size);
  for (int i = 0; i < pair_dofs; ++i)
    {
      p.absolute_tolerance[i]             = o.absolute_tolerance * s[i];
      p.absolute_tolerance[pair_dofs + i] = o.absolute_tolerance * s[i] / period;
    }
  std::vector<double> y(p.size);
  Eigen::Map<PairVector>(y.data())             = q0;
  Eigen::Map<PairVector>(y.data() + pair_dofs) = v0;
  CvodeSolver      solver(p, 0.0, y);
  const int        n_out = int(std::lround(o.mesh_cycles * o.samples_per_cycle));
  double           tau   = 0;
  bool             going = record(model, o, 0, q0, v0, out);
  std::vector<int> fired;
  for (int k = 1; k <= n_out && going; ++k)
    {
      const double tout = double(k) / o.samples_per_cycle;
      while (going && solver.advance(tout, tau, y, &fired))
        {
          const Sample at = sample(model, o, tau * period, Eigen::Map<const PairVector>(y.data()),
                                   Eigen::Map<const PairVector>(y.data() + pair_dofs));
          if (at.within)
            extend(out, at);
          if (!backlash || (fired[2] == 0 && fired[3] == 0))
            continue;   // an extreme only
          ++out.events; // the mesh force changes its law here: restart the method
          // past the bound at an event: the run stops there (its state is not a sample)
          if (!at.within)
            out.diverged = true, out.diverged_at = tau * period;
          going = at.within;
          if (going)
            solver.reinit(tau, y);
        }
      if (going)
        going = record(model, o, tout * period, Eigen::Map<const PairVector>(y.data()),
                       Eigen::Map<const PairVector>(y.data() + pair_dofs), out);
    }
  out.steps = std::size_t(solver.steps());
  return out;
}

/// The stationary points of delta_D and delta_D - E_t inside Newmark's step n (from t - h to
/// t = n h), on the average acceleration's quadratic q(t - h + s) = q + s v + s^2 a_mean / 2
/// with the mesh state m (gradient g) of the step's end and E_t linear over the step.
void
stationary_points(const PairModel &model, const RunOptions &o, const MeshState &m,
                  const PairVector &g, const PairVector &q, const PairVector &v,
                  const PairVector &a_mean, int n, double h, Trajectory &out)
{
  const double x1 = g.dot(v), x2 = g.dot(a_mean);
  if (x2 == 0)
    return;
  const double et_rate = m.det * model.parameters().pinion_teeth * o.omega / (2 * pi);
  for (const double rate : {0.0, et_rate}) // delta_D' = 0, (delta_D - E_t)' = 0
    {
      const double s = (rate - x1) / x2;
      if (!(s > 0 && s < h))
        continue;
      const PairVector qs = q + s * v + s * s / 2 * a_mean, vs = v + s * a_mean;
      const Sample     at = sample(model, o, (n - 1) * h + s, qs, vs);
      if (at.within)
        extend(out, at);
    }
}

Trajectory
run_newmark(const PairModel &model, const PairVector &q0, const PairVector &v0, const RunOptions &o)
{
  Trajectory        out;
  const double      period = 2 * pi / (model.parameters().pinion_teeth * o.omega);
  const double      h      = period / o.steps_per_cycle;
  const PairMatrix &M = model.mass(), &K = model.stiffness(), &C = model.damping();
  const double      c_m           = model.mesh_damping();
  const int         z             = model.parameters().pinion_teeth;
  const PairVector  F_ext         = model.torques(o.motor_torque, o.load_torque);
  const PairVector  free          = model.active();
  const PairVector  held_dofs     = PairVector::Ones() - free;
  const PairMatrix  held          = held_dofs.asDiagonal();
  const double      b             = model.parameters().half_backlash;
  const bool        always_damped = !model.parameters().mesh_damping_in_contact_only;
  // Each step is linear in q_{n+1} except for the mesh force, a piecewise linear function of
  // the single number delta_D = g . q_{n+1}: with L = 4/h^2 M + 2/h C + K (on the free DOFs;
  // one factorisation), q_{n+1} = q_n + dq* - L^-1 g F_m, delta = delta* - (g^T L^-1 g) F_m(delta),
  // solved exactly branch by branch (contact on either flank, or none) - no Newton iterations
  // to cycle at the backlash boundaries.
  const PairMatrix L =
      free.asDiagonal() * (4 / (h * h) * M + 2 / h * C + K) * free.asDiagonal() + held;
  const Eigen::LDLT<PairMatrix> Lf(L);
  // The phase advances by 1 / steps_per_cycle a step, so the mesh repeats after one period of
  // the tables: its state, gradient and L^-1 g once for each step of that period (the tables'
  // interpolation and a solve per step were most of a step's cost).
  struct StepMesh
  {
    MeshState  m;
    PairVector g, Lg;
    double     gLg = 0;
  };
  std::vector<StepMesh> mesh(std::size_t(o.steps_per_cycle * model.mesh().cycles()));
  for (std::size_t k = 0; k < mesh.size(); ++k)
    {
      StepMesh &s = mesh[k];
      s.m         = model.mesh().at(double(k) / o.steps_per_cycle);
      s.g         = PairModel::mesh_gradient(s.m).cwiseProduct(free);
      s.Lg        = Lf.solve(s.g);
      s.gLg       = s.g.dot(s.Lg);
    }
  // dq* = L^-1 (F_ext - K q + M (4/h v + a) + C v) on the free DOFs, as one product
  const PairMatrix                                F = free.asDiagonal();
  Eigen::Matrix<double, pair_dofs, 3 * pair_dofs> P;
  P << Lf.solve(-F * K), Lf.solve(F * (4 / h * M + C)), Lf.solve(F * M);
  const PairVector                        base = Lf.solve(F_ext.cwiseProduct(free));
  Eigen::Matrix<double, 3 * pair_dofs, 1> state;
  PairVector                              q = q0, v = v0, a;
  {
    const MeshState  &m  = mesh.front().m;
    const PairVector &g  = mesh.front().g;
    const double      Fm = model.mesh_force(m, g.dot(q), g.dot(v), m.det * z * o.omega / (2 * pi));
    a                    = M.ldlt().solve(F_ext - K * q - C * v - g * Fm).cwiseProduct(free);
  }
  if (!record(model, o, 0, q, v, out))
    return out;
  const int steps_total = int(std::lround(o.mesh_cycles * o.steps_per_cycle));
  const int every       = o.steps_per_cycle / o.samples_per_cycle;
  for (int n = 1; n <= steps_total; ++n)
    {
      const double      t  = n * h;
      const StepMesh   &sm = mesh[std::size_t(n) % mesh.size()];
      const MeshState  &m  = sm.m;
      const PairVector &g = sm.g, &Lg = sm.Lg;
      const double      gLg     = sm.gLg;
      const double      et_rate = m.det * z * o.omega / (2 * pi);
      // in increments (the rigid rotation of a torque-driven train grows without bound; the
      // step must not cancel it against itself): L dq = dq* - L^-1 g F_m
      state << q, v, a;
      const PairVector dqs   = base + P * state;
      const double     dstar = g.dot(q) + g.dot(dqs);
      const double     D0    = -(2 / h * g.dot(q) + g.dot(v)); // delta' = 2/h delta + D0
      const double     c2h = 2 / h * c_m, damp0 = c_m * (D0 - et_rate);
      // F_m = alpha delta + beta on each branch; delta = dstar - gLg F_m
      double delta = 0, Fm = 0;
      bool   found  = false;
      auto   branch = [&](double alpha, double beta, double lo, double hi) {
        if (found)
          return;
        const double d = (dstar - gLg * beta) / (1 + gLg * alpha);
        const double x = d - m.et;
        if (x >= lo && x <= hi)
          delta = d, Fm = alpha * d + beta, found = true;
      };
      branch(m.km + c2h, -m.km * (m.et + b) + damp0, b, HUGE_VAL);           // drive flank
      branch(always_damped ? c2h : 0.0, always_damped ? damp0 : 0.0, -b, b); // no contact
      branch(m.km + c2h, -m.km * (m.et - b) + damp0, -HUGE_VAL, -b);         // coast flank
      if (!found) // the root sits in the damping force's jump at a boundary: stay there
        {
          const double x = dstar - m.et > 0 ? b : -b;
          delta = m.et + x, Fm = (dstar - delta) / gLg;
        }
      // diverged (or not finite: the comparison fails for NaN): stop before the step
      if (!(std::abs(delta - m.et) <= o.divergence_bound) || !std::isfinite(Fm))
        {
          out.diverged = true, out.diverged_at = t;
          break;
        }
      const PairVector dq = dqs - Lg * Fm; // the increment: no cancellation against q
      const PairVector an = 4 / (h * h) * (dq - h * v) - a;
      stationary_points(model, o, m, g, q, v, (a + an) / 2, n, h, out);
      v += h / 2 * (a + an);
      q += dq;
      a = an;
      ++out.steps;
      if (n % every == 0 && !record(model, o, t, q, v, out))
        break;
    }
  return out;
}
} // namespace

Trajectory
simulate(const PairModel &model, const PairVector &q0, const PairVector &v0, const RunOptions &o)
{
  auto require = [](bool ok, const std::string &what, double value, const std::string &allowed) {
    require_value(ok, "pair dynamics", what, value, allowed);
  };
  require(o.omega > 0 && std::isfinite(o.omega), "pinion speed [rad/s]", o.omega, "> 0");
  require(o.mesh_cycles > 0, "mesh cycles", o.mesh_cycles, "> 0");
  require(o.samples_per_cycle >= 1, "samples per mesh cycle", o.samples_per_cycle, ">= 1");
  require(o.relative_tolerance > 0 && o.absolute_tolerance > 0, "tolerance",
          std::min(o.relative_tolerance, o.absolute_tolerance), "> 0");
  require(o.method != Integrator::newmark ||
              (o.steps_per_cycle >= 1 && o.steps_per_cycle % o.samples_per_cycle == 0),
          "Newmark steps per mesh cycle", o.steps_per_cycle,
          "a multiple of the output samples per mesh cycle (" +
              std::to_string(o.samples_per_cycle) + ")");
  require(q0.allFinite() && v0.allFinite(), "initial state (finite)", 0, "finite values");
  return o.method == Integrator::newmark ? run_newmark(model, q0, v0, o)
                                         : run_cvode(model, q0, v0, o);
}
} // namespace gearkit

#include "sweep.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gearkit
{
namespace
{
void
peak_and_rms(const std::vector<double> &x, double &pp, double &rms)
{
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  pp                  = *hi - *lo;
  const double mean   = std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
  double       s      = 0;
  for (double xi : x)
    s += (xi - mean) * (xi - mean);
  rms = std::sqrt(s / double(x.size()));
}
/// Period (1 to 4 mesh cycles) with which the last Poincare points repeat, or 0. The train's
/// rigid rotation may drift: displacements are compared through their increments per cycle.
int
repeat_period(const std::vector<PairVector> &q, const std::vector<PairVector> &v,
              const PairVector &scale, double rate_scale, double tolerance)
{
  const int n = int(q.size());
  for (int p = 1; p <= 4; ++p)
    {
      if (n < 2 * p + 2)
        break;
      double worst = 0;
      for (int k = n - p; k < n; ++k) // the last p points against those a period earlier
        {
          const PairVector dq = (q[k] - q[k - 1]) - (q[k - p] - q[k - p - 1]);
          worst               = std::max(worst, (dq.array() / scale.array()).abs().maxCoeff());
          worst               = std::max(
                            worst, ((v[k] - v[k - p]).array() / (rate_scale * scale.array())).abs().maxCoeff());
        }
      if (worst < tolerance)
        return p;
    }
  return 0;
}
} // namespace

std::vector<SweepPoint>
sweep(const PairModel &model, PairVector &q, PairVector &v, const SweepOptions &o)
{
  if (o.speeds.empty() || o.settle_cycles < 0 || o.record_cycles < 1)
    throw InputError("pair dynamics: a sweep needs speeds, settle cycles >= 0 and record cycles "
                     ">= 1");
  const StaticEquilibrium s0 = model.static_equilibrium(o.load_torque);
  // Poincare points compare against the static deflection's scale
  const PairVector        scale = model.dof_scale(std::max(std::abs(s0.deflection), 1e-9));
  std::vector<SweepPoint> out;
  for (double omega : o.speeds)
    {
      RunOptions r   = o.run;
      r.omega        = omega;
      r.motor_torque = o.motor_torque, r.load_torque = o.load_torque;
      // settle in chunks, watching the Poincare points (states at whole mesh cycles)
      int settled = 0, period = 0;
      {
        const double rate = model.parameters().pinion_teeth * omega; // mesh frequency [rad/s]
        std::vector<PairVector> pq{q}, pv{v};
        while (settled < o.settle_cycles && period == 0)
          {
            RunOptions settle        = r;
            settle.mesh_cycles       = std::min(10, o.settle_cycles - settled);
            settle.samples_per_cycle = 1;
            settle.steps_per_cycle   = std::max(r.steps_per_cycle, 1);
            const Trajectory t       = simulate(model, q, v, settle);
            pq.insert(pq.end(), t.q.begin() + 1, t.q.end());
            pv.insert(pv.end(), t.v.begin() + 1, t.v.end());
            q = t.q.back(), v = t.v.back();
            settled += int(settle.mesh_cycles);
            if (o.steady_tolerance > 0 && settled >= o.min_settle_cycles)
              period = repeat_period(pq, pv, scale, rate, o.steady_tolerance);
            if (pq.size() > 16) // keep the last points only
              pq.erase(pq.begin(), pq.end() - 16), pv.erase(pv.begin(), pv.end() - 16);
          }
      }
      r.mesh_cycles      = o.record_cycles;
      const Trajectory t = simulate(model, q, v, r);
      q = t.q.back(), v = t.v.back();
      SweepPoint p;
      p.speed = omega;
      peak_and_rms(t.dte, p.dte_pp, p.dte_rms);
      peak_and_rms(t.relative, p.relative_pp, p.relative_rms);
      p.max_force    = *std::max_element(t.force.begin(), t.force.end());
      p.load_factor  = p.max_force / s0.mesh_force;
      const double b = model.parameters().half_backlash;
      p.contact_loss = double(std::count_if(t.relative.begin(), t.relative.end(),
                                            [&](double x) { return std::abs(x) < b; })) /
                       double(t.relative.size());
      p.events         = t.events;
      p.settled_cycles = settled;
      p.period         = period;
      out.push_back(p);
    }
  return out;
}
} // namespace gearkit

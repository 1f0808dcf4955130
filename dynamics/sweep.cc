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
} // namespace

std::vector<SweepPoint>
sweep(const PairModel &model, PairVector &q, PairVector &v, const SweepOptions &o)
{
  if (o.speeds.empty() || o.settle_cycles < 0 || o.record_cycles < 1)
    throw InputError("pair dynamics: a sweep needs speeds, settle cycles >= 0 and record cycles "
                     ">= 1");
  const double static_force = model.static_equilibrium(o.load_torque).mesh_force;
  std::vector<SweepPoint> out;
  for (double omega : o.speeds)
    {
      RunOptions r   = o.run;
      r.omega        = omega;
      r.motor_torque = o.motor_torque, r.load_torque = o.load_torque;
      if (o.settle_cycles > 0)
        {
          RunOptions settle        = r;
          settle.mesh_cycles       = o.settle_cycles;
          settle.samples_per_cycle = 1;
          const Trajectory s       = simulate(model, q, v, settle);
          q = s.q.back(), v = s.v.back();
        }
      r.mesh_cycles      = o.record_cycles;
      const Trajectory t = simulate(model, q, v, r);
      q = t.q.back(), v = t.v.back();
      SweepPoint p;
      p.speed = omega;
      peak_and_rms(t.dte, p.dte_pp, p.dte_rms);
      peak_and_rms(t.relative, p.relative_pp, p.relative_rms);
      p.max_force   = *std::max_element(t.force.begin(), t.force.end());
      p.load_factor = p.max_force / static_force;
      const double b = model.parameters().half_backlash;
      p.contact_loss = double(std::count_if(t.relative.begin(), t.relative.end(),
                                            [&](double x) { return std::abs(x) < b; })) /
                       double(t.relative.size());
      p.events = t.events;
      out.push_back(p);
    }
  return out;
}
} // namespace gearkit

#include "dynamics/sweep.h"

#include "base/parallel.h"
#include "base/progress.h"
#include "base/spectrum.h"
#include "dynamics/newmark_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

namespace gearkit
{
namespace
{
/// Root mean square of x about its mean.
double
rms_about_mean(const std::vector<double> &x)
{
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
  double       s    = 0;
  for (double xi : x)
    s += (xi - mean) * (xi - mean);
  return std::sqrt(s / double(x.size()));
}
/// Largest mismatch of the last `count` Poincare points against those p sections earlier
/// (relative to the scales; displacements through their increments per section: the train's
/// rigid rotation may drift); infinite when there are too few points.
double
repeat_mismatch(const std::vector<PairVector> &q, const std::vector<PairVector> &v, int p,
                int count, const PairVector &scale, double rate_scale)
{
  const int n = int(q.size());
  if (n < count + p + 1)
    return std::numeric_limits<double>::infinity();
  double worst = 0;
  for (int k = n - count; k < n; ++k)
    {
      const PairVector dq = (q[k] - q[k - 1]) - (q[k - p] - q[k - p - 1]);
      worst               = std::max(worst, (dq.array() / scale.array()).abs().maxCoeff());
      worst               = std::max(worst,
                                     ((v[k] - v[k - p]).array() / (rate_scale * scale.array())).abs().maxCoeff());
    }
  return worst;
}

/// Mismatches of the last Poincare points against those 1 to 4 sections earlier (index p),
/// each over three whole periods.
using Mismatches = std::array<double, 5>;

Mismatches
mismatches(const std::vector<PairVector> &q, const std::vector<PairVector> &v,
           const PairVector &scale, double rate_scale)
{
  Mismatches m;
  m[0] = 0;
  for (int p = 1; p <= 4; ++p)
    m[std::size_t(p)] = repeat_mismatch(q, v, p, 3 * p, scale, rate_scale);
  return m;
}

/// Period (1 to 4 sections) with which the Poincare points repeat over three whole periods, or
/// 0 (not yet), from their mismatches now and one settling chunk (ten mesh cycles or more)
/// before. A period p > 1 counts only
/// when the mismatches of every shorter period hold still (within 0.1 %): a transient that
/// decays while alternating between p states (a Floquet multiplier near a p-th root of unity)
/// repeats after p sections sooner than after fewer and would pass for a subharmonic, but
/// those shorter mismatches fall, while a subharmonic's stay. A subharmonic's points stand
/// apart by a hundred times the tolerance at least (closer, it is not told from the scatter
/// and a decaying transient) and repeat to the tolerance relative to their spread (the
/// integrator's scatter grows with the motion).
int
repeat_period(const Mismatches &now, const Mismatches &before, double tolerance)
{
  if (now[1] < tolerance)
    return 1;
  if (now[1] < 100 * tolerance)
    return 0; // near period 1: a subharmonic that close is not told from the scatter
  const double subharmonic = tolerance * std::max(1.0, 10 * now[1]);
  for (std::size_t p = 2; p <= 4; ++p)
    {
      const double shorter = now[p - 1], earlier = before[p - 1];
      if (!std::isfinite(earlier) || std::abs(shorter - earlier) > 1e-3 * shorter)
        return 0; // a shorter period's mismatch still moves: settle on
      if (now[p] < subharmonic)
        return int(p);
    }
  return 0;
}

/// The tolerance of the Poincare test: the sweep's, but no less than what the integrator can
/// repeat: CVODE's Poincare points scatter by up to a thousand times its tolerances (relative
/// to the same scales; measured on the Kahraman-Singh sweep: with 10 or 100 times, 1 in 4
/// speeds never settles at 1e-8), Newmark's fixed steps repeat to rounding.
double
steady_tolerance(const SweepOptions &o, const RunOptions &r)
{
  if (r.method == Integrator::newmark)
    return o.steady_tolerance;
  return std::max(o.steady_tolerance, 1e3 * std::max(r.relative_tolerance, r.absolute_tolerance));
}

/// Index of the speed in the list nearest w.
std::size_t
nearest(const std::vector<double> &speeds, double w)
{
  std::size_t best = 0;
  for (std::size_t i = 1; i < speeds.size(); ++i)
    if (std::abs(speeds[i] - w) < std::abs(speeds[best] - w))
      best = i;
  return best;
}
/// Rounded up to whole periods of the excitation.
int
whole_periods(int cycles, int period)
{
  return period * ((cycles + period - 1) / period);
}
/// Settles (q, v) at r.omega in chunks of whole periods of the excitation (each run starts
/// at phase 0), watching the Poincare points (states at whole periods), until they repeat, the
/// response diverges (r.divergence_bound; `diverged_at` [s] then says when, from the start of
/// this call), or `most` mesh cycles - extended up to five times that while the mismatch of
/// period 1 still falls geometrically fast enough to reach the tolerance within the extension
/// (a slowly decaying transient near a parametric resonance, not a motion that never repeats).
void
settle(const PairModel &model, PairVector &q, PairVector &v, const RunOptions &r,
       const SweepOptions &o, int most, const PairVector &scale, int &settled, int &period,
       bool &diverged, double &diverged_at)
{
  const int    K         = model.mesh().cycles();
  const double rate      = model.parameters().pinion_teeth * r.omega / K;        // [rad/s]
  const double cycle     = 2 * pi / (model.parameters().pinion_teeth * r.omega); // [s]
  const double tolerance = steady_tolerance(o, r);
  const int    chunk_len = whole_periods(10, K);
  const int    hardest   = 5 * most;
  int          limit     = most;
  Mismatches   previous;
  previous.fill(std::numeric_limits<double>::infinity());
  std::vector<PairVector> pq{q}, pv{v};
  while (settled < limit && period == 0 && !diverged)
    {
      RunOptions chunk        = r;
      chunk.mesh_cycles       = std::min(chunk_len, limit - settled);
      chunk.samples_per_cycle = 1;
      chunk.steps_per_cycle   = std::max(r.steps_per_cycle, 1);
      const Trajectory t      = simulate(model, q, v, chunk);
      q = t.q.back(), v = t.v.back();
      if (t.diverged)
        {
          diverged    = true;
          diverged_at = settled * cycle + t.diverged_at;
          settled += int(t.t.size()) - 1; // the whole mesh cycles run before
          break;
        }
      for (std::size_t k = std::size_t(K); k < t.q.size(); k += std::size_t(K))
        pq.push_back(t.q[k]), pv.push_back(t.v[k]);
      settled += int(chunk.mesh_cycles);
      if (o.steady_tolerance > 0 && settled >= o.min_settle_cycles)
        {
          const Mismatches now = mismatches(pq, pv, scale, rate);
          period               = K * repeat_period(now, previous, tolerance);
          if (period == 0 && settled >= limit && now[1] < previous[1] &&
              std::isfinite(previous[1]) && int(chunk.mesh_cycles) == chunk_len)
            {
              // chunks to the tolerance at the last chunk's rate of decay
              const double chunks = std::log(tolerance / now[1]) / std::log(now[1] / previous[1]);
              if (chunks > 0 && settled + (std::ceil(chunks) + 1) * chunk_len <= hardest)
                limit = settled + int(std::ceil(chunks) + 1) * chunk_len;
            }
          previous = now;
        }
      if (pq.size() > 24) // keep the last points only (three periods of 4 and more)
        pq.erase(pq.begin(), pq.end() - 24), pv.erase(pv.begin(), pv.end() - 24);
    }
}
} // namespace

std::vector<SweepPoint>
sweep(const PairModel &model, PairVector &q, PairVector &v, const SweepOptions &o)
{
  if (o.speeds.empty() || o.settle_cycles < 0 || o.record_cycles < 1 || o.spectrum_orders < 0 ||
      o.warmup_speeds < 0 || o.warmup_speeds >= int(o.speeds.size()))
    throw InputError("pair dynamics: a sweep needs speeds (more than its warm-up speeds), settle "
                     "cycles >= 0, record cycles >= 1 and spectrum orders >= 0");
  require_value(o.divergence_factor > 0, "pair dynamics", "divergence factor", o.divergence_factor,
                "> 0 (infinite: only a state that is not finite diverges)");
  const int               K  = model.mesh().cycles(); // mesh cycles per period of the excitation
  const StaticEquilibrium s0 = model.static_equilibrium(o.load_torque);
  // Poincare points compare against the static deflection's scale
  const PairVector scale       = model.dof_scale(std::max(std::abs(s0.deflection), 1e-9));
  const int        record      = whole_periods(o.record_cycles, K);
  const int        settle_most = whole_periods(o.settle_cycles, K);
  // a response beyond any physical meaning (or not finite): the mesh deflection far past its
  // length scale, the static deflection, the clearance and E_t's peak-to-peak
  // (SweepOptions::divergence_factor)
  const auto &et            = model.tables().transmission_error;
  const auto [et_lo, et_hi] = std::minmax_element(et.begin(), et.end());
  const double bound        = o.divergence_factor * (std::abs(s0.deflection) +
                                              model.parameters().half_backlash + *et_hi - *et_lo);
  // the swept speeds whose time series are kept
  std::vector<bool> keep(o.speeds.size(), false);
  for (double w : o.series_speeds)
    keep[nearest(o.speeds, w)] = true;
  // Newmark: its error estimated at every speed; with an accuracy asked for, its steps chosen
  // from the estimate for the tables' forcing (exact for the linear model), then raised while
  // the estimate from the recorded motion's own harmonics exceeds half of it (first order, and
  // blind above the record's Nyquist order: contact loss at Kahraman-Singh's Omega 0.3 errs by
  // 1.2 times that estimate). Both estimate the RMS of the error signal, which bounds the
  // error of the RMS.
  std::optional<NewmarkError> newmark;
  if (o.run.method == Integrator::newmark)
    newmark.emplace(model, o.load_torque);
  const int               most_steps = std::max(o.most_steps, o.run.steps_per_cycle);
  std::vector<SweepPoint> out;
  for (std::size_t i = 0; i < o.speeds.size(); ++i)
    {
      const double omega = o.speeds[i];
      const double cycle = 2 * pi / (model.parameters().pinion_teeth * omega); // [s]
      RunOptions   r     = o.run;
      r.omega            = omega;
      r.divergence_bound = bound;
      if (newmark && o.accuracy > 0)
        r.steps_per_cycle = newmark->steps(omega, o.accuracy, o.run.steps_per_cycle,
                                           r.samples_per_cycle, most_steps);
      r.motor_torque = o.motor_torque, r.load_torque = o.load_torque;
      int        settled = 0, period = 0;
      bool       diverged    = false;
      double     diverged_at = 0, run = 0; // [s]; the time run at this speed so far
      double     error = std::numeric_limits<double>::quiet_NaN();
      Trajectory t;
      for (int refinements = 0;; ++refinements)
        {
          period   = 0;
          int more = 0;
          settle(model, q, v, r, o, settle_most, scale, more, period, diverged, diverged_at);
          settled += more;
          if (diverged)
            {
              diverged_at += run;
              break;
            }
          run += more * cycle;
          r.mesh_cycles = record;
          t             = simulate(model, q, v, r);
          q = t.q.back(), v = t.v.back();
          if (t.diverged)
            {
              diverged = true, diverged_at = run + t.diverged_at;
              break;
            }
          run += record * cycle;
          if (!newmark)
            break;
          const std::vector<double> dte(t.dte.begin(), t.dte.end() - 1);
          const double posterior = newmark->recorded(omega, r.steps_per_cycle, dte, record);
          error                  = std::max(newmark->forced(omega, r.steps_per_cycle), posterior);
          if (!(o.accuracy > 0) || posterior <= o.accuracy / 2 || r.steps_per_cycle >= most_steps ||
              refinements == 4)
            break;
          const double more_steps = std::max(1.5, 1.05 * std::sqrt(2 * posterior / o.accuracy));
          r.steps_per_cycle =
              newmark->steps(omega, o.accuracy,
                             std::min(most_steps, int(std::ceil(r.steps_per_cycle * more_steps))),
                             r.samples_per_cycle, most_steps);
        }
      if (diverged) // the next speed starts afresh
        q = s0.q, v = PairVector::Zero();
      if (int(i) < o.warmup_speeds)
        continue;
      SweepPoint p;
      p.speed           = omega;
      p.settled_cycles  = settled;
      p.record_cycles   = record;
      p.steps_per_cycle = newmark ? r.steps_per_cycle : 0;
      p.error_estimate  = error;
      if (diverged) // no results: zeros, flagged (never an input to maxima or means)
        {
          p.diverged       = true;
          p.diverged_time  = diverged_at;
          p.error_estimate = newmark ? 0 : error;
          p.spectrum.assign(std::size_t(o.spectrum_orders * record) + 1, 0.0);
          out.push_back(std::move(p));
          if (o.progress)
            o.progress->advance();
          continue;
        }
      p.dte_rms      = rms_about_mean(t.dte);
      p.relative_rms = rms_about_mean(t.relative);
      // the extremes of the continuous solution (located inside the steps), not the samples'
      p.dte_pp       = t.dte_max - t.dte_min;
      p.relative_pp  = t.relative_max - t.relative_min;
      p.max_force    = t.force_max;
      p.load_factor  = p.max_force / s0.mesh_force;
      const double b = model.parameters().half_backlash;
      p.contact_loss = double(std::count_if(t.relative.begin(), t.relative.end(),
                                            [&](double x) { return std::abs(x) < b; })) /
                       double(t.relative.size());
      p.events = t.events;
      p.period = period;
      // the samples cover whole periods; the last one starts the next
      p.spectrum = amplitude_spectrum(std::vector<double>(t.dte.begin(), t.dte.end() - 1),
                                      o.spectrum_orders * record);
      if (keep[i])
        for (std::size_t k = 0; k < t.t.size(); ++k)
          {
            p.series_time.push_back(t.t[k]);
            p.series_dte.push_back(t.dte[k]);
            p.series_transmission_error.push_back(t.dte[k] - t.relative[k]);
            p.series_force.push_back(t.force[k]);
          }
      out.push_back(std::move(p));
      if (o.progress)
        o.progress->advance();
    }
  return out;
}

std::vector<SweepOptions>
split_sweep(const SweepOptions &o, int blocks, int warmup)
{
  const int n = int(o.speeds.size());
  if (blocks < 1 || warmup < 0)
    throw InputError("pair dynamics: a sweep splits into >= 1 blocks with >= 0 warm-up speeds");
  blocks = std::min(blocks, std::max(n, 1));
  std::vector<SweepOptions> out;
  for (int b = 0; b < blocks; ++b)
    {
      const int    begin = n * b / blocks, end = n * (b + 1) / blocks;
      const int    from  = std::max(0, begin - warmup);
      SweepOptions piece = o;
      piece.speeds.assign(o.speeds.begin() + from, o.speeds.begin() + end);
      piece.warmup_speeds = begin - from;
      piece.series_speeds.clear(); // the whole sweep's nearest speeds, in the block that has them
      for (double w : o.series_speeds)
        if (const auto i = int(nearest(o.speeds, w)); i >= begin && i < end)
          piece.series_speeds.push_back(o.speeds[std::size_t(i)]);
      out.push_back(std::move(piece));
    }
  return out;
}

std::vector<std::vector<SweepPoint>>
run_sweeps(const std::vector<SweepTask> &tasks, unsigned threads, const std::string &progress)
{
  std::vector<std::vector<SweepPoint>> results(tasks.size());
  std::size_t                          speeds = 0;
  for (const SweepTask &t : tasks)
    speeds += t.options.speeds.size();
  std::optional<Progress> line;
  if (!progress.empty())
    line.emplace(progress, speeds);
  parallel_for(tasks.size(), threads, [&](std::size_t i) {
    PairVector   q = tasks[i].q, v = tasks[i].v;
    SweepOptions o = tasks[i].options;
    o.progress     = line ? &*line : nullptr;
    results[i]     = sweep(*tasks[i].model, q, v, o);
  });
  return results;
}
} // namespace gearkit

#include "driver/results_dynamics.h"

#include "base/types.h"

#include <cmath>
#include <limits>
#include <string>

namespace gearkit
{
namespace
{
std::vector<double>
column(const std::vector<SweepPoint> &p, double SweepPoint::*field)
{
  std::vector<double> v;
  for (const SweepPoint &x : p)
    v.push_back(x.*field);
  return v;
}

} // namespace

void
write_sweep(const H5Group &g, const std::vector<SweepPoint> &p)
{
  const hsize_t       n = p.size();
  std::vector<double> rpm, diverged_time;
  std::vector<int>    period, settled, diverged, steps, status;
  for (const SweepPoint &x : p)
    rpm.push_back(x.speed * 60 / (2 * pi)), period.push_back(x.period),
        settled.push_back(x.settled_cycles), diverged.push_back(x.diverged),
        steps.push_back(x.steps_per_cycle), diverged_time.push_back(x.diverged_time),
        status.push_back(x.diverged     ? 2
                         : x.period > 0 ? 0
                                        : 1);
  // a diverged speed has no results: zeros there, which `status` (or `diverged`) masks
  g.write("speed", rpm, {n});
  g.write("status", status, {n});
  g.write("dte_peak_to_peak", column(p, &SweepPoint::dte_pp), {n});
  g.write("dte_rms", column(p, &SweepPoint::dte_rms), {n});
  g.write("relative_peak_to_peak", column(p, &SweepPoint::relative_pp), {n});
  g.write("max_mesh_force", column(p, &SweepPoint::max_force), {n});
  g.write("dynamic_load_factor", column(p, &SweepPoint::load_factor), {n});
  g.write("contact_loss", column(p, &SweepPoint::contact_loss), {n});
  g.write("period", period, {n});
  g.write("settled_cycles", settled, {n});
  g.write("diverged", diverged, {n});
  g.write("diverged_time", diverged_time, {n});
  if (p.front().steps_per_cycle > 0) // Newmark
    {
      g.write("steps_per_cycle", steps, {n});
      g.write("error_estimate", column(p, &SweepPoint::error_estimate), {n});
    }

  // the DTE spectrum: every speed recorded the same whole periods
  const int           R    = p.front().record_cycles;
  const std::size_t   bins = p.front().spectrum.size();
  std::vector<double> spectrum, order;
  for (const SweepPoint &x : p)
    spectrum.insert(spectrum.end(), x.spectrum.begin(), x.spectrum.end());
  for (std::size_t k = 0; k < bins; ++k)
    order.push_back(double(k) / R);
  g.write("spectrum_order", order, {bins});
  g.write("dte_spectrum", spectrum, {n, bins});

  int k = 0;
  for (const SweepPoint &x : p)
    if (!x.series_time.empty())
      {
        const H5Group s = g.group("time_series").group(std::to_string(k++), "<k>");
        const hsize_t m = x.series_time.size();
        s.write("speed", x.speed * 60 / (2 * pi));
        s.write("time", x.series_time, {m});
        s.write("dte", x.series_dte, {m});
        s.write("transmission_error", x.series_transmission_error, {m});
        s.write("mesh_force", x.series_force, {m});
      }
}

std::vector<SweepPoint>
read_sweep(const H5Group &g)
{
  const std::vector<double> rpm = g.read_doubles("speed");
  const std::size_t         n   = rpm.size();
  std::vector<SweepPoint>   p(n);
  const bool                newmark = g.has("steps_per_cycle");
  const auto                ints    = [&](const char *name) { return g.read_ints(name); };
  const auto                doubles = [&](const char *name) { return g.read_doubles(name); };
  const std::vector<double> dte_pp = doubles("dte_peak_to_peak"), dte_rms = doubles("dte_rms"),
                            rel_pp = doubles("relative_peak_to_peak"),
                            force = doubles("max_mesh_force"), dlf = doubles("dynamic_load_factor"),
                            loss = doubles("contact_loss"), when = doubles("diverged_time");
  const std::vector<int> period = ints("period"), settled = ints("settled_cycles"),
                         diverged = ints("diverged");
  const std::vector<int>    steps = newmark ? ints("steps_per_cycle") : std::vector<int>(n, 0);
  const std::vector<double> error =
      newmark ? doubles("error_estimate")
              : std::vector<double>(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<hsize_t>      shape;
  const std::vector<double> spectrum = g.read_doubles("dte_spectrum", &shape);
  const std::vector<double> order    = doubles("spectrum_order");
  const std::size_t         bins     = shape.at(1);
  const int record = order.size() > 1 && order[1] > 0 ? int(std::lround(1 / order[1])) : 0;
  for (std::size_t i = 0; i < n; ++i)
    {
      SweepPoint &x     = p[i];
      x.speed           = rpm[i] * 2 * pi / 60;
      x.dte_pp          = dte_pp[i];
      x.dte_rms         = dte_rms[i];
      x.relative_pp     = rel_pp[i];
      x.max_force       = force[i];
      x.load_factor     = dlf[i];
      x.contact_loss    = loss[i];
      x.period          = period[i];
      x.settled_cycles  = settled[i];
      x.diverged        = diverged[i] != 0;
      x.diverged_time   = when[i];
      x.steps_per_cycle = steps[i];
      x.error_estimate  = error[i];
      x.record_cycles   = record;
      x.spectrum.assign(spectrum.begin() + long(i * bins), spectrum.begin() + long((i + 1) * bins));
    }
  if (g.has("time_series"))
    {
      const H5Group series = g.group("time_series");
      for (const std::string &k : series.children())
        {
          const H5Group s       = series.group(k, "<k>");
          const double  speed   = s.read_double("speed");
          std::size_t   nearest = 0;
          for (std::size_t i = 1; i < n; ++i)
            if (std::abs(rpm[i] - speed) < std::abs(rpm[nearest] - speed))
              nearest = i;
          SweepPoint &x               = p.at(nearest);
          x.series_time               = s.read_doubles("time");
          x.series_dte                = s.read_doubles("dte");
          x.series_transmission_error = s.read_doubles("transmission_error");
          x.series_force              = s.read_doubles("mesh_force");
        }
    }
  return p;
}
} // namespace gearkit

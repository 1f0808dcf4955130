#include "base/decimator.h"

#include "base/types.h"

#include <array>
#include <cmath>

namespace gearkit
{
AntiAliasFilter
AntiAliasFilter::design(int factor, double pass, double attenuation)
{
  require_value(factor >= 2 && factor <= 64, "Anti-alias filter", "averages per output interval",
                double(factor), "in [2, 64]");
  require_value(pass > 0 && pass < 0.5, "Anti-alias filter", "passband edge [output rate]", pass,
                "in (0, 0.5)");
  require_value(attenuation >= 21 && attenuation <= 150, "Anti-alias filter",
                "stopband attenuation [dB]", attenuation, "in [21, 150]");
  AntiAliasFilter f;
  f.factor = factor, f.pass = pass, f.attenuation = attenuation;
  // Kaiser: length from the transition width (normalised to the fine rate) and attenuation
  const double width = (0.5 - pass) / factor;
  long         N     = long(std::ceil((attenuation - 7.95) / (14.36 * width))) + 1;
  N += N % 2; // even: the output times lie midway between two fine averages' centres
  const double beta   = attenuation > 50 ? 0.1102 * (attenuation - 8.7)
                        : attenuation > 21
                            ? 0.5842 * std::pow(attenuation - 21, 0.4) + 0.07886 * (attenuation - 21)
                            : 0.0;
  const double cutoff = (pass + 0.5) / 2 / factor; // cycles per fine interval
  const double centre = double(N - 1) / 2;
  f.taps.resize(std::size_t(N));
  double sum = 0;
  for (long m = 0; m < N; ++m)
    {
      const double x      = double(m) - centre;
      const double r      = 2 * double(m) / double(N - 1) - 1;
      const double window = std::cyl_bessel_i(0.0, beta * std::sqrt(std::max(0.0, 1 - r * r))) /
                            std::cyl_bessel_i(0.0, beta);
      const double a         = 2 * pi * cutoff * x;
      f.taps[std::size_t(m)] = window * 2 * cutoff * std::sin(a) / a;
      sum += f.taps[std::size_t(m)];
    }
  for (double &h : f.taps)
    h /= sum;
  return f;
}

double
AntiAliasFilter::response(double frequency) const
{
  const double x      = frequency / factor; // cycles per fine interval
  const double box    = x == 0 ? 1.0 : std::pow(std::sin(pi * x) / (pi * x), 3);
  const double centre = double(taps.size() - 1) / 2;
  double       H      = 0;
  for (std::size_t m = 0; m < taps.size(); ++m)
    H += taps[m] * std::cos(2 * pi * x * (double(m) - centre));
  return box * H;
}

Decimator::Decimator(AntiAliasFilter filter, std::size_t channels)
    : f(std::move(filter))
    , channels(channels)
    , half(long(f.taps.size() / 2))
    , first(channels, 0.0)
    , last(channels, 0.0)
    , kept(channels)
    , out(channels)
{
  require_value(channels >= 1, "Decimator", "channels", double(channels), ">= 1");
}

void
Decimator::start(const double *values)
{
  first.assign(values, values + channels);
}

void
Decimator::push(const double *averages)
{
  for (std::size_t c = 0; c < channels; ++c)
    kept[c].push_back(averages[c]);
  ++pushed;
  emit(false);
}

void
Decimator::finish(const double *values)
{
  require_value(pushed > 0 && pushed % std::size_t(f.factor) == 0, "Decimator",
                "fine intervals at the end", double(pushed),
                "a whole positive number of output intervals");
  last.assign(values, values + channels);
  end = long(pushed);
  emit(true);
}

double
Decimator::fine(std::size_t c, long j) const
{
  if (j < 1)
    return 2 * first[c] - fine(c, 1 - j);
  if (end > 0 && j > end)
    return 2 * last[c] - fine(c, 2 * end + 1 - j);
  return kept[c][std::size_t(j - base)];
}

void
Decimator::emit(bool at_end)
{
  const long R = f.factor;
  for (long k = long(out[0].size());; ++k)
    {
      if (at_end ? k * R > end : k * R + half > long(pushed))
        break;
      const long j0       = k * R - half + 1; // the first fine average of output k
      const bool interior = j0 >= 1 && (end < 0 || j0 + 2 * half - 1 <= end);
      for (std::size_t c = 0; c < channels; ++c)
        {
          double y = 0;
          if (interior)
            {
              const double *x = kept[c].data() + (j0 - base);
              for (std::size_t m = 0; m < f.taps.size(); ++m)
                y += f.taps[m] * x[m];
            }
          else
            for (std::size_t m = 0; m < f.taps.size(); ++m)
              y += f.taps[m] * fine(c, j0 + long(m));
          out[c].push_back(y);
        }
    }
  // forget the averages no later output needs (the start's reflection needs the first `half`)
  const long needed = long(out[0].size()) * R - half + 1;
  if (!at_end && needed > half && needed - base > 8 * half)
    {
      for (std::vector<double> &k : kept)
        k.erase(k.begin(), k.begin() + (needed - base));
      base = needed;
    }
}

AntiAliasRecorder::AntiAliasRecorder(double rate, long outputs, std::size_t channels,
                                     AntiAliasFilter filter)
    : width(channels)
    , fine_rate(rate * filter.factor)
    , last_interval(outputs * filter.factor)
    , decimator(std::move(filter), channels)
    , a(channels, 0.0)
    , b(channels, 0.0)
    , c(channels, 0.0)
    , before(channels, 0.0)
    , own(channels, 0.0)
    , own_right(channels, 0.0)
    , start_values(channels, 0.0)
    , values(channels, 0.0)
    , fine(channels, 0.0)
{
  require_value(rate > 0 && std::isfinite(rate), "Anti-alias recorder", "output rate [1/s]", rate,
                "> 0");
  require_value(outputs >= 1, "Anti-alias recorder", "output intervals", double(outputs), ">= 1");
}

void
AntiAliasRecorder::advance(double from, double to, const Signal &signal)
{
  if (finished)
    return;
  if (!started)
    {
      signal(0.0, start_values.data());
      decimator.start(start_values.data());
      started = true;
    }
  // three-point Gauss-Legendre on [0, 1]: exact for the spline weight (degree 2) times a
  // signal of degree 3 (an integrator's polynomial of higher degree over a fine interval: to
  // its 6th derivative)
  static const std::array<double, 3> node{0.5 - 0.5 * std::sqrt(0.6), 0.5,
                                          0.5 + 0.5 * std::sqrt(0.6)};
  static const std::array<double, 3> weight{5.0 / 18, 8.0 / 18, 5.0 / 18};
  const double                       end = double(last_interval) / fine_rate;
  to = to >= end * (1 - 1e-13) ? end : to; // the end, up to the rounding of the caller's times
  while (from < to)
    {
      const double left  = double(interval - 1) / fine_rate;
      const double right = double(interval) / fine_rate;
      const double upto  = std::min(to, right);
      const double h     = upto - from;
      for (int g = 0; g < 3; ++g)
        {
          const double t = from + h * node[std::size_t(g)];
          const double u = (t - left) * fine_rate;
          signal(t, values.data());
          const double w = h * weight[std::size_t(g)];
          for (std::size_t k = 0; k < width; ++k)
            {
              a[k] += w * (1 - u) * (1 - u) / 2 * values[k];
              b[k] += w * (0.75 - (u - 0.5) * (u - 0.5)) * values[k];
              c[k] += w * u * u / 2 * values[k];
            }
        }
      from = upto;
      if (upto >= right)
        close_interval(signal);
      if (finished)
        return;
    }
}

void
AntiAliasRecorder::close_interval(const Signal &signal)
{
  // the fine value of interval j: (C_{j-1} + B_j + A_{j+1}) / dt, the quadratic B-spline
  // (pieces u^2/2, 3/4 - (u - 1/2)^2, (1 - u)^2/2 over three intervals) centred on it;
  // before t = 0 the reflected signal's C_0 = G(0) dt / 3 - A_1, after the end A = G dt / 3 - C
  const double dt = 1 / fine_rate;
  for (std::size_t k = 0; k < width; ++k)
    {
      if (interval == 1)
        before[k] = start_values[k] * dt / 3 - a[k];
      else
        fine[k] = (before[k] + own[k] + a[k]) * fine_rate;
    }
  if (interval > 1)
    decimator.push(fine.data());
  for (std::size_t k = 0; k < width; ++k)
    {
      if (interval > 1)
        before[k] = own_right[k];
      own[k] = b[k], own_right[k] = c[k];
      a[k] = b[k] = c[k] = 0;
    }
  if (interval == last_interval) // the piece reaches the end: its point values close the record
    {
      signal(double(last_interval) / fine_rate, values.data());
      for (std::size_t k = 0; k < width; ++k)
        fine[k] = (before[k] + own[k] + values[k] * dt / 3 - own_right[k]) * fine_rate;
      decimator.push(fine.data());
      decimator.finish(values.data());
      finished = true;
      return;
    }
  ++interval;
}
} // namespace gearkit

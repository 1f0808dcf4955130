// Output without aliasing: a signal known continuously (an integrator's solution: its
// interpolating polynomial) is averaged with quadratic B-spline weights around R fine points
// per output interval and decimated by R through a linear-phase low-pass filter (a
// Kaiser-windowed sinc), so that nothing above the output's Nyquist frequency folds back into
// the output's spectrum:
//   * the B-spline averages (exact integrals of the signal's polynomial pieces, by Gauss) filter
//     by sinc^3(f / (R f_s)) before the fine points sample: what folds onto the fine points
//     (near multiples of R f_s) is attenuated by that, >= 70 dB for R = 8;
//   * the FIR keeps [0, pass f_s] flat and attenuates [f_s / 2, R f_s / 2] by at least the
//     stopband attenuation: no line above the output Nyquist frequency folds back above
//     -attenuation; (pass f_s, f_s / 2) is the transition band (true content, attenuated).
// Both are symmetric about each output time (no delay); at the record's ends the signal is
// continued by point reflection about its value there (x(-t) = 2 x(0) - x(t)), which keeps
// constants and straight lines (a shaft's angle at constant speed) exact, and gives the point
// values at the two ends.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace gearkit
{
struct AntiAliasFilter
{
  int    factor      = 8;   ///< R: averaging intervals per output interval
  double pass        = 0.4; ///< passband edge, times the output rate
  double attenuation = 70;  ///< stopband attenuation from the output Nyquist frequency on [dB]
  std::vector<double> taps; ///< FIR at R times the output rate, even length, sum 1
  /// The Kaiser-window design for these settings (Kaiser's formulas for the length and beta).
  static AntiAliasFilter
  design(int factor = 8, double pass = 0.4, double attenuation = 70);
  /// H(f) of the whole chain (B-spline average, then the FIR) at frequency f, a multiple of
  /// the output rate (real: the chain has no phase): within 1.3 % of 1 in the passband
  /// (the average's droop sinc^3(pass / R)), at most 10^(-attenuation / 20) from 0.5 on.
  double
  response(double f) const;
};

/// Decimates several channels together. Feed the point values at t = 0 (start), then the
/// channels' fine values (averages centred at (j - 1/2) dt, dt = 1 / (R f_s)), in order (push),
/// then the point values at the end (finish), which must fall on an output time (a whole number
/// of output intervals pushed). output(c) holds channel c at the output times 0, 1/f_s, ...
class Decimator
{
public:
  Decimator(AntiAliasFilter filter, std::size_t channels);
  void
  start(const double *values);
  void
  push(const double *averages);
  void
  finish(const double *values);
  const std::vector<double> &
  output(std::size_t channel) const
  {
    return out[channel];
  }
  std::vector<double> &
  output(std::size_t channel)
  {
    return out[channel];
  }
  std::size_t
  intervals() const
  {
    return pushed;
  }
  const AntiAliasFilter &
  filter() const
  {
    return f;
  }

private:
  /// The fine average j (1-based) of channel c, reflected about the start or the end point.
  double
  fine(std::size_t c, long j) const;
  /// Computes the outputs whose taps are all known (or all, at the end).
  void
                                   emit(bool at_end);
  AntiAliasFilter                  f;
  std::size_t                      channels;
  long                             half;        ///< taps / 2
  std::vector<double>              first, last; ///< point values at the ends
  std::vector<std::vector<double>> kept;        ///< per channel: fine averages from `base` on
  long                             base   = 1;  ///< index of kept[c][0]
  std::size_t                      pushed = 0;  ///< fine averages so far
  long                             end    = -1; ///< the last fine index (at finish)
  std::vector<std::vector<double>> out;
};

/// Records channels of a continuous signal without aliasing at `rate` samples per second over
/// [0, outputs / rate]: feed the signal piece by piece as the integrator steps (advance, with
/// a function giving the channels at any time of the piece); the outputs are complete once a
/// piece reaches the end (done()).
class AntiAliasRecorder
{
public:
  using Signal = std::function<void(double t, double *values)>;
  AntiAliasRecorder(double rate, long outputs, std::size_t channels,
                    AntiAliasFilter filter = AntiAliasFilter::design());
  /// The signal on [a, b] (a: where the last piece ended; 0 for the first), evaluated at most
  /// at a few points of every fine interval the piece overlaps, and at the end time.
  void
  advance(double a, double b, const Signal &signal);
  bool
  done() const
  {
    return finished;
  }
  std::size_t
  channels() const
  {
    return width;
  }
  /// Channel c at the output times k / rate, k = 0 .. outputs (once done).
  const std::vector<double> &
  output(std::size_t c) const
  {
    return decimator.output(c);
  }
  std::vector<double> &
  output(std::size_t c)
  {
    return decimator.output(c);
  }
  const AntiAliasFilter &
  filter() const
  {
    return decimator.filter();
  }

private:
  /// Interval i (1-based) complete: its B-spline moments make the fine value of interval i - 1.
  void
              close_interval(const Signal &signal);
  std::size_t width;
  double      fine_rate;     ///< R rate
  long        last_interval; ///< R outputs
  Decimator   decimator;
  long        interval = 1; ///< the open fine interval [(i - 1) dt, i dt]
  bool        started = false, finished = false;
  /// per channel: the open interval's moments (left, middle, right spline pieces) and the
  /// pending fine value's parts: C of the interval before it, B of its own, C of its own
  std::vector<double> a, b, c, before, own, own_right, start_values, values, fine;
};
} // namespace gearkit

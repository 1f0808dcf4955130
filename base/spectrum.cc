#include "base/spectrum.h"

#include "base/types.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <mutex>

namespace gearkit
{
std::vector<std::complex<double>>
fourier_coefficients(const std::vector<double> &samples)
{
  const int n = int(samples.size());
  if (n < 2)
    throw InputError("a spectrum needs at least two samples");
  static std::mutex                 planner; // FFTW's planner is not thread-safe
  std::vector<double>               in(samples);
  std::vector<std::complex<double>> out(std::size_t(n / 2 + 1));
  fftw_plan                         plan;
  {
    const std::lock_guard<std::mutex> lock(planner);
    plan = fftw_plan_dft_r2c_1d(n, in.data(), reinterpret_cast<fftw_complex *>(out.data()),
                                FFTW_ESTIMATE);
  }
  fftw_execute(plan);
  {
    const std::lock_guard<std::mutex> lock(planner);
    fftw_destroy_plan(plan);
  }
  for (int k = 0; k <= n / 2; ++k)
    out[std::size_t(k)] *= (k == 0 || 2 * k == n) ? 1.0 / n : 2.0 / n;
  return out;
}

std::vector<double>
amplitude_spectrum(const std::vector<double> &samples, int max_bin)
{
  if (max_bin < 0)
    throw InputError("a spectrum needs a highest bin >= 0");
  const std::vector<std::complex<double>> c = fourier_coefficients(samples);
  std::vector<double>                     amplitude(std::size_t(max_bin) + 1, 0.0);
  for (std::size_t k = 0; k < std::min(amplitude.size(), c.size()); ++k)
    amplitude[k] = std::abs(c[k]);
  return amplitude;
}

std::vector<double>
mesh_order_amplitudes(const std::vector<double> &samples, int cycles, int max_order)
{
  if (samples.size() < 2 || cycles < 1)
    throw InputError("harmonics need at least two samples over at least one mesh cycle");
  const std::vector<double> bins = amplitude_spectrum(samples, max_order * cycles);
  std::vector<double>       amplitude(std::size_t(max_order) + 1);
  for (int m = 0; m <= max_order; ++m)
    amplitude[std::size_t(m)] = bins[std::size_t(m * cycles)];
  return amplitude;
}
} // namespace gearkit

namespace gearkit
{
namespace
{
std::vector<double>
window_weights(Window w, std::size_t n)
{
  std::vector<double> x(n, 1.0);
  if (w == Window::rectangular)
    return x;
  const double a0 = w == Window::hann ? 0.5 : 25.0 / 46.0;
  for (std::size_t i = 0; i < n; ++i)
    x[i] = a0 - (1 - a0) * std::cos(2 * pi * double(i) / double(n)); // periodic form
  return x;
}

/// Amplitudes of bins 0..n/2 of a windowed record (mean removed), coherent gain divided out.
std::vector<double>
windowed_amplitudes(const double *samples, std::size_t n, const std::vector<double> &w)
{
  double mean = 0, gain = 0;
  for (std::size_t i = 0; i < n; ++i)
    mean += samples[i], gain += w[i];
  mean /= double(n);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i)
    x[i] = (samples[i] - mean) * w[i];
  std::vector<double> a = amplitude_spectrum(x, int(n / 2));
  for (double &v : a)
    v *= double(n) / gain;
  return a;
}
} // namespace

FrequencySpectrum
frequency_spectrum(const std::vector<double> &samples, double sample_rate, Window window)
{
  require_value(samples.size() >= 4, "spectrum", "samples", double(samples.size()), ">= 4");
  require_value(sample_rate > 0, "spectrum", "sample rate [1/s]", sample_rate, "> 0");
  FrequencySpectrum s;
  s.window     = window;
  s.resolution = sample_rate / double(samples.size());
  s.amplitude =
      windowed_amplitudes(samples.data(), samples.size(), window_weights(window, samples.size()));
  return s;
}

SpectralLine
spectral_peak(const FrequencySpectrum &s, double low, double high)
{
  const std::size_t n  = s.amplitude.size();
  std::size_t       lo = std::size_t(std::max(1.0, std::ceil(low / s.resolution)));
  std::size_t       hi = std::min(n - 2, std::size_t(std::floor(high / s.resolution)));
  require_value(lo <= hi, "spectral peak", "band [Hz]", high, "a band that holds a bin");
  std::size_t k = lo;
  for (std::size_t i = lo; i <= hi; ++i)
    if (s.amplitude[i] > s.amplitude[k])
      k = i;
  const double a = s.amplitude[k - 1], b = s.amplitude[k], c = s.amplitude[k + 1];
  double       delta = 0;
  if (s.window == Window::hann && b > 0)
    // a lone sinusoid's Hann main lobe: the neighbours' ratio gives the offset exactly (a band
    // of zeros, a silent signal, has no line: the bin itself)
    delta = c > a ? (2 * c - b) / (b + c) : -(2 * a - b) / (a + b);
  else if (a > 0 && b > 0 && c > 0)
    {
      const double la = std::log(a), lb = std::log(b), lc = std::log(c);
      delta = 0.5 * (la - lc) / (la - 2 * lb + lc);
    }
  delta = std::clamp(delta, -0.5, 0.5);
  SpectralLine line;
  line.frequency = (double(k) + delta) * s.resolution;
  line.amplitude = b;
  if (s.window == Window::hann && std::abs(delta) > 0)
    {
      // the Hann lobe's amplitude at offset delta: sinc(delta) / (1 - delta^2)
      const double x = pi * delta;
      line.amplitude = b * (1 - delta * delta) * x / std::sin(x);
    }
  return line;
}

ExpectedLine
spectral_line_near(const FrequencySpectrum &s, double frequency, double half_width,
                   double prominence)
{
  require_value(half_width >= s.resolution, "spectral line", "half width [Hz]", half_width,
                "at least the resolution " + std::to_string(s.resolution) + " Hz");
  require_value(frequency - half_width > s.resolution &&
                    (frequency + half_width) / s.resolution < double(s.amplitude.size()) - 2,
                "spectral line", "frequency [Hz]", frequency,
                "a band inside the spectrum (above its first bin, below its last)");
  ExpectedLine e;
  e.expected = frequency;
  e.line     = spectral_peak(s, frequency - half_width, frequency + half_width);
  // the bin spectral_peak took, and the band's first and last bins
  const std::size_t lo = std::size_t(std::ceil((frequency - half_width) / s.resolution));
  const std::size_t hi = std::size_t(std::floor((frequency + half_width) / s.resolution));
  std::size_t       k  = lo;
  for (std::size_t i = lo; i <= hi; ++i)
    if (s.amplitude[i] > s.amplitude[k])
      k = i;
  const double        reach = 10 * half_width / s.resolution;
  const std::size_t   a     = std::size_t(std::max(1.0, double(k) - reach));
  const std::size_t   b     = std::min(s.amplitude.size() - 1, std::size_t(double(k) + reach));
  std::vector<double> near(s.amplitude.begin() + long(a), s.amplitude.begin() + long(b) + 1);
  std::nth_element(near.begin(), near.begin() + long(near.size() / 2), near.end());
  e.floor = near[near.size() / 2];
  e.found = k > lo && k < hi && s.amplitude[k] > s.amplitude[k - 1] &&
            s.amplitude[k] >= s.amplitude[k + 1] && s.amplitude[k] >= prominence * e.floor;
  return e;
}

Spectrogram
spectrogram(const std::vector<double> &samples, double sample_rate, double window_seconds,
            double overlap, Window window, double max_frequency)
{
  require_value(sample_rate > 0, "spectrogram", "sample rate [1/s]", sample_rate, "> 0");
  require_value(overlap >= 0 && overlap < 1, "spectrogram", "overlap", overlap, "in [0, 1)");
  const std::size_t n = std::size_t(std::lround(window_seconds * sample_rate));
  require_value(n >= 4 && n <= samples.size(), "spectrogram", "window [s]", window_seconds,
                "at least 4 samples and at most the record");
  const std::size_t hop =
      std::max<std::size_t>(1, std::size_t(std::lround(double(n) * (1 - overlap))));
  const std::vector<double> w  = window_weights(window, n);
  const double              df = sample_rate / double(n);
  const std::size_t         bins =
      max_frequency > 0 ? std::min(n / 2 + 1, std::size_t(max_frequency / df) + 1) : n / 2 + 1;
  Spectrogram s;
  for (std::size_t j = 0; j < bins; ++j)
    s.frequency.push_back(df * double(j));
  for (std::size_t start = 0; start + n <= samples.size(); start += hop)
    {
      s.time.push_back((double(start) + double(n) / 2) / sample_rate);
      const std::vector<double> a = windowed_amplitudes(samples.data() + start, n, w);
      s.amplitude.insert(s.amplitude.end(), a.begin(), a.begin() + long(bins));
    }
  return s;
}
} // namespace gearkit

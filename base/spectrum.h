// Amplitude spectra (FFTW): mesh-order harmonics of a transmission error sampled uniformly over
// whole mesh cycles; windowed spectra of time signals in hertz with interpolated line
// frequencies; short-time spectra (spectrograms) for run-ups.
#pragma once

#include <complex>
#include <vector>

namespace gearkit
{
/// Single-sided Fourier coefficients c_0 .. c_{n/2} of n >= 2 uniformly spaced samples over one
/// period: x_j = Re sum_k c_k exp(2 pi i k j / n) (c_0 the mean; |c_k| the amplitude of the
/// sinusoid with k periods over the record). Thread-safe like amplitude_spectrum.
std::vector<std::complex<double>>
fourier_coefficients(const std::vector<double> &samples);

/// Single-sided amplitude spectrum (same unit as the signal) of uniformly spaced `samples`,
/// bins 0..max_bin (bin k: k periods over the whole record; 0 is the mean). Bins above the
/// Nyquist limit are reported as 0. Safe to call from several threads (FFTW's planner is
/// serialised).
std::vector<double>
amplitude_spectrum(const std::vector<double> &samples, int max_bin);

/// Amplitudes of mesh orders 0..max_order of `samples`, which cover exactly `cycles` mesh cycles
/// with uniform spacing (the last sample is the one before the first of the next cycle). Order
/// 0 is the mean; order m > 0 the amplitude of the sinusoid with m periods per mesh cycle.
/// Orders above the Nyquist limit are reported as 0.
std::vector<double>
mesh_order_amplitudes(const std::vector<double> &samples, int cycles, int max_order);

enum class Window
{
  rectangular,
  hann,
  hamming
};

/// A single-sided amplitude spectrum in hertz: a sinusoid of amplitude A at a bin's frequency
/// shows A there (the window's coherent gain is divided out).
struct FrequencySpectrum
{
  double              resolution = 0; ///< bin spacing [Hz] (sample rate / samples)
  std::vector<double> amplitude;      ///< bins 0 .. n/2 (signal unit)
  Window              window = Window::hann;
  double
  frequency(std::size_t bin) const
  {
    return resolution * double(bin);
  }
};

/// The windowed spectrum of samples at a sample rate [1/s] (the mean removed first).
FrequencySpectrum
frequency_spectrum(const std::vector<double> &samples, double sample_rate,
                   Window window = Window::hann);

/// The largest line in [low, high] Hz: its frequency, interpolated between bins from the
/// window's shape (Hann: exact for a lone sinusoid; others: parabolic on the log amplitude),
/// and its amplitude.
struct SpectralLine
{
  double frequency = 0, amplitude = 0;
};
SpectralLine
spectral_peak(const FrequencySpectrum &spectrum, double low, double high);

/// A line looked for at an expected frequency (a mesh frequency, its harmonics and sidebands):
/// the largest bin within half_width [Hz] of it, interpolated as spectral_peak. It counts as
/// found when that bin is a local maximum strictly inside the band (a bin on the band's edge is
/// the skirt of a line outside it) and stands at least `prominence` times above the local floor,
/// the median amplitude of the bins within 10 half-widths.
struct ExpectedLine
{
  double       expected = 0; ///< [Hz]
  SpectralLine line;         ///< the largest bin of the band, interpolated
  double       floor = 0;    ///< median amplitude nearby (signal unit)
  bool         found = false;
};
ExpectedLine
spectral_line_near(const FrequencySpectrum &spectrum, double frequency, double half_width,
                   double prominence = 4);

/// Short-time spectra: windows of `window_seconds`, each `overlap` (in [0, 1)) shared with the
/// next, up to max_frequency (0: the Nyquist frequency).
struct Spectrogram
{
  std::vector<double> time;      ///< window centres [s]
  std::vector<double> frequency; ///< [Hz]
  /// amplitude[i * frequency.size() + j]: window i, frequency j (signal unit)
  std::vector<double> amplitude;
};
Spectrogram
spectrogram(const std::vector<double> &samples, double sample_rate, double window_seconds,
            double overlap, Window window = Window::hamming, double max_frequency = 0);
} // namespace gearkit

// Mesh-order amplitudes against a signal built from known harmonics.
#include "base/spectrum.h"
#include "base/types.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

TEST(Harmonics, RecoversKnownMeshOrders)
{
  // 3 mesh cycles x 64 samples: mean 2, order 1 amplitude 5 (phase 0.3), order 3 amplitude 0.7.
  // The DFT of a sampled sinusoid at an exact bin is exact up to rounding (~1e-15 here).
  const int           cycles = 3, per_cycle = 64, n = cycles * per_cycle;
  std::vector<double> s(n);
  for (int i = 0; i < n; ++i)
    {
      const double x = 2 * pi * double(i) / per_cycle; // mesh phase
      s[i]           = 2 + 5 * std::cos(x + 0.3) + 0.7 * std::sin(3 * x);
    }
  const std::vector<double> a = mesh_order_amplitudes(s, cycles, 5);
  EXPECT_NEAR(a[0], 2, 1e-13);
  EXPECT_NEAR(a[1], 5, 1e-13);
  EXPECT_NEAR(a[2], 0, 1e-13);
  EXPECT_NEAR(a[3], 0.7, 1e-13);
  EXPECT_NEAR(a[4], 0, 1e-13);
  EXPECT_THROW(mesh_order_amplitudes({1.0}, 1, 2), InputError);
}

TEST(Harmonics, FourierCoefficientsCarryThePhase)
{
  // x_j = Re sum c_k exp(2 pi i k j / n): 2 + 5 cos(x + 0.3) + 0.7 sin(3 x) -> c_0 = 2,
  // c_1 = 5 exp(0.3 i), c_3 = 0.7 exp(-i pi / 2); the Nyquist bin holds its cosine
  const int           n = 64;
  std::vector<double> s(n);
  for (int j = 0; j < n; ++j)
    {
      const double x = 2 * pi * j / n;
      s[j]           = 2 + 5 * std::cos(x + 0.3) + 0.7 * std::sin(3 * x) + 0.2 * std::cos(32 * x);
    }
  const auto c = fourier_coefficients(s);
  ASSERT_EQ(c.size(), 33u);
  EXPECT_NEAR(std::abs(c[0] - 2.0), 0, 1e-13);
  EXPECT_NEAR(std::abs(c[1] - std::polar(5.0, 0.3)), 0, 1e-13);
  EXPECT_NEAR(std::abs(c[3] - std::polar(0.7, -pi / 2)), 0, 1e-13);
  EXPECT_NEAR(std::abs(c[32] - 0.2), 0, 1e-13);
  for (int k : {2, 4, 5, 31})
    EXPECT_NEAR(std::abs(c[std::size_t(k)]), 0, 1e-13);
}

TEST(FrequencySpectrum, HannInterpolationFindsALineBetweenBins)
{
  // 453.19 Hz (GMF1 of seed 002) with sidebands at +-1.993 Hz, 4 s at 20 kHz
  const double        fs = 20e3, f = 453.19, fm = 1.993;
  std::vector<double> x(80000);
  for (std::size_t i = 0; i < x.size(); ++i)
    {
      const double t = double(i) / fs;
      x[i] = 3 + 500 * std::sin(2 * pi * f * t + 0.3) + 40 * std::cos(2 * pi * (f + fm) * t) +
             40 * std::cos(2 * pi * (f - fm) * t);
    }
  const FrequencySpectrum s = frequency_spectrum(x, fs);
  EXPECT_DOUBLE_EQ(s.resolution, 0.25);
  const SpectralLine gmf = spectral_peak(s, 440, 460);
  EXPECT_NEAR(gmf.frequency, f, 1e-4 * f); // well within 0.1 %
  EXPECT_NEAR(gmf.amplitude, 500, 0.02 * 500);
  const SpectralLine upper = spectral_peak(s, f + 1, f + 3);
  EXPECT_NEAR(upper.frequency, f + fm, 1e-3 * (f + fm));
  EXPECT_NEAR(upper.amplitude, 40, 0.1 * 40);
  // the mean (3) is removed; what is left at 0 Hz is leakage of the lines
  EXPECT_LT(s.amplitude[0], 0.1);
}

TEST(Spectrogram, FollowsARisingTone)
{
  // f(t) = 100 + 200 t Hz over 2 s; 50 ms Hamming windows, 80 % overlap
  const double        fs = 10e3;
  std::vector<double> x(20000);
  for (std::size_t i = 0; i < x.size(); ++i)
    {
      const double t = double(i) / fs;
      x[i]           = std::sin(2 * pi * (100 * t + 100 * t * t));
    }
  const Spectrogram s = spectrogram(x, fs, 0.05, 0.8, Window::hamming, 1000);
  ASSERT_GT(s.time.size(), 150u);
  EXPECT_NEAR(s.time[1] - s.time[0], 0.01, 1e-12);
  EXPECT_NEAR(s.frequency[1], 20, 1e-12);
  const std::size_t nf = s.frequency.size();
  for (std::size_t i = 0; i < s.time.size(); i += 20)
    {
      std::size_t k = 0;
      for (std::size_t j = 0; j < nf; ++j)
        if (s.amplitude[i * nf + j] > s.amplitude[i * nf + k])
          k = j;
      EXPECT_NEAR(s.frequency[k], 100 + 200 * s.time[i], 20) << "window at " << s.time[i] << " s";
      EXPECT_NEAR(s.amplitude[i * nf + k], 1.0, 0.25);
    }
}

// Expected lines: a carrier at GMF1 with sidebands 30 dB down at +-1.993 Hz and a little
// noise are found where they are; where there is nothing (+-5 Hz) the band's largest bin is
// noise (not prominent) or the carrier's skirt (on the band's edge) and is not found.
TEST(FrequencySpectrum, ExpectedLinesFoundOnlyWhereThereAreLines)
{
  const double        fs = 20e3, f = 453.19, fm = 1.993;
  std::vector<double> x(60000); // 3 s: 1/3 Hz bins, the Hann main lobe +-2/3 Hz
  unsigned            seed = 7;
  for (std::size_t i = 0; i < x.size(); ++i)
    {
      const double t     = double(i) / fs;
      seed               = seed * 1103515245u + 12345u;
      const double noise = (double((seed >> 8) & 0xffff) / 65535.0 - 0.5) * 2.0;
      x[i]               = 500 * std::sin(2 * pi * f * t) + 16 * std::cos(2 * pi * (f + fm) * t) +
             16 * std::cos(2 * pi * (f - fm) * t) + noise;
    }
  const FrequencySpectrum s = frequency_spectrum(x, fs);
  for (double g : {f, f + fm, f - fm})
    {
      const ExpectedLine e = spectral_line_near(s, g, fm / 2);
      EXPECT_TRUE(e.found) << g;
      EXPECT_NEAR(e.line.frequency, g, 1e-3 * g) << g; // 0.1 %
      EXPECT_EQ(e.expected, g);
    }
  EXPECT_NEAR(spectral_line_near(s, f, fm / 2).line.amplitude, 500, 10);
  EXPECT_NEAR(spectral_line_near(s, f + fm, fm / 2).line.amplitude, 16, 1);
  for (double g : {f + 2.5 * fm, f - 2.5 * fm, 300.0})
    EXPECT_FALSE(spectral_line_near(s, g, fm / 2).found) << g;
  // a band wider than the distance to the carrier ends on its skirt: the edge is no line
  EXPECT_FALSE(spectral_line_near(s, f + 1.0, 0.4).found);
  EXPECT_THROW(spectral_line_near(s, f, 0.1), InputError);  // narrower than a bin
  EXPECT_THROW(spectral_line_near(s, 9999, 5), InputError); // beyond the spectrum

  // a silent signal (a mesh apart over the whole window) has no line, and no NaN either
  const FrequencySpectrum silent = frequency_spectrum(std::vector<double>(x.size(), 0.0), fs);
  const ExpectedLine      none   = spectral_line_near(silent, f, fm / 2);
  EXPECT_FALSE(none.found);
  EXPECT_TRUE(std::isfinite(none.line.frequency));
  EXPECT_EQ(none.line.amplitude, 0.0);
}

// The anti-alias decimator against exact solutions: the averages of a sinusoid over the fine
// intervals are known in closed form, so every interior output must be the sinusoid scaled by
// the chain's response (the filter is symmetric: no phase), a straight line passes unchanged
// (ends included), and the designed response keeps its passband and stopband.
#include "base/decimator.h"
#include "base/types.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace gearkit;

namespace
{
/// Records x(t) over `outputs` output intervals at output rate 1, fed in pieces as an
/// integrator would step: irregular, and at most 1/20 of the signal's period.
std::vector<std::vector<double>>
record(const std::function<void(double, double *)> &x, std::size_t channels, long outputs,
       double frequency)
{
  AntiAliasRecorder r(1.0, outputs, channels);
  double            t = 0;
  for (int k = 0; !r.done(); ++k)
    {
      const double h = std::min(0.05 / frequency, 0.013 * (1 + 0.7 * std::sin(1.3 * k)));
      r.advance(t, t + h, x);
      t += h;
    }
  std::vector<std::vector<double>> out;
  for (std::size_t c = 0; c < channels; ++c)
    out.push_back(r.output(c));
  return out;
}
} // namespace

TEST(AntiAliasFilter, PassbandFlatStopbandBelowItsAttenuation)
{
  const AntiAliasFilter f   = AntiAliasFilter::design();
  double                low = 1, high = 0, stop = 0;
  for (int i = 0; i <= 4000; ++i)
    {
      const double pass = f.pass * i / 4000;
      low               = std::min(low, std::abs(f.response(pass)));
      high              = std::max(high, f.response(pass));
    }
  for (int i = 0; i <= 200000; ++i) // up to 4 times the fine grid's Nyquist frequency
    stop = std::max(stop, std::abs(f.response(0.5 + (4.0 * f.factor - 0.5) * i / 200000)));
  std::printf("%zu taps; passband %.5f .. %.5f; stopband %.1f dB\n", f.taps.size(), low, high,
              20 * std::log10(stop));
  EXPECT_GT(low, 0.987); // the spline average's droop, sinc^3(0.05) = 0.9877
  EXPECT_LT(high, 1.0005);
  EXPECT_LT(stop, std::pow(10, -f.attenuation / 20 + 0.1)); // Kaiser's estimate within 2 dB
  EXPECT_THROW(AntiAliasFilter::design(1), InputError);
  EXPECT_THROW(AntiAliasFilter::design(8, 0.5), InputError);
}

TEST(Decimator, SinusoidsComeOutScaledByTheResponseWithoutPhase)
{
  const AntiAliasFilter f       = AntiAliasFilter::design();
  const long            outputs = 400;
  for (double frequency : {0.0371, 0.25, 0.39, 0.45, 0.53, 0.71, 0.97, 3.3, 7.61, 8.4})
    {
      const std::vector<double> y =
          record([&](double t, double *v) { v[0] = std::sin(2 * pi * frequency * t); }, 1, outputs,
                 frequency)[0];
      ASSERT_EQ(y.size(), std::size_t(outputs + 1));
      const double H     = f.response(frequency);
      const long   edge  = long(f.taps.size()) / (2 * f.factor) + 2;
      double       worst = 0, largest = 0;
      for (long k = edge; k <= outputs - edge; ++k)
        {
          worst   = std::max(worst, std::abs(y[k] - H * std::sin(2 * pi * frequency * k)));
          largest = std::max(largest, std::abs(y[k]));
        }
      EXPECT_LT(worst, 1e-9) << "f " << frequency << " response " << H;
      if (frequency > 0.5) // above Nyquist: nothing folds back above -60 dB
        {
          EXPECT_LT(largest, 1e-3) << "f " << frequency;
        }
      else if (frequency <= f.pass) // the passband: through within the spline's droop
        {
          EXPECT_GT(largest, 0.98);
        }
    }
}

TEST(Decimator, StraightLinesPassUnchangedToTheEnds)
{
  const double a = 3.25, b = -17.5;
  const long   outputs = 30; // shorter than the filter: reflected at both ends
  const auto   y       = record(
      [&](double t, double *v) {
        v[0] = a + b * t;
        v[1] = -a - b * t;
      },
      2, outputs, 1.0);
  ASSERT_EQ(y[0].size(), std::size_t(outputs + 1));
  for (long k = 0; k <= outputs; ++k)
    {
      EXPECT_NEAR(y[0][k], a + b * k, 1e-12 * (1 + std::abs(b * k)));
      EXPECT_NEAR(y[1][k], -a - b * k, 1e-12 * (1 + std::abs(b * k)));
    }
  Decimator    partial(AntiAliasFilter::design(), 1);
  const double x0 = 1;
  partial.start(&x0);
  partial.push(&x0);
  EXPECT_THROW(partial.finish(&x0), InputError); // not a whole output interval
  EXPECT_THROW(AntiAliasRecorder(1.0, 0, 1), InputError);
}

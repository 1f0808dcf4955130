#include "base/spectrum.h"

#include "base/types.h"

#include <fftw3.h>

#include <cmath>
#include <complex>
#include <mutex>

namespace gearkit
{
std::vector<double>
amplitude_spectrum(const std::vector<double> &samples, int max_bin)
{
  const int n = int(samples.size());
  if (n < 2 || max_bin < 0)
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
  std::vector<double> amplitude(std::size_t(max_bin) + 1, 0.0);
  for (int k = 0; k <= std::min(max_bin, n / 2); ++k)
    amplitude[std::size_t(k)] =
        std::abs(out[std::size_t(k)]) * ((k == 0 || 2 * k == n) ? 1.0 / n : 2.0 / n);
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

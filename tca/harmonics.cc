#include "harmonics.h"

#include "types.h"

#include <fftw3.h>

#include <cmath>
#include <complex>

namespace gearkit
{
std::vector<double>
mesh_order_amplitudes(const std::vector<double> &samples, int cycles, int max_order)
{
  const int n = int(samples.size());
  if (n < 2 || cycles < 1)
    throw InputError("harmonics need at least two samples over at least one mesh cycle");
  std::vector<double>               in(samples);
  std::vector<std::complex<double>> out(n / 2 + 1);
  fftw_plan plan = fftw_plan_dft_r2c_1d(n, in.data(), reinterpret_cast<fftw_complex *>(out.data()),
                                        FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  std::vector<double> amplitude(max_order + 1, 0.0);
  for (int m = 0; m <= max_order; ++m)
    {
      const int k = m * cycles; // bin of mesh order m
      if (k > n / 2)
        break;
      const double scale = (k == 0 || 2 * k == n) ? 1.0 / n : 2.0 / n;
      amplitude[m]       = std::abs(out[k]) * scale;
    }
  return amplitude;
}
} // namespace gearkit

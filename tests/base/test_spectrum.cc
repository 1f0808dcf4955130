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

// Mesh-order harmonics of a transmission error sampled uniformly over whole mesh cycles (FFTW).
#pragma once

#include <vector>

namespace gearkit
{
/// Amplitudes (same unit as the signal) of mesh orders 0..max_order of `samples`, which cover
/// exactly `cycles` mesh cycles with uniform spacing (the last sample is the one before the
/// first of the next cycle). Order 0 is the mean; order m > 0 the amplitude of the sinusoid with
/// m periods per mesh cycle. Orders above the Nyquist limit are reported as 0.
std::vector<double>
mesh_order_amplitudes(const std::vector<double> &samples, int cycles, int max_order);
} // namespace gearkit

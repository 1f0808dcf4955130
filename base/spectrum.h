// Mesh-order harmonics of a transmission error sampled uniformly over whole mesh cycles (FFTW).
#pragma once

#include <vector>

namespace gearkit
{
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
} // namespace gearkit

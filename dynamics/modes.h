// Linear modes of the pair model about its static equilibrium, in drive-side contact at the
// phase-averaged mesh: (K + K_m g g^T) phi = omega^2 M phi. With a torque-driven motor the rigid
// rotation of the whole train is the first mode (0 Hz). The mesh resonances of a speed sweep
// sit where a mesh order j z_p n / 60 meets a mode with mesh strain energy (Campbell diagram).
//
// Parametric stability: with K_m, the normals and the arms varying over the mesh cycle the
// model in contact is linear with periodic coefficients; its Floquet multipliers (eigenvalues
// of the map of a perturbation over one period of the tables) tell whether vibrations die out
// (all |mu| < 1) or grow (parametric resonance: some |mu| > 1, where no steady state exists
// until contact is lost).
#pragma once

#include "dynamics/integrators.h"

#include <complex>
#include <vector>

namespace gearkit
{
struct PairModes
{
  std::vector<double> frequency;   ///< [Hz], ascending; one per free DOF
  std::vector<double> mesh_energy; ///< share of each mode's strain energy in the mesh
  Eigen::MatrixXd     shapes;      ///< columns: mass-normalised mode shapes
};

PairModes
linear_modes(const PairModel &model);

/// Floquet multipliers of the model in contact (no backlash: linear) at the pinion speed
/// run.omega and run's torques: the monodromy matrix over one period of the tables, built
/// column by column from perturbations of the free DOFs and their rates (integrated with run's
/// method and settings), largest modulus first. A torque-driven train's rigid rotation gives
/// multipliers 1.
std::vector<std::complex<double>>
floquet_multipliers(const PairModel &model, const RunOptions &run);

/// Whether the largest Floquet multiplier's modulus means growth: above 1 by more than 1e-6.
/// Undamped, the stable multipliers lie on the unit circle, which their computation reproduces
/// to about 1e-13; a torque-driven train's rigid rotation gives a double multiplier 1 (a Jordan
/// block: angle and speed) even with damping, whose computed pair splits by about the square
/// root of the rounding (1.4e-8 measured). A growth of 1e-6 a period would take 7e6 periods to
/// reach a thousandfold amplitude - thousands of times a sweep's settling.
inline bool
parametrically_unstable(double spectral_radius)
{
  return spectral_radius > 1 + 1e-6;
}

/// Pinion speeds [rpm] at which mesh order `order` excites a mode of the given frequency.
inline double
resonance_speed_rpm(double frequency_hz, int pinion_teeth, int order)
{
  return 60 * frequency_hz / (order * pinion_teeth);
}
} // namespace gearkit

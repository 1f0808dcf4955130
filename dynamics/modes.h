// Linear modes of the pair model about its static equilibrium, in drive-side contact at the
// phase-averaged mesh: (K + K_m g g^T) phi = omega^2 M phi. With a torque-driven motor the rigid
// rotation of the whole train is the first mode (0 Hz). The mesh resonances of a speed sweep
// sit where a mesh order j z_p n / 60 meets a mode with mesh strain energy (Campbell diagram).
#pragma once

#include "pair_model.h"

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

/// Pinion speeds [rpm] at which mesh order `order` excites a mode of the given frequency.
inline double
resonance_speed_rpm(double frequency_hz, int pinion_teeth, int order)
{
  return 60 * frequency_hz / (order * pinion_teeth);
}
} // namespace gearkit

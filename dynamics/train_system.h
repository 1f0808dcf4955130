// The gear train's equations, shared by the run (dynamics/train.cc) and written in
// dynamics/train_system.cc: each mesh's tooth pair contact at a state (forces, the generalised
// forces on the two angles, energies, penetrations and their rates for the root functions and
// the located extremes) and the bodies' accelerations. Internal to the dynamics library.
#pragma once

#include "dynamics/train.h"

#include <cmath>
#include <utility>
#include <vector>

namespace gearkit::train_internal
{
/// One mesh at one state: forces on its bodies, energies, root functions, outputs.
struct MeshEval
{
  double torque_driver = 0, torque_driven = 0; ///< generalised forces on the two angles
  double force[2] = {0, 0};                    ///< normal force per side [N]
  double energy = 0, dissipation_rate = 0;
  double max_penetration[2] = {-HUGE_VAL, -HUGE_VAL};
  /// The second and third deepest penetrations per side [m] (pairs entering and leaving while
  /// another touches)
  double next_penetration[2][2] = {{-HUGE_VAL, -HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL}};
  /// The k-th deepest penetration of a side (k = 0, 1, 2)
  double
  penetration(int side, int k) const
  {
    return k == 0 ? max_penetration[side] : next_penetration[side][k - 1];
  }
  /// dF/dt per side, linear in the two bodies' accelerations: its part without them and their
  /// coefficients (force_rate)
  double rate_fixed[2] = {0, 0}, rate_driver[2] = {0, 0}, rate_driven[2] = {0, 0};
  /// dF/dt of a side [N/s] at the driver's and driven body's accelerations: zero where the
  /// side's force peaks
  double
  force_rate(int side, double alpha_driver, double alpha_driven) const
  {
    return rate_fixed[side] + rate_driver[side] * alpha_driver + rate_driven[side] * alpha_driven;
  }
  /// The rate of each side's deepest penetration (max_penetration) [m/s], touching or not
  /// (TrainSystem::mesh with deepest_rates; else 0)
  double deepest_rate[2] = {0, 0};
  /// The penetration rates of the touching pairs, weighted by their elastic force over d: zero
  /// where the deepest penetration peaks (a finite number at first touch)
  double penetration_rate = 0, penetration_weight = 0;
  int    pairs            = 0;
  double parametric_power = 0; ///< of a finite-element K_m's variation [W]
};

/// The train's equations: each mesh's contact, the accelerations, the energies.
class TrainSystem
{
public:
  TrainSystem(const TrainModel &m, const TrainRunOptions &o);

  /// One mesh at (theta, omega); with deepest_rates, also the rates of the sides' deepest
  /// penetrations (touching or not: a step's ends, where the recorder follows them).
  MeshEval
  mesh(int index, const double *theta, const double *omega, bool deepest_rates = false) const;

  /// S of a mesh [m].
  double
  relative(int index, const double *theta) const;

  /// Accelerations, the power of the torques (and of a finite-element K_m's variation) and the
  /// dissipation rate at (t, theta, omega); the meshes as evaluated, if asked.
  void
  evaluate(double t, const double *theta, const double *omega, double *alpha, double &power,
           double &dissipation, std::vector<MeshEval> *evaluated = nullptr,
           bool deepest_rates = false) const;

  double
  kinetic(const double *theta, const double *omega) const;

  double
  potential(const double *theta, const double *omega) const;

  int                 n;
  const TrainModel   &model;
  TrainRunOptions     options;
  std::vector<double> centre; ///< band centre per mesh [rad]
  /// per mesh, the local pinion angles any of its curves has samples at [rad]
  std::vector<std::pair<double, double>> sampled;
};
} // namespace gearkit::train_internal

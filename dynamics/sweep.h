// Speed sweeps of the pair model with continuation: the state at the end of one speed starts
// the next (up or down the list), so that jumps and hysteresis show. Per speed: settle until
// the motion repeats (Poincare section at whole mesh cycles: the state - its elastic part, the
// train's rigid rotation may drift - returns after 1 to 4 cycles within the tolerance), or at
// most for the given number of mesh cycles, then record; dynamic transmission error delta_D
// peak-to-peak and RMS (about its mean), the largest mesh force, the dynamic load factor (largest
// over the static mesh force) and the share of the time out of contact.
#pragma once

#include "integrators.h"

#include <vector>

namespace gearkit
{
struct SweepOptions
{
  std::vector<double> speeds; ///< pinion speeds [rad/s], in the order swept
  double              motor_torque = 0, load_torque = 0;       ///< [N m]
  int                 settle_cycles = 200, record_cycles = 50; ///< settle: at most
  /// Steady when the Poincare points repeat within this (relative to the static deflection and
  /// its rate at the mesh frequency); 0: always settle for settle_cycles.
  double     steady_tolerance  = 1e-6;
  int        min_settle_cycles = 20;
  RunOptions run; ///< integrator, tolerances, samples / steps per mesh cycle
};

struct SweepPoint
{
  double      speed       = 0;                   ///< [rad/s]
  double      dte_pp      = 0;                   ///< delta_D peak-to-peak [m]
  double      dte_rms     = 0;                   ///< RMS of delta_D about its mean [m]
  double      relative_pp = 0, relative_rms = 0; ///< the same for delta_D - E_t [m]
  double      max_force      = 0;                ///< largest F_m [N]
  double      load_factor    = 0;                ///< max F_m / static F_m
  double      contact_loss   = 0;                ///< share of the recorded samples without contact
  std::size_t events         = 0;                ///< backlash boundaries crossed while recording
  int         settled_cycles = 0;                ///< mesh cycles spent settling
  /// Mesh cycles after which the motion repeats (1: periodic with the mesh; 2 to 4:
  /// subharmonic); 0: not steady within settle_cycles (or not checked).
  int period = 0;
};

/// Sweeps from (q, v) (e.g. the static equilibrium at rest); the final state is returned in
/// q and v (for a sweep back).
std::vector<SweepPoint>
sweep(const PairModel &model, PairVector &q, PairVector &v, const SweepOptions &options);
} // namespace gearkit

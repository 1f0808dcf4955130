// Time integration of the pair model (pair_model.h) at a constant pinion speed:
//  * CVODE (SUNDIALS; BDF for stiff supports or Adams for tight, non-stiff runs) with adaptive
//    steps and event location at the backlash boundaries delta_D - E_t = +-b_c, where the mesh
//    force changes its law (contact gained or lost): the integration restarts there;
//  * Newmark's average acceleration (trapezoidal) with a fixed number of steps per mesh cycle
//    and Newton iterations on the mesh force: unconditionally stable, no numerical damping, and
//    for a linear undamped model it conserves the energy exactly - the fast path for sweeps.
// Time and displacements are scaled inside (time in mesh cycles; tolerances relative to the
// static mesh deflection).
//
// Divergence: a run stops where the state stops being finite or |delta_D - E_t| passes
// RunOptions::divergence_bound (Newmark: checked at every step; CVODE: at every output sample
// and located event); the trajectory then ends at the last sample before it, and says when.
#pragma once

#include "dynamics/pair_model.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace gearkit
{
enum class Integrator
{
  cvode_bdf,
  cvode_adams,
  newmark
};

struct RunOptions
{
  double     omega              = 0;  ///< pinion speed [rad/s] (> 0)
  double     motor_torque       = 0;  ///< T_E [N m]
  double     load_torque        = 0;  ///< T_L [N m]
  double     mesh_cycles        = 10; ///< duration [mesh cycles]
  int        samples_per_cycle  = 32; ///< output samples per mesh cycle
  Integrator method             = Integrator::cvode_bdf;
  double     relative_tolerance = 1e-8; ///< CVODE
  /// CVODE absolute tolerance relative to the displacement scale (the static mesh deflection,
  /// per DOF through the mesh's moment arms) and its rate
  double absolute_tolerance = 1e-8;
  int    steps_per_cycle    = 64; ///< Newmark
  /// |delta_D - E_t| [m] past which the run stops as diverged (dynamics/sweep.h derives it from
  /// the static deflection and the backlash); infinite: only a state that is not finite stops it
  double divergence_bound = std::numeric_limits<double>::infinity();
};

struct Trajectory
{
  std::vector<double>     t;          ///< [s]
  std::vector<PairVector> q, v;       ///< state at the output times
  std::vector<double>     dte;        ///< delta_D [m]
  std::vector<double>     relative;   ///< delta_D - E_t [m]
  std::vector<double>     force;      ///< F_m [N]
  std::size_t             events = 0; ///< backlash boundaries crossed (CVODE)
  std::size_t             steps  = 0; ///< integrator steps taken
  /// The run stopped early: the state was not finite or |delta_D - E_t| passed the divergence
  /// bound at time `diverged_at` [s]; the samples (all finite, within the bound) end before it.
  bool   diverged    = false;
  double diverged_at = 0;
  /// Extremes of the continuous solution, not of the samples: delta_D and delta_D - E_t at the
  /// samples and at their stationary points inside the steps (Newmark: the average
  /// acceleration's quadratic q(t_n + s) = q_n + s v_n + s^2 (a_n + a_n+1) / 4, with the mesh
  /// state of the step's end; CVODE: roots of g . v and g . v - E_t' on the method's
  /// polynomial - g's own change over the mesh cycle left out, an error of second order in the
  /// extreme's value); the largest mesh force at the same points. The same at any output rate
  /// (Newmark: at any multiple of it in the steps).
  double dte_min = HUGE_VAL, dte_max = -HUGE_VAL;
  double relative_min = HUGE_VAL, relative_max = -HUGE_VAL;
  double force_max = -HUGE_VAL;
};

/// Integrates from (q0, v0) at t = 0, or until the response diverges (Trajectory::diverged).
/// Throws InputError for bad options and for integrator failures (step size collapse, event
/// failures), naming the time and the CVODE flag.
Trajectory
simulate(const PairModel &model, const PairVector &q0, const PairVector &v0,
         const RunOptions &options);
} // namespace gearkit

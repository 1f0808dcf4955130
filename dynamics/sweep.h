// Speed sweeps of the pair model with continuation: the state at the end of one speed starts
// the next (up or down the list), so that jumps and hysteresis show. Per speed: settle until
// the motion repeats (Poincare section at whole periods of the excitation - one mesh cycle, or
// the several a measured pair's tables span: the state - its elastic part, the train's rigid
// rotation may drift - returns after 1 to 4 periods within the tolerance), or at most for the
// given number of mesh cycles, or until the response diverges (SweepOptions::divergence_factor:
// flagged, zero results), then record; dynamic transmission error delta_D peak-to-peak and
// RMS (about its mean), its amplitude spectrum, the largest mesh force, the dynamic load factor
// (largest over the static mesh force) and the share of the time out of contact; the time
// series at chosen speeds.
//
// Sweeps are independent tasks (excitations, directions, blocks of speeds); run_sweeps runs
// them on threads, split_sweep cuts one sweep into blocks that start a few speeds early to
// regain the continuation (for threads here, or MPI processes in the driver).
#pragma once

#include "dynamics/integrators.h"

#include <string>
#include <vector>

namespace gearkit
{
class Progress;

struct SweepOptions
{
  Progress           *progress = nullptr; ///< advanced by one per speed, if given
  std::vector<double> speeds;             ///< pinion speeds [rad/s], in the order swept
  double              motor_torque = 0, load_torque = 0; ///< [N m]
  /// Mesh cycles: settle at most this many (up to five times as many while the Poincare
  /// points still converge geometrically fast enough to repeat within them), record this many
  /// (both rounded up to whole periods of the excitation).
  int settle_cycles = 200, record_cycles = 50;
  /// Steady when the Poincare points repeat within this (relative to the static deflection and
  /// its rate at the mesh frequency; CVODE: at least 1e3 times its tolerances, what its points
  /// repeat to) over three whole periods (1 to 4 periods of the excitation; a period above 1
  /// only while the shorter periods' mismatches hold still over ten mesh cycles: not a
  /// decaying transient);
  /// 0: always settle for settle_cycles. The default is the scene's (Dynamics/<pair>/steady
  /// tolerance takes it from here).
  double steady_tolerance  = 1e-4;
  int    min_settle_cycles = 20;
  /// Diverged when |delta_D - E_t| passes this times the response's own length scale - the
  /// static deflection plus the half backlash plus E_t's peak-to-peak - or the state is not
  /// finite (parametric resonance pumping without bound, an undamped forced resonance), checked
  /// at every Newmark step and every CVODE sample (RunOptions::divergence_bound): that speed
  /// stops there, its point is flagged (SweepPoint::diverged, with the time) and its results
  /// are zero, and the next speed starts from the static equilibrium. Why 1000: no gear pair
  /// survives a mesh force of even ten times its static one (dynamic load factors through
  /// resonances stay below about 3), and a damped linear resonance stays within 1 / (2 zeta)
  /// times its excitation's amplitude, so every bounded response with zeta above 5e-4 stays
  /// below the bound, while a motion growing by the Floquet multiplier |mu| > 1 a period
  /// crosses it within log(1000) / log|mu| periods.
  double divergence_factor = 1e3;
  /// Swept first to regain the continuation, not returned (the first speeds of a block).
  int warmup_speeds = 0;
  /// DTE spectrum up to this mesh order, at the record's resolution (1 / record cycles).
  int spectrum_orders = 10;
  /// Keep the recorded time series at the swept speeds nearest to these [rad/s].
  std::vector<double> series_speeds;
  RunOptions          run; ///< integrator, tolerances, samples / steps per mesh cycle
  /// Newmark: the relative RMS error of delta_D wanted (> 0) instead of a step count. At each
  /// speed the steps per mesh cycle (multiples of run.samples_per_cycle, run.steps_per_cycle
  /// the least) are the fewest whose error for the tables' forcing is within it
  /// (NewmarkError::steps), then raised, the speed settled and recorded again (up to four
  /// times), while the recorded motion's harmonics (NewmarkError::recorded: what contact loss
  /// and K_m's variation add) say more than half of it; 0: run's steps at every speed. The
  /// default (0.5 % of the DTE RMS) is the scene's (Dynamics/<pair>/accuracy takes it from here).
  double accuracy = 0.005;
  /// The most Newmark steps per mesh cycle the accuracy may ask for (a bound on the sweep's
  /// cost; at least run.steps_per_cycle): where it asks more, the speed runs with these and its
  /// error estimate above the accuracy (a caller refuses an accuracy the forced estimate puts
  /// beyond them first: the driver's Dynamics/<pair>/accuracy).
  int most_steps = 1 << 16;
};

struct SweepPoint
{
  double speed = 0; ///< [rad/s]
  /// delta_D peak-to-peak [m], from the continuous solution's extremes (Trajectory: located
  /// inside the steps), not the samples'; the RMS from the samples
  double      dte_pp      = 0;
  double      dte_rms     = 0;                   ///< RMS of delta_D about its mean [m]
  double      relative_pp = 0, relative_rms = 0; ///< the same for delta_D - E_t [m]
  double      max_force       = 0;               ///< largest F_m [N] (Trajectory::force_max)
  double      load_factor     = 0;               ///< max F_m / static F_m
  double      contact_loss    = 0;               ///< share of the recorded samples without contact
  std::size_t events          = 0;               ///< backlash boundaries crossed while recording
  int         settled_cycles  = 0;               ///< mesh cycles spent settling
  int         steps_per_cycle = 0;               ///< Newmark's at this speed (0: CVODE)
  /// Newmark: the larger of NewmarkError's estimates (forced, recorded) of delta_D's relative
  /// RMS error; NaN for CVODE (its tolerances), 0 for diverged points.
  double error_estimate = 0;
  /// Mesh cycles after which the motion repeats (a multiple of the excitation's period; 1:
  /// periodic with the mesh); 0: not steady within settle_cycles (or not checked, or diverged).
  int period = 0;
  /// The response diverged (SweepOptions::divergence_factor): every result above and the
  /// spectrum are 0 - no values, never to enter maxima or means - and there is no time series.
  bool   diverged      = false;
  double diverged_time = 0; ///< when: time run at this speed until then [s] (0: not diverged)
  /// Amplitudes of delta_D at mesh orders k / record cycles, k = 0 .. spectrum_orders * record
  /// cycles [m] (k = 0: the mean).
  std::vector<double> spectrum;
  int                 record_cycles = 0; ///< as recorded (the spectrum's resolution)
  /// The recorded time series, at the speeds asked for (else empty): time [s], delta_D, E_t [m],
  /// F_m [N].
  std::vector<double> series_time, series_dte, series_transmission_error, series_force;
};

/// Sweeps from (q, v) (e.g. the static equilibrium at rest); the final state is returned in
/// q and v (for a sweep back).
std::vector<SweepPoint>
sweep(const PairModel &model, PairVector &q, PairVector &v, const SweepOptions &options);

/// One sweep in `blocks` consecutive pieces of its speed list, each but the first starting
/// `warmup` speeds early (SweepOptions::warmup_speeds): concatenated, their results are the
/// sweep's (up to the settling the warm-up hides). Time series are kept at the whole sweep's
/// speeds nearest those asked for.
std::vector<SweepOptions>
split_sweep(const SweepOptions &options, int blocks, int warmup);

struct SweepTask
{
  const PairModel *model = nullptr;
  PairVector       q = PairVector::Zero(), v = PairVector::Zero(); ///< start
  SweepOptions     options;
};

/// Runs the tasks on up to `threads` threads (0: the hardware's); results in the tasks'
/// order. An error in any task is rethrown (the first task's by index) after all have stopped.
/// A non-empty `progress` names the speeds on a progress line (base/progress.h).
std::vector<std::vector<SweepPoint>>
run_sweeps(const std::vector<SweepTask> &tasks, unsigned threads = 0,
           const std::string &progress = "");
} // namespace gearkit

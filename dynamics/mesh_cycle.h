// What the dynamic model needs of the mesh over one period of its excitation - one mesh cycle
// of perfect flanks, or several of measured flanks whose teeth differ - sampled at equal steps
// of the pinion's rotation (from the /ste and /stiffness tables, or analytic): the unloaded
// transmission error E_t as a displacement along the line of action, the mesh stiffness K_m,
// the unit normals n_p, n_g along which the pinion pushes the gear (global frame) and the moment
// arms lambda_p = r_p x n_p, lambda_g = r_g x n_g about each body's centre. Interpolated
// periodically in the mesh phase, exact at the samples: trigonometric (smooth; Boost.Math on
// FFTW) for smooth tables, or modified Akima (Boost.Math makima; no overshoot at kinks and
// noise, continuous slope) for measured ones.
#pragma once

#include "base/types.h"

#include <memory>
#include <vector>

namespace gearkit
{
enum class MeshInterpolation
{
  trigonometric,
  makima
};

struct MeshCycleSamples
{
  int                 cycles        = 1; ///< mesh cycles the samples span (the excitation period)
  MeshInterpolation   interpolation = MeshInterpolation::trigonometric;
  std::vector<double> transmission_error; ///< E_t [m], one value per sample
  std::vector<double> mesh_stiffness;     ///< K_m [N/m]
  std::vector<Vec3>   normal_pinion, normal_gear;
  std::vector<Vec3>   arm_pinion, arm_gear; ///< [m]
};

/// The mesh at one phase.
struct MeshState
{
  double et = 0, det = 0; ///< E_t [m] and dE_t / d(phase) [m per mesh cycle]
  double km = 0;          ///< [N/m]
  Vec3   np = Vec3::Zero(), ng = Vec3::Zero(), lp = Vec3::Zero(), lg = Vec3::Zero();
};

class MeshCycle
{
public:
  /// All tables of one length >= 1 (1: constant; makima: >= 4), cycles >= 1; K_m > 0, unit
  /// normals, finite values. Throws InputError naming the table and sample otherwise.
  explicit MeshCycle(const MeshCycleSamples &samples);
  ~MeshCycle();
  MeshCycle(const MeshCycle &) = delete;
  MeshCycle &
  operator=(const MeshCycle &) = delete;

  /// At the phase (mesh cycles; any real number, periodic with period cycles()).
  MeshState
  at(double phase) const;
  /// The phase averages (the static equilibrium's mesh).
  MeshState
  mean() const;
  std::size_t
  samples() const;
  /// Mesh cycles in one period of the tables.
  int
  cycles() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};

/// A periodic table given at values.size() equal phases of one period, sampled at n equal
/// phases by the interpolation the mesh tables use (e.g. K_m from the finite elements' positions
/// onto the TCA's).
std::vector<double>
resample_periodic(const std::vector<double> &values, int n,
                  MeshInterpolation how = MeshInterpolation::trigonometric);

/// K_m (1 - variation cos 2 pi phase) at n equal phases of one mesh cycle.
std::vector<double>
varying_mesh_stiffness(double mean, double variation, int n);

/// The unloaded contact as the TCA tabulates it, position-major: per position its pair slots
/// (3-vectors per slot) and which slot leads.
struct ContactTables
{
  std::size_t         positions = 0, slots = 0;
  std::vector<double> normal_pinion;      ///< pinion outward normal [position][slot][xyz]
  std::vector<double> lambda_pinion;      ///< r_p x n_p, pinion frame [position][slot][xyz] [m]
  std::vector<double> lambda_gear;        ///< r_g x n_g with the gear's own normal [m]
  std::vector<double> transmission_error; ///< e_0 [rad of the pinion], per position
  std::vector<int>    leading;            ///< slot of the pair that carries the load (< 0: 0)
};

/// The mesh tables of the first `cycles` mesh cycles (n positions each) of the TCA's leading
/// contact: n = the pinion's outward normal (the pinion pushes the gear along it) for both
/// members, the gear's arm r_g x n minus the TCA's (taken with the gear's own normal), E_t =
/// (lambda_p . pinion axis) e_0 along the line of action; K_m (one mesh cycle, n values)
/// repeats over the cycles. Throws InputError when the TCA has fewer positions.
MeshCycleSamples
mesh_cycle_samples(const ContactTables &tca, int n, int cycles, const Vec3 &pinion_axis,
                   const std::vector<double> &mesh_stiffness);

/// The load torque that balances the motor torque through the mean moment arms of the mesh
/// (each about its member's axis in its driven sense).
double
balancing_load_torque(const MeshCycle &mesh, double motor_torque, const Vec3 &pinion_axis,
                      const Vec3 &gear_axis);
} // namespace gearkit

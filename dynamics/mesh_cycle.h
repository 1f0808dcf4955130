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
} // namespace gearkit

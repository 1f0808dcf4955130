// The gear train's equations, shared by the run (dynamics/train.cc) and written in
// dynamics/train_system.cc: each mesh's tooth pair contact at a state (forces, the generalised
// forces on the two angles, energies, penetrations and their rates for the root functions and
// the located extremes) and the bodies' accelerations. Internal to the dynamics library.
#pragma once

#include "dynamics/train.h"

#include <array>
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

/// A tooth pair curve's offset and arm at a local pinion angle (CurveCubics::at).
struct CurvePoint
{
  double        u             = 0;       ///< position within its piece [0, 1]
  const double *a             = nullptr; ///< the piece's coefficients (offset 0-3, arm 4-7)
  double        inverse_width = 0;       ///< of the piece's width [1/rad]
  double        offset = 0, arm = 0;
};

/// A tooth pair curve (ToothPairCurve) as cubic Hermite pieces between its samples, each
/// piece's offset and arm in powers of its local coordinate (a value in three multiply-adds).
/// Without kinks the slopes are central differences (one-sided at the ends); a kink
/// (CurveKnot) splits its interval in two, and each smooth stretch between kinks takes its
/// slopes from parabolas through its own nodes only: the kink stays a kink.
class CurveCubics
{
public:
  explicit CurveCubics(const ToothPairCurve &c);
  /// The offset and arm at local pinion angle x; false outside the samples.
  bool
  at(double x, CurvePoint &p) const
  {
    const double s = (x - start) * inverse_step;
    if (!(s >= 0) || s > intervals)
      return false;
    const Interval &i = intervals_[std::size_t(std::min(int(s), intervals - 1))];
    const Piece    &q = pieces[std::size_t(i.first + (x >= i.cut))];
    const double    u = p.u = (x - q.x0) * q.inverse_width;
    const double   *c = p.a = q.c.data();
    p.inverse_width         = q.inverse_width;
    p.offset                = ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
    p.arm                   = ((c[7] * u + c[6]) * u + c[5]) * u + c[4];
    return true;
  }
  /// Their derivatives by the local pinion angle at p, first and second.
  void
  slopes(const CurvePoint &p, double &offset_slope, double &arm_slope) const;
  void
  curvatures(const CurvePoint &p, double &offset_curvature, double &arm_curvature) const;

private:
  struct Piece
  {
    std::array<double, 8> c; ///< offset 0-3, arm 4-7
    double                x0, inverse_width;
  };
  /// A sample interval: its first piece, and the kink splitting it (else HUGE_VAL)
  struct Interval
  {
    int    first;
    double cut;
  };
  double                start, step, inverse_step;
  int                   intervals;
  std::vector<Piece>    pieces;
  std::vector<Interval> intervals_;
};

/// What TrainSystem::mesh evaluates: the forces and torques alone (the right-hand side), also
/// the outputs (energies, penetrations, force rates), also the rates of the sides' deepest
/// penetrations touching or not (a step's ends, where the recorder follows them).
enum class MeshDetail
{
  forces,
  outputs,
  deepest_rates
};

/// The train's equations: each mesh's contact, the accelerations, the energies.
class TrainSystem
{
public:
  TrainSystem(const TrainModel &m, const TrainRunOptions &o);

  /// One mesh at (theta, omega), as much as `detail` asks.
  MeshEval
  mesh(int index, const double *theta, const double *omega,
       MeshDetail detail = MeshDetail::outputs) const;

  /// The cubics of mesh `index`'s curve on `side` for pairing k (its teeth's class pair).
  const CurveCubics &
  curve(int index, int side, int k) const;

  /// S of a mesh [m].
  double
  relative(int index, const double *theta) const;

  /// A kink of a mesh's tooth pair curves (ToothPairCurve::knots): its side and local pinion
  /// angle; every pairing passes it once a mesh cycle.
  struct Kink
  {
    int    side;
    double at;
    double cosine, sine; ///< of z1 at / 2
  };
  /// The kinks of mesh `index`, one per local angle (modulo a mesh cycle) over its class pairs.
  const std::vector<Kink> &
  kinks(int index) const
  {
    return kink_list[std::size_t(index)];
  }
  /// The root functions of mesh `index`'s kinks into g: sin(z1 (phi - at) / 2), zero
  /// (changing sign) each time a pairing passes the kink.
  void
  kink_roots(int index, const double *theta, double *g) const;
  /// Whether the pairing now nearest kink `k` of mesh `index` touches there (its penetration
  /// just past the kink > 0): a pairing passing a kink apart feels nothing.
  bool
  kink_touches(int index, int k, const double *theta) const;

  /// Accelerations, the power of the torques (and of a finite-element K_m's variation) and the
  /// dissipation rate at (t, theta, omega); the meshes as evaluated with their outputs, if
  /// asked (without: the forces alone, the right-hand side's evaluation).
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
  /// per mesh and side, its curves as cubics (ToothPairTables::curves' order)
  std::vector<std::array<std::vector<CurveCubics>, 2>> cubics;
  std::vector<std::vector<Kink>>                       kink_list;
};
} // namespace gearkit::train_internal

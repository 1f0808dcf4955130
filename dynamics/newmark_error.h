// Newmark's error in the frequency domain: how many steps per mesh cycle a sweep needs.
//
// For a linear model M q'' + C q' + K q = f, the average-acceleration rule's steady response
// to a force sampled at its steps, f_n = F exp(i W t_n), is exactly the continuous response at
// the warped frequency W~ = (2/h) tan(W h / 2): the rule is the trapezoidal one, so v = s q and
// a = s^2 q with s = (2/h)(z - 1)/(z + 1) = i W~, z = exp(i W h). A mode above the excitation
// is not lost but moved (W~ > W: the response at W is the continuous one at a higher
// frequency, as if the mode sat lower), and orders at or above h's Nyquist limit alias.
//
// The pair model in drive-side contact at its phase-averaged mesh is such a model (K + k_m g
// g^T, C + c_m g g^T on the free DOFs), forced by the tables' variation about the static
// equilibrium q_s: f(phase) = -g(phase) K_m(phase) (g(phase) . q_s - E_t(phase) - b_c) + g c_m
// E_t'(phase) (the normals, arms and K_m varying over the cycle), whose harmonics come from the
// tables' own interpolation sampled eight times as densely as the tables. With delta_D = g . q
// its harmonics are g(phase) . q_s (kinematic: no integrator error) plus g^T H(i W) f_k, so the
// error of each harmonic is g^T (H(i W~) - H(i W)) f_k, exactly for that linear model; a
// harmonic at or past the Nyquist order is lost where it belongs and answered where it folds
// (both counted, as in continuous time). What it
// leaves out - K_m's parametric coupling, contact loss, impacts - makes new harmonics of the
// response; `recorded` weighs a recorded delta_D's harmonics by the same warping of the mesh
// receptance G(s) = g^T H(s) g: a harmonic D_k made at the mesh answers D_k (1 - G(i W_k) /
// G(i W~_k)) off.
#pragma once

#include "dynamics/pair_model.h"

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace gearkit
{
class NewmarkError
{
public:
  /// How g^T H(s) f is found: from the damped modes (sum over poles: a few hundred harmonics
  /// at a few step counts per speed cost microseconds), or by a complex solve per frequency
  /// (the check; also where the damped modes cannot be separated).
  enum class Evaluation
  {
    modal,
    direct
  };
  /// The model about its static equilibrium under the load torque [N m].
  NewmarkError(const PairModel &model, double load_torque,
               Evaluation evaluation = Evaluation::modal);

  /// A priori: the RMS of delta_D's error over the RMS of delta_D about its mean, at pinion
  /// speed omega [rad/s] and `steps` per mesh cycle, for the forcing of the tables.
  double
  forced(double omega, int steps) const;

  /// The fewest steps, a multiple of `multiple` (>= 1) and at least `least`, with forced() <=
  /// accuracy (at most `most`, whatever its error): walked up by the steps^-2 law, then bisected
  /// to one multiple (the error need not fall monotonically where orders fold).
  int
  steps(double omega, double accuracy, int least, int multiple, int most = 1 << 16) const;

  /// A posteriori: the relative RMS error of a recorded delta_D (uniform samples over `cycles`
  /// whole mesh cycles from phase 0, the last sample excluded) from its harmonics less the
  /// kinematic g(phase) . q_s, each weighed by |1 - G(i W) / G(i W~)|; the harmonics holding
  /// all but (0.1 `resolution`)^2 of its energy are weighed, the rest counted as wholly wrong
  /// (at most 0.1 `resolution`).
  double
  recorded(double omega, int steps, const std::vector<double> &dte, int cycles,
           double resolution = 1e-3) const;

private:
  using Complex = std::complex<double>;
  struct Harmonic
  {
    double           order = 0;                  ///< mesh order
    Eigen::VectorXcd force, damping;             ///< f_k = force + f_mesh damping (free DOFs)
    Eigen::VectorXcd modal_force, modal_damping; ///< their projections on the damped modes
    Complex          kinematic;                  ///< of g(phase) . q_s
  };
  /// The damped modes of (M, C, K) without the rigid rotation: poles, g's left factors and the
  /// projection of forces; false where they cannot be separated (then: direct solves).
  bool
  damped_modes();
  Eigen::VectorXcd
  project(const Eigen::VectorXcd &f) const;
  /// g^T H(i w) f (w of either sign), f also given projected (modal evaluation).
  Complex
  transfer(const Eigen::VectorXcd &f, const Eigen::VectorXcd &modal_f, double w) const;
  /// ... for a harmonic's force at the mesh frequency f_mesh [Hz].
  Complex
  transfer(const Harmonic &h, double f_mesh, double w) const;
  /// Warped frequency of mesh order `order` at `steps` per cycle and mesh frequency f [Hz];
  /// infinite at and above the Nyquist limit.
  static double
  warped(double order, int steps, double f_mesh);
  /// At one speed: each harmonic's exact dynamic part g^T H(i W) f_k and the exact delta_D's
  /// energy; error(steps) is forced()'s.
  struct AtSpeed
  {
    double               f_mesh = 0, energy = 0;
    std::vector<Complex> dynamic;
    const NewmarkError  *owner = nullptr;
    double
    error(int steps) const;
  };
  AtSpeed
  at_speed(double omega) const;

  Eigen::MatrixXd       M, C, K; ///< on the free DOFs, mean mesh in contact
  Eigen::VectorXd       g;
  int                   pinion_teeth = 0;
  bool                  modal        = false;
  Eigen::VectorXcd      poles, left, g_modal;
  Eigen::MatrixXcd      into_modes;
  std::vector<Harmonic> harmonics;
};
} // namespace gearkit

// Frictionless contact of discretised surfaces under a prescribed load, the small linear
// complementarity problem the fast (compliance) mode solves at every mesh position:
//
//   w = C F,   w_j = lambda_j delta - g_j where F_j > 0,   w_j >= lambda_j delta - g_j where F_j =
//   0, F_j >= 0,  sum_j lambda_j F_j = load.
//
// F_j: normal force on cell j [N]; C: compliance (normal approach of both surfaces at j per unit
// force at i) [m/N], symmetric positive definite; g_j: unloaded normal gap [m]; delta: rigid
// approach of the bodies (a translation [m] with lambda = 1, or a rotation [rad] with lambda_j
// the moment arm of cell j [m]); load: total force [N] or torque [N m].
#pragma once

#include <Eigen/Core>

#include <vector>

namespace gearkit
{
struct ContactProblem
{
  Eigen::MatrixXd compliance; ///< C [m/N]
  Eigen::VectorXd gap;        ///< g [m]
  Eigen::VectorXd lever;      ///< lambda (> 0)
  double          load = 0;   ///< sum lambda F [N or N m], >= 0
};

struct ContactSolution
{
  Eigen::VectorXd   force;           ///< F [N]
  double            approach   = 0;  ///< delta
  int               active     = 0;  ///< cells in contact
  int               iterations = 0;  ///< active-set changes
  std::vector<char> active_set;      ///< per cell: in contact (a warm start for a similar problem)
  double            penetration = 0; ///< largest violation of w >= lambda delta - g [m]
};

/// Active-set solution (Cholesky of the active block, the approach from the load balance);
/// all negative forces leave and all penetrating cells join per iteration, one at a time if
/// that cycles. Zero load gives zero forces and the first-touch approach min g / lambda.
/// Throws InputError for inconsistent sizes, negative load or non-positive levers, and when the
/// active set does not settle.
ContactSolution
solve_contact(const ContactProblem &problem);

/// The same problem given in parts, the compliance shared by many problems (not copied, and
/// not checked here: its entries must be finite, which the caller checks once), with
/// the cells in contact to start from: a warm start from a similar problem's active set (one
/// entry per cell; empty: the first cell to touch). The solution does not depend on `start`.
ContactSolution
solve_contact(const Eigen::MatrixXd &compliance, const Eigen::VectorXd &gap,
              const Eigen::VectorXd &lever, double load, const std::vector<char> &start = {});
} // namespace gearkit

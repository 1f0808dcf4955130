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

/// The Cholesky factor L L^T of a symmetric positive definite matrix's block over a set of its
/// cells (an active set), kept as the set changes instead of factorised anew (m^3 / 3):
/// cells that join are appended by bordering (L^-1 of their columns, the Cholesky factor of
/// their Schur complement: ~m^2 per cell), cells that leave cost a refactorisation of the rows
/// after the first of them (B B^T of those rows' trailing part), so that cells likely to leave
/// belong at the end. Where an update would cost more than factorising anew, the block is
/// factorised anew. Only the block's lower triangle is read.
class ActiveSetFactor
{
public:
  ActiveSetFactor() = default;
  /// The block of `cells` of `matrix` (in this order). Throws InputError if it is not positive
  /// definite.
  ActiveSetFactor(const Eigen::MatrixXd &matrix, std::vector<Eigen::Index> cells);

  /// Factorises the block of `cells` anew (as the constructor).
  void
  assign(const Eigen::MatrixXd &matrix, std::vector<Eigen::Index> cells);
  /// Becomes a copy of `other`, in this factor's storage where it has room.
  void
  copy(const ActiveSetFactor &other);

  /// The cells, in the factor's order.
  const std::vector<Eigen::Index> &
  cells() const
  {
    return order;
  }
  Eigen::Index
  size() const
  {
    return Eigen::Index(order.size());
  }
  /// x := block^-1 x (x: one row per cell, in cells()' order).
  void
  solve(Eigen::MatrixXd &x) const;
  /// Removes the cells whose entry of `leave` (one per row of `matrix`) is set; with a
  /// `source`, becomes `source` less those cells (reading of it only the rows it keeps: less
  /// than a copy followed by the removal).
  void
  remove(const Eigen::MatrixXd &matrix, const std::vector<char> &leave,
         const ActiveSetFactor *source = nullptr);
  /// Appends `cells` (not in the set) in this order.
  void
  append(const Eigen::MatrixXd &matrix, const std::vector<Eigen::Index> &cells);

private:
  /// Factorises the block of `cells` anew; false if it is not positive definite.
  bool
  factorise(const Eigen::MatrixXd &matrix, std::vector<Eigen::Index> cells);
  /// Room for `m` cells (keeps the factor).
  void
  reserve(Eigen::Index m);

  std::vector<Eigen::Index> order;
  /// The factor in the lower triangle of the leading size() x size() block (the strict upper
  /// triangle is neither read nor kept); the leading dimension is L.rows() >= size(), room to
  /// append.
  Eigen::MatrixXd L;
  Eigen::MatrixXd work;
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

/// Active-set solution (Cholesky of the active block, updated as cells leave and join; the
/// approach from the load balance);
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

/// The same, from the factor of the cells to start from (their order, the compliance's block
/// over them factorised: a zone solving many similar problems factorises its own active set
/// once, the cells most loaded first): each iteration updates it instead of factorising anew.
ContactSolution
solve_contact(const Eigen::MatrixXd &compliance, const Eigen::VectorXd &gap,
              const Eigen::VectorXd &lever, double load, const ActiveSetFactor &start);
} // namespace gearkit

#include "stiffness/contact_solver.h"

#include "geometry/types.h"

#include <deal.II/lac/lapack_templates.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace gearkit
{
namespace
{
using blas_int = dealii::types::blas_int;

const std::string not_positive_definite =
    "contact solver: the compliance matrix is not positive definite";

/// The lower triangle of the leading n x n block of `from` into `to` (a factor's entries).
void
copy_lower(Eigen::MatrixXd &to, const Eigen::MatrixXd &from, Eigen::Index n)
{
  for (Eigen::Index c = 0; c < n; ++c)
    to.col(c).segment(c, n - c) = from.col(c).segment(c, n - c);
}
} // namespace

ActiveSetFactor::ActiveSetFactor(const Eigen::MatrixXd &matrix, std::vector<Eigen::Index> cells)
{
  assign(matrix, std::move(cells));
}

void
ActiveSetFactor::reserve(Eigen::Index m)
{
  if (m <= L.rows())
    return;
  const Eigen::Index n = size(), room = std::max(m, L.rows() + L.rows() / 2 + 16);
  Eigen::MatrixXd    bigger(room, room);
  copy_lower(bigger, L, n);
  L.swap(bigger);
}

void
ActiveSetFactor::assign(const Eigen::MatrixXd &matrix, std::vector<Eigen::Index> cells)
{
  if (!factorise(matrix, std::move(cells)))
    throw InputError(not_positive_definite);
}

void
ActiveSetFactor::copy(const ActiveSetFactor &other)
{
  const Eigen::Index m = other.size();
  if (L.rows() < m)
    L.resize(other.L.rows(), other.L.rows());
  copy_lower(L, other.L, m);
  order = other.order;
}

bool
ActiveSetFactor::factorise(const Eigen::MatrixXd &matrix, std::vector<Eigen::Index> cells)
{
  order                = std::move(cells);
  const Eigen::Index m = size();
  if (L.rows() < m)
    L.resize(m + m / 4 + 16, m + m / 4 + 16);
  for (Eigen::Index b = 0; b < m; ++b)
    {
      const double *column = matrix.data() + order[std::size_t(b)] * matrix.rows();
      for (Eigen::Index a = b; a < m; ++a)
        L(a, b) = column[order[std::size_t(a)]];
    }
  // LAPACK's Cholesky factorisation (OpenBLAS's kernels for this processor)
  const blas_int size = blas_int(m), lda = blas_int(L.rows());
  blas_int       info = 0;
  if (m > 0)
    dealii::potrf("L", &size, L.data(), &lda, &info);
  return info == 0;
}

void
ActiveSetFactor::solve(Eigen::MatrixXd &x) const
{
  // (LAPACK's potrs packs the factor for BLAS 3 at each call: for the few right-hand sides
  // here, triangular solves by BLAS 2 without packing take less time)
  const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> F(
      L.data(), size(), size(), Eigen::OuterStride<>(L.rows()));
  for (Eigen::Index c = 0; c < x.cols(); ++c)
    {
      F.triangularView<Eigen::Lower>().solveInPlace(x.col(c));
      F.transpose().triangularView<Eigen::Upper>().solveInPlace(x.col(c));
    }
}

void
ActiveSetFactor::remove(const Eigen::MatrixXd &matrix, const std::vector<char> &leave,
                        const ActiveSetFactor *source)
{
  const ActiveSetFactor           &S  = source ? *source : *this;
  const std::vector<Eigen::Index> &so = S.order;
  const Eigen::Index               m  = S.size();
  Eigen::Index                     r0 = 0; // the first cell to leave
  while (r0 < m && !leave[std::size_t(so[std::size_t(r0)])])
    ++r0;
  if (r0 == m)
    {
      if (&S != this)
        copy(S);
      return;
    }
  std::vector<Eigen::Index> kept; // the rows after it that stay
  for (Eigen::Index a = r0 + 1; a < m; ++a)
    if (!leave[std::size_t(so[std::size_t(a)])])
      kept.push_back(a);
  const Eigen::Index        t = Eigen::Index(kept.size()), w = m - r0, left = r0 + t;
  std::vector<Eigen::Index> cells(so.begin(), so.begin() + r0);
  for (const Eigen::Index a : kept)
    cells.push_back(so[std::size_t(a)]);
  // The kept rows' Schur complement on the first r0 cells is B B^T, B their part of the
  // factor from column r0 on: t^2 w + t^3 / 3 against (r0 + t)^3 / 3 anew.
  if (double(t) * double(t) * (double(w) + double(t) / 3) >
      double(left) * double(left) * double(left) / 3)
    {
      if (!factorise(matrix, std::move(cells)))
        throw InputError(not_positive_definite);
      return;
    }
  // (column by column: the factor is stored by columns; its lower triangle alone)
  work.resize(t, w);
  for (Eigen::Index c = r0; c < m; ++c)
    for (Eigen::Index i = 0; i < t; ++i)
      work(i, c - r0) = kept[std::size_t(i)] >= c ? S.L(kept[std::size_t(i)], c) : 0.0;
  if (&S != this) // the rows before the first to leave, read from the source alone
    {
      if (L.rows() < m)
        L.resize(S.L.rows(), S.L.rows());
      copy_lower(L, S.L, r0);
    }
  for (Eigen::Index c = 0; c < r0; ++c) // rows move up (kept[i] > r0 + i)
    for (Eigen::Index i = 0; i < t; ++i)
      L(r0 + i, c) = S.L(kept[std::size_t(i)], c);
  const blas_int tt = blas_int(t), ww = blas_int(w), lda = blas_int(L.rows());
  const double   one = 1, zero = 0;
  blas_int       info = 0;
  if (t > 0)
    {
      dealii::syrk("L", "N", &tt, &ww, &one, work.data(), &tt, &zero, &L(r0, r0), &lda);
      dealii::potrf("L", &tt, &L(r0, r0), &lda, &info);
    }
  if (info != 0)
    {
      if (!factorise(matrix, std::move(cells)))
        throw InputError(not_positive_definite);
      return;
    }
  order = std::move(cells);
}

void
ActiveSetFactor::append(const Eigen::MatrixXd &matrix, const std::vector<Eigen::Index> &cells)
{
  const Eigen::Index m = size(), k = Eigen::Index(cells.size());
  if (k == 0)
    return;
  std::vector<Eigen::Index> all = order;
  all.insert(all.end(), cells.begin(), cells.end());
  // Bordering: m^2 k + m k^2 + k^3 / 3 against (m + k)^3 / 3 anew.
  if (double(k) * (double(m) * double(m) + double(m) * double(k) + double(k) * double(k) / 3) >
      double(m + k) * double(m + k) * double(m + k) / 3)
    {
      if (!factorise(matrix, std::move(all)))
        throw InputError(not_positive_definite);
      return;
    }
  reserve(m + k);
  const Eigen::Index n = matrix.rows();
  work.resize(m, k);
  for (Eigen::Index c = 0; c < k; ++c)
    {
      const double *column = matrix.data() + cells[std::size_t(c)] * n;
      for (Eigen::Index a = 0; a < m; ++a)
        work(a, c) = column[order[std::size_t(a)]];
      for (Eigen::Index a = c; a < k; ++a)
        L(m + a, m + c) = column[cells[std::size_t(a)]];
    }
  const blas_int mm = blas_int(m), kk = blas_int(k), lda = blas_int(L.rows());
  const double   one = 1, minus_one = -1;
  blas_int       info = 0;
  if (m > 0)
    {
      // W = L^-1 C_AJ; the joining cells' Schur complement C_JJ - W^T W
      dealii::trtrs("L", "N", "N", &mm, &kk, L.data(), &lda, work.data(), &mm, &info);
      dealii::syrk("L", "T", &kk, &mm, &minus_one, work.data(), &mm, &one, &L(m, m), &lda);
    }
  if (info == 0)
    dealii::potrf("L", &kk, &L(m, m), &lda, &info);
  if (info != 0)
    {
      if (!factorise(matrix, std::move(all)))
        throw InputError(not_positive_definite);
      return;
    }
  L.block(m, 0, k, m) = work.transpose();
  order               = std::move(all);
}

ContactSolution
solve_contact(const ContactProblem &p)
{
  if (!p.compliance.allFinite())
    throw InputError("contact solver: the compliance must be finite");
  return solve_contact(p.compliance, p.gap, p.lever, p.load);
}

ContactSolution
solve_contact(const Eigen::MatrixXd &compliance, const Eigen::VectorXd &gap,
              const Eigen::VectorXd &lever, double load, const std::vector<char> &start)
{
  const Eigen::Index n = gap.size();
  if (!start.empty() && Eigen::Index(start.size()) != n)
    throw InputError("contact solver: the warm start has " + std::to_string(start.size()) +
                     " entries for " + std::to_string(n) + " cells");
  std::vector<Eigen::Index> cells;
  for (Eigen::Index j = 0; j < Eigen::Index(start.size()); ++j)
    if (start[std::size_t(j)])
      cells.push_back(j);
  if (cells.empty() || load == 0 || compliance.rows() != n || compliance.cols() != n)
    return solve_contact(compliance, gap, lever, load, ActiveSetFactor());
  return solve_contact(compliance, gap, lever, load, ActiveSetFactor(compliance, cells));
}

ContactSolution
solve_contact(const Eigen::MatrixXd &compliance, const Eigen::VectorXd &gap,
              const Eigen::VectorXd &lever, double load, const ActiveSetFactor &start)
{
  const Eigen::Index n = gap.size();
  if (n == 0 || compliance.rows() != n || compliance.cols() != n || lever.size() != n)
    throw InputError("contact solver: compliance, gap and lever sizes differ (or are zero)");
  if (!(load >= 0) || !(lever.minCoeff() > 0) || !gap.allFinite())
    throw InputError("contact solver: the load must be >= 0, the levers > 0 and all data finite");

  ContactSolution s;
  s.force                           = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd first_touch = gap.cwiseQuotient(lever);
  Eigen::Index          first;
  s.approach = first_touch.minCoeff(&first);
  if (load == 0)
    return s;

  if (std::any_of(start.cells().begin(), start.cells().end(),
                  [n](Eigen::Index j) { return j < 0 || j >= n; }))
    throw InputError("contact solver: the warm start names a cell beyond the " + std::to_string(n) +
                     " cells");
  // The factor updated from the start's: each thread's own storage, reused from solve to solve
  // (no allocation, a copy of the start's block alone, made when the set first changes: a
  // start that is the solution's own is only read).
  thread_local ActiveSetFactor factor;
  const ActiveSetFactor       *current = &start;
  if (start.size() == 0)
    factor.assign(compliance, {first}), current = &factor;
  const auto changing = [&]() -> ActiveSetFactor & {
    if (current != &factor)
      factor.copy(*current), current = &factor;
    return factor;
  };
  std::vector<char> active(std::size_t(n), 0);
  for (const Eigen::Index j : current->cells())
    active[std::size_t(j)] = 1;
  const double      scale = std::max(gap.cwiseAbs().maxCoeff(), 1e-9);
  std::vector<char> leave(std::size_t(n), 0);
  for (int it = 0; it < 4 * n + 50; ++it)
    {
      const std::vector<Eigen::Index> &A = current->cells();
      const Eigen::Index               m = current->size();
      // x = C_AA^-1 [lever_A gap_A]; the approach from the load balance
      Eigen::MatrixXd x(m, 2);
      for (Eigen::Index a = 0; a < m; ++a)
        x(a, 0) = lever[A[std::size_t(a)]], x(a, 1) = gap[A[std::size_t(a)]];
      const Eigen::VectorXd lA = x.col(0);
      current->solve(x);
      s.approach               = (load + lA.dot(x.col(1))) / lA.dot(x.col(0));
      const Eigen::VectorXd FA = s.approach * x.col(0) - x.col(1);
      s.force.setZero();
      for (Eigen::Index a = 0; a < m; ++a)
        s.force[A[std::size_t(a)]] = FA[a];
      s.iterations             = it;
      const bool one_at_a_time = it > 2 * n; // cycling: change one cell per iteration

      // Tensile cells leave.
      Eigen::Index worst = -1;
      for (Eigen::Index a = 0; a < m; ++a)
        if (FA[a] < 0 && (worst < 0 || FA[a] < FA[worst]))
          worst = a;
      if (worst >= 0)
        {
          std::fill(leave.begin(), leave.end(), 0);
          for (Eigen::Index a = 0; a < m; ++a)
            if (one_at_a_time ? a == worst : FA[a] < 0)
              leave[std::size_t(A[std::size_t(a)])] = 1, active[std::size_t(A[std::size_t(a)])] = 0;
          // (the start's factor read, not copied: the rows after the first to leave are
          // computed anew anyway)
          factor.remove(compliance, leave, current == &factor ? nullptr : current);
          current = &factor;
          continue;
        }
      // Penetrating cells join, the deepest first: h = approach lever - gap - C F (the loaded
      // columns of C alone, four at a time: h read and written once for four of them).
      Eigen::VectorXd h      = s.approach * lever - gap;
      const auto      column = [&](Eigen::Index a) {
        return Eigen::Map<const Eigen::VectorXd>(compliance.data() + A[std::size_t(a)] * n, n);
      };
      Eigen::Index a = 0;
      for (; a + 4 <= m; a += 4)
        h.noalias() -= column(a) * FA[a] + column(a + 1) * FA[a + 1] + column(a + 2) * FA[a + 2] +
                       column(a + 3) * FA[a + 3];
      for (; a < m; ++a)
        h.noalias() -= column(a) * FA[a];
      std::vector<Eigen::Index> join;
      for (Eigen::Index j = 0; j < n; ++j)
        if (!active[std::size_t(j)] && h[j] > 1e-12 * scale)
          join.push_back(j);
      if (join.empty())
        {
          s.active     = int(m);
          s.active_set = active;
          for (Eigen::Index j = 0; j < n; ++j)
            if (!active[std::size_t(j)])
              s.penetration = std::max(s.penetration, h[j]);
          return s;
        }
      std::stable_sort(join.begin(), join.end(),
                       [&h](Eigen::Index a, Eigen::Index b) { return h[a] > h[b]; });
      if (one_at_a_time)
        join.resize(1);
      for (const Eigen::Index j : join)
        active[std::size_t(j)] = 1;
      changing().append(compliance, join);
    }
  std::ostringstream msg;
  msg << "contact solver: the active set did not settle after " << 4 * n + 50 << " iterations ("
      << n << " cells)";
  throw InputError(msg.str());
}
} // namespace gearkit

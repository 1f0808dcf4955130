// The contact solver's updated Cholesky factor against factorising anew, and its solution
// against brute force (every active set of a small problem) and the complementarity conditions.
#include "geometry/types.h"
#include "stiffness/contact_solver.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace gearkit;

namespace
{
/// A compliance like a contact zone's: cells on a grid, a smooth structural part and a
/// singular-like local part (exp(-r / l)), symmetric positive definite [m/N].
Eigen::MatrixXd
zone_like_compliance(int nx, int ny)
{
  const int       n = nx * ny;
  Eigen::MatrixXd C(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      {
        const double dx = (i % nx - j % nx) * 0.3, dy = (i / nx - j / nx) * 0.5;
        const double r = std::hypot(dx, dy);
        C(i, j)        = 1e-9 * (std::exp(-r / 0.4) + 0.2 * std::exp(-r * r / 20));
      }
  return C;
}

/// x = C_AA^-1 b by Eigen's Cholesky factorisation of the block, in `cells`' order.
Eigen::VectorXd
direct(const Eigen::MatrixXd &C, const std::vector<Eigen::Index> &cells, const Eigen::VectorXd &b)
{
  const Eigen::Index m = Eigen::Index(cells.size());
  Eigen::MatrixXd    block(m, m);
  for (Eigen::Index a = 0; a < m; ++a)
    for (Eigen::Index c = 0; c < m; ++c)
      block(a, c) = C(cells[std::size_t(a)], cells[std::size_t(c)]);
  return block.llt().solve(b);
}
} // namespace

TEST(ActiveSetFactor, UpdatesSolveAsAFactorisationAnew)
{
  const Eigen::MatrixXd     C = zone_like_compliance(12, 10);
  const Eigen::Index        n = C.rows();
  std::mt19937              random(7);
  std::vector<Eigen::Index> cells;
  for (Eigen::Index j = 0; j < n; j += 2)
    cells.push_back(j);
  std::shuffle(cells.begin(), cells.end(), random);
  ActiveSetFactor f(C, cells);
  // cells leave and join: a few at the end (updates), many anywhere (factorised anew)
  for (int step = 0; step < 40; ++step)
    {
      std::vector<char> in(std::size_t(n), 0), leave(std::size_t(n), 0);
      for (const Eigen::Index j : f.cells())
        in[std::size_t(j)] = 1;
      const int  changes = step % 5 == 0 ? 25 : 1 + step % 4;
      const auto size    = f.cells().size();
      for (int k = 0; k < changes && k < int(size) - 1; ++k)
        {
          // mostly among the last cells of the factor, now and then anywhere
          const std::size_t from =
              step % 3 == 0 ? 0 : size - std::min<std::size_t>(size, std::size_t(3 * changes));
          const std::size_t at              = from + std::size_t(random()) % (size - from);
          leave[std::size_t(f.cells()[at])] = 1;
        }
      f.remove(C, leave);
      for (const Eigen::Index j : f.cells())
        EXPECT_FALSE(leave[std::size_t(j)]);
      std::vector<Eigen::Index> join;
      for (Eigen::Index j = 0; j < n && int(join.size()) < changes; ++j)
        if (!in[std::size_t(j)] && random() % 3 == 0)
          join.push_back(j);
      f.append(C, join);
      EXPECT_TRUE(std::equal(join.begin(), join.end(), f.cells().end() - long(join.size())));

      Eigen::MatrixXd x(f.size(), 2);
      for (Eigen::Index a = 0; a < f.size(); ++a)
        x(a, 0) = 1 + 0.1 * double(a % 7), x(a, 1) = std::sin(double(a));
      const Eigen::VectorXd b0 = x.col(0), b1 = x.col(1);
      f.solve(x);
      const Eigen::VectorXd r0 = direct(C, f.cells(), b0), r1 = direct(C, f.cells(), b1);
      EXPECT_LT((x.col(0) - r0).norm(), 1e-11 * r0.norm()) << "step " << step;
      EXPECT_LT((x.col(1) - r1).norm(), 1e-11 * r1.norm()) << "step " << step;
    }
}

// A factor becoming another one less some cells (the solver's first change of a warm start)
// equals that other one copied and updated, in storage that held a different factor before
// (its stale entries above the diagonal are not read).
TEST(ActiveSetFactor, RemovalFromASourceEqualsACopyUpdated)
{
  const Eigen::MatrixXd     C = zone_like_compliance(12, 10);
  const Eigen::Index        n = C.rows();
  std::mt19937              random(11);
  std::vector<Eigen::Index> cells, other;
  for (Eigen::Index j = 0; j < n; ++j)
    (j % 3 == 0 ? cells : other).push_back(j);
  std::shuffle(cells.begin(), cells.end(), random);
  const ActiveSetFactor source(C, cells);
  for (int trial = 0; trial < 12; ++trial)
    {
      std::vector<char> leave(std::size_t(n), 0);
      const int         changes = trial == 0 ? 0 : 1 + trial % 6;
      for (int k = 0; k < changes; ++k) // near the end mostly (updates), now and then anywhere
        {
          const std::size_t from = trial % 4 == 0 ? 0 : cells.size() - 12;
          leave[std::size_t(cells[from + std::size_t(random()) % (cells.size() - from)])] = 1;
        }
      ActiveSetFactor copied;
      copied.copy(source);
      copied.remove(C, leave);
      ActiveSetFactor from(C, other); // storage holding another factor
      from.remove(C, leave, &source);
      ASSERT_EQ(from.cells(), copied.cells()) << "trial " << trial;
      Eigen::MatrixXd x(from.size(), 1);
      for (Eigen::Index a = 0; a < from.size(); ++a)
        x(a, 0) = 1 + 0.1 * double(a % 5);
      const Eigen::VectorXd b = x.col(0);
      Eigen::MatrixXd       y = x;
      from.solve(x);
      copied.solve(y);
      const Eigen::VectorXd r = direct(C, from.cells(), b);
      EXPECT_LT((x.col(0) - r).norm(), 1e-11 * r.norm()) << "trial " << trial;
      EXPECT_LT((x - y).norm(), 1e-13 * r.norm()) << "trial " << trial;
    }
}

TEST(ActiveSetFactor, NotPositiveDefiniteIsRefused)
{
  Eigen::MatrixXd C = Eigen::MatrixXd::Identity(3, 3);
  C(0, 1) = C(1, 0) = 2; // eigenvalues -1, 1, 3
  EXPECT_THROW(ActiveSetFactor(C, {0, 1}), InputError);
  ActiveSetFactor f(C, {0, 2});
  EXPECT_THROW(f.append(C, {1}), InputError);
}

TEST(ContactSolver, WarmStartsGiveTheSolutionOfBruteForce)
{
  // a small zone: every active set tried, the one meeting the complementarity conditions
  // (F >= 0 on it, no penetration off it) is the solution
  const Eigen::MatrixXd C = zone_like_compliance(4, 3);
  const Eigen::Index    n = C.rows();
  Eigen::VectorXd       gap(n), lever(n);
  for (Eigen::Index j = 0; j < n; ++j)
    {
      const double s = (double(j % 4) - 1.6) * 0.3, t = (double(j / 4) - 0.8) * 0.5;
      gap[j]   = 2e-6 * s * s + 0.5e-6 * t * t + 0.1e-6 * std::cos(double(7 * j));
      lever[j] = 0.03 + 0.002 * t;
    }
  const double    load = 40; // N m
  ContactSolution brute;
  int             found = 0;
  for (long mask = 1; mask < (1L << n); ++mask)
    {
      std::vector<Eigen::Index> A;
      for (Eigen::Index j = 0; j < n; ++j)
        if (mask >> j & 1)
          A.push_back(j);
      Eigen::VectorXd lA(Eigen::Index(A.size())), gA(Eigen::Index(A.size()));
      for (std::size_t a = 0; a < A.size(); ++a)
        lA[Eigen::Index(a)] = lever[A[a]], gA[Eigen::Index(a)] = gap[A[a]];
      const Eigen::VectorXd x1 = direct(C, A, lA), x2 = direct(C, A, gA);
      const double          approach = (load + lA.dot(x2)) / lA.dot(x1);
      const Eigen::VectorXd FA       = approach * x1 - x2;
      if (FA.minCoeff() < 0)
        continue;
      Eigen::VectorXd F = Eigen::VectorXd::Zero(n);
      for (std::size_t a = 0; a < A.size(); ++a)
        F[A[a]] = FA[Eigen::Index(a)];
      const Eigen::VectorXd h  = approach * lever - gap - C * F;
      bool                  ok = true;
      for (Eigen::Index j = 0; j < n; ++j)
        ok = ok && (F[j] > 0 || h[j] <= 1e-12 * gap.cwiseAbs().maxCoeff());
      if (ok)
        brute.force = F, brute.approach = approach, ++found;
    }
  ASSERT_EQ(found, 1); // a strictly convex problem: one solution
  ASSERT_GT((brute.force.array() > 0).count(), 2);

  const ContactSolution cold = solve_contact(C, gap, lever, load);
  EXPECT_NEAR(cold.approach, brute.approach, 1e-12 * std::abs(brute.approach));
  EXPECT_LT((cold.force - brute.force).norm(), 1e-10 * brute.force.norm());
  // from factors of other sets (every cell, the far cells, a single cell) in any order
  std::vector<Eigen::Index> all(static_cast<std::size_t>(n)), far;
  for (Eigen::Index j = 0; j < n; ++j)
    all[std::size_t(j)] = n - 1 - j;
  for (Eigen::Index j = 0; j < n; ++j)
    if (brute.force[j] == 0)
      far.push_back(j);
  for (const std::vector<Eigen::Index> &start : {all, far, std::vector<Eigen::Index>{5}})
    {
      const ContactSolution warm = solve_contact(C, gap, lever, load, ActiveSetFactor(C, start));
      EXPECT_NEAR(warm.approach, brute.approach, 1e-12 * std::abs(brute.approach));
      EXPECT_LT((warm.force - brute.force).norm(), 1e-10 * brute.force.norm());
      EXPECT_EQ(warm.active, (brute.force.array() > 0).count());
    }
  EXPECT_THROW(
      solve_contact(C, gap, lever, load, ActiveSetFactor(zone_like_compliance(5, 3), {14})),
      InputError); // a cell beyond the zone
}

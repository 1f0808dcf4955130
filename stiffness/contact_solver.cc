#include "stiffness/contact_solver.h"

#include "geometry/types.h"

#include <deal.II/lac/lapack_templates.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace gearkit
{
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
  const struct
  {
    const Eigen::MatrixXd &compliance;
    const Eigen::VectorXd &gap, &lever;
    double                 load;
  } p{compliance, gap, lever, load};
  const Eigen::Index n = p.gap.size();
  if (n == 0 || p.compliance.rows() != n || p.compliance.cols() != n || p.lever.size() != n)
    throw InputError("contact solver: compliance, gap and lever sizes differ (or are zero)");
  if (!(p.load >= 0) || !(p.lever.minCoeff() > 0) || !p.gap.allFinite())
    throw InputError("contact solver: the load must be >= 0, the levers > 0 and all data finite");

  ContactSolution s;
  s.force                           = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd first_touch = p.gap.cwiseQuotient(p.lever);
  Eigen::Index          first;
  s.approach = first_touch.minCoeff(&first);
  if (p.load == 0)
    return s;

  if (!start.empty() && Eigen::Index(start.size()) != n)
    throw InputError("contact solver: the warm start has " + std::to_string(start.size()) +
                     " entries for " + std::to_string(n) + " cells");
  std::vector<char> active(n, 0);
  if (std::any_of(start.begin(), start.end(), [](char c) { return c != 0; }))
    for (Eigen::Index j = 0; j < n; ++j)
      active[j] = start[j] != 0;
  else
    active[first] = 1;
  const double scale = std::max(p.gap.cwiseAbs().maxCoeff(), 1e-9);
  for (int it = 0; it < 4 * n + 50; ++it)
    {
      std::vector<Eigen::Index> A;
      for (Eigen::Index j = 0; j < n; ++j)
        if (active[j])
          A.push_back(j);
      const Eigen::Index m = Eigen::Index(A.size());
      Eigen::MatrixXd    C(m, m);
      Eigen::VectorXd    lA(m), gA(m);
      for (Eigen::Index b = 0; b < m; ++b)
        {
          lA[b] = p.lever[A[b]], gA[b] = p.gap[A[b]];
          for (Eigen::Index a = b; a < m; ++a) // the lower triangle
            C(a, b) = p.compliance(A[a], A[b]);
        }
      // LAPACK's Cholesky factorisation and solve (OpenBLAS's kernels for this processor):
      // x = C^-1 [lA gA]
      Eigen::MatrixXd               x(m, 2);
      const dealii::types::blas_int size = dealii::types::blas_int(m), columns = 2;
      dealii::types::blas_int       info = 0;
      x << lA, gA;
      dealii::potrf("L", &size, C.data(), &size, &info);
      if (info != 0)
        throw InputError("contact solver: the compliance matrix is not positive definite");
      dealii::potrs("L", &size, &columns, C.data(), &size, x.data(), &size, &info);
      const Eigen::VectorXd x1 = x.col(0), x2 = x.col(1);
      s.approach               = (p.load + lA.dot(x2)) / lA.dot(x1);
      const Eigen::VectorXd FA = s.approach * x1 - x2;
      s.force.setZero();
      for (Eigen::Index a = 0; a < m; ++a)
        s.force[A[a]] = FA[a];
      s.iterations             = it;
      const bool one_at_a_time = it > 2 * n; // cycling: change one cell per iteration

      // Tensile cells leave.
      Eigen::Index worst = -1;
      for (Eigen::Index a = 0; a < m; ++a)
        if (FA[a] < 0 && (worst < 0 || FA[a] < FA[worst]))
          worst = a;
      if (worst >= 0)
        {
          for (Eigen::Index a = 0; a < m; ++a)
            if (one_at_a_time ? a == worst : FA[a] < 0)
              active[A[a]] = 0;
          continue;
        }
      // Penetrating cells join: h = approach lever - gap - C F (the loaded columns of C alone).
      Eigen::VectorXd h = s.approach * p.lever - p.gap;
      for (Eigen::Index a = 0; a < m; ++a)
        h.noalias() -= p.compliance.col(A[a]) * FA[a];
      Eigen::Index deepest = -1;
      for (Eigen::Index j = 0; j < n; ++j)
        if (!active[j] && h[j] > 1e-12 * scale && (deepest < 0 || h[j] > h[deepest]))
          deepest = j;
      if (deepest < 0)
        {
          s.active      = int(m);
          s.active_set  = active;
          s.penetration = 0;
          for (Eigen::Index j = 0; j < n; ++j)
            if (!active[j])
              s.penetration = std::max(s.penetration, h[j]);
          return s;
        }
      for (Eigen::Index j = 0; j < n; ++j)
        if (!active[j] && (one_at_a_time ? j == deepest : h[j] > 1e-12 * scale))
          active[j] = 1;
    }
  std::ostringstream msg;
  msg << "contact solver: the active set did not settle after " << 4 * n + 50 << " iterations ("
      << n << " cells)";
  throw InputError(msg.str());
}
} // namespace gearkit

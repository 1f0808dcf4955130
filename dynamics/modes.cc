#include "dynamics/modes.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gearkit
{
PairModes
linear_modes(const PairModel &model)
{
  const MeshState  m  = model.mesh().mean();
  const PairVector g  = PairModel::mesh_gradient(m);
  const PairMatrix Km = m.km * g * g.transpose();
  const PairMatrix K  = model.stiffness() + Km;
  // on the free DOFs (a speed-controlled motor, a torsional model hold the others)
  const std::vector<int> index = model.free_dofs();
  const int              n     = int(index.size());
  Eigen::MatrixXd        Kr(n, n), Mr(n, n), Kmr(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      Kr(i, j) = K(index[i], index[j]), Mr(i, j) = model.mass()(index[i], index[j]),
            Kmr(i, j) = Km(index[i], index[j]);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kr, Mr);
  if (eig.info() != Eigen::Success)
    throw InputError(
        "pair dynamics: the modal analysis failed (mass matrix not positive definite?)");
  PairModes out;
  out.shapes = Eigen::MatrixXd::Zero(pair_dofs, n);
  for (int i = 0; i < n; ++i)
    {
      for (int k = 0; k < n; ++k)
        out.shapes(index[k], i) = eig.eigenvectors()(k, i);
      const double w2 = std::max(0.0, eig.eigenvalues()[i]);
      out.frequency.push_back(std::sqrt(w2) / (2 * pi));
      const Eigen::VectorXd phi   = eig.eigenvectors().col(i);
      const double          total = phi.dot(Kr * phi);
      // the rigid rotation (0 Hz) strains nothing: no share
      out.mesh_energy.push_back(
          w2 > 1e-6 * eig.eigenvalues().maxCoeff() && total > 0 ? phi.dot(Kmr * phi) / total : 0.0);
    }
  return out;
}

std::vector<std::complex<double>>
floquet_multipliers(const PairModel &model, const RunOptions &run)
{
  // the model in contact: no backlash, so the mesh force is linear on both sides and a
  // perturbation's response is the difference of two runs, exactly
  PairModelParameters p          = model.parameters();
  p.half_backlash                = 0;
  p.mesh_damping_in_contact_only = false;
  const PairModel linear(p, model.tables());
  RunOptions      o            = run;
  o.mesh_cycles                = model.mesh().cycles(); // one period of the tables
  o.samples_per_cycle          = 1;
  const PairVector       q0    = linear.static_equilibrium(o.load_torque).q;
  const Trajectory       base  = simulate(linear, q0, PairVector::Zero(), o);
  const std::vector<int> index = model.free_dofs();
  const int              n     = int(index.size());
  // perturbations of the static deflection's order (exact for any size: linear), per DOF
  const PairVector scale = linear.dof_scale(1e-6);
  const double     rate  = model.parameters().pinion_teeth * o.omega; // [rad/s]
  Eigen::MatrixXd  Phi(2 * n, 2 * n);
  for (int j = 0; j < 2 * n; ++j)
    {
      PairVector dq = PairVector::Zero(), dv = PairVector::Zero();
      const int  i         = index[std::size_t(j % n)];
      (j < n ? dq : dv)[i] = j < n ? scale[i] : rate * scale[i];
      const Trajectory t   = simulate(linear, q0 + dq, dv, o);
      for (int k = 0; k < n; ++k) // in the same scaled coordinates
        {
          const int d   = index[std::size_t(k)];
          Phi(k, j)     = (t.q.back()[d] - base.q.back()[d]) / scale[d];
          Phi(n + k, j) = (t.v.back()[d] - base.v.back()[d]) / (rate * scale[d]);
        }
    }
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(Phi, false);
  std::vector<std::complex<double>>         mu(eig.eigenvalues().begin(), eig.eigenvalues().end());
  std::sort(mu.begin(), mu.end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  return mu;
}
} // namespace gearkit

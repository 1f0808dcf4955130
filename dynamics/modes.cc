#include "modes.h"

#include <Eigen/Eigenvalues>

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
  std::vector<int> index;
  for (int i = 0; i < pair_dofs; ++i)
    if (model.active()[i] > 0)
      index.push_back(i);
  const int       n = int(index.size());
  Eigen::MatrixXd Kr(n, n), Mr(n, n), Kmr(n, n);
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
} // namespace gearkit

#include "modes.h"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace gearkit
{
PairModes
linear_modes(const PairModel &model)
{
  const MeshState  m = model.mesh().mean();
  const PairVector g = PairModel::mesh_gradient(m);
  const PairMatrix Km = m.km * g * g.transpose();
  const PairMatrix K  = model.stiffness() + Km;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, model.mass());
  if (eig.info() != Eigen::Success)
    throw InputError("pair dynamics: the modal analysis failed (mass matrix not positive definite?)");
  PairModes out;
  out.shapes = eig.eigenvectors();
  for (int i = 0; i < pair_dofs; ++i)
    {
      const double w2 = std::max(0.0, eig.eigenvalues()[i]);
      out.frequency.push_back(std::sqrt(w2) / (2 * pi));
      const Eigen::VectorXd phi = out.shapes.col(i);
      const double          total = phi.dot(K * phi);
      // the rigid rotation (0 Hz) strains nothing: no share
      out.mesh_energy.push_back(w2 > 1e-6 * eig.eigenvalues().maxCoeff() && total > 0
                                    ? phi.dot(Km * phi) / total
                                    : 0.0);
    }
  return out;
}
} // namespace gearkit

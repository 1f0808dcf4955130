#include "dynamics/newmark_error.h"

#include "base/spectrum.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace gearkit
{
NewmarkError::NewmarkError(const PairModel &model, double load_torque, Evaluation evaluation)
    : pinion_teeth(model.parameters().pinion_teeth)
{
  const std::vector<int> index = model.free_dofs();
  const int              n     = int(index.size());
  const MeshState        m0    = model.mesh().mean();
  const PairVector       g0    = PairModel::mesh_gradient(m0);
  const double           cm    = model.mesh_damping();
  const PairMatrix       Kt    = model.stiffness() + m0.km * g0 * g0.transpose();
  const PairMatrix       Ct    = model.damping() + cm * g0 * g0.transpose();
  M.resize(n, n), C.resize(n, n), K.resize(n, n), g.resize(n);
  for (int i = 0; i < n; ++i)
    {
      g[i] = g0[index[i]];
      for (int j = 0; j < n; ++j)
        M(i, j) = model.mass()(index[i], index[j]), C(i, j) = Ct(index[i], index[j]),
             K(i, j) = Kt(index[i], index[j]);
    }
  if (evaluation == Evaluation::modal)
    modal = damped_modes();

  // the forcing over one period of the tables, eight times as densely sampled as they are
  // (their products and a makima interpolant's kinks reach beyond the tables' own orders)
  const PairVector  qs      = model.static_equilibrium(load_torque).q;
  const double      b       = model.parameters().half_backlash;
  const int         cycles  = model.mesh().cycles();
  const std::size_t samples = 8 * std::max<std::size_t>(model.tables().mesh_stiffness.size(), 8);
  const std::vector<double>        zero(samples, 0.0);
  std::vector<std::vector<double>> force(std::size_t(n), zero), damping(std::size_t(n), zero);
  std::vector<double>              kinematic = zero;
  for (std::size_t s = 0; s < samples; ++s)
    {
      const MeshState  m  = model.mesh().at(double(cycles) * double(s) / double(samples));
      const PairVector gm = PairModel::mesh_gradient(m);
      const double     F0 = m.km * (gm.dot(qs) - m.et - b);
      kinematic[s]        = gm.dot(qs);
      for (int i = 0; i < n; ++i)
        force[std::size_t(i)][s]   = -gm[index[i]] * F0,
        damping[std::size_t(i)][s] = cm * gm[index[i]] * m.det;
    }
  std::vector<std::vector<Complex>> fc, dc;
  for (int i = 0; i < n; ++i)
    fc.push_back(fourier_coefficients(force[std::size_t(i)])),
        dc.push_back(fourier_coefficients(damping[std::size_t(i)]));
  const std::vector<Complex> kc = fourier_coefficients(kinematic);
  // harmonics with content (below 1e-7 of the largest - at most 1e-6 of the response even at
  // a resonance - left out)
  double largest = 0, kinematic_largest = 0;
  for (std::size_t k = 1; k < kc.size(); ++k)
    kinematic_largest = std::max(kinematic_largest, std::abs(kc[k]));
  for (int i = 0; i < n; ++i)
    for (std::size_t k = 1; k < fc[std::size_t(i)].size(); ++k)
      largest = std::max(largest, std::abs(fc[std::size_t(i)][k]) * std::abs(g[i]));
  for (std::size_t k = 1; k < kc.size(); ++k)
    {
      Harmonic h;
      h.order = double(k) / cycles;
      h.force.resize(n), h.damping.resize(n);
      double size = 0;
      for (int i = 0; i < n; ++i)
        {
          h.force[i] = fc[std::size_t(i)][k], h.damping[i] = dc[std::size_t(i)][k];
          size = std::max(size, std::abs(h.force[i]) * std::abs(g[i]));
        }
      h.kinematic = kc[k];
      if (!(size > 1e-7 * largest || std::abs(h.kinematic) > 1e-7 * kinematic_largest))
        continue;
      if (modal)
        h.modal_force = project(h.force), h.modal_damping = project(h.damping);
      harmonics.push_back(std::move(h));
    }
}

bool
NewmarkError::damped_modes()
{
  // the undamped modes; the rigid ones (the whole train turning: neither forced nor seen by
  // the mesh, g . r = 0) left out, the others M-normalised
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> undamped(K, M);
  if (undamped.info() != Eigen::Success)
    return false;
  const Eigen::VectorXd w2  = undamped.eigenvalues();
  const double          top = w2.cwiseAbs().maxCoeff();
  std::vector<int>      flexible;
  for (int i = 0; i < int(w2.size()); ++i)
    if (w2[i] > 1e-10 * top)
      flexible.push_back(i);
  const int       m = int(flexible.size());
  Eigen::MatrixXd Phi(M.rows(), m);
  for (int i = 0; i < m; ++i)
    Phi.col(i) = undamped.eigenvectors().col(flexible[std::size_t(i)]);
  // first order in the modal coordinates: y'' + D y' + W^2 y = Phi^T f
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  A.topRightCorner(m, m).setIdentity();
  A.bottomRightCorner(m, m) = -Phi.transpose() * C * Phi;
  for (int i = 0; i < m; ++i)
    A(m + i, i) = -w2[flexible[std::size_t(i)]];
  const Eigen::EigenSolver<Eigen::MatrixXd> damped(A);
  if (damped.info() != Eigen::Success)
    return false;
  const Eigen::MatrixXcd V    = damped.eigenvectors();
  const Eigen::MatrixXcd Vinv = V.inverse();
  poles                       = damped.eigenvalues();
  // a defective pair of poles (critical damping) would not be told apart: check A back
  const Eigen::MatrixXcd back = V * poles.asDiagonal() * Vinv;
  if (!((back - A.cast<Complex>()).norm() <= 1e-9 * A.norm()) || !Vinv.allFinite())
    return false;
  // g^T x = sum_r left_r right_r(f) / (s - pole_r)
  into_modes = Vinv.rightCols(m) * Phi.transpose().cast<Complex>();
  left       = (g.transpose() * Phi).cast<Complex>() * V.topRows(m);
  g_modal    = project(g.cast<Complex>());
  return true;
}

Eigen::VectorXcd
NewmarkError::project(const Eigen::VectorXcd &f) const
{
  return into_modes * f;
}

NewmarkError::Complex
NewmarkError::transfer(const Eigen::VectorXcd &f, const Eigen::VectorXcd &modal_f, double w) const
{
  const Complex s(0, w);
  if (modal)
    {
      Complex sum = 0;
      for (Eigen::Index r = 0; r < poles.size(); ++r)
        sum += left[r] * modal_f[r] / (s - poles[r]);
      return sum;
    }
  const Eigen::MatrixXcd A =
      (s * s) * M.cast<Complex>() + s * C.cast<Complex>() + K.cast<Complex>();
  return g.cast<Complex>().dot(A.partialPivLu().solve(f)); // g real: dot = g^T
}

NewmarkError::Complex
NewmarkError::transfer(const Harmonic &h, double f_mesh, double w) const
{
  return transfer(
      h.force + f_mesh * h.damping,
      modal ? Eigen::VectorXcd(h.modal_force + f_mesh * h.modal_damping) : Eigen::VectorXcd(), w);
}

double
NewmarkError::warped(double order, int steps, double f_mesh)
{
  if (2 * order >= steps)
    return std::numeric_limits<double>::infinity();
  return 2 * steps * f_mesh * std::tan(pi * order / steps);
}

NewmarkError::AtSpeed
NewmarkError::at_speed(double omega) const
{
  AtSpeed a;
  a.owner  = this;
  a.f_mesh = pinion_teeth * std::abs(omega) / (2 * pi);
  for (const Harmonic &h : harmonics)
    {
      const Complex d = transfer(h, a.f_mesh, 2 * pi * a.f_mesh * h.order);
      a.dynamic.push_back(d);
      a.energy += std::norm(h.kinematic + d);
    }
  return a;
}

double
NewmarkError::AtSpeed::error(int steps) const
{
  double e = 0;
  for (std::size_t k = 0; k < dynamic.size(); ++k)
    {
      const Harmonic &h = owner->harmonics[k];
      const double    o = h.order;
      if (2 * o < steps) // in place, at the warped frequency
        {
          e += std::norm(owner->transfer(h, f_mesh, warped(o, steps, f_mesh)) - dynamic[k]);
          continue;
        }
      // at or above the Nyquist order: sampled at the steps, the force is one of the order it
      // folds to (conjugate when it folds from above), answered there - perhaps near a mode -
      // and lost where it belongs
      e += std::norm(dynamic[k]);
      double     folded = std::fmod(o, double(steps));
      const bool mirror = 2 * folded > steps;
      if (mirror)
        folded = steps - folded;
      if (folded < 1e-9 || 2 * folded >= steps) // a constant (the mean) or a sampled zero
        continue;
      // a real model: g^T H(s) conj(f) = conj(g^T H(conj s) f)
      const double w = warped(folded, steps, f_mesh);
      e += std::norm(owner->transfer(h, f_mesh, mirror ? -w : w));
    }
  return energy > 0 ? std::sqrt(e / energy) : 0.0;
}

double
NewmarkError::forced(double omega, int steps) const
{
  return at_speed(omega).error(steps);
}

int
NewmarkError::steps(double omega, double accuracy, int least, int multiple, int most) const
{
  require_value(accuracy > 0 && accuracy < 1, "pair dynamics", "accuracy", accuracy, "in (0, 1)");
  require_value(least >= 1, "Newmark steps", "least steps per mesh cycle", least, ">= 1");
  require_value(multiple >= 1, "Newmark steps", "multiple of the steps per mesh cycle", multiple,
                ">= 1");
  require_value(most >= least, "Newmark steps", "least steps per mesh cycle", least,
                "at most the most steps per mesh cycle, " + std::to_string(most));
  const auto up = [&](double s) { // to a multiple, within [least, most]
    const int n = multiple * int(std::ceil(std::min(s, double(most)) / multiple));
    return std::clamp(n, multiple * ((least + multiple - 1) / multiple), std::max(most, least));
  };
  const AtSpeed a = at_speed(omega);
  // the error falls as steps^-2 once the harmonics are resolved (faster while orders alias):
  // aim there, walk up, then halve the interval to the fewest steps that pass
  int lo = 0, hi = up(least);
  for (int tries = 0; tries < 40; ++tries)
    {
      const double e = a.error(hi);
      if (e <= accuracy || hi >= most)
        break;
      lo = hi;
      hi = std::max(up(hi * std::min(4.0, 1.05 * std::sqrt(e / accuracy))), up(hi + multiple));
    }
  while (lo > 0 && hi - lo > multiple)
    {
      const int mid                        = lo + multiple * ((hi - lo) / multiple / 2);
      (a.error(mid) <= accuracy ? hi : lo) = mid;
    }
  return hi;
}

double
NewmarkError::recorded(double omega, int steps, const std::vector<double> &dte, int cycles,
                       double resolution) const
{
  std::vector<Complex> c      = fourier_coefficients(dte);
  double               energy = 0; // of delta_D about its mean
  for (std::size_t k = 1; k < c.size(); ++k)
    energy += std::norm(c[k]);
  if (!(energy > 0))
    return 0;
  // less the kinematic harmonics g(phase) . q_s (the record starts at phase 0), folded where
  // the record's sampling aliases them: no integrator error in those
  const long L = long(dte.size());
  for (const Harmonic &h : harmonics)
    {
      const double at = h.order * cycles;
      if (std::abs(at - std::round(at)) > 1e-9 * std::max(1.0, at))
        continue; // not a whole number of its periods in the record
      const long b = std::lround(at) % L;
      if (b == 0)
        continue;
      if (2 * b == L) // the Nyquist bin holds the cosine only
        c[std::size_t(b)] -= h.kinematic.real();
      else if (2 * b < L)
        c[std::size_t(b)] -= h.kinematic;
      else
        c[std::size_t(L - b)] -= std::conj(h.kinematic);
    }
  std::vector<std::size_t> order(c.size() - 1);
  std::iota(order.begin(), order.end(), std::size_t(1));
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return std::norm(c[i]) > std::norm(c[j]); });
  double left = 0;
  for (std::size_t k : order)
    left += std::norm(c[k]);
  const double f_mesh = pinion_teeth * std::abs(omega) / (2 * pi);
  const auto   G      = [&](double w) { return transfer(g.cast<Complex>(), g_modal, w); };
  double       e      = 0;
  for (std::size_t k : order)
    {
      if (left <= resolution * resolution * 0.01 * energy)
        {
          e += left; // the small rest: counted as wholly wrong
          break;
        }
      left -= std::norm(c[k]);
      const double o = double(k) / cycles, w = 2 * pi * f_mesh * o, ww = warped(o, steps, f_mesh);
      e += std::isfinite(ww) ? std::norm(c[k]) * std::norm(1.0 - G(w) / G(ww)) : std::norm(c[k]);
    }
  return std::sqrt(e / energy);
}
} // namespace gearkit

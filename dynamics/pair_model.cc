#include "dynamics/pair_model.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace gearkit
{
namespace
{
Eigen::Matrix3d
cross_matrix(const Vec3 &a)
{
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

void
require(bool ok, const std::string &parameter, double value, const std::string &allowed)
{
  require_value(ok, "pair dynamics", parameter, value, allowed);
}

/// One body's mass, support stiffness and damping into the 14 x 14 matrices at `offset`.
void
add_body(const BodyParameters &b, const std::string &name, int offset, PairMatrix &M, PairMatrix &K,
         PairMatrix &C)
{
  require(b.mass > 0, name + " mass [kg]", b.mass, "> 0");
  require(b.axial_inertia > 0, name + " axial inertia [kg m^2]", b.axial_inertia, "> 0");
  require(b.transverse_inertia > 0, name + " transverse inertia [kg m^2]", b.transverse_inertia,
          "> 0");
  require(std::abs(b.axis.norm() - 1) < 1e-9, name + " axis length", b.axis.norm(), "1");
  require(b.bearings.size() >= 1, name + " radial bearings", double(b.bearings.size()),
          "at least one (two hold the tilt)");
  require(b.axial_stiffness >= 0 && b.axial_damping >= 0, name + " axial stiffness / damping",
          std::min(b.axial_stiffness, b.axial_damping), ">= 0");
  const Vec3           &a       = b.axis;
  const Eigen::Matrix3d P       = Eigen::Matrix3d::Identity() - a * a.transpose();
  M.block<3, 3>(offset, offset) = b.mass * Eigen::Matrix3d::Identity();
  M.block<3, 3>(offset + 3, offset + 3) =
      b.transverse_inertia * P + b.axial_inertia * a * a.transpose();
  for (const RadialBearing &r : b.bearings)
    {
      require(r.stiffness >= 0 && r.damping >= 0, name + " bearing stiffness / damping",
              std::min(r.stiffness, r.damping), ">= 0");
      // displacement at the bearing: d + Theta x (s a) = d - s [a]x Theta; radial part only
      Eigen::Matrix<double, 3, 6> B;
      B << Eigen::Matrix3d::Identity(), -r.position * cross_matrix(a);
      K.block<6, 6>(offset, offset) += r.stiffness * B.transpose() * P * B;
      C.block<6, 6>(offset, offset) += r.damping * B.transpose() * P * B;
    }
  K.block<3, 3>(offset, offset) += b.axial_stiffness * a * a.transpose();
  C.block<3, 3>(offset, offset) += b.axial_damping * a * a.transpose();
}
} // namespace

PairModel::PairModel(const PairModelParameters &parameters, const MeshCycleSamples &tables)
    : p(parameters)
    , samples(tables)
    , cycle(tables)
    , M(PairMatrix::Zero())
    , K(PairMatrix::Zero())
    , C(PairMatrix::Zero())
{
  require(p.motor_inertia >= 0, "motor inertia [kg m^2]", p.motor_inertia,
          ">= 0 (0: no motor DOF)");
  require(p.load_inertia >= 0, "load inertia [kg m^2]", p.load_inertia, ">= 0 (0: no load DOF)");
  require(p.pinion_teeth >= 1, "pinion teeth", p.pinion_teeth, ">= 1");
  require(p.half_backlash >= 0, "half backlash [m]", p.half_backlash, ">= 0");
  require(p.mesh_damping_ratio >= 0, "mesh damping ratio", p.mesh_damping_ratio, ">= 0");
  add_body(p.gear, "gear", dof::gear, M, K, C);
  add_body(p.pinion, "pinion", dof::pinion, M, K, C);
  free = PairVector::Ones();
  if (p.torsion_only)
    for (int o : {dof::gear, dof::gear_rotation, dof::pinion, dof::pinion_rotation})
      free.segment<3>(o).setZero();
  if (p.torsion_only) // each body turns about its own axis only
    {
      for (int k = 0; k < 3; ++k)
        {
          free[dof::pinion_rotation + k] = std::abs(p.pinion.axis[k]) == 1 ? 1 : 0;
          free[dof::gear_rotation + k]   = std::abs(p.gear.axis[k]) == 1 ? 1 : 0;
        }
      require(free.segment<3>(dof::pinion_rotation).sum() == 1 &&
                  free.segment<3>(dof::gear_rotation).sum() == 1,
              "torsional model: body axes along global axes", 0, "unit axes along X, Y or Z");
    }
  free[dof::motor]          = p.motor_inertia > 0 && !p.speed_controlled_motor ? 1 : 0;
  free[dof::load]           = p.load_inertia > 0 ? 1 : 0;
  M(dof::motor, dof::motor) = p.motor_inertia > 0 ? p.motor_inertia : 1; // held if 0
  M(dof::load, dof::load)   = p.load_inertia > 0 ? p.load_inertia : 1;
  // shafts: motor - pinion (theta_E - a_p . Theta_p), gear - load (a_g . Theta_g - theta_L)
  auto shaft = [&](const ShaftParameters &s, int end, int body, const Vec3 &axis, double sign,
                   const std::string &name) {
    require(s.stiffness >= 0 && s.damping >= 0, name + " shaft stiffness / damping",
            std::min(s.stiffness, s.damping), ">= 0");
    PairVector w       = PairVector::Zero();
    w[end]             = sign;
    w.segment<3>(body) = -sign * axis;
    K += s.stiffness * w * w.transpose();
    C += s.damping * w * w.transpose();
  };
  if (p.motor_inertia > 0)
    shaft(p.motor_shaft, dof::motor, dof::pinion_rotation, p.pinion.axis, 1, "motor");
  if (free[dof::load] > 0)
    shaft(p.load_shaft, dof::load, dof::gear_rotation, p.gear.axis, -1, "load");
  const MeshState  m0 = cycle.mean();
  const PairVector g  = mesh_gradient(m0).cwiseProduct(free);
  m_e                 = 1 / g.dot(M.ldlt().solve(g));
  c_m                 = 2 * p.mesh_damping_ratio * std::sqrt(m0.km * m_e);
}

PairVector
PairModel::mesh_gradient(const MeshState &m)
{
  PairVector g                       = PairVector::Zero();
  g.segment<3>(dof::gear)            = -m.ng;
  g.segment<3>(dof::gear_rotation)   = -m.lg;
  g.segment<3>(dof::pinion)          = m.np;
  g.segment<3>(dof::pinion_rotation) = m.lp;
  return g;
}

PairVector
PairModel::dof_scale(double length) const
{
  const MeshState m   = cycle.mean();
  const double    arm = std::max({m.lp.norm(), m.lg.norm(), 1e-3});
  PairVector      s   = PairVector::Constant(length);
  for (int i : {dof::motor, dof::load})
    s[i] = length / arm;
  for (int k = 0; k < 3; ++k)
    s[dof::gear_rotation + k] = s[dof::pinion_rotation + k] = length / arm;
  return s;
}

double
PairModel::phase(double t, double omega) const
{
  return p.pinion_teeth * omega * t / (2 * pi);
}

double
PairModel::mesh_force(const MeshState &m, double delta, double delta_rate, double et_rate) const
{
  const double x = delta - m.et, b = p.half_backlash;
  const double damping = c_m * (delta_rate - et_rate);
  if (x >= b)
    return m.km * (x - b) + damping;
  if (x <= -b)
    return m.km * (x + b) + damping;
  return p.mesh_damping_in_contact_only ? 0.0 : damping;
}

PairVector
PairModel::torques(double motor_torque, double load_torque) const
{
  PairVector F = PairVector::Zero();
  if (free[dof::motor] > 0)
    F[dof::motor] = motor_torque;
  else if (!(p.motor_inertia > 0)) // no motor: its torque acts on the pinion
    F.segment<3>(dof::pinion_rotation) = motor_torque * p.pinion.axis;
  if (free[dof::load] > 0)
    F[dof::load] = -load_torque;
  else
    F.segment<3>(dof::gear_rotation) = -load_torque * p.gear.axis;
  return F;
}

PairVector
PairModel::acceleration(double t, const PairVector &q, const PairVector &qd, double omega,
                        double motor_torque, double load_torque) const
{
  const MeshState  m       = cycle.at(phase(t, omega));
  const PairVector g       = mesh_gradient(m);
  const double     et_rate = m.det * p.pinion_teeth * omega / (2 * pi);
  const double     Fm      = mesh_force(m, g.dot(q), g.dot(qd), et_rate);
  const PairVector F       = torques(motor_torque, load_torque) - K * q - C * qd - g * Fm;
  // M is block diagonal: scalars and 3 x 3 blocks
  PairVector a;
  a[dof::motor] = F[dof::motor] / M(dof::motor, dof::motor);
  a[dof::load]  = F[dof::load] / M(dof::load, dof::load);
  for (int o : {dof::gear, dof::gear_rotation, dof::pinion, dof::pinion_rotation})
    a.segment<3>(o) = M.block<3, 3>(o, o).ldlt().solve(F.segment<3>(o));
  return a.cwiseProduct(free); // held DOFs stay where they are
}

StaticEquilibrium
PairModel::static_equilibrium(double load_torque) const
{
  const MeshState  m = cycle.mean();
  const PairVector g = mesh_gradient(m);
  // drive-side contact: F_m = K_m (g . q - E_t - b_c); the pinion's rotation about its axis
  // held (the reaction there is the motor torque), the motor too; then the motor angle that
  // carries that torque through its shaft (held there in the dynamics when speed-controlled)
  const PairMatrix A    = K + m.km * g * g.transpose();
  const PairVector rhs  = m.km * (m.et + p.half_backlash) * g + torques(0, load_torque);
  const int        hold = dof::pinion_rotation + [&] {
    int k = 0;
    while (std::abs(p.pinion.axis[k]) < std::abs(p.pinion.axis[(k + 1) % 3]) ||
           std::abs(p.pinion.axis[k]) < std::abs(p.pinion.axis[(k + 2) % 3]))
      ++k;
    return k;
  }();
  std::vector<int> index;
  for (int i = 0; i < pair_dofs; ++i)
    if (free[i] > 0 && i != hold && i != dof::motor)
      index.push_back(i);
  const int       n = int(index.size());
  Eigen::MatrixXd Ar(n, n);
  Eigen::VectorXd br(n);
  for (int i = 0; i < n; ++i)
    {
      br[i] = rhs[index[i]];
      for (int j = 0; j < n; ++j)
        Ar(i, j) = A(index[i], index[j]);
    }
  const Eigen::VectorXd x = Ar.ldlt().solve(br);
  StaticEquilibrium     s;
  for (int i = 0; i < n; ++i)
    s.q[index[i]] = x[i];
  s.deflection = g.dot(s.q) - m.et - p.half_backlash;
  s.mesh_force = m.km * s.deflection;
  // the torque the held DOF takes: the motor torque that balances the load
  s.motor_torque = (A.row(hold).dot(s.q) - rhs[hold]) / p.pinion.axis[hold - dof::pinion_rotation];
  if (p.motor_inertia > 0)
    s.q[dof::motor] = (s.motor_torque - K.row(dof::motor).dot(s.q)) / K(dof::motor, dof::motor);
  if (!(s.mesh_force > 0))
    {
      std::ostringstream msg;
      msg << "pair dynamics: the load torque " << load_torque
          << " N m opens the mesh in the static equilibrium (mesh force " << s.mesh_force
          << " N); the moment arms' signs and the torque must drive the flanks together";
      throw InputError(msg.str());
    }
  return s;
}

PairModelParameters
placed_in_assembly(PairModelParameters p, int pinion_teeth, const Vec3 &pinion_axis,
                   const Vec3 &gear_frame_axis)
{
  p.pinion_teeth = pinion_teeth;
  p.pinion.axis  = pinion_axis;
  p.gear.axis    = -gear_frame_axis;
  for (RadialBearing &b : p.gear.bearings)
    b.position = -b.position;
  return p;
}
} // namespace gearkit

// The 14-DOF lumped model of a gear pair on flexible bearings (seed 000, "Dynamic Modeling"):
// motor torsion theta_E; gear X_g, Y_g, Z_g, theta_gx, theta_gy, theta_gz; pinion X_p, Y_p, Z_p,
// theta_px, theta_py, theta_pz; load torsion theta_L (this order), all small motions about the
// nominal rotation, global frame (for the seed's bevel pair: pinion axis Z, gear axis Y).
//
//   M q'' + C q' + K q = F_ext - g(t) F_m,     F_ext = (T_E, 0, ..., 0, -T_L)
//   delta_D = g . q = n_p . d_p + lambda_p . Theta_p - (n_g . d_g + lambda_g . Theta_g)
//   F_m = K_m(t) f(delta_D - E_t(t), b_c) + c_m (delta_D' - E_t')   (damping only in contact)
//
// with the dead zone f of half backlash b_c. The mesh force's generalised forces are -g F_m,
// the derivative of the mesh's potential, so that the undamped model with constant tables
// conserves energy. K and C come from the supports: per body radial bearings at axial
// positions along its axis (their spans couple translation and tilt), an axial bearing, and the
// torsional shafts motor-pinion and gear-load; the rotation of each body about its own axis is
// held by its shaft only. Time enters through the mesh phase: the pinion turns at speed Omega,
// phase = z_p Omega t / (2 pi).
#pragma once

#include "dynamics/mesh_cycle.h"

#include <Eigen/Core>

#include <vector>

namespace gearkit
{
constexpr int pair_dofs = 14;
using PairVector        = Eigen::Matrix<double, pair_dofs, 1>;
using PairMatrix        = Eigen::Matrix<double, pair_dofs, pair_dofs>;

/// Indices into q.
namespace dof
{
constexpr int motor = 0, gear = 1, gear_rotation = 4, pinion = 7, pinion_rotation = 10, load = 13;
}

struct RadialBearing
{
  double position  = 0; ///< along the body's axis from its centre of mass [m]
  double stiffness = 0; ///< radial [N/m]
  double damping   = 0; ///< radial [N s/m]
};

struct BodyParameters
{
  double mass               = 0;             ///< [kg]
  double axial_inertia      = 0;             ///< about the body's axis [kg m^2]
  double transverse_inertia = 0;             ///< about axes across it through the centre [kg m^2]
  Vec3   axis               = Vec3::UnitZ(); ///< unit, global
  std::vector<RadialBearing> bearings;
  double                     axial_stiffness = 0, axial_damping = 0; ///< [N/m], [N s/m]
};

struct ShaftParameters
{
  double stiffness = 0; ///< torsional [N m/rad]
  double damping   = 0; ///< [N m s/rad]
};

struct PairModelParameters
{
  /// [kg m^2]; 0 removes the DOF: the motor torque then acts on the pinion's axis directly (the
  /// load torque on the gear's), and the shaft is not modelled
  double          motor_inertia = 0, load_inertia = 0;
  BodyParameters  pinion, gear;
  ShaftParameters motor_shaft, load_shaft; ///< motor-pinion, gear-load
  int             pinion_teeth       = 0;
  double          half_backlash      = 0; ///< b_c [m]
  double          mesh_damping_ratio = 0; ///< c_m = 2 zeta sqrt(K_m,mean m_e)
  /// The seed's mesh damping acts only in contact; false: always (Kahraman and Singh's model)
  bool mesh_damping_in_contact_only = true;
  /// Translations and tilts of both bodies held: the pure torsional model
  bool torsion_only = false;
  /// The motor runs at the nominal speed (theta_E held; its torque is the reaction) instead of
  /// at a constant torque: no free rigid rotation of the train, whose drift would otherwise
  /// grow without bound wherever the torques balance only on average
  bool speed_controlled_motor = false;
};

/// The parameters of a pair as its member frames place it: the pinion turns about
/// `pinion_axis`, the gear in its driven sense about -`gear_frame_axis` (the TCA's gear frame
/// axis; the driven gear turns against it); bearing positions, given along each member frame's
/// own axis, follow the gear's flip.
PairModelParameters
placed_in_assembly(PairModelParameters p, int pinion_teeth, const Vec3 &pinion_axis,
                   const Vec3 &gear_frame_axis);

/// Static equilibrium under a load torque at the phase-averaged mesh, with the pinion's rotation
/// about its axis held at zero: the shafts' wind-up goes to the motor and load angles (a
/// speed-controlled motor is then held at its wound-up angle), so that the bodies' rotations are
/// the mesh's own. (Linearised, delta_D = lambda . Theta turns a static rotation of the pinion
/// into a time-varying term lambda(t) . Theta wherever the arms vary over the cycle - a
/// first-order phase shift of e_0 - which for a noisy measured e_0 is no small quantity.)
struct StaticEquilibrium
{
  PairVector q            = PairVector::Zero();
  double     mesh_force   = 0; ///< F_m [N]
  double     deflection   = 0; ///< delta_D - E_t - b_c [m]
  double     motor_torque = 0; ///< T_E that balances the load torque [N m]
};

class PairModel
{
public:
  /// Throws InputError (naming the parameter) for non-positive masses or inertias, non-unit
  /// axes, negative stiffnesses or damping, a body without radial support, z_p < 1.
  PairModel(const PairModelParameters &parameters, const MeshCycleSamples &tables);

  const PairMatrix &
  mass() const
  {
    return M;
  }
  const PairMatrix &
  stiffness() const
  {
    return K;
  }
  const PairMatrix &
  damping() const
  {
    return C;
  }
  const MeshCycle &
  mesh() const
  {
    return cycle;
  }
  /// The samples the mesh interpolates.
  const MeshCycleSamples &
  tables() const
  {
    return samples;
  }
  const PairModelParameters &
  parameters() const
  {
    return p;
  }
  /// g at the mesh state: delta_D = g . q.
  static PairVector
  mesh_gradient(const MeshState &m);
  /// Mesh damping coefficient c_m [N s/m] (from the ratio and the mean mesh).
  double
  mesh_damping() const
  {
    return c_m;
  }
  /// Effective mass of the mesh, 1 / (g^T M^-1 g) over the free DOFs at the mean mesh [kg].
  double
  mesh_mass() const
  {
    return m_e;
  }

  /// F_m for the dynamic TE delta_D and its rate at the mesh state (rate of E_t per second).
  double
  mesh_force(const MeshState &m, double delta, double delta_rate, double et_rate) const;

  /// q'' for the state at time t, pinion speed Omega [rad/s] and the torques.
  PairVector
  acceleration(double t, const PairVector &q, const PairVector &qd, double omega,
               double motor_torque, double load_torque) const;

  /// The static equilibrium under the load torque T_L (in contact on the drive side).
  StaticEquilibrium
  static_equilibrium(double load_torque) const;

  /// 1 for the DOFs that move, 0 for those held (removed motor or load; supports in the
  /// torsional model).
  const PairVector &
  active() const
  {
    return free;
  }
  /// The indices of the DOFs that move (active() 1), ascending.
  std::vector<int>
  free_dofs() const
  {
    std::vector<int> index;
    for (int i = 0; i < pair_dofs; ++i)
      if (free[i] > 0)
        index.push_back(i);
    return index;
  }
  /// The external forces of the torques (motor torque on theta_E or the pinion's axis, load
  /// torque against theta_L or the gear's axis).
  PairVector
  torques(double motor_torque, double load_torque) const;

  /// Per-DOF scale of a mesh displacement `length` [m]: translations the length itself,
  /// rotations the length over the mean moment arm (tolerances mean the same along every DOF).
  PairVector
  dof_scale(double length) const;

  /// Mesh phase [mesh cycles] at time t and pinion speed Omega.
  double
  phase(double t, double omega) const;

private:
  PairModelParameters p;
  MeshCycleSamples    samples;
  MeshCycle           cycle;
  PairMatrix          M, K, C;
  PairVector          free;
  double              c_m = 0, m_e = 0;
};
} // namespace gearkit

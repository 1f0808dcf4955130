// System deflection: the mesh in the position its static load puts it in. The static
// equilibrium of the 14-DOF model moves and tilts both members on their bearings and shafts;
// the gear's rigid motion relative to the pinion, less the turns about the members' own axes
// (transmission error), is a misalignment of the pair. The contact analysis run at that
// misalignment gives new tables (contact points, normals, arms, e_0), the static equilibrium on
// them a new motion, and so on to a fixed point: the dynamics then runs on the tables of the
// deflected mesh. The caller supplies the contact analysis (tca/ with tca/assembly.h's
// misalignment_after); this file only knows the model.
#pragma once

#include "dynamics/pair_model.h"

#include <functional>
#include <memory>
#include <vector>

namespace gearkit
{
/// The gear's rigid motion relative to the pinion in the state q, u_g(x) - u_p(x), each body
/// moving by u_b(x) = d_b + Theta_b x (x - O_b) about its body point O_b (the member frame's
/// origin, which its moment arms and bearing positions are taken from).
RigidMotion
relative_gear_motion(const PairVector &q, const Vec3 &pinion_centre, const Vec3 &gear_centre);

/// The state in which the gear alone makes the rigid motion u.
PairVector
gear_displacement(const RigidMotion &u, const Vec3 &gear_centre);

/// A contact analysis with the gear moved relative to the pinion: its tables, and the part of
/// the motion its geometry took (the misalignment's share; the turns about the axes excluded).
struct DeflectedTables
{
  MeshCycleSamples tables;
  RigidMotion      taken;
};

struct SystemDeflectionOptions
{
  double motor_torque  = 0;             ///< on the pinion [N m]
  Vec3   pinion_axis   = Vec3::UnitZ(); ///< unit
  Vec3   gear_axis     = Vec3::UnitZ(); ///< unit, the gear's driven sense
  Vec3   pinion_centre = Vec3::Zero(), gear_centre = Vec3::Zero(); ///< body points [m]
  /// 0: the tables as assembled, no iteration
  int max_iterations = 10;
  /// converged when the motion changes by less than this share of its size
  double tolerance = 1e-3;
};

struct SystemDeflection
{
  std::unique_ptr<PairModel> model;           ///< on the tables of the deflected mesh
  StaticEquilibrium          equilibrium;     ///< of `model`
  double                     load_torque = 0; ///< balancing the motor torque [N m]
  RigidMotion                motion;          ///< the gear's, relative to the pinion, statically
  RigidMotion                taken;           ///< its part in the tables' geometry
  /// per iteration: the size of the motion's change, |du(O_g)| + |dw| arm [m]
  std::vector<double> change;
  bool                converged = false;
};

/// The fixed point static equilibrium -> misalignment -> contact analysis -> tables.
/// `tables_at(u)` runs the contact analysis with the gear moved by u (u = 0: as assembled).
/// The tables' E_t become E_t + g . q_taken (q_taken = gear_displacement(taken)), so that the
/// model, whose mesh deflection is g . q - E_t with q from the undeflected position, counts the
/// taken motion once: the moved geometry's E_t holds it already, to first order.
SystemDeflection
system_deflection(const PairModelParameters                                 &parameters,
                  const std::function<DeflectedTables(const RigidMotion &)> &tables_at,
                  const SystemDeflectionOptions                             &options);
} // namespace gearkit

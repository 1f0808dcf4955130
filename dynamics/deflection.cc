#include "dynamics/deflection.h"

#include <algorithm>

namespace gearkit
{
RigidMotion
relative_gear_motion(const PairVector &q, const Vec3 &pinion_centre, const Vec3 &gear_centre)
{
  const auto motion = [&](int d, int r, const Vec3 &centre) {
    const Vec3 shift = q.segment<3>(d), turn = q.segment<3>(r);
    return RigidMotion{shift - turn.cross(centre), turn};
  };
  const RigidMotion g = motion(dof::gear, dof::gear_rotation, gear_centre),
                    p = motion(dof::pinion, dof::pinion_rotation, pinion_centre);
  return {g.translation - p.translation, g.rotation - p.rotation};
}

PairVector
gear_displacement(const RigidMotion &u, const Vec3 &gear_centre)
{
  PairVector q                     = PairVector::Zero();
  q.segment<3>(dof::gear)          = u.at(gear_centre);
  q.segment<3>(dof::gear_rotation) = u.rotation;
  return q;
}

SystemDeflection
system_deflection(const PairModelParameters                                 &p,
                  const std::function<DeflectedTables(const RigidMotion &)> &tables_at,
                  const SystemDeflectionOptions                             &o)
{
  SystemDeflection r;
  // the model on the tables at the motion u, its static equilibrium and the motion it gives
  const auto solve = [&](const RigidMotion &u) {
    DeflectedTables  t     = tables_at(u);
    const PairVector taken = gear_displacement(t.taken, o.gear_centre);
    for (std::size_t i = 0; i < t.tables.transmission_error.size(); ++i)
      {
        MeshState m;
        m.np = t.tables.normal_pinion[i], m.ng = t.tables.normal_gear[i];
        m.lp = t.tables.arm_pinion[i], m.lg = t.tables.arm_gear[i];
        t.tables.transmission_error[i] += PairModel::mesh_gradient(m).dot(taken);
      }
    r.model = std::make_unique<PairModel>(p, t.tables);
    r.load_torque =
        balancing_load_torque(r.model->mesh(), o.motor_torque, o.pinion_axis, o.gear_axis);
    r.equilibrium = r.model->static_equilibrium(r.load_torque);
    r.taken       = t.taken;
    return relative_gear_motion(r.equilibrium.q, o.pinion_centre, o.gear_centre);
  };
  RigidMotion u    = solve(RigidMotion{});
  const auto  size = [&](const RigidMotion &v) {
    const MeshState m = r.model->mesh().mean();
    return v.at(o.gear_centre).norm() + v.rotation.norm() * std::max(m.lp.norm(), m.lg.norm());
  };
  r.converged  = o.max_iterations == 0;
  double relax = 1;
  for (int k = 0; k < o.max_iterations && !r.converged; ++k)
    {
      const RigidMotion next = solve(u);
      const RigidMotion step{next.translation - u.translation, next.rotation - u.rotation};
      r.change.push_back(size(step));
      r.converged = r.change.back() <= o.tolerance * size(next);
      // a change that does not halve: the next motion half way (contact that jumps between
      // two places as the pattern moves would otherwise alternate)
      if (k > 0 && r.change.back() > 0.5 * r.change[std::size_t(k - 1)])
        relax *= 0.5;
      u = {u.translation + relax * step.translation, u.rotation + relax * step.rotation};
    }
  r.motion = u;
  return r;
}
} // namespace gearkit

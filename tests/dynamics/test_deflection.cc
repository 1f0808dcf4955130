// System deflection (dynamics/deflection.h): the gear's static motion relative to the pinion,
// and the fixed point over contact analyses at the deflected position, with contact analyses
// stood in for by tables whose response to the motion is known.
#include "dynamics/deflection.h"
#include "tests/dynamics/pair_fixture.h"

#include <gtest/gtest.h>

using namespace gearkit;

namespace
{
const Vec3 pinion_centre(0, 0, 0.01), gear_centre(0, 0.09, 0);

SystemDeflectionOptions
options(const PairModelParameters &p)
{
  SystemDeflectionOptions o;
  o.motor_torque = 150;
  o.pinion_axis = p.pinion.axis, o.gear_axis = p.gear.axis;
  o.pinion_centre = pinion_centre, o.gear_centre = gear_centre;
  return o;
}
} // namespace

TEST(SystemDeflection, RelativeMotionIsTheGearsLessThePinions)
{
  PairVector q;
  for (int i = 0; i < pair_dofs; ++i)
    q[i] = 1e-5 * std::sin(1.3 * i + 0.2);
  const RigidMotion u = relative_gear_motion(q, pinion_centre, gear_centre);
  for (const Vec3 &x : {Vec3(0.07, 0.02, 0.05), Vec3(-0.03, 0.1, 0.0)})
    {
      const Vec3 gear = q.segment<3>(dof::gear) +
                        Vec3(q.segment<3>(dof::gear_rotation)).cross(x - gear_centre),
                 pinion = q.segment<3>(dof::pinion) +
                          Vec3(q.segment<3>(dof::pinion_rotation)).cross(x - pinion_centre);
      EXPECT_LT((u.at(x) - (gear - pinion)).norm(), 1e-18);
    }
  const RigidMotion back =
      relative_gear_motion(gear_displacement(u, gear_centre), pinion_centre, gear_centre);
  EXPECT_LT((back.translation - u.translation).norm() + (back.rotation - u.rotation).norm(), 1e-18);
}

TEST(SystemDeflection, ATakenMotionIsCountedOnce)
{
  // A contact analysis that obeys the first-order relation exactly: the geometry takes the
  // motion less its turn about the gear axis, and E_t changes by the normal approach of what it
  // took. The fixed point is then the static equilibrium as assembled: nothing counted twice.
  const PairModelParameters p         = test_data::bevel_like_parameters();
  const MeshCycleSamples    base      = test_data::bevel_like_tables(8, 3e8, 2e-6);
  const auto                tables_at = [&](const RigidMotion &u) {
    DeflectedTables d;
    d.tables = base;
    d.taken  = u;
    d.taken.rotation -= u.rotation.dot(p.gear.axis) * p.gear.axis;
    d.taken.translation = u.translation; // (a turn about an axis through the origin)
    const PairVector taken = gear_displacement(d.taken, gear_centre);
    for (std::size_t i = 0; i < base.transmission_error.size(); ++i)
      {
        MeshState m;
        m.np = base.normal_pinion[i], m.ng = base.normal_gear[i];
        m.lp = base.arm_pinion[i], m.lg = base.arm_gear[i];
        d.tables.transmission_error[i] -= PairModel::mesh_gradient(m).dot(taken);
      }
    return d;
  };
  const PairModel         aligned(p, base);
  SystemDeflectionOptions o = options(p);
  const SystemDeflection  s = system_deflection(p, tables_at, o);
  const StaticEquilibrium e = aligned.static_equilibrium(
      balancing_load_torque(aligned.mesh(), 150, o.pinion_axis, o.gear_axis));
  EXPECT_TRUE(s.converged);
  EXPECT_LE(s.change.size(), 2u);
  EXPECT_GT(e.q.norm(), 1e-6); // the load does deflect the supports
  EXPECT_LT((s.equilibrium.q - e.q).norm(), 1e-9 * e.q.norm());
  EXPECT_NEAR(s.equilibrium.mesh_force, e.mesh_force, 1e-9 * e.mesh_force);
}

TEST(SystemDeflection, TheFixedPointIsTheEquilibriumOfItsOwnTables)
{
  // Tables whose contact moves with the motion (the normal turns and the contact point slides,
  // as a pattern does under misalignment): the result must be the static equilibrium of the
  // tables at the motion it reports, and that equilibrium's motion the reported one.
  const PairModelParameters p         = test_data::bevel_like_parameters();
  const MeshCycleSamples    base      = test_data::bevel_like_tables(8, 3e8, 2e-6);
  const auto                tables_at = [&](const RigidMotion &u) {
    DeflectedTables d;
    d.tables = base;
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(20 * u.rotation.norm(), Vec3::UnitX()).toRotationMatrix();
    const Vec3 slide = 20 * u.translation;
    const Vec3 P     = Vec3(0.075, 0, 0.06) + slide;
    for (std::size_t i = 0; i < base.transmission_error.size(); ++i)
      {
        const Vec3 n              = turn * base.normal_pinion[i];
        d.tables.normal_pinion[i] = d.tables.normal_gear[i] = n;
        d.tables.arm_pinion[i]                              = P.cross(n);
        d.tables.arm_gear[i] = (P - gear_centre).cross(n);
      }
    return d;
  };
  const SystemDeflection s = system_deflection(p, tables_at, options(p));
  ASSERT_TRUE(s.converged);
  EXPECT_GE(s.change.size(), 2u);
  const RigidMotion again = relative_gear_motion(s.equilibrium.q, pinion_centre, gear_centre);
  const double      size  = s.motion.translation.norm() + 0.1 * s.motion.rotation.norm();
  EXPECT_LT((again.translation - s.motion.translation).norm() +
                0.1 * (again.rotation - s.motion.rotation).norm(),
            5e-3 * size);
  const PairModel own(p, tables_at(s.motion).tables);
  const auto      e =
      own.static_equilibrium(balancing_load_torque(own.mesh(), 150, p.pinion.axis, p.gear.axis));
  EXPECT_LT((e.q - s.equilibrium.q).norm(), 5e-3 * e.q.norm());
}

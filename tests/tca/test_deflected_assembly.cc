// A static motion of the gear relative to the pinion (the system deflection of
// dynamics/deflection.h) as a misalignment of the assembly (tca/assembly.h:
// misalignment_after), checked by geometry and by the TCA's first-order response.
#include "tca/bevel_synthesis.h"
#include "tca/unloaded_tca.h"
#include "tests/fzg_c_pair.h"
#include "tests/seed_bevel_pair.h"

#include <Eigen/QR>
#include <gtest/gtest.h>

#include <cmath>

using namespace gearkit;

namespace
{
/// The rigid motion of one unit of a member's turn about `axis` through `pivot`, as a 6-vector.
Eigen::Matrix<double, 6, 1>
turn(const Vec3 &axis, const Vec3 &pivot)
{
  Eigen::Matrix<double, 6, 1> c;
  c << -axis.cross(pivot), axis;
  return c;
}

/// Checks misalignment_after on `assembly` (built with `m`) against the assembly `moved`
/// rebuilt from its result: every gear point goes where the taken motion moves it, the rest of
/// the motion only turns the members about their axes, and the TCA's e_0 changes by the normal
/// approach of the taken motion at the contact, E_t(moved) - E_t = n . u(x_c) (to first order:
/// the contact point moves along the flanks, which changes the gap to second order only).
void
check_motion_becomes_misalignment(const std::shared_ptr<const MemberFlanks> &pinion,
                                  const std::shared_ptr<const MemberFlanks> &gear,
                                  const Assembly &assembly, const Assembly &moved,
                                  const RigidMotion &motion, const RigidMotion &taken,
                                  const std::string &what)
{
  for (const Vec3 &x : {Vec3(0.05, 0.01, 0.0), Vec3(-0.02, 0.08, 0.015), Vec3(0.1, 0, -0.01)})
    for (double psi : {0.0, 0.7})
      {
        // relative to the pinion (whose axial shift moves the pinion itself); second order:
        // |rotation|^2 |x| ~ 1e-10 m
        const Vec3 X = assembly.gear_to_global(x, psi) - assembly.pinion_centre();
        EXPECT_LT((moved.gear_to_global(x, psi) - moved.pinion_centre() - X -
                   taken.at(X + assembly.pinion_centre()))
                      .norm(),
                  1e-9)
            << what;
      }
  Eigen::Matrix<double, 6, 2> turns;
  turns << turn(assembly.gear_axis(), assembly.gear_centre()), turn(Vec3::UnitZ(), Vec3::Zero());
  Eigen::Matrix<double, 6, 1> rest;
  rest << motion.translation - taken.translation, motion.rotation - taken.rotation;
  const Eigen::Vector2d eps = turns.colPivHouseholderQr().solve(rest);
  EXPECT_LT((turns * eps - rest).norm(), 1e-12) << what << ": more than turns left out";

  TcaOptions o;
  o.positions_per_mesh    = 8;
  const TcaResult r0      = UnloadedTca(pinion, gear, assembly, o).run();
  const TcaResult r1      = UnloadedTca(pinion, gear, moved, o).run();
  double          largest = 0, worst = 0;
  for (std::size_t i = 0; i < r0.positions.size(); ++i)
    {
      // the pairs that touch (several at once for conjugate profiles): the one the motion
      // closes most (n . u < 0: toward the pinion) leads
      const PairContact &c        = r0.positions[i].pairs[r0.positions[i].leading];
      const double       shift    = c.lambda_pinion.z() * (r1.positions[i].transmission_error -
                                                  r0.positions[i].transmission_error);
      double             approach = HUGE_VAL;
      for (const PairContact &p : r0.positions[i].pairs)
        if (p.separation < 1e-9)
          approach = std::min(approach, p.normal_pinion.dot(taken.at(p.position)) *
                                            c.lambda_pinion.z() / p.lambda_pinion.z());
      largest = std::max(largest, std::abs(approach));
      worst   = std::max(worst, std::abs(shift - approach));
    }
  EXPECT_GT(largest, 1e-6) << what; // the motion does move the flanks apart
  EXPECT_LT(worst, 0.01 * largest) << what;
}
} // namespace

TEST(DeflectedAssembly, AStaticMotionOfTheGearBecomesAMisalignmentThatShiftsTheErrorByTheApproach)
{
  // System deflection (dynamics/deflection.h): the static equilibrium's motion of the gear
  // relative to the pinion is turned into offset, axial shifts and shaft angle error.
  PinionMismatch mm;
  mm.cutter_radius = 2e-3;
  Misalignment scene;
  scene.offset                 = 20e-6;
  const BevelPairFlanks f      = bevel_pair_flanks(test_data::seed_bevel_design(), mm, scene);
  const RigidMotion     motion = {Vec3(3e-6, -2e-6, 4e-6), Vec3(2e-5, -3e-5, 1e-5)};
  RigidMotion           taken;
  const Misalignment    m = misalignment_after(f.assembly, scene, motion, &taken);
  const BevelPairFlanks g = bevel_pair_flanks(test_data::seed_bevel_design(), mm, m);
  EXPECT_EQ(m.centre_distance_error, 0);
  EXPECT_EQ(m.crossing_angle, 0);
  check_motion_becomes_misalignment(f.pinion, f.gear, f.assembly, g.assembly, motion, taken,
                                    "spiral bevel");
}

TEST(DeflectedAssembly, AStaticMotionOfTheGearBecomesAParallelAxisMisalignment)
{
  // Helical FZG C pair (15 deg), lead crowned (point contact: the first-order relation holds
  // only where the contact point moves smoothly, not for a line tilted onto an edge), at a
  // slightly opened centre distance: the motion becomes centre distance error, offset,
  // crossing and inclination of the axes and the gear's axial shift.
  auto [dp, dg]                        = test_data::fzg_c_pair(15 * pi / 180);
  dp.drive_modifications.lead_crowning = 10e-6;
  dg.drive_modifications.lead_crowning = 10e-6;
  const auto [pinion, gear]            = create_pair(dp, dg);
  const double       a                 = working_centre_distance(*pinion, *gear) + 20e-6;
  const Assembly     assembly(a, gear->teeth());
  const RigidMotion  motion = {Vec3(3e-6, -2e-6, 4e-6), Vec3(2e-5, -3e-5, 1e-5)};
  RigidMotion        taken;
  const Misalignment m = misalignment_after(assembly, {}, motion, &taken);
  EXPECT_EQ(m.pinion_axial_shift, 0);
  check_motion_becomes_misalignment(std::make_shared<InvoluteMemberFlanks>(pinion),
                                    std::make_shared<InvoluteMemberFlanks>(gear), assembly,
                                    Assembly(a, gear->teeth(), m), motion, taken, "helical");
}

TEST(DeflectedAssembly, TiltingAnAlignedAssemblyIsAssemblingItWithTheAngles)
{
  // Assembly::tilted on aligned parallel axes places every gear point where the assembly built
  // with those crossing and intersecting angles does; on a bevel pair it turns the gear about
  // its frame's origin (the apex) and keeps the pinion.
  const double   a = 91.5e-3, beta = 0.47e-3, delta = -0.94e-3;
  const Assembly tilted = Assembly(a, 24).tilted(beta, delta);
  Misalignment   m;
  m.crossing_angle = beta, m.intersecting_angle = delta;
  const Assembly built(a, 24, m);
  for (const Vec3 &x : {Vec3(40e-3, 5e-3, 7e-3), Vec3(-30e-3, 20e-3, -7e-3), Vec3(0, 0, 0)})
    for (const double psi : {0.0, 0.3, -1.2})
      {
        EXPECT_LT((tilted.gear_to_global(x, psi) - built.gear_to_global(x, psi)).norm(), 1e-15);
        EXPECT_LT((tilted.pinion_to_global(x, psi) - built.pinion_to_global(x, psi)).norm(), 1e-15);
      }
  const Assembly        bevel  = Assembly::bevel(pi / 2, 0.86, 47);
  const Assembly        turned = bevel.tilted(beta, delta);
  const Vec3            x(20e-3, 3e-3, 50e-3);
  const Vec3            X = bevel.gear_to_global(x, 0.2), Y = turned.gear_to_global(x, 0.2);
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(delta, Vec3::UnitY()) * Eigen::AngleAxisd(beta, Vec3::UnitX()))
          .toRotationMatrix();
  EXPECT_LT((Y - (bevel.gear_centre() + R * (X - bevel.gear_centre()))).norm(), 1e-15);
  EXPECT_LT(bevel.gear_centre().norm(), 1e-15); // the apex
  EXPECT_LT((turned.pinion_to_global(x, 0.2) - bevel.pinion_to_global(x, 0.2)).norm(), 1e-15);
}

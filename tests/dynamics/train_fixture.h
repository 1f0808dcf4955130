// Ideal tooth pair curves and small trains for the gear-train tests.
#pragma once

#include "base/types.h"
#include "dynamics/train.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace gearkit::test_data
{
/// Ideal conjugate flanks: every pairing touches over `contact_ratio` base pitches around its
/// centre with a constant offset (drive -beta/2, coast +beta/2: the angular backlash beta) and
/// arm r_bg; beyond, the flanks recede quadratically (100 um along the normal a pitch further)
/// as tip edges do, or with `kinked` linearly (the slope jumps where the path ends: a kink,
/// given as a knot), sampled `samples` times a mesh cycle.
inline ToothPairTables
ideal_tables(int z1, int z2, double r_bg, double beta, double contact_ratio = 1.0, int samples = 64,
             bool kinked = false)
{
  ToothPairTables t;
  t.pinion_teeth = z1, t.gear_teeth = z2;
  t.pinion_class.assign(z1, 0);
  t.gear_class.assign(z2, 0);
  t.pinion_classes = t.gear_classes = 1;
  const double pitch                = 2 * pi / z1;
  for (int side = 0; side < 2; ++side)
    {
      ToothPairCurve c;
      const double   s   = side == drive_side ? -1.0 : 1.0;
      const double   end = contact_ratio * pitch / 2;
      c.step             = pitch / samples;
      c.start            = -(contact_ratio / 2 + 1) * pitch;
      for (double x = c.start; x <= -c.start + 1e-12; x += c.step)
        {
          const double beyond = std::max(0.0, std::abs(x) - end) / pitch;
          c.offset.push_back(s * (beta / 2 + 100e-6 / r_bg * (kinked ? beyond : beyond * beyond)));
          c.arm.push_back(r_bg);
        }
      if (kinked)
        for (double at : {-end, end})
          c.knots.push_back({at, {s * beta / 2, s * beta / 2}, {r_bg, r_bg}});
      t.curves[side] = {c};
    }
  return t;
}

inline TrainModel
two_body_model(double J_p, double J_g, int z1, int z2, double r_bp, double beta,
               const ImpactLaw &law, double contact_ratio = 1.0)
{
  TrainModel m;
  m.bodies.resize(2);
  m.bodies[0].name = "pinion", m.bodies[0].inertia = J_p;
  m.bodies[1].name = "gear", m.bodies[1].inertia = J_g;
  TrainMesh mesh;
  mesh.name               = "stage";
  mesh.pinion_base_radius = r_bp;
  mesh.gear_base_radius   = r_bp * z2 / z1;
  mesh.teeth              = ideal_tables(z1, z2, mesh.gear_base_radius, beta, contact_ratio);
  mesh.law                = law;
  m.meshes                = {mesh};
  return m;
}
/// Seed 002's train for its kinematics alone: input, intermediate and output bodies, stages
/// 17/60 and 19/72 (tooth counts only, no contact curves).
inline TrainModel
seed002_kinematic_train()
{
  TrainModel m;
  m.bodies.resize(3);
  for (int i = 0; i < 3; ++i)
    m.bodies[i].name = "b" + std::to_string(i), m.bodies[i].inertia = 1e-3;
  TrainMesh a, b;
  a.name = "1", a.driver = 0, a.driven = 1, a.teeth.pinion_teeth = 17, a.teeth.gear_teeth = 60;
  b.name = "2", b.driver = 1, b.driven = 2, b.teeth.pinion_teeth = 19, b.teeth.gear_teeth = 72;
  m.meshes = {a, b};
  return m;
}
} // namespace gearkit::test_data

// The gear train's model outside its integration: the torque law, the crank-slider's
// kinematics and inertia, the model's checks, the train's kinematics and frequencies
// (dynamics/train.h).
#include "base/types.h"
#include "dynamics/train.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gearkit
{
double
TorqueLaw::operator()(double t, double speed) const
{
  const double ramp = time_constant > 0 ? -std::expm1(-t / time_constant) : 1.0;
  return constant + step * ramp - viscous * speed;
}

std::pair<double, double>
CrankSlider::piston(double c) const
{
  const double s = std::sin(c), k = std::cos(c);
  const double w = std::sqrt(rod_length * rod_length - crank_radius * crank_radius * s * s);
  return {crank_radius * k + w, -crank_radius * s - crank_radius * crank_radius * s * k / w};
}

std::pair<double, double>
CrankSlider::inertia(double c) const
{
  // J(c) of the moving parts referred to the crank angle and dJ/dc, each term with its
  // derivative by c (the chain rule through the crank-slider's kinematics)
  const double s = std::sin(c), co = std::cos(c), r = crank_radius, l = rod_length;
  const double w = std::sqrt(l * l - r * r * s * s), dw = -r * r * s * co / w;
  // piston velocity per crank rate
  const double xs  = -r * s - r * r * s * co / w;
  const double dxs = -r * co - r * r * (co * co - s * s) / w + r * r * s * co * dw / (w * w);
  // the crank pin's velocity, and the rod's centre of mass
  const double px = -r * s, py = r * co, dpx = -r * co, dpy = -r * s;
  const double f  = rod_centre / l;
  const double gx = px + f * (xs - px), gy = (1 - f) * py;
  const double dgx = dpx + f * (dxs - dpx), dgy = (1 - f) * dpy;
  // the rod's angular rate per crank rate
  const double beta = r * co / w, dbeta = (-r * s * w - r * co * dw) / (w * w);
  return {
      piston_mass * xs * xs + rod_mass * (gx * gx + gy * gy) + rod_inertia * beta * beta,
      2 * (piston_mass * xs * dxs + rod_mass * (gx * dgx + gy * dgy) + rod_inertia * beta * dbeta)};
}

void
TrainModel::check() const
{
  const std::string section = "Train";
  auto              fail    = [](const std::string &where, const std::string &what, double value,
                 const std::string &allowed) { require_value(false, where, what, value, allowed); };
  if (bodies.size() < 2)
    fail(section, "bodies", double(bodies.size()), "at least two bodies");
  const int n = int(bodies.size());
  for (const TrainBody &b : bodies)
    {
      const std::string where = "Train body " + b.name;
      if (!(b.inertia > 0) || !std::isfinite(b.inertia))
        fail(where, "inertia [kg m^2]", b.inertia, "> 0");
      if (!std::isfinite(b.initial_speed) || !std::isfinite(b.initial_angle))
        fail(where, "initial speed", b.initial_speed, "finite");
      if (b.torque.time_constant < 0 || b.torque.viscous < 0)
        fail(where, "torque time constant / viscous coefficient",
             std::min(b.torque.time_constant, b.torque.viscous), ">= 0");
      if (b.has_crank)
        {
          const CrankSlider &k = b.crank;
          if (!(k.crank_radius > 0) || !(k.rod_length > k.crank_radius))
            fail(where, "crank radius and rod length [m]", k.rod_length,
                 "0 < crank radius < rod length");
          if (k.rod_centre < 0 || k.rod_centre > k.rod_length)
            fail(where, "rod centre of mass [m]", k.rod_centre, "in [0, rod length]");
          if (k.rod_mass < 0 || k.rod_inertia < 0 || k.piston_mass < 0)
            fail(where, "rod and piston masses",
                 std::min({k.rod_mass, k.rod_inertia, k.piston_mass}), ">= 0");
        }
    }
  for (const TrainMesh &m : meshes)
    {
      const std::string where = "Train mesh " + m.name;
      if (m.driver < 0 || m.driver >= n || m.driven < 0 || m.driven >= n)
        fail(where, "body index", m.driver < 0 || m.driver >= n ? m.driver : m.driven,
             "a body of the train");
      if (m.driver == m.driven)
        fail(where, "driven body", m.driven, "another body than the driver");
      const ToothPairTables &t = m.teeth;
      if (t.pinion_teeth < 1 || t.gear_teeth < 1 || int(t.pinion_class.size()) != t.pinion_teeth ||
          int(t.gear_class.size()) != t.gear_teeth)
        fail(where, "tooth pair tables (teeth)", t.pinion_teeth, "tables for every tooth");
      for (const auto &side : t.curves)
        {
          if (int(side.size()) != t.pinion_classes * t.gear_classes)
            fail(where, "tooth pair tables (class pairs)", double(side.size()),
                 "one curve per class pair");
          for (const ToothPairCurve &c : side) // empty: the pair never touches (a missing tooth)
            if (c.offset.size() == 1 || c.arm.size() != c.offset.size() ||
                (!c.offset.empty() && !(c.step > 0)))
              fail(where, "tooth pair curve samples", double(c.offset.size()),
                   "none (never touching) or >= 2 samples, positive spacing");
        }
      const ImpactLaw &l = m.law;
      if (!(l.stiffness > 0) || !std::isfinite(l.stiffness))
        fail(where, "contact stiffness", l.stiffness, "> 0");
      if (!(l.exponent >= 1) || l.exponent > 10)
        fail(where, "force exponent", l.exponent, "in [1, 10]");
      if (l.damping < 0 || (l.damping > 0 && !(l.depth > 0)))
        fail(where, "damping / penetration depth", l.damping > 0 ? l.depth : l.damping,
             "damping >= 0, depth > 0 with damping");
      if (!m.mesh_stiffness.empty())
        {
          if (m.mesh_stiffness.size() < 2)
            fail(where, "mesh stiffness samples", double(m.mesh_stiffness.size()),
                 ">= 2 over the mesh cycle");
          for (double K : m.mesh_stiffness)
            if (!(K > 0) || !std::isfinite(K))
              fail(where, "mesh stiffness [N/m]", K, "> 0 and finite at every sample");
        }
      if (!(m.pinion_base_radius > 0) || !(m.gear_base_radius > 0))
        fail(where, "base radii [m]", std::min(m.pinion_base_radius, m.gear_base_radius), "> 0");
    }
  for (const TrainShaft &s : shafts)
    {
      if (s.a < 0 || s.a >= n || s.b < 0 || s.b >= n || s.a == s.b)
        fail("Train shaft", "bodies", s.a, "two different bodies of the train");
      if (s.stiffness < 0 || s.damping < 0)
        fail("Train shaft", "stiffness / damping", std::min(s.stiffness, s.damping), ">= 0");
    }
}

std::vector<double>
train_speeds(const TrainModel &model, int body, double speed)
{
  const int           n = int(model.bodies.size());
  std::vector<double> w(n, std::nan(""));
  require_value(body >= 0 && body < n, "Train", "body", body, "a body of the train");
  w[body] = speed;
  // propagate along meshes and shafts until nothing changes; a second value for a body must
  // agree with the first
  for (bool changed = true; changed;)
    {
      changed   = false;
      auto link = [&](int a, int b, double ratio, const std::string &what) {
        for (int pass = 0; pass < 2; ++pass)
          {
            const int    from = pass ? b : a, to = pass ? a : b;
            const double r = pass ? 1 / ratio : ratio;
            if (std::isnan(w[from]))
              continue;
            if (std::isnan(w[to]))
              w[to] = w[from] * r, changed = true;
            else if (std::abs(w[to] - w[from] * r) > 1e-12 * std::abs(w[to]) + 1e-300)
              {
                std::ostringstream m;
                m << "Train: " << what << " does not close: it would turn " << model.bodies[to].name
                  << " at " << w[from] * r << " rad/s where the rest of "
                  << "the train turns it at " << w[to]
                  << " rad/s; expected tooth ratios that agree around every loop";
                throw InputError(m.str());
              }
          }
      };
      for (const TrainMesh &m : model.meshes)
        link(m.driver, m.driven, double(m.teeth.pinion_teeth) / m.teeth.gear_teeth,
             "mesh " + m.name);
      for (const TrainShaft &s : model.shafts)
        link(s.a, s.b, 1.0, "a shaft");
    }
  return w;
}

TrainFrequencies
train_frequencies(const TrainModel &model, int body, double speed)
{
  TrainFrequencies f;
  for (const double w : train_speeds(model, body, speed))
    f.shaft.push_back(std::abs(w) / (2 * pi));
  for (const TrainMesh &m : model.meshes)
    f.mesh.push_back(m.teeth.pinion_teeth * f.shaft[std::size_t(m.driver)]);
  return f;
}
} // namespace gearkit

#include "mesh_cycle.h"

#include <boost/math/interpolators/cardinal_trigonometric.hpp>

#include <array>
#include <cmath>
#include <sstream>

namespace gearkit
{
namespace
{
using Trig = boost::math::interpolators::cardinal_trigonometric<std::vector<double>>;

/// One periodic table: constant, or the trigonometric interpolant over one period [0, 1).
struct Periodic
{
  double                constant = 0;
  std::shared_ptr<Trig> trig;
  double                mean = 0;

  explicit Periodic(const std::vector<double> &v)
  {
    for (double x : v)
      mean += x / double(v.size());
    bool same = true;
    for (double x : v)
      same = same && x == v.front();
    if (same)
      constant = v.front();
    else
      trig = std::make_shared<Trig>(v, 0.0, 1.0 / double(v.size()));
  }
  double
  operator()(double phase) const
  {
    return trig ? (*trig)(phase - std::floor(phase)) : constant;
  }
  double
  prime(double phase) const
  {
    return trig ? trig->prime(phase - std::floor(phase)) : 0.0;
  }
};
} // namespace

struct MeshCycle::Impl
{
  std::size_t           n = 0;
  std::vector<Periodic> tables; // E_t, K_m, then n_p, n_g, l_p, l_g (x, y, z each)
};

MeshCycle::MeshCycle(const MeshCycleSamples &s)
    : impl(std::make_unique<Impl>())
{
  const std::size_t n = s.transmission_error.size();
  auto fail = [&](const std::string &what) { throw InputError("mesh cycle tables: " + what); };
  if (n == 0)
    fail("no samples");
  if (s.mesh_stiffness.size() != n || s.normal_pinion.size() != n || s.normal_gear.size() != n ||
      s.arm_pinion.size() != n || s.arm_gear.size() != n)
    fail("every table needs the same number of samples (" + std::to_string(n) +
         " transmission errors)");
  for (std::size_t i = 0; i < n; ++i)
    {
      std::ostringstream where;
      where << " at sample " << i << " of " << n;
      if (!std::isfinite(s.transmission_error[i]))
        fail("transmission error is not finite" + where.str());
      if (!(s.mesh_stiffness[i] > 0) || !std::isfinite(s.mesh_stiffness[i]))
        fail("mesh stiffness " + std::to_string(s.mesh_stiffness[i]) + " N/m" + where.str() +
             "; expected a finite value > 0");
      for (const Vec3 *v : {&s.normal_pinion[i], &s.normal_gear[i]})
        if (!(std::abs(v->norm() - 1) < 1e-6))
          fail("normal of length " + std::to_string(v->norm()) + where.str() +
               "; expected a unit vector");
      if (!s.arm_pinion[i].allFinite() || !s.arm_gear[i].allFinite())
        fail("moment arm is not finite" + where.str());
    }
  impl->n = n;
  impl->tables.emplace_back(s.transmission_error);
  impl->tables.emplace_back(s.mesh_stiffness);
  for (const auto *table : {&s.normal_pinion, &s.normal_gear, &s.arm_pinion, &s.arm_gear})
    for (int k = 0; k < 3; ++k)
      {
        std::vector<double> c(n);
        for (std::size_t i = 0; i < n; ++i)
          c[i] = (*table)[i][k];
        impl->tables.emplace_back(c);
      }
}

MeshCycle::~MeshCycle() = default;

std::size_t
MeshCycle::samples() const
{
  return impl->n;
}

MeshState
MeshCycle::at(double phase) const
{
  const auto &t = impl->tables;
  MeshState   m;
  m.et       = t[0](phase);
  m.det      = t[0].prime(phase);
  m.km       = t[1](phase);
  Vec3 *v[4] = {&m.np, &m.ng, &m.lp, &m.lg};
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 3; ++k)
      (*v[j])[k] = t[2 + 3 * j + k](phase);
  return m;
}

MeshState
MeshCycle::mean() const
{
  const auto &t = impl->tables;
  MeshState   m;
  m.et = t[0].mean, m.km = t[1].mean;
  Vec3 *v[4] = {&m.np, &m.ng, &m.lp, &m.lg};
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 3; ++k)
      (*v[j])[k] = t[2 + 3 * j + k].mean;
  return m;
}
} // namespace gearkit

#include "dynamics/mesh_cycle.h"

#include <boost/math/interpolators/cardinal_trigonometric.hpp>
#include <boost/math/interpolators/makima.hpp>

#include <array>
#include <cmath>
#include <sstream>

namespace gearkit
{
namespace
{
using Trig   = boost::math::interpolators::cardinal_trigonometric<std::vector<double>>;
using Makima = boost::math::interpolators::makima<std::vector<double>>;

/// One periodic table over [0, period): constant, or an interpolant of the samples at
/// period / n steps. Makima is not periodic by itself: it is built on the samples extended by
/// three periodic copies on each side, so that its slopes wrap around.
struct Periodic
{
  double                  period   = 1;
  double                  constant = 0;
  std::shared_ptr<Trig>   trig;
  std::shared_ptr<Makima> makima;
  double                  mean = 0;

  Periodic(const std::vector<double> &v, double period, MeshInterpolation how)
      : period(period)
  {
    const std::size_t n = v.size();
    for (double x : v)
      mean += x / double(n);
    bool same = true;
    for (double x : v)
      same = same && x == v.front();
    if (same)
      constant = v.front();
    else if (how == MeshInterpolation::trigonometric)
      trig = std::make_shared<Trig>(v, 0.0, period / double(n));
    else
      {
        const long          pad = 3, m = long(n);
        std::vector<double> x, y;
        for (long i = -pad; i <= m + pad; ++i)
          {
            x.push_back(period * double(i) / double(m));
            y.push_back(v[std::size_t(mod(i, m))]);
          }
        makima = std::make_shared<Makima>(std::move(x), std::move(y));
      }
  }
  double
  wrap(double phase) const
  {
    return phase - period * std::floor(phase / period);
  }
  double
  operator()(double phase) const
  {
    return trig ? (*trig)(wrap(phase)) : makima ? (*makima)(wrap(phase)) : constant;
  }
  double
  prime(double phase) const
  {
    return trig ? trig->prime(wrap(phase)) : makima ? makima->prime(wrap(phase)) : 0.0;
  }
};
} // namespace

struct MeshCycle::Impl
{
  std::size_t           n      = 0;
  int                   cycles = 1;
  std::vector<Periodic> tables; // E_t, K_m, then n_p, n_g, l_p, l_g (x, y, z each)
};

MeshCycle::MeshCycle(const MeshCycleSamples &s)
    : impl(std::make_unique<Impl>())
{
  const std::size_t n = s.transmission_error.size();
  auto fail = [&](const std::string &what) { throw InputError("mesh cycle tables: " + what); };
  if (n == 0)
    fail("no samples");
  if (s.cycles < 1)
    fail("the tables span " + std::to_string(s.cycles) + " mesh cycles; expected >= 1");
  if (s.interpolation == MeshInterpolation::makima && n > 1 && n < 4)
    fail(std::to_string(n) + " samples; makima interpolation needs >= 4 (or 1: constant)");
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
  impl->n      = n;
  impl->cycles = s.cycles;
  auto add     = [&](const std::vector<double> &v) {
    impl->tables.emplace_back(v, double(s.cycles), s.interpolation);
  };
  add(s.transmission_error);
  add(s.mesh_stiffness);
  for (const auto *table : {&s.normal_pinion, &s.normal_gear, &s.arm_pinion, &s.arm_gear})
    for (int k = 0; k < 3; ++k)
      {
        std::vector<double> c(n);
        for (std::size_t i = 0; i < n; ++i)
          c[i] = (*table)[i][k];
        add(c);
      }
}

MeshCycle::~MeshCycle() = default;

std::size_t
MeshCycle::samples() const
{
  return impl->n;
}

int
MeshCycle::cycles() const
{
  return impl->cycles;
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

std::vector<double>
resample_periodic(const std::vector<double> &values, int n, MeshInterpolation how)
{
  const Periodic      f(values, 1.0, how);
  std::vector<double> out;
  for (int i = 0; i < n; ++i)
    out.push_back(f(double(i) / n));
  return out;
}

std::vector<double>
varying_mesh_stiffness(double mean, double variation, int n)
{
  std::vector<double> k;
  for (int i = 0; i < n; ++i)
    k.push_back(mean * (1 - variation * std::cos(2 * pi * i / n)));
  return k;
}

MeshCycleSamples
mesh_cycle_samples(const ContactTables &tca, int n, int cycles, const Vec3 &pinion_axis,
                   const std::vector<double> &km)
{
  const std::size_t N = std::size_t(n * cycles);
  if (tca.positions < N)
    throw InputError("dynamics: the TCA has " + std::to_string(tca.positions) +
                     " positions, fewer than " + std::to_string(cycles) + " mesh cycles of " +
                     std::to_string(n));
  const auto      &np = tca.normal_pinion, &lp = tca.lambda_pinion, &lg = tca.lambda_gear;
  MeshCycleSamples s;
  s.cycles = cycles;
  for (std::size_t i = 0; i < N; ++i)
    {
      const std::size_t k = (i * tca.slots + std::size_t(std::max(tca.leading[i], 0))) * 3;
      const Vec3        normal(np[k], np[k + 1], np[k + 2]);
      const Vec3        arm_p(lp[k], lp[k + 1], lp[k + 2]);
      s.normal_pinion.push_back(normal);
      s.normal_gear.push_back(normal);
      s.arm_pinion.push_back(arm_p);
      s.arm_gear.push_back(-Vec3(lg[k], lg[k + 1], lg[k + 2]));
      s.transmission_error.push_back(arm_p.dot(pinion_axis) * tca.transmission_error[i]);
      s.mesh_stiffness.push_back(km[i % std::size_t(n)]);
    }
  return s;
}

double
balancing_load_torque(const MeshCycle &mesh, double motor_torque, const Vec3 &pinion_axis,
                      const Vec3 &gear_axis)
{
  const MeshState m0 = mesh.mean();
  return motor_torque * m0.lg.dot(gear_axis) / m0.lp.dot(pinion_axis);
}
} // namespace gearkit

// Stage "dynamics": the 14-DOF pair model (dynamics/pair_model.h) on the mesh-cycle tables of
// the unloaded TCA (E_t = lambda_pz e_0, normals, moment arms of the contact that carries the
// load) and K_m from the stiffness stage (or constant); static equilibrium, linear modes with
// the resonance speeds of the first mesh orders, and a speed sweep up and then down with
// continuation, for the theoretical flanks. (Measured flanks with pitch errors do not repeat
// with the mesh cycle - only over the hunting period - so one cycle of their e_0 is no periodic
// excitation; not yet run.)
#include "modes.h"
#include "pair_members.h"
#include "stages.h"
#include "sweep.h"

#include <boost/math/interpolators/cardinal_trigonometric.hpp>

#include <cmath>

namespace gearkit
{
namespace
{
/// K_m at n equal phases of the mesh cycle from samples at other equal phases (periodic).
std::vector<double>
resample_periodic(const std::vector<double> &k, int n)
{
  std::vector<double> out(std::size_t(n), k.front());
  if (k.size() > 1)
    {
      const boost::math::interpolators::cardinal_trigonometric<std::vector<double>> f(
          k, 0.0, 1.0 / double(k.size()));
      for (int i = 0; i < n; ++i)
        out[std::size_t(i)] = f(double(i) / n);
    }
  return out;
}

/// The mesh-cycle tables of the first mesh cycle of a TCA group (the leading pair's contact).
/// n = pinion outward normal (the pinion pushes the gear along it) for both members; the
/// gear's arm r_g x n is minus the TCA's (taken with the gear's own outward normal).
MeshCycleSamples
mesh_tables(const H5Group &ste, int n, const Vec3 &pinion_axis, const std::vector<double> &km)
{
  std::vector<hsize_t> shape;
  const auto           np = ste.read_doubles("normal_pinion", &shape);
  const auto           lp = ste.read_doubles("lambda_pinion"), lg = ste.read_doubles("lambda_gear");
  const auto           e0    = ste.read_doubles("transmission_error");
  const auto           lead  = ste.read_ints("leading");
  const std::size_t    slots = shape[1];
  if (shape[0] < std::size_t(n))
    throw InputError("dynamics: the TCA has fewer positions than one mesh cycle");
  MeshCycleSamples s;
  for (int i = 0; i < n; ++i)
    {
      const std::size_t k = (std::size_t(i) * slots + std::size_t(std::max(lead[i], 0))) * 3;
      const Vec3        normal(np[k], np[k + 1], np[k + 2]);
      const Vec3        arm_p(lp[k], lp[k + 1], lp[k + 2]);
      s.normal_pinion.push_back(normal);
      s.normal_gear.push_back(normal);
      s.arm_pinion.push_back(arm_p);
      s.arm_gear.push_back(-Vec3(lg[k], lg[k + 1], lg[k + 2]));
      s.transmission_error.push_back(arm_p.dot(pinion_axis) * e0[std::size_t(i)]);
      s.mesh_stiffness.push_back(km[std::size_t(i)]);
    }
  return s;
}

std::vector<double>
column(const std::vector<SweepPoint> &p, double SweepPoint::*field)
{
  std::vector<double> v;
  for (const SweepPoint &x : p)
    v.push_back(x.*field);
  return v;
}

void
write_sweep(const H5Group &g, const std::vector<SweepPoint> &p)
{
  const hsize_t       n = p.size();
  std::vector<double> rpm;
  std::vector<int>    period, settled;
  for (const SweepPoint &x : p)
    rpm.push_back(x.speed * 60 / (2 * pi)), period.push_back(x.period),
        settled.push_back(x.settled_cycles);
  g.write("speed", rpm, {n}, "rpm", "pinion speed, in the order swept");
  g.write("dte_peak_to_peak", column(p, &SweepPoint::dte_pp), {n}, "m", "DTE delta_D peak-to-peak");
  g.write("dte_rms", column(p, &SweepPoint::dte_rms), {n}, "m", "RMS of delta_D about its mean");
  g.write("relative_peak_to_peak", column(p, &SweepPoint::relative_pp), {n}, "m",
          "delta_D - E_t peak-to-peak (the mesh deflection)");
  g.write("max_mesh_force", column(p, &SweepPoint::max_force), {n}, "N", "largest F_m");
  g.write("dynamic_load_factor", column(p, &SweepPoint::load_factor), {n}, "1",
          "largest F_m over the static mesh force");
  g.write("contact_loss", column(p, &SweepPoint::contact_loss), {n}, "1",
          "share of the recorded time out of contact");
  g.write("period", period, {n}, "mesh cycles", "the motion repeats after (0: not steady)");
  g.write("settled_cycles", settled, {n}, "mesh cycles", "spent settling");
}
} // namespace

void
run_dynamics_stage(const Scene &scene, const Upstream &upstream, const H5Group &out,
                   std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      const DynamicsScene &d   = scene.dynamics.at(pair.name);
      const TcaScene      &tca = scene.tca.at(pair.name);
      const PairMembers    members =
          theoretical_members(pair, tca, upstream.at("flanks")->group(pair.name));
      const H5Group ste = upstream.at("ste")->group(pair.name);
      const int     n = tca.options.positions_per_mesh, z1 = members.pinion->teeth();
      const Vec3    pinion_axis = Vec3::UnitZ();
      const Vec3    gear_axis   = -members.assembly.gear_axis(); // its driven sense

      // K_m over the cycle: from the stiffness stage at the torque nearest the scene's
      auto stiffness = [&](bool measured) {
        if (!d.fe_stiffness)
          {
            std::vector<double> k;
            for (int i = 0; i < n; ++i)
              k.push_back(d.mesh_stiffness *
                          (1 - d.stiffness_variation * std::cos(2 * pi * i / n)));
            return k;
          }
        const H5Group        all     = upstream.at("stiffness")->group(pair.name);
        const bool           own     = measured && all.has("measured");
        const auto           torques = all.read_doubles("torque");
        std::vector<hsize_t> shape;
        const auto           K = own ? all.group("measured").read_doubles("mesh_stiffness", &shape)
                                     : all.read_doubles("mesh_stiffness", &shape);
        std::size_t          best = 0;
        for (std::size_t t = 1; t < torques.size(); ++t)
          if (std::abs(torques[t] - d.torque) < std::abs(torques[best] - d.torque))
            best = t;
        return resample_periodic(std::vector<double>(K.begin() + long(best * shape[1]),
                                                     K.begin() + long((best + 1) * shape[1])),
                                 n);
      };

      PairModelParameters p = d.model;
      p.pinion_teeth        = z1;
      p.pinion.axis         = pinion_axis;
      p.gear.axis           = gear_axis;
      for (RadialBearing &b : p.gear.bearings) // given along the gear frame's axis
        b.position = -b.position;

      const H5Group                  g = out.group(pair.name);
      const std::vector<std::string> excitations{"theoretical"};
      bool                           first = true;
      for (const std::string &label : excitations)
        {
          const bool       measured = label == "measured";
          MeshCycleSamples tables =
              measured ? mesh_tables(ste.group("measured"), n, pinion_axis, stiffness(true))
                       : mesh_tables(ste, n, pinion_axis, stiffness(false));
          if (!d.tca_transmission_error)
            for (int i = 0; i < n; ++i)
              tables.transmission_error[std::size_t(i)] =
                  d.transmission_error_amplitude * std::sin(2 * pi * i / n);
          const PairModel model(p, tables);
          const MeshState m0 = model.mesh().mean();
          const double    TE = d.torque, TL = TE * m0.lg.dot(gear_axis) / m0.lp.dot(pinion_axis);
          const StaticEquilibrium s = model.static_equilibrium(TL);
          const H5Group           e = g.group(label);
          e.write("static_mesh_force", s.mesh_force, "N", "F_m in the static equilibrium");
          e.write("static_deflection", s.deflection, "m", "delta_D - E_t - b_c, static");
          e.write("load_torque", TL, "N m", "T_L balancing the pinion torque");
          if (first)
            {
              const PairModes     modes = linear_modes(model);
              std::vector<double> rpm;
              for (int order = 1; order <= 3; ++order)
                for (double f : modes.frequency)
                  rpm.push_back(resonance_speed_rpm(f, z1, order));
              const hsize_t nm = modes.frequency.size();
              g.write("mode_frequency", modes.frequency, {nm}, "Hz",
                      "linear modes of the free DOFs at the mean mesh (a torque-driven train: the "
                      "first is "
                      "its rigid rotation)");
              g.write("mode_mesh_energy", modes.mesh_energy, {nm}, "1",
                      "share of each mode's strain energy in the mesh");
              g.write("pinion_teeth", double(z1), "1", "mesh orders: z_p per pinion turn");
              g.write("resonance_speed", rpm, {3, nm}, "rpm",
                      "pinion speed at which mesh order 1, 2, 3 meets each mode");
              log << "  " << pair.name << ": static mesh force " << s.mesh_force
                  << " N; modes with mesh energy above 5 %:";
              for (std::size_t i = 0; i < nm; ++i)
                if (modes.mesh_energy[i] > 0.05)
                  log << " " << modes.frequency[i] << " Hz";
              log << "\n";
              first = false;
            }
          SweepOptions o;
          o.motor_torque = TE, o.load_torque = TL;
          o.settle_cycles = d.settle_cycles, o.record_cycles = d.record_cycles;
          o.run.method            = d.integrator;
          o.run.steps_per_cycle   = d.steps_per_cycle;
          o.run.samples_per_cycle = std::min(32, d.steps_per_cycle);
          for (int i = 0; i < d.speeds; ++i)
            o.speeds.push_back(d.speed_from +
                               (d.speed_to - d.speed_from) * i / std::max(1, d.speeds - 1));
          PairVector q = s.q, v = PairVector::Zero();
          const auto up = sweep(model, q, v, o);
          std::reverse(o.speeds.begin(), o.speeds.end());
          const auto down = sweep(model, q, v, o);
          write_sweep(e.group("up"), up);
          write_sweep(e.group("down"), down);
          double dlf = 0;
          for (const auto &x : up)
            dlf = std::max(dlf, x.load_factor);
          log << "  " << pair.name << " " << label << ": " << d.speeds
              << " speeds up and down, largest dynamic load factor " << dlf << "\n";
        }
    }
}
} // namespace gearkit

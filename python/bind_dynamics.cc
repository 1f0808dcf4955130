// The Python module's library level for the dynamics, on library types (SI units): the 14-DOF
// pair model of an excitation as the dynamics stage builds it (driver/dynamics_models.h: the same
// functions), its speed sweeps (dynamics/sweep.h), and a gear train's model as the train stage
// builds it and its run (dynamics/train.h). Upstream stage results come from the stage cache
// (StageUpstream: run or reused as by the executable).
#include "driver/driver.h"
#include "driver/dynamics_models.h"
#include "dynamics/modes.h"
#include "python/bindings.h"

#include <cmath>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <sstream>
#include <thread>

namespace gearkit::python
{
namespace
{
/// An excitation of a scene's pair as the dynamics stage builds it, with the stage's sweep: its
/// options up (ascending speeds, the excitation's torques) and its blocks.
struct SceneExcitation
{
  std::string    pair;
  PairExcitation excitation;
  SweepOptions   sweep_up;
  int            blocks = 1, warmup = 0;
};

/// A 14-vector from Python (a state q or v), refused by name unless 14 finite numbers.
PairVector
pair_state(const std::vector<double> &x, const char *name)
{
  if (x.size() != std::size_t(pair_dofs))
    throw InputError("gearkit.sweep: " + std::string(name) + " has " + std::to_string(x.size()) +
                     " values; expected the 14 DOFs of the pair model (PairModel.dof_names)");
  PairVector v;
  for (int i = 0; i < pair_dofs; ++i)
    {
      if (!std::isfinite(x[std::size_t(i)]))
        throw InputError("gearkit.sweep: " + std::string(name) + "[" + std::to_string(i) +
                         "] is not finite; expected finite values");
      v[i] = x[std::size_t(i)];
    }
  return v;
}

const char *
integrator_name(Integrator i)
{
  return i == Integrator::newmark     ? "newmark"
         : i == Integrator::cvode_bdf ? "cvode bdf"
                                      : "cvode adams";
}

/// Refuses a scene whose outputs do not run `stage`: its parameters are checked only then.
void
require_stage(const Scene &scene, const std::string &stage)
{
  const std::vector<std::string> stages = required_stages(scene);
  if (std::find(stages.begin(), stages.end(), stage) == stages.end())
    throw InputError("scene " + scene.name + ": its outputs (Scene/outputs) do not run the " +
                     stage + " stage, whose parameters are checked only then; add " + stage +
                     " to Scene/outputs");
}

/// The excitation `label` of pair `pair` as the dynamics stage builds it; its upstream stages
/// run or reused in the scene's cache under output_root.
SceneExcitation
scene_excitation(const Scene &scene, const std::string &pair, const std::string &label,
                 const std::string &output_root, std::ostream &log)
{
  const PairScene &p = scene.pair(pair);
  if (label != "theoretical" && label != "measured")
    throw InputError("excitation = '" + label +
                     "' is not allowed; expected theoretical or measured");
  require_stage(scene, "dynamics");
  const DynamicsScene &d = scene.dynamics.at(pair);
  if (!(label == "measured" ? d.measured : d.theoretical))
    throw InputError("excitation = '" + label + "' is not allowed for pair " + pair +
                     ": Dynamics/" + pair + "/excitations does not sweep it");
  const StageUpstream      upstream(scene, "dynamics", output_root, log);
  const PairDynamicsInputs in = pair_dynamics_inputs(scene, p, upstream.upstream());
  SceneExcitation          s{pair, build_excitation(label, in, upstream.upstream()), {}, 1, 0};
  s.sweep_up = excitation_sweep_options(s.excitation, d, true);
  s.blocks = d.sweep_blocks, s.warmup = d.warmup_speeds;
  return s;
}

/// Speeds from Python [rad/s], refused by name unless finite and positive.
void
check_speeds(const std::vector<double> &speeds)
{
  if (speeds.empty())
    throw InputError("gearkit.sweep: speeds is empty; expected pinion speeds [rad/s] > 0");
  for (std::size_t i = 0; i < speeds.size(); ++i)
    if (!(std::isfinite(speeds[i]) && speeds[i] > 0))
      {
        std::ostringstream m;
        m << "gearkit.sweep: speeds[" << i << "] = " << speeds[i]
          << " is not allowed; expected pinion speeds > 0 in rad/s (rpm * pi / 30)";
        throw InputError(m.str());
      }
}

/// A sweep's points as NumPy arrays per speed (the names of results.h5's sweep groups where
/// they hold the same, but SI: speed in rad/s).
py::dict
sweep_dict(const std::vector<SweepPoint> &p, bool newmark)
{
  const auto column = [&](auto field) {
    using T = std::remove_cv_t<std::remove_reference_t<decltype(p.front().*field)>>;
    std::vector<T> v;
    for (const SweepPoint &x : p)
      v.push_back(x.*field);
    return array(v);
  };
  std::vector<int> status, diverged, events;
  for (const SweepPoint &x : p)
    status.push_back(x.diverged     ? 2
                     : x.period > 0 ? 0
                                    : 1),
        diverged.push_back(x.diverged), events.push_back(int(x.events));
  py::dict d;
  d["speed"]                 = column(&SweepPoint::speed);
  d["status"]                = array(status);
  d["dte_peak_to_peak"]      = column(&SweepPoint::dte_pp);
  d["dte_rms"]               = column(&SweepPoint::dte_rms);
  d["relative_peak_to_peak"] = column(&SweepPoint::relative_pp);
  d["relative_rms"]          = column(&SweepPoint::relative_rms);
  d["max_mesh_force"]        = column(&SweepPoint::max_force);
  d["dynamic_load_factor"]   = column(&SweepPoint::load_factor);
  d["contact_loss"]          = column(&SweepPoint::contact_loss);
  d["events"]                = array(events);
  d["period"]                = column(&SweepPoint::period);
  d["settled_cycles"]        = column(&SweepPoint::settled_cycles);
  d["diverged"]              = array(diverged);
  d["diverged_time"]         = column(&SweepPoint::diverged_time);
  if (newmark) // CVODE has no estimate (its tolerances): left out, not NaN
    {
      d["steps_per_cycle"] = column(&SweepPoint::steps_per_cycle);
      d["error_estimate"]  = column(&SweepPoint::error_estimate);
    }
  const int           R    = p.front().record_cycles;
  const std::size_t   bins = p.front().spectrum.size();
  py::array_t<double> spectrum({py::ssize_t(p.size()), py::ssize_t(bins)});
  auto                s = spectrum.mutable_unchecked<2>();
  for (std::size_t i = 0; i < p.size(); ++i)
    {
      if (p[i].spectrum.size() != bins)
        throw std::logic_error("gearkit.sweep: spectra of different lengths");
      for (std::size_t k = 0; k < bins; ++k)
        s(py::ssize_t(i), py::ssize_t(k)) = p[i].spectrum[k];
    }
  std::vector<double> order;
  for (std::size_t k = 0; k < bins; ++k)
    order.push_back(double(k) / R);
  d["spectrum_order"] = array(order);
  d["dte_spectrum"]   = spectrum;
  py::list series;
  for (const SweepPoint &x : p)
    if (!x.series_time.empty())
      series.append(py::dict(py::arg("speed") = x.speed, py::arg("time") = array(x.series_time),
                             py::arg("dte")                = array(x.series_dte),
                             py::arg("transmission_error") = array(x.series_transmission_error),
                             py::arg("mesh_force")         = array(x.series_force)));
  d["time_series"] = series;
  return d;
}

/// The sweep from (q, v) as the dynamics stage runs one: in blocks of speeds on threads.
std::vector<SweepPoint>
run_sweep(const PairModel &model, const PairVector &q, const PairVector &v,
          const SweepOptions &options, int blocks, int warmup)
{
  const auto results =
      run_sweeps(sweep_block_tasks(model, q, v, options, blocks, warmup),
                 std::max(1u, std::thread::hardware_concurrency()), "sweep: speed");
  std::vector<SweepPoint> points;
  for (const auto &r : results)
    points.insert(points.end(), r.begin(), r.end());
  return points;
}

void
bind_sweep_options(py::module_ &m)
{
  py::class_<RunOptions>(m, "RunOptions",
                         "Integrator options of the pair model (dynamics/integrators.h), SI")
      .def(py::init<>())
      .def_property(
          "method", [](const RunOptions &o) { return integrator_name(o.method); },
          [](RunOptions &o, const std::string &s) {
            for (Integrator i :
                 {Integrator::newmark, Integrator::cvode_bdf, Integrator::cvode_adams})
              if (s == integrator_name(i))
                return void(o.method = i);
            throw InputError("RunOptions.method = '" + s +
                             "' is not allowed; expected newmark, cvode bdf or cvode adams");
          })
      .def_readwrite("omega", &RunOptions::omega)
      .def_readwrite("motor_torque", &RunOptions::motor_torque)
      .def_readwrite("load_torque", &RunOptions::load_torque)
      .def_readwrite("mesh_cycles", &RunOptions::mesh_cycles)
      .def_readwrite("samples_per_cycle", &RunOptions::samples_per_cycle)
      .def_readwrite("relative_tolerance", &RunOptions::relative_tolerance)
      .def_readwrite("absolute_tolerance", &RunOptions::absolute_tolerance)
      .def_readwrite("steps_per_cycle", &RunOptions::steps_per_cycle)
      .def_readwrite("divergence_bound", &RunOptions::divergence_bound);
  py::class_<SweepOptions>(m, "SweepOptions",
                           "Options of a speed sweep (dynamics/sweep.h), SI: speeds in rad/s. "
                           "Lists (speeds, series_speeds) are set whole, not appended to.")
      .def(py::init<>())
      .def(py::init<const SweepOptions &>(), "A copy")
      .def("__copy__", [](const SweepOptions &o) { return SweepOptions(o); })
      .def("__deepcopy__", [](const SweepOptions &o, py::dict) { return SweepOptions(o); })
      .def_readwrite("speeds", &SweepOptions::speeds)
      .def_readwrite("motor_torque", &SweepOptions::motor_torque)
      .def_readwrite("load_torque", &SweepOptions::load_torque)
      .def_readwrite("settle_cycles", &SweepOptions::settle_cycles)
      .def_readwrite("record_cycles", &SweepOptions::record_cycles)
      .def_readwrite("steady_tolerance", &SweepOptions::steady_tolerance)
      .def_readwrite("min_settle_cycles", &SweepOptions::min_settle_cycles)
      .def_readwrite("divergence_factor", &SweepOptions::divergence_factor)
      .def_readwrite("warmup_speeds", &SweepOptions::warmup_speeds)
      .def_readwrite("spectrum_orders", &SweepOptions::spectrum_orders)
      .def_readwrite("series_speeds", &SweepOptions::series_speeds)
      .def_readwrite("run", &SweepOptions::run)
      .def_readwrite("accuracy", &SweepOptions::accuracy)
      .def_readwrite("most_steps", &SweepOptions::most_steps);
}

void
bind_pair_model(py::module_ &m)
{
  py::class_<StaticEquilibrium>(m, "StaticEquilibrium",
                                "Static equilibrium of the pair model (dynamics/pair_model.h)")
      .def_property_readonly("q", [](const StaticEquilibrium &s) { return PairVector(s.q); })
      .def_readonly("mesh_force", &StaticEquilibrium::mesh_force)
      .def_readonly("deflection", &StaticEquilibrium::deflection)
      .def_readonly("motor_torque", &StaticEquilibrium::motor_torque);
  py::class_<RadialBearing>(m, "RadialBearing")
      .def_readonly("position", &RadialBearing::position)
      .def_readonly("stiffness", &RadialBearing::stiffness)
      .def_readonly("damping", &RadialBearing::damping);
  py::class_<BodyParameters>(m, "BodyParameters", "A body of the pair model, SI")
      .def_readonly("mass", &BodyParameters::mass)
      .def_readonly("axial_inertia", &BodyParameters::axial_inertia)
      .def_readonly("transverse_inertia", &BodyParameters::transverse_inertia)
      .def_property_readonly("axis", [](const BodyParameters &b) { return vec3(b.axis); })
      .def_readonly("bearings", &BodyParameters::bearings)
      .def_readonly("axial_stiffness", &BodyParameters::axial_stiffness)
      .def_readonly("axial_damping", &BodyParameters::axial_damping);
  py::class_<ShaftParameters>(m, "ShaftParameters")
      .def_readonly("stiffness", &ShaftParameters::stiffness)
      .def_readonly("damping", &ShaftParameters::damping);
  py::class_<PairModelParameters>(m, "PairModelParameters",
                                  "The pair model's parameters as placed in the assembly, SI")
      .def_readonly("motor_inertia", &PairModelParameters::motor_inertia)
      .def_readonly("load_inertia", &PairModelParameters::load_inertia)
      .def_readonly("pinion", &PairModelParameters::pinion)
      .def_readonly("gear", &PairModelParameters::gear)
      .def_readonly("motor_shaft", &PairModelParameters::motor_shaft)
      .def_readonly("load_shaft", &PairModelParameters::load_shaft)
      .def_readonly("pinion_teeth", &PairModelParameters::pinion_teeth)
      .def_readonly("half_backlash", &PairModelParameters::half_backlash)
      .def_readonly("mesh_damping_ratio", &PairModelParameters::mesh_damping_ratio)
      .def_readonly("mesh_damping_in_contact_only",
                    &PairModelParameters::mesh_damping_in_contact_only)
      .def_readonly("torsion_only", &PairModelParameters::torsion_only)
      .def_readonly("speed_controlled_motor", &PairModelParameters::speed_controlled_motor);
  py::class_<PairModel>(m, "PairModel",
                        "The 14-DOF pair model (dynamics/pair_model.h) on its mesh tables, SI")
      .def_property_readonly_static("dof_names",
                                    [](py::object) {
                                      return std::vector<std::string>{
                                          "theta_E",  "X_g",      "Y_g",      "Z_g",    "theta_gx",
                                          "theta_gy", "theta_gz", "X_p",      "Y_p",    "Z_p",
                                          "theta_px", "theta_py", "theta_pz", "theta_L"};
                                    })
      .def_property_readonly("mass", [](const PairModel &p) { return PairMatrix(p.mass()); })
      .def_property_readonly("stiffness",
                             [](const PairModel &p) { return PairMatrix(p.stiffness()); })
      .def_property_readonly("damping", [](const PairModel &p) { return PairMatrix(p.damping()); })
      .def_property_readonly("active", [](const PairModel &p) { return PairVector(p.active()); })
      .def_property_readonly("free_dofs", &PairModel::free_dofs)
      .def_property_readonly("mesh_damping", &PairModel::mesh_damping, "c_m [N s/m]")
      .def_property_readonly("mesh_mass", &PairModel::mesh_mass, "m_e [kg]")
      .def_property_readonly("parameters", &PairModel::parameters)
      .def_property_readonly(
          "tables",
          [](const PairModel &p) {
            const MeshCycleSamples &t = p.tables();
            return py::dict(py::arg("cycles")        = t.cycles,
                            py::arg("interpolation") = t.interpolation == MeshInterpolation::makima
                                                           ? "makima"
                                                           : "trigonometric",
                            py::arg("transmission_error") = array(t.transmission_error),
                            py::arg("mesh_stiffness")     = array(t.mesh_stiffness),
                            py::arg("normal_pinion")      = vec3_array(t.normal_pinion),
                            py::arg("normal_gear")        = vec3_array(t.normal_gear),
                            py::arg("arm_pinion")         = vec3_array(t.arm_pinion),
                            py::arg("arm_gear")           = vec3_array(t.arm_gear));
          },
          "The mesh tables over one period of the excitation: E_t [m], K_m [N/m], normals, "
          "moment arms [m] (samples x 3)")
      .def(
          "mesh_at",
          [](const PairModel &p, double phase) {
            if (!std::isfinite(phase))
              throw InputError("PairModel.mesh_at: phase is not finite; expected mesh cycles");
            const MeshState s = p.mesh().at(phase);
            return py::dict(py::arg("transmission_error") = s.et, py::arg("rate") = s.det,
                            py::arg("mesh_stiffness") = s.km, py::arg("normal_pinion") = vec3(s.np),
                            py::arg("normal_gear") = vec3(s.ng), py::arg("arm_pinion") = vec3(s.lp),
                            py::arg("arm_gear") = vec3(s.lg));
          },
          py::arg("phase"), "The interpolated mesh at a phase [mesh cycles]")
      .def("static_equilibrium", &PairModel::static_equilibrium, py::arg("load_torque"),
           "The static equilibrium under the load torque [N m]")
      .def(
          "modes",
          [](const PairModel &p) {
            const PairModes modes = linear_modes(p);
            return py::dict(py::arg("frequency")   = array(modes.frequency),
                            py::arg("mesh_energy") = array(modes.mesh_energy),
                            py::arg("shapes")      = modes.shapes);
          },
          "Linear modes at the mean mesh: frequency [Hz], mesh energy share, mass-normalised "
          "shapes (DOF x mode)");
}
} // namespace

namespace
{
void
bind_excitation(py::module_ &m)
{
  py::class_<SceneExcitation, std::shared_ptr<SceneExcitation>>(
      m, "PairExcitation",
      "An excitation of a scene's pair (theoretical or measured flanks) as the dynamics stage "
      "builds it: the pair model on the TCA's tables in the system deflection's fixed point, its "
      "static equilibrium and torques, and the stage's sweep (Scene.dynamics_model)")
      .def_readonly("pair", &SceneExcitation::pair)
      .def_property_readonly("label", [](const SceneExcitation &s) { return s.excitation.label; })
      .def_property_readonly(
          "model",
          [](const SceneExcitation &s) -> const PairModel & { return s.excitation.model(); },
          py::return_value_policy::reference_internal)
      .def_property_readonly("motor_torque",
                             [](const SceneExcitation &s) { return s.excitation.motor_torque; })
      .def_property_readonly("load_torque",
                             [](const SceneExcitation &s) { return s.excitation.load_torque(); })
      .def_property_readonly("static_equilibrium",
                             [](const SceneExcitation &s) { return s.excitation.equilibrium(); })
      .def_property_readonly("excitation_cycles",
                             [](const SceneExcitation &s) { return s.excitation.cycles; })
      .def_property_readonly(
          "sweep_options", [](const SceneExcitation &s) { return s.sweep_up; },
          "The stage's sweep up (a copy): the scene's settings, speeds ascending [rad/s], the "
          "torques; reversed speeds give its sweep down")
      .def_readonly("sweep_blocks", &SceneExcitation::blocks)
      .def_readonly("warmup_speeds", &SceneExcitation::warmup)
      .def_property_readonly(
          "system_deflection",
          [](const SceneExcitation &s) {
            const SystemDeflection &d = s.excitation.deflection;
            return py::dict(py::arg("iterated")  = s.excitation.iterated,
                            py::arg("converged") = d.converged, py::arg("change") = array(d.change),
                            py::arg("gear_translation") = vec3(d.motion.translation),
                            py::arg("gear_rotation")    = vec3(d.motion.rotation));
          },
          "The fixed point: iterated (the scene's system deflection), converged, the motion's "
          "change per iteration [m], the gear's static motion relative to the pinion [m, rad]");
  m.def(
      "dynamics_excitation",
      [](const Scene &scene, const std::string &pair, const std::string &excitation,
         const std::string &output_root) {
        return std::make_shared<SceneExcitation>(
            logged<SceneExcitation>([&](std::ostream &out, std::ostream &) {
              return scene_excitation(scene, pair, excitation, output_root, out);
            }));
      },
      py::arg("scene"), py::arg("pair"), py::arg("excitation"), py::arg("output_root"));
  m.def(
      "sweep",
      [](const PairModel &model, const std::vector<double> &q, const std::vector<double> &v,
         const SweepOptions &options, int blocks, int warmup) {
        check_speeds(options.speeds);
        if (blocks < 1)
          throw InputError("gearkit.sweep: blocks = " + std::to_string(blocks) +
                           " is not allowed; expected 1 or more");
        if (warmup < 0)
          throw InputError("gearkit.sweep: warmup = " + std::to_string(warmup) +
                           " is not allowed; expected 0 or more");
        const PairVector q0 = pair_state(q, "start q"), v0 = pair_state(v, "start v");
        const auto       points = interruptible<std::vector<SweepPoint>>(
            [&] { return run_sweep(model, q0, v0, options, blocks, warmup); });
        return sweep_dict(points, options.run.method == Integrator::newmark);
      },
      py::arg("model"), py::arg("q"), py::arg("v"), py::arg("options"), py::arg("blocks"),
      py::arg("warmup"));
}

py::dict
train_result_dict(const TrainModel &model, const TrainResult &r)
{
  const auto rows = [](const std::vector<std::vector<double>> &x) {
    const std::size_t   n = x.empty() ? 0 : x.front().size();
    py::array_t<double> a({py::ssize_t(x.size()), py::ssize_t(n)});
    auto                w = a.mutable_unchecked<2>();
    for (std::size_t b = 0; b < x.size(); ++b)
      for (std::size_t i = 0; i < n; ++i)
        w(py::ssize_t(b), py::ssize_t(i)) = x[b][i];
    return a;
  };
  py::dict meshes;
  for (std::size_t i = 0; i < r.meshes.size(); ++i)
    {
      const MeshSeries   &s = r.meshes[i];
      std::vector<double> side, touch, separation, peak, peak_time, impulse;
      for (const TrainImpact &c : s.contacts)
        side.push_back(c.side == drive_side ? 1.0 : -1.0), touch.push_back(c.touch),
            separation.push_back(c.separation), peak.push_back(c.peak),
            peak_time.push_back(c.peak_time), impulse.push_back(c.impulse);
      meshes[py::str(model.meshes[i].name)] = py::dict(
          py::arg("relative") = array(s.relative), py::arg("force") = array(s.force),
          py::arg("force_magnitude") = array(s.magnitude), py::arg("pairs") = array(s.pairs),
          py::arg("impacts") = s.impacts, py::arg("drive_impacts") = s.drive_impacts,
          py::arg("coast_impacts") = s.coast_impacts, py::arg("max_force") = s.max_force,
          py::arg("max_force_time")  = s.max_force_time,
          py::arg("max_penetration") = s.max_penetration,
          py::arg("first_contact")   = s.first_contact,
          py::arg("contacts")        = py::dict(
                     py::arg("side") = array(side), py::arg("touch") = array(touch),
                     py::arg("separation") = array(separation), py::arg("peak") = array(peak),
                     py::arg("peak_time") = array(peak_time), py::arg("impulse") = array(impulse)));
    }
  return py::dict(py::arg("time") = array(r.t), py::arg("angle") = rows(r.angle),
                  py::arg("speed") = rows(r.speed), py::arg("work") = array(r.work),
                  py::arg("kinetic") = array(r.kinetic), py::arg("potential") = array(r.potential),
                  py::arg("dissipated")   = array(r.dissipated),
                  py::arg("energy_error") = r.energy_error, py::arg("steps") = r.steps,
                  py::arg("events")     = r.events,
                  py::arg("integrator") = r.method == TrainIntegrator::bdf ? "bdf" : "adams",
                  py::arg("meshes")     = meshes);
}

const TrainScene &
scene_train(const Scene &scene, const std::string &name)
{
  std::string known;
  for (const TrainScene &t : scene.trains)
    {
      if (t.name == name)
        return t;
      known += (known.empty() ? "" : ", ") + t.name;
    }
  throw InputError("train '" + name + "' is not in Scene/trains" +
                   (known.empty() ? " (the scene has none)" : " (" + known + ")"));
}

void
bind_train(py::module_ &m)
{
  py::class_<TrainRunOptions>(m, "TrainRunOptions",
                              "Options of a train's run (dynamics/train.h), SI")
      .def(py::init<>())
      .def_property(
          "method",
          [](const TrainRunOptions &o) {
            return o.method == TrainIntegrator::adams ? "adams"
                   : o.method == TrainIntegrator::bdf ? "bdf"
                                                      : "automatic";
          },
          [](TrainRunOptions &o, const std::string &s) {
            if (s == "adams" || s == "bdf" || s == "automatic")
              o.method = s == "adams" ? TrainIntegrator::adams
                         : s == "bdf" ? TrainIntegrator::bdf
                                      : TrainIntegrator::automatic;
            else
              throw InputError("TrainRunOptions.method = '" + s +
                               "' is not allowed; expected adams, bdf or automatic");
          })
      .def_readwrite("progress", &TrainRunOptions::progress)
      .def_readwrite("duration", &TrainRunOptions::duration)
      .def_readwrite("sample_rate", &TrainRunOptions::sample_rate)
      .def_readwrite("relative_tolerance", &TrainRunOptions::relative_tolerance)
      .def_readwrite("absolute_tolerance", &TrainRunOptions::absolute_tolerance)
      .def_readwrite("energy_tolerance", &TrainRunOptions::energy_tolerance)
      .def_readwrite("max_steps", &TrainRunOptions::max_steps)
      .def_readwrite("pairings_each_side", &TrainRunOptions::pairings_each_side)
      .def_readwrite("anti_alias", &TrainRunOptions::anti_alias);
  py::class_<TorqueLaw>(m, "TorqueLaw")
      .def_readonly("constant", &TorqueLaw::constant)
      .def_readonly("step", &TorqueLaw::step)
      .def_readonly("time_constant", &TorqueLaw::time_constant)
      .def_readonly("viscous", &TorqueLaw::viscous);
  py::class_<ImpactLaw>(m, "ImpactLaw")
      .def_readonly("stiffness", &ImpactLaw::stiffness)
      .def_readonly("exponent", &ImpactLaw::exponent)
      .def_readonly("damping", &ImpactLaw::damping)
      .def_readonly("depth", &ImpactLaw::depth);
  py::class_<TrainBody>(m, "TrainBody", "A rigid rotor of a train (read-only), SI")
      .def_readonly("name", &TrainBody::name)
      .def_readonly("inertia", &TrainBody::inertia)
      .def_readonly("initial_angle", &TrainBody::initial_angle)
      .def_readonly("initial_speed", &TrainBody::initial_speed)
      .def_readonly("constant_speed", &TrainBody::constant_speed)
      .def_readonly("torque", &TrainBody::torque)
      .def_readonly("has_crank", &TrainBody::has_crank);
  py::class_<TrainMesh>(m, "TrainMesh", "A gear mesh of a train (read-only), SI")
      .def_readonly("name", &TrainMesh::name)
      .def_readonly("driver", &TrainMesh::driver)
      .def_readonly("driven", &TrainMesh::driven)
      .def_readonly("pinion_angle_0", &TrainMesh::pinion_angle_0)
      .def_readonly("gear_angle_0", &TrainMesh::gear_angle_0)
      .def_readonly("law", &TrainMesh::law)
      .def_readonly("pinion_base_radius", &TrainMesh::pinion_base_radius)
      .def_readonly("gear_base_radius", &TrainMesh::gear_base_radius)
      .def_property_readonly("pinion_teeth",
                             [](const TrainMesh &t) { return t.teeth.pinion_teeth; })
      .def_property_readonly("gear_teeth", [](const TrainMesh &t) { return t.teeth.gear_teeth; })
      .def_property_readonly("mesh_stiffness",
                             [](const TrainMesh &t) { return array(t.mesh_stiffness); })
      .def_readonly("mesh_stiffness_start", &TrainMesh::mesh_stiffness_start);
  py::class_<TrainShaft>(m, "TrainShaft")
      .def_readonly("a", &TrainShaft::a)
      .def_readonly("b", &TrainShaft::b)
      .def_readonly("stiffness", &TrainShaft::stiffness)
      .def_readonly("damping", &TrainShaft::damping);
  py::class_<TrainModel, std::shared_ptr<TrainModel>>(
      m, "TrainModel", "A gear train's model (dynamics/train.h) as the train stage builds it")
      .def_readonly("bodies", &TrainModel::bodies)
      .def_readonly("meshes", &TrainModel::meshes)
      .def_readonly("shafts", &TrainModel::shafts)
      .def(
          "frequencies",
          [](const TrainModel &t, int body, double speed) {
            const TrainFrequencies f = train_frequencies(t, body, speed);
            return py::dict(py::arg("shaft") = array(f.shaft), py::arg("mesh") = array(f.mesh));
          },
          py::arg("body"), py::arg("speed"),
          "Kinematic frequencies [Hz] with body `body` at `speed` [rad/s]: per body and per mesh");
  m.def(
      "train_model",
      [](const Scene &scene, const std::string &name, const std::string &output_root) {
        const TrainScene &train = scene_train(scene, name);
        require_stage(scene, "train");
        return std::make_shared<TrainModel>(
            logged<TrainModel>([&](std::ostream &out, std::ostream &) {
              const StageUpstream upstream(scene, "train", output_root, out);
              return train_model(scene, train, upstream.upstream());
            }));
      },
      py::arg("scene"), py::arg("name"), py::arg("output_root"));
  m.def(
      "train_run_options",
      [](const Scene &scene, const std::string &name) { return scene_train(scene, name).run; },
      py::arg("scene"), py::arg("name"));
  m.def(
      "simulate_train",
      [](const TrainModel &model, TrainRunOptions options) {
        if (options.progress.empty())
          options.progress = "train: sample";
        const TrainResult r =
            interruptible<TrainResult>([&] { return simulate_train(model, options); });
        return train_result_dict(model, r);
      },
      py::arg("model"), py::arg("options"));
}
} // namespace

void
bind_dynamics(py::module_ &m)
{
  bind_sweep_options(m);
  bind_pair_model(m);
  bind_excitation(m);
  bind_train(m);
}
} // namespace gearkit::python

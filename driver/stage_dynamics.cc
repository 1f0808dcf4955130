// Stage "dynamics": the 14-DOF pair model (dynamics/pair_model.h) on the tables of the unloaded
// TCA (E_t = lambda_pz e_0, normals, moment arms of the contact that carries the load) and K_m
// from the stiffness stage (or constant); static equilibrium, linear modes with the resonance
// speeds of the first mesh orders, and speed sweeps up and down with continuation, for the
// theoretical flanks (one mesh cycle repeats) and the measured flanks (their teeth differ: the
// excitation's period is the TCA's mesh cycles, interpolated by makima). The sweeps - per
// excitation and direction, optionally in blocks of speeds - run on threads, and spread over
// the MPI processes under mpirun; every process gathers all results. What the stage builds
// before it sweeps (the excitations, the sweeps' options and tasks) is declared in
// driver/dynamics_models.h: the Python module builds the same through the same functions.
#include "driver/dynamics_models.h"
#include "driver/pair_tca.h"
#include "driver/results_dynamics.h"
#include "driver/results_stiffness.h"
#include "driver/stages.h"
#include "dynamics/deflection.h"
#include "dynamics/modes.h"
#include "dynamics/newmark_error.h"
#include "dynamics/sweep.h"
#include "stiffness/collective.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <thread>
#include <tuple>

namespace gearkit
{
namespace
{
// A sweep point as numbers (for the MPI gather) and back.
void
pack(const SweepPoint &p, std::vector<double> &out)
{
  out.insert(out.end(), {p.speed, p.dte_pp, p.dte_rms, p.relative_pp, p.relative_rms, p.max_force,
                         p.load_factor, p.contact_loss, p.error_estimate, p.diverged_time,
                         double(p.events), double(p.settled_cycles), double(p.steps_per_cycle),
                         double(p.period), double(p.record_cycles), double(p.diverged)});
  for (const auto *v :
       {&p.spectrum, &p.series_time, &p.series_dte, &p.series_transmission_error, &p.series_force})
    {
      out.push_back(double(v->size()));
      out.insert(out.end(), v->begin(), v->end());
    }
}

SweepPoint
unpack(const std::vector<double> &in, std::size_t &at)
{
  SweepPoint p;
  for (double *x : {&p.speed, &p.dte_pp, &p.dte_rms, &p.relative_pp, &p.relative_rms, &p.max_force,
                    &p.load_factor, &p.contact_loss, &p.error_estimate, &p.diverged_time})
    *x = in[at++];
  p.events          = std::size_t(in[at++]);
  p.settled_cycles  = int(in[at++]);
  p.steps_per_cycle = int(in[at++]);
  p.period          = int(in[at++]);
  p.record_cycles   = int(in[at++]);
  p.diverged        = in[at++] != 0;
  for (auto *v :
       {&p.spectrum, &p.series_time, &p.series_dte, &p.series_transmission_error, &p.series_force})
    {
      const auto n = std::size_t(in[at++]);
      v->assign(in.begin() + long(at), in.begin() + long(at + n));
      at += n;
    }
  return p;
}

/// The tasks, spread over the MPI processes (task i on process i mod size) and each process's
/// share of the threads; every process returns all results.
std::vector<std::vector<SweepPoint>>
run_everywhere(const std::vector<SweepTask> &tasks, const std::string &progress)
{
  const unsigned                 size  = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const std::vector<std::size_t> index = my_jobs(tasks.size(), MPI_COMM_WORLD);
  std::vector<SweepTask>         mine;
  for (const std::size_t i : index)
    mine.push_back(tasks[i]);
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency() / size);
  std::vector<std::vector<SweepPoint>> results(tasks.size());
  std::vector<std::vector<SweepPoint>> done;
  // a failure on any process is thrown on all (before the results are gathered)
  collectively(MPI_COMM_WORLD, [&] { done = run_sweeps(mine, threads, progress); });
  for (std::size_t k = 0; k < mine.size(); ++k)
    results[index[k]] = done[k];
  share_jobs(
      MPI_COMM_WORLD, index,
      [&](std::size_t i, std::vector<double> &out) {
        out.push_back(double(results[i].size()));
        for (const SweepPoint &p : results[i])
          pack(p, out);
      },
      [&](std::size_t i, const std::vector<double> &in, std::size_t &at) {
        const auto n = std::size_t(in[at++]);
        for (std::size_t k = 0; k < n; ++k)
          results[i].push_back(unpack(in, at));
      });
  return results;
}

/// The system deflection of one excitation: iterations, the gear's motion, the misalignment it
/// adds to the scene's (`m` less `tca`'s), the deflected TCA's tables and the shifts of the
/// contact pattern and of e_0.
void
write_deflection(const H5Group &g, const SystemDeflection &sd, const TcaScene &tca,
                 const Misalignment &m, const PairMembers &moved, const TcaResult &deflected,
                 const H5Group &aligned, std::ostream &log, const std::string &what)
{
  const hsize_t n = sd.change.size();
  g.write("iterations", double(n));
  g.write("converged", double(sd.converged));
  g.write("change", sd.change, {n});
  const std::vector<double> t(sd.motion.translation.data(), sd.motion.translation.data() + 3),
      w(sd.motion.rotation.data(), sd.motion.rotation.data() + 3);
  g.write("gear_translation", t, {3});
  g.write("gear_rotation", w, {3});
  const Misalignment &s = tca.misalignment;
  Misalignment        added;
  added.offset                = m.offset - s.offset;
  added.centre_distance_error = m.centre_distance_error - s.centre_distance_error;
  added.crossing_angle        = m.crossing_angle - s.crossing_angle;
  added.intersecting_angle    = m.intersecting_angle - s.intersecting_angle;
  added.pinion_axial_shift    = m.pinion_axial_shift - s.pinion_axial_shift;
  added.gear_axial_shift      = m.gear_axial_shift - s.gear_axial_shift;
  for (auto [name, value] : {std::pair{"offset", added.offset},
                             {"centre_distance_error", added.centre_distance_error},
                             {"crossing_angle", added.crossing_angle},
                             {"intersecting_angle", added.intersecting_angle},
                             {"pinion_axial_shift", added.pinion_axial_shift},
                             {"gear_axial_shift", added.gear_axial_shift}})
    g.write(name, value);
  const H5Group tables       = g.group("tca");
  const double  peak_to_peak = write_tca_tables(deflected, tca, moved, tables).first;
  const Vec2    shift        = contact_pattern_centre(tables) - contact_pattern_centre(aligned);
  const auto    e0           = contact_tables(aligned).transmission_error;
  double        mean_shift   = -std::accumulate(e0.begin(), e0.end(), 0.0);
  for (const TcaPosition &p : deflected.positions)
    mean_shift += p.transmission_error;
  mean_shift /= double(e0.size());
  g.write("pattern_shift", std::vector<double>{shift.x(), shift.y()}, {2});
  g.write("transmission_error_mean_shift", mean_shift);
  log << "  " << what << ": system deflection " << (sd.converged ? "converged" : "NOT converged")
      << " in " << n << " TCA runs: ";
  if (moved.centre_distance == 0) // bevel
    log << "offset dE " << added.offset * 1e6 << " um, pinion axial dP "
        << added.pinion_axial_shift * 1e6 << " um, gear axial dG " << added.gear_axial_shift * 1e6
        << " um, shaft angle " << added.intersecting_angle * 1e3 << " mrad";
  else
    log << "centre distance " << added.centre_distance_error * 1e6 << " um, offset "
        << added.offset * 1e6 << " um, crossing " << added.crossing_angle * 1e3
        << " mrad, inclination " << added.intersecting_angle * 1e3 << " mrad, gear axial "
        << added.gear_axial_shift * 1e6 << " um";
  log << "; contact pattern moves " << shift.x() * 1e3 << " mm radially, " << shift.y() * 1e3
      << " mm axially on the gear; e_0 peak-to-peak "
      << (*std::max_element(e0.begin(), e0.end()) - *std::min_element(e0.begin(), e0.end())) * 1e6
      << " -> " << peak_to_peak * 1e6 << " urad, mean " << mean_shift * 1e6 << " urad\n";
}

/// Linear modes at the model's mean mesh and the resonance speeds of mesh orders 1 to 3.
void
write_modes(const H5Group &g, const PairModel &model, const std::string &label, int z1,
            std::ostream &log, const std::string &pair)
{
  const PairModes     modes = linear_modes(model);
  std::vector<double> rpm;
  for (int order = 1; order <= 3; ++order)
    for (double f : modes.frequency)
      rpm.push_back(resonance_speed_rpm(f, z1, order));
  const hsize_t nm = modes.frequency.size();
  g.write("mode_frequency", modes.frequency, {nm}, label == "theoretical" ? 0 : 1);
  g.write("mode_mesh_energy", modes.mesh_energy, {nm});
  g.write("pinion_teeth", double(z1));
  g.write("resonance_speed", rpm, {3, nm});
  log << "  " << pair << ": modes with mesh energy above 5 %:";
  for (std::size_t i = 0; i < nm; ++i)
    if (modes.mesh_energy[i] > 0.05)
      log << " " << modes.frequency[i] << " Hz";
  log << "\n";
}

/// Newmark with an accuracy: the steps per mesh cycle it asks for at every swept speed (the
/// estimate for the tables' forcing, as the sweep takes them: NewmarkError::steps from the
/// scene's least steps, to the sweep's most) must reach it; else the accuracy is refused by its
/// own name - not by the steps it implies, which the user did not set - with those steps, the
/// limit, and the accuracy reachable within it: the largest error at the most steps over the
/// speeds (with it, every speed reaches).
void
check_accuracy(const PairModel &model, double load_torque, const DynamicsScene &d,
               const std::string &pair)
{
  if (!(d.sweep.run.method == Integrator::newmark && d.sweep.accuracy > 0))
    return;
  const int          most     = std::max(d.sweep.most_steps, d.sweep.run.steps_per_cycle);
  const int          multiple = d.sweep.run.samples_per_cycle;
  const NewmarkError newmark(model, load_torque);
  double             reachable = 0, worst_speed = 0, worst_error = 0;
  for (double w : sweep_speeds(d))
    {
      const double error = newmark.forced(w, most);
      reachable          = std::max(reachable, error);
      const int steps =
          newmark.steps(w, d.sweep.accuracy, d.sweep.run.steps_per_cycle, multiple, most);
      if (newmark.forced(w, steps) > d.sweep.accuracy && error > worst_error)
        worst_speed = w, worst_error = error;
    }
  if (!(worst_error > 0))
    return;
  constexpr int beyond = 1 << 30;
  const int     asked  = newmark.steps(worst_speed, d.sweep.accuracy, most, multiple, beyond);
  // the reachable accuracy to three digits, rounded up (so that the value as printed passes)
  const double       scale = std::pow(10.0, std::floor(std::log10(reachable)) - 2);
  const double       least = std::ceil(reachable / scale) * scale;
  std::ostringstream m;
  m << "Dynamics/" << pair << "/accuracy = " << plausible_number(d.sweep.accuracy)
    << " is not allowed with integrator = newmark: at "
    << plausible_number(std::round(worst_speed * 60 / (2 * pi))) << " rpm it asks for "
    << (asked >= beyond ? "more than " : "") << asked
    << " Newmark steps per mesh cycle (the rule's error estimated for the tables' forcing, "
       "dynamics/newmark_error.h), beyond the "
    << most << " a speed of the sweep may take; within them the DTE's relative RMS error comes "
    << "down to " << plausible_number(worst_error) << " there"
    << (worst_error < reachable ? " and to " + plausible_number(reachable) + " at every swept speed"
                                : ", the most at any swept speed")
    << "; expected an accuracy of at least " << plausible_number(least)
    << " (or integrator = cvode bdf)";
  throw InputError(m.str());
}

/// Parametric stability of the mesh in contact at every swept speed (Floquet), in `g`: with
/// Newmark on the steps per mesh cycle the sweeps took at that speed (`steps`, ascending speeds:
/// the more of up and down), so the multipliers are those of the motion the sweep computed.
void
write_stability(const H5Group &g, const PairModel &model, const DynamicsScene &d, double TE,
                double TL, const std::vector<int> &steps, std::ostream &log,
                const std::string &what)
{
  std::vector<double>       rpm, radius;
  std::vector<int>          grows;
  std::string               unstable;
  const std::vector<double> speeds = sweep_speeds(d);
  for (std::size_t i = 0; i < speeds.size(); ++i)
    {
      const double w = speeds[i];
      RunOptions   r = d.sweep.run;
      r.omega        = w;
      r.motor_torque = TE, r.load_torque = TL;
      if (d.sweep.run.method == Integrator::newmark)
        r.steps_per_cycle = steps.at(i);
      rpm.push_back(w * 60 / (2 * pi));
      radius.push_back(std::abs(floquet_multipliers(model, r).front()));
      grows.push_back(parametrically_unstable(radius.back()));
      if (grows.back())
        unstable += " " + std::to_string(int(std::lround(rpm.back())));
    }
  const hsize_t n = rpm.size();
  g.write("speed", rpm, {n});
  g.write("spectral_radius", radius, {n});
  g.write("unstable", grows, {n});
  if (!unstable.empty())
    log << "  " << what << ": parametrically unstable in contact (Floquet) at [rpm]:" << unstable
        << "\n";
}
/// K_m over the mesh cycle (n samples): the scene's constant and variation, or the stiffness
/// stage's at the torque nearest the scene's (the measured flanks' where there are some).
std::vector<double>
mesh_stiffness_table(const DynamicsScene &d, const Upstream &upstream, const PairScene &pair,
                     bool measured, int n)
{
  if (!d.fe_stiffness)
    return varying_mesh_stiffness(d.mesh_stiffness, d.stiffness_variation, n);
  const H5Group         all = upstream.at("stiffness")->group(pair.name);
  const StiffnessRecord r = measured && all.has("measured") ? read_mesh_cycle(all.group("measured"))
                                                            : read_mesh_cycle(all);
  return resample_periodic(r.mesh_stiffness_at(nearest_torque(r.torques, d.torque)), n);
}

/// One excitation's record in <pair>/<label>: the system deflection (where it iterated), the
/// static equilibrium and the excitation's period; and its lines of the log.
void
write_excitation(const PairExcitation &e, const PairDynamicsInputs &in, const Upstream &upstream,
                 const H5Group &g, std::ostream &log)
{
  const PairScene &pair     = *in.pair;
  const bool       measured = e.label == "measured";
  const H5Group    eg       = g.group(e.label, "<excitation>");
  if (e.iterated)
    {
      const H5Group &ste = *upstream.at("ste");
      const H5Group  aligned =
          measured ? ste.group(pair.name).group("measured") : ste.group(pair.name);
      write_deflection(eg.group("deflection"), e.deflection, *in.tca, e.misalignment,
                       e.moved ? *e.moved : in.members, e.deflected, aligned, log,
                       pair.name + " " + e.label);
    }
  eg.write("static_mesh_force", e.equilibrium().mesh_force);
  eg.write("static_deflection", e.equilibrium().deflection);
  eg.write("load_torque", e.load_torque());
  eg.write("excitation_cycles", double(e.cycles));
  const auto  &et   = e.model().tables().transmission_error;
  const double wrap = et.front() - et.back();
  double       step = 0;
  for (std::size_t i = 1; i < et.size(); ++i)
    step = std::max(step, std::abs(et[i] - et[i - 1]));
  eg.write("wrap_step", wrap);
  log << "  " << pair.name << " " << e.label << ": " << e.cycles << " mesh cycle"
      << (e.cycles > 1 ? "s" : "") << " of " << in.tca->options.positions_per_mesh
      << " samples per period";
  if (measured)
    log << "; E_t steps " << wrap * 1e6 << " um where the period wraps (largest step "
        << "between samples " << step * 1e6 << " um)";
  log << "\n";
}

/// The sweeps' tasks: per excitation up and down (each from the static equilibrium at its
/// first speed), in blocks; `first_task` gets where each (excitation, direction) begins, and the
/// end.
std::vector<SweepTask>
sweep_tasks(const std::vector<PairExcitation> &excitations, const DynamicsScene &d,
            std::vector<std::size_t> &first_task)
{
  std::vector<SweepTask> tasks;
  for (const PairExcitation &e : excitations)
    for (bool up : {true, false})
      {
        first_task.push_back(tasks.size());
        for (SweepTask &t :
             sweep_block_tasks(e.model(), e.equilibrium().q, PairVector::Zero(),
                               excitation_sweep_options(e, d, up), d.sweep_blocks, d.warmup_speeds))
          tasks.push_back(std::move(t));
      }
  first_task.push_back(tasks.size());
  return tasks;
}

/// The points of excitation x's sweep up (dir 0) or down (1), gathered from its tasks.
std::vector<SweepPoint>
sweep_points(std::size_t x, int dir, const std::vector<std::size_t> &first_task,
             const std::vector<std::vector<SweepPoint>> &results)
{
  const std::size_t       j = 2 * x + std::size_t(dir);
  std::vector<SweepPoint> points;
  for (std::size_t t = first_task[j]; t < first_task[j + 1]; ++t)
    points.insert(points.end(), results[t].begin(), results[t].end());
  return points;
}

/// Newmark's steps per mesh cycle at each speed of excitation x's sweeps, ascending speeds: the
/// more of the sweep up's and the sweep down's.
std::vector<int>
sweep_steps(std::size_t x, const std::vector<std::size_t> &first_task,
            const std::vector<std::vector<SweepPoint>> &results)
{
  const std::vector<SweepPoint> up   = sweep_points(x, 0, first_task, results),
                                down = sweep_points(x, 1, first_task, results);
  if (up.size() != down.size())
    throw std::logic_error("sweep_steps: the sweeps up and down differ in their speeds");
  std::vector<int> steps;
  for (std::size_t i = 0; i < up.size(); ++i)
    steps.push_back(std::max(up[i].steps_per_cycle, down[up.size() - 1 - i].steps_per_cycle));
  return steps;
}

/// One excitation's sweeps (up and down) written to <pair>/<label>/{up,down}, and the log's
/// summary: the largest load factor, the speeds that did not settle, did not reach the accuracy
/// or diverged.
void
write_sweeps(const PairExcitation &e, std::size_t x, const std::vector<std::size_t> &first_task,
             const std::vector<std::vector<SweepPoint>> &results, std::size_t n_tasks,
             const DynamicsScene &d, const std::string &pair, const H5Group &g, std::ostream &log)
{
  const H5Group eg  = g.group(e.label, "<excitation>");
  double        dlf = 0, unreached_error = 0;
  std::string   unsteady, diverged, unreached;
  for (int dir = 0; dir < 2; ++dir)
    {
      const std::vector<SweepPoint> points = sweep_points(x, dir, first_task, results);
      write_sweep(eg.group(dir == 0 ? "up" : "down", "<sweep>"), points);
      for (const auto &pt : points)
        {
          const std::string at = " " + std::to_string(int(std::lround(pt.speed * 60 / (2 * pi)))) +
                                 (dir == 0 ? " up" : " down");
          if (pt.diverged)
            {
              std::ostringstream when;
              when << at << " (after " << pt.diverged_time * 1e3 << " ms)";
              diverged += when.str();
            }
          else
            dlf = std::max(dlf, pt.load_factor);
          if (!pt.diverged && pt.period == 0 && d.sweep.steady_tolerance > 0)
            unsteady += at;
          // Newmark at the sweep's most steps, its error estimate still above the accuracy
          // (the recorded motion's harmonics ask for more)
          if (!pt.diverged && d.sweep.accuracy > 0 && pt.error_estimate > d.sweep.accuracy)
            unreached += at, unreached_error = std::max(unreached_error, pt.error_estimate);
        }
    }
  log << "  " << pair << " " << e.label << ": " << d.speeds << " speeds up and down in " << n_tasks
      << " tasks, largest dynamic load factor " << dlf
      << (diverged.empty() ? "" : " (of the speeds that did not diverge)") << "\n";
  if (!unsteady.empty())
    log << "  " << pair << " " << e.label << ": not steady within " << d.sweep.settle_cycles
        << " mesh cycles (growing or not periodic) at [rpm]:" << unsteady << "\n";
  if (!unreached.empty())
    log << "  " << pair << " " << e.label << ": accuracy " << d.sweep.accuracy
        << " not reached within the sweep's most Newmark steps ("
        << std::max(d.sweep.most_steps, d.sweep.run.steps_per_cycle)
        << " per mesh cycle; the recorded motion's harmonics asked for more), error "
           "estimates up to "
        << unreached_error << " (error_estimate) at [rpm]:" << unreached << "\n";
  if (!diverged.empty())
    log << "  " << pair << " " << e.label << ": DIVERGED (the response grew past "
        << int(SweepOptions().divergence_factor)
        << " times its length scale: no results there, status 2) at [rpm]:" << diverged << "\n";
}
} // namespace

PairDynamicsInputs
pair_dynamics_inputs(const Scene &scene, const PairScene &pair, const Upstream &upstream)
{
  const DynamicsScene &d   = scene.dynamics.at(pair.name);
  const TcaScene      &tca = scene.tca.at(pair.name);
  PairMembers members = theoretical_members(pair, tca, upstream.at("flanks")->group(pair.name));
  const PairModelParameters p = placed_in_assembly(d.model, members.pinion->teeth(), Vec3::UnitZ(),
                                                   members.assembly.gear_axis());
  return {&pair, &d, &tca, std::move(members), p};
}

PairExcitation
build_excitation(const std::string &label, const PairDynamicsInputs &in, const Upstream &upstream)
{
  const PairScene     &pair        = *in.pair;
  const DynamicsScene &d           = *in.dynamics;
  const TcaScene      &tca         = *in.tca;
  const PairMembers   &members     = in.members;
  const bool           measured    = label == "measured";
  const H5Group        ste         = upstream.at("ste")->group(pair.name);
  const int            n           = tca.options.positions_per_mesh;
  const Vec3           pinion_axis = Vec3::UnitZ();
  const Vec3           gear_axis   = -members.assembly.gear_axis(); // its driven sense
  PairExcitation       e;
  e.label        = label;
  e.motor_torque = d.torque;
  e.cycles =
      measured ? (d.excitation_cycles > 0 ? d.excitation_cycles : tca.options.mesh_cycles) : 1;
  const int K = e.cycles;
  // the tables of an analysis; the system deflection's fixed point over them
  std::optional<H5Group> measured_ste;
  if (measured)
    measured_ste.emplace(ste.group("measured"));
  const H5Group &aligned   = measured ? *measured_ste : ste;
  const auto     tables_of = [&](const ContactTables &c) {
    MeshCycleSamples tables = mesh_cycle_samples(
            c, n, K, pinion_axis, mesh_stiffness_table(d, upstream, pair, measured, n));
    if (measured) // kinks and noise: no ringing between the samples
      tables.interpolation = MeshInterpolation::makima;
    if (!d.tca_transmission_error)
      for (int i = 0; i < n * K; ++i)
        tables.transmission_error[std::size_t(i)] =
            d.transmission_error_amplitude * std::sin(2 * pi * i / n);
    return tables;
  };
  // the measured flanks, read when the deflection first needs them
  std::pair<MemberPointer, MemberPointer> flanks;
  e.misalignment       = tca.misalignment;
  const auto tables_at = [&](const RigidMotion &u) {
    DeflectedTables out;
    if (u.translation.isZero(0) && u.rotation.isZero(0))
      return out.tables = tables_of(contact_tables(aligned)), out;
    TcaScene t     = tca;
    t.misalignment = misalignment_after(members.assembly, tca.misalignment, u, &out.taken);
    e.misalignment = t.misalignment;
    e.moved        = theoretical_members(pair, t, upstream.at("flanks")->group(pair.name));
    if (measured && !flanks.first)
      flanks = measured_members(upstream.at("measured")->group(pair.name));
    try
      {
        e.deflected = pair_tca(measured ? flanks.first : e.moved->pinion,
                               measured ? flanks.second : e.moved->gear, e.moved->assembly, t,
                               measured, [] {});
      }
    catch (const InputError &error)
      {
        std::ostringstream msg;
        msg << "Dynamics/" << pair.name << "/system deflection: the static load moves "
            << "the gear by " << u.translation.norm() * 1e6 << " um and " << u.rotation.norm() * 1e3
            << " mrad relative to the pinion, and the TCA "
            << "there fails (" << error.what() << "); stiffen the supports (bearing and "
            << "axial stiffness), lower the torque, or set system deflection = false";
        throw InputError(msg.str());
      }
    out.tables = tables_of(contact_tables(e.deflected));
    return out;
  };
  SystemDeflectionOptions so;
  so.motor_torque = d.torque;
  so.pinion_axis = pinion_axis, so.gear_axis = gear_axis;
  so.pinion_centre  = members.assembly.pinion_centre();
  so.gear_centre    = members.assembly.gear_to_global(Vec3::Zero(), 0);
  so.max_iterations = d.system_deflection && d.tca_transmission_error ? 10 : 0;
  e.iterated        = so.max_iterations > 0;
  e.deflection      = system_deflection(in.parameters, tables_at, so);
  return e;
}

std::vector<double>
sweep_speeds(const DynamicsScene &d)
{
  std::vector<double> w;
  for (int i = 0; i < d.speeds; ++i)
    w.push_back(d.speed_from + (d.speed_to - d.speed_from) * i / std::max(1, d.speeds - 1));
  return w;
}

SweepOptions
excitation_sweep_options(const PairExcitation &e, const DynamicsScene &d, bool up)
{
  SweepOptions o = d.sweep;
  o.motor_torque = e.motor_torque, o.load_torque = e.load_torque();
  o.speeds = sweep_speeds(d);
  if (!up)
    std::reverse(o.speeds.begin(), o.speeds.end());
  return o;
}

std::vector<SweepTask>
sweep_block_tasks(const PairModel &model, const PairVector &q, const PairVector &v,
                  const SweepOptions &options, int blocks, int warmup)
{
  std::vector<SweepTask> tasks;
  for (const SweepOptions &b : split_sweep(options, blocks, warmup))
    tasks.push_back({&model, q, v, b});
  return tasks;
}

void
run_dynamics_stage(const Scene &scene, const Upstream &upstream, const H5Group &out,
                   std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      // 1. The pair and its model placed in the assembly.
      const DynamicsScene     &d  = scene.dynamics.at(pair.name);
      const PairDynamicsInputs in = pair_dynamics_inputs(scene, pair, upstream);
      const int                z1 = in.members.pinion->teeth();

      // 2. The excitations: models on the TCA's tables, static equilibria, the modes.
      std::vector<PairExcitation> excitations;
      const H5Group               g = out.group(pair.name, "<pair>");
      for (const char *label : {"theoretical", "measured"})
        if (std::string(label) == "measured" ? d.measured : d.theoretical)
          {
            excitations.push_back(build_excitation(label, in, upstream));
            write_excitation(excitations.back(), in, upstream, g, log);
          }
      log << "  " << pair.name << ": static mesh force "
          << excitations.front().equilibrium().mesh_force << " N\n";
      write_modes(g, excitations.front().model(), excitations.front().label, z1, log, pair.name);
      for (const PairExcitation &e : excitations)
        check_accuracy(e.model(), e.load_torque(), d, pair.name);

      // 3. The sweeps, shared among the processes and threads; the Floquet stability.
      std::vector<std::size_t>     first_task; // per (excitation, direction)
      const std::vector<SweepTask> tasks = sweep_tasks(excitations, d, first_task);
      const auto results = run_everywhere(tasks, "dynamics " + pair.name + ": speed");
      for (std::size_t x = 0; x < excitations.size(); ++x)
        {
          const PairExcitation &e = excitations[x];
          write_stability(g.group(e.label, "<excitation>").group("stability"), e.model(), d,
                          e.motor_torque, e.load_torque(), sweep_steps(x, first_task, results), log,
                          pair.name + " " + e.label);
        }

      // 4. The sweeps' results.
      for (std::size_t x = 0; x < excitations.size(); ++x)
        write_sweeps(excitations[x], x, first_task, results, tasks.size(), d, pair.name, g, log);
    }
}
} // namespace gearkit

// Stage "train": the impact dynamics of every gear train of the scene (dynamics/train.h). Each
// mesh's tooth pair contact curves come from the pair's involute flanks at the mesh's centre
// distance (tca/tooth_pairs.h), its gear starts in the middle of the backlash (or touching),
// and the run is written with its kinematic frequencies, the mesh forces' spectra with the lines
// found at the mesh frequencies, their harmonics and sidebands, and a spectrogram of the first
// mesh's force. The train's model (train_model, driver/dynamics_models.h) is the Python module's
// too.
#include "base/spectrum.h"
#include "driver/dynamics_models.h"
#include "driver/results_stiffness.h"
#include "driver/stages.h"
#include "dynamics/train.h"
#include "tca/tooth_pairs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace gearkit
{
namespace
{
/// The stiffness stage's K_m of a pair over its mesh cycle at the loaded-contact torque nearest
/// `torque` (0: the largest): the mesh's TrainMesh::mesh_stiffness and its start angle.
void
fe_mesh_stiffness(const H5Group &stiffness, const std::string &pair, double torque, int z1,
                  TrainMesh &m)
{
  const StiffnessRecord      r   = read_mesh_cycle(stiffness.group(pair));
  const std::vector<double> &phi = r.cycle.pinion_angle;
  const std::size_t          n   = r.cycle.positions;
  // uniform positions over one mesh cycle (the stiffness stage's), or the table is refused
  const double step = 2 * pi / z1 / double(std::max<std::size_t>(n, 1));
  for (std::size_t i = 1; i < phi.size(); ++i)
    if (phi.size() != n || n < 2 || std::abs(phi[i] - phi[i - 1] - step) > 1e-9 * step)
      throw InputError("stiffness/" + pair + "/pinion_angle: positions that are not " +
                       std::to_string(n) +
                       " uniform steps over one mesh cycle are not allowed "
                       "for a train mesh's K_m (stiffness = finite elements)");
  m.mesh_stiffness       = r.mesh_stiffness_at(nearest_torque(r.torques, torque));
  m.mesh_stiffness_start = phi.front();
}

/// The lines of a mesh's force spectrum at its GMF harmonics and their sidebands (every
/// shaft frequency of the train that the spectrum resolves).
struct LineTable
{
  std::vector<double> expected, frequency, amplitude, floor;
  std::vector<int>    found, harmonic, sideband, shaft;
};

LineTable
find_lines(const FrequencySpectrum &s, double gmf, const std::vector<double> &shafts,
           const TrainScene &train)
{
  LineTable    t;
  const double top   = s.resolution * double(s.amplitude.size() - 3);
  const double res   = s.resolution;
  double       f_min = gmf;
  for (double f : shafts)
    if (f > 1.5 * res / 0.45) // resolved: its sidebands' bands hold at least 3 bins
      f_min = std::min(f_min, f);
  // one band width for every line of the mesh: less than half the closest spacing
  const double half = std::max(0.45 * f_min, 1.5 * res);
  auto         look = [&](double f, int h, int order, int shaft) {
    if (f - half <= res || f + half >= top)
      return;
    const ExpectedLine e = spectral_line_near(s, f, half);
    t.expected.push_back(f);
    t.frequency.push_back(e.line.frequency);
    t.amplitude.push_back(e.line.amplitude);
    t.floor.push_back(e.floor);
    t.found.push_back(e.found);
    t.harmonic.push_back(h);
    t.sideband.push_back(order);
    t.shaft.push_back(shaft);
  };
  for (int h = 1; h <= train.harmonics; ++h)
    {
      look(h * gmf, h, 0, -1);
      for (std::size_t b = 0; b < shafts.size(); ++b)
        if (0.45 * shafts[b] >= half * (1 - 1e-12))
          for (int j = 1; j <= train.sidebands; ++j)
            for (int sign : {-1, 1})
              look(h * gmf + sign * j * shafts[b], h, sign * j, int(b));
    }
  // the lowest shaft orders too (an eccentric or chipped tooth turns once per revolution)
  for (std::size_t b = 0; b < shafts.size(); ++b)
    if (0.45 * shafts[b] >= half * (1 - 1e-12))
      for (int j = 1; j <= train.harmonics; ++j)
        look(j * shafts[b], 0, j, int(b));
  return t;
}

void
write_lines(const H5Group &g, const LineTable &t)
{
  const hsize_t n = t.expected.size();
  g.write("expected", t.expected, {n});
  g.write("frequency", t.frequency, {n});
  g.write("amplitude", t.amplitude, {n});
  g.write("floor", t.floor, {n});
  g.write("found", t.found, {n});
  g.write("harmonic", t.harmonic, {n});
  g.write("sideband", t.sideband, {n});
  g.write("shaft", t.shaft, {n});
}

/// Every contact of a mesh's flank sides, located by the integrator (the same at any output
/// rate).
void
write_contacts(const H5Group &g, const std::vector<TrainImpact> &contacts)
{
  const hsize_t       n = contacts.size();
  std::vector<double> side, touch, separation, peak, peak_time, impulse;
  for (const TrainImpact &c : contacts)
    {
      side.push_back(c.side == drive_side ? 1.0 : -1.0);
      touch.push_back(c.touch), separation.push_back(c.separation);
      peak.push_back(c.peak), peak_time.push_back(c.peak_time), impulse.push_back(c.impulse);
    }
  g.write("side", side, {n});
  g.write("touch", touch, {n});
  g.write("separation", separation, {n});
  g.write("peak", peak, {n});
  g.write("peak_time", peak_time, {n});
  g.write("impulse", impulse, {n});
}
/// The run's time series, the energy balance and the integrator's figures into train/<name>.
void
write_series(const TrainModel &model, const TrainScene &train, const TrainResult &r, double seconds,
             const H5Group &g)
{
  const hsize_t     n  = r.t.size();
  const std::size_t nb = model.bodies.size();
  std::string       names;
  for (const TrainBody &b : model.bodies)
    names += (names.empty() ? "" : ", ") + b.name;
  g.attribute("bodies", names);
  names.clear();
  for (const TrainMesh &m : model.meshes)
    names += (names.empty() ? "" : ", ") + m.name;
  g.attribute("meshes", names);
  std::vector<double> inertia, initial, angle, speed;
  for (std::size_t b = 0; b < nb; ++b)
    {
      inertia.push_back(model.bodies[b].inertia);
      initial.push_back(model.bodies[b].initial_speed);
      angle.insert(angle.end(), r.angle[b].begin(), r.angle[b].end());
      speed.insert(speed.end(), r.speed[b].begin(), r.speed[b].end());
    }
  g.write("time", r.t, {n});
  g.write("inertia", inertia, {nb});
  g.write("initial_speed", initial, {nb});
  g.write("angle", angle, {nb, n});
  g.write("speed", speed, {nb, n});
  g.write("work", r.work, {n});
  g.write("kinetic", r.kinetic, {n});
  g.write("potential", r.potential, {n});
  g.write("dissipated", r.dissipated, {n});
  g.write("energy_error", r.energy_error);
  g.write("steps", double(r.steps));
  g.attribute("integrator", r.method == TrainIntegrator::bdf ? "bdf" : "adams");
  g.write("events", double(r.events));
  g.write("seconds", seconds);
  g.write("anti_alias", double(train.run.anti_alias));
}

/// Where the spectra's interval starts (the first sample at or after it) and the reference
/// body's mean speed over it.
struct SpectrumInterval
{
  std::size_t from       = 0;
  int         reference  = 0;
  double      mean_speed = 0;
};

/// The per-mesh part: series, impacts and located peaks, and the force spectrum with its lines
/// where the train runs steadily (mesh i, into train/<name>/meshes/<mesh>).
void
write_mesh(const Scene &scene, const TrainScene &train, const TrainModel &model,
           const TrainResult &r, const TrainFrequencies &f, const SpectrumInterval &iv,
           std::size_t i, const H5Group &g, std::ostream &log)
{
  const hsize_t         n   = r.t.size();
  const TrainMesh      &m   = model.meshes[i];
  const TrainMeshScene &s   = train.meshes[i];
  const MeshSeries     &ms  = r.meshes[i];
  const H5Group         mg  = g.group("meshes").group(m.name, "<mesh>");
  const double          a   = train_mesh_centre_distance(scene, s);
  const auto [pinion, gear] = scene.pair(s.pair).involute_members(
      operating_centre_distance(a, scene.tca.at(s.pair).misalignment));
  const auto [drive, coast] = band_edges(m.teeth);
  mg.attribute("pair", s.pair);
  mg.attribute("pinion_body", s.pinion_body);
  mg.attribute("gear_body", s.gear_body);
  mg.write("centre_distance", a);
  mg.write("circumferential_backlash", circumferential_backlash(*pinion, *gear, a));
  mg.write("band_half_width", m.gear_base_radius * (coast - drive) / 2);
  mg.write("pinion_base_radius", m.pinion_base_radius);
  mg.write("gear_base_radius", m.gear_base_radius);
  mg.write("pinion_angle_0", m.pinion_angle_0);
  mg.write("gear_angle_0", m.gear_angle_0);
  if (!m.mesh_stiffness.empty())
    {
      const hsize_t       N = m.mesh_stiffness.size();
      std::vector<double> phi;
      for (hsize_t j = 0; j < N; ++j)
        phi.push_back(m.mesh_stiffness_start + 2 * pi / pinion->teeth() * double(j) / double(N));
      mg.write("mesh_stiffness", m.mesh_stiffness, {N});
      mg.write("mesh_stiffness_pinion_angle", phi, {N});
      log << "  " << train.name << "/" << m.name << ": finite-element K_m, mean "
          << std::accumulate(m.mesh_stiffness.begin(), m.mesh_stiffness.end(), 0.0) / double(N) /
                 1e6
          << " N/um\n";
    }
  mg.write("relative", ms.relative, {n});
  mg.write("force", ms.force, {n});
  mg.write("force_magnitude", ms.magnitude, {n});
  mg.write("pairs", ms.pairs, {n});
  mg.write("impacts", double(ms.impacts));
  mg.write("drive_impacts", double(ms.drive_impacts));
  mg.write("coast_impacts", double(ms.coast_impacts));
  mg.write("first_contact", ms.first_contact);
  mg.write("max_force", ms.max_force);
  mg.write("max_force_time", ms.max_force_time);
  write_contacts(mg.group("contacts"), ms.contacts);
  mg.write("max_penetration", ms.max_penetration);
  if (ms.max_penetration > 0.5 * train.curves.recess)
    log << "  WARNING " << train.name << " " << m.name << ": a tooth pair penetrates "
        << ms.max_penetration * 1e6 << " um, more than half the tooth pair curves' "
        << "recess (" << train.curves.recess * 1e6 << " um): pairs may leave their "
        << "curves still touching (raise Train/" << train.name << "/Contact/tooth pair recess)\n";
  mg.write("gmf", f.mesh[i]);

  // the spectrum only where the train runs steadily: the highest harmonic looked for may sweep
  // at most two bins over the window (a run-up, a coast-down or a transient smears every line:
  // the spectrogram shows those)
  const std::vector<double> &w        = r.speed[std::size_t(iv.reference)];
  const FrequencySpectrum    spectrum = frequency_spectrum(
         std::vector<double>(ms.magnitude.begin() + long(iv.from), ms.magnitude.end()),
         train.run.sample_rate, Window::hann);
  const auto [slowest, fastest] = std::minmax_element(w.begin() + long(iv.from), w.end());
  const double sweep            = train.harmonics * f.mesh[i] * (*fastest - *slowest) /
                       std::max(std::abs(iv.mean_speed), 1e-300);
  const bool steady = sweep <= 2 * spectrum.resolution;
  log << "  " << train.name << " " << m.name << ": " << ms.impacts << " impacts ("
      << ms.drive_impacts << " drive, " << ms.coast_impacts << " coast), first contact "
      << ms.first_contact * 1e3 << " ms, max force " << ms.max_force << " N, GMF " << f.mesh[i]
      << " Hz";
  if (!steady)
    {
      log << "; no spectrum: GMF x " << train.harmonics << " sweeps " << sweep
          << " Hz over the spectrum interval (bins " << spectrum.resolution
          << " Hz apart; a spectrum means something where the speed holds to 2 bins)\n";
      return;
    }
  std::size_t bins = spectrum.amplitude.size();
  if (train.spectrum_max_frequency > 0)
    bins = std::min(bins, std::size_t(train.spectrum_max_frequency / spectrum.resolution) + 1);
  const H5Group sg = mg.group("spectrum");
  sg.write("start", r.t[iv.from]);
  sg.write("resolution", spectrum.resolution);
  sg.write("gmf_sweep", sweep);
  sg.write("amplitude",
           std::vector<double>(spectrum.amplitude.begin(), spectrum.amplitude.begin() + long(bins)),
           {hsize_t(bins)});
  const LineTable lines = find_lines(spectrum, f.mesh[i], f.shaft, train);
  write_lines(sg.group("lines"), lines);
  if (!lines.expected.empty() && lines.found[0])
    log << " found at " << lines.frequency[0] << " Hz";
  else if (!lines.expected.empty())
    log << " not found";
  log << " (spectrum bins " << spectrum.resolution << " Hz apart)";
  log << "\n";
}

/// A spectrogram of the first mesh's force magnitude over the whole run (train/<name>/
/// spectrogram).
void
write_spectrogram(const TrainScene &train, const TrainModel &model, const TrainResult &r,
                  const H5Group &g)
{
  const Spectrogram sp =
      spectrogram(r.meshes[0].magnitude, train.run.sample_rate, train.spectrogram_window,
                  train.spectrogram_overlap, Window::hamming, train.spectrogram_max_frequency);
  const H5Group sg = g.group("spectrogram");
  sg.attribute("mesh", model.meshes[0].name);
  sg.write("time", sp.time, {hsize_t(sp.time.size())});
  sg.write("frequency", sp.frequency, {hsize_t(sp.frequency.size())});
  sg.write("amplitude", sp.amplitude, {hsize_t(sp.time.size()), hsize_t(sp.frequency.size())});
}
} // namespace

TrainModel
train_model(const Scene &scene, const TrainScene &train, const Upstream &upstream)
{
  TrainModel model = train.model(scene);
  for (std::size_t i = 0; i < train.meshes.size(); ++i)
    {
      const TrainMeshScene &s = train.meshes[i];
      TrainMesh            &m = model.meshes[i];
      // the flanks as this mesh runs: their active profiles at its own centre distance (the
      // backlash opens it) with the pair's centre distance error and offset
      const double a            = train_mesh_centre_distance(scene, s);
      const auto [pinion, gear] = scene.pair(s.pair).involute_members(
          operating_centre_distance(a, scene.tca.at(s.pair).misalignment));
      m.teeth                   = tooth_pair_tables(std::make_shared<InvoluteMemberFlanks>(pinion),
                                                    std::make_shared<InvoluteMemberFlanks>(gear), a,
                                                    scene.tca.at(s.pair).misalignment, train.curves);
      const auto [drive, coast] = band_edges(m.teeth);
      const double offset       = s.start == MeshStart::centre  ? (drive + coast) / 2
                                  : s.start == MeshStart::drive ? drive
                                                                : coast;
      const double ratio        = double(pinion->teeth()) / gear->teeth();
      const double theta_p      = model.bodies[std::size_t(m.driver)].initial_angle;
      const double theta_g      = model.bodies[std::size_t(m.driven)].initial_angle;
      m.gear_angle_0            = offset + ratio * (theta_p + m.pinion_angle_0) - theta_g;
      if (s.fe_stiffness)
        fe_mesh_stiffness(*upstream.at("stiffness"), s.pair, s.stiffness_torque, pinion->teeth(),
                          m);
    }
  return model;
}

void
run_train_stage(const Scene &scene, const Upstream &upstream, const H5Group &out, std::ostream &log)
{
  for (const TrainScene &train : scene.trains)
    {
      // 1. The model and its run; the time series and the energy balance.
      const TrainModel model = train_model(scene, train, upstream);
      const auto       start = std::chrono::steady_clock::now();
      TrainRunOptions  run   = train.run;
      run.progress           = "train " + train.name + ": sample";
      const TrainResult r    = simulate_train(model, run);
      const double      seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const H5Group g = out.group(train.name, "<train>");
      write_series(model, train, r, seconds, g);

      // 2. Kinematic frequencies at the reference body's mean speed over the spectrum interval.
      SpectrumInterval iv;
      const double t0 = train.spectrum_start > 0 ? train.spectrum_start : train.run.duration / 2;
      iv.from = std::size_t(std::lower_bound(r.t.begin(), r.t.end(), t0 - 1e-12) - r.t.begin());
      iv.reference                 = train.reference();
      const std::vector<double> &w = r.speed[std::size_t(iv.reference)];
      iv.mean_speed =
          std::accumulate(w.begin() + long(iv.from), w.end(), 0.0) / double(w.size() - iv.from);
      const TrainFrequencies f = train_frequencies(model, iv.reference, iv.mean_speed);
      const H5Group          k = g.group("kinematics");
      k.write("reference_body", double(iv.reference));
      k.write("reference_speed", iv.mean_speed);
      k.write("shaft_frequency", f.shaft, {hsize_t(model.bodies.size())});
      k.write("mesh_frequency", f.mesh, {hsize_t(f.mesh.size())});
      log << "  " << train.name << ": " << (r.method == TrainIntegrator::bdf ? "BDF" : "Adams")
          << " (damping time constant " << damping_time_constant(model) * 1e6 << " us), " << r.steps
          << " steps, " << r.events << " events in " << seconds << " s; energy error "
          << r.energy_error << "\n";

      // 3. Per mesh: series, impacts, the force spectrum and its lines.
      for (std::size_t i = 0; i < model.meshes.size(); ++i)
        write_mesh(scene, train, model, r, f, iv, i, g, log);

      // 4. A spectrogram of the first mesh's force magnitude over the whole run.
      if (train.spectrogram_window > 0)
        write_spectrogram(train, model, r, g);
    }
}
} // namespace gearkit

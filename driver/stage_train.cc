// Stage "train": the impact dynamics of every gear train of the scene (dynamics/train.h). Each
// mesh's tooth pair contact curves come from the pair's involute flanks at the mesh's centre
// distance (tca/tooth_pairs.h), its gear starts in the middle of the backlash (or touching),
// and the run is written with its kinematic frequencies, the mesh forces' spectra with the lines
// found at the mesh frequencies, their harmonics and sidebands, and a spectrogram of the first
// mesh's force.
#include "base/spectrum.h"
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
/// The train model of the scene with its tooth pair tables and mesh angles.
/// The stiffness stage's K_m of a pair over its mesh cycle at the loaded-contact torque nearest
/// `torque` (0: the largest): the mesh's TrainMesh::mesh_stiffness and its start angle.
void
fe_mesh_stiffness(const H5Group &stiffness, const std::string &pair, double torque, int z1,
                  TrainMesh &m)
{
  const H5Group        g       = stiffness.group(pair);
  const auto           torques = g.read_doubles("torque");
  const auto           phi     = g.read_doubles("pinion_angle");
  std::vector<hsize_t> shape;
  const auto           K    = g.read_doubles("mesh_stiffness", &shape);
  const std::size_t    best = nearest_torque(torques, torque);
  const std::size_t    n    = shape.size() == 2 ? std::size_t(shape[1]) : 0;
  // uniform positions over one mesh cycle (the stiffness stage's), or the table is refused
  const double step = 2 * pi / z1 / double(std::max<std::size_t>(n, 1));
  for (std::size_t i = 1; i < phi.size(); ++i)
    if (phi.size() != n || n < 2 || std::abs(phi[i] - phi[i - 1] - step) > 1e-9 * step)
      throw InputError("stiffness/" + pair + "/pinion_angle: positions that are not " +
                       std::to_string(n) +
                       " uniform steps over one mesh cycle are not allowed "
                       "for a train mesh's K_m (stiffness = finite elements)");
  m.mesh_stiffness.assign(K.begin() + long(best * n), K.begin() + long((best + 1) * n));
  m.mesh_stiffness_start = phi.front();
}

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
  g.write("expected", t.expected, {n}, "Hz",
          "where a line is looked for: harmonic x GMF + sideband x the shaft's frequency (harmonic "
          "0: the shaft's own orders)");
  g.write("frequency", t.frequency, {n}, "Hz",
          "the largest bin's frequency within the band around it, interpolated (spectral_peak)");
  g.write("amplitude", t.amplitude, {n}, "N", "its amplitude");
  g.write("floor", t.floor, {n}, "N", "median amplitude within 10 band widths (the local floor)");
  g.write("found", t.found, {n}, "1",
          "1: a local maximum inside the band, 4 times above the floor (base/spectrum.h "
          "spectral_line_near)");
  g.write("harmonic", t.harmonic, {n}, "1", "GMF harmonic (0: shaft orders)");
  g.write("sideband", t.sideband, {n}, "1", "sideband order (signed), or the shaft order");
  g.write("shaft", t.shaft, {n}, "1", "body index of the shaft frequency (-1: none)");
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
  g.write("side", side, {n}, "1", "+1 drive flanks, -1 coast flanks");
  g.write("touch", touch, {n}, "s", "located first touch");
  g.write("separation", separation, {n}, "s", "located separation (-1: touching at the end)");
  g.write("peak", peak, {n}, "N", "the side's largest force in the contact (located)");
  g.write("peak_time", peak_time, {n}, "s", "its time");
  g.write("impulse", impulse, {n}, "N s",
          "integral of the side's force over the contact (Simpson's rule on every step piece)");
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
  g.write("time", r.t, {n}, "s", "sample times");
  g.write("inertia", inertia, {nb}, "kg m^2",
          "each body's inertia about its axis (a crank-slider's varying part not included)");
  g.write("initial_speed", initial, {nb}, "rad/s", "each body's speed at t = 0");
  g.write("angle", angle, {nb, n}, "rad", "body angles (in the sense the train runs forward)");
  g.write("speed", speed, {nb, n}, "rad/s", "body speeds");
  g.write("work", r.work, {n}, "J",
          "work of the torques (constant-speed drives included) and of a finite-element "
          "K_m's variation");
  g.write("kinetic", r.kinetic, {n}, "J", "kinetic energy");
  g.write("potential", r.potential, {n}, "J", "elastic energy stored in the contacts");
  g.write("dissipated", r.dissipated, {n}, "J", "energy dissipated by the contact damping");
  g.write("energy_error", r.energy_error, "1",
          "max |work - kinetic change - potential change - dissipated| over the run, "
          "relative to the largest of the terms");
  g.write("steps", double(r.steps), "1", "CVODE steps");
  g.attribute("integrator", r.method == TrainIntegrator::bdf ? "bdf" : "adams");
  g.write("events", double(r.events), "1",
          "contact changes located (a side's or a tooth pair's touch and separation)");
  g.write("seconds", seconds, "s", "wall time of the run");
  g.write("anti_alias", double(train.run.anti_alias), "1",
          "1: angles, speeds, S and forces recorded without aliasing (B-spline averages "
          "decimated through a 70 dB low-pass: flat to 0.4 x the sample rate, nothing folds "
          "back from above half of it); 0: the solution's values at the sample times");
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
  const H5Group         mg  = g.group("meshes").group(m.name);
  const double          a   = train_mesh_centre_distance(scene, s);
  const auto [pinion, gear] = scene.pair(s.pair).involute_members(
      operating_centre_distance(a, scene.tca.at(s.pair).misalignment));
  const auto [drive, coast] = band_edges(m.teeth);
  mg.attribute("pair", s.pair);
  mg.attribute("pinion_body", s.pinion_body);
  mg.attribute("gear_body", s.gear_body);
  mg.write("centre_distance", a, "m",
           "nominal centre distance (the TCA's centre distance error comes on top)");
  mg.write("circumferential_backlash", circumferential_backlash(*pinion, *gear, a), "m",
           "of the nominal teeth on the operating pitch circles at that centre distance");
  mg.write("band_half_width", m.gear_base_radius * (coast - drive) / 2, "m",
           "S at drive contact of pairing 0 (minus it at coast contact): half the normal "
           "backlash for perfect flanks");
  mg.write("pinion_base_radius", m.pinion_base_radius, "m", "r_b1");
  mg.write("gear_base_radius", m.gear_base_radius, "m", "r_b2");
  mg.write("pinion_angle_0", m.pinion_angle_0, "rad", "pinion angle on its body");
  mg.write("gear_angle_0", m.gear_angle_0, "rad", "gear angle on its body");
  if (!m.mesh_stiffness.empty())
    {
      const hsize_t       N = m.mesh_stiffness.size();
      std::vector<double> phi;
      for (hsize_t j = 0; j < N; ++j)
        phi.push_back(m.mesh_stiffness_start + 2 * pi / pinion->teeth() * double(j) / double(N));
      mg.write("mesh_stiffness", m.mesh_stiffness, {N}, "N/m",
               "the stiffness stage's K_m on each side's deepest pair (stiffness = finite "
               "elements), over one mesh cycle");
      mg.write("mesh_stiffness_pinion_angle", phi, {N}, "rad", "its pinion angles phi");
      log << "  " << train.name << "/" << m.name << ": finite-element K_m, mean "
          << std::accumulate(m.mesh_stiffness.begin(), m.mesh_stiffness.end(), 0.0) / double(N) /
                 1e6
          << " N/um\n";
    }
  mg.write("relative", ms.relative, {n}, "m",
           "S = r_b2 ((z1/z2) phi + c - psi) along the line of action (> 0: pinion "
           "ahead; drive contact at +band_half_width, coast at -band_half_width)");
  mg.write("force", ms.force, {n}, "N", "normal force, drive flanks + and coast -");
  mg.write("force_magnitude", ms.magnitude, {n}, "N",
           "drive + coast flanks' force (the spectra's signal)");
  mg.write("pairs", ms.pairs, {n}, "1", "tooth pairs touching");
  mg.write("impacts", double(ms.impacts), "1", "first touches of a side after separation");
  mg.write("drive_impacts", double(ms.drive_impacts), "1", "of them on the drive flanks");
  mg.write("coast_impacts", double(ms.coast_impacts), "1", "of them on the coast flanks");
  mg.write("first_contact", ms.first_contact, "s", "time of the first touch (-1: none)");
  mg.write("max_force", ms.max_force, "N",
           "largest force of a flank side over the continuous solution (at every "
           "integrator step's end and every located root of its rate dF/dt)");
  mg.write("max_force_time", ms.max_force_time, "s", "its time");
  write_contacts(mg.group("contacts"), ms.contacts);
  mg.write("max_penetration", ms.max_penetration, "m",
           "deepest penetration of a tooth pair (the curves reach tooth pair recess "
           "beyond the conjugate touch)");
  if (ms.max_penetration > 0.5 * train.curves.recess)
    log << "  WARNING " << train.name << " " << m.name << ": a tooth pair penetrates "
        << ms.max_penetration * 1e6 << " um, more than half the tooth pair curves' "
        << "recess (" << train.curves.recess * 1e6 << " um): pairs may leave their "
        << "curves still touching (raise Train/" << train.name << "/Contact/tooth pair recess)\n";
  mg.write("gmf", f.mesh[i], "Hz", "tooth mesh frequency (kinematics)");

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
  sg.write("start", r.t[iv.from], "s", "the spectrum's record starts here (to the end)");
  sg.write("resolution", spectrum.resolution, "Hz", "bin spacing");
  sg.write("gmf_sweep", sweep, "Hz",
           "how far the highest harmonic looked for moves over the record (at most 2 "
           "bins: a spectrum is written only then)");
  sg.write("amplitude",
           std::vector<double>(spectrum.amplitude.begin(), spectrum.amplitude.begin() + long(bins)),
           {hsize_t(bins)}, "N",
           "single-sided amplitude of the force magnitude (drive + coast flanks, recorded "
           "as its own channel: without aliasing when anti-alias = true; Hann window, "
           "mean removed), bins 0, resolution, 2 resolution, ...");
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
  sg.write("time", sp.time, {hsize_t(sp.time.size())}, "s", "window centres");
  sg.write("frequency", sp.frequency, {hsize_t(sp.frequency.size())}, "Hz", "bins");
  sg.write("amplitude", sp.amplitude, {hsize_t(sp.time.size()), hsize_t(sp.frequency.size())}, "N",
           "amplitude of the first mesh's force magnitude per window (Hamming) and "
           "frequency");
}
} // namespace

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
      const H5Group g = out.group(train.name);
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
      k.write("reference_body", double(iv.reference), "1",
              "index of the body whose speed sets them");
      k.write("reference_speed", iv.mean_speed, "rad/s",
              "its mean speed over the spectrum interval");
      k.write("shaft_frequency", f.shaft, {hsize_t(model.bodies.size())}, "Hz",
              "every body's rotation frequency");
      k.write("mesh_frequency", f.mesh, {hsize_t(f.mesh.size())}, "Hz",
              "every mesh's tooth mesh frequency (GMF): pinion teeth x its shaft frequency");
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

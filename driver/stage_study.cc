// Stage "study": design studies of every pair on its compliance (the compliance stage's tables,
// computed once), each variant's loaded mesh cycles on fixed contact zones (study/). A
// micro-geometry map: the grid of modification variants of Study/<pair> over the torques, the
// best variant per torque and the classical tip relief F_bt / (b c_gamma) to compare with. A
// tolerance Monte Carlo: samples of the design within ISO 1328-1 classes over a pinion
// revolution, the design alone, percentiles, their convergence and the sensitivities.
#include "base/parallel.h"
#include "base/progress.h"
#include "driver/pair_contact.h"
#include "driver/stages.h"
#include "stiffness/iso6336.h"
#include "study/misalignment_study.h"
#include "study/modification_grid.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>

namespace gearkit
{
namespace
{
/// A member as the study's zones are built on it: without modifications on either side.
std::shared_ptr<const InvoluteMemberFlanks>
unmodified(const MemberFlanks &m)
{
  InvoluteGearData d    = involute(m).data();
  d.drive_modifications = d.coast_modifications = {};
  return std::make_shared<const InvoluteMemberFlanks>(InvoluteGear::create(d));
}

/// The best (least TE p-p) valid variant at torque m, -1 if none.
int
best_variant(const std::vector<VariantCycle> &r, std::size_t m)
{
  int best = -1;
  for (std::size_t g = 0; g < r.size(); ++g)
    if (!r[g].zone_edge[m] &&
        (best < 0 || r[g].te_peak_to_peak[m] < r[std::size_t(best)].te_peak_to_peak[m]))
      best = int(g);
  return best;
}

/// A warning where variants loaded a cell on their fixed zone's edge at some torque: their
/// contact may reach beyond the zone (the map leaves them out of its best variants; the Monte
/// Carlo's percentiles count them).
void
warn_zone_edges(std::ostream &log, const PairScene &pair, const std::vector<VariantCycle> &r,
                std::size_t count, const char *what)
{
  std::size_t at_edge = 0;
  for (std::size_t k = 0; k < count; ++k)
    at_edge += std::any_of(r[k].zone_edge.begin(), r[k].zone_edge.end(), [](char e) { return e; });
  if (at_edge > 0)
    log << "  warning: Study/" << pair.name << ": " << at_edge << " of " << count << " " << what
        << " loaded a cell on the edge of their fixed contact zone at some torque (their "
           "contact may reach beyond it; results/study/"
        << pair.name << "/zone_edge says which); raise `zone widening`" << std::endl;
}

/// The relief of least TE p-p along a single axis at torque m: the vertex of the parabola
/// through the grid's best valid value and its two neighbours (the best value itself at an end
/// of the axis or where the three do not open upwards).
double
best_relief(const std::vector<VariantCycle> &r, const std::vector<double> &values, std::size_t m)
{
  const int b = best_variant(r, m);
  if (b < 0)
    return std::nan("");
  const std::size_t i = std::size_t(b);
  if (i == 0 || i + 1 >= values.size() || r[i - 1].zone_edge[m] || r[i + 1].zone_edge[m])
    return values[i];
  const double x0 = values[i - 1], x1 = values[i], x2 = values[i + 1];
  const double y0 = r[i - 1].te_peak_to_peak[m], y1 = r[i].te_peak_to_peak[m],
               y2 = r[i + 1].te_peak_to_peak[m];
  // divided differences: y = y1 + d1 (x - x1) + d2 (x - x0)(x - x1) ... vertex of the parabola
  const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1);
  const double a = (d12 - d01) / (x2 - x0);
  if (!(a > 0))
    return x1;
  const double x = (x0 + x1) / 2 - d01 / (2 * a);
  return std::clamp(x, x0, x2);
}

/// The grid's axes (axes/<name>, attribute parameters), the values per axis (shape) and each
/// point's (grid).
void
write_grid(const H5Group &g, const ParameterGrid &grid)
{
  std::string      names;
  std::vector<int> shape;
  const H5Group    axes = g.group("axes");
  for (const GridAxis &a : grid.axes())
    {
      names += (names.empty() ? "" : ",") + a.name;
      shape.push_back(int(a.values.size()));
      axes.write(a.name, a.values, {a.values.size()});
    }
  g.attribute("parameters", names);
  const hsize_t P = grid.axes().size();
  g.write("shape", shape, {P});
  g.write("grid", grid.points(), {hsize_t(grid.size()), P});
}

void
write_map(const H5Group &g, const StudyScene &s, const std::vector<double> &torques,
          const ModificationGrid &grid, const std::vector<VariantCycle> &r,
          const std::vector<double> &pinion_angle, double pitch_radius)
{
  const std::size_t G = r.size(), M = torques.size(), N = pinion_angle.size(),
                    H = std::size_t(s.harmonics);
  g.attribute("kind", "microgeometry map");
  g.attribute("members", s.members == GridMembers::both     ? "both"
                         : s.members == GridMembers::pinion ? "pinion"
                                                            : "gear");
  write_grid(g, grid.parameters());
  g.write("torques", torques, {M});
  g.write("design_torque", s.design_torque);
  g.write("pitch_radius", pitch_radius);
  const auto gather = [&](auto field, std::vector<hsize_t> dims, const char *name) {
    std::vector<double> all;
    for (const VariantCycle &c : r)
      all.insert(all.end(), (c.*field).begin(), (c.*field).end());
    dims.insert(dims.begin(), G);
    g.write(name, all, dims);
  };
  gather(&VariantCycle::te_peak_to_peak, {M}, "te_peak_to_peak");
  gather(&VariantCycle::te_harmonics, {M, H}, "te_harmonics");
  gather(&VariantCycle::stiffness_mean, {M}, "stiffness_mean");
  gather(&VariantCycle::stiffness_range, {M}, "stiffness_range");
  gather(&VariantCycle::max_pressure, {M}, "max_pressure");
  gather(&VariantCycle::max_interior_pressure, {M}, "max_interior_pressure");
  gather(&VariantCycle::max_edge_share, {M}, "max_edge_share");
  gather(&VariantCycle::unloaded_te, {N}, "unloaded_te");
  gather(&VariantCycle::loaded_te, {M, N}, "loaded_te");
  gather(&VariantCycle::mesh_stiffness, {M, N}, "mesh_stiffness");
  std::vector<double> e0_pp;
  std::vector<int>    edge, best;
  for (const VariantCycle &c : r)
    {
      const auto [lo, hi] = std::minmax_element(c.unloaded_te.begin(), c.unloaded_te.end());
      e0_pp.push_back(*hi - *lo);
      for (const char e : c.zone_edge)
        edge.push_back(e);
    }
  for (std::size_t m = 0; m < M; ++m)
    best.push_back(best_variant(r, m));
  g.write("unloaded_te_peak_to_peak", e0_pp, {G});
  g.write("zone_edge", edge, {G, M});
  g.write("best_variant", best, {M});
  g.write("pinion_angle", pinion_angle, {N});
}

/// What both kinds of study start from: the pair on its compliance, the zones' members (without
/// modifications), the design (the scene's modifications with the study's single values).
struct StudyInputs
{
  LoadedPair                                  lp;
  TcaOptions                                  tca;
  std::shared_ptr<const InvoluteMemberFlanks> pinion, gear;
  MeshCycleStudyOptions                       options;
};

StudyInputs
study_inputs(const Scene &scene, const PairScene &pair, const Upstream &up)
{
  const StudyScene     &s   = scene.study.at(pair.name);
  LoadedPair            lp  = loaded_pair(scene, pair, up.at("flanks")->group(pair.name),
                                          up.at("compliance")->group(pair.name));
  const TcaOptions      tca = lp.theory->options_data();
  MeshCycleStudyOptions o;
  o.positions = s.positions, o.widening = s.widening, o.harmonics = s.harmonics;
  o.torques = s.study_torques(scene.loaded.at(pair.name));
  o.threads = cores_per_process();
  auto p = unmodified(*lp.members.pinion), g = unmodified(*lp.members.gear);
  return {std::move(lp), tca, std::move(p), std::move(g), o};
}

PairVariant
scene_design(const StudyInputs &in)
{
  const auto working = [&](const MemberFlanks &m) {
    const InvoluteGearData &d = involute(m).data();
    return in.tca.side == FlankSide::drive ? d.drive_modifications : d.coast_modifications;
  };
  PairVariant v;
  v.pinion = working(*in.lp.members.pinion), v.gear = working(*in.lp.members.gear);
  return v;
}

void
run_map(const PairScene &pair, const StudyScene &s, const StudyInputs &in, const H5Group &g,
        std::ostream &log)
{
  const ModificationGrid       grid(scene_design(in), s.members, s.axes);
  const MeshCycleStudyOptions &o  = in.options;
  const LoadedPair            &lp = in.lp;
  log << "  " << pair.name << ": " << grid.size() << " variants x " << o.torques.size()
      << " torques x " << o.positions << " positions on one compliance" << std::endl;
  const std::size_t processes = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  Progress          progress("study " + pair.name + ": variant",
                             (grid.size() * o.torques.size() + processes - 1) / processes);
  const std::vector<VariantCycle> r = microgeometry_map(
      in.pinion, in.gear, lp.members.assembly, in.tca, lp.options, lp.pinion_compliance,
      lp.gear_compliance, o, grid, MPI_COMM_WORLD, [&] { progress.advance(); });

  std::vector<double> phi;
  const double        mesh_angle = 2 * pi / pair.pinion.teeth;
  for (int i = 0; i < o.positions; ++i)
    phi.push_back(in.tca.start_angle + mesh_angle * i / o.positions);
  write_map(g, s, o.torques, grid, r, phi, lp.members.pitch_radius);
  warn_zone_edges(log, pair, r, r.size(), "variants");
  int unmodified = -1;
  for (std::size_t v = 0; v < grid.size() && unmodified < 0; ++v)
    if (const PairVariant w = grid.variant(v); !w.pinion.any() && !w.gear.any())
      unmodified = int(v);
  g.write("unmodified_variant", std::vector<int>{unmodified}, {});

  // The classical tip relief at the design torque: the mesh deflection F_bt / (b c_gamma)
  // with ISO 6336-1's c_gamma_alpha, and with the FE K_m of the unmodified variant.
  const InvoluteGear &p = involute(*lp.members.pinion), &q = involute(*lp.members.gear);
  const IsoPair       iso = iso_pair(p, q, lp.members.centre_distance);
  const double        b_c = iso6336_mesh_stiffness(iso.input).c_gamma_alpha * 1e9 * iso.face_width;
  g.write("iso_c_gamma_alpha", b_c);
  const auto design = std::find(o.torques.begin(), o.torques.end(), s.design_torque);
  if (design == o.torques.end())
    return;
  const std::size_t m   = std::size_t(design - o.torques.begin());
  const double      F_b = s.design_torque / p.base_radius;
  g.write("classical_relief_iso", F_b / b_c);
  if (unmodified >= 0 && !r[std::size_t(unmodified)].zone_edge[m])
    g.write("mesh_deflection_design", F_b / r[std::size_t(unmodified)].stiffness_mean[m]);
  // One axis of several values, a relief amount (the others single values): its best.
  std::vector<const ModificationAxis *> varied;
  for (const ModificationAxis &a : grid.axes())
    if (a.values.size() > 1)
      varied.push_back(&a);
  if (varied.size() == 1 && varied[0]->name.find("relief") != std::string::npos &&
      varied[0]->name.find("length") == std::string::npos)
    {
      const double x = best_relief(r, varied[0]->values, m);
      if (std::isfinite(x))
        {
          g.write("best_relief_design", x);
          log << "  " << pair.name << ": least TE p-p at " << s.design_torque << " N m with "
              << varied[0]->name << " " << x * 1e6 << " um; classical F_bt / (b c_gamma) "
              << F_b / b_c * 1e6 << " um" << std::endl;
        }
    }
}

/// The outputs the tolerance study summarises: [sample][torque] tables of VariantCycle.
const std::vector<std::pair<const char *, std::vector<double> VariantCycle::*>> &
tolerance_outputs()
{
  static const std::vector<std::pair<const char *, std::vector<double> VariantCycle::*>> o = {
      {"te_peak_to_peak", &VariantCycle::te_peak_to_peak},
      {"stiffness_mean", &VariantCycle::stiffness_mean},
      {"stiffness_range", &VariantCycle::stiffness_range},
      {"max_pressure", &VariantCycle::max_pressure},
      {"max_interior_pressure", &VariantCycle::max_interior_pressure},
      {"max_edge_share", &VariantCycle::max_edge_share}};
  return o;
}

void
run_tolerances(const PairScene &pair, const StudyScene &s, StudyInputs in, const H5Group &g,
               std::ostream &log)
{
  const ModificationGrid design_grid(scene_design(in), s.members, s.axes);
  const PairVariant      design  = design_grid.variant(0);
  MeshCycleStudyOptions &o       = in.options;
  o.cycles                       = s.mesh_cycles > 0 ? s.mesh_cycles : pair.pinion.teeth;
  o.turned_gear_compliance       = false; // (MeshCycleStudyOptions: speed)
  const std::size_t            S = std::size_t(s.samples), M = o.torques.size();
  std::vector<ToleranceSample> drawn(S); // each from its own stream: the same on any process
  parallel_for(S, o.threads, [&](std::size_t k) {
    drawn[k] = draw_tolerance_sample(in.pinion->involute(), in.gear->involute(), in.tca.side,
                                     s.sampling, design, k);
  });
  log << "  " << pair.name << ": " << S << " samples (ISO 1328-1 classes "
      << s.sampling.pinion_class << " / " << s.sampling.gear_class << ") x " << M << " torques x "
      << o.cycles << " mesh cycles x " << o.positions << " positions on one compliance"
      << std::endl;
  const std::size_t processes = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  Progress progress("study " + pair.name + ": sample", ((S + 1) * M + processes - 1) / processes);
  const LoadedPair &lp = in.lp;
  // the samples, then the design itself (the nominal run)
  const std::vector<VariantCycle> r = evaluate_variants(
      in.pinion, in.gear, lp.members.assembly, in.tca, lp.options, lp.pinion_compliance,
      lp.gear_compliance, o, S + 1,
      [&](std::size_t k) { return k < S ? drawn[k].variant : design; }, MPI_COMM_WORLD,
      [&] { progress.advance(); }, &design);

  g.attribute("kind", "tolerances");
  g.attribute("distribution",
              s.sampling.distribution == ToleranceDistribution::normal ? "normal" : "uniform");
  g.attribute("classes", std::to_string(s.sampling.pinion_class) + "," +
                             std::to_string(s.sampling.gear_class));
  std::string names;
  for (const std::string &f : tolerance_feature_names())
    names += (names.empty() ? "" : ",") + f;
  g.attribute("features", names);
  g.write("torques", o.torques, {M});
  g.write("design_torque", s.design_torque);
  g.write("pitch_radius", lp.members.pitch_radius);
  std::vector<std::vector<double>> features;
  std::vector<double>              flat;
  for (const ToleranceSample &t : drawn)
    {
      features.push_back(t.features);
      flat.insert(flat.end(), t.features.begin(), t.features.end());
    }
  const std::size_t F = tolerance_feature_names().size();
  g.write("features", flat, {S, F});
  std::vector<int> edge;
  for (std::size_t k = 0; k < S; ++k)
    for (const char e : r[k].zone_edge)
      edge.push_back(e);
  g.write("zone_edge", edge, {S, M});
  warn_zone_edges(log, pair, r, S, "samples");
  const std::vector<double> levels = {5, 50, 95};
  g.write("percentile_levels", levels, {levels.size()});
  // Convergence: the percentiles of the first n samples, n doubling up to all.
  std::vector<double> counts;
  for (std::size_t n = std::min<std::size_t>(S, 25); n < S; n *= 2)
    counts.push_back(double(n));
  counts.push_back(double(S));
  g.write("convergence_samples", counts, {counts.size()});
  const H5Group nominal = g.group("nominal");
  for (const auto &[name, field] : tolerance_outputs())
    {
      std::vector<double> table, pct, conv;
      for (std::size_t k = 0; k < S; ++k)
        table.insert(table.end(), (r[k].*field).begin(), (r[k].*field).end());
      g.write(name, table, {S, M});
      nominal.write(name, r[S].*field, {M});
      for (std::size_t m = 0; m < M; ++m)
        {
          std::vector<double> x;
          for (std::size_t k = 0; k < S; ++k)
            x.push_back(table[k * M + m]);
          for (const double p : levels)
            pct.push_back(percentile(x, p));
          for (const double n : counts)
            for (const double p : levels)
              conv.push_back(percentile(std::vector<double>(x.begin(), x.begin() + long(n)), p));
        }
      const H5Group q = g.group("percentiles");
      q.write(name, pct, {M, levels.size()});
      g.group("convergence").write(name, conv, {M, counts.size(), levels.size()});
    }
  // Which deviation drives the TE peak-to-peak and K_m's range: standardized regression.
  if (S >= 3)
    for (const char *name : {"te_peak_to_peak", "stiffness_range"})
      {
        std::vector<double> c, lo, hi, r2;
        for (std::size_t m = 0; m < M; ++m)
          {
            std::vector<double> y;
            for (std::size_t k = 0; k < S; ++k)
              y.push_back(name == std::string("te_peak_to_peak") ? r[k].te_peak_to_peak[m]
                                                                 : r[k].stiffness_range[m]);
            const Sensitivity sens = standardized_regression(features, y, 200, s.sampling.seed);
            c.insert(c.end(), sens.coefficient.begin(), sens.coefficient.end());
            lo.insert(lo.end(), sens.low.begin(), sens.low.end());
            hi.insert(hi.end(), sens.high.begin(), sens.high.end());
            r2.push_back(sens.r2);
          }
        const H5Group q = g.group("sensitivity").group(name, "<output>");
        q.write("coefficient", c, {M, F});
        q.write("low", lo, {M, F});
        q.write("high", hi, {M, F});
        q.write("r2", r2, {M});
      }
  const double rp = lp.members.pitch_radius * 1e6;
  for (std::size_t m = 0; m < M; ++m)
    {
      std::vector<double> x;
      for (std::size_t k = 0; k < S; ++k)
        x.push_back(r[k].te_peak_to_peak[m]);
      log << "  " << pair.name << " at " << o.torques[m] << " N m: TE p-p " << percentile(x, 5) * rp
          << " / " << percentile(x, 50) * rp << " / " << percentile(x, 95) * rp
          << " um (5 / 50 / 95 %), the design alone " << r[S].te_peak_to_peak[m] * rp << " um"
          << std::endl;
    }
}
/// The misalignment (V-H) check: every grid point's assembly of the theoretical members on the
/// compliance tables; e_0, e_L, K_m and the contact pattern on the gear flank.
void
run_misalignments(const Scene &scene, const PairScene &pair, const StudyScene &s,
                  const Upstream &up, const H5Group &g, std::ostream &log)
{
  const H5Group       flanks = up.at("flanks")->group(pair.name);
  const LoadedPair    lp = loaded_pair(scene, pair, flanks, up.at("compliance")->group(pair.name));
  const ParameterGrid grid(s.misalignment_axes, misalignment_field_names(),
                           "Study/" + pair.name + "/misalignments", 10000);
  TcaScene            tca = scene.tca.at(pair.name);
  MisalignmentStudyOptions o;
  o.torques      = s.study_torques(scene.loaded.at(pair.name));
  o.positions    = s.positions;
  o.profile_bins = s.profile_bins, o.face_bins = s.face_bins;
  const std::size_t G = grid.size(), M = o.torques.size();
  log << "  " << pair.name << ": " << G << " misaligned assemblies x " << M << " torques x "
      << o.positions << " positions on one compliance" << std::endl;
  Progress                    progress("study " + pair.name + ": assembly", G);
  std::vector<MisalignedMesh> r;
  for (std::size_t k = 0; k < G; ++k)
    {
      tca.misalignment     = grid_misalignment(grid, k, scene.tca.at(pair.name).misalignment);
      const PairMembers pm = theoretical_members(pair, tca, flanks);
      try
        {
          r.push_back(misaligned_mesh(pm.pinion, pm.gear, pm.assembly, tca.options, lp.options,
                                      lp.pinion_compliance, lp.gear_compliance, o));
        }
      catch (const InputError &e)
        {
          const std::vector<std::size_t> index = grid.index(k);
          std::string                    at;
          for (std::size_t j = 0; j < grid.axes().size(); ++j)
            at += (at.empty() ? "" : ", ") + grid.axes()[j].name + " " +
                  std::to_string(grid.axes()[j].values[index[j]]);
          throw InputError("Study/" + pair.name + " (" + at + " [m, rad]): " + e.what());
        }
      progress.advance();
    }

  g.attribute("kind", "misalignments");
  write_grid(g, grid);
  g.write("torques", o.torques, {M});
  g.write("design_torque", s.design_torque);
  g.write("pitch_radius", lp.members.pitch_radius);
  const MemberFlanks &gear = *lp.members.gear;
  const FlankDomain   d    = gear.flank(0, tca.options.side).domain();
  const auto [u0, v0]      = flank_lengths(gear, d.u_min, d.v_min);
  const auto [u1, v1]      = flank_lengths(gear, d.u_max, d.v_max);
  g.write("pattern_profile_range", std::vector<double>{u0, u1}, {2});
  g.write("pattern_face_range", std::vector<double>{v0, v1}, {2});
  const std::size_t T = r[0].unloaded_te.size(), N = std::size_t(o.positions),
                    U = std::size_t(o.profile_bins), V = std::size_t(o.face_bins);
  std::vector<double> e0, e0_tca, e0_pp, eL, K, eL_pp, K_mean, p_max, p_interior, edge, path,
      path_centre, pattern, centre, extent;
  const auto lengths = [&](double u, double v, std::vector<double> &to) {
    const auto [a, b] = flank_lengths(gear, u, v);
    to.insert(to.end(), {a, b});
  };
  for (const MisalignedMesh &m : r)
    {
      e0.insert(e0.end(), m.loaded.unloaded_te.begin(), m.loaded.unloaded_te.end());
      e0_tca.insert(e0_tca.end(), m.unloaded_te.begin(), m.unloaded_te.end());
      e0_pp.push_back(m.unloaded_peak_to_peak);
      eL.insert(eL.end(), m.loaded.loaded_te.begin(), m.loaded.loaded_te.end());
      K.insert(K.end(), m.loaded.mesh_stiffness.begin(), m.loaded.mesh_stiffness.end());
      for (auto [from, to] : {std::pair{&m.loaded_peak_to_peak, &eL_pp},
                              {&m.stiffness_mean, &K_mean},
                              {&m.max_pressure, &p_max},
                              {&m.max_interior_pressure, &p_interior},
                              {&m.max_edge_share, &edge},
                              {&m.pattern, &pattern}})
        to->insert(to->end(), from->begin(), from->end());
      for (std::size_t i = 0; i < T; ++i)
        lengths(m.path[2 * i], m.path[2 * i + 1], path);
      lengths(m.path_centre[0], m.path_centre[1], path_centre);
      for (std::size_t j = 0; j < M; ++j)
        {
          lengths(m.pattern_centre[2 * j], m.pattern_centre[2 * j + 1], centre);
          const double *x     = &m.pattern_extent[4 * j];
          const auto [a0, b0] = flank_lengths(gear, x[0], x[2]);
          const auto [a1, b1] = flank_lengths(gear, x[1], x[3]);
          extent.insert(extent.end(), {a0, a1, b0, b1});
        }
    }
  g.write("pinion_angle", r[0].loaded.pinion_angle, {N});
  g.write("tca_pinion_angle", r[0].tca_pinion_angle, {T});
  g.write("unloaded_te", e0, {G, N});
  g.write("tca_unloaded_te", e0_tca, {G, T});
  g.write("unloaded_te_peak_to_peak", e0_pp, {G});
  g.write("loaded_te", eL, {G, M, N});
  g.write("mesh_stiffness", K, {G, M, N});
  g.write("te_peak_to_peak", eL_pp, {G, M});
  g.write("stiffness_mean", K_mean, {G, M});
  g.write("max_pressure", p_max, {G, M});
  g.write("max_interior_pressure", p_interior, {G, M});
  g.write("max_edge_share", edge, {G, M});
  g.write("contact_path", path, {G, T, 2});
  g.write("path_centre", path_centre, {G, 2});
  g.write("pattern", pattern, {G, M, U, V});
  g.write("pattern_centre", centre, {G, M, 2});
  g.write("pattern_extent", extent, {G, M, 4});
  const double rp = lp.members.pitch_radius * 1e6;
  for (std::size_t k = 0; k < G; ++k)
    log << "  " << pair.name << " assembly " << k << ": e_0 p-p " << r[k].unloaded_peak_to_peak * rp
        << " um, e_L p-p " << r[k].loaded_peak_to_peak.back() * rp << " um at " << o.torques.back()
        << " N m, pattern centre (profile, face) (" << centre[(k * M + M - 1) * 2] * 1e3 << ", "
        << centre[(k * M + M - 1) * 2 + 1] * 1e3 << ") mm" << std::endl;
}
} // namespace

void
run_study_stage(const Scene &scene, const Upstream &up, const H5Group &out, std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      const StudyScene &s  = scene.study.at(pair.name);
      const auto        t0 = std::chrono::steady_clock::now();
      const H5Group     g  = out.group(pair.name, "<pair>");
      if (s.kind == StudyScene::Kind::misalignments)
        run_misalignments(scene, pair, s, up, g, log);
      else if (s.kind == StudyScene::Kind::tolerances)
        run_tolerances(pair, s, study_inputs(scene, pair, up), g, log);
      else
        run_map(pair, s, study_inputs(scene, pair, up), g, log);
      log << "  " << pair.name << ": study in "
          << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s"
          << std::endl;
    }
}
} // namespace gearkit

// Stages "compliance" and "stiffness": the finite-element compliance tables of both members
// (gmsh tooth segments, deal.II + PETSc; computed once, reused for every torque and for the
// measured flanks), then the loaded contact over the mesh cycle for every torque: loaded TE
// e_L, mesh stiffness K_m, load per tooth pair and the contact pressure on the cells.
#include "driver/pair_contact.h"
#include "driver/pair_members.h"
#include "driver/pair_tca.h"
#include "driver/results_compliance.h"
#include "driver/results_stiffness.h"
#include "driver/stages.h"
#include "geometry/measured_flank.h"
#include "stiffness/iso6336.h"
#include "stiffness/loaded_contact.h"
#include "stiffness/member_compliance.h"
#include "stiffness/reference_contact.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>

namespace gearkit
{
namespace
{
/// Pairs within this gap somewhere in the mesh cycle get their teeth into the segments: 20 um
/// at a module of 4.5 mm, in proportion to the module (geometrically similar pairs at the same
/// nominal tooth load deflect in proportion to their size; tip reliefs of that size engage
/// under load). A pair the load brings into contact outside the segments is refused.
constexpr double segment_gap_per_module = 20e-6 / 4.5e-3;

MemberComplianceOptions
member_options(double module, int z, bool pinion, const FeScene &fe, FlankSide side,
               const SegmentChoice &segment, const std::string &dir)
{
  MemberComplianceOptions o;
  // With unit loads on the middle tooth alone, responses on the teeth as far from it as the
  // loaded teeth lie apart (on a segment spanning at most half the gear: at least as far as
  // teeth stand apart in contact at once).
  const bool whole        = fe.whole(pinion);
  const int  loaded_reach = (segment.teeth - 1) / 2;
  int        reach        = loaded_reach;
  if (fe.cyclic)
    {
      // without cuts the segment may span more than half the gear
      reach = whole || fe.whole_rim(pinion) ? segment.teeth - 1
                                            : std::min(segment.teeth - 1, (z / 2 - 1) / 2);
      if (reach < segment.span)
        throw InputError(
            "Finite elements: unit loads = middle tooth needs responses " +
            std::to_string(segment.span) +
            " teeth either side of the middle one, "
            "more than a segment of at most half the " +
            std::to_string(z) +
            " teeth holds; expected whole gears, whole rims or unit loads = loaded teeth");
    }
  o.mesh.teeth         = whole ? z : std::min(z, std::max(fe.segment_teeth, 2 * reach + 1));
  o.mesh.fine_teeth    = whole ? segment.teeth : 0;
  o.mesh.central_tooth = segment.central;
  o.mesh.whole_rim     = fe.whole_rim(pinion);
  o.hold_cuts          = fe.hold_cuts;
  o.mesh.flank_size    = fe.flank_size * module;
  o.mesh.far_size      = fe.far_size * module;
  o.mesh.other_size    = fe.other_size * module;
  o.mesh.fillet_size   = fe.fillet_size * module;
  o.degree             = fe.degree;
  o.material           = fe.material;
  o.side               = side;
  o.n_u = fe.n_u, o.n_v = fe.n_v;
  o.graded_grid         = fe.graded_grid;
  o.depth_elements      = fe.depth;
  o.analytic_near_field = fe.analytic_near_field;
  o.near_field_radius   = fe.near_field_radius * module;
  o.threads             = cores_per_process();
  o.local_refinements   = fe.local_refinements;
  o.refine_depth        = fe.refine_depth;
  o.work_directory      = dir;
  // Unit loads only on the teeth that can carry load over the mesh cycle, or on the middle one
  // for all; the segment's other teeth are there for the stiffness of the surroundings.
  for (int k = -loaded_reach; k <= loaded_reach; ++k)
    o.loaded_teeth.push_back(mod(segment.central + k, z));
  o.cyclic_tooth = fe.cyclic ? segment.central : -1;
  o.cyclic_reach = fe.cyclic ? reach : 0;
  return o;
}

/// The pair as its compliance is computed: an involute pair without its flanks' micro-geometry
/// (modifications, per-tooth deviations, pitch deviations, runout, eccentricity: micrometres
/// that the finite-element mesh, of elements a quarter module in size, does not follow; they
/// enter the loaded contact as gaps). The segments follow the macro-geometry's contact (a tip
/// relief would otherwise take a pair out of the gap band, and with it a tooth out of the
/// segments), and the unit loads lie on the mesh's surface (on a 50 um tip relief they lay
/// inside the material, and the tables' structural part, the half-space part removed, came out
/// negative). A design or tolerance study's variants reuse this compliance, and the modified
/// scene run on its own computes the same one.
PairScene
macro_geometry(PairScene pair)
{
  for (InvoluteGearData *d : {&pair.pinion, &pair.gear})
    {
      d->drive_modifications = d->coast_modifications = ToothModifications{};
      d->drive_tooth_deviations.clear(), d->coast_tooth_deviations.clear();
      d->single_pitch_deviations.clear(), d->eccentric_teeth.clear();
      d->runout = Runout{};
    }
  return pair;
}

/// The compliance table of one member on its tooth segment.
FlankCompliance
compliance_table(const PairScene &pair, const MemberFlanks &flanks, bool is_pinion,
                 const MemberComplianceOptions &o, MemberComplianceInfo *info)
{
  if (pair.type == PairType::spiral_bevel)
    return bevel_member_compliance(dynamic_cast<const BevelMemberFlanks &>(flanks),
                                   is_pinion ? "pinion" : "gear", member_module(pair), o, info);
  return involute_member_compliance(involute(flanks), flanks, o, info);
}
} // namespace

void
run_compliance_stage(const Scene &scene, const Upstream &upstream, const H5Group &out,
                     std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      const FeScene   fe   = pair_fe(scene, pair);
      const TcaScene &tca  = scene.tca.at(pair.name);
      const FlankSide side = tca.options.side;
      // The members' macro-geometry (macro_geometry): the teeth that can carry load over a
      // mesh cycle decide the segments, and the unit loads lie on the flanks the mesh has.
      const PairMembers members =
          theoretical_members(macro_geometry(pair), tca, upstream.at("flanks")->group(pair.name));
      const UnloadedTca        t(members.pinion, members.gear, members.assembly, tca.options);
      std::vector<TcaPosition> positions;
      const int                z1 = members.pinion->teeth();
      for (int i = 0; i < tca.options.positions_per_mesh; ++i)
        positions.push_back(
            t.at(tca.options.start_angle + 2 * pi / z1 * i / tca.options.positions_per_mesh));
      const auto    segments = loaded_segments(positions, z1, members.gear->teeth(),
                                               segment_gap_per_module * member_module(pair));
      const H5Group g        = out.group(pair.name, "<pair>");
      // The tables on the scene's mesh, and for the error estimate on one of twice its element
      // sizes at the flanks (FeScene::error_estimate).
      // Both tables are computed before either is written: a failure leaves no half group.
      using Tables = std::vector<std::pair<FlankCompliance, MemberComplianceInfo>>;
      Progress progress("finite elements " + pair.name + ": member", fe.error_estimate ? 4 : 2);
      // With several processes the members are computed at once, each on its share of them
      // (member_compliances).
      auto compute = [&](const FeScene &mesh_fe, const std::string &mesh_dir) {
        std::vector<MemberJob> jobs;
        for (const bool is_pinion : {true, false})
          {
            const MemberFlanks  &flanks  = is_pinion ? *members.pinion : *members.gear;
            const SegmentChoice &segment = is_pinion ? segments.first : segments.second;
            const std::string    label   = std::string(is_pinion ? "pinion" : "gear") +
                                      (&mesh_fe == &fe ? "" : " (coarse mesh)") + ": ";
            MemberComplianceOptions mo = member_options(
                member_module(pair), flanks.teeth(), is_pinion, mesh_fe, side, segment, mesh_dir);
            mo.on_phase = [&progress, label](const std::string &what) {
              progress.note(label + what);
            };
            jobs.push_back({&flanks, [&pair, &flanks, is_pinion, mo, &progress](
                                         MPI_Comm comm, double memory, MemberComplianceInfo &info) {
                              MemberComplianceOptions o = mo;
                              o.communicator            = comm;
                              o.memory_available        = memory;
                              FlankCompliance table =
                                  compliance_table(pair, flanks, is_pinion, o, &info);
                              progress.advance();
                              return table;
                            }});
          }
        return member_compliances(jobs, MPI_COMM_WORLD);
      };
      int processes = 1;
      MPI_Comm_size(MPI_COMM_WORLD, &processes);
      auto write = [&](const Tables &tables, const H5Group &group, const std::string &label) {
        for (const bool is_pinion : {true, false})
          {
            const auto &[table, info]    = tables[is_pinion ? 0 : 1];
            const SegmentChoice &segment = is_pinion ? segments.first : segments.second;
            write_compliance(group.group(is_pinion ? "pinion" : "gear", "<member>"), table, info,
                             segment.central, fe.analytic_near_field);
            const hsize_t loads = table.load_points().size();
            log << "  " << pair.name << " " << (is_pinion ? "pinion" : "gear") << label << ": "
                << info.hexahedra << " hexahedra, " << info.dofs << " dofs, " << loads
                << " unit loads (";
            if (fe.analytic_near_field)
              log << "near field analytic within " << info.min_near_field_radius * 1e3
                  << " mm or more), ";
            else
              log << info.shallow_points << " read shallower), ";
            log << info.mesh_seconds + info.setup_seconds + info.solve_seconds << " s (mesh "
                << info.mesh_seconds << ", set-up " << info.setup_seconds << ", unit loads "
                << info.solve_seconds << " with the matrix's assembly and factorisation "
                << info.solver_seconds << " beside their assembly, of it factorisation "
                << info.factor_seconds << ")"
                << (info.out_of_core ? ", factors out of core (in memory they did not fit)" : "")
                << (processes > 1 ? " on " + std::to_string(info.processes) + " of " +
                                        std::to_string(processes) + " processes"
                                  : "")
                << "\n";
          }
      };
      // The segment meshes beside the cache file: every process reads them.
      write(compute(fe, stage_side_directory(out, "-mesh-" + pair.name)), g, "");
      if (!fe.error_estimate)
        continue;
      // Twice the element sizes; where gmsh cannot mesh that well (a twisted helical segment
      // with few layers can fold an element) or a load point lands across a held face, one and
      // a half, then one and a quarter times; else no estimate.
      for (const double factor : {2.0, 1.5, 1.25})
        try
          {
            const Tables tables = compute(
                fe.coarsened(factor), stage_side_directory(out, "-mesh-" + pair.name + "-coarse"));
            const H5Group cg = g.group("coarse");
            cg.attribute("method", "the same tables on a mesh of coarser elements at the flanks, "
                                   "fillets and other flanks (error estimate)");
            cg.write("coarsening", factor);
            write(tables, cg, " (coarse)");
            break;
          }
        catch (const InputError &e)
          {
            log << "  " << pair.name << ": the coarse mesh (element sizes x " << factor
                << ") failed: " << e.what()
                << (factor > 1.25 ? "; trying a finer one\n" : "; no error estimate\n");
          }
    }
}

/// Reference mode at the scene's chosen positions (both members meshed per position and
/// refined about its cells, finite elements alone; VTU files) on the fast mode's fitted zone,
/// at the torques the fast mode solved: <pair>/reference.
static void
run_reference_mode(const PairScene &pair, const FeScene &fe, const LoadedScene &lc,
                   const TcaScene &tca, const PairMembers &members, const UnloadedTca &theory,
                   const H5Group &cg, const LoadedContactOptions &lo, const MeshCycleContact &fine,
                   const std::vector<double> &torques, const H5Group &out, const H5Group &g,
                   std::ostream &log)
{
  const bool            bevel = pair.type == PairType::spiral_bevel;
  const int             z1 = members.pinion->teeth(), z2 = members.gear->teeth();
  const ReferenceMember ref_pinion =
      bevel
          ? bevel_reference_member(dynamic_cast<const BevelMemberFlanks &>(theory.pinion_flanks()),
                                   member_module(pair))
          : involute_reference_member(involute(*members.pinion), theory.pinion_flanks());
  const ReferenceMember ref_gear =
      bevel ? bevel_reference_member(dynamic_cast<const BevelMemberFlanks &>(theory.gear_flanks()),
                                     member_module(pair))
            : involute_reference_member(involute(*members.gear), theory.gear_flanks());
  // Reference mode at the chosen positions on the compliance stage's segments; VTU
  // files next to the stage's cache file (the driver copies them to <output>/vtu/).
  const std::filesystem::path vtu = stage_side_directory(out, "-vtu");
  ReferenceContactOptions     ro;
  ro.cells         = lo;
  ro.cells.covered = nullptr;
  // the reference zone: the fast mode's band at the position, for its largest torque
  ro.degree            = fe.degree;
  ro.hold_cuts         = fe.hold_cuts;
  ro.elements_per_cell = lc.reference_elements_per_cell;
  ro.work_directory    = vtu.string();
  // the segments of the fast mode (member_options): the teeth with grids, at least
  // the scene's segment teeth, or the whole gear
  auto segment = [&](const char *member, int z) {
    const ComplianceRecord m = read_compliance(cg.group(member), false);
    SegmentChoice          s;
    s.central = m.central_tooth;
    s.teeth   = fe.whole(std::string(member) == "pinion")
                    ? z
                    : std::max(fe.segment_teeth, int(m.grid_teeth.size()));
    return s;
  };
  ro.pinion_segment = segment("pinion", z1), ro.gear_segment = segment("gear", z2);
  ro.pinion_whole_rim = fe.whole_rim(true), ro.gear_whole_rim = fe.whole_rim(false);
  ro.flank_size         = fe.flank_size * member_module(pair);
  ro.far_size           = fe.far_size * member_module(pair);
  const std::size_t   P = lc.reference_positions.size(), M = torques.size();
  std::vector<double> phi, eL, K, F, dofs, seconds;
  Progress            progress("reference mode " + pair.name + ": position", P);
  for (std::size_t k = 0; k < P; ++k)
    {
      const int i = lc.reference_positions[k];
      progress.note("position " + std::to_string(i) + " meshing and solving");
      ro.vtu_prefix           = (vtu / (pair.name + "_position" + std::to_string(i))).string();
      ro.cells.cells.gap_band = 0;
      for (std::size_t m = 0; m < M; ++m)
        ro.cells.cells.gap_band =
            std::max(ro.cells.cells.gap_band, fine.gap_band[m * fine.positions + i]);
      ReferenceContactInfo              info;
      const std::vector<LoadedPosition> r = reference_contact(
          ref_pinion, ref_gear, theory,
          theory.at(tca.options.start_angle + 2 * pi / z1 * i / lc.positions), torques, ro, &info);
      phi.push_back(r.front().pinion_angle);
      for (const LoadedPosition &p : r)
        eL.push_back(p.eL), K.push_back(p.mesh_stiffness), F.push_back(p.normal_force);
      dofs.push_back(double(info.dofs));
      seconds.push_back(info.mesh_seconds + info.solve_seconds + info.contact_seconds);
      log << "  " << pair.name << " reference mode, position " << i << ": K_m";
      for (const LoadedPosition &p : r)
        log << " " << p.mesh_stiffness << " N/m";
      log << " (" << info.dofs << " dofs, " << seconds.back() << " s)\n";
      progress.advance();
    }
  // stored position-major: [position][torque]; transposed to the fast mode's layout
  auto by_torque = [&](const std::vector<double> &v) {
    std::vector<double> t(v.size());
    for (std::size_t k = 0; k < P; ++k)
      for (std::size_t m = 0; m < M; ++m)
        t[m * P + k] = v[k * M + m];
    return t;
  };
  const H5Group rg = g.group("reference");
  rg.attribute("method", "reference mode: both members meshed per position, refined "
                         "about its contact cells, finite elements alone");
  rg.write("position", lc.reference_positions, {P});
  rg.write("pinion_angle", phi, {P});
  rg.write("transmission_error_loaded", by_torque(eL), {M, P});
  rg.write("mesh_stiffness", by_torque(K), {M, P});
  rg.write("normal_force", by_torque(F), {M, P});
  rg.write("dofs", dofs, {P});
  rg.write("seconds", seconds, {P});
}

namespace
{
/// The loaded contact of one pair's mesh cycle at the scene's torques, written to `g`: a torque
/// that fails at some position is refused alone, with a warning (into `warnings`); the others
/// are kept. The contact at the kept torques and those torques.
std::pair<MeshCycleContact, std::vector<double>>
analyse_mesh_cycle(const PairScene &pair, const LoadedScene &lc, const UnloadedTca &t,
                   const LoadedContactOptions &lo, const StructuralCompliance &sp,
                   const StructuralCompliance &sg, const H5Group &g, const char *label,
                   std::string &warnings, std::ostream &log)
{
  Progress               progress("stiffness", lc.positions * lc.torques.size());
  const MeshCycleContact all =
      loaded_contact_cycle(t, lc.positions, lc.torques, lo, sp, sg, [&] { progress.advance(); });
  std::vector<std::size_t> keep;
  std::vector<double>      torques, refused;
  for (std::size_t k = 0; k < all.torques; ++k)
    if (all.torque_failure[k].empty())
      keep.push_back(k), torques.push_back(lc.torques[k]);
    else
      {
        std::ostringstream w;
        w << "Loaded contact/" << pair.name << "/torques" << label << ": " << lc.torques[k]
          << " N m refused: " << all.torque_failure[k];
        log << "  warning: " << w.str() << "\n";
        warnings += w.str() + "\n";
        refused.push_back(lc.torques[k]);
      }
  if (keep.empty())
    throw InputError("loaded contact of " + pair.name + label +
                     ": no torque could be solved; at the first, " + all.torque_failure.front());
  MeshCycleContact  c = select_torques(all, keep);
  const std::size_t n = c.positions;
  for (std::size_t k = 0; k < c.torques; ++k)
    {
      double k_mean = 0, de_min = HUGE_VAL, de_max = -HUGE_VAL;
      for (std::size_t i = 0; i < n; ++i)
        {
          const double de = c.loaded_te[k * n + i] - c.unloaded_te[i];
          k_mean += c.mesh_stiffness[k * n + i] / n;
          de_min = std::min(de_min, de), de_max = std::max(de_max, de);
        }
      log << "  " << pair.name << label << ", " << torques[k] << " N m: K_m mean " << k_mean
          << " N/m, e_L - e_0 " << de_min * 1e6 << " .. " << de_max * 1e6 << " urad\n";
    }
  write_mesh_cycle(g, c, torques, refused);
  return {std::move(c), torques};
}

/// The discretisation error estimate (mesh_cycle_error): the same mesh cycle on the coarse
/// mesh's tables (element sizes times c), and on half the contact cells; written to
/// stiffness/<pair>/error_estimate, or a warning (into `warnings`) where a contact failed.
void
run_error_estimate(const PairScene &pair, const FeScene &fe, const LoadedScene &lc, FlankSide side,
                   const PairMembers &members, const UnloadedTca &theory, const H5Group &cg,
                   const LoadedContactOptions &lo, const StructuralCompliance &sp,
                   const StructuralCompliance &sg, const MeshCycleContact &fine,
                   const std::vector<double> &torques, const H5Group &g, std::string &warnings,
                   std::ostream &log)
{
  const H5Group         coarse_tables = cg.group("coarse");
  const double          c             = coarse_tables.read_double("coarsening");
  const FlankCompliance cp2  = read_table(*members.pinion, coarse_tables, "pinion", fe, lc, side);
  const FlankCompliance cgr2 = read_table(*members.gear, coarse_tables, "gear", fe, lc, side);
  LoadedContactOptions  half = lo;
  half.cells                 = halved_cells(lo.cells);
  Progress               progress("stiffness error estimate", 2 * lc.positions * torques.size());
  const auto             step = [&] { progress.advance(); };
  const MeshCycleContact coarse =
      loaded_contact_cycle(theory, lc.positions, torques, lo, table_compliance(cp2, true),
                           table_compliance(cgr2, false), step);
  const MeshCycleContact halved =
      loaded_contact_cycle(theory, lc.positions, torques, half, sp, sg, step);
  std::string lost;
  for (std::size_t k = 0; k < torques.size() && lost.empty(); ++k)
    for (const MeshCycleContact *other : {&coarse, &halved})
      if (lost.empty() && !other->torque_failure[k].empty())
        lost = "Loaded contact/" + pair.name + ": no error estimate (at " +
               std::to_string(torques[k]) + " N m on " +
               (other == &coarse ? "the coarse elements" : "half the cells") +
               " the contact failed: " + other->torque_failure[k] + ")";
  if (!lost.empty())
    {
      log << "  warning: " << lost << "\n";
      warnings += lost + "\n";
      return;
    }
  const MeshCycleError err = mesh_cycle_error(fine, coarse, c, halved);
  const std::size_t    n = fine.positions, M = fine.torques;
  const H5Group        e = g.group("error_estimate");
  e.attribute("method", "|K(h) - K(c h)| / (c - 1) of the finite elements (the "
                        "compliance tables on a mesh of c times the element sizes at "
                        "the flanks, c = compliance/<pair>/coarse/coarsening, 2 unless "
                        "that mesh failed) plus |K(cells) - K(cells / 2)| of the contact "
                        "cells (half across and along); an upper estimate wherever the "
                        "error falls at least linearly with the size");
  e.write("mesh_stiffness", err.mesh_stiffness, {M, n});
  e.write("mesh_stiffness_elements", err.stiffness_by_elements, {M, n});
  e.write("mesh_stiffness_cells", err.stiffness_by_cells, {M, n});
  e.write("transmission_error_loaded", err.loaded_te, {M, n});
  for (std::size_t k = 0; k < M; ++k)
    {
      double largest = 0, mean = 0;
      for (std::size_t i = 0; i < n; ++i)
        {
          const double r = err.mesh_stiffness[k * n + i] / fine.mesh_stiffness[k * n + i];
          largest        = std::max(largest, r), mean += r / n;
        }
      log << "  " << pair.name << ", " << torques[k] << " N m: K_m error estimate mean "
          << mean * 100 << " %, largest " << largest * 100 << " %\n";
    }
}

/// ISO 6336-1 method B beside the finite elements (the standard's yardstick); for spiral bevel
/// pairs on the virtual cylindrical gears of the mean point (ISO 10300-1).
void
write_iso(const PairScene &pair, const PairMembers &members, const H5Group &g)
{
  const bool    bevel = pair.type == PairType::spiral_bevel;
  const IsoPair iso =
      bevel ? iso_pair(pair.bevel)
            : iso_pair(involute(*members.pinion), involute(*members.gear), members.centre_distance);
  if (bevel)
    g.attribute("iso_basis", "virtual cylindrical gears of the mean point (ISO 10300-1)");
  const double b = iso.face_width;
  g.write("transverse_contact_ratio", iso.input.transverse_contact_ratio);
  g.write("overlap_ratio", iso.overlap_ratio);
  const IsoMeshStiffness s = iso6336_mesh_stiffness(iso.input);
  g.write("iso_c_prime", s.c_prime * 1e9 * b);
  g.write("iso_c_gamma_alpha", s.c_gamma_alpha * 1e9 * b);
  g.write("iso_c_th", s.c_th * 1e9 * b);
}

/// The measured flanks' loaded contact (stiffness/<pair>/measured) on the theoretical pair's
/// compliances (measured_contact_options).
void
run_measured_flanks(const PairScene &pair, const LoadedScene &lc, const TcaScene &tca,
                    const LoadedPair &lp, const H5Group &measured, const H5Group &g,
                    std::string &warnings, std::ostream &log)
{
  const auto [mp, mg] = measured_members(measured);
  const H5Group gm    = g.group("measured");
  gm.attribute("method", "fast mode on the measured flanks, theoretical compliances reused");
  analyse_mesh_cycle(pair, lc, UnloadedTca(mp, mg, lp.members.assembly, tca.options),
                     measured_contact_options(lp, *mp, *mg, tca.options.side), lp.pinion_compliance,
                     lp.gear_compliance, gm, " measured", warnings, log);
}
} // namespace

void
run_stiffness_stage(const Scene &scene, const Upstream &upstream, const H5Group &out,
                    std::ostream &log)
{
  for (const PairScene &pair : scene.pairs)
    {
      // 1. The pair on the compliance tables as the compliance stage computed them.
      const FeScene      fe  = pair_fe(scene, pair);
      const LoadedScene &lc  = scene.loaded.at(pair.name);
      const TcaScene    &tca = scene.tca.at(pair.name);
      const H5Group      cg  = upstream.at("compliance")->group(pair.name);
      const LoadedPair   lp = loaded_pair(scene, pair, upstream.at("flanks")->group(pair.name), cg);
      const PairMembers &members     = lp.members;
      const UnloadedTca &theory      = *lp.theory;
      const LoadedContactOptions &lo = lp.options;
      const StructuralCompliance &sp = lp.pinion_compliance, &sg = lp.gear_compliance;

      // 2. The loaded contact over the mesh cycle at every torque (fast mode).
      const H5Group g = out.group(pair.name, "<pair>");
      g.attribute("method", "fast mode: FE compliance (tooth segments) + half-space contact");
      std::string pair_warnings; // of the loaded contact: refused torques, a lost estimate
      const auto [fine, torques] =
          analyse_mesh_cycle(pair, lc, theory, lo, sp, sg, g, "", pair_warnings, log);

      // 3. Its accuracy: the discretisation error estimate, the reference mode's positions.
      if (cg.has("coarse"))
        run_error_estimate(pair, fe, lc, tca.options.side, members, theory, cg, lo, sp, sg, fine,
                           torques, g, pair_warnings, log);
      if (!lc.reference_positions.empty())
        run_reference_mode(pair, fe, lc, tca, members, theory, cg, lo, fine, torques, out, g, log);

      // 4. ISO 6336-1 beside it, and the measured flanks on the same compliances.
      write_iso(pair, members, g);
      if (lc.measured) // (a measurement source is there: LoadedScene::check)
        run_measured_flanks(pair, lc, tca, lp, upstream.at("measured")->group(pair.name), g,
                            pair_warnings, log);
      if (!pair_warnings.empty())
        g.attribute("warnings", pair_warnings);
    }
}
} // namespace gearkit

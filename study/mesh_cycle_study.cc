#include "study/mesh_cycle_study.h"

#include "base/parallel.h"
#include "base/spectrum.h"
#include "geometry/involute_gear.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gearkit
{
namespace
{
const ToothModifications &
working_side(const InvoluteGearData &d, FlankSide side)
{
  return side == FlankSide::drive ? d.drive_modifications : d.coast_modifications;
}

/// A member's modifications `m` at flank parameters (roll angle u, z).
NormalDeviation
at_cell(const InvoluteGear &member, const ToothModifications &m, double u, double z)
{
  return evaluate_modifications(m, member.modification_frame(), member.base_radius * u, z);
}

/// sin and cos of k (L - L_form) at roll angle u on `member`, k = 2 pi / its
/// profile_form_wavelength.
std::pair<double, double>
form_wave(const InvoluteGear &member, double u)
{
  const ModificationFrame &f = member.modification_frame();
  const double             a =
      2 * pi / profile_form_wavelength(f) * (member.base_radius * u - f.roll_length_form);
  return {std::sin(a), std::cos(a)};
}

/// A member's per-tooth deviations for evaluation at many cells: each tooth's profile waviness
/// of the profile form wavelength taken out (`rest`), to be added from the cells' sines
/// (form_wave) with the tooth's amplitude and its phase's sine and cosine.
struct ToothWaves
{
  std::vector<ToothModifications> rest;
  std::vector<double>             amplitude, sin_phase, cos_phase;
  double                          wavelength = 0;

  ToothWaves(const InvoluteGear &member, const std::vector<ToothModifications> &teeth)
      : rest(teeth)
      , amplitude(teeth.size(), 0.0)
      , sin_phase(teeth.size(), 0.0)
      , cos_phase(teeth.size(), 1.0)
      , wavelength(profile_form_wavelength(member.modification_frame()))
  {
    for (std::size_t k = 0; k < rest.size(); ++k)
      if (rest[k].waviness_wavelength == wavelength)
        {
          amplitude[k] = rest[k].waviness_amplitude, rest[k].waviness_amplitude = 0;
          sin_phase[k] = std::sin(rest[k].waviness_phase);
          cos_phase[k] = std::cos(rest[k].waviness_phase);
        }
  }
  /// tooth k's deviations at a cell at (u, z) whose form_wave is `wave`
  NormalDeviation
  at(const InvoluteGear &member, std::size_t k, double u, double z,
     const std::pair<double, double> &wave) const
  {
    NormalDeviation d = at_cell(member, rest[k], u, z);
    if (amplitude[k] != 0)
      {
        const NormalDeviation w = waviness_term(amplitude[k], wavelength, sin_phase[k],
                                                cos_phase[k], wave.first, wave.second);
        d.value += w.value, d.d_dL += w.d_dL;
      }
    return d;
  }
};

/// Where a variant's search for a pair's contact starts: the pair's cell of the first touch
/// (the least gap less the added material per moment arm) and steps of about a cell in the
/// pinion's flank parameters.
struct SearchStart
{
  bool   any = false;
  double u1 = 0, v1 = 0, du = 0, dv = 0;
};

/// A variant's unloaded TE at the reference pair's position `at`: the gear's rotation is the
/// largest touch angle of the pairs that can touch (`has_cells` in a zone, or standing apart by
/// less than the most material the variant adds anywhere in the zones), each searched on the
/// variant's flanks: from the pair's first touch in its cells (`start`), else over the flank
/// and also from the reference pair's contact point (UnloadedTca::pair).
double
variant_unloaded_te(const UnloadedTca &variant, const TcaPosition &at,
                    const std::vector<char> &has_cells, double most_added,
                    const std::vector<SearchStart> &start)
{
  const int    z1 = variant.pinion_flanks().teeth(), z2 = variant.gear_flanks().teeth();
  const double s   = variant.options_data().side == FlankSide::drive ? 1.0 : -1.0;
  const int    k0  = int(std::lround(at.pinion_angle * z1 / (2 * pi)));
  double       psi = 0;
  bool         any = false;
  for (std::size_t p = 0; p < at.pairs.size(); ++p)
    {
      const PairContact &ref = at.pairs[p];
      if (!ref.found || (!has_cells[p] && ref.separation > most_added))
        continue;
      for (int k = k0 - 3; k <= k0 + 3; ++k) // the pairing of the pair's pinion tooth
        if (((-k % z1) + z1) % z1 == ref.pinion_tooth)
          {
            const SearchStart &a = start[p];
            PairContact        c;
            if (a.any)
              c = variant.pair_from(k, at.pinion_angle, a.u1, a.v1, a.du, a.dv);
            if (!c.found)
              c = variant.pair(k, at.pinion_angle, &ref);
            if (c.found && (!any || s * c.touch_angle > s * psi))
              psi = c.touch_angle, any = true;
          }
    }
  if (!any)
    {
      std::ostringstream msg;
      msg << "mesh cycle study: no tooth pair of the variant meets at pinion angle "
          << at.pinion_angle << " rad";
      throw InputError(msg.str());
    }
  return at.pinion_angle - psi / (double(z1) / z2); // as UnloadedTca::at
}
} // namespace

MeshCycleStudy::MeshCycleStudy(std::shared_ptr<const InvoluteMemberFlanks> pinion_,
                               std::shared_ptr<const InvoluteMemberFlanks> gear_,
                               const Assembly &assembly_, const TcaOptions &tca_,
                               const LoadedContactOptions  &contact,
                               const StructuralCompliance  &pinion_compliance,
                               const StructuralCompliance  &gear_compliance,
                               const MeshCycleStudyOptions &options)
    : pinion(std::move(pinion_))
    , gear(std::move(gear_))
    , assembly(assembly_)
    , tca_options(tca_)
    , o(options)
{
  if (!pinion || !gear)
    throw InputError("mesh cycle study: both members must be involute gears");
  if (o.positions < 4)
    throw InputError("mesh cycle study: at least 4 positions per mesh cycle (got " +
                     std::to_string(o.positions) + ")");
  if (o.torques.empty())
    throw InputError("mesh cycle study: no torque given");
  for (const double T : o.torques)
    if (!(T > 0) || !std::isfinite(T))
      throw InputError("mesh cycle study: the torques must be finite and > 0 (got " +
                       std::to_string(T) + " N m)");
  if (o.harmonics < 1 || o.harmonics > o.positions / 2)
    throw InputError("mesh cycle study: the mesh orders summarised must lie in [1, positions / 2]"
                     " (got " +
                     std::to_string(o.harmonics) + ")");
  if (o.cycles < 1)
    throw InputError("mesh cycle study: at least one mesh cycle (got " + std::to_string(o.cycles) +
                     ")");
  for (const InvoluteMemberFlanks *m : {pinion.get(), gear.get()})
    if (!m->teeth_alike())
      throw InputError("mesh cycle study: the members' teeth must be alike (no pitch "
                       "deviations, runout, per-tooth deviations, eccentric or chipped teeth "
                       "on " +
                       m->involute().data().name + "): the variants carry those");
  own.pinion = working_side(pinion->involute().data(), tca_options.side);
  own.gear   = working_side(gear->involute().data(), tca_options.side);
  tca        = std::make_unique<const UnloadedTca>(pinion, gear, assembly, tca_options);

  const std::size_t        N = std::size_t(o.positions), M = o.torques.size();
  const double             mesh_angle = 2 * pi / pinion->teeth();
  std::vector<TcaPosition> at(N);
  parallel_for(N, o.threads, [&](std::size_t i) {
    at[i] = tca->at(tca_options.start_angle + mesh_angle * double(i) / double(N));
  });
  zones.resize(M * N);
  LoadedContactOptions lo = contact;
  lo.threads              = 1;
  points.resize(M * N);
  parallel_for(M * N, o.threads, [&](std::size_t k) {
    zones[k]        = std::make_unique<const FixedZone>(*tca, at[k % N], o.torques[k / N], lo,
                                                 pinion_compliance, gear_compliance, o.widening);
    MemberPoints &q = points[k];
    // the rows of (J^T J)^-1 J^T, J = [P_u P_v]: flank parameters per tangential motion
    const auto projection = [](const FlankPoint &f) {
      Eigen::Matrix<double, 3, 2> J;
      J << f.d_du, f.d_dv;
      const Eigen::Matrix<double, 2, 3> G = (J.transpose() * J).inverse() * J.transpose();
      return std::pair<Vec3, Vec3>(G.row(0).transpose(), G.row(1).transpose());
    };
    for (const ContactCell &c : zones[k]->cells())
      {
        const FlankPoint a  = pinion->flank(c.pinion_tooth, tca_options.side).evaluate(c.u1, c.v1);
        const FlankPoint b  = gear->flank(c.gear_tooth, tca_options.side).evaluate(c.u2, c.v2);
        const auto [pu, pv] = projection(a);
        const auto [gu, gv] = projection(b);
        q.pinion_point.push_back(a.position), q.pinion_normal.push_back(a.normal);
        q.pinion_gu.push_back(pu), q.pinion_gv.push_back(pv);
        q.gear_point.push_back(b.position), q.gear_normal.push_back(b.normal);
        q.gear_gu.push_back(gu), q.gear_gv.push_back(gv);
        q.pinion_own.push_back(at_cell(pinion->involute(), own.pinion, c.u1, c.v1));
        q.gear_own.push_back(at_cell(gear->involute(), own.gear, c.u2, c.v2));
        q.pinion_wave.push_back(form_wave(pinion->involute(), c.u1));
        q.gear_wave.push_back(form_wave(gear->involute(), c.u2));
      }
  });
}

std::pair<std::shared_ptr<const InvoluteMemberFlanks>, std::shared_ptr<const InvoluteMemberFlanks>>
MeshCycleStudy::members(const PairVariant &v) const
{
  const auto with = [side = tca_options.side](const InvoluteGearData                &d,
                                              const ToothModifications              &m,
                                              const std::vector<ToothModifications> &teeth,
                                              const std::vector<double> &pitch, Runout runout) {
    InvoluteGearData out                                                                 = d;
    (side == FlankSide::drive ? out.drive_modifications : out.coast_modifications)       = m;
    (side == FlankSide::drive ? out.drive_tooth_deviations : out.coast_tooth_deviations) = teeth;
    out.single_pitch_deviations                                                          = pitch;
    out.runout                                                                           = runout;
    return std::make_shared<const InvoluteMemberFlanks>(InvoluteGear::create(out));
  };
  return {
      with(pinion->involute().data(), v.pinion, v.pinion_teeth, v.pinion_pitch, v.pinion_runout),
      with(gear->involute().data(), v.gear, v.gear_teeth, v.gear_pitch, v.gear_runout)};
}

MeshCycleStudy::Deviations
MeshCycleStudy::deviations(std::size_t torque, std::size_t position, int cycle,
                           const PairVariant &v) const
{
  const FixedZone                &zn    = zone(torque, position);
  const MemberPoints             &q     = points[torque * std::size_t(o.positions) + position];
  const std::vector<ContactCell> &cells = zn.cells();
  const InvoluteGear             &p = pinion->involute(), &g = gear->involute();
  const int                       z1 = p.teeth(), z2 = g.teeth();
  // The change of a member's deviations at roll angle u and z on its tooth k (value, d/du,
  // d/dz) and the derivatives of the variant's whole deviation there; `was`: the study's own
  // modifications there, which the variant's `now` replace (the same ones on tolerance samples).
  struct Change
  {
    NormalDeviation change;
    double          du = 0, dz = 0;
  };
  const bool       pinion_same = v.pinion == own.pinion, gear_same = v.gear == own.gear;
  const ToothWaves pinion_teeth(p, v.pinion_teeth), gear_teeth(g, v.gear_teeth);
  const auto       change = [](const InvoluteGear &m, const ToothModifications &now, bool same,
                         const ToothWaves &teeth, int k, const NormalDeviation &was,
                         const std::pair<double, double> &wave, double u, double z) {
    NormalDeviation a = same ? was : at_cell(m, now, u, z);
    if (!teeth.rest.empty())
      {
        const NormalDeviation t = teeth.at(m, std::size_t(k), u, z, wave);
        a.value += t.value, a.d_dL += t.d_dL, a.d_dz += t.d_dz;
      }
    return Change{{a.value - was.value, (a.d_dL - was.d_dL) * m.base_radius, a.d_dz - was.d_dz},
                  a.d_dL * m.base_radius,
                  a.d_dz};
  };
  // A tooth's turn by its cumulative pitch deviation (InvoluteGear's tooth angles) and the
  // toothing's runout e, in the member's frame at the zone's tooth's point: turn (e_z x P) and
  // Rz(-2 pi j / z) e (the runout seen from the zone's tooth, j = k - zone tooth); per member
  // and tooth once, not per cell.
  struct Rigid
  {
    std::vector<double> turn;   ///< [tooth] [rad]
    std::vector<Vec3>   runout; ///< [j] Rz(-2 pi j / z) e
  };
  const auto rigid_terms = [](const InvoluteGear &m, const std::vector<double> &pitch,
                              const Runout &runout) {
    Rigid     r;
    const int z          = m.teeth();
    double    cumulative = 0;
    for (int k = 0; k < z; ++k)
      {
        if (!pitch.empty() && k > 0)
          cumulative += pitch[std::size_t(k)];
        r.turn.push_back(cumulative / m.reference_radius);
        const double a = runout.phase - 2 * pi * k / z;
        r.runout.emplace_back(runout.eccentricity * std::cos(a), runout.eccentricity * std::sin(a),
                              0);
      }
    return r;
  };
  const Rigid rp    = rigid_terms(p, v.pinion_pitch, v.pinion_runout);
  const Rigid rg    = rigid_terms(g, v.gear_pitch, v.gear_runout);
  const auto  rigid = [](const Rigid &r, int z, int k, int zone_tooth, const Vec3 &point) {
    return Vec3(r.turn[std::size_t(k)] * Vec3::UnitZ().cross(point) +
                 r.runout[std::size_t(((k - zone_tooth) % z + z) % z)]);
  };
  // A member's material moved by w (its frame) at a flank point with normal n and tangents
  // P_u, P_v: the normal part moves the flank (w . n of material where n points out of it);
  // the tangential part brings the material of the flank parameters (u, v) - (du, dv) to the
  // point, and with it the deviation there, to first order value - (d/du du + d/dv dv).
  // (du, dv) = (J^T J)^-1 J^T w, J = [P_u P_v]: the rows of MemberPoints' tangent projection.
  const auto moved = [](const Vec3 &w, const Vec3 &n, const Vec3 &Gu, const Vec3 &Gv,
                        const Change &c) { return w.dot(n) - c.du * Gu.dot(w) - c.dz * Gv.dot(w); };
  // The gear axis's tilt: the rotation R = Ry(intersecting) Rx(crossing) about the gear centre
  // (Assembly::tilted) brings to X the gear's material from C + R^T (X - C): it moved by
  // (I - R^T)(X - C) (global; exact: its second-order part, 2e-8 m for 1 mrad at a 50 mm
  // radius, is a fifth of a percent of a light load's approach), in the gear's frame at the
  // zone's gear angle Rz(psi) (global_to_gear_unrotated).
  const Eigen::Matrix3d tilt =
      Eigen::Matrix3d::Identity() - (Eigen::AngleAxisd(v.intersecting_angle, Vec3::UnitY()) *
                                     Eigen::AngleAxisd(v.crossing_angle, Vec3::UnitX()))
                                        .toRotationMatrix()
                                        .transpose();
  const Vec3   centre = assembly.gear_centre();
  const bool   tilted = v.crossing_angle != 0 || v.intersecting_angle != 0;
  const double psi    = zn.position().gear_angle;
  // (I - R^T) in the gear's frame at the zone's gear angle: Rz(psi) global_to_gear_unrotated
  Eigen::Matrix3d to_gear;
  for (int k = 0; k < 3; ++k)
    to_gear.col(k) = assembly.global_to_gear_unrotated_vector(Vec3::Unit(k));
  const Eigen::Matrix3d tilt_in_gear =
      Eigen::AngleAxisd(psi, Vec3::UnitZ()).toRotationMatrix() * to_gear * tilt;
  Deviations d;
  d.added.resize(Eigen::Index(cells.size()));
  d.pinion_slope.resize(Eigen::Index(cells.size()), 2);
  d.gear_turn.resize(Eigen::Index(cells.size()));
  for (std::size_t j = 0; j < cells.size(); ++j)
    {
      const ContactCell &c  = cells[j];
      const int          tp = ((c.pinion_tooth - cycle) % z1 + z1) % z1;
      const int          tg = (c.gear_tooth + cycle) % z2;
      const Change       dp = change(p, v.pinion, pinion_same, pinion_teeth, tp, q.pinion_own[j],
                                     q.pinion_wave[j], c.u1, c.v1);
      const Change       dg =
          change(g, v.gear, gear_same, gear_teeth, tg, q.gear_own[j], q.gear_wave[j], c.u2, c.v2);
      Vec3 wg = rigid(rg, z2, tg, c.gear_tooth, q.gear_point[j]);
      if (tilted)
        wg += tilt_in_gear * (c.position - centre);
      const Vec3 wp = rigid(rp, z1, tp, c.pinion_tooth, q.pinion_point[j]);
      // (the gear's material moving along its outward normal opens the gap: - w . n)
      const auto i = Eigen::Index(j);
      d.added[i]   = dp.change.value + dg.change.value +
                   moved(wp, q.pinion_normal[j], q.pinion_gu[j], q.pinion_gv[j], dp) +
                   moved(wg, q.gear_normal[j], q.gear_gu[j], q.gear_gv[j], dg);
      d.pinion_slope(i, 0) = dp.change.d_dL, d.pinion_slope(i, 1) = dp.change.d_dz;
      const Vec3 turn = Vec3::UnitZ().cross(q.gear_point[j]);
      d.gear_turn[i]  = moved(turn, q.gear_normal[j], q.gear_gu[j], q.gear_gv[j], dg);
    }
  return d;
}

LoadedPosition
MeshCycleStudy::solve_variant(std::size_t m, std::size_t i, const Deviations &d, double e0,
                              const ActiveSetFactor *start) const
{
  const FixedZone &z            = zone(m, i);
  const double     sign         = tca_options.side == FlankSide::drive ? 1.0 : -1.0;
  const double     turned       = e0 - z.position().transmission_error; // [rad, pinion]
  const double     rotation     = sign * turned;
  const double     per_rotation = z.turn_per_rotation();
  if (!(std::abs(per_rotation) > 0) || !std::isfinite(per_rotation + turned))
    throw InputError("mesh cycle study: the gear's turn to the variant's unloaded TE does not "
                     "move the zone's cells along their normals (a zone off the flanks?)");
  return z.solve(d.added + (rotation / per_rotation) * d.gear_turn, o.torques[m], e0,
                 &d.pinion_slope, start, turned, o.turned_gear_compliance);
}

void
MeshCycleStudy::warm_start_from(const PairVariant &v)
{
  const std::size_t N = std::size_t(o.positions), M = o.torques.size();
  const int         cycles = o.cycles;
  o.cycles                 = 1; // the variant's active sets in the zones' own cycle
  warm.clear();
  const VariantCycle r = evaluate(v);
  o.cycles             = cycles;
  std::vector<ActiveSetFactor> starts(M * N);
  parallel_for(M * N, o.threads, [&](std::size_t k) {
    const std::size_t    m = k / N, i = k % N;
    const LoadedPosition p = solve_variant(m, i, deviations(m, i, 0, v), r.unloaded_te[i], nullptr);
    starts[k]              = zone(m, i).warm_start(p);
  });
  warm = std::move(starts);
}

VariantCycle
MeshCycleStudy::evaluate(const PairVariant &v, unsigned threads) const
{
  const std::size_t N = std::size_t(o.positions), M = o.torques.size();
  const std::size_t C = std::size_t(o.cycles), CN = C * N;
  const auto [vp, vg] = members(v); // checks the modifications against the flanks
  // The variant's TCA searches each pair from the reference pair's contact point (the
  // variant's lies near it): a coarse grid besides it suffices.
  TcaOptions search      = tca_options;
  search.profile_samples = std::min(search.profile_samples, 5);
  search.face_samples    = std::min(search.face_samples, 3);
  const UnloadedTca own_tca(vp, vg, assembly.tilted(v.crossing_angle, v.intersecting_angle),
                            search);
  const int         z1 = pinion->teeth(), z2 = gear->teeth();
  VariantCycle      r;
  r.torques = M, r.positions = CN, r.harmonics = o.harmonics;
  for (std::size_t i = 0; i < N; ++i)
    r.slots = std::max(r.slots, zone(0, i).position().pairs.size());
  r.unloaded_te.assign(CN, 0.0);
  r.loaded_te.assign(M * CN, 0.0), r.mesh_stiffness.assign(M * CN, 0.0);
  r.normal_force.assign(M * CN, 0.0), r.peak_pressure.assign(M * CN, 0.0);
  r.interior_pressure.assign(M * CN, 0.0);
  r.edge_load_share.assign(M * CN, 0.0), r.pair_share.assign(M * CN * r.slots, 0.0);
  std::vector<char> edge(M * CN, 0);
  // (each zone's cycles one after the other: its compliance stays in the cache)
  parallel_for(CN, threads == 0 ? o.threads : threads, [&](std::size_t q) {
    const std::size_t i     = q / C;
    const int         cycle = int(q % C);
    const std::size_t job   = std::size_t(cycle) * N + i;
    // The zone's position one mesh cycle on per cycle: the next teeth in the same place.
    TcaPosition at = zone(0, i).position();
    at.pinion_angle += 2 * pi * cycle / z1, at.gear_angle += 2 * pi * cycle / z2;
    for (PairContact &c : at.pairs)
      c.pinion_tooth = ((c.pinion_tooth - cycle) % z1 + z1) % z1,
      c.gear_tooth   = (c.gear_tooth + cycle) % z2;
    std::vector<Deviations> dev;
    std::vector<char>       has_cells(at.pairs.size(), 0);
    double                  most_added = 0;
    for (std::size_t m = 0; m < M; ++m)
      {
        dev.push_back(deviations(m, i, cycle, v));
        most_added = std::max(most_added, dev.back().added.maxCoeff());
        for (const ContactCell &c : zone(m, i).cells())
          has_cells[std::size_t(c.pair)] = 1;
      }
    // each pair's first touch in the first torque's zone
    std::vector<SearchStart> search_from(at.pairs.size());
    std::vector<double>      first(at.pairs.size(), HUGE_VAL);
    const MemberPoints      &q0 = points[i];
    for (std::size_t j = 0; j < zone(0, i).cells().size(); ++j)
      {
        const ContactCell &c     = zone(0, i).cells()[j];
        const double       touch = (c.gap - dev[0].added[Eigen::Index(j)]) / c.lever;
        const std::size_t  p     = std::size_t(c.pair);
        if (touch < first[p])
          {
            const double h = std::max(c.ds, c.dt);
            first[p]       = touch;
            search_from[p] = {true, c.u1, c.v1, h * q0.pinion_gu[j].norm(),
                              h * q0.pinion_gv[j].norm()};
          }
      }
    const double e0    = variant_unloaded_te(own_tca, at, has_cells, most_added, search_from);
    r.unloaded_te[job] = e0;
    for (std::size_t m = 0; m < M; ++m)
      {
        const ActiveSetFactor *start = warm.empty() ? nullptr : &warm[m * N + i];
        const LoadedPosition   p     = solve_variant(m, i, dev[m], e0, start);
        const std::size_t      k     = m * CN + job;
        r.loaded_te[k] = p.eL, r.mesh_stiffness[k] = p.mesh_stiffness;
        r.normal_force[k] = p.normal_force;
        for (std::size_t s = 0; s < p.pair_force.size(); ++s)
          r.pair_share[k * r.slots + s] = p.pair_force[s] / p.normal_force;
        for (std::size_t j = 0; j < p.cells.size(); ++j)
          {
            const double pressure = p.force[Eigen::Index(j)] / (p.cells[j].ds * p.cells[j].dt);
            r.peak_pressure[k]    = std::max(r.peak_pressure[k], pressure);
            if (!p.cells[j].flank_edge)
              r.interior_pressure[k] = std::max(r.interior_pressure[k], pressure);
          }
        r.edge_load_share[k] = p.edge_force / p.normal_force;
        edge[k]              = p.zone_edge_reached;
      }
  });
  for (std::size_t m = 0; m < M; ++m)
    {
      const auto row = [&](const std::vector<double> &t) {
        return std::vector<double>(t.begin() + long(m * CN), t.begin() + long((m + 1) * CN));
      };
      const std::vector<double> eL = row(r.loaded_te), K = row(r.mesh_stiffness);
      const auto [lo, hi] = std::minmax_element(eL.begin(), eL.end());
      r.te_peak_to_peak.push_back(*hi - *lo);
      const std::vector<double> h = mesh_order_amplitudes(eL, int(C), o.harmonics);
      r.te_harmonics.insert(r.te_harmonics.end(), h.begin() + 1, h.end());
      const auto [klo, khi] = std::minmax_element(K.begin(), K.end());
      double mean           = 0;
      for (const double k : K)
        mean += k / double(CN);
      r.stiffness_mean.push_back(mean), r.stiffness_range.push_back(*khi - *klo);
      const std::vector<double> p = row(r.peak_pressure), e = row(r.edge_load_share);
      const std::vector<double> q = row(r.interior_pressure);
      r.max_pressure.push_back(*std::max_element(p.begin(), p.end()));
      r.max_interior_pressure.push_back(*std::max_element(q.begin(), q.end()));
      r.max_edge_share.push_back(*std::max_element(e.begin(), e.end()));
      r.zone_edge.push_back(std::any_of(edge.begin() + long(m * CN),
                                        edge.begin() + long((m + 1) * CN),
                                        [](char c) { return c != 0; }));
    }
  return r;
}
} // namespace gearkit

#include "study/misalignment_study.h"

#include "geometry/member_flanks.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gearkit
{
namespace
{
const GridFields<Misalignment> &
fields()
{
  static const GridFields<Misalignment> f(
      "misalignment grid", {{"offset", &Misalignment::offset},
                            {"centre_distance_error", &Misalignment::centre_distance_error},
                            {"crossing_angle", &Misalignment::crossing_angle},
                            {"intersecting_angle", &Misalignment::intersecting_angle},
                            {"pinion_axial_shift", &Misalignment::pinion_axial_shift},
                            {"gear_axial_shift", &Misalignment::gear_axial_shift}});
  return f;
}

/// The contact pattern of torque m of `c` on the gear flank's domain `d`: the raster of the
/// largest pressure, the pressure-weighted centre and the loaded cells' extent (appended).
void
add_pattern(MisalignedMesh &r, const MeshCycleContact &c, std::size_t m, const FlankDomain &d,
            const MisalignmentStudyOptions &o)
{
  const std::size_t   NU = std::size_t(o.profile_bins), NV = std::size_t(o.face_bins);
  std::vector<double> raster(NU * NV, 0.0);
  double              weight = 0, cu = 0, cv = 0;
  double              u_lo = HUGE_VAL, u_hi = -HUGE_VAL, v_lo = HUGE_VAL, v_hi = -HUGE_VAL;
  const auto          bin = [](double x, double lo, double hi, std::size_t n) {
    const double t = (x - lo) / (hi - lo) * double(n);
    return std::size_t(std::clamp(t, 0.0, double(n) - 1));
  };
  for (std::size_t i = 0; i < c.positions; ++i)
    for (std::size_t j = 0; j < c.cells; ++j)
      {
        const std::size_t at = (m * c.positions + i) * c.cells + j;
        const double      p  = c.cell_pressure[at * 4 + 3];
        if (!(p > 0) || c.cell_pressure[at * 4] < 0)
          continue;
        const double u = c.cell_gear[at * 2], v = c.cell_gear[at * 2 + 1];
        double &cell = raster[bin(u, d.u_min, d.u_max, NU) * NV + bin(v, d.v_min, d.v_max, NV)];
        cell         = std::max(cell, p);
        weight += p, cu += p * u, cv += p * v;
        u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u);
        v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
      }
  if (!(weight > 0))
    throw InputError("misalignment check: no cell carries load at torque " +
                     std::to_string(o.torques[m]) + " N m");
  r.pattern.insert(r.pattern.end(), raster.begin(), raster.end());
  r.pattern_centre.insert(r.pattern_centre.end(), {cu / weight, cv / weight});
  r.pattern_extent.insert(r.pattern_extent.end(), {u_lo, u_hi, v_lo, v_hi});
}
} // namespace

const std::vector<std::string> &
misalignment_field_names()
{
  return fields().names();
}

double Misalignment::       *
misalignment_field(const std::string &name)
{
  return fields().field(name);
}

Misalignment
grid_misalignment(const ParameterGrid &grid, std::size_t g, Misalignment m)
{
  const std::vector<std::size_t> at = grid.index(g);
  for (std::size_t k = 0; k < grid.axes().size(); ++k)
    m.*misalignment_field(grid.axes()[k].name) = grid.axes()[k].values[at[k]];
  return m;
}

std::pair<double, double>
flank_lengths(const MemberFlanks &member, double u, double v)
{
  if (const auto *inv = dynamic_cast<const InvoluteMemberFlanks *>(&member))
    return {inv->involute().base_radius * u, v};
  return {u, v};
}

MisalignedMesh
misaligned_mesh(std::shared_ptr<const MemberFlanks> pinion,
                std::shared_ptr<const MemberFlanks> gear, const Assembly &assembly,
                const TcaOptions &tca_options, const LoadedContactOptions &contact,
                const StructuralCompliance &pinion_compliance,
                const StructuralCompliance &gear_compliance, const MisalignmentStudyOptions &o)
{
  if (o.torques.empty())
    throw InputError("misalignment check: no torque given");
  for (const double T : o.torques)
    if (!(T > 0) || !std::isfinite(T))
      throw InputError("misalignment check: torques must be finite and > 0 (got " +
                       std::to_string(T) + " N m)");
  if (o.positions < 4 || o.profile_bins < 1 || o.face_bins < 1)
    throw InputError("misalignment check: at least 4 positions and one bin each way");
  const FlankDomain domain = gear->flank(0, tca_options.side).domain();
  // Members whose teeth are all alike (involute ones) repeat every mesh cycle: the unloaded
  // TCA over one. (Spiral bevel members count each tooth as its own class: the TCA's cycles.)
  TcaOptions once = tca_options;
  if (pinion->teeth_alike() && gear->teeth_alike())
    once.mesh_cycles = 1;
  const UnloadedTca tca(pinion, gear, assembly, once);

  // 1. Unloaded: e_0 over the TCA's positions and the leading pair's path on the gear flank.
  MisalignedMesh  r;
  const TcaResult unloaded = tca.run();
  double          lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &p : unloaded.positions)
    {
      r.unloaded_te.push_back(p.transmission_error);
      r.tca_pinion_angle.push_back(p.pinion_angle);
      lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
      if (p.leading < 0)
        throw InputError("misalignment check: no pair touches at pinion angle " +
                         std::to_string(p.pinion_angle) +
                         " rad: the misalignment separates the flanks");
      const PairContact &c = p.pairs[std::size_t(p.leading)];
      r.path.insert(r.path.end(), {c.u2, c.v2});
      r.path_centre[0] += c.u2 / double(unloaded.positions.size());
      r.path_centre[1] += c.v2 / double(unloaded.positions.size());
    }
  r.unloaded_peak_to_peak = hi - lo;

  // 2. Loaded: the mesh cycle at every torque on the compliances, and its summaries.
  r.loaded = loaded_contact_cycle(tca, o.positions, o.torques, contact, pinion_compliance,
                                  gear_compliance);
  const MeshCycleContact &c = r.loaded;
  for (std::size_t m = 0; m < c.torques; ++m)
    {
      if (!c.torque_failure[m].empty())
        throw InputError("misalignment check at " + std::to_string(o.torques[m]) +
                         " N m: " + c.torque_failure[m]);
      const auto row = [&](const std::vector<double> &v) {
        return std::pair{v.begin() + long(m * c.positions),
                         v.begin() + long((m + 1) * c.positions)};
      };
      const auto [e0, e1]     = row(c.loaded_te);
      const auto [lo_e, hi_e] = std::minmax_element(e0, e1);
      r.loaded_peak_to_peak.push_back(*hi_e - *lo_e);
      const auto [k0, k1] = row(c.mesh_stiffness);
      double sum          = 0;
      for (auto k = k0; k != k1; ++k)
        sum += *k;
      r.stiffness_mean.push_back(sum / double(c.positions));
      const auto [p0, p1] = row(c.peak_pressure);
      r.max_pressure.push_back(*std::max_element(p0, p1));
      const auto [q0, q1] = row(c.interior_peak_pressure);
      r.max_interior_pressure.push_back(*std::max_element(q0, q1));
      const auto [s0, s1] = row(c.edge_load_share);
      r.max_edge_share.push_back(*std::max_element(s0, s1));
      add_pattern(r, c, m, domain, o);
    }
  return r;
}
} // namespace gearkit

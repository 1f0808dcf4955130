#include "stiffness/loaded_contact.h"

#include "base/parallel.h"
#include "stiffness/contact_solver.h"

#include <algorithm>
#include <mutex>
#include <sstream>

namespace gearkit
{
std::vector<ContactCell>
loaded_cells(const UnloadedTca &tca, const TcaPosition &position, const LoadedContactOptions &o)
{
  std::vector<ContactCell> cells = contact_cells(tca, position, o.cells);
  if (o.covered)
    {
      for (const PairContact &c : position.pairs)
        if (c.found && c.separation <= tca.options_data().contact_tolerance &&
            !o.covered(c.pinion_tooth, c.gear_tooth))
          throw InputError("loaded contact: pinion tooth " + std::to_string(c.pinion_tooth) +
                           " and gear tooth " + std::to_string(c.gear_tooth) +
                           " touch but the finite-element segments do not cover them; use more "
                           "segment teeth");
      cells.erase(std::remove_if(cells.begin(), cells.end(),
                                 [&](const ContactCell &c) {
                                   return !o.covered(c.pinion_tooth, c.gear_tooth);
                                 }),
                  cells.end());
    }
  if (cells.empty())
    {
      std::ostringstream msg;
      msg << "loaded contact: no contact cell within the gap band (" << o.cells.gap_band * 1e6
          << " um) at pinion angle " << position.pinion_angle << " rad";
      throw InputError(msg.str());
    }
  if (o.table_parameters)
    for (ContactCell &c : cells)
      o.table_parameters(c);
  return cells;
}

static LoadedPosition
loaded_contact_in_zone(const UnloadedTca &, const TcaPosition &, double,
                       const LoadedContactOptions &, const StructuralCompliance &,
                       const StructuralCompliance &);

LoadedPosition
loaded_contact(const UnloadedTca &tca, const TcaPosition &position, double torque,
               const LoadedContactOptions &options, const StructuralCompliance &pinion,
               const StructuralCompliance &gear)
{
  LoadedContactOptions o = options;
  for (int widening = 0;; ++widening)
    {
      LoadedPosition r = loaded_contact_in_zone(tca, position, torque, o, pinion, gear);
      if (!r.zone_edge_reached)
        return r;
      if (widening == 4)
        {
          const ContactCell &c = r.cells[std::size_t(r.zone_edge_cell)];
          std::ostringstream msg;
          msg << "loaded contact: at pinion angle " << position.pinion_angle << " rad and "
              << torque << " N m the contact spreads beyond a cell zone of gap band "
              << o.cells.gap_band * 1e6 << " um (pinion tooth " << c.pinion_tooth << ", gear tooth "
              << c.gear_tooth << ", pinion point z = " << c.position.z() * 1e3
              << " mm, r = " << c.position.head<2>().norm() * 1e3 << " mm, "
              << r.force[r.zone_edge_cell] << " N of " << r.normal_force
              << " N); check the load and the compliances, or raise the gap band (scene: "
                 "Loaded contact/<pair>/gap band [um])";
          throw InputError(msg.str());
        }
      o.cells.gap_band *= 2;
      // the zone's width grows with the square root of the gap band: cells of the same size
      o.cells.cells_across = int(std::ceil(o.cells.cells_across * std::sqrt(2.0))) | 1;
    }
}

static LoadedPosition
loaded_contact_in_zone(const UnloadedTca &tca, const TcaPosition &position, double torque,
                       const LoadedContactOptions &o, const StructuralCompliance &pinion,
                       const StructuralCompliance &gear)
{
  std::vector<ContactCell> cells = loaded_cells(tca, position, o);
  const Eigen::Index       n     = Eigen::Index(cells.size());
  Eigen::MatrixXd          C(n, n);
  const double             Estar = contact_modulus(o.pinion_material, o.gear_material);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      {
        const ContactCell &ci = cells[i], &cj = cells[j];
        double             c = pinion(ci, cj) + gear(ci, cj);
        if (o.half_space && ci.pair == cj.pair)
          c += rectangle_displacement(cj.s - ci.s, cj.t - ci.t, ci.ds / 2, ci.dt / 2, 1.0, Estar);
        C(j, i) = c;
      }
  LoadedPosition r = solve_loaded_contact(tca, position, torque, std::move(cells), C);
  r.gap_band       = o.cells.gap_band;
  return r;
}

LoadedPosition
solve_loaded_contact(const UnloadedTca &tca, const TcaPosition &position, double torque,
                     std::vector<ContactCell> cells, const Eigen::MatrixXd &compliance)
{
  if (!(torque >= 0) || !std::isfinite(torque))
    throw InputError("loaded contact: the pinion torque must be finite and >= 0 (got " +
                     std::to_string(torque) + " N m)");
  const Eigen::Index n = Eigen::Index(cells.size());
  if (n == 0 || compliance.rows() != n || compliance.cols() != n || !compliance.allFinite())
    throw InputError("loaded contact: the compliance must be a finite square matrix, one row "
                     "per contact cell");
  LoadedPosition out;
  out.pinion_angle = position.pinion_angle;
  out.e0           = position.transmission_error;
  out.torque       = torque;
  out.cells        = std::move(cells);
  ContactProblem p;
  p.gap.resize(n);
  p.lever.resize(n);
  p.load = torque;
  for (Eigen::Index i = 0; i < n; ++i)
    p.gap[i] = out.cells[i].gap, p.lever[i] = out.cells[i].lever;
  // Maxwell-Betti: the exact compliance is symmetric; interpolation is not quite.
  p.compliance = (compliance + compliance.transpose()) / 2;

  if (torque == 0)
    {
      out.eL    = out.e0; // nothing moves; the cells' first touch only samples the gap
      out.force = Eigen::VectorXd::Zero(n);
      out.pair_force.assign(position.pairs.size(), 0.0);
      return out;
    }
  const ContactSolution s = solve_contact(p);
  for (Eigen::Index i = 0; i < n; ++i)
    if (s.force[i] > 0 && out.cells[i].zone_edge &&
        (out.zone_edge_cell < 0 || s.force[i] > s.force[out.zone_edge_cell]))
      out.zone_edge_cell = int(i);
  out.zone_edge_reached = out.zone_edge_cell >= 0;
  const double sign     = tca.options_data().side == FlankSide::drive ? 1.0 : -1.0;
  out.force             = s.force;
  out.active_cells      = s.active;
  out.iterations        = s.iterations;
  out.eL                = out.e0 + sign * s.approach;
  out.pair_force.assign(position.pairs.size(), 0.0);
  for (Eigen::Index i = 0; i < n; ++i)
    out.pair_force[out.cells[i].pair] += s.force[i];
  out.normal_force = s.force.sum();
  // e_L - e_0 = the approach: pinion rotation beyond the unloaded position, gear held.
  out.lever          = torque / out.normal_force;
  out.mesh_stiffness = out.normal_force / (out.lever * s.approach);
  return out;
}

MeshCycleContact
loaded_contact_cycle(const UnloadedTca &t, int n, const std::vector<double> &torques,
                     const LoadedContactOptions &lo, const StructuralCompliance &sp,
                     const StructuralCompliance &sg, const std::function<void()> &step)
{
  const int                m          = int(torques.size());
  const double             mesh_angle = 2 * pi / t.pinion_flanks().teeth();
  std::vector<TcaPosition> positions;
  double                   touching = 0;
  for (int i = 0; i < n; ++i)
    {
      positions.push_back(t.at(t.options_data().start_angle + mesh_angle * i / n));
      touching += positions.back().touching;
    }
  MeshCycleContact c;
  c.torques = std::size_t(m), c.positions = std::size_t(n);
  for (const TcaPosition &p : positions)
    c.slots = std::max(c.slots, p.pairs.size());
  for (const TcaPosition &p : positions)
    for (std::size_t s = 0; s < c.slots; ++s)
      c.slot_tooth.push_back(s < p.pairs.size() ? p.pairs[s].pinion_tooth : -1);
  // Every (torque, position) on its own, on a few threads.
  std::vector<std::vector<LoadedPosition>> results(
      static_cast<std::size_t>(m), std::vector<LoadedPosition>(static_cast<std::size_t>(n)));
  std::mutex progress;
  parallel_for(std::size_t(m * n), lo.threads, [&](std::size_t job) {
    results[job / std::size_t(n)][job % std::size_t(n)] = loaded_contact(
        t, positions[job % std::size_t(n)], torques[job / std::size_t(n)], lo, sp, sg);
    if (step)
      {
        const std::lock_guard<std::mutex> lock(progress);
        step();
      }
  });
  for (const auto &torque : results)
    for (const LoadedPosition &r : torque)
      c.cells = std::max(c.cells, r.cells.size());
  for (int i = 0; i < n; ++i)
    c.pinion_angle.push_back(positions[i].pinion_angle),
        c.unloaded_te.push_back(positions[i].transmission_error);
  for (int k = 0; k < m; ++k)
    for (int i = 0; i < n; ++i)
      {
        const LoadedPosition &r = results[k][i];
        c.loaded_te.push_back(r.eL), c.mesh_stiffness.push_back(r.mesh_stiffness);
        c.normal_force.push_back(r.normal_force), c.lever.push_back(r.lever);
        for (std::size_t s = 0; s < c.slots; ++s)
          c.pair_force.push_back(s < r.pair_force.size() ? r.pair_force[s] : 0.0);
        double p_max = 0;
        for (std::size_t j = 0; j < c.cells; ++j)
          {
            const bool         used = j < r.cells.size();
            const ContactCell  none;
            const ContactCell &cell = used ? r.cells[j] : none;
            const double       p    = used ? r.force[Eigen::Index(j)] / (cell.ds * cell.dt) : 0.0;
            p_max                   = std::max(p_max, p);
            c.cell_pressure.insert(c.cell_pressure.end(),
                                   {used ? double(cell.pinion_tooth) : -1.0, cell.u1, cell.v1, p});
          }
        c.peak_pressure.push_back(p_max);
      }
  c.mean_pairs_in_contact = touching / n;
  return c;
}

MeshCycleError
mesh_cycle_error(const MeshCycleContact &r, const MeshCycleContact &coarse, double c,
                 const MeshCycleContact &half)
{
  const std::size_t n = r.mesh_stiffness.size();
  if (!(c > 1) || coarse.mesh_stiffness.size() != n || half.mesh_stiffness.size() != n)
    throw InputError("mesh cycle error: the coarsening must exceed 1 and the three cycles "
                     "share their torques and positions");
  MeshCycleError e;
  for (std::size_t i = 0; i < n; ++i)
    {
      e.stiffness_by_elements.push_back(std::abs(r.mesh_stiffness[i] - coarse.mesh_stiffness[i]) /
                                        (c - 1));
      e.stiffness_by_cells.push_back(std::abs(r.mesh_stiffness[i] - half.mesh_stiffness[i]));
      e.mesh_stiffness.push_back(e.stiffness_by_elements[i] + e.stiffness_by_cells[i]);
      e.loaded_te.push_back(std::abs(r.loaded_te[i] - coarse.loaded_te[i]) / (c - 1) +
                            std::abs(r.loaded_te[i] - half.loaded_te[i]));
    }
  return e;
}

ContactCellOptions
halved_cells(ContactCellOptions cells)
{
  cells.cells_across = (cells.cells_across / 2) | 1;
  cells.cells_along  = std::max(1, cells.cells_along / 2);
  return cells;
}
} // namespace gearkit

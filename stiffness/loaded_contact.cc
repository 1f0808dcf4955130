#include "stiffness/loaded_contact.h"

#include "base/parallel.h"
#include "stiffness/collective.h"
#include "stiffness/contact_solver.h"

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <map>
#include <mutex>
#include <sstream>

namespace gearkit
{
StructuralCompliance::StructuralCompliance(Pair pair, Matrix matrix)
    : pair(std::move(pair))
    , all(std::move(matrix))
{
}

Eigen::MatrixXd
StructuralCompliance::matrix(const std::vector<ContactCell> &cells) const
{
  if (all)
    return all(cells);
  const Eigen::Index n = Eigen::Index(cells.size());
  Eigen::MatrixXd    M(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      M(j, i) = pair(cells[std::size_t(i)], cells[std::size_t(j)]);
  return M;
}

StructuralCompliance
table_compliance(const FlankCompliance &table, bool pinion)
{
  const auto at = [pinion](const ContactCell &c) {
    return pinion ? FlankCompliance::Location{c.pinion_tooth, c.table_u1, c.table_v1}
                  : FlankCompliance::Location{c.gear_tooth, c.table_u2, c.table_v2};
  };
  return StructuralCompliance(
      [&table, at](const ContactCell &i, const ContactCell &j) {
        const FlankCompliance::Location a = at(i), b = at(j);
        return table(a.tooth, a.u, a.v, b.tooth, b.u, b.v);
      },
      [&table, at](const std::vector<ContactCell> &cells) {
        std::vector<FlankCompliance::Location> points;
        for (const ContactCell &c : cells)
          points.push_back(at(c));
        return table.matrix(points);
      });
}

std::vector<ContactCell>
loaded_cells(const UnloadedTca &tca, const TcaPosition &position, const LoadedContactOptions &o)
{
  std::vector<ContactCell> cells = contact_cells(tca, position, o.cells);
  if (o.covered)
    {
      for (const PairContact &c : position.pairs)
        if (c.found &&
            c.separation <= std::max(tca.options_data().contact_tolerance, o.cells.pair_gap) &&
            !o.covered(c.pinion_tooth, c.gear_tooth))
          throw InputError("loaded contact: pinion tooth " + std::to_string(c.pinion_tooth) +
                           " and gear tooth " + std::to_string(c.gear_tooth) +
                           (c.separation <= tca.options_data().contact_tolerance
                                ? " touch"
                                : " come into contact under the load") +
                           " but the finite-element segments do not cover them; use more "
                           "segment teeth (Finite elements/<pair>/segment teeth)");
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

namespace
{
/// The most loaded of the cells that have `flag` set (-1: none loaded). Forces within 1e-8 of
/// the largest count as equal and the first such cell wins: a pair's mirror-symmetric cells
/// (the two face ends of a spur pair) carry equal loads up to rounding, and the answer must not
/// depend on the rounding of the machine's BLAS.
int
most_loaded(const Eigen::VectorXd &force, const std::vector<ContactCell> &cells,
            bool ContactCell::*flag)
{
  double largest = 0;
  for (Eigen::Index i = 0; i < force.size(); ++i)
    if (cells[std::size_t(i)].*flag)
      largest = std::max(largest, force[i]);
  if (!(largest > 0))
    return -1;
  for (Eigen::Index i = 0; i < force.size(); ++i)
    if (cells[std::size_t(i)].*flag && force[i] >= largest * (1 - 1e-8))
      return int(i);
  return -1;
}

/// The gap band to start from when the scene leaves it to the load: four times the gap at the
/// edge of Hertz's line contact, 2 q / (pi E*), for the torque on the leading pair alone along
/// the pinion flank's face (a thousandth of the face with no load: only the cells' positions
/// matter then).
double
starting_band(const UnloadedTca &tca, const TcaPosition &position, double torque, double Estar)
{
  const PairContact &c     = position.pairs[std::size_t(position.leading)];
  const Flank       &flank = tca.pinion_flanks().flank(c.pinion_tooth, tca.options_data().side);
  const FlankDomain  d     = flank.domain();
  const double       u     = (d.u_min + d.u_max) / 2;
  const double       face =
      (flank.evaluate(u, d.v_max).position - flank.evaluate(u, d.v_min).position).norm();
  const double lever = pinion_lever(c.position, c.normal_pinion);
  if (!(torque > 0) || !(lever > 0))
    return 1e-3 * face;
  return 4 * 2 * (torque / lever / face) / (pi * Estar);
}

/// The gap at the edge of the solved contact (relative to each pair's separation). A column
/// with one loaded cell shows no gap of its own (the contact is narrower than a cell): there
/// Hertz's 2 q / (pi E*) for the column's load per length q, at most the gap at half a cell's
/// width (band / cells across^2), which the next zone resolves.
double
contact_edge_gap(const TcaPosition &position, const LoadedPosition &r,
                 const ContactCellOptions &cells, double Estar)
{
  struct Column
  {
    double q      = 0;
    int    loaded = 0;
  };
  double                                g = 0;
  std::map<std::pair<int, int>, Column> column;
  for (std::size_t i = 0; i < r.cells.size(); ++i)
    {
      const ContactCell &c = r.cells[i];
      const double       f = r.force[Eigen::Index(i)];
      if (!(f > 0))
        continue;
      g = std::max(g, c.gap - std::max(0.0, position.pairs[std::size_t(c.pair)].separation));
      Column &k = column[{c.pair, c.column}];
      k.q += f / c.dt, ++k.loaded;
    }
  for (const auto &[key, k] : column)
    if (k.loaded == 1)
      g = std::max(g, std::min(2 * k.q / (pi * Estar),
                               cells.gap_band / (cells.cells_across * cells.cells_across)));
  return g;
}
} // namespace

LoadedPosition
loaded_contact(const UnloadedTca &tca, const TcaPosition &position, double torque,
               const LoadedContactOptions &options, const StructuralCompliance &pinion,
               const StructuralCompliance &gear)
{
  LoadedContactOptions o     = options;
  const double         Estar = contact_modulus(o.pinion_material, o.gear_material);
  if (!(o.cells.gap_band > 0))
    o.cells.gap_band = starting_band(tca, position, torque, Estar);
  bool widened = false;
  for (int zone = 1;; ++zone)
    {
      LoadedPosition r = loaded_contact_in_zone(tca, position, torque, o, pinion, gear);
      r.zones          = zone;
      if (zone == 60)
        {
          std::ostringstream msg;
          msg << "loaded contact: at pinion angle " << position.pinion_angle << " rad and "
              << torque << " N m the cell zone did not settle after 60 zones (last gap band "
              << o.cells.gap_band * 1e6 << " um); check the load and the compliances";
          throw InputError(msg.str());
        }
      // Pairs standing further apart than the cells reach that the approach brings into
      // contact join (the pair's lever times the rigid approach exceeds its separation).
      const double approach = std::abs(r.eL - r.e0); // the pinion's rotation [rad]
      bool         joined   = false;
      for (const PairContact &c : position.pairs)
        if (c.found && c.separation > std::max(o.cells.pair_gap, o.cells.gap_band) &&
            approach * pinion_lever(c.position, c.normal_pinion) > c.separation)
          o.cells.pair_gap = std::max(o.cells.pair_gap, c.separation * (1 + 1e-9)), joined = true;
      if (joined)
        continue;
      if (torque == 0 || (!o.adapt_band && !r.zone_edge_reached))
        return r;
      const double edge_gap = contact_edge_gap(position, r, o.cells, Estar);
      if (r.zone_edge_reached && !o.adapt_band)
        {
          o.cells.gap_band *= 2; // the zone's width grows with sqrt of the band: cells of one size
          o.cells.cells_across = int(std::ceil(o.cells.cells_across * std::sqrt(2.0))) | 1;
        }
      else if (r.zone_edge_reached)
        o.cells.gap_band = std::max(4 * o.cells.gap_band, 4 * edge_gap), widened = true;
      else if (!widened && o.cells.gap_band > 9 * edge_gap)
        o.cells.gap_band = 4 * edge_gap; // the contact fills less than a third of the zone
      else
        return r;
    }
}

Eigen::MatrixXd
zone_compliance(const std::vector<ContactCell> &cells, const LoadedContactOptions &o,
                const StructuralCompliance &pinion, const StructuralCompliance &gear)
{
  const Eigen::Index n = Eigen::Index(cells.size());
  Eigen::MatrixXd    C = pinion.matrix(cells);
  C += gear.matrix(cells);
  const double Estar = contact_modulus(o.pinion_material, o.gear_material);
  if (o.half_space)
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        {
          const ContactCell &ci = cells[i], &cj = cells[j];
          if (ci.pair == cj.pair)
            C(j, i) +=
                rectangle_displacement(cj.s - ci.s, cj.t - ci.t, ci.ds / 2, ci.dt / 2, 1.0, Estar);
        }
  return C;
}

static LoadedPosition
loaded_contact_in_zone(const UnloadedTca &tca, const TcaPosition &position, double torque,
                       const LoadedContactOptions &o, const StructuralCompliance &pinion,
                       const StructuralCompliance &gear)
{
  std::vector<ContactCell> cells = loaded_cells(tca, position, o);
  const Eigen::MatrixXd    C     = zone_compliance(cells, o, pinion, gear);
  LoadedPosition           r     = solve_loaded_contact(tca, position, torque, std::move(cells), C);
  r.gap_band                     = o.cells.gap_band;
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
  Eigen::VectorXd gap(n), lever(n);
  for (Eigen::Index i = 0; i < n; ++i)
    gap[i] = cells[std::size_t(i)].gap, lever[i] = cells[std::size_t(i)].lever;
  ContactSolution s;
  if (torque == 0) // nothing moves; the cells' first touch only samples the gap
    s.force = Eigen::VectorXd::Zero(n);
  else // Maxwell-Betti: the exact compliance is symmetric; interpolation is not quite.
    s = solve_contact((compliance + compliance.transpose()) / 2, gap, lever, torque);
  return loaded_position(tca, position, torque, std::move(cells), s, 0);
}

LoadedPosition
loaded_position(const UnloadedTca &tca, const TcaPosition &position, double torque,
                std::vector<ContactCell> cells, const ContactSolution &s, double first_touch)
{
  const Eigen::Index n    = Eigen::Index(cells.size());
  const double       sign = tca.options_data().side == FlankSide::drive ? 1.0 : -1.0;
  LoadedPosition     out;
  out.pinion_angle = position.pinion_angle;
  out.e0           = position.transmission_error + sign * first_touch;
  out.torque       = torque;
  out.cells        = std::move(cells);
  out.pair_force.assign(position.pairs.size(), 0.0);
  if (torque == 0)
    {
      out.eL    = out.e0;
      out.force = Eigen::VectorXd::Zero(n);
      return out;
    }
  out.zone_edge_cell    = most_loaded(s.force, out.cells, &ContactCell::zone_edge);
  out.zone_edge_reached = out.zone_edge_cell >= 0;
  out.edge_cell         = most_loaded(s.force, out.cells, &ContactCell::flank_edge);
  for (Eigen::Index i = 0; i < n; ++i)
    if (s.force[i] > 0 && out.cells[i].flank_edge)
      out.edge_force += s.force[i];
  out.force        = s.force;
  out.active_cells = s.active;
  out.iterations   = s.iterations;
  out.eL           = position.transmission_error + sign * s.approach;
  for (Eigen::Index i = 0; i < n; ++i)
    out.pair_force[out.cells[i].pair] += s.force[i];
  out.normal_force = s.force.sum();
  // e_L - e_0 = the approach beyond the first touch: pinion rotation, gear held.
  const double approach = s.approach - first_touch;
  if (!(approach > 0))
    {
      std::ostringstream msg;
      msg << "loaded contact: at pinion angle " << position.pinion_angle << " rad and " << torque
          << " N m the loaded approach (" << approach
          << " rad) is not positive; the unloaded TE given lies beyond the loaded one";
      throw InputError(msg.str());
    }
  out.lever          = torque / out.normal_force;
  out.mesh_stiffness = out.normal_force / (out.lever * approach);
  return out;
}

namespace
{
/// What the tables need of one solved (torque, position) of a mesh cycle; sent to every
/// process.
struct Solved
{
  double              eL = 0, mesh_stiffness = 0, normal_force = 0, lever = 0;
  double              interior_peak = 0, edge_force = 0, edge_radius = 0, edge_z = 0, gap_band = 0;
  std::vector<double> pair_force;
  std::vector<std::array<double, 6>> cells; ///< pinion tooth, u1, v1, pressure, u2, v2
  std::string                        failure;
};

/// The loaded contact of job `job` of a mesh cycle (torque job / n at position job % n) into
/// s; false where it failed (InputError: its message in s.failure).
bool
solve_job(const UnloadedTca &t, int n, const std::vector<TcaPosition> &positions,
          const std::vector<double> &torques, const LoadedContactOptions &lo,
          const StructuralCompliance &sp, const StructuralCompliance &sg, std::size_t job,
          Solved &s)
{
  LoadedPosition r;
  try
    {
      r = loaded_contact(t, positions[job % std::size_t(n)], torques[job / std::size_t(n)], lo, sp,
                         sg);
    }
  catch (const InputError &e)
    {
      std::ostringstream msg;
      msg << "position " << job % std::size_t(n) << " (pinion angle "
          << positions[job % std::size_t(n)].pinion_angle << " rad): " << e.what();
      s.failure = msg.str();
      return false;
    }
  s.eL = r.eL, s.mesh_stiffness = r.mesh_stiffness;
  s.normal_force = r.normal_force, s.lever = r.lever;
  s.pair_force = r.pair_force;
  s.edge_force = r.edge_force, s.gap_band = r.gap_band;
  if (r.edge_cell >= 0)
    {
      const Vec3 &x = r.cells[std::size_t(r.edge_cell)].position;
      s.edge_radius = x.head<2>().norm(), s.edge_z = x.z();
    }
  for (std::size_t j = 0; j < r.cells.size(); ++j)
    {
      const ContactCell &cell     = r.cells[j];
      const double       pressure = r.force[Eigen::Index(j)] / (cell.ds * cell.dt);
      s.cells.push_back(
          {{double(cell.pinion_tooth), cell.u1, cell.v1, pressure, cell.u2, cell.v2}});
      if (!cell.flank_edge)
        s.interior_peak = std::max(s.interior_peak, pressure);
    }
  return true;
}

/// Every process's solved jobs and failures (its jobs: `mine`) to every process. Collective.
void
share_solved(MPI_Comm comm, const std::vector<std::size_t> &mine, std::vector<Solved> &solved)
{
  std::vector<std::pair<std::size_t, std::string>> failed;
  for (const std::size_t job : mine)
    if (!solved[job].failure.empty())
      failed.emplace_back(job, solved[job].failure);
  for (const auto &from : dealii::Utilities::MPI::all_gather(comm, failed))
    for (const auto &[job, why] : from)
      solved[job].failure = why;
  share_jobs(
      comm, mine,
      [&](std::size_t job, std::vector<double> &out) {
        const Solved &s = solved[job];
        out.insert(out.end(), {s.eL, s.mesh_stiffness, s.normal_force, s.lever, s.interior_peak,
                               s.edge_force, s.edge_radius, s.edge_z, s.gap_band,
                               double(s.pair_force.size()), double(s.cells.size())});
        out.insert(out.end(), s.pair_force.begin(), s.pair_force.end());
        for (const auto &cell : s.cells)
          out.insert(out.end(), cell.begin(), cell.end());
      },
      [&](std::size_t job, const std::vector<double> &in, std::size_t &at) {
        Solved &s = solved[job]; // (a failed job sends zeros)
        s.eL = in[at], s.mesh_stiffness = in[at + 1];
        s.normal_force = in[at + 2], s.lever = in[at + 3];
        s.interior_peak = in[at + 4], s.edge_force = in[at + 5];
        s.edge_radius = in[at + 6], s.edge_z = in[at + 7], s.gap_band = in[at + 8];
        const auto slots = std::size_t(in[at + 9]), cells = std::size_t(in[at + 10]);
        at += 11;
        s.pair_force.assign(in.begin() + long(at), in.begin() + long(at + slots));
        at += slots;
        s.cells.resize(cells);
        for (auto &cell : s.cells)
          for (double &x : cell)
            x = in[at++];
      });
}

/// The mesh cycle's tables from the solved jobs (torque-major).
void
fill_tables(MeshCycleContact &c, const std::vector<Solved> &solved,
            const std::vector<TcaPosition> &positions, int m, int n)
{
  const std::size_t jobs = std::size_t(m * n);
  c.torque_failure.assign(std::size_t(m), "");
  for (std::size_t job = 0; job < jobs; ++job)
    if (!solved[job].failure.empty() && c.torque_failure[job / std::size_t(n)].empty())
      c.torque_failure[job / std::size_t(n)] = solved[job].failure;
  for (const Solved &s : solved)
    c.cells = std::max(c.cells, s.cells.size());
  for (int i = 0; i < n; ++i)
    c.pinion_angle.push_back(positions[i].pinion_angle),
        c.unloaded_te.push_back(positions[i].transmission_error);
  for (const Solved &r : solved) // torque-major, as the jobs
    {
      c.loaded_te.push_back(r.eL), c.mesh_stiffness.push_back(r.mesh_stiffness);
      c.normal_force.push_back(r.normal_force), c.lever.push_back(r.lever);
      for (std::size_t s = 0; s < c.slots; ++s)
        c.pair_force.push_back(s < r.pair_force.size() ? r.pair_force[s] : 0.0);
      double p_max = 0;
      for (std::size_t j = 0; j < c.cells; ++j)
        {
          const std::array<double, 6>  unused{{-1.0, 0.0, 0.0, 0.0, 0.0, 0.0}};
          const std::array<double, 6> &cell = j < r.cells.size() ? r.cells[j] : unused;
          p_max                             = std::max(p_max, cell[3]);
          c.cell_pressure.insert(c.cell_pressure.end(), cell.begin(), cell.begin() + 4);
          c.cell_gear.insert(c.cell_gear.end(), cell.begin() + 4, cell.end());
        }
      c.peak_pressure.push_back(p_max);
      c.interior_peak_pressure.push_back(r.interior_peak);
      c.edge_load_share.push_back(r.normal_force > 0 ? r.edge_force / r.normal_force : 0.0);
      c.edge_position.insert(c.edge_position.end(), {r.edge_radius, r.edge_z});
      c.gap_band.push_back(r.gap_band);
    }
}
} // namespace

MeshCycleContact
loaded_contact_cycle(const UnloadedTca &t, int n, const std::vector<double> &torques,
                     const LoadedContactOptions &lo, const StructuralCompliance &sp,
                     const StructuralCompliance &sg, const std::function<void()> &step)
{
  const int m = int(torques.size());
  for (const double T : torques) // bad input: refused whole (a failing solve: per torque)
    if (!(T >= 0) || !std::isfinite(T))
      throw InputError("loaded contact: the pinion torques must be finite and >= 0 (got " +
                       std::to_string(T) + " N m)");
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
  // Every (torque, position) on its own: job j on process j modulo the processes, each
  // process's jobs on a few threads; what the tables need of each sent to every process.
  const MPI_Comm                 comm = lo.communicator;
  const std::size_t              jobs = std::size_t(m * n);
  const std::vector<std::size_t> mine = my_jobs(jobs, comm);
  std::vector<Solved>            solved(jobs);
  std::mutex                     progress;
  // a failure on any process is thrown on all (the first failed process's)
  collectively(comm, [&] {
    parallel_for(mine.size(), lo.threads, [&](std::size_t k) {
      const std::size_t job = mine[k];
      if (!solve_job(t, n, positions, torques, lo, sp, sg, job, solved[job]))
        return;
      if (step)
        {
          const std::lock_guard<std::mutex> lock(progress);
          step();
        }
    });
  });
  if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
    share_solved(comm, mine, solved);
  fill_tables(c, solved, positions, m, n);
  c.mean_pairs_in_contact = touching / n;
  return c;
}

MeshCycleContact
select_torques(const MeshCycleContact &c, const std::vector<std::size_t> &keep)
{
  MeshCycleContact  out = c;
  const std::size_t N = c.positions, S = c.slots, C = c.cells;
  auto pick = [&](std::vector<double> &to, const std::vector<double> &from, std::size_t per) {
    to.clear();
    for (const std::size_t k : keep)
      {
        if (k >= c.torques)
          throw InputError("select_torques: torque index " + std::to_string(k) + " of " +
                           std::to_string(c.torques));
        to.insert(to.end(), from.begin() + long(k * per), from.begin() + long((k + 1) * per));
      }
  };
  pick(out.loaded_te, c.loaded_te, N), pick(out.mesh_stiffness, c.mesh_stiffness, N);
  pick(out.normal_force, c.normal_force, N), pick(out.lever, c.lever, N);
  pick(out.pair_force, c.pair_force, N * S), pick(out.peak_pressure, c.peak_pressure, N);
  pick(out.cell_pressure, c.cell_pressure, N * C * 4), pick(out.cell_gear, c.cell_gear, N * C * 2);
  pick(out.interior_peak_pressure, c.interior_peak_pressure, N);
  pick(out.edge_load_share, c.edge_load_share, N), pick(out.edge_position, c.edge_position, 2 * N);
  pick(out.gap_band, c.gap_band, N);
  out.torque_failure.clear();
  for (const std::size_t k : keep)
    out.torque_failure.push_back(c.torque_failure[k]);
  out.torques = keep.size();
  return out;
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

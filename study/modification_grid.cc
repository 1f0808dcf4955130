#include "study/modification_grid.h"

#include "base/parallel.h"
#include "stiffness/collective.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace gearkit
{
namespace
{
const GridFields<ToothModifications> &
fields()
{
  static const GridFields<ToothModifications> f(
      "modification grid", {{"tip_relief", &ToothModifications::tip_relief},
                            {"tip_relief_length", &ToothModifications::tip_relief_length},
                            {"root_relief", &ToothModifications::root_relief},
                            {"root_relief_length", &ToothModifications::root_relief_length},
                            {"lead_crowning", &ToothModifications::lead_crowning},
                            {"end_relief", &ToothModifications::end_relief},
                            {"end_relief_length", &ToothModifications::end_relief_length},
                            {"profile_crowning", &ToothModifications::profile_crowning},
                            {"profile_slope", &ToothModifications::profile_slope},
                            {"helix_slope", &ToothModifications::helix_slope}});
  return f;
}

/// The vectors of a VariantCycle, in one order (packing and appending a torque), and the size
/// of each for M torques, N positions, S pair slots and H harmonics.
std::vector<std::vector<double> *>
per_torque(VariantCycle &c)
{
  return {&c.loaded_te,
          &c.mesh_stiffness,
          &c.normal_force,
          &c.pair_share,
          &c.peak_pressure,
          &c.interior_pressure,
          &c.edge_load_share,
          &c.te_peak_to_peak,
          &c.te_harmonics,
          &c.stiffness_mean,
          &c.stiffness_range,
          &c.max_pressure,
          &c.max_interior_pressure,
          &c.max_edge_share};
}
std::vector<std::size_t>
per_torque_sizes(std::size_t M, std::size_t N, std::size_t S, std::size_t H)
{
  return {M * N, M * N, M * N, M * N * S, M * N, M * N, M * N, M, M * H, M, M, M, M, M};
}

/// Appends the torques of `more` (the same variant, positions and slots) to `all`.
void
append_torques(VariantCycle &all, VariantCycle more)
{
  if (all.torques == 0)
    {
      all = std::move(more);
      return;
    }
  const std::vector<std::vector<double> *> to = per_torque(all), from = per_torque(more);
  for (std::size_t k = 0; k < to.size(); ++k)
    to[k]->insert(to[k]->end(), from[k]->begin(), from[k]->end());
  all.zone_edge.insert(all.zone_edge.end(), more.zone_edge.begin(), more.zone_edge.end());
  all.torques += more.torques;
}
} // namespace

const std::vector<std::string> &
modification_field_names()
{
  return fields().names();
}

double ToothModifications::       *
modification_field(const std::string &name)
{
  return fields().field(name);
}

ModificationGrid::ModificationGrid(PairVariant base_, GridMembers members,
                                   std::vector<ModificationAxis> axes, std::size_t most)
    : base(std::move(base_))
    , on(members)
    , grid(std::move(axes), modification_field_names(), "modification grid", most)
{
}

PairVariant
ModificationGrid::variant(std::size_t g) const
{
  PairVariant                    v  = base;
  const std::vector<std::size_t> at = index(g);
  for (std::size_t k = 0; k < grid.axes().size(); ++k)
    {
      const auto   field = modification_field(grid.axes()[k].name);
      const double value = grid.axes()[k].values[at[k]];
      if (on != GridMembers::gear)
        v.pinion.*field = value;
      if (on != GridMembers::pinion)
        v.gear.*field = value;
    }
  return v;
}

std::vector<VariantCycle>
microgeometry_map(std::shared_ptr<const InvoluteMemberFlanks> pinion,
                  std::shared_ptr<const InvoluteMemberFlanks> gear, const Assembly &assembly,
                  const TcaOptions &tca, const LoadedContactOptions &contact,
                  const StructuralCompliance &pinion_compliance,
                  const StructuralCompliance &gear_compliance, const MeshCycleStudyOptions &options,
                  const ModificationGrid &grid, MPI_Comm comm, const std::function<void()> &step)
{
  return evaluate_variants(
      std::move(pinion), std::move(gear), assembly, tca, contact, pinion_compliance,
      gear_compliance, options, grid.size(), [&grid](std::size_t g) { return grid.variant(g); },
      comm, step);
}

std::vector<VariantCycle>
evaluate_variants(std::shared_ptr<const InvoluteMemberFlanks> pinion,
                  std::shared_ptr<const InvoluteMemberFlanks> gear, const Assembly &assembly,
                  const TcaOptions &tca, const LoadedContactOptions &contact,
                  const StructuralCompliance &pinion_compliance,
                  const StructuralCompliance &gear_compliance, const MeshCycleStudyOptions &options,
                  std::size_t G, const std::function<PairVariant(std::size_t)> &variant,
                  MPI_Comm comm, const std::function<void()> &step, const PairVariant *warm_from)
{
  const std::vector<std::size_t> mine = my_jobs(G, comm);
  std::vector<VariantCycle>      out(G);
  std::mutex                     progress;
  for (const double torque : options.torques)
    {
      MeshCycleStudyOptions o = options;
      o.torques               = {torque};
      std::vector<VariantCycle> at(G);
      collectively(comm, [&] {
        MeshCycleStudy study(pinion, gear, assembly, tca, contact, pinion_compliance,
                             gear_compliance, o);
        if (warm_from)
          study.warm_start_from(*warm_from);
        parallel_for(mine.size(), o.threads, [&](std::size_t k) {
          at[mine[k]] = study.evaluate(variant(mine[k]), 1);
          if (step)
            {
              const std::lock_guard<std::mutex> lock(progress);
              step();
            }
        });
      });
      for (const std::size_t g : mine)
        append_torques(out[g], std::move(at[g]));
    }
  // Every process's variants to every process: the tables of all torques as numbers.
  share_jobs(
      comm, mine,
      [&](std::size_t g, std::vector<double> &data) {
        VariantCycle &c = out[g];
        data.insert(data.end(),
                    {double(c.torques), double(c.positions), double(c.slots), double(c.harmonics)});
        data.insert(data.end(), c.unloaded_te.begin(), c.unloaded_te.end());
        for (const std::vector<double> *v : per_torque(c))
          data.insert(data.end(), v->begin(), v->end());
        for (const char e : c.zone_edge)
          data.push_back(e);
      },
      [&](std::size_t g, const std::vector<double> &data, std::size_t &at) {
        VariantCycle &c = out[g];
        c.torques = std::size_t(data[at]), c.positions = std::size_t(data[at + 1]);
        c.slots = std::size_t(data[at + 2]), c.harmonics = int(data[at + 3]);
        at += 4;
        const std::size_t M = c.torques, N = c.positions;
        const auto        take = [&](std::vector<double> &v, std::size_t n) {
          v.assign(data.begin() + long(at), data.begin() + long(at + n));
          at += n;
        };
        take(c.unloaded_te, N);
        const std::vector<std::size_t> sizes =
            per_torque_sizes(M, N, c.slots, std::size_t(c.harmonics));
        const std::vector<std::vector<double> *> v = per_torque(c);
        if (sizes.size() != v.size())
          throw std::logic_error("modification grid: per_torque and per_torque_sizes differ");
        for (std::size_t k = 0; k < v.size(); ++k)
          take(*v[k], sizes[k]);
        for (std::size_t m = 0; m < M; ++m)
          c.zone_edge.push_back(char(data[at++]));
      });
  return out;
}
} // namespace gearkit

#include "driver/pair_contact.h"

#include "driver/results_compliance.h"
#include "driver/stages.h"
#include "stiffness/member_compliance.h"

#include <algorithm>
#include <tuple>

namespace gearkit
{
double
member_module(const PairScene &pair)
{
  return pair.type == PairType::spiral_bevel ? bevel_geometry(pair.bevel).mean_normal_module
                                             : pair.pinion.normal_module;
}

FeScene
pair_fe(const Scene &scene, const PairScene &pair)
{
  FeScene fe = scene.fe.at(pair.name);
  if (fe.n_v == 0)
    fe.n_v = face_grid_points(pair.type == PairType::spiral_bevel
                                  ? pair.bevel.face_width
                                  : std::min(pair.pinion.face_width, pair.gear.face_width),
                              member_module(pair));
  return fe;
}

FlankCompliance
read_table(const MemberFlanks &flanks, const H5Group &tables, const char *member, const FeScene &fe,
           const LoadedScene &lc, FlankSide side)
{
  FlankGridSpec spec;
  spec.follow_load = lc.follow_load;
  spec.side        = side;
  spec.n_u = fe.n_u, spec.n_v = fe.n_v;
  spec.graded = fe.graded_grid;
  return compliance_table(flanks, read_compliance(tables.group(member)), spec);
}

LoadedPair
loaded_pair(const Scene &scene, const PairScene &pair, const H5Group &flanks,
            const H5Group &compliance)
{
  const FeScene      fe      = pair_fe(scene, pair);
  const LoadedScene &lc      = scene.loaded.at(pair.name);
  const TcaScene    &tca     = scene.tca.at(pair.name);
  const FlankSide    side    = tca.options.side;
  PairMembers        members = theoretical_members(pair, tca, flanks);
  const auto         cp      = std::make_shared<const FlankCompliance>(
      read_table(*members.pinion, compliance, "pinion", fe, lc, side));
  const auto cg = std::make_shared<const FlankCompliance>(
      read_table(*members.gear, compliance, "gear", fe, lc, side));
  LoadedContactOptions lo;
  lo.cells           = lc.cells;
  lo.pinion_material = lo.gear_material = fe.material;
  lo.covered        = [cp, cg](int p, int g) { return cp->covers(p) && cg->covers(g); };
  lo.threads        = cores_per_process();
  lo.communicator   = MPI_COMM_WORLD;
  const auto theory = std::make_shared<const UnloadedTca>(members.pinion, members.gear,
                                                          members.assembly, tca.options);
  return {std::move(members),          cp, cg, theory, lo, table_compliance(*cp, true),
          table_compliance(*cg, false)};
}

LoadedContactOptions
measured_contact_options(const LoadedPair &pair, const MemberFlanks &measured_pinion,
                         const MemberFlanks &measured_gear, FlankSide side)
{
  LoadedContactOptions lo = pair.options;
  const auto           tp = pair.members.pinion, tg = pair.members.gear;
  lo.table_parameters = [tp, tg, &measured_pinion, &measured_gear, side](ContactCell &c) {
    std::tie(c.table_u1, c.table_v1) = tp->rotational_parameters(
        measured_pinion.flank(c.pinion_tooth, side).evaluate(c.u1, c.v1).position);
    std::tie(c.table_u2, c.table_v2) = tg->rotational_parameters(
        measured_gear.flank(c.gear_tooth, side).evaluate(c.u2, c.v2).position);
  };
  lo.cells.zone_from_gaps = true;
  return lo;
}
} // namespace gearkit

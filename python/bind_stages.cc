// The Python module's library calls on a scene's pair that start from its stages' results, run
// or reused through the stage cache as the executable runs them: the pair's flanks, its measured
// flanks, and the loaded contact at any torque on the compliance tables the compliance stage
// computed once (driver/pair_contact.h, as the stiffness stage builds them).
#include "driver/driver.h"
#include "driver/pair_contact.h"
#include "driver/pair_tca.h"
#include "driver/stages.h"
#include "python/bindings.h"

#include <map>
#include <memory>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

namespace gearkit::python
{
namespace
{
/// The stages `stages`' results for a scene, run or reused from the cache, with the log in
/// Python's stdout.
std::unique_ptr<StageUpstream>
stage_results(const Scene &scene, const std::string &output_root,
              const std::vector<std::string> &stages)
{
  return logged<std::unique_ptr<StageUpstream>>([&](std::ostream &out, std::ostream &) {
    return std::make_unique<StageUpstream>(scene, stages, output_root, out);
  });
}

/// The pair's group in a stage's results.
H5Group
pair_group(const StageUpstream &results, const std::string &stage, const std::string &pair)
{
  return results.upstream().at(stage)->group(pair);
}

/// A pair on its compliance tables, with the scene it came from (for its defaults).
struct PythonLoadedPair
{
  LoadedPair  pair;
  int         positions = 0; ///< the scene's positions per mesh cycle
  TcaOptions  tca;           ///< the scene's TCA options (side, searches)
  std::string name;
};

py::dict
contact_dict(const MeshCycleContact &c)
{
  const auto M = py::ssize_t(c.torques), N = py::ssize_t(c.positions), S = py::ssize_t(c.slots),
             C = py::ssize_t(c.cells);
  auto shaped  = [](const auto &v, std::vector<py::ssize_t> shape) {
    return array(v).reshape(shape);
  };
  return py::dict(py::arg("pinion_angle")                = array(c.pinion_angle),
                  py::arg("transmission_error_unloaded") = array(c.unloaded_te),
                  py::arg("transmission_error_loaded")   = shaped(c.loaded_te, {M, N}),
                  py::arg("mesh_stiffness")              = shaped(c.mesh_stiffness, {M, N}),
                  py::arg("normal_force")                = shaped(c.normal_force, {M, N}),
                  py::arg("lever")                       = shaped(c.lever, {M, N}),
                  py::arg("pair_force")                  = shaped(c.pair_force, {M, N, S}),
                  py::arg("pinion_tooth")                = shaped(c.slot_tooth, {N, S}),
                  py::arg("peak_pressure")               = shaped(c.peak_pressure, {M, N}),
                  py::arg("interior_peak_pressure")      = shaped(c.interior_peak_pressure, {M, N}),
                  py::arg("edge_load_share")             = shaped(c.edge_load_share, {M, N}),
                  py::arg("edge_position")               = shaped(c.edge_position, {M, N, 2}),
                  py::arg("gap_band")                    = shaped(c.gap_band, {M, N}),
                  py::arg("contact_cells")               = shaped(c.cell_pressure, {M, N, C, 4}),
                  py::arg("mean_pairs_in_contact")       = c.mean_pairs_in_contact);
}

py::tuple
members_tuple(const PairMembers &m)
{
  return flanks_tuple(m.pinion, m.gear, m.assembly);
}
} // namespace

void
bind_stages(py::module_ &m)
{
  m.def(
      "pair_members",
      [](const Scene &scene, const std::string &pair, const std::string &root) {
        const PairScene &p = scene.pair(pair);
        const auto       r = stage_results(scene, root, {"flanks"});
        return members_tuple(
            theoretical_members(p, scene.tca.at(pair), pair_group(*r, "flanks", pair)));
      },
      py::arg("scene"), py::arg("pair"), py::arg("output_root"),
      "(pinion flanks, gear flanks, assembly) of the scene's pair as the stages build them");
  m.def(
      "measured_members",
      [](const Scene &scene, const std::string &pair, const std::string &root) {
        scene.pair(pair);
        if (!scene.measured.count(pair) || scene.measured.at(pair).source == MeasuredSource::none)
          throw InputError(scene.file + ": pair " + pair +
                           " has no measured flanks (section Measured flanks/" + pair + ")");
        const auto    r = stage_results(scene, root, {"measured"});
        const H5Group g = pair_group(*r, "measured", pair);
        return py::make_tuple(read_measured(g.group("pinion"), "pinion"),
                              read_measured(g.group("gear"), "gear"));
      },
      py::arg("scene"), py::arg("pair"), py::arg("output_root"),
      "(pinion, gear) measured flanks of the scene's pair as the measured stage stored them");

  py::class_<FlankCompliance, std::shared_ptr<FlankCompliance>>(
      m, "FlankCompliance",
      "A member's compliance table: the approach of grid points per unit normal load [m/N]")
      .def_property_readonly("points",
                             [](const FlankCompliance &c) {
                               std::vector<Vec3> x;
                               for (const FlankCompliance::Point &p : c.points())
                                 x.push_back(p.position);
                               return vec3_array(x);
                             })
      .def_property_readonly("teeth",
                             [](const FlankCompliance &c) {
                               std::vector<int> t;
                               for (const FlankCompliance::Point &p : c.points())
                                 t.push_back(p.tooth);
                               return array(t);
                             })
      .def_property_readonly("load_points", &FlankCompliance::load_points)
      .def_property_readonly("grid_teeth", &FlankCompliance::grid_teeth)
      .def_property_readonly(
          "matrix", [](const FlankCompliance &c) -> Eigen::MatrixXd { return c.matrix(); },
          "S(j, k): the approach at point j per unit load on load point k [m/N]")
      .def("covers", &FlankCompliance::covers, py::arg("tooth"))
      .def("__call__", &FlankCompliance::operator(), py::arg("tooth_i"), py::arg("u_i"),
           py::arg("v_i"), py::arg("tooth_j"), py::arg("u_j"), py::arg("v_j"),
           "The approach at (tooth_j, u_j, v_j) per unit normal load at (tooth_i, u_i, v_i)");

  py::class_<PythonLoadedPair>(m, "LoadedPair",
                               "A scene's pair on the compliance tables of its compliance stage")
      .def_readonly("name", &PythonLoadedPair::name)
      .def_readonly("positions", &PythonLoadedPair::positions)
      .def_property_readonly(
          "members", [](const PythonLoadedPair &p) { return members_tuple(p.pair.members); })
      .def_property_readonly("pinion_table",
                             [](const PythonLoadedPair &p) {
                               return std::const_pointer_cast<FlankCompliance>(p.pair.pinion_table);
                             })
      .def_property_readonly("gear_table",
                             [](const PythonLoadedPair &p) {
                               return std::const_pointer_cast<FlankCompliance>(p.pair.gear_table);
                             })
      .def(
          "loaded_contact",
          [](const PythonLoadedPair &p, const std::vector<double> &torques, int positions,
             const std::shared_ptr<MemberFlanks> &pinion_flanks,
             const std::shared_ptr<MemberFlanks> &gear_flanks) {
            if (torques.empty())
              throw InputError("loaded_contact: torques is empty; expected at least one [N m]");
            for (const double t : torques)
              if (!(t > 0 && std::isfinite(t)))
                throw InputError("loaded_contact: torque " + std::to_string(t) +
                                 " N m is not allowed; expected positive finite torques [N m] "
                                 "on the pinion");
            if (positions == 0)
              positions = p.positions;
            if (positions < 1)
              throw InputError("loaded_contact: positions = " + std::to_string(positions) +
                               "; expected at least 1 per mesh cycle");
            if (bool(pinion_flanks) != bool(gear_flanks))
              throw InputError("loaded_contact: pinion_flanks and gear_flanks go together");
            if (pinion_flanks)
              for (const auto &[flanks, theory, member] :
                   {std::tuple{pinion_flanks.get(), p.pair.members.pinion.get(), "pinion"},
                    std::tuple{gear_flanks.get(), p.pair.members.gear.get(), "gear"}})
                if (flanks->teeth() != theory->teeth())
                  throw InputError("loaded_contact: the " + std::string(member) + " flanks have " +
                                   std::to_string(flanks->teeth()) + " teeth, the " + member +
                                   " of pair " + p.name + " " + std::to_string(theory->teeth()) +
                                   "; expected flanks of the same member (measured or modified)");
            const MeshCycleContact all = interruptible<MeshCycleContact>([&] {
              const LoadedPair &lp = p.pair;
              Progress          progress("loaded contact " + p.name,
                                         torques.size() * std::size_t(positions));
              const auto        step = [&] { progress.advance(); };
              if (!pinion_flanks)
                return loaded_contact_cycle(*lp.theory, positions, torques, lp.options,
                                            lp.pinion_compliance, lp.gear_compliance, step);
              // other flanks (measured, modified) on the same compliance tables
              const UnloadedTca other(pinion_flanks, gear_flanks, lp.members.assembly, p.tca);
              return loaded_contact_cycle(
                  other, positions, torques,
                  measured_contact_options(lp, *pinion_flanks, *gear_flanks, p.tca.side),
                  lp.pinion_compliance, lp.gear_compliance, step);
            });
            // a torque some position of which failed is refused alone, as the stage does
            std::vector<std::size_t> keep;
            std::vector<double>      kept, refused;
            std::string              why;
            for (std::size_t k = 0; k < torques.size(); ++k)
              if (all.torque_failure[k].empty())
                keep.push_back(k), kept.push_back(torques[k]);
              else
                refused.push_back(torques[k]),
                    why += plausible_number(torques[k]) + " N m: " + all.torque_failure[k] + "\n";
            if (keep.empty())
              throw InputError("loaded contact of " + p.name + ": no torque could be solved; " +
                               why);
            py::dict d          = contact_dict(select_torques(all, keep));
            d["torque"]         = array(kept);
            d["refused_torque"] = array(refused);
            d["refused"]        = why;
            return d;
          },
          py::arg("torques"), py::arg("positions") = 0, py::arg("pinion_flanks") = nullptr,
          py::arg("gear_flanks") = nullptr,
          "The loaded contact over a mesh cycle at the pinion torques [N m] (positions per mesh "
          "cycle: 0 = the scene's); on other flanks (measured or modified) when given, each "
          "cell reading the theoretical tables at its own place");
  m.def(
      "loaded_pair",
      [](const Scene &scene, const std::string &pair, const std::string &root) {
        const PairScene &p = scene.pair(pair);
        const auto       r = stage_results(scene, root, {"flanks", "compliance"});
        cores_per_process();
        return PythonLoadedPair{loaded_pair(scene, p, pair_group(*r, "flanks", pair),
                                            pair_group(*r, "compliance", pair)),
                                scene.loaded.at(pair).positions, scene.tca.at(pair).options, pair};
      },
      py::arg("scene"), py::arg("pair"), py::arg("output_root"),
      "The scene's pair on its compliance tables (the compliance stage run or reused)");
}
} // namespace gearkit::python

// The Python module's library level for geometry and the unloaded TCA, on library types (SI
// units): involute gears and their pair, member flanks, assemblies, the TCA as the ste stage
// runs it.
#include "driver/pair_tca.h"
#include "geometry/involute_gear.h"
#include "geometry/member_flanks.h"
#include "python/bindings.h"
#include "tca/assembly.h"
#include "tca/unloaded_tca.h"

#include <pybind11/stl.h>

namespace gearkit::python
{
namespace
{
using GearPointer = std::shared_ptr<InvoluteGear>; // pybind11 holds no pointer to const

/// The unloaded TCA of an involute pair as the ste stage runs it (pair_tca: positions_per_mesh x
/// mesh_cycles positions from the options' start angle), as tables.
struct TcaTables
{
  std::vector<double> pinion_angle, gear_angle, transmission_error;
  std::vector<int>    touching, leading;
};

TcaTables
involute_tca(const GearPointer &pinion, const GearPointer &gear, double centre_distance,
             const TcaOptions &o, const Misalignment &m)
{
  TcaScene scene;
  scene.options = o;
  Progress        progress("unloaded TCA: position",
                           std::size_t(std::max(o.positions_per_mesh * o.mesh_cycles, 1)));
  const TcaResult r = pair_tca(
      std::make_shared<InvoluteMemberFlanks>(pinion), std::make_shared<InvoluteMemberFlanks>(gear),
      Assembly(centre_distance, gear->teeth(), m), scene, false, [&] { progress.advance(); });
  TcaTables t;
  for (const TcaPosition &p : r.positions)
    {
      t.pinion_angle.push_back(p.pinion_angle);
      t.gear_angle.push_back(p.gear_angle);
      t.transmission_error.push_back(p.transmission_error);
      t.touching.push_back(p.touching);
      t.leading.push_back(p.leading);
    }
  return t;
}
} // namespace

void
bind_geometry_tca(py::module_ &m)
{
  py::class_<InvoluteGearData>(m, "InvoluteGearData",
                               "An involute gear's data (geometry/involute_gear.h), SI units")
      .def(py::init<>())
      .def_readwrite("teeth", &InvoluteGearData::teeth)
      .def_readwrite("normal_module", &InvoluteGearData::normal_module)
      .def_readwrite("normal_pressure_angle", &InvoluteGearData::normal_pressure_angle)
      .def_readwrite("helix_angle", &InvoluteGearData::helix_angle)
      .def_readwrite("profile_shift", &InvoluteGearData::profile_shift)
      .def_readwrite("face_width", &InvoluteGearData::face_width)
      .def_readwrite("addendum_factor", &InvoluteGearData::addendum_factor)
      .def_readwrite("dedendum_factor", &InvoluteGearData::dedendum_factor)
      .def_readwrite("root_radius_factor", &InvoluteGearData::root_radius_factor)
      .def_readwrite("bore_diameter", &InvoluteGearData::bore_diameter)
      .def_readwrite("density", &InvoluteGearData::density)
      .def_readwrite("active_profile_start_radius", &InvoluteGearData::active_profile_start_radius);
  py::class_<InvoluteGear, GearPointer>(m, "InvoluteGear",
                                        "An involute gear (ISO 21771 quantities), SI units")
      .def_static(
          "create",
          [](const InvoluteGearData &d) {
            return std::const_pointer_cast<InvoluteGear>(InvoluteGear::create(d));
          },
          "Checks the data (ValueError naming the parameter) and builds the gear")
      .def_property_readonly("data", &InvoluteGear::data)
      .def_property_readonly("teeth", &InvoluteGear::teeth)
      .def_readonly("reference_radius", &InvoluteGear::reference_radius)
      .def_readonly("base_radius", &InvoluteGear::base_radius)
      .def_readonly("tip_radius", &InvoluteGear::tip_radius)
      .def_readonly("root_radius", &InvoluteGear::root_radius)
      .def_readonly("form_radius", &InvoluteGear::form_radius)
      .def_readonly("transverse_base_pitch", &InvoluteGear::transverse_base_pitch)
      .def("tooth_thickness", &InvoluteGear::tooth_thickness, py::arg("radius"));
  m.def(
      "create_pair",
      [](const InvoluteGearData &p, const InvoluteGearData &g, double a) {
        const auto [pinion, gear] = create_pair(p, g, a);
        return py::make_tuple(std::const_pointer_cast<InvoluteGear>(pinion),
                              std::const_pointer_cast<InvoluteGear>(gear));
      },
      py::arg("pinion"), py::arg("gear"), py::arg("centre_distance") = 0.0,
      "Pinion and gear of an external pair, each's start of active profile from its mate");
  m.def(
      "working_centre_distance",
      [](const GearPointer &p, const GearPointer &g) { return working_centre_distance(*p, *g); },
      "The centre distance of zero backlash [m]");
  py::class_<Misalignment>(m, "Misalignment", "Misalignments of the gear (tca/assembly.h), SI")
      .def(py::init<>())
      .def_readwrite("offset", &Misalignment::offset)
      .def_readwrite("centre_distance_error", &Misalignment::centre_distance_error)
      .def_readwrite("crossing_angle", &Misalignment::crossing_angle)
      .def_readwrite("intersecting_angle", &Misalignment::intersecting_angle)
      .def_readwrite("pinion_axial_shift", &Misalignment::pinion_axial_shift)
      .def_readwrite("gear_axial_shift", &Misalignment::gear_axial_shift);
  py::class_<TcaOptions>(m, "TcaOptions", "Options of the unloaded TCA (tca/unloaded_tca.h)")
      .def(py::init<>())
      .def_property(
          "side",
          [](const TcaOptions &o) { return o.side == FlankSide::drive ? "drive" : "coast"; },
          [](TcaOptions &o, const std::string &s) {
            if (s != "drive" && s != "coast")
              throw InputError("TcaOptions.side = '" + s +
                               "' is not allowed; expected drive or coast");
            o.side = s == "drive" ? FlankSide::drive : FlankSide::coast;
          })
      .def_readwrite("positions_per_mesh", &TcaOptions::positions_per_mesh)
      .def_readwrite("mesh_cycles", &TcaOptions::mesh_cycles)
      .def_readwrite("start_angle", &TcaOptions::start_angle)
      .def_readwrite("profile_samples", &TcaOptions::profile_samples)
      .def_readwrite("face_samples", &TcaOptions::face_samples)
      .def_readwrite("contact_tolerance", &TcaOptions::contact_tolerance)
      .def_readwrite("robust_search", &TcaOptions::robust_search);
  m.def(
      "unloaded_tca",
      [](const GearPointer &pinion, const GearPointer &gear, double centre_distance,
         const TcaOptions &options, const Misalignment &misalignment) {
        if (!(options.positions_per_mesh > 0 && options.mesh_cycles > 0))
          throw InputError("TcaOptions: positions_per_mesh and mesh_cycles must be positive");
        const TcaTables t = interruptible<TcaTables>(
            [&] { return involute_tca(pinion, gear, centre_distance, options, misalignment); });
        return py::dict(py::arg("pinion_angle")       = array(t.pinion_angle),
                        py::arg("gear_angle")         = array(t.gear_angle),
                        py::arg("transmission_error") = array(t.transmission_error),
                        py::arg("pairs_in_contact")   = array(t.touching),
                        py::arg("leading")            = array(t.leading));
      },
      py::arg("pinion"), py::arg("gear"), py::arg("centre_distance"),
      py::arg("options") = TcaOptions(), py::arg("misalignment") = Misalignment(),
      "The unloaded TCA of an involute pair: e_0 [rad, pinion] per position, as the ste stage");
}
} // namespace gearkit::python

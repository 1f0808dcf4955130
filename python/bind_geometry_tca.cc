// The Python module's library level for geometry and the unloaded TCA, on library types (SI
// units): involute gears and their pair, member flanks, assemblies, the TCA as the ste stage
// runs it.
#include "driver/pair_tca.h"
#include "driver/scene.h"
#include "geometry/bevel_gear.h"
#include "geometry/involute_gear.h"
#include "geometry/measured_flank.h"
#include "geometry/member_flanks.h"
#include "python/bindings.h"
#include "tca/assembly.h"
#include "tca/bevel_synthesis.h"
#include "tca/unloaded_tca.h"

#include <cmath>
#include <pybind11/stl.h>

namespace gearkit::python
{
namespace
{
using GearPointer = std::shared_ptr<InvoluteGear>; // pybind11 holds no pointer to const

using FlanksPointer = std::shared_ptr<MemberFlanks>; // the same

/// The unloaded TCA of any pair as the ste stage runs it (pair_tca: positions_per_mesh x
/// mesh_cycles positions from the options' start angle; on measured flanks the fast
/// discrete-point analysis), as NumPy tables.
py::dict
tca_tables(const MemberPointer &pinion, const MemberPointer &gear, const Assembly &assembly,
           const TcaOptions &o)
{
  if (!(o.positions_per_mesh > 0 && o.mesh_cycles > 0))
    throw InputError("TcaOptions: positions_per_mesh = " + std::to_string(o.positions_per_mesh) +
                     ", mesh_cycles = " + std::to_string(o.mesh_cycles) +
                     "; expected both positive");
  TcaScene scene;
  scene.options         = o;
  const TcaResult     r = interruptible<TcaResult>([&] {
    Progress progress("unloaded TCA: position", std::size_t(o.positions_per_mesh * o.mesh_cycles));
    return pair_tca(pinion, gear, assembly, scene, false, [&] { progress.advance(); });
  });
  std::vector<double> phi, psi, te;
  std::vector<int>    touching, leading;
  for (const TcaPosition &p : r.positions)
    {
      phi.push_back(p.pinion_angle), psi.push_back(p.gear_angle);
      te.push_back(p.transmission_error);
      touching.push_back(p.touching), leading.push_back(p.leading);
    }
  return py::dict(py::arg("pinion_angle") = array(phi), py::arg("gear_angle") = array(psi),
                  py::arg("transmission_error") = array(te),
                  py::arg("pairs_in_contact")   = array(touching),
                  py::arg("leading")            = array(leading));
}

/// The flank of a member's tooth and side, checked (ValueError naming what exists).
const Flank &
flank_of(const MemberFlanks &f, int tooth, const std::string &side)
{
  if (tooth < 0 || tooth >= f.teeth())
    throw InputError("tooth = " + std::to_string(tooth) + " is out of range; expected 0 .. " +
                     std::to_string(f.teeth() - 1));
  return f.flank(tooth, flank_side(side, "side"));
}

py::dict
grid_dict(const FlankGrid &g)
{
  return py::dict(py::arg("u") = array(g.u), py::arg("v") = array(g.v),
                  py::arg("positions") = vec3_array(g.positions, {g.n_u, g.n_v}),
                  py::arg("normals")   = vec3_array(g.normals, {g.n_u, g.n_v}));
}

/// The flanks, assemblies and CMM point sets.
void
bind_flanks(py::module_ &m)
{
  py::class_<Assembly>(m, "Assembly", "Both members placed for contact (tca/assembly.h), SI")
      .def(py::init<double, int, const Misalignment &>(), py::arg("centre_distance"),
           py::arg("gear_teeth"), py::arg("misalignment") = Misalignment(),
           "Parallel axes at the centre distance [m]")
      .def_static("bevel", &Assembly::bevel, py::arg("shaft_angle"), py::arg("pinion_pitch_angle"),
                  py::arg("gear_teeth"), py::arg("misalignment") = Misalignment(),
                  "Intersecting axes (bevel pair), angles in radians")
      .def_property_readonly("gear_centre", [](const Assembly &a) { return vec3(a.gear_centre()); })
      .def_property_readonly("gear_axis", [](const Assembly &a) { return vec3(a.gear_axis()); });

  py::class_<MemberFlanks, FlanksPointer>(
      m, "Flanks",
      "The flank surfaces of a member's teeth (theoretical or interpolated from measured points), "
      "each r(u, v) in the member frame (axis z), metres")
      .def_static(
          "involute",
          [](const std::shared_ptr<InvoluteGear> &g) -> FlanksPointer {
            return std::make_shared<InvoluteMemberFlanks>(g);
          },
          py::arg("gear"), "Every flank of an involute gear")
      .def_static(
          "measured",
          [](const MeasuredMember &member) -> FlanksPointer {
            return std::make_shared<MeasuredMemberFlanks>(member);
          },
          py::arg("member"),
          "A member's measured flanks, interpolated; unmeasured teeth take the nearest measured "
          "tooth's flank turned into place")
      .def_property_readonly("teeth", &MemberFlanks::teeth)
      .def(
          "has",
          [](const MemberFlanks &f, int tooth, const std::string &side) {
            return f.has(tooth, flank_side(side, "side"));
          },
          py::arg("tooth"), py::arg("side") = "drive")
      .def(
          "domain",
          [](const MemberFlanks &f, int tooth, const std::string &side) {
            const FlankDomain d = flank_of(f, tooth, side).domain();
            return py::make_tuple(d.u_min, d.u_max, d.v_min, d.v_max);
          },
          py::arg("tooth"), py::arg("side") = "drive", "(u_min, u_max, v_min, v_max)")
      .def(
          "evaluate",
          [](const MemberFlanks &f, int tooth, const std::string &side, double u, double v) {
            const Flank      &flank = flank_of(f, tooth, side);
            const FlankDomain d     = flank.domain();
            if (!(u >= d.u_min && u <= d.u_max && v >= d.v_min && v <= d.v_max))
              throw InputError("evaluate: (u, v) = (" + std::to_string(u) + ", " +
                               std::to_string(v) + ") lies outside the flank's domain u in [" +
                               std::to_string(d.u_min) + ", " + std::to_string(d.u_max) +
                               "], v in [" + std::to_string(d.v_min) + ", " +
                               std::to_string(d.v_max) + "] (Flanks.domain)");
            const FlankPoint p = flank.evaluate(u, v);
            return py::make_tuple(vec3(p.position), vec3(p.normal));
          },
          py::arg("tooth"), py::arg("side"), py::arg("u"), py::arg("v"),
          "(position, unit outward normal) at the flank parameters (u, v)")
      .def(
          "sample",
          [](const MemberFlanks &f, int tooth, const std::string &side, int n_u, int n_v,
             double margin) {
            if (n_u < 2 || n_v < 2 || !(margin >= 0 && margin < 0.5))
              throw InputError("sample: n_u = " + std::to_string(n_u) + ", n_v = " +
                               std::to_string(n_v) + ", margin = " + std::to_string(margin) +
                               "; expected n_u, n_v >= 2 and 0 <= margin < 0.5");
            return grid_dict(sample_flank(flank_of(f, tooth, side), n_u, n_v, margin));
          },
          py::arg("tooth"), py::arg("side") = "drive", py::arg("n_u") = 9, py::arg("n_v") = 9,
          py::arg("margin") = 0.0,
          "The flank on a uniform n_u x n_v grid of its domain: u, v, positions and normals "
          "(n_u, n_v, 3)");

  py::class_<MeasuredFlank>(m, "MeasuredFlank",
                            "One measured flank: points on an n_profile x n_face grid (metres)")
      .def(py::init([](int tooth, const std::string &side, const py::array_t<double> &points,
                       const py::object &normals) {
             MeasuredFlank f;
             f.tooth = tooth;
             f.side  = flank_side(side, "MeasuredFlank side");
             if (points.ndim() != 3 || points.shape(2) != 3)
               throw InputError("MeasuredFlank points: an array of shape (n_profile, n_face, "
                                "3) expected (root to tip, one face end to the other; metres)");
             f.n_profile = int(points.shape(0)), f.n_face = int(points.shape(1));
             f.points = vec3_list(points, "MeasuredFlank points");
             if (!normals.is_none())
               {
                 f.normals =
                     vec3_list(normals.cast<py::array_t<double>>(), "MeasuredFlank normals");
                 if (f.normals.size() != f.points.size())
                   throw InputError("MeasuredFlank normals: one per point expected (" +
                                    std::to_string(f.points.size()) + "), got " +
                                    std::to_string(f.normals.size()));
               }
             return f;
           }),
           py::arg("tooth"), py::arg("side"), py::arg("points"), py::arg("normals") = py::none())
      .def_readonly("tooth", &MeasuredFlank::tooth)
      .def_property_readonly("side", [](const MeasuredFlank &f) { return to_string(f.side); })
      .def_property_readonly("points",
                             [](const MeasuredFlank &f) {
                               return vec3_array(f.points, {f.n_profile, f.n_face});
                             })
      .def_property_readonly("normals", [](const MeasuredFlank &f) -> py::object {
        if (f.normals.empty())
          return py::none();
        return vec3_array(f.normals, {f.n_profile, f.n_face});
      });
  py::class_<MeasuredMember>(m, "MeasuredMember", "The measured flanks of one member")
      .def(py::init(
               [](const std::string &member, int teeth, const std::vector<MeasuredFlank> &flanks) {
                 MeasuredMember mm{member, teeth, flanks};
                 check_member(mm, "MeasuredMember " + member);
                 return mm;
               }),
           py::arg("member"), py::arg("teeth"), py::arg("flanks"))
      .def_readonly("member", &MeasuredMember::member)
      .def_readonly("teeth", &MeasuredMember::teeth)
      .def_readonly("flanks", &MeasuredMember::flanks);
  m.def("read_cmm_file", &read_cmm_file, py::arg("path"),
        "Reads a CMM point file (ValueError '<file>:<line>: what is wrong; expected ...')");
  m.def(
      "write_cmm_file",
      [](const std::string &path, const MeasuredMember &member, bool millimetres) {
        CmmWriteOptions o;
        o.millimetres = millimetres;
        write_cmm_file(path, member, o);
      },
      py::arg("path"), py::arg("member"), py::arg("millimetres") = true,
      "Writes a CMM point file atomically (a temporary file, then renamed)");
  m.def(
      "virtual_cmm",
      [](const MemberFlanks &flanks, const std::string &name, int n_profile, int n_face,
         double margin, const std::vector<int> &teeth, bool both_sides) {
        return virtual_cmm(flanks, name, n_profile, n_face, margin, teeth, both_sides);
      },
      py::arg("flanks"), py::arg("member"), py::arg("n_profile") = 29, py::arg("n_face") = 9,
      py::arg("margin") = 0.0, py::arg("teeth") = std::vector<int>{}, py::arg("both_sides") = true,
      "A perfect CMM of the flanks: n_profile x n_face points per flank (all teeth by default)");
}
/// The slips of SI fields the scene's checks (in mm and deg) cannot name as such: a length
/// typed in millimetres into a metre field, an angle in degrees into a radian field.
void
check_si_units(const BevelPairDesign &d)
{
  const auto length = [](const char *name, double v, double largest) {
    if (std::isfinite(v) && v >= largest)
      throw InputError("BevelPairDesign." + std::string(name) + " = " + plausible_number(v) +
                       " m is not allowed: the fields are SI (metres), and no bevel pair has " +
                       std::string(name) + " >= " + plausible_number(largest) +
                       " m; it looks like millimetres (" + plausible_number(v) +
                       " mm = " + plausible_number(v / 1000) + " m)");
  };
  length("module", d.module, 0.1);
  length("face_width", d.face_width, 2.0);
  length("cutter_radius", d.cutter_radius, 5.0);
  for (const auto &[name, v] : {std::pair{"shaft_angle", d.shaft_angle},
                                {"mean_spiral_angle", d.mean_spiral_angle},
                                {"pressure_angle", d.pressure_angle}})
    if (std::isfinite(v) && std::abs(v) > pi)
      throw InputError("BevelPairDesign." + std::string(name) + " = " + plausible_number(v) +
                       " rad is not allowed: the fields are SI (radians); it looks like degrees (" +
                       plausible_number(v) + " deg = " + plausible_number(v * pi / 180) + " rad)");
}

/// Face-milled spiral bevel pairs from their design.
void
bind_bevel(py::module_ &m)
{
  py::class_<BevelPairDesign>(m, "BevelPairDesign",
                              "A face-milled spiral bevel pair's design (geometry/bevel_gear.h), "
                              "SI units, angles in radians")
      .def(py::init<>())
      .def_readwrite("pinion_teeth", &BevelPairDesign::pinion_teeth)
      .def_readwrite("gear_teeth", &BevelPairDesign::gear_teeth)
      .def_readwrite("shaft_angle", &BevelPairDesign::shaft_angle)
      .def_readwrite("module", &BevelPairDesign::module)
      .def_property(
          "module_kind",
          [](const BevelPairDesign &d) {
            return d.module_kind == BevelModule::outer_transverse ? "outer transverse"
                                                                  : "mean normal";
          },
          [](BevelPairDesign &d, const std::string &k) {
            if (k != "outer transverse" && k != "mean normal")
              throw InputError("BevelPairDesign.module_kind = '" + k +
                               "' is not allowed; expected outer transverse or mean normal");
            d.module_kind =
                k == "mean normal" ? BevelModule::mean_normal : BevelModule::outer_transverse;
          })
      .def_readwrite("face_width", &BevelPairDesign::face_width)
      .def_readwrite("mean_spiral_angle", &BevelPairDesign::mean_spiral_angle)
      .def_readwrite("pressure_angle", &BevelPairDesign::pressure_angle)
      .def_property(
          "pinion_hand",
          [](const BevelPairDesign &d) { return d.pinion_hand == Hand::left ? "left" : "right"; },
          [](BevelPairDesign &d, const std::string &h) {
            if (h != "left" && h != "right")
              throw InputError("BevelPairDesign.pinion_hand = '" + h +
                               "' is not allowed; expected left or right");
            d.pinion_hand = h == "left" ? Hand::left : Hand::right;
          })
      .def_readwrite("cutter_radius", &BevelPairDesign::cutter_radius)
      .def_readwrite("pinion_addendum", &BevelPairDesign::pinion_addendum)
      .def_readwrite("clearance", &BevelPairDesign::clearance)
      .def_readwrite("pinion_thickness", &BevelPairDesign::pinion_thickness)
      .def_readwrite("edge_radius", &BevelPairDesign::edge_radius);
  py::class_<PinionMismatch>(m, "PinionMismatch",
                             "The pinion's mismatch to the gear (geometry/bevel_gear.h), SI")
      .def(py::init<>())
      .def_readwrite("cutter_radius", &PinionMismatch::cutter_radius)
      .def_readwrite("blade_curvature", &PinionMismatch::blade_curvature)
      .def_readwrite("modified_roll_2c", &PinionMismatch::modified_roll_2c)
      .def_readwrite("modified_roll_6d", &PinionMismatch::modified_roll_6d);
  m.def(
      "bevel_pair_flanks",
      [](const BevelPairDesign &design, const PinionMismatch &mismatch,
         const Misalignment &misalignment) {
        // Unit slips of the SI fields, then the scene's checks of the design; its warnings as
        // Python's.
        check_si_units(design);
        PairScene pair;
        pair.name     = "python";
        pair.type     = PairType::spiral_bevel;
        pair.bevel    = design;
        pair.mismatch = mismatch;
        std::vector<std::string> warnings;
        const auto               plain = [](std::string text) {
          for (const std::string prefix :
               {"Flanks/python/Spiral bevel/", "Flanks/python/Spiral bevel: ", "Flanks/python/"})
            for (std::size_t at; (at = text.find(prefix)) != std::string::npos;)
              text.replace(at, prefix.size(), "BevelPairDesign: ");
          return text;
        };
        try
          {
            pair.check(warnings);
          }
        catch (const InputError &e)
          {
            throw InputError(plain(e.what()));
          }
        for (const std::string &w : warnings)
          PyErr_WarnEx(PyExc_UserWarning, plain(w).c_str(), 1);
        const BevelPairFlanks f = bevel_pair_flanks(design, mismatch, misalignment);
        return flanks_tuple(f.pinion, f.gear, f.assembly);
      },
      py::arg("design"), py::arg("mismatch") = PinionMismatch(),
      py::arg("misalignment") = Misalignment(),
      "(pinion flanks, gear flanks, assembly) of a spiral bevel pair: the gear generated by the "
      "design's machine settings, the pinion mismatched to it");
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
          [](TcaOptions &o, const std::string &s) { o.side = flank_side(s, "TcaOptions.side"); })
      .def_readwrite("positions_per_mesh", &TcaOptions::positions_per_mesh)
      .def_readwrite("mesh_cycles", &TcaOptions::mesh_cycles)
      .def_readwrite("start_angle", &TcaOptions::start_angle)
      .def_readwrite("profile_samples", &TcaOptions::profile_samples)
      .def_readwrite("face_samples", &TcaOptions::face_samples)
      .def_readwrite("contact_tolerance", &TcaOptions::contact_tolerance)
      .def_readwrite("robust_search", &TcaOptions::robust_search);
  bind_flanks(m);
  m.def(
      "unloaded_tca",
      [](const FlanksPointer &pinion, const FlanksPointer &gear, const Assembly &assembly,
         const TcaOptions &options) { return tca_tables(pinion, gear, assembly, options); },
      py::arg("pinion"), py::arg("gear"), py::arg("assembly"), py::arg("options") = TcaOptions(),
      "The unloaded TCA of any pair (involute, spiral bevel or measured flanks) in its "
      "assembly: e_0 [rad, pinion] per position, as the ste stage computes it");
  m.def(
      "unloaded_tca",
      [](const GearPointer &pinion, const GearPointer &gear, double centre_distance,
         const TcaOptions &options, const Misalignment &misalignment) {
        return tca_tables(std::make_shared<InvoluteMemberFlanks>(pinion),
                          std::make_shared<InvoluteMemberFlanks>(gear),
                          Assembly(centre_distance, gear->teeth(), misalignment), options);
      },
      py::arg("pinion"), py::arg("gear"), py::arg("centre_distance"),
      py::arg("options") = TcaOptions(), py::arg("misalignment") = Misalignment(),
      "The unloaded TCA of an involute pair at the centre distance [m]");
  bind_bevel(m);
}
} // namespace gearkit::python

// The compiled part of the Python module `gearkit` (python/gearkit/ is its face): the driver's
// scene reader and its run - the same stage graph, cache and outputs as the executable - and the
// results schema. MPI and PETSc start once per interpreter; an input error is a ValueError with
// the driver's message; a long call runs with the GIL released, its log goes to Python's
// sys.stdout line by line, and Ctrl-C stops it at its next progress step (KeyboardInterrupt).
#include "base/blas_kernels.h"
#include "base/progress.h"
#include "base/types.h"
#include "driver/driver.h"
#include "driver/pair_tca.h"
#include "driver/results_schema.h"
#include "geometry/involute_gear.h"
#include "geometry/member_flanks.h"
#include "tca/assembly.h"
#include "tca/unloaded_tca.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <streambuf>
#include <string>

namespace py = pybind11;
using namespace gearkit;

namespace
{
/// MPI and PETSc for the interpreter's life: started at import, finalised at exit.
std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;

void
start_mpi()
{
  static int    argc    = 1;
  static char   name[]  = "gearkit";
  static char  *words[] = {name, nullptr};
  static char **argv    = words;
  mpi                   = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc, argv, 1);
}

/// A stream buffer that writes each whole line to a Python stream (sys.stdout, sys.stderr),
/// taking the GIL for it: the driver's log in a notebook's cell.
class PythonLines : public std::streambuf
{
public:
  explicit PythonLines(const char *stream)
      : stream(stream)
  {
  }
  ~PythonLines() override { flush_line(); }

protected:
  int
  overflow(int c) override
  {
    if (c == traits_type::eof())
      return 0;
    line += char(c);
    if (c == '\n')
      flush_line();
    return c;
  }
  int
  sync() override
  {
    flush_line();
    return 0;
  }

private:
  void
  flush_line()
  {
    if (line.empty())
      return;
    py::gil_scoped_acquire gil;
    py::module_::import("sys").attr(stream).attr("write")(line);
    line.clear();
  }
  const char *stream;
  std::string line;
};

/// Runs work() on a thread of its own while Python's thread waits with the GIL released,
/// looking for Ctrl-C ten times a second: on a KeyboardInterrupt every computation is asked to
/// stop (gearkit::interrupt: it unwinds at its next progress step, as after any error) and,
/// once the work has ended, the KeyboardInterrupt is raised. The work's own error is rethrown.
template <class Result>
Result
interruptible(const std::function<Result()> &work)
{
  clear_interrupt();
  std::future<Result> done = std::async(std::launch::async, work);
  for (;;)
    {
      {
        py::gil_scoped_release release;
        if (done.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready)
          break;
      }
      if (PyErr_CheckSignals() != 0) // the KeyboardInterrupt is now set on this thread
        {
          interrupt();
          {
            py::gil_scoped_release release;
            done.wait();
          }
          clear_interrupt();
          try
            {
              done.get();
            }
          catch (...) // Interrupted, or whatever the work met on its way out
            {
            }
          throw py::error_already_set();
        }
    }
  clear_interrupt();
  return done.get();
}

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

template <class T>
py::array_t<T>
array(const std::vector<T> &v)
{
  return py::array_t<T>(py::ssize_t(v.size()), v.data());
}

py::dict
summary_dict(const RunSummary &s)
{
  py::list stages;
  for (const StageRun &r : s.stages)
    stages.append(py::dict(py::arg("name") = r.name, py::arg("reused") = r.reused,
                           py::arg("seconds") = r.seconds, py::arg("cache_file") = r.cache_file));
  return py::dict(py::arg("results_file") = s.results_file, py::arg("status") = s.status,
                  py::arg("stages") = stages);
}
} // namespace

PYBIND11_MODULE(_core, m)
{
  m.doc() = "gearkit's compiled core (use the package gearkit)";
  start_mpi();
  py::module_::import("atexit").attr("register")(py::cpp_function([] { mpi.reset(); }));

  // 1. Errors: an input error is a ValueError with the driver's message, a stopped computation
  //    a KeyboardInterrupt.
  py::register_exception_translator([](std::exception_ptr p) {
    try
      {
        if (p)
          std::rethrow_exception(p);
      }
    catch (const InputError &e)
      {
        PyErr_SetString(PyExc_ValueError, e.what());
      }
    catch (const Interrupted &)
      {
        PyErr_SetNone(PyExc_KeyboardInterrupt);
      }
  });

  // 2. Scenes as the driver reads them.
  py::class_<Scene>(m, "CoreScene", "A scene as the driver read and checked it")
      .def_readonly("file", &Scene::file)
      .def_readonly("name", &Scene::name)
      .def_readonly("outputs", &Scene::outputs)
      .def_readonly("sections", &Scene::sections)
      .def_readonly("warnings", &Scene::warnings)
      .def_property_readonly("pairs",
                             [](const Scene &s) {
                               std::vector<std::string> names;
                               for (const PairScene &p : s.pairs)
                                 names.push_back(p.name);
                               return names;
                             })
      .def(
          "involute_pair",
          [](const Scene &s, const std::string &name) {
            const PairScene &pair = s.pair(name);
            if (pair.type == PairType::spiral_bevel)
              throw InputError("pair " + name + " is a spiral bevel pair, not an involute one");
            const auto [p, g] = pair.involute_members(s.tca.at(name));
            return py::make_tuple(std::const_pointer_cast<InvoluteGear>(p),
                                  std::const_pointer_cast<InvoluteGear>(g));
          },
          "The pair's involute members as the stages build them (at its operating centre "
          "distance)")
      .def("tca_options",
           [](const Scene &s, const std::string &name) { return s.tca.at(name).options; })
      .def("misalignment",
           [](const Scene &s, const std::string &name) { return s.tca.at(name).misalignment; })
      .def("tca_centre_distance",
           [](const Scene &s, const std::string &name) {
             const TcaScene &t = s.tca.at(name);
             if (t.centre_distance > 0)
               return t.centre_distance;
             const auto [p, g] = s.pair(name).involute_members(t);
             return working_centre_distance(*p, *g);
           })
      .def_property_readonly("trains", [](const Scene &s) {
        std::vector<std::string> names;
        for (const TrainScene &t : s.trains)
          names.push_back(t.name);
        return names;
      });
  m.def(
      "read_scene",
      [](const std::string &path, const std::string &base_directory, const std::string &shown_as) {
        Scene s = read_scene(path, base_directory);
        if (!shown_as.empty())
          s.file = shown_as;
        return s;
      },
      py::arg("path"), py::arg("base_directory") = "", py::arg("shown_as") = "",
      "Reads and checks a scene file as the driver does (ValueError with its message).");

  // 3. The run: lock, stages, pictures, report - as `gearkit [--plot] SCENE`.
  m.def(
      "run_scene",
      [](const Scene &scene, const std::string &output_root, bool plot) {
        const RunSummary s = interruptible<RunSummary>([&] {
          PythonLines  out_lines("stdout"), err_lines("stderr");
          std::ostream out(&out_lines), err(&err_lines);
          blas_threads_per_process();
          return run_and_report(scene, output_root, plot, out, err);
        });
        return summary_dict(s);
      },
      py::arg("scene"), py::arg("output_root"), py::arg("plot") = false,
      "Runs the stages the scene's outputs need (cache, results.h5, report, pictures).");

  // 4. Library level: involute gears, their pair and its unloaded TCA, on library types (SI).
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

  // 5. The results schema and the machine's BLAS kernels.
  m.def("results_schema", [] {
    py::list entries;
    for (const ResultDataset &d : results_schema())
      entries.append(py::dict(py::arg("group") = d.group, py::arg("dataset") = d.name,
                              py::arg("shape") = d.shape, py::arg("units") = d.units,
                              py::arg("description") = d.description));
    return entries;
  });
  m.def("blas_kernels", &blas_core_name, "The kernels OpenBLAS uses in this process");
  m.def(
      "fitting_blas_kernels", [] { return fitting_blas_core(blas_core_name()); },
      "The kernels the executable switches OpenBLAS to on this processor (empty: none)");
  m.def("interrupt", &interrupt, "Asks the running computation to stop (as Ctrl-C does)");
  m.attr("source_dir") = GEARKIT_SOURCE_DIR;
}

// The compiled part of the Python module `gearkit` (python/gearkit/ is its face): the driver's
// scene reader and its run - the same stage graph, cache and outputs as the executable - and the
// results schema. MPI and PETSc start once per interpreter; an input error is a ValueError with
// the driver's message; a long call runs with the GIL released, its log goes to Python's
// sys.stdout line by line, and Ctrl-C stops it at its next progress step (KeyboardInterrupt).
#include "base/blas_kernels.h"
#include "base/progress.h"
#include "base/types.h"
#include "driver/driver.h"
#include "driver/results_schema.h"
#include "python/bindings.h"

#include <deal.II/base/mpi.h>

#include <memory>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <string>

namespace py = pybind11;
using namespace gearkit;
using gearkit::python::interruptible;
using gearkit::python::logged;

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
      .def("tca_options",
           [](const Scene &s, const std::string &name) { return s.tca.at(name).options; })
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
        const RunSummary s = logged<RunSummary>([&](std::ostream &out, std::ostream &err) {
          blas_threads_per_process();
          return run_and_report(scene, output_root, plot, out, err);
        });
        return summary_dict(s);
      },
      py::arg("scene"), py::arg("output_root"), py::arg("plot") = false,
      "Runs the stages the scene's outputs need (cache, results.h5, report, pictures).");

  // 4. Library level, on library types (SI units).
  python::bind_geometry_tca(m);
  python::bind_stages(m);
  python::bind_dynamics(m);

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

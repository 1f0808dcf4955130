// What the compiled parts of the Python module share: the driver's log into Python's streams,
// long calls with the GIL released and Ctrl-C, vectors as NumPy arrays, and the functions that
// bind each library's part (one file each).
#pragma once

#include "base/progress.h"
#include "base/types.h"
#include "geometry/member_flanks.h"
#include "geometry/types.h"
#include "tca/assembly.h"

#include <atomic>
#include <csignal>
#include <functional>
#include <memory>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <streambuf>
#include <string>
#include <vector>

namespace gearkit::python
{
namespace py = pybind11;

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

/// Set by interruptible's SIGINT handler (a lock-free atomic: safe in a signal handler).
inline std::atomic<bool> sigint_seen{false};

/// Runs work() on this thread with the GIL released, Ctrl-C (SIGINT) meanwhile caught by a
/// handler of its own: every computation is asked to stop (gearkit::interrupt: it unwinds at its
/// next progress step, as after any error) and, once the work has ended, KeyboardInterrupt is
/// raised. Python's handler is back in place afterwards; the work's own error is rethrown. (On
/// the calling thread, not a thread of its own: the same thread and memory arena as the
/// executable's run.)
template <class Result>
Result
interruptible(const std::function<Result()> &work)
{
  clear_interrupt();
  sigint_seen           = false;
  struct sigaction ours = {}, previous = {};
  ours.sa_handler = [](int) {
    sigint_seen = true;
    interrupt();
  };
  sigemptyset(&ours.sa_mask);
  sigaction(SIGINT, &ours, &previous);
  struct Restore
  {
    struct sigaction *previous;
    ~Restore()
    {
      sigaction(SIGINT, previous, nullptr);
      clear_interrupt();
    }
  } restore{&previous};
  std::optional<Result> result;
  std::exception_ptr    error;
  {
    py::gil_scoped_release release;
    try
      {
        result.emplace(work());
      }
    catch (...) // Interrupted, or whatever the work met on its way out
      {
        error = std::current_exception();
      }
  }
  if (sigint_seen)
    {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
  if (error)
    std::rethrow_exception(error);
  return std::move(*result);
}

template <class T>
py::array_t<T>
array(const std::vector<T> &v)
{
  return py::array_t<T>(py::ssize_t(v.size()), v.data());
}

/// Points as an array of the given shape (default: one axis, the points), the last axis x, y, z
/// (e.g. {n_profile, n_face}).
inline py::array_t<double>
vec3_array(const std::vector<Vec3> &points, std::vector<py::ssize_t> shape = {})
{
  if (shape.empty())
    shape.push_back(py::ssize_t(points.size()));
  shape.push_back(3);
  py::array_t<double> a(shape);
  double             *out = a.mutable_data();
  for (std::size_t k = 0; k < points.size(); ++k)
    for (int c = 0; c < 3; ++c)
      out[3 * k + std::size_t(c)] = points[k][c];
  return a;
}

/// One point or vector as an array of 3.
inline py::array_t<double>
vec3(const Vec3 &v)
{
  return py::array_t<double>(3, v.data());
}

/// An array whose last axis has length 3 as points (row-major over the other axes); `what`
/// names it in the InputError for another shape.
inline std::vector<Vec3>
vec3_list(const py::array_t<double, py::array::c_style | py::array::forcecast> &a,
          const std::string                                                    &what)
{
  if (a.ndim() < 1 || a.shape(a.ndim() - 1) != 3)
    throw InputError(what + ": an array of shape (..., 3) expected (x, y, z in metres)");
  std::vector<Vec3> points(std::size_t(a.size() / 3));
  const double     *in = a.data();
  for (std::size_t k = 0; k < points.size(); ++k)
    points[k] = Vec3(in[3 * k], in[3 * k + 1], in[3 * k + 2]);
  return points;
}

/// "drive" or "coast"; `what` names the parameter in the InputError for anything else.
inline FlankSide
flank_side(const std::string &side, const std::string &what)
{
  if (side != "drive" && side != "coast")
    throw InputError(what + " = '" + side + "' is not allowed; expected drive or coast");
  return side == "drive" ? FlankSide::drive : FlankSide::coast;
}

/// (pinion flanks, gear flanks, assembly) as Python sees a pair (pybind11 holds no pointer to
/// const).
inline py::tuple
flanks_tuple(const std::shared_ptr<const MemberFlanks> &pinion,
             const std::shared_ptr<const MemberFlanks> &gear, const Assembly &assembly)
{
  return py::make_tuple(std::const_pointer_cast<MemberFlanks>(pinion),
                        std::const_pointer_cast<MemberFlanks>(gear), assembly);
}

/// Runs work() with the driver's log (std::ostream out, err) going to sys.stdout and
/// sys.stderr, interruptible.
template <class Result>
Result
logged(const std::function<Result(std::ostream &out, std::ostream &err)> &work)
{
  return interruptible<Result>([&] {
    PythonLines  out_lines("stdout"), err_lines("stderr");
    std::ostream out(&out_lines), err(&err_lines);
    return work(out, err);
  });
}

/// Involute gears, flanks (involute, spiral bevel, measured) and the unloaded TCA.
void
bind_geometry_tca(py::module_ &m);

/// A scene's pair from its stages' results: flanks, measured flanks, the loaded contact at any
/// torque on the compliance tables.
void
bind_stages(py::module_ &m);

/// The 14-DOF pair model and its speed sweeps, gear trains (models as the stages build them).
void
bind_dynamics(py::module_ &m);
} // namespace gearkit::python

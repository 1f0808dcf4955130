// The one time integrator family of dynamics/: SUNDIALS CVODE (BDF for stiff problems, Adams
// for tight non-stiff runs) with a dense Newton solver, per-component absolute tolerances and
// root finding (event location). Every model (the 14-DOF pair, the gear train) supplies its
// right-hand side and root functions; this class owns the SUNDIALS objects and turns every
// failure into an InputError naming the model, the call, the time and the CVODE flag.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace gearkit
{
struct CvodeProblem
{
  std::string what = "dynamics"; ///< the model, for messages
  int         size = 0;
  /// y' = f(t, y); a non-zero return tells CVODE the step failed (recoverable if > 0)
  std::function<int(double t, const double *y, double *ydot)> rhs;
  int roots = 0; ///< root functions g(t, y) located by CVODE
  std::function<void(double t, const double *y, double *g)> root_functions;
  /// Quadratures q' = h(t, y) integrated alongside (e.g. the work and the dissipated energy of
  /// an energy balance), in the error test with these absolute tolerances (none: all outside
  /// it; an infinite one: that quadrature outside it, the others' error test exactly as
  /// without it, e.g. running integrals kept only to be read back)
  int                 quadratures = 0;
  std::vector<double> quadrature_tolerance;
  /// Relative tolerance of the quadratures' error test (< 0: relative_tolerance). A quadrature
  /// that accumulates (work over a long run) lets its local error grow with its value under a
  /// relative test; 0 holds every step to the absolute tolerances.
  double                                                      quadrature_relative_tolerance = -1;
  std::function<int(double t, const double *y, double *qdot)> quadrature_rhs;
  bool                                                        bdf = true;
  /// Fixed-point (functional) iteration for the implicit stages instead of Newton's method
  /// with a dense Jacobian: no Jacobian and no factorisation, for non-stiff problems (with
  /// Adams); a stiff one fails to converge and shrinks the steps.
  bool                functional_iteration = false;
  double              relative_tolerance   = 1e-8;
  std::vector<double> absolute_tolerance; ///< per component (size entries)
  long                max_steps_per_call = 1000000;
  std::string         hint = "try a smaller tolerance or check the model's stiffnesses";
};

class CvodeSolver
{
public:
  CvodeSolver(const CvodeProblem &problem, double t0, const std::vector<double> &y0);
  ~CvodeSolver();
  CvodeSolver(const CvodeSolver &) = delete;
  CvodeSolver &
  operator=(const CvodeSolver &) = delete;

  /// Advances towards t_out; returns false there, or true at a root before it (then `fired`,
  /// if given, holds the root functions' directions: +1 rising, -1 falling, 0 not fired).
  /// t and y hold the time and state reached.
  bool
  advance(double t_out, double &t, std::vector<double> &y, std::vector<int> *fired = nullptr);
  /// One internal step towards t_end, never past it (CVODE's one-step mode with t_end as its
  /// stop time): returns true at a root inside the step (t is the root, `fired` as for
  /// advance), false at the step's end. The steps do not depend on when the caller wants
  /// output (interpolate): every event, peak and count is the same at any output rate.
  bool
  step(double t_end, double &t, std::vector<double> &y, std::vector<int> *fired = nullptr);
  /// Bounds the steps from here on (0: no bound).
  void
  set_max_step(double h);
  /// The state (and, if asked, the quadratures) at time t inside the last step, from the
  /// method's interpolating polynomial (CVodeGetDky).
  void
  interpolate(double t, std::vector<double> &y, std::vector<double> *quadratures = nullptr) const;
  /// Restarts the method at (t, y), t inside the last step (an event, or a change the caller
  /// found inside the step), the quadratures interpolated there.
  void
  reinit(double t, const std::vector<double> &y);
  /// The quadratures at the time last reached.
  std::vector<double>
  quadratures() const;
  /// Steps taken since the start, restarts included.
  long
  steps() const;

private:
  /// CVode towards t_out in the given task (CV_NORMAL, CV_ONE_STEP), as advance returns.
  bool
  call(double t_out, int task, double &t, std::vector<double> &y, std::vector<int> *fired);
  long
       steps_since_start() const;
  long steps_before = 0;
  void
  release();
  void
               check(int flag, const char *call, double t) const;
  CvodeProblem p;
  void        *context = nullptr, *memory = nullptr, *state = nullptr, *tolerance = nullptr,
       *matrix = nullptr, *solver = nullptr, *quadrature = nullptr, *nonlinear = nullptr;
  /// interpolate's results (allocated once)
  void *interpolated = nullptr, *interpolated_quadratures = nullptr;
};
} // namespace gearkit

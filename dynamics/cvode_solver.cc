#include "dynamics/cvode_solver.h"

#include "base/types.h"

#include <algorithm>
#include <cmath>
#include <cvodes/cvodes.h>
#include <limits>
#include <nvector/nvector_serial.h>
#include <sstream>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

namespace gearkit
{
namespace
{
int
rhs_callback(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
  const auto *p = static_cast<const CvodeProblem *>(user);
  return p->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

int
quadrature_callback(sunrealtype t, N_Vector y, N_Vector qdot, void *user)
{
  const auto   *p = static_cast<const CvodeProblem *>(user);
  double *const q = N_VGetArrayPointer(qdot);
  std::fill(q + p->quadratures, q + N_VGetLength(qdot), 0.0); // the padding (see the constructor)
  return p->quadrature_rhs(t, N_VGetArrayPointer(y), q);
}

int
root_callback(sunrealtype t, N_Vector y, sunrealtype *g, void *user)
{
  const auto *p = static_cast<const CvodeProblem *>(user);
  p->root_functions(t, N_VGetArrayPointer(y), g);
  return 0;
}
} // namespace

void
CvodeSolver::check(int flag, const char *call, double t) const
{
  if (flag >= 0)
    return;
  std::ostringstream msg;
  msg << p.what << ": CVODE failed in " << call << " at t = " << t << " (flag " << flag << ": "
      << CVodeGetReturnFlagName(flag) << "); " << p.hint;
  throw InputError(msg.str());
}

CvodeSolver::CvodeSolver(const CvodeProblem &problem, double t0, const std::vector<double> &y0)
    : p(problem)
{
  require_value(int(y0.size()) == p.size && int(p.absolute_tolerance.size()) == p.size, p.what,
                "state size", double(y0.size()), "the problem's size");
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0)
    throw InputError(p.what + ": cannot create a SUNDIALS context");
  context       = ctx;
  N_Vector y    = N_VNew_Serial(p.size, ctx);
  N_Vector atol = N_VNew_Serial(p.size, ctx);
  N_Vector dky  = N_VNew_Serial(p.size, ctx);
  state = y, tolerance = atol, interpolated = dky;
  SUNMatrix A        = SUNDenseMatrix(p.size, p.size, ctx);
  matrix             = A;
  SUNLinearSolver LS = SUNLinSol_Dense(y, A, ctx);
  solver             = LS;
  memory             = CVodeCreate(p.bdf ? CV_BDF : CV_ADAMS, ctx);
  if (!y || !atol || !dky || !A || !LS || !memory)
    {
      release();
      throw InputError(p.what + ": cannot allocate the CVODE integrator");
    }
  try
    {
      for (int i = 0; i < p.size; ++i)
        {
          N_VGetArrayPointer(y)[i]    = y0[i];
          N_VGetArrayPointer(atol)[i] = p.absolute_tolerance[i];
        }
      check(CVodeInit(memory, rhs_callback, t0, y), "CVodeInit", t0);
      check(CVodeSVtolerances(memory, p.relative_tolerance, atol), "CVodeSVtolerances", t0);
      check(CVodeSetUserData(memory, &p), "CVodeSetUserData", t0);
      if (p.functional_iteration)
        {
          SUNNonlinearSolver fixed_point = SUNNonlinSol_FixedPoint(y, 0, ctx);
          if (!fixed_point)
            throw InputError(p.what + ": cannot allocate the fixed-point iteration");
          nonlinear = fixed_point;
          check(CVodeSetNonlinearSolver(memory, fixed_point), "CVodeSetNonlinearSolver", t0);
        }
      else
        check(CVodeSetLinearSolver(memory, LS, A), "CVodeSetLinearSolver", t0);
      check(CVodeSetMaxNumSteps(memory, p.max_steps_per_call), "CVodeSetMaxNumSteps", t0);
      if (p.quadratures > 0)
        {
          // quadratures with an infinite tolerance are outside the error test (weight 0). CVODE's
          // norm is the root mean square over all quadratures, so the vector is padded with
          // zeros to 4^k times the tested ones and their tolerances halved k times: every
          // weight, square and mean then changes by a power of two only, and the error test is
          // bit for bit the one without the untested quadratures (the bound on a restart's
          // first step, from the absolute tolerances alone, is halved k times).
          const bool tested = !p.quadrature_tolerance.empty();
          if (tested)
            require_value(int(p.quadrature_tolerance.size()) == p.quadratures, p.what,
                          "quadrature tolerances", double(p.quadrature_tolerance.size()),
                          "one per quadrature");
          const int controlled =
              int(std::count_if(p.quadrature_tolerance.begin(), p.quadrature_tolerance.end(),
                                [](double a) { return std::isfinite(a); }));
          int    length = p.quadratures;
          double shrink = 1;
          if (controlled > 0 && controlled < p.quadratures)
            for (length = controlled; length < p.quadratures; length *= 4)
              shrink /= 2;
          N_Vector q               = N_VNew_Serial(length, ctx);
          quadrature               = q;
          interpolated_quadratures = N_VNew_Serial(length, ctx);
          if (!q || !interpolated_quadratures)
            throw InputError(p.what + ": cannot allocate the CVODE quadratures");
          N_VConst(0.0, q);
          check(CVodeQuadInit(memory, quadrature_callback, q), "CVodeQuadInit", t0);
          if (tested && controlled > 0)
            {
              N_Vector a = N_VClone(q);
              N_VConst(std::numeric_limits<double>::infinity(), a);
              for (int i = 0; i < p.quadratures; ++i)
                N_VGetArrayPointer(a)[i] = p.quadrature_tolerance[i] * shrink;
              const double relative = p.quadrature_relative_tolerance < 0
                                          ? p.relative_tolerance
                                          : p.quadrature_relative_tolerance;
              const int    flag     = CVodeQuadSVtolerances(memory, relative * shrink, a);
              N_VDestroy(a);
              check(flag, "CVodeQuadSVtolerances", t0);
              check(CVodeSetQuadErrCon(memory, SUNTRUE), "CVodeSetQuadErrCon", t0);
            }
        }
      if (p.roots > 0)
        check(CVodeRootInit(memory, p.roots, root_callback), "CVodeRootInit", t0);
    }
  catch (...)
    {
      release();
      throw;
    }
}

CvodeSolver::~CvodeSolver() { release(); }

void
CvodeSolver::release()
{
  if (memory)
    CVodeFree(&memory);
  if (nonlinear)
    SUNNonlinSolFree(static_cast<SUNNonlinearSolver>(nonlinear));
  if (solver)
    SUNLinSolFree(static_cast<SUNLinearSolver>(solver));
  if (matrix)
    SUNMatDestroy(static_cast<SUNMatrix>(matrix));
  for (void *v : {quadrature, interpolated, interpolated_quadratures, tolerance, state})
    if (v)
      N_VDestroy(static_cast<N_Vector>(v));
  if (context)
    {
      SUNContext ctx = static_cast<SUNContext>(context);
      SUNContext_Free(&ctx);
    }
  memory = solver = matrix = tolerance = state = context = quadrature = nonlinear = nullptr;
  interpolated = interpolated_quadratures = nullptr;
}

bool
CvodeSolver::call(double t_out, int task, double &t, std::vector<double> &y,
                  std::vector<int> *fired)
{
  N_Vector    v       = static_cast<N_Vector>(state);
  sunrealtype reached = 0;
  const int   flag    = CVode(memory, t_out, v, &reached, task);
  check(flag, "CVode", reached);
  t = reached;
  y.assign(N_VGetArrayPointer(v), N_VGetArrayPointer(v) + p.size);
  if (flag != CV_ROOT_RETURN)
    return false;
  if (fired)
    {
      fired->assign(p.roots, 0);
      check(CVodeGetRootInfo(memory, fired->data()), "CVodeGetRootInfo", t);
    }
  return true;
}

bool
CvodeSolver::advance(double t_out, double &t, std::vector<double> &y, std::vector<int> *fired)
{
  return call(t_out, CV_NORMAL, t, y, fired);
}

bool
CvodeSolver::step(double t_end, double &t, std::vector<double> &y, std::vector<int> *fired)
{
  check(CVodeSetStopTime(memory, t_end), "CVodeSetStopTime", t);
  return call(t_end, CV_ONE_STEP, t, y, fired);
}

void
CvodeSolver::set_max_step(double h)
{
  check(CVodeSetMaxStep(memory, h), "CVodeSetMaxStep", 0);
}

void
CvodeSolver::interpolate(double t, std::vector<double> &y, std::vector<double> *q) const
{
  N_Vector v = static_cast<N_Vector>(interpolated);
  check(CVodeGetDky(memory, t, 0, v), "CVodeGetDky", t);
  y.assign(N_VGetArrayPointer(v), N_VGetArrayPointer(v) + p.size);
  if (q && quadrature)
    {
      N_Vector w = static_cast<N_Vector>(interpolated_quadratures);
      check(CVodeGetQuadDky(memory, t, 0, w), "CVodeGetQuadDky", t);
      q->assign(N_VGetArrayPointer(w), N_VGetArrayPointer(w) + p.quadratures);
    }
}

void
CvodeSolver::reinit(double t, const std::vector<double> &y)
{
  steps_before += steps_since_start(); // CVodeReInit zeroes CVODE's count
  if (quadrature) // their values at t, where the method restarts (t may lie inside the step)
    check(CVodeGetQuadDky(memory, t, 0, static_cast<N_Vector>(quadrature)), "CVodeGetQuadDky", t);
  N_Vector v = static_cast<N_Vector>(state);
  for (int i = 0; i < p.size; ++i)
    N_VGetArrayPointer(v)[i] = y[i];
  check(CVodeReInit(memory, t, v), "CVodeReInit", t);
  if (quadrature)
    check(CVodeQuadReInit(memory, static_cast<N_Vector>(quadrature)), "CVodeQuadReInit", t);
}

std::vector<double>
CvodeSolver::quadratures() const
{
  if (!quadrature)
    return {};
  N_Vector    q = static_cast<N_Vector>(quadrature);
  sunrealtype t = 0;
  check(CVodeGetQuad(memory, &t, q), "CVodeGetQuad", t);
  return {N_VGetArrayPointer(q), N_VGetArrayPointer(q) + p.quadratures};
}

long
CvodeSolver::steps_since_start() const
{
  long n = 0;
  CVodeGetNumSteps(memory, &n);
  return n;
}

long
CvodeSolver::steps() const
{
  return steps_before + steps_since_start();
}
} // namespace gearkit

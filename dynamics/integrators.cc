#include "dynamics/integrators.h"

#include <Eigen/Dense>

#include <cmath>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sstream>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace gearkit
{
namespace
{
void
record(const PairModel &model, const RunOptions &o, double t, const PairVector &q,
       const PairVector &v, Trajectory &out)
{
  const MeshState  m       = model.mesh().at(model.phase(t, o.omega));
  const PairVector g       = PairModel::mesh_gradient(m);
  const double     et_rate = m.det * model.parameters().pinion_teeth * o.omega / (2 * pi);
  out.t.push_back(t);
  out.q.push_back(q);
  out.v.push_back(v);
  out.dte.push_back(g.dot(q));
  out.relative.push_back(g.dot(q) - m.et);
  out.force.push_back(model.mesh_force(m, g.dot(q), g.dot(v), et_rate));
}

struct CvodeData
{
  const PairModel  *model;
  const RunOptions *o;
  double            period; // mesh period [s]
};

// y = [q; v] in SI, time tau in mesh cycles: dy/dtau = T dy/dt
int
cvode_rhs(sunrealtype tau, N_Vector y, N_Vector ydot, void *user)
{
  const auto                  *d = static_cast<CvodeData *>(user);
  Eigen::Map<const PairVector> q(N_VGetArrayPointer(y));
  Eigen::Map<const PairVector> v(N_VGetArrayPointer(y) + pair_dofs);
  Eigen::Map<PairVector>       dq(N_VGetArrayPointer(ydot));
  Eigen::Map<PairVector>       dv(N_VGetArrayPointer(ydot) + pair_dofs);
  const double                 t = tau * d->period;
  dq                             = d->period * v;
  dv                             = d->period *
       d->model->acceleration(t, q, v, d->o->omega, d->o->motor_torque, d->o->load_torque);
  return 0;
}

int
cvode_roots(sunrealtype tau, N_Vector y, sunrealtype *gout, void *user)
{
  const auto                  *d = static_cast<CvodeData *>(user);
  Eigen::Map<const PairVector> q(N_VGetArrayPointer(y));
  const MeshState              m = d->model->mesh().at(tau); // tau is the mesh phase
  const double                 x = PairModel::mesh_gradient(m).dot(q) - m.et,
               b                 = d->model->parameters().half_backlash;
  gout[0]                        = x - b;
  gout[1]                        = x + b;
  return 0;
}

void
cvode_check(int flag, const char *call, double tau)
{
  if (flag < 0)
    {
      std::ostringstream msg;
      msg << "pair dynamics: CVODE failed in " << call << " at mesh cycle " << tau << " (flag "
          << flag << ": " << CVodeGetReturnFlagName(flag)
          << "); try a smaller tolerance, the Newmark path, or check the model's stiffnesses";
      throw InputError(msg.str());
    }
}

Trajectory
run_cvode(const PairModel &model, const PairVector &q0, const PairVector &v0, const RunOptions &o)
{
  Trajectory out;
  CvodeData  data{&model, &o, 2 * pi / (model.parameters().pinion_teeth * o.omega)};
  SUNContext ctx;
  if (SUNContext_Create(nullptr, &ctx) != 0)
    throw InputError("pair dynamics: cannot create a SUNDIALS context");
  N_Vector        y = N_VNew_Serial(2 * pair_dofs, ctx), abstol = N_VNew_Serial(2 * pair_dofs, ctx);
  SUNMatrix       A   = SUNDenseMatrix(2 * pair_dofs, 2 * pair_dofs, ctx);
  SUNLinearSolver LS  = SUNLinSol_Dense(y, A, ctx);
  void           *mem = CVodeCreate(o.method == Integrator::cvode_adams ? CV_ADAMS : CV_BDF, ctx);
  auto            release = [&] {
    CVodeFree(&mem);
    SUNLinSolFree(LS);
    SUNMatDestroy(A);
    N_VDestroy(abstol);
    N_VDestroy(y);
    SUNContext_Free(&ctx);
  };
  try
    {
      Eigen::Map<PairVector>(N_VGetArrayPointer(y))             = q0;
      Eigen::Map<PairVector>(N_VGetArrayPointer(y) + pair_dofs) = v0;
      // scales: displacements, and their rates per mesh cycle... per second (v in SI)
      // the static mesh deflection's scale: the half backlash, at least a micrometre
      const PairVector s = model.dof_scale(std::max(model.parameters().half_backlash, 1e-6));
      Eigen::Map<PairVector>(N_VGetArrayPointer(abstol)) = o.absolute_tolerance * s;
      Eigen::Map<PairVector>(N_VGetArrayPointer(abstol) + pair_dofs) =
          o.absolute_tolerance * s / data.period;
      cvode_check(CVodeInit(mem, cvode_rhs, 0.0, y), "CVodeInit", 0);
      cvode_check(CVodeSVtolerances(mem, o.relative_tolerance, abstol), "CVodeSVtolerances", 0);
      cvode_check(CVodeSetUserData(mem, &data), "CVodeSetUserData", 0);
      cvode_check(CVodeSetLinearSolver(mem, LS, A), "CVodeSetLinearSolver", 0);
      cvode_check(CVodeSetMaxNumSteps(mem, 1000000), "CVodeSetMaxNumSteps", 0);
      if (model.parameters().half_backlash > 0)
        cvode_check(CVodeRootInit(mem, 2, cvode_roots), "CVodeRootInit", 0);
      record(model, o, 0, q0, v0, out);
      const int n_out = int(std::lround(o.mesh_cycles * o.samples_per_cycle));
      double    tau   = 0;
      for (int k = 1; k <= n_out; ++k)
        {
          const double tout = double(k) / o.samples_per_cycle;
          while (true)
            {
              const int flag = CVode(mem, tout, y, &tau, CV_NORMAL);
              cvode_check(flag, "CVode", tau);
              if (flag != CV_ROOT_RETURN)
                break;
              ++out.events; // the mesh force changes its law here: restart the method
              cvode_check(CVodeReInit(mem, tau, y), "CVodeReInit", tau);
            }
          Eigen::Map<const PairVector> q(N_VGetArrayPointer(y));
          Eigen::Map<const PairVector> v(N_VGetArrayPointer(y) + pair_dofs);
          record(model, o, tout * data.period, q, v, out);
        }
      long steps = 0;
      CVodeGetNumSteps(mem, &steps);
      out.steps = std::size_t(steps);
    }
  catch (...)
    {
      release();
      throw;
    }
  release();
  return out;
}

Trajectory
run_newmark(const PairModel &model, const PairVector &q0, const PairVector &v0, const RunOptions &o)
{
  Trajectory        out;
  const double      period = 2 * pi / (model.parameters().pinion_teeth * o.omega);
  const double      h      = period / o.steps_per_cycle;
  const PairMatrix &M = model.mass(), &K = model.stiffness(), &C = model.damping();
  const double      c_m           = model.mesh_damping();
  const int         z             = model.parameters().pinion_teeth;
  const PairVector  F_ext         = model.torques(o.motor_torque, o.load_torque);
  const PairVector  free          = model.active();
  const PairVector  held_dofs     = PairVector::Ones() - free;
  const PairMatrix  held          = held_dofs.asDiagonal();
  const double      b             = model.parameters().half_backlash;
  const bool        always_damped = !model.parameters().mesh_damping_in_contact_only;
  // Each step is linear in q_{n+1} except for the mesh force, a piecewise linear function of
  // the single number delta_D = g . q_{n+1}: with L = 4/h^2 M + 2/h C + K (on the free DOFs;
  // one factorisation), q_{n+1} = q_n + dq* - L^-1 g F_m, delta = delta* - (g^T L^-1 g) F_m(delta),
  // solved exactly branch by branch (contact on either flank, or none) - no Newton iterations
  // to cycle at the backlash boundaries.
  const PairMatrix L =
      free.asDiagonal() * (4 / (h * h) * M + 2 / h * C + K) * free.asDiagonal() + held;
  const Eigen::LDLT<PairMatrix> Lf(L);
  PairVector                    q = q0, v = v0, a;
  {
    const MeshState  m  = model.mesh().at(0);
    const PairVector g  = PairModel::mesh_gradient(m).cwiseProduct(free);
    const double     Fm = model.mesh_force(m, g.dot(q), g.dot(v), m.det * z * o.omega / (2 * pi));
    a                   = M.ldlt().solve(F_ext - K * q - C * v - g * Fm).cwiseProduct(free);
  }
  record(model, o, 0, q, v, out);
  const int steps_total = int(std::lround(o.mesh_cycles * o.steps_per_cycle));
  const int every       = std::max(1, o.steps_per_cycle / o.samples_per_cycle);
  for (int n = 1; n <= steps_total; ++n)
    {
      const double     t       = n * h;
      const MeshState  m       = model.mesh().at(model.phase(t, o.omega));
      const PairVector g       = PairModel::mesh_gradient(m).cwiseProduct(free);
      const double     et_rate = m.det * z * o.omega / (2 * pi);
      const PairVector Lg      = Lf.solve(g);
      const double     gLg     = g.dot(Lg);
      // in increments (the rigid rotation of a torque-driven train grows without bound; the
      // step must not cancel it against itself): L dq = dq* - L^-1 g F_m
      const PairVector rhs   = (F_ext - K * q + M * (4 / h * v + a) + C * v).cwiseProduct(free);
      const PairVector dqs   = Lf.solve(rhs);
      const double     dstar = g.dot(q) + g.dot(dqs);
      const double     D0    = -(2 / h * g.dot(q) + g.dot(v)); // delta' = 2/h delta + D0
      const double     c2h = 2 / h * c_m, damp0 = c_m * (D0 - et_rate);
      // F_m = alpha delta + beta on each branch; delta = dstar - gLg F_m
      double delta = 0, Fm = 0;
      bool   found  = false;
      auto   branch = [&](double alpha, double beta, double lo, double hi) {
        if (found)
          return;
        const double d = (dstar - gLg * beta) / (1 + gLg * alpha);
        const double x = d - m.et;
        if (x >= lo && x <= hi)
          delta = d, Fm = alpha * d + beta, found = true;
      };
      branch(m.km + c2h, -m.km * (m.et + b) + damp0, b, HUGE_VAL);           // drive flank
      branch(always_damped ? c2h : 0.0, always_damped ? damp0 : 0.0, -b, b); // no contact
      branch(m.km + c2h, -m.km * (m.et - b) + damp0, -HUGE_VAL, -b);         // coast flank
      if (!found) // the root sits in the damping force's jump at a boundary: stay there
        {
          const double x = dstar - m.et > 0 ? b : -b;
          delta = m.et + x, Fm = (dstar - delta) / gLg;
        }
      const PairVector dq = dqs - Lg * Fm; // the increment: no cancellation against q
      const PairVector an = 4 / (h * h) * (dq - h * v) - a;
      v += h / 2 * (a + an);
      q += dq;
      a = an;
      if (n % every == 0)
        record(model, o, t, q, v, out);
    }
  out.steps = std::size_t(steps_total);
  return out;
}
} // namespace

Trajectory
simulate(const PairModel &model, const PairVector &q0, const PairVector &v0, const RunOptions &o)
{
  auto require = [](bool ok, const std::string &what, double value, const std::string &allowed) {
    require_value(ok, "pair dynamics", what, value, allowed);
  };
  require(o.omega > 0 && std::isfinite(o.omega), "pinion speed [rad/s]", o.omega, "> 0");
  require(o.mesh_cycles > 0, "mesh cycles", o.mesh_cycles, "> 0");
  require(o.samples_per_cycle >= 1, "samples per mesh cycle", o.samples_per_cycle, ">= 1");
  require(o.relative_tolerance > 0 && o.absolute_tolerance > 0, "tolerance",
          std::min(o.relative_tolerance, o.absolute_tolerance), "> 0");
  require(o.steps_per_cycle >= o.samples_per_cycle, "Newmark steps per mesh cycle",
          o.steps_per_cycle, ">= the output samples per mesh cycle");
  require(q0.allFinite() && v0.allFinite(), "initial state (finite)", 0, "finite values");
  return o.method == Integrator::newmark ? run_newmark(model, q0, v0, o)
                                         : run_cvode(model, q0, v0, o);
}
} // namespace gearkit

#include "loaded_contact.h"

#include "contact_solver.h"

#include <algorithm>
#include <sstream>

namespace gearkit
{
LoadedPosition
loaded_contact(const UnloadedTca &tca, const TcaPosition &position, double torque,
               const LoadedContactOptions &o, const StructuralCompliance &pinion,
               const StructuralCompliance &gear)
{
  if (!(torque >= 0) || !std::isfinite(torque))
    throw InputError("loaded contact: the pinion torque must be finite and >= 0 (got " +
                     std::to_string(torque) + " N m)");
  LoadedPosition out;
  out.pinion_angle = position.pinion_angle;
  out.e0           = position.transmission_error;
  out.torque       = torque;
  out.cells        = contact_cells(tca, position, o.cells);
  if (o.covered)
    {
      for (const PairContact &c : position.pairs)
        if (c.found && c.separation <= tca.options_data().contact_tolerance &&
            !o.covered(c.pinion_tooth, c.gear_tooth))
          throw InputError("loaded contact: pinion tooth " + std::to_string(c.pinion_tooth) +
                           " and gear tooth " + std::to_string(c.gear_tooth) +
                           " touch but the finite-element segments do not cover them; use more "
                           "segment teeth");
      out.cells.erase(std::remove_if(out.cells.begin(), out.cells.end(),
                                     [&](const ContactCell &c) {
                                       return !o.covered(c.pinion_tooth, c.gear_tooth);
                                     }),
                      out.cells.end());
    }
  if (out.cells.empty())
    {
      std::ostringstream msg;
      msg << "loaded contact: no contact cell within the gap band ("
          << o.cells.gap_band * 1e6 << " um) at pinion angle " << position.pinion_angle
          << " rad";
      throw InputError(msg.str());
    }

  if (o.table_parameters)
    for (ContactCell &c : out.cells)
      o.table_parameters(c);
  const Eigen::Index n = Eigen::Index(out.cells.size());
  ContactProblem     p;
  p.compliance.resize(n, n);
  p.gap.resize(n);
  p.lever.resize(n);
  p.load            = torque;
  const double Estar = contact_modulus(o.pinion_material, o.gear_material);
  for (Eigen::Index i = 0; i < n; ++i)
    {
      const ContactCell &ci = out.cells[i];
      p.gap[i]              = ci.gap;
      p.lever[i]            = ci.lever;
      for (Eigen::Index j = 0; j < n; ++j)
        {
          const ContactCell &cj = out.cells[j];
          double             c  = pinion(ci, cj) + gear(ci, cj);
          if (o.half_space && ci.pair == cj.pair)
            c += rectangle_displacement(cj.s - ci.s, cj.t - ci.t, ci.ds / 2, ci.dt / 2, 1.0, Estar);
          p.compliance(j, i) = c;
        }
    }
  // Maxwell-Betti: the exact compliance is symmetric; interpolation is not quite.
  p.compliance = (p.compliance + p.compliance.transpose()).eval() / 2;

  if (torque == 0)
    {
      out.eL = out.e0; // nothing moves; the cells' first touch only samples the gap
      out.force = Eigen::VectorXd::Zero(n);
      out.pair_force.assign(position.pairs.size(), 0.0);
      return out;
    }
  const ContactSolution s = solve_contact(p);
  const double sign = tca.options_data().side == FlankSide::drive ? 1.0 : -1.0;
  out.force        = s.force;
  out.active_cells = s.active;
  out.iterations   = s.iterations;
  out.eL           = out.e0 + sign * s.approach;
  out.pair_force.assign(position.pairs.size(), 0.0);
  for (Eigen::Index i = 0; i < n; ++i)
    out.pair_force[out.cells[i].pair] += s.force[i];
  out.normal_force = s.force.sum();
  // e_L - e_0 = the approach: pinion rotation beyond the unloaded position, gear held.
  out.lever          = torque / out.normal_force;
  out.mesh_stiffness = out.normal_force / (out.lever * s.approach);
  return out;
}
} // namespace gearkit

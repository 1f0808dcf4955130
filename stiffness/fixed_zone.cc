#include "stiffness/fixed_zone.h"

#include "stiffness/contact_solver.h"

#include <cmath>
#include <sstream>

namespace gearkit
{
FixedZone::FixedZone(const UnloadedTca &tca, const TcaPosition &position, double torque,
                     const LoadedContactOptions &options, const StructuralCompliance &pinion,
                     const StructuralCompliance &gear, double widening)
    : tca(&tca)
    , at(position)
{
  if (!(widening >= 1) || !std::isfinite(widening))
    throw InputError("fixed contact zone: the widening must be finite and >= 1 (got " +
                     std::to_string(widening) + ")");
  // The zone fitted to the pair's own contact, then widened across (a band k^2 times as
  // large reaches k times as far: sqrt(2 g / k_max)).
  const LoadedPosition fitted = loaded_contact(tca, position, torque, options, pinion, gear);
  LoadedContactOptions o      = options;
  o.adapt_band                = false;
  o.cells.gap_band            = fitted.gap_band * widening * widening;
  o.cells.cells_across        = int(std::ceil(o.cells.cells_across * widening)) | 1;
  // Pairs standing apart that the pair's own approach, `widening` times larger, would close.
  const double approach = std::abs(fitted.eL - fitted.e0);
  for (const PairContact &c : position.pairs)
    if (c.found && c.separation <= widening * approach * pinion_lever(c.position, c.normal_pinion))
      o.cells.pair_gap = std::max(o.cells.pair_gap, c.separation * (1 + 1e-9));
  zone_cells              = loaded_cells(tca, position, o);
  const Eigen::MatrixXd C = zone_compliance(zone_cells, o, pinion, gear);
  if (!C.allFinite())
    throw InputError("fixed contact zone: the compliance of the cells is not finite");
  compliance           = (C + C.transpose()) / 2; // Maxwell-Betti, as solve_loaded_contact
  const Eigen::Index n = Eigen::Index(zone_cells.size());
  gap.resize(n), lever.resize(n);
  lever_slope.resize(n, 2);
  const FlankSide side = tca.options_data().side;
  for (Eigen::Index i = 0; i < n; ++i)
    {
      const ContactCell &c = zone_cells[std::size_t(i)];
      gap[i] = c.gap, lever[i] = c.lever;
      // lever = |a . n| with a = e_z x r; the normal tilted by the deviation's surface gradient
      // J (J^T J)^-1 (d_u, d_v) moves it by -sign(a . n) a . J (J^T J)^-1 (d_u, d_v).
      const FlankPoint f = tca.pinion_flanks().flank(c.pinion_tooth, side).evaluate(c.u1, c.v1);
      Eigen::Matrix<double, 3, 2> J;
      J.col(0)       = tca.assembly_data().pinion_vector_to_global(f.d_du, position.pinion_angle);
      J.col(1)       = tca.assembly_data().pinion_vector_to_global(f.d_dv, position.pinion_angle);
      const Vec3   a = Vec3::UnitZ().cross(c.position);
      const double sign_a = a.dot(c.normal) >= 0 ? 1.0 : -1.0;
      lever_slope.row(i) =
          -sign_a * (J.transpose() * J).ldlt().solve(J.transpose() * a).transpose();
    }
  own          = solve(Eigen::VectorXd::Zero(n), torque, position.transmission_error);
  own.gap_band = o.cells.gap_band;
  own_active   = warm_start(own);
  std::vector<char> has_cells(position.pairs.size(), 0);
  for (const ContactCell &c : zone_cells)
    has_cells[std::size_t(c.pair)] = 1;
  for (std::size_t k = 0; k < position.pairs.size(); ++k)
    if (position.pairs[k].found && !has_cells[k])
      outside.push_back(
          {position.pairs[k].separation,
           pinion_lever(position.pairs[k].position, position.pairs[k].normal_pinion)});
}

ActiveSetFactor
FixedZone::warm_start(const LoadedPosition &p) const
{
  // The cells in contact, the most loaded first: those that leave for a similar variant are
  // the lightly loaded ones at the contact's edges, at the factor's end where removing them
  // costs least.
  if (p.force.size() != gap.size())
    throw InputError("fixed contact zone: a warm start needs a contact on this zone's cells");
  std::vector<Eigen::Index> loaded;
  for (Eigen::Index i = 0; i < p.force.size(); ++i)
    if (p.force[i] > 0)
      loaded.push_back(i);
  std::stable_sort(loaded.begin(), loaded.end(),
                   [&p](Eigen::Index a, Eigen::Index b) { return p.force[a] > p.force[b]; });
  return ActiveSetFactor(compliance, loaded);
}

LoadedPosition
FixedZone::solve(const Eigen::VectorXd &added, double torque, double e0,
                 const Eigen::MatrixX2d *pinion_slope, const ActiveSetFactor *start,
                 double turned) const
{
  const Eigen::Index n = gap.size();
  if (added.size() != n || !added.allFinite())
    {
      std::ostringstream msg;
      msg << "fixed contact zone: the added material must be finite, one entry per cell (got "
          << added.size() << " entries for " << n << " cells)";
      throw InputError(msg.str());
    }
  if (!(torque >= 0) || !std::isfinite(torque))
    throw InputError("fixed contact zone: the pinion torque must be finite and >= 0 (got " +
                     std::to_string(torque) + " N m)");
  if (pinion_slope && (pinion_slope->rows() != n || !pinion_slope->allFinite()))
    throw InputError("fixed contact zone: the pinion's deviation slopes must be finite, one row "
                     "per cell");
  const double          sign = tca->options_data().side == FlankSide::drive ? 1.0 : -1.0;
  const Eigen::VectorXd g    = gap - added;
  Eigen::VectorXd       arm  = lever;
  if (pinion_slope)
    arm += (lever_slope.array() * pinion_slope->array()).rowwise().sum().matrix();
  if (!(arm.minCoeff() > 0))
    throw InputError("fixed contact zone: a deviation's slope turns a cell's normal away from "
                     "the pinion's rotation (a moment arm <= 0); slopes of micrometre "
                     "deviations are far smaller");
  if (!std::isfinite(turned))
    throw InputError("fixed contact zone: the gear's turn must be finite");
  // The position the pinion rotates from: the gear turned on by `turned`.
  TcaPosition from = at;
  from.transmission_error += turned;
  // The variant's first touch: rotation beyond that position's gear angle [rad].
  const double first_touch =
      std::isnan(e0) ? g.cwiseQuotient(arm).minCoeff() : sign * (e0 - from.transmission_error);
  if (!std::isfinite(first_touch))
    throw InputError("fixed contact zone: the variant's unloaded TE must be finite");
  ContactSolution s;
  if (torque > 0)
    s = solve_contact(compliance, g, arm, torque, start ? *start : own_active);
  LoadedPosition r = loaded_position(*tca, from, torque, zone_cells, s, first_touch);
  r.gap_band       = own.gap_band;
  for (const auto &[separation, arm_outside] : outside)
    if ((s.approach + sign * turned) * arm_outside > separation)
      r.zone_edge_reached = true; // a pair without cells would touch
  return r;
}
} // namespace gearkit

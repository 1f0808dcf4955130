#include "stiffness/fixed_zone.h"

#include "stiffness/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace gearkit
{
namespace
{
/// Each loaded cell's depth inside its pair's contact, in cells: the distance (the larger of
/// its parts across and along the line, each in the cell's own size) to the nearest unloaded
/// cell of its pair, at most the distance to the pair's first or last column and half a cell
/// on an edge of a flank or of the zone; 0 where unloaded.
std::vector<double>
contact_depth(const std::vector<ContactCell> &cells, const Eigen::VectorXd &force)
{
  std::map<int, std::pair<double, double>> along; // each pair's cells' extent in t
  for (const ContactCell &c : cells)
    {
      auto &[lo, hi] = along.try_emplace(c.pair, c.t, c.t).first->second;
      lo = std::min(lo, c.t), hi = std::max(hi, c.t);
    }
  std::vector<double> depth(cells.size(), 0);
  for (std::size_t a = 0; a < cells.size(); ++a)
    {
      if (!(force[Eigen::Index(a)] > 0))
        continue;
      const ContactCell &c = cells[a];
      const auto [t0, t1]  = along.at(c.pair);
      double d = c.flank_edge || c.zone_edge ? 0.5 : std::min(c.t - t0, t1 - c.t) / c.dt + 0.5;
      for (std::size_t b = 0; b < cells.size() && d > 0.5; ++b)
        if (cells[b].pair == c.pair && !(force[Eigen::Index(b)] > 0))
          d = std::min(
              d, std::max(std::abs(cells[b].s - c.s) / c.ds, std::abs(cells[b].t - c.t) / c.dt));
      depth[a] = d;
    }
  return depth;
}
} // namespace

FixedZone::FixedZone(const UnloadedTca &tca, const TcaPosition &position, double torque,
                     const LoadedContactOptions &options, const StructuralCompliance &pinion,
                     const StructuralCompliance &gear, double widening)
    : tca(&tca)
    , at(position)
    , gear_compliance(gear)
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
  gear_motion.resize(n, 2);
  const FlankSide     side        = tca.options_data().side;
  double              least_width = HUGE_VAL, most_slide = 0;
  std::vector<double> ratio;
  for (Eigen::Index i = 0; i < n; ++i)
    {
      const ContactCell &c = zone_cells[std::size_t(i)];
      gap[i] = c.gap, lever[i] = c.lever;
      // The gear turned by 1 rad moves its material at the cell by w = e_z x P (its frame):
      // the normal part per moment arm is the gear's turn per pinion rotation; the tangential
      // part brings the material of the flank parameters (u2, v2) - G w to the cell, G =
      // (J^T J)^-1 J^T.
      const FlankPoint b = tca.gear_flanks().flank(c.gear_tooth, side).evaluate(c.u2, c.v2);
      Eigen::Matrix<double, 3, 2> Jg;
      Jg << b.d_du, b.d_dv;
      const Vec3            w     = Vec3::UnitZ().cross(b.position);
      const Eigen::Vector2d moved = (Jg.transpose() * Jg).ldlt().solve(Jg.transpose() * w);
      gear_motion.row(i)          = -moved.transpose();
      most_slide                  = std::max(most_slide, (Jg * moved).norm());
      least_width                 = std::min(least_width, c.ds);
      ratio.push_back(w.dot(b.normal) / c.lever);
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
  std::nth_element(ratio.begin(), ratio.begin() + long(ratio.size() / 2), ratio.end());
  gear_per_pinion = ratio.empty() ? 0.0 : ratio[ratio.size() / 2];
  slide_per_turn  = n > 0 ? most_slide / least_width : 0.0;
  own             = solve(Eigen::VectorXd::Zero(n), torque, position.transmission_error);
  own.gap_band    = o.cells.gap_band;
  own_active      = warm_start(own);
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
  // The cells in contact, the deepest inside the contact first: those that leave for a
  // similar variant lie at the contact's edges (across the line, and along it where a helix
  // slope unloads a face end), at the factor's end where removing them costs least; among
  // cells as deep, the most loaded first.
  if (p.force.size() != gap.size())
    throw InputError("fixed contact zone: a warm start needs a contact on this zone's cells");
  const std::vector<double> depth = contact_depth(zone_cells, p.force);
  std::vector<Eigen::Index> loaded;
  for (Eigen::Index i = 0; i < p.force.size(); ++i)
    if (p.force[i] > 0)
      loaded.push_back(i);
  std::stable_sort(loaded.begin(), loaded.end(), [&](Eigen::Index a, Eigen::Index b) {
    const double da = depth[std::size_t(a)], db = depth[std::size_t(b)];
    return da != db ? da > db : p.force[a] > p.force[b];
  });
  return ActiveSetFactor(compliance, loaded);
}

LoadedPosition
FixedZone::solve(const Eigen::VectorXd &added, double torque, double e0,
                 const Eigen::MatrixX2d *pinion_slope, const ActiveSetFactor *start, double turned,
                 bool turned_gear_compliance) const
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
  if (torque > 0 && turned != 0 && turned_gear_compliance)
    {
      if (!(std::abs(gear_per_pinion) > 0))
        throw InputError("fixed contact zone: the gear's turn does not move the cells along "
                         "their normals (a zone off the flanks?)");
      const double gear_turn = sign * turned / gear_per_pinion;
      if (std::abs(gear_turn) * slide_per_turn > gear_slide_tolerance)
        s = gear_turned(s, g, arm, torque, gear_turn);
    }
  LoadedPosition r = loaded_position(*tca, from, torque, zone_cells, s, first_touch);
  r.gap_band       = own.gap_band;
  for (const auto &[separation, arm_outside] : outside)
    if ((s.approach + sign * turned) * arm_outside > separation)
      r.zone_edge_reached = true; // a pair without cells would touch
  return r;
}

ContactSolution
FixedZone::gear_turned(const ContactSolution &s, const Eigen::VectorXd &g,
                       const Eigen::VectorXd &arm, double torque, double gear_turn) const
{
  const Eigen::Index        n     = g.size();
  const double              scale = std::max(g.cwiseAbs().maxCoeff(), 1e-9);
  std::vector<char>         in(std::size_t(n), 0);
  std::vector<Eigen::Index> S;
  for (Eigen::Index j = 0; j < n; ++j)
    if (s.force[j] > 0)
      S.push_back(j), in[std::size_t(j)] = 1;
  for (int pass = 0; pass < 50; ++pass)
    {
      // the compliance over S, its gear part read where the turned gear's material lies
      const auto               k = Eigen::Index(S.size());
      std::vector<ContactCell> was(S.size()), now(S.size());
      Eigen::MatrixXd          C(k, k);
      Eigen::VectorXd          gS(k), armS(k);
      for (Eigen::Index a = 0; a < k; ++a)
        {
          const Eigen::Index j = S[std::size_t(a)];
          was[std::size_t(a)] = now[std::size_t(a)] = zone_cells[std::size_t(j)];
          now[std::size_t(a)].table_u2 += gear_turn * gear_motion(j, 0);
          now[std::size_t(a)].table_v2 += gear_turn * gear_motion(j, 1);
          gS[a] = g[j], armS[a] = arm[j];
          for (Eigen::Index b = 0; b < k; ++b)
            C(b, a) = compliance(S[std::size_t(b)], j);
        }
      const Eigen::MatrixXd D = gear_compliance.matrix(now) - gear_compliance.matrix(was);
      C += (D + D.transpose()) / 2;
      if (!C.allFinite())
        throw InputError("fixed contact zone: the gear's compliance where its turned material "
                         "lies is not finite");
      const ContactSolution r = solve_contact(C, gS, armS, torque, std::vector<char>(S.size(), 1));
      // the cells outside S on their rows as they were
      Eigen::VectorXd h = r.approach * arm - g;
      for (Eigen::Index a = 0; a < k; ++a)
        if (r.force[a] != 0)
          h.noalias() -= compliance.col(S[std::size_t(a)]) * r.force[a];
      std::vector<Eigen::Index> join;
      for (Eigen::Index j = 0; j < n; ++j)
        if (!in[std::size_t(j)] && h[j] > 1e-12 * scale)
          join.push_back(j);
      if (join.empty())
        {
          ContactSolution out;
          out.force      = Eigen::VectorXd::Zero(n);
          out.approach   = r.approach;
          out.active     = r.active;
          out.iterations = s.iterations + r.iterations;
          out.active_set.assign(std::size_t(n), 0);
          for (Eigen::Index a = 0; a < k; ++a)
            {
              out.force[S[std::size_t(a)]]                   = r.force[a];
              out.active_set[std::size_t(S[std::size_t(a)])] = r.force[a] > 0;
            }
          out.penetration = r.penetration;
          for (Eigen::Index j = 0; j < n; ++j)
            if (!in[std::size_t(j)])
              out.penetration = std::max(out.penetration, h[j]);
          return out;
        }
      for (const Eigen::Index j : join)
        S.push_back(j), in[std::size_t(j)] = 1;
    }
  throw InputError("fixed contact zone: the contact on the turned gear's compliance did not "
                   "settle");
}
} // namespace gearkit

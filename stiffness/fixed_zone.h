// The loaded contact of one mesh position on a cell zone fixed once for many variants of a pair
// that differ from it only by micrometre deviations along the flank normals (micro-geometry
// designs, tolerance samples): the finite-element compliance of a member does not change with
// them, so the cells and their compliance matrix are built once, and a variant only changes
// the cells' unloaded gaps (first order: by the material its deviations add at each cell on
// either flank) and solves the contact again, warm-started from the pair's own active set.
//
// The zone is the one loaded_contact fits to the pair at a torque, widened across the contact
// line so that the variants' contacts (narrower or wider, shifted by the modifications' slopes)
// stay inside it, and with cells on the pairs standing apart that a `widening` times larger
// approach would close. A variant whose contact reaches the zone's outermost row, or whose
// approach closes a pair without cells, says so (LoadedPosition::zone_edge_reached): then the
// zone is too narrow for it.
#pragma once

#include "stiffness/contact_solver.h"
#include "stiffness/loaded_contact.h"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace gearkit
{
class FixedZone
{
public:
  /// The zone loaded_contact fits to `torque` at `position` of `tca` (the pair the variants
  /// deviate from, usually without modifications), `widening` (>= 1) times as wide across the
  /// contact line: its gap band widening^2 times, as many more cells across (cells of the same
  /// size). Throws InputError as loaded_contact does.
  FixedZone(const UnloadedTca &tca, const TcaPosition &position, double torque,
            const LoadedContactOptions &options, const StructuralCompliance &pinion,
            const StructuralCompliance &gear, double widening = 2);

  const std::vector<ContactCell> &
  cells() const
  {
    return zone_cells;
  }
  /// The pair's own contact on the zone at the torque it was fitted to.
  const LoadedPosition &
  nominal() const
  {
    return own;
  }
  const TcaPosition &
  position() const
  {
    return at;
  }

  /// A variant's loaded contact under a pinion torque: `added` is the material both members'
  /// deviations add at each cell, along the normals [m] (> 0 closes the gap); `e0` the variant's
  /// unloaded TE at this pinion angle [rad] (from its own TCA; NaN: the first touch of the
  /// cells, min (gap - added) / lever, a lower estimate by up to the gap across half a cell).
  /// `pinion_slope` (optional, one row per cell): the derivatives of the pinion's deviation by
  /// its flank parameters (d/du1, d/dv1) [m]; they tilt the pinion's normal, the direction of
  /// the contact force, and so change each cell's moment arm at first order (a tip relief's
  /// slope of 1/200 by up to half a percent). Thread-safe. Throws InputError for sizes other
  /// than the cells' and non-finite entries.
  /// `start` (optional): the cells to start the active set from, factorised (warm_start of a
  /// similar variant's contact); by default the pair's own. The solution does not depend on it.
  /// `turned` [rad, TE]: the part of the unloaded TE beyond this position's that `added`
  /// already holds as the gear's turn (the variant's members meeting at e0 as its TCA turns
  /// them); the pinion's rotation, with the moment arms, starts from there. The gear's
  /// material then lies at the cells from flank parameters a turn of turned / turn_per_rotation()
  /// further on: where that slide passes gear_slide_tolerance of the cells' size across, the
  /// gear's compliance is read there again over the cells in contact and the contact solved on
  /// it (a 50 um tip relief turns the gear by 0.6 mrad at the FZG pair: 31 um, most of a cell,
  /// and its tooth's compliance along the profile moved the TE by up to 0.5 urad);
  /// `turned_gear_compliance` false keeps the compliance as it is (faster).
  LoadedPosition
  solve(const Eigen::VectorXd &added, double torque,
        double                  e0           = std::numeric_limits<double>::quiet_NaN(),
        const Eigen::MatrixX2d *pinion_slope = nullptr, const ActiveSetFactor *start = nullptr,
        double turned = 0, bool turned_gear_compliance = true) const;
  /// A warm start for solve from a contact `p` on this zone's cells (a variant's solution): its
  /// cells in contact, their compliance factorised, the deepest inside the contact first (then
  /// the most loaded): those a similar variant unloads come last, where removing them is cheap.
  ActiveSetFactor
  warm_start(const LoadedPosition &p) const;

  /// The gear's turn about its axis [rad] per unit pinion rotation along the line of action
  /// at the cells (the median over them of the normal motion per gear turn over the moment
  /// arm: -z2/z1 r_b2 / r_b1 for an involute pair).
  double
  turn_per_rotation() const
  {
    return gear_per_pinion;
  }
  /// The gear's slide at the cells, as a share of their size across, below which its
  /// compliance is not read again (solve): a slide of 5 % of a cell moves the approach by
  /// about 1e-5 of itself on the FZG pair (the slide's effect grows with it).
  static constexpr double gear_slide_tolerance = 0.05;

private:
  /// The contact `s` solved again on the compliance with the gear's part read where its
  /// material lies after a turn by `gear_turn` [rad] (the cells in contact, and those that
  /// join, only; the others' rows as they were).
  ContactSolution
  gear_turned(const ContactSolution &s, const Eigen::VectorXd &g, const Eigen::VectorXd &arm,
              double torque, double gear_turn) const;

  const UnloadedTca       *tca;
  TcaPosition              at;
  std::vector<ContactCell> zone_cells;
  Eigen::MatrixXd          compliance; ///< symmetric [m/N]
  Eigen::VectorXd          gap, lever;
  /// d lever / d (du1, dv1) of the pinion's deviation at each cell [1]: the moment arm of the
  /// tilted normal n - J (J^T J)^-1 grad delta, J = the flank's tangents.
  Eigen::MatrixX2d lever_slope;
  LoadedPosition   own;
  ActiveSetFactor  own_active; ///< the warm start: the pair's own active set, factorised
  /// The pairs of the position without cells: separation [m] and lever [m].
  std::vector<std::pair<double, double>> outside;
  /// The gear's compliance (its table outlives the zone), the change of each cell's gear
  /// flank parameters (u2, v2) per unit gear turn (its material's, at the cell), the largest
  /// material slide per unit gear turn over the cells' least size across [1/rad].
  StructuralCompliance gear_compliance;
  Eigen::MatrixX2d     gear_motion;
  double               slide_per_turn  = 0;
  double               gear_per_pinion = 0;
};
} // namespace gearkit

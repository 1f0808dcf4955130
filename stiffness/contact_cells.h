// The potential contact zone of one mesh position, discretised for the loaded contact: around
// each tooth pair's unloaded contact point, a grid of rectangular cells in the common tangent
// plane (t along the contact line = the direction of least relative curvature, s across it),
// projected onto the pinion flank. Each cell knows its place on both flanks, its unloaded gap
// (from the TCA's touch angle at that pinion point) and its moment arm about the pinion axis.
#pragma once

#include "tca/unloaded_tca.h"

#include <cmath>
#include <vector>

namespace gearkit
{
struct ContactCellOptions
{
  int cells_across = 17; ///< cells across the contact line (s); odd: a row on the line
  int cells_along  = 24; ///< cells along it (t), over the flank
  /// Grading of the columns along the line towards an end at a flank's edge (a face end, a tip)
  /// that the contact reaches, where a line contact's pressure peaks: 0 uniform; 1 cosine
  /// spacing (both ends at flank edges: the edge column 1 - cos(pi / n) over 2 of the extent,
  /// 0.1 of a uniform one at 24 columns; one end: a quarter cosine towards it). Between: the
  /// blend, and so for an end whose gap lies between a quarter of gap_band and gap_band.
  double along_grading = 0;
  /// Largest unloaded gap the zone covers [m], measured from each pair's own contact point:
  /// the band across the line reaches where the relative curvature opens the gap to this
  /// (s = sqrt(2 g / k_max)), and along the line where the gap on the line (crowning, a
  /// point contact) opens to twice this; choose it above the local elastic approach expected
  /// (loaded_contact sets it from the load).
  double gap_band = 10e-6;
  /// Pairs standing apart by up to max(gap_band, pair_gap) [m] get cells (a pair further apart
  /// than the zone's band can still touch under a load whose approach exceeds its separation).
  double pair_gap = 0;
  /// Set the contact line's direction and the zone's width from a quadratic fitted to the
  /// unloaded gaps about each contact point (where it disagrees with the local curvature), not
  /// from the local curvature alone: for measured flanks, whose curvature at a point carries the
  /// measurement's noise. Exact flanks keep their exact curvature.
  bool zone_from_gaps = false;
};

struct ContactCell
{
  int    pair         = 0; ///< index into TcaPosition::pairs
  int    column       = 0; ///< index along the contact line (0 ... cells_along - 1)
  int    pinion_tooth = 0, gear_tooth = 0;
  double u1 = 0, v1 = 0, u2 = 0, v2 = 0; ///< flank parameters on pinion and gear
  Vec3   position = Vec3::Zero();        ///< pinion flank point, global [m]
  Vec3   normal   = Vec3::Zero();        ///< pinion outward normal, global
  double gap      = 0;                   ///< unloaded normal gap to the gear flank [m]
  double lever    = 0;                   ///< normal motion per pinion rotation, |(e_z x r) . n| [m]
  /// Flank parameters of the cell in the structural compliance tables (the theoretical
  /// flanks'): the same as u1, v1, u2, v2 unless the flanks are measured ones.
  double table_u1 = 0, table_v1 = 0, table_u2 = 0, table_v2 = 0;
  double s = 0, t = 0;   ///< centre in the pair's tangent plane [m]
  double ds = 0, dt = 0; ///< cell size [m]
  /// In the outermost row across of a zone the gap band cut short of the flank: contact here
  /// means the zone is too narrow for the load.
  bool zone_edge = false;
  /// At an edge of either flank (tip, face end, start of the working flank): the cell's side
  /// on the edge; contact here is edge contact, whose pressure the half-space does not bound.
  bool flank_edge = false;
};

/// Normal motion of a pinion flank point per unit pinion rotation, |(e_z x r) . n| [m]: the
/// moment arm of a normal force there about the pinion axis (global point and normal).
inline double
pinion_lever(const Vec3 &position, const Vec3 &normal)
{
  return std::abs(Vec3::UnitZ().cross(position).dot(normal));
}

/// Cells of every pair of `position` that touches or stands within the gap band. Where an edge
/// of either flank (or where the gear flank cannot reach the pinion point) crosses the band,
/// a column's cells share its part on the flanks equally (the same number across), so the
/// zone follows the contact line continuously to the tips.
std::vector<ContactCell>
contact_cells(const UnloadedTca &tca, const TcaPosition &position,
              const ContactCellOptions &options = {});
} // namespace gearkit

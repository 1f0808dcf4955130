// A misalignment check (a V-H check for bevel pairs): one pair over a grid of assembly
// misalignments (offset E, axial shifts P and G, shaft angle, crossing angle, centre distance)
// on its members' compliance, computed once: a misalignment moves the members, not their
// material, so the finite-element compliance tables serve every grid point. Per point the
// unloaded TCA (e_0, the contact path) and the loaded contact over a mesh cycle (e_L, K_m,
// the contact pattern on the gear flank: where the marking compound of a V-H test would wear).
#pragma once

#include "stiffness/loaded_contact.h"
#include "study/parameter_grid.h"
#include "tca/unloaded_tca.h"

#include <functional>
#include <memory>

namespace gearkit
{
/// The Misalignment fields a grid can vary, by the names results use: offset,
/// centre_distance_error, crossing_angle, intersecting_angle, pinion_axial_shift,
/// gear_axial_shift (SI: m, rad).
const std::vector<std::string> &
misalignment_field_names();

/// The field of a name; throws InputError naming the known ones.
double Misalignment::       *
misalignment_field(const std::string &name);

/// Grid point g's misalignment: `base` with each axis's field at its value.
Misalignment
grid_misalignment(const ParameterGrid &grid, std::size_t g, Misalignment base);

struct MisalignmentStudyOptions
{
  std::vector<double> torques;        ///< pinion torques of the loaded contact [N m], > 0
  int                 positions = 16; ///< loaded positions per mesh cycle, >= 4
  /// The contact pattern's raster over the gear flank's parameter domain: bins along the
  /// profile (u) and the face (v).
  int profile_bins = 16, face_bins = 40;
};

/// One grid point: the pair in one misaligned assembly.
struct MisalignedMesh
{
  /// Unloaded TE over the TCA's positions (its options: positions per mesh cycle, cycles; one
  /// cycle where every tooth of both members is alike, MemberFlanks::teeth_alike) and its
  /// peak-to-peak [rad, pinion]; the pinion angles of those positions [rad].
  std::vector<double> unloaded_te, tca_pinion_angle;
  double              unloaded_peak_to_peak = 0;
  /// The unloaded contact path on the gear flank: the leading pair's contact at each TCA
  /// position as gear flank parameters (u, v) [P][2] (flank_lengths: as lengths), and its
  /// centre (the mean).
  std::vector<double> path;
  double              path_centre[2] = {0, 0};
  /// The loaded contact at the study's torques (its positions; cell_gear holds each cell's
  /// gear flank parameters).
  MeshCycleContact loaded;
  /// Per torque [M]: e_L peak-to-peak [rad], K_m mean [N/m], the largest pressure and the
  /// largest off the flanks' edges [Pa] and edge-load share over the cycle.
  std::vector<double> loaded_peak_to_peak, stiffness_mean, max_pressure, max_interior_pressure,
      max_edge_share;
  /// The contact pattern per torque: the largest pressure over the cycle in each bin of the
  /// gear flank's domain [M][profile_bins][face_bins] [Pa]; its centre (pressure-weighted
  /// mean of the loaded cells' gear flank parameters) [M][2] (u, v) and its extent (the
  /// loaded cells' u min, u max, v min, v max) [M][4].
  std::vector<double> pattern, pattern_centre, pattern_extent;
};

/// The pair `pinion`, `gear` assembled by `assembly`, analysed with `tca`, loaded as `contact`
/// says on the members' compliances. The pattern raster spans `gear_domain` (the gear's working
/// flank's parameter domain). Throws InputError where the TCA or the loaded contact at some
/// torque fails (the message names the torque).
MisalignedMesh
misaligned_mesh(std::shared_ptr<const MemberFlanks> pinion,
                std::shared_ptr<const MemberFlanks> gear, const Assembly &assembly,
                const TcaOptions &tca, const LoadedContactOptions &contact,
                const StructuralCompliance     &pinion_compliance,
                const StructuralCompliance     &gear_compliance,
                const MisalignmentStudyOptions &options);

/// Flank parameters (u, v) of a member as lengths [m]: (profile, face). Involute: the roll
/// length r_b u and z; spiral bevel: the height above the pitch cone and the cone distance from
/// the mean (its parameters already); other members: (u, v) as they are.
std::pair<double, double>
flank_lengths(const MemberFlanks &member, double u, double v);
} // namespace gearkit

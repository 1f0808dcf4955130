// The seed paper's discrete-point STE, implemented literally ("paper mode"), so that its cost and
// accuracy can be measured against the exact contact analysis:
//
// dense point clouds are sampled from the (interpolated) flanks at spacing a x b; for each driver
// angle the driven member is rotated in steps theta until the minimum distance between the two
// clouds falls within the contact tolerance E >= sqrt((a/2)^2 + (b/2)^2 + l^2), l = r theta; then
// STE(i) = (theta_p(i) - theta_p(1)) - (Z_g / Z_p) (theta_g(i) - theta_g(1)).
// Nearest-point queries use nanoflann KD-trees of the driven flanks' clouds.
#pragma once

#include "tca/unloaded_tca.h"

#include <functional>
#include <vector>

namespace gearkit
{
struct PaperModeOptions
{
  FlankSide side          = FlankSide::drive;
  double    spacing       = 20e-6; ///< target point spacing a = b on the flanks [m]
  double    rotation_step = 1e-6;  ///< driven-member rotation step theta [rad]
  /// Contact tolerance E [m]; 0 = the smallest admissible, sqrt((a/2)^2 + (b/2)^2 + l^2). A
  /// smaller E is refused (clouds could pass through each other between points).
  double                tolerance          = 0;
  int                   positions_per_mesh = 50;
  int                   mesh_cycles        = 1;
  double                start_angle        = 0;
  std::function<void()> on_position; ///< called after each position (progress)
};

struct PaperModeResult
{
  /// The same tables as classical TCA: per position e_0 = phi - (z2/z1) psi (absolute, with psi
  /// the first gear angle within E, so it carries the method's early-contact bias) and per pair
  /// the closest points of the clouds (contact point on the pinion cloud, parameters, normals and
  /// moment arms of the flanks there; separation = cloud distance, touching if within E).
  TcaResult           tca;
  std::vector<double> seed_ste;      ///< the seed's STE, relative to the first position [rad]
  double              tolerance = 0; ///< E [m]
  std::size_t         points    = 0; ///< points in all clouds built
  std::size_t         queries   = 0; ///< nearest-point queries made
};

PaperModeResult
paper_mode_ste(const MemberFlanks &pinion, const MemberFlanks &gear, double centre_distance,
               const Misalignment &misalignment, const PaperModeOptions &options);
/// The same in any assembly (e.g. Assembly::bevel).
PaperModeResult
paper_mode_ste(const MemberFlanks &pinion, const MemberFlanks &gear, const Assembly &assembly,
               const PaperModeOptions &options);
} // namespace gearkit

// The loaded mesh cycle of many variants of one involute pair on one compliance: variants
// differ from the pair by their flank modifications (micro-geometry designs, tolerance samples),
// which do not change the members' finite-element compliance. Per (torque, mesh position) the
// cell zone and its compliance matrix are built once (stiffness/fixed_zone.h) on the pair
// without modifications; a variant adds its modifications' material at the cells (first order
// in the deviations along the normals) and solves the contact again; its unloaded TE comes
// from its own TCA on the modified flanks (exact).
#pragma once

#include "geometry/member_flanks.h"
#include "stiffness/fixed_zone.h"
#include "tca/unloaded_tca.h"

#include <memory>
#include <string>
#include <vector>

namespace gearkit
{
/// A variant of the pair: the modifications of each member's working flank side (the same on
/// every tooth) and, for tolerance samples, each tooth's own deviations on top of them, the
/// toothings' single pitch deviations and runout (InvoluteGearData's fields of these names).
struct PairVariant
{
  ToothModifications              pinion, gear;
  std::vector<ToothModifications> pinion_teeth, gear_teeth; ///< empty, or one per tooth
  std::vector<double>             pinion_pitch, gear_pitch; ///< f_p per tooth [m], or empty
  Runout                          pinion_runout, gear_runout;
  /// The gear axis turned further about the gear centre (Assembly::tilted; the parallelism
  /// deviations f_Sigma_beta / L, f_Sigma_delta / L of ISO/TR 10064-3) [rad]: at the cells to
  /// first order (the gear's material moved by the small rotation), the unloaded TE exact.
  double crossing_angle = 0, intersecting_angle = 0;
};

/// One variant's mesh cycles at every torque of the study: tables by torque (M) and position
/// (N: the positions of all the cycles run, in order), pair slot (S) as MeshCycleContact, and
/// the summaries a designer reads.
struct VariantCycle
{
  std::size_t         torques = 0, positions = 0, slots = 0;
  std::vector<double> unloaded_te;    ///< e_0 [N] [rad, pinion]
  std::vector<double> loaded_te;      ///< e_L [M][N] [rad, pinion]
  std::vector<double> mesh_stiffness; ///< K_m [M][N] [N/m]
  std::vector<double> normal_force;   ///< F [M][N] [N]
  std::vector<double> pair_share;     ///< load share of each pair slot [M][N][S]
  std::vector<double> peak_pressure;  ///< largest cell pressure [M][N] [Pa]
  /// largest pressure on cells off the flanks' edges [M][N] [Pa] (Hertz's where the flanks
  /// are smooth; a flank edge's cell pressure depends on the cells' layout)
  std::vector<double> interior_pressure;
  std::vector<double> edge_load_share; ///< force on flank-edge cells / F [M][N]
  /// Summaries per torque [M]: e_L peak-to-peak over the positions [rad]; amplitudes of mesh
  /// orders 1..H of e_L [M][H] [rad]; K_m mean and range (max - min) [N/m]; the largest cell
  /// pressure and the largest off the flanks' edges [Pa]; the largest edge-load share; whether
  /// a contact reached the edge of the fixed zone at some position (the zone was too narrow:
  /// the results there are not valid).
  std::vector<double> te_peak_to_peak, te_harmonics, stiffness_mean, stiffness_range;
  std::vector<double> max_pressure, max_interior_pressure, max_edge_share;
  std::vector<char>   zone_edge;
  int                 harmonics = 0;
};

struct MeshCycleStudyOptions
{
  int                 positions = 40; ///< per mesh cycle, from the TCA's start angle
  std::vector<double> torques;        ///< pinion torques [N m], > 0
  double              widening  = 2;  ///< of each zone against the pair's own (FixedZone)
  int                 harmonics = 4;  ///< mesh orders summarised
  /// Mesh cycles each variant runs over (the zones of one cycle serve every cycle, the teeth
  /// renumbered): 1 for variants alike on every tooth; a pinion revolution (z1) or the
  /// hunting cycle for per-tooth deviations.
  int cycles = 1;
  /// Threads for building the zones and for one variant's positions (0: the hardware's).
  unsigned threads = 0;
  /// Read the gear's compliance where its material lies once the gear is turned to the
  /// variant's e_0 (FixedZone::solve): a 50 um relief's turn on the FZG pair moves the TE p-p
  /// by 0.09 % at 200 N m. Tolerance samples turn it off: each would cost three times as much,
  /// and their percentiles of TE p-p move by 0.06 % (fzg_tolerances, class 6).
  bool turned_gear_compliance = true;
};

class MeshCycleStudy
{
public:
  /// The pair's involute members (their modifications are the reference the variants replace:
  /// usually none; no per-tooth deviations, pitch deviations or runout: every tooth alike),
  /// assembled as `assembly`, analysed with `tca` (side, start angle), its contact as
  /// `contact` says on the members' structural compliances. Builds every zone. Throws
  /// InputError for members that are not involute or whose teeth differ, empty or non-positive
  /// torques, fewer than 4 positions, no cycle, and whatever FixedZone throws.
  MeshCycleStudy(std::shared_ptr<const InvoluteMemberFlanks> pinion,
                 std::shared_ptr<const InvoluteMemberFlanks> gear, const Assembly &assembly,
                 const TcaOptions &tca, const LoadedContactOptions &contact,
                 const StructuralCompliance &pinion_compliance,
                 const StructuralCompliance &gear_compliance, const MeshCycleStudyOptions &options);

  /// Starts every later evaluation's contact solves from this variant's active sets (a
  /// design the variants lie near: the samples of a tolerance study); by default the
  /// reference's. Only speed changes. Not thread-safe: call before evaluating.
  void
  warm_start_from(const PairVariant &variant);

  /// The variant's mesh cycle. `threads` for its positions (0: the study's). Thread-safe.
  /// Throws InputError for modifications the flanks refuse (check_modifications) and when a
  /// position's contact fails.
  VariantCycle
  evaluate(const PairVariant &variant, unsigned threads = 0) const;

  /// What a variant changes at the cells of zone (torque, position) in mesh cycle `cycle`
  /// (its teeth renumbered: pinion tooth - cycle, gear tooth + cycle) beyond the study's
  /// members (their own modifications subtracted): the material both members' deviations add
  /// at each cell's flank parameters [m] (modifications and the tooth's own deviations; the
  /// tooth's turn by its cumulative pitch deviation and the toothing's runout, each to first
  /// order along the flank's normal; the gear axis's tilt likewise), and the derivatives of the
  /// pinion's modifications by its flank parameters (roll angle, z) [m] (FixedZone::solve).
  /// `gear_turn`: what the gear's turn by 1 rad about its axis adds at each cell (its normal
  /// part and the gear's deviation its material brings along) [m]; the gear's turn equal to a
  /// unit pinion rotation is the zone's (FixedZone::turn_per_rotation).
  struct Deviations
  {
    Eigen::VectorXd  added;
    Eigen::MatrixX2d pinion_slope;
    Eigen::VectorXd  gear_turn;
  };
  Deviations
  deviations(std::size_t torque, std::size_t position, int cycle, const PairVariant &variant) const;
  /// The variant's loaded contact in zone (torque, position) from its unloaded TE e0 (its own
  /// TCA): the gear turned to e0 (as the TCA and the stiffness stage turn it: its deviations
  /// slide along; a pinion rotated instead would bring the pinion's, the TE at another pinion
  /// angle), then the pinion's approach under the torque.
  LoadedPosition
  solve_variant(std::size_t torque, std::size_t position, const Deviations &d, double e0,
                const ActiveSetFactor *start) const;

  /// The variant's members: the study's with the variant's modifications.
  std::pair<std::shared_ptr<const InvoluteMemberFlanks>,
            std::shared_ptr<const InvoluteMemberFlanks>>
  members(const PairVariant &variant) const;

  const FixedZone &
  zone(std::size_t torque, std::size_t position) const
  {
    return *zones[torque * std::size_t(o.positions) + position];
  }
  const MeshCycleStudyOptions &
  options() const
  {
    return o;
  }
  /// The study's members without a variant: the reference every variant is measured from.
  const PairVariant &
  reference() const
  {
    return own;
  }

private:
  std::shared_ptr<const InvoluteMemberFlanks>   pinion, gear;
  Assembly                                      assembly;
  TcaOptions                                    tca_options;
  MeshCycleStudyOptions                         o;
  PairVariant                                   own;
  std::unique_ptr<const UnloadedTca>            tca;
  std::vector<std::unique_ptr<const FixedZone>> zones; ///< [M][N]
  /// Per zone and cell, each member's flank point, outward normal and the rows (g_u, g_v) of
  /// (J^T J)^-1 J^T, J its tangents (g_u . w, g_v . w: the flank parameters a tangential motion
  /// w moves by) in its own frame at the cell's flank parameters on the zone's tooth (the rigid
  /// motions: runout, pitch, tilt), [M][N].
  struct MemberPoints
  {
    std::vector<Vec3> pinion_point, pinion_normal, pinion_gu, pinion_gv;
    std::vector<Vec3> gear_point, gear_normal, gear_gu, gear_gv;
    /// the study's members' own modifications at each cell (those a variant replaces)
    std::vector<NormalDeviation> pinion_own, gear_own;
    /// sin and cos of k (L - L_form) at each cell, k = 2 pi / profile_form_wavelength: the
    /// tolerance samples' profile form deviations (waviness_term)
    std::vector<std::pair<double, double>> pinion_wave, gear_wave;
  };
  std::vector<MemberPoints>    points;
  std::vector<ActiveSetFactor> warm; ///< [M][N] the active sets to start from (empty: own)
};
} // namespace gearkit

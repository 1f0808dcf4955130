// Flank modifications and deviations that are superposed along the flank normal.
//
// A deviation delta(L, z) > 0 adds material (the flank moves along its outward normal); a relief
// removes material (delta < 0). L is the transverse roll length (distance along the line of
// action from the base-circle tangent point, L = r_b * xi), z the axial position measured from the
// middle of the face. The flank's involute runs from L_form (start of the involute) to L_tip;
// in mesh the active profile starts at L_A (the start of active profile SAP, where the mate's
// tip circle crosses the line of action). The slope deviations f_Halpha and f_Hbeta are those of
// ISO 1328-1: the differences of the mean profile (helix) line between the ends of the profile
// (helix) evaluation range, the line extended linearly beyond it. All lengths in metres.
#pragma once

#include <limits>
#include <string>
#include <utility>

namespace gearkit
{
enum class ReliefShape
{
  linear,
  parabolic
};

/// Design modifications and form deviations of one flank side (the same on every tooth).
struct ToothModifications
{
  double      tip_relief         = 0; ///< Ca: removal at the tip [m]
  double      tip_relief_length  = 0; ///< roll length from the tip over which it acts [m]
  ReliefShape tip_relief_shape   = ReliefShape::linear;
  double      root_relief        = 0; ///< Cf: removal at the start of the involute [m]
  double      root_relief_length = 0; ///< roll length from the form point [m]
  ReliefShape root_relief_shape  = ReliefShape::linear;
  double      lead_crowning      = 0; ///< C_beta: removal at each face end, parabolic [m]
  double      end_relief         = 0; ///< C_I: linear removal at each face end [m]
  double      end_relief_length  = 0; ///< axial length over which the end relief acts [m]
  double      profile_crowning =
      0; ///< C_alpha: parabolic removal at both ends of the active profile [m]
  double profile_slope       = 0; ///< f_Halpha over L_alpha; > 0 adds at the tip [m]
  double helix_slope         = 0; ///< f_Hbeta over L_beta; > 0 adds at +z [m]
  double waviness_amplitude  = 0; ///< profile waviness amplitude [m]
  double waviness_wavelength = 0; ///< along the roll length [m]; 0 = none
  double waviness_phase      = 0; ///< [rad], phase at the form point

  bool
  any() const;
  /// Every field equal (the same modifications).
  bool
  operator==(const ToothModifications &other) const;
  bool
  operator!=(const ToothModifications &other) const
  {
    return !(*this == other);
  }
};

/// The extent of the flank the modifications refer to.
struct ModificationFrame
{
  double roll_length_form;  ///< L at the start of the involute [m]
  double roll_length_tip;   ///< L at the tip [m]
  double face_width;        ///< b [m]; z runs over [-b/2, b/2]
  double normal_module = 0; ///< m_n [m] (the helix evaluation range)
  /// L_A: L at the start of the active profile (SAP) in mesh with the mate [m]; NaN when no
  /// mate is known: then the profile evaluation range starts at the form circle instead.
  double roll_length_active_start = std::numeric_limits<double>::quiet_NaN();
};

/// The active profile as roll lengths [L_A, L_E]: from the start of active profile in mesh
/// with the mate (the form circle's roll length without a mate) to the tip.
std::pair<double, double>
active_profile(const ModificationFrame &frame);

/// ISO 1328-1 profile evaluation range L_alpha as roll lengths [L_A, L_A + 0.92 (L_E - L_A)]:
/// the active length from the start of active profile L_A to its end L_E (the tip; no tip
/// chamfer or rounding is modelled) less its 8 % at the tip end. Without a mate L_A is the form
/// circle's roll length.
std::pair<double, double>
profile_evaluation_range(const ModificationFrame &frame);

/// ISO 1328-1 helix evaluation range L_beta as axial positions [-b/2 + e, b/2 - e]: the face
/// width less at each end e = min(0.05 b, m_n).
std::pair<double, double>
helix_evaluation_range(const ModificationFrame &frame);

/// The wavelength of the profile form deviation tolerance samples take (one wave over the
/// profile evaluation range: its peak-to-peak is f_falpha) [m].
double
profile_form_wavelength(const ModificationFrame &frame);

/// delta and its derivatives with respect to L and z.
struct NormalDeviation
{
  double value = 0;
  double d_dL  = 0;
  double d_dz  = 0;
};

/// A profile waviness of `amplitude` and `wavelength` from the sine and cosine of its phase
/// (sin_phase, cos_phase) and of k (L - L_form) at the point, k = 2 pi / wavelength (the angle
/// sum): value and d/dL (evaluate_modifications' term; a caller evaluating many teeth's
/// waviness of one wavelength at the same points takes the sines of each once).
NormalDeviation
waviness_term(double amplitude, double wavelength, double sin_phase, double cos_phase,
              double sin_at, double cos_at);

/// Sum of all modifications at (L, z).
NormalDeviation
evaluate_modifications(const ToothModifications &m, const ModificationFrame &frame, double L,
                       double z);

/// Checks lengths and amounts against the flank they act on; throws InputError naming the
/// offending parameter (prefix: e.g. "Pinion drive flank").
void
check_modifications(const ToothModifications &m, const ModificationFrame &frame,
                    const std::string &prefix);
} // namespace gearkit

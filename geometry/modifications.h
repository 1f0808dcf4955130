// Flank modifications and deviations that are superposed along the flank normal.
//
// A deviation delta(L, z) > 0 adds material (the flank moves along its outward normal); a relief
// removes material (delta < 0). L is the transverse roll length (distance along the line of
// action from the base-circle tangent point, L = r_b * xi), z the axial position measured from the
// middle of the face. The active profile runs from L_form (start of the involute) to L_tip.
// All lengths in metres.
#pragma once

#include <string>

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
  double      profile_crowning   = 0; ///< C_alpha: parabolic removal at both profile ends [m]
  double      profile_slope      = 0; ///< f_Halpha over the active profile; > 0 adds at the tip [m]
  double      helix_slope        = 0; ///< f_Hbeta over the face width; > 0 adds at +z [m]
  double      waviness_amplitude = 0; ///< profile waviness amplitude [m]
  double      waviness_wavelength = 0; ///< along the roll length [m]; 0 = none
  double      waviness_phase      = 0; ///< [rad], phase at the form point

  bool
  any() const;
};

/// The extent of the flank the modifications refer to.
struct ModificationFrame
{
  double roll_length_form; ///< L at the start of the involute [m]
  double roll_length_tip;  ///< L at the tip [m]
  double face_width;       ///< b [m]; z runs over [-b/2, b/2]
};

/// delta and its derivatives with respect to L and z.
struct NormalDeviation
{
  double value = 0;
  double d_dL  = 0;
  double d_dz  = 0;
};

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

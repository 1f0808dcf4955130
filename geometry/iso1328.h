// ISO 1328-1:2013 flank tolerances of a cylindrical involute gear for a flank tolerance class
// A = 1..11, and per-tooth deviations of one gear drawn within them (for a tolerance Monte Carlo).
//
// Formulas (ISO 1328-1:2013, 5.3; d, m_n, b in mm, results in um; each times the class step
// factor (sqrt 2)^(A - 5) applied to the unrounded class-5 value, 5.2.2):
//   (5)  single pitch          f_pT     = (0.001 d + 0.4 m_n + 5)
//   (6)  total cumulative pitch F_pT    = (0.002 d + 0.55 sqrt(d) + 0.7 m_n + 12)
//   (7)  profile slope         f_HalphaT = (0.4 m_n + 0.001 d + 4)
//   (8)  profile form          f_falphaT = (0.55 m_n + 5)
//   (9)  total profile         F_alphaT  = sqrt(f_HalphaT^2 + f_falphaT^2)
//   (10) helix slope           f_HbetaT  = (0.05 sqrt(d) + 0.35 sqrt(b) + 4)
//   (11) helix form            f_fbetaT  = (0.07 sqrt(d) + 0.45 sqrt(b) + 4)
//   (12) total helix           F_betaT   = sqrt(f_HbetaT^2 + f_fbetaT^2)
//        runout                F_rT      = 0.9 F_pT
// The totals (9), (12) and the runout are formed from the unrounded values, then every value is
// rounded (5.2.3): above 10 um to the nearest 1 um, from 5 um to 10 um to the nearest 0.5 um,
// below 5 um to the nearest 0.1 um (halves round up).
//
// What was verified, and where (the standard's own text was not available here):
// * Range of application (clause 1): 5 <= z <= 1000, 5 mm <= d <= 15000 mm, 0.5 mm <= m_n <= 70 mm,
//   4 mm <= b <= 1200 mm, beta <= 45 deg: quoted in the publisher's description of BS ISO
//   1328-1:2013 (pdfstandards.shop, "bs-iso-1328-12013"), which also lists an annex "Allowable
//   values of runout". No condition b <= 15 m_n (or any b/m_n ratio) was found; none is imposed.
// * Formulas (5), (6), (8), (9), (10), (12), the step factor and the rounding rule: identical in
//   four independent public implementations found by code search (two Python, one C#, one
//   JavaScript, all citing ISO 1328-1:2013 or its identical German adoption DIN ISO 1328-1:2018);
//   one of them checks its values against phrases of the standard's text (clause 5.2.1 "shall not
//   be extrapolated beyond these limits", 5.2.2 step sqrt 2, 5.2.3 the three rounding ranges).
//   Three of them say the totals use the unrounded slope and form values.
// * (7): three of the four include the 0.001 d term; one (read "visually" from DIN ISO
//   1328-1:2018) omits it. Implemented with the term (the majority, and the project's brief).
// * (11): all four give f_fbetaT = (0.07 sqrt(d) + 0.45 sqrt(b) + 4), NOT equal to f_HbetaT (the
//   brief remembered them equal; the 1995 edition had f_fbeta = f_Hbeta). Implemented as (11).
// * Runout F_rT = 0.9 F_pT: only one public implementation attributes it to ISO 1328-1:2013; that
//   the standard has a runout annex is confirmed (above), its factor 0.9 is NOT confirmed here.
// No published table of values was found to compare with; the tests check hand-computed values.
//
// Interface in SI (metres in, metres out); the standard's mm and um only inside.
#pragma once

#include "geometry/types.h"

#include <random>
#include <vector>

namespace gearkit
{
class InvoluteGear;

/// Flank tolerances of one gear [m], each rounded as ISO 1328-1:2013 5.2.3 says (or unrounded,
/// from iso1328_tolerances_unrounded).
struct Iso1328Tolerances
{
  double single_pitch;     ///< f_pT: |single pitch deviation| <= f_pT
  double cumulative_pitch; ///< F_pT: total cumulative pitch deviation (max - min) <= F_pT
  double profile_total;    ///< F_alphaT
  double profile_form;     ///< f_falphaT
  double profile_slope;    ///< f_HalphaT: |profile slope deviation| <= f_HalphaT
  double helix_total;      ///< F_betaT
  double helix_form;       ///< f_fbetaT
  double helix_slope;      ///< f_HbetaT: |helix slope deviation| <= f_HbetaT
  double runout;           ///< F_rT (radial runout)
};

/// The flank tolerances of flank tolerance class `flank_class` (1 = finest .. 11) for a gear of
/// reference diameter d, normal module m_n and face width b [m] with z teeth, rounded per 5.2.3.
/// Throws InputError, naming the parameter, its value in mm (as the standard states its ranges),
/// the allowed range and a hint at a unit slip, for a class outside 1..11 or a gear outside the
/// standard's range of application (the formulas must not be extrapolated): z outside
/// [5, 1000], d outside [5, 15000] mm, m_n outside [0.5, 70] mm, b outside [4, 1200] mm, or a
/// helix angle implied by d = z m_n / cos(beta) outside [0, 45] deg (z m_n <= d <= sqrt 2 z m_n).
Iso1328Tolerances
iso1328_tolerances(int flank_class, double reference_diameter, double normal_module,
                   double face_width, int teeth);

/// The same values before rounding (same checks): the class step is exactly (sqrt 2)^(A - 5).
Iso1328Tolerances
iso1328_tolerances_unrounded(int flank_class, double reference_diameter, double normal_module,
                             double face_width, int teeth);

/// The rounding rule of ISO 1328-1:2013 5.2.3 on a value in micrometres: > 10 um to the nearest
/// 1 um, 5 um..10 um to the nearest 0.5 um, < 5 um to the nearest 0.1 um (halves up).
double
iso1328_round_um(double micrometres);

/// The deviations of one flank side of one tooth [m].
struct ToothDeviations
{
  /// Cumulative pitch deviation of the tooth's flank (of the side drawn) as ISO 1328-1 measures
  /// it, about the axis of rotation: the flank's position on the reference circle in the
  /// transverse section at mid-face (z = 0), against nominal, along the circle, positive in the
  /// +theta direction (the member frame's positive rotation). It includes the eccentricity's
  /// share (below). Referred to the mean over the teeth (a common shift is a rotation of the
  /// whole gear).
  double pitch_position;
  /// Profile slope deviation f_Halpha: the mean profile line's rise over the profile evaluation
  /// range L_alpha, > 0 adds material toward the tip (ToothModifications::profile_slope).
  double profile_slope;
  /// Profile form: half the peak-to-peak of a form deviation without linear part over L_alpha
  /// (f_falpha = 2 |amplitude|), signed: the sign flips a shape the consumer chooses (e.g. a
  /// waviness, ToothModifications::waviness_amplitude, or a symmetric parabola).
  double profile_form_amplitude;
  /// Helix slope deviation f_Hbeta over the helix evaluation range L_beta, > 0 adds material
  /// toward +z (ToothModifications::helix_slope).
  double helix_slope;
  /// Helix form: as profile_form_amplitude, along the face (f_fbeta = 2 |amplitude|).
  double helix_form_amplitude;
};

/// The deviations of one gear, all teeth, one flank side.
struct GearDeviations
{
  std::vector<ToothDeviations> teeth;
  /// Runout: the toothing's centre displaced from the axis of rotation by this distance [m] in
  /// the direction runout_phase [rad] of the member frame (InvoluteGearData::runout). Alone it
  /// gives a ball probe in the tooth spaces a radial runout of 2 e.
  double runout_eccentricity;
  double runout_phase;
};

/// How a deviation is spread within its tolerance.
enum class ToleranceDistribution
{
  uniform, ///< uniform over the whole tolerance (+-T for signed values, [0, T] for sizes)
  normal   ///< normal, zero mean, the tolerance being 3 sigma; values beyond it are drawn again
};

/// Per-tooth deviations of one gear (all teeth, one flank side) drawn within the tolerances `t`
/// (rounded ones, as a drawing states them) for a gear of `teeth` teeth in [5, 1000].
///
/// What is drawn. Let X stand for a fresh draw on [-1, 1] from `dist` (uniform on [-1, 1], or a
/// normal of standard deviation 1/3 drawn again while |X| > 1), U for a uniform draw on [0, 1):
/// * Runout: eccentricity e = |X| F_rT / 2, phase 2 pi U. Then 2 e <= F_rT.
/// * Pitch, as measured about the axis of rotation: tooth k (at theta_k = 2 pi k / z) at
///       p_k = a sin(theta_k + psi) + c X_k,   less the mean over the teeth,
///   a long wave of one period per revolution (a = |X| a_max, psi = 2 pi U) plus an independent
///   per-tooth scatter (c = min(f_pT, F_pT) / 4), with the long wave's largest amplitude
///       a_max = min((F_pT - 2 c) / 2, (f_pT - 2 c) / (2 sin(pi / z))).
///   So by construction max_k p_k - min_k p_k <= 2 a + 2 c <= F_pT, and every single pitch
///   deviation p_k - p_(k-1) (cyclic, tooth 0 after tooth z-1) lies within +-(2 a sin(pi/z) + 2 c)
///   <= +-f_pT. The long wave is what eccentricity and the machine's index error leave on the
///   measured pitch; it is drawn independently of the runout (phase and size): the toothing's
///   own spacing then makes up the difference (single_pitch_deviations below).
/// * Per tooth, profile: slope s = X f_HalphaT and form amplitude m = X f_falphaT / 2 are drawn
///   independently and the pair is drawn again until |s| + 2 |m| <= F_alphaT: the distribution
///   conditioned on the tooth passing its total profile tolerance (|s| + 2 |m| bounds the total
///   profile deviation of a line of rise s plus a form of peak-to-peak 2 |m|). Helix: the same
///   with f_HbetaT, f_fbetaT, F_betaT.
/// Slopes and form amplitudes have zero mean.
///
/// Not budgeted: a ball probe's runout reading also sees the spacing (a tooth space widened by
/// delta lets the ball sink by delta / (2 tan alpha_t)), so 2 e <= F_rT bounds the eccentricity's
/// part of the measured runout only; and the other flank side's pitch (it measures the
/// toothing's spacing plus its own, different share of the runout).
///
/// Deterministic: the same rng state gives the same draw on every platform (uniform numbers from
/// the engine's 53 high bits, normal ones by Box-Muller; no std:: distributions). Throws
/// InputError for teeth outside [5, 1000] or tolerances that are not positive and finite, or whose
/// totals are below their slope or form tolerance (not a set from iso1328_tolerances).
/// A value within +-tolerance: uniform, or normal with the tolerance 3 sigma (drawn again
/// beyond it), from `rng` (the draws draw_gear_deviations makes).
double
draw_within(double tolerance, ToleranceDistribution dist, std::mt19937_64 &rng);

GearDeviations
draw_gear_deviations(const Iso1328Tolerances &t, int teeth, ToleranceDistribution dist,
                     std::mt19937_64 &rng);

/// The toothing's single pitch deviations (InvoluteGearData::single_pitch_deviations) that give
/// `gear` (its nominal geometry; its own deviations are ignored), displaced by the drawn runout
/// (InvoluteGearData::runout = {runout_eccentricity, runout_phase}), the drawn pitch positions
/// on its `side` flanks, measured about the axis of rotation. The runout moves the flank of
/// tooth k, at polar angle g_k = theta_k +- s_t / (2 r) on the reference circle (+ drive,
/// - coast), along the circle by
///       e sin(phase - g_k) +- e tan(alpha_t) cos(phase - g_k)
/// (the displacement's component along the flank normal, which leans by alpha_t from the
/// circle's tangent, over cos alpha_t); the toothing places the tooth at q_k = p_k less that.
/// Entry k is q_k - q_(k-1), entry 0 is q_0 - q_(z-1); they sum to zero. First order in e / r
/// (the neglected terms are of order e^2 / (r_b tan alpha_t), nanometres). The other flank side
/// then measures q_k plus its own share of the runout. Throws InputError when the number of
/// teeth differs from the gear's.
std::vector<double>
single_pitch_deviations(const GearDeviations &deviations, const InvoluteGear &gear, FlankSide side);
} // namespace gearkit

// ISO 1328-1:2013 flank tolerances of a cylindrical involute gear for a flank tolerance class
// A = 1..11.
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

namespace gearkit
{
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
} // namespace gearkit

// ISO 1328-1:2013 flank tolerances against values computed by hand from the formulas of 5.3 and
// the rounding rule of 5.2.3, and the deviation sampler against its limits by brute force.
// No published table of values was found to compare with (see geometry/iso1328.h).
#include "geometry/involute_gear.h"
#include "geometry/iso1328.h"
#include "geometry/types.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace gearkit;

namespace
{
constexpr double um = 1e-6, mm = 1e-3;

// Rounded values are multiples of 0.1 um: compare in um to 1e-9 um (the conversion to metres and
// back loses a few ulps, nothing near 1e-9).
void
expect_um(double metres, double expected_um, const char *what)
{
  EXPECT_NEAR(metres / um, expected_um, 1e-9) << what;
}

// Runs f, expects an InputError whose message contains every one of `parts`.
void
expect_input_error(const std::function<void()> &f, const std::vector<std::string> &parts)
{
  try
    {
      f();
      ADD_FAILURE() << "no InputError; expected one naming " << parts.front();
    }
  catch (const InputError &e)
    {
      for (const std::string &p : parts)
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
            << "message \"" << e.what() << "\" lacks \"" << p << "\"";
    }
}
} // namespace

TEST(Iso1328Tolerances, RoundingRuleAtItsThreeRanges)
{
  // Above 10 um: nearest integer (halves up).
  EXPECT_EQ(iso1328_round_um(10.4), 10);
  EXPECT_EQ(iso1328_round_um(10.5), 11);
  EXPECT_EQ(iso1328_round_um(144.6254), 145);
  // 5 um to 10 um: nearest 0.5 um (10 itself belongs here and stays 10).
  EXPECT_EQ(iso1328_round_um(10.0), 10);
  EXPECT_EQ(iso1328_round_um(9.8), 10);
  EXPECT_EQ(iso1328_round_um(9.7), 9.5);
  EXPECT_EQ(iso1328_round_um(7.26), 7.5);
  EXPECT_EQ(iso1328_round_um(7.24), 7);
  EXPECT_EQ(iso1328_round_um(5.0), 5);
  // Below 5 um: nearest 0.1 um (1.25 is exact in binary: its half rounds up).
  EXPECT_NEAR(iso1328_round_um(4.96), 5.0, 1e-12);
  EXPECT_NEAR(iso1328_round_um(4.94), 4.9, 1e-12);
  EXPECT_NEAR(iso1328_round_um(1.25), 1.3, 1e-12);
  EXPECT_NEAR(iso1328_round_um(1.91626), 1.9, 1e-12);
}

TEST(Iso1328Tolerances, Class6SpurGearByHand)
{
  // Class 6, spur, m_n 3 mm, z 40: d = 120 mm; b 30 mm. Step (sqrt 2)^1 = 1.41421356.
  // sqrt(d) = 10.9544512, sqrt(b) = 5.47722558.
  //   f_pT   = (0.12 + 1.2 + 5) * 1.41421356            = 8.93783  -> 9.0 (0.5 range)
  //   F_pT   = (0.24 + 6.02494813 + 2.1 + 12) * 1.414.. = 28.80039 -> 29  (integer)
  //   f_HaT  = (1.2 + 0.12 + 4) * 1.414..               = 7.52362  -> 7.5
  //   f_faT  = (1.65 + 5) * 1.414..                     = 9.40452  -> 9.5
  //   F_aT   = hypot(7.52362, 9.40452)                  = 12.04366 -> 12
  //   f_HbT  = (0.54772256 + 1.91702895 + 4) * 1.414..  = 9.14254  -> 9.0
  //   f_fbT  = (0.76681158 + 2.46475151 + 4) * 1.414..  = 10.22697 -> 10  (just above 10)
  //   F_bT   = hypot(9.14254, 10.22697)                 = 13.71776 -> 14
  //   F_rT   = 0.9 * 28.80039                           = 25.92035 -> 26
  const Iso1328Tolerances t = iso1328_tolerances(6, 120 * mm, 3 * mm, 30 * mm, 40);
  expect_um(t.single_pitch, 9.0, "f_pT");
  expect_um(t.cumulative_pitch, 29, "F_pT");
  expect_um(t.profile_slope, 7.5, "f_HalphaT");
  expect_um(t.profile_form, 9.5, "f_falphaT");
  expect_um(t.profile_total, 12, "F_alphaT");
  expect_um(t.helix_slope, 9.0, "f_HbetaT");
  expect_um(t.helix_form, 10, "f_fbetaT");
  expect_um(t.helix_total, 14, "F_betaT");
  expect_um(t.runout, 26, "F_rT");

  // The unrounded values, to the digits above.
  const Iso1328Tolerances u = iso1328_tolerances_unrounded(6, 120 * mm, 3 * mm, 30 * mm, 40);
  EXPECT_NEAR(u.single_pitch / um, 6.32 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(u.cumulative_pitch / um, 28.80039, 1e-5);
  EXPECT_NEAR(u.profile_total / um, 12.04366, 1e-5);
  EXPECT_NEAR(u.helix_form / um, 10.22697, 1e-5);
  EXPECT_NEAR(u.helix_total / um, 13.71776, 1e-5);
  EXPECT_NEAR(u.runout / um, 25.92035, 1e-5);
}

TEST(Iso1328Tolerances, Class2SmallGearBelowFiveMicrometres)
{
  // Class 2, spur, m_n 1 mm, z 20: d = 20 mm; b 10 mm. Step (sqrt 2)^-3 = 0.35355339.
  // sqrt(d) = 4.47213595, sqrt(b) = 3.16227766.
  //   f_pT  = (0.02 + 0.4 + 5) * 0.35355339              = 1.91626 -> 1.9 (0.1 range)
  //   F_pT  = (0.04 + 2.45967477 + 0.7 + 12) * 0.3535..  = 5.37390 -> 5.5 (0.5 range)
  //   f_HaT = (0.4 + 0.02 + 4) * 0.3535..                = 1.56271 -> 1.6
  //   f_faT = (0.55 + 5) * 0.3535..                      = 1.96222 -> 2.0
  //   F_aT  = hypot(1.56271, 1.96222)                    = 2.50846 -> 2.5
  //   f_HbT = (0.22360680 + 1.10679718 + 4) * 0.3535..   = 1.88458 -> 1.9
  //   f_fbT = (0.31304952 + 1.42302495 + 4) * 0.3535..   = 2.02801 -> 2.0
  //   F_bT  = hypot(1.88458, 2.02801)                    = 2.76848 -> 2.8
  //   F_rT  = 0.9 * 5.37390 (unrounded F_pT)             = 4.83651 -> 4.8 (not 0.9 * 5.5 = 4.95)
  const Iso1328Tolerances t = iso1328_tolerances(2, 20 * mm, 1 * mm, 10 * mm, 20);
  expect_um(t.single_pitch, 1.9, "f_pT");
  expect_um(t.cumulative_pitch, 5.5, "F_pT");
  expect_um(t.profile_slope, 1.6, "f_HalphaT");
  expect_um(t.profile_form, 2.0, "f_falphaT");
  expect_um(t.profile_total, 2.5, "F_alphaT");
  expect_um(t.helix_slope, 1.9, "f_HbetaT");
  expect_um(t.helix_form, 2.0, "f_fbetaT");
  expect_um(t.helix_total, 2.8, "F_betaT");
  expect_um(t.runout, 4.8, "F_rT");
}

TEST(Iso1328Tolerances, Class9LargeGearByHand)
{
  // Class 9, spur, m_n 10 mm, z 80: d = 800 mm; b 100 mm. Step (sqrt 2)^4 = 4 exactly.
  // sqrt(d) = 28.2842712, sqrt(b) = 10.
  //   f_pT  = (0.8 + 4 + 5) * 4                    = 39.2      -> 39
  //   F_pT  = (1.6 + 15.5563492 + 7 + 12) * 4      = 144.62540 -> 145
  //   f_HaT = (4 + 0.8 + 4) * 4                    = 35.2      -> 35
  //   f_faT = (5.5 + 5) * 4                        = 42        -> 42
  //   F_aT  = hypot(35.2, 42) = sqrt(3003.04)      = 54.80     -> 55
  //   f_HbT = (1.41421356 + 3.5 + 4) * 4           = 35.65685  -> 36
  //   f_fbT = (1.97989899 + 4.5 + 4) * 4           = 41.91960  -> 42
  //   F_bT  = hypot(35.65685, 41.91960)            = 55.03330  -> 55
  //   F_rT  = 0.9 * 144.62540                      = 130.16286 -> 130
  const Iso1328Tolerances t = iso1328_tolerances(9, 800 * mm, 10 * mm, 100 * mm, 80);
  expect_um(t.single_pitch, 39, "f_pT");
  expect_um(t.cumulative_pitch, 145, "F_pT");
  expect_um(t.profile_slope, 35, "f_HalphaT");
  expect_um(t.profile_form, 42, "f_falphaT");
  expect_um(t.profile_total, 55, "F_alphaT");
  expect_um(t.helix_slope, 36, "f_HbetaT");
  expect_um(t.helix_form, 42, "f_fbetaT");
  expect_um(t.helix_total, 55, "F_betaT");
  expect_um(t.runout, 130, "F_rT");
}

TEST(Iso1328Tolerances, HelicalGearUpToFortyFiveDegrees)
{
  // Class 5 (step 1), m_n 2 mm, z 30, beta 20 deg: d = 60 / cos 20 deg = 63.8507 mm.
  //   f_pT = 0.0638507 + 0.8 + 5 = 5.86385 -> 6.0 (nearest 0.5).
  const double d = 30 * 2 * mm / std::cos(20 * pi / 180);
  const auto   t = iso1328_tolerances(5, d, 2 * mm, 25 * mm, 30);
  expect_um(t.single_pitch, 6.0, "f_pT");
  EXPECT_NEAR(iso1328_tolerances_unrounded(5, d, 2 * mm, 25 * mm, 30).single_pitch / um,
              0.001 * d / mm + 5.8, 1e-12);
  // beta = 45 deg is the standard's limit: accepted; 46 deg is not.
  EXPECT_NO_THROW(iso1328_tolerances(5, 60 * mm / std::cos(pi / 4), 2 * mm, 25 * mm, 30));
  expect_input_error(
      [] { iso1328_tolerances(5, 60 * mm / std::cos(46 * pi / 180), 2 * mm, 25 * mm, 30); },
      {"helix angle", "45 deg", "d = 86.37"});
}

TEST(Iso1328Tolerances, TwoClassesApartIsAFactorTwoBeforeRounding)
{
  // (sqrt 2)^(A + 2 - 5) / (sqrt 2)^(A - 5) = 2 for every value, totals and runout included.
  // 1e-13: a quotient of two results of a dozen double operations each.
  const double d = 150 * mm, m_n = 4 * mm, b = 40 * mm;
  const int    z = 37;
  for (int A = 1; A <= 9; ++A)
    {
      const auto                      lo      = iso1328_tolerances_unrounded(A, d, m_n, b, z);
      const auto                      hi      = iso1328_tolerances_unrounded(A + 2, d, m_n, b, z);
      const std::pair<double, double> pairs[] = {{lo.single_pitch, hi.single_pitch},
                                                 {lo.cumulative_pitch, hi.cumulative_pitch},
                                                 {lo.profile_total, hi.profile_total},
                                                 {lo.profile_form, hi.profile_form},
                                                 {lo.profile_slope, hi.profile_slope},
                                                 {lo.helix_total, hi.helix_total},
                                                 {lo.helix_form, hi.helix_form},
                                                 {lo.helix_slope, hi.helix_slope},
                                                 {lo.runout, hi.runout}};
      for (const auto &[l, h] : pairs)
        EXPECT_NEAR(h / l, 2, 1e-13) << "class " << A;
    }
  // Class 5 is the formulas' bracket itself: f_pT = 0.001 d + 0.4 m_n + 5 = 6.75 um.
  EXPECT_NEAR(iso1328_tolerances_unrounded(5, d, m_n, b, z).single_pitch / um, 6.75, 1e-12);
  // And the rounded values are the rule applied to the unrounded ones, class by class.
  for (int A = 1; A <= 11; ++A)
    {
      const auto r = iso1328_tolerances(A, d, m_n, b, z);
      const auto u = iso1328_tolerances_unrounded(A, d, m_n, b, z);
      expect_um(r.cumulative_pitch, iso1328_round_um(u.cumulative_pitch / um), "F_pT");
      expect_um(r.helix_total, iso1328_round_um(u.helix_total / um), "F_betaT");
    }
}

TEST(Iso1328Tolerances, OutsideTheRangeOfApplicationNamesTheParameter)
{
  const double d = 108 * mm, m_n = 4.5 * mm, b = 30 * mm;
  const int    z = 24;
  EXPECT_NO_THROW(iso1328_tolerances(7, d, m_n, b, z)); // SI: m_n = 0.0045 m
  // The module given in millimetres by mistake: 4.5 "m" = 4500 mm.
  expect_input_error(
      [&] { iso1328_tolerances(7, d, 4.5, b, z); },
      {"normal module", "m_n = 4500 mm", "0.5 mm <= m_n <= 70 mm", "millimetres given as metres"});
  expect_input_error([&] { iso1328_tolerances(7, 108, m_n, b, z); },
                     {"reference diameter", "108000 mm", "5 mm <= d <= 15000 mm"});
  expect_input_error([&] { iso1328_tolerances(7, d, m_n, 2 * mm, z); },
                     {"face width", "b = 2 mm", "4 mm <= b <= 1200 mm"});
  expect_input_error([&] { iso1328_tolerances(7, d, m_n, 1.3, z); }, {"face width", "1300 mm"});
  expect_input_error([&] { iso1328_tolerances(7, d, 0.4 * mm, b, z); },
                     {"normal module", "m_n = 0.4 mm"});
  expect_input_error([&] { iso1328_tolerances(7, d, std::nan(""), b, z); }, {"normal module"});
  expect_input_error([&] { iso1328_tolerances(0, d, m_n, b, z); }, {"class", "A = 0", "1"});
  expect_input_error([&] { iso1328_tolerances(12, d, m_n, b, z); }, {"class", "A = 12", "11"});
  expect_input_error([&] { iso1328_tolerances_unrounded(12, d, m_n, b, z); }, {"A = 12"});
  expect_input_error([&] { iso1328_tolerances(7, 20 * mm, 4 * mm, b, 4); },
                     {"number of teeth", "z = 4", "5 <= z <= 1000"});
  expect_input_error([&] { iso1328_tolerances(7, 5005 * mm, 5 * mm, b, 1001); },
                     {"number of teeth", "z = 1001"});
  // A tip diameter d_a = d + 2 m_n = 117 mm passed for d is caught by the helix angle it implies
  // only beyond 45 deg; a diameter below z m_n (cos beta > 1) always is.
  expect_input_error([&] { iso1328_tolerances(7, 100 * mm, m_n, b, z); },
                     {"helix angle", "d = 100 mm", "[108, 152.735] mm"});
}

namespace
{
// Class 6, spur, m_n 3 mm, z 24 (d 72 mm), b 30 mm: f_pT 9.0, F_pT 27, f_HaT 7.5, f_faT 9.5,
// F_aT 12, f_HbT 9.0, f_fbT 10, F_bT 13, F_rT 24 um.
constexpr int sampler_teeth = 24;
Iso1328Tolerances
sampler_tolerances()
{
  return iso1328_tolerances(6, 72 * mm, 3 * mm, 30 * mm, sampler_teeth);
}

// Brute force: the total profile deviation of the trace s (xi - 1/2) + m cos(2 pi xi) over
// xi in [0, 1] (a form without linear part, peak-to-peak 2 |m|): max - min on 2001 points.
double
total_deviation(double s, double m)
{
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i <= 2000; ++i)
    {
      const double xi = i / 2000.0, y = s * (xi - 0.5) + m * std::cos(2 * pi * xi);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
  return hi - lo;
}
} // namespace

TEST(Iso1328Sampler, EveryDrawWithinEveryLimit)
{
  // 2000 gears of 24 teeth per distribution, each checked against every limit. Slack 1e-12
  // relative: a limit met with equality by construction may be missed by the rounding of a few
  // additions.
  const Iso1328Tolerances t   = sampler_tolerances();
  const double            tol = 1 + 1e-12;
  for (ToleranceDistribution dist : {ToleranceDistribution::uniform, ToleranceDistribution::normal})
    {
      std::mt19937_64 rng(20240611);
      double          largest_pp = 0, largest_single = 0, largest_slope = 0, largest_e = 0;
      for (int draw = 0; draw < 2000; ++draw)
        {
          const GearDeviations g = draw_gear_deviations(t, sampler_teeth, dist, rng);
          ASSERT_EQ(static_cast<int>(g.teeth.size()), sampler_teeth);
          double lo = 1e300, hi = -1e300, sum = 0;
          for (int k = 0; k < sampler_teeth; ++k)
            {
              const ToothDeviations &d    = g.teeth[k];
              const ToothDeviations &prev = g.teeth[(k + sampler_teeth - 1) % sampler_teeth];
              lo                          = std::min(lo, d.pitch_position);
              hi                          = std::max(hi, d.pitch_position);
              sum += d.pitch_position;
              const double single = std::abs(d.pitch_position - prev.pitch_position);
              ASSERT_LE(single, t.single_pitch * tol) << "draw " << draw << " tooth " << k;
              largest_single = std::max(largest_single, single);
              ASSERT_LE(std::abs(d.profile_slope), t.profile_slope * tol);
              ASSERT_LE(std::abs(d.helix_slope), t.helix_slope * tol);
              ASSERT_LE(2 * std::abs(d.profile_form_amplitude), t.profile_form * tol);
              ASSERT_LE(2 * std::abs(d.helix_form_amplitude), t.helix_form * tol);
              ASSERT_LE(std::abs(d.profile_slope) + 2 * std::abs(d.profile_form_amplitude),
                        t.profile_total * tol);
              ASSERT_LE(std::abs(d.helix_slope) + 2 * std::abs(d.helix_form_amplitude),
                        t.helix_total * tol);
              largest_slope = std::max(largest_slope, std::abs(d.profile_slope));
            }
          ASSERT_LE(hi - lo, t.cumulative_pitch * tol) << "draw " << draw;
          EXPECT_NEAR(sum, 0, 1e-18); // referred to the mean
          largest_pp = std::max(largest_pp, hi - lo);
          ASSERT_GE(g.runout_eccentricity, 0);
          ASSERT_LE(2 * g.runout_eccentricity, t.runout * tol);
          ASSERT_GE(g.runout_phase, 0);
          ASSERT_LT(g.runout_phase, 2 * pi);
          largest_e = std::max(largest_e, g.runout_eccentricity);
        }
      // The draws also use their room: over 2000 gears the largest total cumulative pitch and
      // slope come near their limits (the long wave's amplitude reaches 0.9 of its largest in
      // 10 % of uniform draws, 0.45 % of normal ones: ~9 of 2000). The largest single pitch stays
      // below f_pT here: with z = 24 the long wave's budget is set by F_pT, and
      // 2 a_max sin(pi / 24) + 2 c = 7.44 um < 9 um.
      EXPECT_GT(largest_pp, 0.8 * t.cumulative_pitch);
      EXPECT_GT(largest_single, 0.5 * t.single_pitch);
      EXPECT_GT(largest_slope, 0.9 * t.profile_slope);
      EXPECT_GT(2 * largest_e, 0.9 * t.runout);
    }
}

TEST(Iso1328Sampler, TotalProfileBoundHoldsByBruteForce)
{
  // The per-tooth condition |s| + 2 |m| <= F_alphaT keeps the total profile deviation of a line
  // of rise s plus a form of peak-to-peak 2 |m| within F_alphaT: checked on the traces. Sampling
  // error of the grid: at most the trace's change over a step, far below 1e-3 of F_alphaT.
  const Iso1328Tolerances t = sampler_tolerances();
  std::mt19937_64         rng(7);
  for (int draw = 0; draw < 200; ++draw)
    for (const ToothDeviations &d :
         draw_gear_deviations(t, sampler_teeth, ToleranceDistribution::uniform, rng).teeth)
      {
        ASSERT_LE(total_deviation(d.profile_slope, d.profile_form_amplitude), t.profile_total);
        ASSERT_LE(total_deviation(d.helix_slope, d.helix_form_amplitude), t.helix_total);
      }
}

TEST(Iso1328Sampler, MeansNearZeroAndThreeSigmaTolerance)
{
  // 2000 gears x 24 teeth = 48000 tooth draws. A uniform slope within +-f_H has a standard
  // deviation below f_H / sqrt 3, so the sample mean's standard error is below 0.0027 f_H; 0.02 f_H
  // is more than 7 standard errors. Same for the form amplitudes (within +-f_f / 2). Tooth 0's
  // pitch position over 2000 gears: its standard deviation is about 0.18 F_pT here (long wave
  // a <= 11.25 um with a random phase, scatter c = 2.25 um), the mean's standard error 0.004 F_pT;
  // allowed 0.07 F_pT (and |p| <= F_pT bounds the error by 0.022 F_pT even without that).
  const Iso1328Tolerances t = sampler_tolerances();
  for (ToleranceDistribution dist : {ToleranceDistribution::uniform, ToleranceDistribution::normal})
    {
      std::mt19937_64 rng(99);
      double          sp = 0, sh = 0, fp = 0, fh = 0, pitch0 = 0, sp2 = 0;
      int             n = 0;
      for (int draw = 0; draw < 2000; ++draw)
        {
          const GearDeviations g = draw_gear_deviations(t, sampler_teeth, dist, rng);
          pitch0 += g.teeth[0].pitch_position / 2000;
          for (const ToothDeviations &d : g.teeth)
            {
              sp += d.profile_slope;
              sp2 += d.profile_slope * d.profile_slope;
              sh += d.helix_slope;
              fp += d.profile_form_amplitude;
              fh += d.helix_form_amplitude;
              ++n;
            }
        }
      EXPECT_LT(std::abs(sp / n), 0.02 * t.profile_slope);
      EXPECT_LT(std::abs(sh / n), 0.02 * t.helix_slope);
      EXPECT_LT(std::abs(fp / n), 0.02 * t.profile_form / 2);
      EXPECT_LT(std::abs(fh / n), 0.02 * t.helix_form / 2);
      EXPECT_LT(std::abs(pitch0), 0.07 * t.cumulative_pitch);
      if (dist == ToleranceDistribution::normal)
        {
          // The tolerance is 3 sigma, truncated there: the standard deviation of a normal
          // truncated at +-3 sigma is sigma sqrt(1 - 6 phi(3) / (2 Phi(3) - 1)) = 0.98657 sigma.
          // The total-profile condition removes about 0.1 % of pairs (|s| + 2 |m| > 12 um with
          // sigmas 2.5 and 3.17 um), changing it by less than 1 %; the sample's own error is
          // 0.3 %. Allowed: 3 %.
          const double sigma = std::sqrt(sp2 / n - (sp / n) * (sp / n));
          EXPECT_NEAR(sigma / (0.98657 * t.profile_slope / 3), 1, 0.03);
        }
    }
}

TEST(Iso1328Sampler, SameSeedSameDraw)
{
  const Iso1328Tolerances t = sampler_tolerances();
  for (ToleranceDistribution dist : {ToleranceDistribution::uniform, ToleranceDistribution::normal})
    {
      std::mt19937_64 a(12345), b(12345), c(12346);
      const auto      ga = draw_gear_deviations(t, sampler_teeth, dist, a);
      const auto      gb = draw_gear_deviations(t, sampler_teeth, dist, b);
      const auto      gc = draw_gear_deviations(t, sampler_teeth, dist, c);
      EXPECT_EQ(ga.runout_eccentricity, gb.runout_eccentricity);
      EXPECT_EQ(ga.runout_phase, gb.runout_phase);
      EXPECT_NE(ga.runout_eccentricity, gc.runout_eccentricity);
      for (int k = 0; k < sampler_teeth; ++k)
        {
          EXPECT_EQ(ga.teeth[k].pitch_position, gb.teeth[k].pitch_position);
          EXPECT_EQ(ga.teeth[k].profile_slope, gb.teeth[k].profile_slope);
          EXPECT_EQ(ga.teeth[k].profile_form_amplitude, gb.teeth[k].profile_form_amplitude);
          EXPECT_EQ(ga.teeth[k].helix_slope, gb.teeth[k].helix_slope);
          EXPECT_EQ(ga.teeth[k].helix_form_amplitude, gb.teeth[k].helix_form_amplitude);
        }
    }
}

namespace
{
// Brute force: the polar angle at which the flank of `tooth`, in the section z = 0, crosses the
// circle of radius r about the axis of rotation (bisection on the roll angle, |P| grows with it).
double
angle_on_circle(const InvoluteGear &gear, int tooth, FlankSide side, double r)
{
  const InvoluteFlank flank = gear.flank(tooth, side);
  double              lo = flank.domain().u_min, hi = flank.domain().u_max;
  for (int i = 0; i < 200; ++i)
    {
      const double mid                         = (lo + hi) / 2;
      const Vec3   p                           = flank.evaluate(mid, 0).position;
      (std::hypot(p.x(), p.y()) < r ? lo : hi) = mid;
    }
  const Vec3 p = flank.evaluate((lo + hi) / 2, 0).position;
  return std::atan2(p.y(), p.x());
}
} // namespace

TEST(Iso1328Sampler, PitchPositionsAreMeasuredAboutTheAxisOfRotation)
{
  // A helical, profile-shifted gear of class 6 (z 24, m_n 3 mm, beta 20 deg, x 0.3, b 30 mm) with
  // the drawn runout and the toothing's single pitch deviations from single_pitch_deviations:
  // the flanks of the side drawn, measured on the reference circle about the axis of rotation
  // against the nominal gear, sit at the drawn pitch positions (up to a common rotation). The
  // other side measures differently (the runout's share changes sign with the flank's lean), so
  // the side matters. Tolerance 5e-8 m (0.2 % of F_pT): the conversion is first order in
  // e / r; the neglected terms are about e^2 / (r_b tan alpha_t) = (12 um)^2 / 13 mm = 1.1e-8 m.
  InvoluteGearData data;
  data.teeth           = sampler_teeth;
  data.normal_module   = 3 * mm;
  data.helix_angle     = 20 * pi / 180;
  data.profile_shift   = 0.3;
  data.face_width      = 30 * mm;
  const auto   nominal = InvoluteGear::create(data);
  const double r       = nominal->reference_radius;
  const auto   t = iso1328_tolerances(6, 2 * r, data.normal_module, data.face_width, data.teeth);
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      // The first draw of this seed whose runout is not small (e >= F_rT / 4 = 6 um).
      std::mt19937_64 rng(side == FlankSide::drive ? 3 : 4);
      GearDeviations  g;
      do
        g = draw_gear_deviations(t, sampler_teeth, ToleranceDistribution::uniform, rng);
      while (g.runout_eccentricity < t.runout / 4);
      const std::vector<double> f = single_pitch_deviations(g, *nominal, side);
      ASSERT_EQ(static_cast<int>(f.size()), sampler_teeth);
      double sum = 0;
      for (double x : f)
        sum += x;
      EXPECT_NEAR(sum, 0, 1e-20);

      InvoluteGearData deviated_data        = data;
      deviated_data.single_pitch_deviations = f;
      deviated_data.runout                  = {g.runout_eccentricity, g.runout_phase};
      const auto deviated                   = InvoluteGear::create(deviated_data);
      const auto measured                   = [&](int k, FlankSide s) {
        return r * std::remainder(angle_on_circle(*deviated, k, s, r) -
                                                        angle_on_circle(*nominal, k, s, r),
                                                    2 * pi);
      };
      const FlankSide other        = side == FlankSide::drive ? FlankSide::coast : FlankSide::drive;
      double          other_misfit = 0;
      for (int k = 0; k < sampler_teeth; ++k)
        {
          EXPECT_NEAR(measured(k, side) - measured(0, side),
                      g.teeth[k].pitch_position - g.teeth[0].pitch_position, 5e-8)
              << to_string(side) << " tooth " << k;
          other_misfit = std::max(
              other_misfit, std::abs(measured(k, other) - measured(0, other) -
                                     (g.teeth[k].pitch_position - g.teeth[0].pitch_position)));
        }
      // 2 e tan(alpha_t) is the other side's share's difference: well above the tolerance.
      EXPECT_GT(other_misfit,
                0.5 * g.runout_eccentricity * std::tan(nominal->transverse_pressure_angle));
    }
  // A gear of another number of teeth is refused.
  std::mt19937_64 rng(5);
  const auto      g25 = draw_gear_deviations(t, 25, ToleranceDistribution::normal, rng);
  expect_input_error([&] { single_pitch_deviations(g25, *nominal, FlankSide::drive); },
                     {"25 teeth drawn", "has 24"});
}

TEST(Iso1328Sampler, RefusesWhatIsNotASetOfTolerances)
{
  const Iso1328Tolerances t = sampler_tolerances();
  std::mt19937_64         rng(1);
  expect_input_error([&] { draw_gear_deviations(t, 4, ToleranceDistribution::uniform, rng); },
                     {"number of teeth", "z = 4"});
  Iso1328Tolerances zero = t;
  zero.helix_slope       = 0;
  expect_input_error([&] { draw_gear_deviations(zero, 24, ToleranceDistribution::normal, rng); },
                     {"helix slope", "positive"});
  Iso1328Tolerances small_total = t;
  small_total.profile_total     = t.profile_slope / 2;
  expect_input_error(
      [&] { draw_gear_deviations(small_total, 24, ToleranceDistribution::uniform, rng); },
      {"total profile or helix", "F_alphaT"});
}

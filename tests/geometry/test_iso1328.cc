// ISO 1328-1:2013 flank tolerances against values computed by hand from the formulas of 5.3 and
// the rounding rule of 5.2.3.
// No published table of values was found to compare with (see geometry/iso1328.h).
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

// The tolerance Monte Carlo's parts: with every class 0 the samples are the design itself (a
// point at the nominal run); samples are deterministic per index and respect their class;
// percentiles against hand values; the standardized regression recovers a known linear model;
// the variants' results do not depend on the threads.
#include "study/modification_grid.h"
#include "study/tolerance_study.h"
#include "tests/study/fzg_study.h"

#include <gtest/gtest.h>

#include <random>

using namespace gearkit;

namespace
{

PairVariant
design()
{
  PairVariant v;
  for (ToothModifications *m : {&v.pinion, &v.gear})
    m->tip_relief = 15e-6, m->tip_relief_length = 3e-3;
  return v;
}
} // namespace

TEST(ToleranceStudy, ZeroTolerancesGiveTheNominalRun)
{
  const test_data::FzgStudyPair s;
  MeshCycleStudyOptions         o;
  o.positions = 4, o.cycles = 2, o.harmonics = 2, o.torques = {150};
  ToleranceSampling zero; // classes 0
  const auto        variant = [&](std::size_t k) {
    return draw_tolerance_sample(s.pinion->involute(), s.gear->involute(), FlankSide::drive, zero,
                                        design(), k)
        .variant;
  };
  const ToleranceSample t = draw_tolerance_sample(s.pinion->involute(), s.gear->involute(),
                                                  FlankSide::drive, zero, design(), 3);
  EXPECT_TRUE(t.variant.pinion_teeth.empty() && t.variant.gear_pitch.empty());
  EXPECT_EQ(t.features, std::vector<double>(tolerance_feature_names().size(), 0.0));
  const std::vector<VariantCycle> r =
      evaluate_variants(s.pinion, s.gear, s.assembly, {}, s.contact, test_data::tooth_compliance,
                        test_data::tooth_compliance, o, 3, variant, MPI_COMM_SELF);
  const MeshCycleStudy study(s.pinion, s.gear, s.assembly, {}, s.contact,
                             test_data::tooth_compliance, test_data::tooth_compliance, o);
  const VariantCycle   nominal = study.evaluate(design());
  for (const VariantCycle &c : r)
    {
      EXPECT_EQ(c.loaded_te, nominal.loaded_te);
      EXPECT_EQ(c.mesh_stiffness, nominal.mesh_stiffness);
      EXPECT_EQ(c.te_peak_to_peak, nominal.te_peak_to_peak);
    }
  // the design repeats every mesh cycle
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(nominal.loaded_te[4 + i], nominal.loaded_te[i], 1e-12);
}

TEST(ToleranceStudy, SamplesAreDeterministicAndWithinTheirClass)
{
  const test_data::FzgStudyPair s;
  ToleranceSampling             o;
  o.pinion_class = 6, o.gear_class = 5, o.seed = 42;
  const InvoluteGear   &p = s.pinion->involute(), &g = s.gear->involute();
  const ToleranceSample a = draw_tolerance_sample(p, g, FlankSide::drive, o, design(), 17);
  const ToleranceSample b = draw_tolerance_sample(p, g, FlankSide::drive, o, design(), 17);
  const ToleranceSample c = draw_tolerance_sample(p, g, FlankSide::drive, o, design(), 18);
  EXPECT_EQ(a.features, b.features);
  EXPECT_EQ(a.variant.pinion_pitch, b.variant.pinion_pitch);
  EXPECT_NE(a.features, c.features);
  ASSERT_EQ(a.variant.pinion_teeth.size(), 16u);
  ASSERT_EQ(a.variant.gear_pitch.size(), 24u);
  EXPECT_EQ(a.variant.pinion.tip_relief, 15e-6); // the design kept
  const Iso1328Tolerances tp = iso1328_tolerances(6, 2 * p.reference_radius, 4.5e-3, 14e-3, 16);
  const Iso1328Tolerances tg = iso1328_tolerances(5, 2 * g.reference_radius, 4.5e-3, 14e-3, 24);
  for (std::size_t k = 0; k < 200; ++k)
    {
      const ToleranceSample t = draw_tolerance_sample(p, g, FlankSide::drive, o, design(), k);
      EXPECT_LE(t.features[0], tp.cumulative_pitch * (1 + 1e-12));
      EXPECT_LE(2 * t.features[1], tp.runout * (1 + 1e-12));
      EXPECT_LE(t.features[2], tp.profile_slope * (1 + 1e-12));
      EXPECT_LE(t.features[6], tg.cumulative_pitch * (1 + 1e-12));
      for (const ToothModifications &m : t.variant.pinion_teeth)
        {
          EXPECT_LE(std::abs(m.profile_slope), tp.profile_slope * (1 + 1e-12));
          EXPECT_LE(2 * m.waviness_amplitude, tp.profile_form * (1 + 1e-12));
          EXPECT_LE(m.lead_crowning, tp.helix_form * (1 + 1e-12));
        }
    }
  o.pinion_class = 12;
  EXPECT_THROW(draw_tolerance_sample(p, g, FlankSide::drive, o, design(), 0), InputError);
}

TEST(ToleranceStudy, PercentilesAsNumPyComputesThem)
{
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 50), 2.5);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 0), 1);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 100), 4);
  EXPECT_DOUBLE_EQ(percentile({10, 20}, 95), 19.5);
  std::vector<double> x;
  for (int i = 0; i <= 100; ++i)
    x.push_back(100 - i);
  EXPECT_DOUBLE_EQ(percentile(x, 37), 37);
  EXPECT_THROW(percentile({}, 50), InputError);
  EXPECT_THROW(percentile({1}, 101), InputError);
}

TEST(ToleranceStudy, StandardizedRegressionRecoversALinearModel)
{
  // y = 3 x1 - 2 x2 + 0 x3 + small noise, x4 constant: the SRC are the slopes times sd(x)/sd(y)
  std::mt19937_64                        rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double>       noise(0, 1e-3);
  std::vector<std::vector<double>>       X;
  std::vector<double>                    y;
  for (int i = 0; i < 400; ++i)
    {
      const double x1 = U(rng), x2 = 2 * U(rng), x3 = U(rng);
      X.push_back({x1, x2, x3, 5.0});
      y.push_back(3 * x1 - 2 * x2 + noise(rng));
    }
  const auto sd = [](const std::vector<double> &v) {
    double m = 0, s = 0;
    for (const double a : v)
      m += a / double(v.size());
    for (const double a : v)
      s += (a - m) * (a - m) / double(v.size() - 1);
    return std::sqrt(s);
  };
  std::vector<double> c1, c2;
  for (const auto &r : X)
    c1.push_back(r[0]), c2.push_back(r[1]);
  const Sensitivity s = standardized_regression(X, y, 100, 9);
  EXPECT_NEAR(s.coefficient[0], 3 * sd(c1) / sd(y), 2e-3);
  EXPECT_NEAR(s.coefficient[1], -2 * sd(c2) / sd(y), 2e-3);
  EXPECT_NEAR(s.coefficient[2], 0, 2e-3);
  EXPECT_EQ(s.coefficient[3], 0); // does not vary
  EXPECT_EQ(s.low[3], 0);
  EXPECT_EQ(s.high[3], 0);
  // Near the population's SRC (x1 ~ U(0, 1), x2 ~ U(0, 2): sd 1 / sqrt 12 and 2 / sqrt 12,
  // sd y = sqrt(9 / 12 + 16 / 12)): 0.6 and -0.8; the sample's SRC vary with the sample's
  // spreads (relative sd about 1 / sqrt(2 n), 0.02 here), and so do the intervals, some 0.1
  // wide, around them.
  const double truth[] = {0.6, -0.8, 0};
  for (std::size_t k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(s.coefficient[k], truth[k], 0.05) << k;
      EXPECT_LE(s.low[k], s.coefficient[k]);
      EXPECT_GE(s.high[k], s.coefficient[k]);
      EXPECT_LT(s.high[k] - s.low[k], 0.2) << k;
    }
  EXPECT_GT(s.r2, 0.9999);
}

TEST(ToleranceStudy, SamplesDoNotDependOnTheThreads)
{
  const test_data::FzgStudyPair s;
  MeshCycleStudyOptions         o;
  o.positions = 4, o.cycles = 2, o.harmonics = 2, o.torques = {150};
  ToleranceSampling classes;
  classes.pinion_class = 7, classes.gear_class = 7;
  const auto variant = [&](std::size_t k) {
    return draw_tolerance_sample(s.pinion->involute(), s.gear->involute(), FlankSide::drive,
                                 classes, design(), k)
        .variant;
  };
  o.threads = 1;
  const auto one =
      evaluate_variants(s.pinion, s.gear, s.assembly, {}, s.contact, test_data::tooth_compliance,
                        test_data::tooth_compliance, o, 3, variant, MPI_COMM_SELF);
  o.threads = 2;
  const auto two =
      evaluate_variants(s.pinion, s.gear, s.assembly, {}, s.contact, test_data::tooth_compliance,
                        test_data::tooth_compliance, o, 3, variant, MPI_COMM_SELF);
  // equal to rounding (OpenBLAS's own threads, where more than one, round differently)
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < one[k].loaded_te.size(); ++i)
      {
        EXPECT_TRUE(std::isfinite(one[k].loaded_te[i]));
        EXPECT_NEAR(one[k].loaded_te[i], two[k].loaded_te[i], 1e-12 * one[k].loaded_te[i]);
      }
  EXPECT_NE(one[0].te_peak_to_peak, one[1].te_peak_to_peak); // the samples differ
}

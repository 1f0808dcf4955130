// Tolerance Monte Carlo of an involute pair on one compliance: samples of manufactured pairs,
// each tooth's flank deviations and each toothing's pitch deviations and runout drawn within an
// ISO 1328-1:2013 flank tolerance class (geometry/iso1328.h), evaluated as variants of the
// pair's mesh cycle study over several mesh cycles; the outputs' percentiles and which
// deviation drives which output (standardized regression coefficients with bootstrap
// confidence intervals).
#pragma once

#include "geometry/iso1328.h"
#include "study/mesh_cycle_study.h"

#include <cstdint>
#include <string>
#include <vector>

namespace gearkit
{
struct ToleranceSampling
{
  /// ISO 1328-1 flank tolerance class of each member, 1..11; 0: that member without
  /// deviations.
  int                   pinion_class = 0, gear_class = 0;
  ToleranceDistribution distribution = ToleranceDistribution::normal;
  std::uint64_t         seed         = 1;
  /// Also draw the gear axis's parallelism deviations within ISO/TR 10064-3's recommendation
  /// for the gear's class (the pinion's where the gear has none): out of the plane of the axes
  /// f_Sigma_beta = 0.5 (L / b) F_beta, in it f_Sigma_delta = (L / b) F_beta, as angles
  /// 0.5 F_beta / b and F_beta / b whatever the bearing span L.
  bool assembly = true;
};

/// The features a sample is described by (its deviations summed up per member), in this order:
/// cumulative pitch (max - min of the pitch positions), runout eccentricity, and the RMS over
/// the teeth of profile slope, profile form, helix slope and helix form (f_Halpha, f_falpha,
/// f_Hbeta, f_fbeta) [m]; "pinion_" and "gear_" before each name; then the assembly's crossing
/// and intersecting angle times the gear's face width, unsigned (assembly_crossing,
/// assembly_intersecting) [m].
const std::vector<std::string> &
tolerance_feature_names();

struct ToleranceSample
{
  PairVariant         variant;
  std::vector<double> features; ///< tolerance_feature_names() [m]
};

/// Sample `index` of a draw: `base` (the design's modifications) with every tooth's deviations of
/// the working side drawn within the members' classes (draw_gear_deviations; the profile form as
/// one wave of a sine over the profile evaluation range, f_falpha its peak-to-peak; the helix
/// form as a lead crowning of f_fbeta), the toothings' spacing and runout as measured about the
/// axis; with sampling.assembly the gear axis's tilt. Each sample draws from its own stream, seeded
/// by (seed, index): the same sample whatever order, thread or process draws it. Throws InputError
/// for a class outside 0..11 and for gears outside ISO 1328-1's range.
ToleranceSample
draw_tolerance_sample(const InvoluteGear &pinion, const InvoluteGear &gear, FlankSide side,
                      const ToleranceSampling &sampling, const PairVariant &base,
                      std::size_t index);

/// The p-th percentile (0..100) of the values: linear between order statistics (Hyndman and
/// Fan's type 7, NumPy's default). Throws InputError for no value or p outside [0, 100].
double
percentile(std::vector<double> values, double p);

/// Standardized regression coefficients of an output on the features: the least-squares slopes
/// of (y - mean y) / sd y on (x_k - mean x_k) / sd x_k, each feature's share of the output's
/// variation (|SRC| ~ 1: it alone drives it), with their 95 % confidence intervals from
/// `bootstrap` resamples of the samples (percentile intervals, seeded). A feature that does not
/// vary gets 0 and an interval [0, 0]. r2: the fit's coefficient of determination (how much of
/// the output the linear model explains).
struct Sensitivity
{
  std::vector<double> coefficient, low, high;
  double              r2 = 0;
};
Sensitivity
standardized_regression(const std::vector<std::vector<double>> &features,
                        const std::vector<double> &output, int bootstrap = 200,
                        std::uint64_t seed = 1);
} // namespace gearkit

#include "study/tolerance_study.h"

#include "geometry/involute_gear.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>

namespace gearkit
{
const std::vector<std::string> &
tolerance_feature_names()
{
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const char *member : {"pinion_", "gear_"})
      for (const char *f : {"cumulative_pitch", "runout", "profile_slope_rms", "profile_form_rms",
                            "helix_slope_rms", "helix_form_rms"})
        n.push_back(std::string(member) + f);
    n.insert(n.end(), {"assembly_crossing", "assembly_intersecting"});
    return n;
  }();
  return names;
}

namespace
{
/// One member's drawn deviations into the variant (its teeth's, spacing and runout) and its six
/// features.
void
draw_member(const InvoluteGear &gear, FlankSide side, int flank_class,
            ToleranceDistribution distribution, std::mt19937_64 &rng,
            std::vector<ToothModifications> &teeth, std::vector<double> &pitch, Runout &runout,
            std::vector<double> &features)
{
  if (flank_class == 0)
    {
      features.insert(features.end(), 6, 0.0);
      return;
    }
  if (flank_class < 0 || flank_class > 11)
    throw InputError("tolerance sample: " + gear.data().name + " flank tolerance class " +
                     std::to_string(flank_class) +
                     " is not allowed; ISO 1328-1 classes are 1 "
                     "to 11 (0: no deviations)");
  const InvoluteGearData &d = gear.data();
  const double            b = d.face_width, m_n = d.normal_module, r = gear.reference_radius;
  const Iso1328Tolerances t             = iso1328_tolerances(flank_class, 2 * r, m_n, b, d.teeth);
  const GearDeviations    g             = draw_gear_deviations(t, d.teeth, distribution, rng);
  double                  profile_slope = 0, profile_form = 0, helix_slope = 0, helix_form = 0;
  double                  lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const ToothDeviations &k : g.teeth)
    {
      ToothModifications m;
      m.profile_slope       = k.profile_slope;
      m.helix_slope         = k.helix_slope;
      m.waviness_amplitude  = std::abs(k.profile_form_amplitude);
      m.waviness_wavelength = profile_form_wavelength(gear.modification_frame());
      m.waviness_phase      = k.profile_form_amplitude < 0 ? pi : 0;
      m.lead_crowning       = 2 * std::abs(k.helix_form_amplitude); // f_fbeta
      teeth.push_back(m);
      profile_slope += k.profile_slope * k.profile_slope;
      profile_form += 4 * k.profile_form_amplitude * k.profile_form_amplitude;
      helix_slope += k.helix_slope * k.helix_slope;
      helix_form += 4 * k.helix_form_amplitude * k.helix_form_amplitude;
      lo = std::min(lo, k.pitch_position), hi = std::max(hi, k.pitch_position);
    }
  pitch          = single_pitch_deviations(g, gear, side);
  runout         = {g.runout_eccentricity, g.runout_phase};
  const double n = double(g.teeth.size());
  features.insert(features.end(), {hi - lo, g.runout_eccentricity, std::sqrt(profile_slope / n),
                                   std::sqrt(profile_form / n), std::sqrt(helix_slope / n),
                                   std::sqrt(helix_form / n)});
}
} // namespace

ToleranceSample
draw_tolerance_sample(const InvoluteGear &pinion, const InvoluteGear &gear, FlankSide side,
                      const ToleranceSampling &o, const PairVariant &base, std::size_t index)
{
  std::seed_seq   seq{std::uint32_t(o.seed), std::uint32_t(o.seed >> 32), std::uint32_t(index),
                    std::uint32_t(std::uint64_t(index) >> 32)};
  std::mt19937_64 rng(seq);
  ToleranceSample s;
  s.variant = base;
  draw_member(pinion, side, o.pinion_class, o.distribution, rng, s.variant.pinion_teeth,
              s.variant.pinion_pitch, s.variant.pinion_runout, s.features);
  draw_member(gear, side, o.gear_class, o.distribution, rng, s.variant.gear_teeth,
              s.variant.gear_pitch, s.variant.gear_runout, s.features);
  // The assembly (after the members: their draws do not depend on it): ISO/TR 10064-3's
  // parallelism of the axes from F_beta of the gear's class at its face width.
  const bool          by_gear = o.gear_class > 0;
  const InvoluteGear &m       = by_gear ? gear : pinion;
  const int           cls     = by_gear ? o.gear_class : o.pinion_class;
  const double        b       = m.data().face_width;
  if (o.assembly && cls > 0)
    {
      const double F_beta =
          iso1328_tolerances(cls, 2 * m.reference_radius, m.data().normal_module, b, m.data().teeth)
              .helix_total;
      s.variant.crossing_angle     = draw_within(0.5 * F_beta / b, o.distribution, rng);
      s.variant.intersecting_angle = draw_within(F_beta / b, o.distribution, rng);
    }
  s.features.insert(s.features.end(), {b * std::abs(s.variant.crossing_angle),
                                       b * std::abs(s.variant.intersecting_angle)});
  return s;
}

double
percentile(std::vector<double> x, double p)
{
  if (x.empty() || !(p >= 0 && p <= 100))
    throw InputError("percentile: needs values and a percentage in [0, 100]");
  std::sort(x.begin(), x.end());
  const double      at = p / 100 * double(x.size() - 1);
  const std::size_t i  = std::size_t(std::floor(at));
  if (i + 1 >= x.size())
    return x.back();
  return x[i] + (at - double(i)) * (x[i + 1] - x[i]);
}

namespace
{
/// The SRC of y on the columns of X that vary (`used`), others 0; and R^2.
std::vector<double>
src(const Eigen::MatrixXd &X, const Eigen::VectorXd &y, const std::vector<Eigen::Index> &used,
    double *r2 = nullptr)
{
  std::vector<double> beta(std::size_t(X.cols()), 0.0);
  const Eigen::Index  n  = X.rows();
  const double        my = y.mean();
  const double        sy = std::sqrt((y.array() - my).square().sum() / double(n - 1));
  if (!(sy > 0) || used.empty())
    {
      if (r2)
        *r2 = 0;
      return beta;
    }
  Eigen::MatrixXd Z(n, Eigen::Index(used.size()));
  for (std::size_t k = 0; k < used.size(); ++k)
    {
      const Eigen::VectorXd c = X.col(used[k]);
      const double          m = c.mean();
      const double          s = std::sqrt((c.array() - m).square().sum() / double(n - 1));
      Z.col(Eigen::Index(k)) =
          s > 0 ? Eigen::VectorXd((c.array() - m) / s) : Eigen::VectorXd::Zero(n);
    }
  const Eigen::VectorXd v = (y.array() - my) / sy;
  const Eigen::VectorXd b = Z.colPivHouseholderQr().solve(v);
  for (std::size_t k = 0; k < used.size(); ++k)
    beta[std::size_t(used[k])] = b[Eigen::Index(k)];
  if (r2)
    *r2 = 1 - (v - Z * b).squaredNorm() / v.squaredNorm();
  return beta;
}
} // namespace

Sensitivity
standardized_regression(const std::vector<std::vector<double>> &features,
                        const std::vector<double> &output, int bootstrap, std::uint64_t seed)
{
  const std::size_t n = output.size();
  if (n < 3 || features.size() != n)
    throw InputError("standardized regression: needs at least 3 samples, one feature row each");
  const std::size_t F = features.front().size();
  Eigen::MatrixXd   X(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(F));
  Eigen::VectorXd   y(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    {
      if (features[i].size() != F)
        throw InputError("standardized regression: every sample needs the same features");
      for (std::size_t k = 0; k < F; ++k)
        X(Eigen::Index(i), Eigen::Index(k)) = features[i][k];
      y[Eigen::Index(i)] = output[i];
    }
  std::vector<Eigen::Index> used;
  for (Eigen::Index k = 0; k < X.cols(); ++k)
    if (X.col(k).maxCoeff() > X.col(k).minCoeff())
      used.push_back(k);
  Sensitivity s;
  s.coefficient = src(X, y, used, &s.r2);
  std::vector<std::vector<double>>           draws(F);
  std::mt19937_64                            rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  for (int b = 0; b < bootstrap; ++b)
    {
      Eigen::MatrixXd Xb(X.rows(), X.cols());
      Eigen::VectorXd yb(y.size());
      for (Eigen::Index i = 0; i < X.rows(); ++i)
        {
          const Eigen::Index j = Eigen::Index(pick(rng));
          Xb.row(i) = X.row(j), yb[i] = y[j];
        }
      const std::vector<double> c = src(Xb, yb, used);
      for (std::size_t k = 0; k < F; ++k)
        draws[k].push_back(c[k]);
    }
  for (std::size_t k = 0; k < F; ++k)
    {
      s.low.push_back(bootstrap > 0 ? percentile(draws[k], 2.5) : s.coefficient[k]);
      s.high.push_back(bootstrap > 0 ? percentile(draws[k], 97.5) : s.coefficient[k]);
    }
  return s;
}
} // namespace gearkit

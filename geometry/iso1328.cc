#include "geometry/iso1328.h"

#include "geometry/involute_gear.h"
#include "geometry/types.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

namespace gearkit
{
namespace
{
const std::string context = "ISO 1328-1:2013 flank tolerances";

std::string
str(double value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}

// A length of the gear against the standard's range of application, in mm as the standard
// states it. The interface takes metres: a value that fits once divided by 1000 was most likely
// given in millimetres.
void
require_length(const std::string &name, const std::string &symbol, double metres, double lo_mm,
               double hi_mm)
{
  const double mm = metres * 1e3;
  if (lo_mm <= mm && mm <= hi_mm) // false for NaN
    return;
  std::string hint = "this interface takes metres";
  if (lo_mm <= metres && metres <= hi_mm)
    hint += "; " + str(mm) + " mm looks like a value in millimetres given as metres";
  throw InputError(context + ": " + name + " " + symbol + " = " + str(mm) +
                   " mm is outside the standard's range of application " + str(lo_mm) +
                   " mm <= " + symbol + " <= " + str(hi_mm) +
                   " mm (its formulas must not be extrapolated; " + hint + ")");
}

// Range checks of clause 1 and the class, then the helix angle that d, z and m_n imply
// (d = z m_n / cos beta, beta <= 45 deg): this catches a tip diameter or a transverse module
// given for the reference diameter or the normal module.
void
check_gear(int flank_class, double d, double m_n, double b, int z)
{
  if (flank_class < 1 || flank_class > 11)
    throw InputError(context + ": flank tolerance class A = " + std::to_string(flank_class) +
                     " is not defined; the classes are 1 (finest) to 11");
  if (z < 5 || z > 1000)
    throw InputError(context + ": number of teeth z = " + std::to_string(z) +
                     " is outside the standard's range of application 5 <= z <= 1000");
  require_length("reference diameter", "d", d, 5, 15000);
  require_length("normal module", "m_n", m_n, 0.5, 70);
  require_length("face width", "b", b, 4, 1200);
  const double cos_beta = z * m_n / d;
  if (!(cos_beta <= 1 + 1e-9 && cos_beta >= std::cos(pi / 4) * (1 - 1e-9)))
    throw InputError(context + ": the helix angle implied by d = z m_n / cos(beta) (d = " +
                     str(d * 1e3) + " mm, z = " + std::to_string(z) + ", m_n = " + str(m_n * 1e3) +
                     " mm: cos(beta) = " + str(cos_beta) +
                     ") is outside the standard's range 0 <= beta <= 45 deg; d must lie in [" +
                     str(z * m_n * 1e3) + ", " + str(std::sqrt(2.0) * z * m_n * 1e3) +
                     "] mm (is d the reference diameter, m_n the normal module?)");
}

// The formulas of 5.3 in mm -> um, class step applied to the unrounded values; the totals and
// the runout from the unrounded values. Fields in um.
Iso1328Tolerances
unrounded_um(int A, double d_m, double m_n_m, double b_m)
{
  const double      d = d_m * 1e3, m_n = m_n_m * 1e3, b = b_m * 1e3;
  const double      step = std::pow(std::sqrt(2.0), A - 5);
  Iso1328Tolerances t;
  t.single_pitch     = (0.001 * d + 0.4 * m_n + 5) * step;
  t.cumulative_pitch = (0.002 * d + 0.55 * std::sqrt(d) + 0.7 * m_n + 12) * step;
  t.profile_slope    = (0.4 * m_n + 0.001 * d + 4) * step;
  t.profile_form     = (0.55 * m_n + 5) * step;
  t.profile_total    = std::hypot(t.profile_slope, t.profile_form);
  t.helix_slope      = (0.05 * std::sqrt(d) + 0.35 * std::sqrt(b) + 4) * step;
  t.helix_form       = (0.07 * std::sqrt(d) + 0.45 * std::sqrt(b) + 4) * step;
  t.helix_total      = std::hypot(t.helix_slope, t.helix_form);
  t.runout           = 0.9 * t.cumulative_pitch;
  return t;
}

template <typename F>
Iso1328Tolerances
each(const Iso1328Tolerances &t, F f)
{
  return {f(t.single_pitch), f(t.cumulative_pitch), f(t.profile_total),
          f(t.profile_form), f(t.profile_slope),    f(t.helix_total),
          f(t.helix_form),   f(t.helix_slope),      f(t.runout)};
}

// Random numbers the same on every platform (as in measured_flank.cc): the standard library's
// distributions are implementation-defined.
class Draw
{
public:
  Draw(std::mt19937_64 &engine, ToleranceDistribution dist)
      : engine(engine)
      , dist(dist)
  {
  }
  double
  uniform() ///< [0, 1), 53 random bits
  {
    return double(engine() >> 11) * 0x1.0p-53;
  }
  double
  unit() ///< X on [-1, 1]: uniform, or normal with sigma 1/3 drawn again beyond +-1
  {
    if (dist == ToleranceDistribution::uniform)
      return 2 * uniform() - 1;
    for (;;)
      {
        const double u = 1 - uniform(), v = uniform();
        const double x = std::sqrt(-2 * std::log(u)) * std::cos(2 * pi * v) / 3;
        if (std::abs(x) <= 1)
          return x;
      }
  }

private:
  std::mt19937_64      &engine;
  ToleranceDistribution dist;
};

// A slope within +-slope_tol and a form amplitude within +-form_tol / 2, drawn again until
// |slope| + 2 |amplitude| <= total_tol.
std::pair<double, double>
slope_and_form(Draw &draw, double slope_tol, double form_tol, double total_tol)
{
  for (;;)
    {
      const double s = draw.unit() * slope_tol, m = draw.unit() * form_tol / 2;
      if (std::abs(s) + 2 * std::abs(m) <= total_tol)
        return {s, m};
    }
}

void
check_tolerances(const Iso1328Tolerances &t, int teeth)
{
  if (teeth < 5 || teeth > 1000)
    throw InputError("drawing ISO 1328-1 deviations: number of teeth z = " + std::to_string(teeth) +
                     " is outside 5 <= z <= 1000");
  const std::pair<const char *, double> values[] = {{"single pitch", t.single_pitch},
                                                    {"cumulative pitch", t.cumulative_pitch},
                                                    {"total profile", t.profile_total},
                                                    {"profile form", t.profile_form},
                                                    {"profile slope", t.profile_slope},
                                                    {"total helix", t.helix_total},
                                                    {"helix form", t.helix_form},
                                                    {"helix slope", t.helix_slope},
                                                    {"runout", t.runout}};
  for (const auto &[name, value] : values)
    if (!(value > 0 && std::isfinite(value)))
      throw InputError("drawing ISO 1328-1 deviations: the " + std::string(name) +
                       " tolerance = " + str(value * 1e6) + " um; it must be positive and finite");
  if (t.profile_total < std::max(t.profile_slope, t.profile_form) ||
      t.helix_total < std::max(t.helix_slope, t.helix_form))
    throw InputError(
        "drawing ISO 1328-1 deviations: a total profile or helix tolerance is below "
        "its slope or form tolerance (F_alphaT = " +
        str(t.profile_total * 1e6) + ", f_HalphaT = " + str(t.profile_slope * 1e6) +
        ", f_falphaT = " + str(t.profile_form * 1e6) + ", F_betaT = " + str(t.helix_total * 1e6) +
        ", f_HbetaT = " + str(t.helix_slope * 1e6) + ", f_fbetaT = " + str(t.helix_form * 1e6) +
        " um): not a set of ISO 1328-1 tolerances");
}
} // namespace

double
iso1328_round_um(double v)
{
  if (v > 10)
    return std::round(v);
  if (v >= 5)
    return std::round(2 * v) / 2;
  return std::round(10 * v) / 10;
}

Iso1328Tolerances
iso1328_tolerances_unrounded(int flank_class, double reference_diameter, double normal_module,
                             double face_width, int teeth)
{
  check_gear(flank_class, reference_diameter, normal_module, face_width, teeth);
  return each(unrounded_um(flank_class, reference_diameter, normal_module, face_width),
              [](double um) { return um * 1e-6; });
}

Iso1328Tolerances
iso1328_tolerances(int flank_class, double reference_diameter, double normal_module,
                   double face_width, int teeth)
{
  check_gear(flank_class, reference_diameter, normal_module, face_width, teeth);
  return each(unrounded_um(flank_class, reference_diameter, normal_module, face_width),
              [](double um) { return iso1328_round_um(um) * 1e-6; });
}

double
draw_within(double tolerance, ToleranceDistribution dist, std::mt19937_64 &rng)
{
  Draw draw(rng, dist);
  return tolerance * draw.unit();
}

GearDeviations
draw_gear_deviations(const Iso1328Tolerances &t, int teeth, ToleranceDistribution dist,
                     std::mt19937_64 &rng)
{
  check_tolerances(t, teeth);
  Draw           draw(rng, dist);
  GearDeviations g;

  // Runout first, then the pitch's long wave, its per-tooth scatter, then tooth by tooth the
  // profile and helix pairs: a fixed order, so one seed gives one gear.
  g.runout_eccentricity = std::abs(draw.unit()) * t.runout / 2;
  g.runout_phase        = 2 * pi * draw.uniform();

  const double f = t.single_pitch, F = t.cumulative_pitch;
  const double c     = std::min(f, F) / 4;
  const double a_max = std::min((F - 2 * c) / 2, (f - 2 * c) / (2 * std::sin(pi / teeth)));
  const double a     = std::abs(draw.unit()) * a_max;
  const double psi   = 2 * pi * draw.uniform();
  g.teeth.resize(teeth);
  double mean = 0;
  for (int k = 0; k < teeth; ++k)
    {
      g.teeth[k].pitch_position = a * std::sin(2 * pi * k / teeth + psi) + c * draw.unit();
      mean += g.teeth[k].pitch_position / teeth;
    }
  for (ToothDeviations &tooth : g.teeth)
    tooth.pitch_position -= mean;

  for (ToothDeviations &tooth : g.teeth)
    {
      std::tie(tooth.profile_slope, tooth.profile_form_amplitude) =
          slope_and_form(draw, t.profile_slope, t.profile_form, t.profile_total);
      std::tie(tooth.helix_slope, tooth.helix_form_amplitude) =
          slope_and_form(draw, t.helix_slope, t.helix_form, t.helix_total);
    }
  return g;
}

std::vector<double>
single_pitch_deviations(const GearDeviations &g, const InvoluteGear &gear, FlankSide side)
{
  const int z = static_cast<int>(g.teeth.size());
  if (z != gear.data().teeth)
    throw InputError("single pitch deviations for " + gear.data().name + ": " + std::to_string(z) +
                     " teeth drawn, the gear has " + std::to_string(gear.data().teeth));
  const double sign     = side == FlankSide::drive ? 1.0 : -1.0;
  const double r        = gear.reference_radius;
  const double e        = g.runout_eccentricity;
  const double lean     = std::tan(gear.transverse_pressure_angle);
  const double half     = gear.tooth_thickness_reference / (2 * r);
  const auto   toothing = [&](int k) { // q_k: p_k less the runout's share
    const double gk = 2 * pi * k / z + sign * half;
    return g.teeth[k].pitch_position - e * std::sin(g.runout_phase - gk) -
           sign * e * lean * std::cos(g.runout_phase - gk);
  };
  std::vector<double> f(z);
  for (int k = 0; k < z; ++k)
    f[k] = toothing(k) - toothing((k + z - 1) % z);
  return f;
}
} // namespace gearkit

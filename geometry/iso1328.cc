#include "geometry/iso1328.h"

#include "geometry/types.h"

#include <cmath>
#include <sstream>
#include <string>

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
} // namespace gearkit

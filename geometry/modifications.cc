#include "geometry/modifications.h"

#include "geometry/types.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace gearkit
{
bool
ToothModifications::any() const
{
  return tip_relief != 0 || root_relief != 0 || lead_crowning != 0 || end_relief != 0 ||
         profile_crowning != 0 || profile_slope != 0 || helix_slope != 0 ||
         (waviness_amplitude != 0 && waviness_wavelength > 0);
}

bool
ToothModifications::operator==(const ToothModifications &o) const
{
  const auto fields = [](const ToothModifications &m) {
    return std::tie(m.tip_relief, m.tip_relief_length, m.tip_relief_shape, m.root_relief,
                    m.root_relief_length, m.root_relief_shape, m.lead_crowning, m.end_relief,
                    m.end_relief_length, m.profile_crowning, m.profile_slope, m.helix_slope,
                    m.waviness_amplitude, m.waviness_wavelength, m.waviness_phase);
  };
  // 13 doubles and 2 shapes (each padded to a double): a field added to the struct must be
  // compared above
  static_assert(sizeof(ToothModifications) == 15 * sizeof(double),
                "ToothModifications changed: compare its new fields in operator==");
  return fields(*this) == fields(o);
}

namespace
{
// A relief ramp that starts at 0 with zero value and grows to 1 at s = 1; s in [0, 1].
void
ramp(ReliefShape shape, double s, double &value, double &slope)
{
  if (shape == ReliefShape::linear)
    {
      value = s;
      slope = 1;
    }
  else
    {
      value = s * s;
      slope = 2 * s;
    }
}
} // namespace

std::pair<double, double>
active_profile(const ModificationFrame &f)
{
  // Without a mate (a gear on its own) the active profile is not known: the whole involute
  // from the form circle stands in for it.
  const double start =
      std::isnan(f.roll_length_active_start) ? f.roll_length_form : f.roll_length_active_start;
  return {start, f.roll_length_tip};
}

std::pair<double, double>
profile_evaluation_range(const ModificationFrame &f)
{
  const auto [start, end] = active_profile(f);
  return {start, start + 0.92 * (end - start)};
}

std::pair<double, double>
helix_evaluation_range(const ModificationFrame &f)
{
  const double e = std::min(0.05 * f.face_width, f.normal_module);
  return {-0.5 * f.face_width + e, 0.5 * f.face_width - e};
}

double
profile_form_wavelength(const ModificationFrame &f)
{
  const auto [L0, L1] = profile_evaluation_range(f);
  return L1 - L0;
}

NormalDeviation
waviness_term(double amplitude, double wavelength, double sin_phase, double cos_phase,
              double sin_at, double cos_at)
{
  const double k = 2 * pi / wavelength;
  return {amplitude * (sin_at * cos_phase + cos_at * sin_phase),
          amplitude * k * (cos_at * cos_phase - sin_at * sin_phase), 0};
}

NormalDeviation
evaluate_modifications(const ToothModifications &m, const ModificationFrame &f, double L, double z)
{
  NormalDeviation d;
  const double    half_b = 0.5 * f.face_width;

  if (m.tip_relief != 0 && m.tip_relief_length > 0)
    {
      const double start = f.roll_length_tip - m.tip_relief_length;
      if (L > start)
        {
          double v, s;
          ramp(m.tip_relief_shape, (L - start) / m.tip_relief_length, v, s);
          d.value -= m.tip_relief * v;
          d.d_dL -= m.tip_relief * s / m.tip_relief_length;
        }
    }
  if (m.root_relief != 0 && m.root_relief_length > 0)
    {
      const double end = f.roll_length_form + m.root_relief_length;
      if (L < end)
        {
          double v, s;
          ramp(m.root_relief_shape, (end - L) / m.root_relief_length, v, s);
          d.value -= m.root_relief * v;
          d.d_dL += m.root_relief * s / m.root_relief_length;
        }
    }
  if (m.profile_crowning != 0)
    {
      // C_alpha at both ends of the active profile (the start of active profile in mesh, and
      // the tip), none in its middle; the parabola goes on below the start.
      const auto [L0, L1] = active_profile(f);
      const double length = L1 - L0, s = 2 * (L - 0.5 * (L0 + L1)) / length;
      d.value -= m.profile_crowning * s * s;
      d.d_dL -= m.profile_crowning * 2 * s * 2 / length;
    }
  if (m.profile_slope != 0)
    {
      // The mean profile line rises by f_Halpha over the evaluation range (zero in its middle)
      // and goes on linearly beyond it.
      const auto [L0, L1] = profile_evaluation_range(f);
      d.value += m.profile_slope * (L - 0.5 * (L0 + L1)) / (L1 - L0);
      d.d_dL += m.profile_slope / (L1 - L0);
    }
  if (m.waviness_amplitude != 0 && m.waviness_wavelength > 0)
    {
      const double a = 2 * pi / m.waviness_wavelength * (L - f.roll_length_form) + m.waviness_phase;
      const NormalDeviation w = waviness_term(m.waviness_amplitude, m.waviness_wavelength, 0, 1,
                                              std::sin(a), std::cos(a));
      d.value += w.value;
      d.d_dL += w.d_dL;
    }
  if (m.lead_crowning != 0)
    {
      const double s = z / half_b;
      d.value -= m.lead_crowning * s * s;
      d.d_dz -= m.lead_crowning * 2 * s / half_b;
    }
  if (m.end_relief != 0 && m.end_relief_length > 0)
    {
      const double start = half_b - m.end_relief_length;
      if (std::abs(z) > start)
        {
          const double s = (std::abs(z) - start) / m.end_relief_length;
          d.value -= m.end_relief * s;
          d.d_dz -= m.end_relief / m.end_relief_length * (z > 0 ? 1 : -1);
        }
    }
  if (m.helix_slope != 0)
    {
      // Likewise over the helix evaluation range, which is centred on z = 0.
      const auto [z0, z1] = helix_evaluation_range(f);
      d.value += m.helix_slope * z / (z1 - z0);
      d.d_dz += m.helix_slope / (z1 - z0);
    }
  return d;
}

void
check_modifications(const ToothModifications &m, const ModificationFrame &f,
                    const std::string &prefix)
{
  const double L_alpha = f.roll_length_tip - f.roll_length_form;
  auto         fail    = [&](const std::string &what, double value, const std::string &allowed) {
    std::ostringstream s;
    s << prefix << ": " << what << " = " << value * 1e3 << " mm is not allowed; " << allowed;
    throw InputError(s.str());
  };
  if (m.tip_relief_length < 0 || m.tip_relief_length > L_alpha)
    fail("tip relief length", m.tip_relief_length,
         "it must lie in [0, " + std::to_string(L_alpha * 1e3) + "] mm (the active profile)");
  if (m.root_relief_length < 0 || m.root_relief_length > L_alpha)
    fail("root relief length", m.root_relief_length,
         "it must lie in [0, " + std::to_string(L_alpha * 1e3) + "] mm (the active profile)");
  if (m.end_relief_length < 0 || m.end_relief_length > 0.5 * f.face_width)
    fail("end relief length", m.end_relief_length,
         "it must lie in [0, b/2 = " + std::to_string(0.5 * f.face_width * 1e3) + "] mm");
  if (m.waviness_wavelength < 0)
    fail("waviness wavelength", m.waviness_wavelength, "it must be >= 0 (0 = no waviness)");
  if (m.tip_relief != 0 && m.tip_relief_length == 0)
    fail("tip relief length", 0, "a tip relief needs a length > 0");
  if (m.root_relief != 0 && m.root_relief_length == 0)
    fail("root relief length", 0, "a root relief needs a length > 0");
  if (m.end_relief != 0 && m.end_relief_length == 0)
    fail("end relief length", 0, "an end relief needs a length > 0");
}
} // namespace gearkit

#include "tca/bevel_synthesis.h"

#include <cmath>
#include <sstream>

namespace gearkit
{
BevelPairFlanks
bevel_pair_flanks(const BevelPairDesign &d, const PinionMismatch &mismatch, const Misalignment &m)
{
  const auto [pc, gc] = mismatched_cuts(d, mismatch);
  return {std::make_shared<BevelMemberFlanks>(pc), std::make_shared<BevelMemberFlanks>(gc),
          Assembly::bevel(d.shaft_angle, bevel_geometry(d).pitch_angle_pinion, d.gear_teeth, m)};
}

double
bevel_transmission_error_amplitude(const BevelPairDesign &d, const PinionMismatch &mismatch,
                                   int positions, const Misalignment &m)
{
  const BevelPairFlanks f = bevel_pair_flanks(d, mismatch, m);
  TcaOptions            o;
  o.positions_per_mesh = positions;
  const TcaResult r    = UnloadedTca(f.pinion, f.gear, f.assembly, o).run();
  double          lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const TcaPosition &p : r.positions)
    lo = std::min(lo, p.transmission_error), hi = std::max(hi, p.transmission_error);
  return hi - lo;
}

PinionMismatch
synthesise_modified_roll(const BevelPairDesign &d, PinionMismatch m, double amplitude,
                         int positions)
{
  if (!(amplitude > 0))
    throw InputError("modified-roll synthesis: the transmission error amplitude must be > 0");
  // The amplitude grows about linearly with |2C|; the parabola must open the way that shortens
  // each pair's contact (the other sign runs the contact onto the tooth tips). Try a small 2C of
  // each sign and keep the one whose contact stays inside.
  auto amplitude_at = [&](double c2) {
    PinionMismatch t   = m;
    t.modified_roll_2c = c2;
    return bevel_transmission_error_amplitude(d, t, positions) - amplitude;
  };
  auto inside = [&](double c2) {
    PinionMismatch t        = m;
    t.modified_roll_2c      = c2;
    const BevelPairFlanks f = bevel_pair_flanks(d, t);
    TcaOptions            o;
    o.positions_per_mesh = positions;
    for (const TcaPosition &p : UnloadedTca(f.pinion, f.gear, f.assembly, o).run().positions)
      if (p.pairs[p.leading].edge)
        return false;
    return true;
  };
  const double probe = 1e-3;
  const double sign  = inside(-probe) ? -1.0 : 1.0;
  double       x0 = 0, f0 = amplitude_at(m.modified_roll_2c = 0);
  double       x1 = sign * probe, f1 = amplitude_at(x1);
  for (int it = 0; it < 30 && std::abs(f1) > 1e-3 * amplitude; ++it)
    {
      if (f1 == f0)
        break;
      const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
      x0 = x1, f0 = f1;
      x1 = x2, f1 = amplitude_at(x1);
    }
  m.modified_roll_2c = x1;
  if (!(std::abs(f1) <= 1e-3 * amplitude) || !inside(x1))
    {
      std::ostringstream msg;
      msg << "modified-roll synthesis: a transmission error of " << amplitude
          << " rad cannot be reached with the contact inside the flanks (reached " << f1 + amplitude
          << " rad at 2C = " << x1 << ")";
      throw InputError(msg.str());
    }
  return m;
}
} // namespace gearkit

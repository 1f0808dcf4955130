#include "geometry/types.h"

#include <cmath>

namespace gearkit
{
std::pair<Vec3, Vec3>
Flank::normal_derivatives(double u, double v) const
{
  // Step a fixed small fraction of the parameter ranges: central differences then have a
  // truncation error ~ h^2 * n''' and a rounding error ~ 1e-16 / h; h = 1e-5 of the range
  // balances both near 1e-10 relative.
  const FlankDomain d   = domain();
  const double      hu  = 1e-5 * (d.u_max - d.u_min);
  const double      hv  = 1e-5 * (d.v_max - d.v_min);
  const Vec3        n_u = (evaluate(u + hu, v).normal - evaluate(u - hu, v).normal) / (2 * hu);
  const Vec3        n_v = (evaluate(u, v + hv).normal - evaluate(u, v - hv).normal) / (2 * hv);
  return {n_u, n_v};
}
} // namespace gearkit

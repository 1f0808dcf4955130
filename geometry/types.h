// Flank identification and the flank surface interface (vectors and errors: base/types.h).
#pragma once

#include "base/types.h"

#include <utility>

namespace gearkit
{
/// Which flank of a tooth. Convention (both members of a pair, each in its own frame with its
/// axis along +z): the drive flank is the one whose outward normal points in the +theta direction.
/// The driver rotates in +theta and pushes with its drive flank; the driven member rotates in
/// -theta and is pushed on its drive flank. Coast flanks touch when the torque reverses.
enum class FlankSide
{
  drive,
  coast
};

inline const char *
to_string(FlankSide side)
{
  return side == FlankSide::drive ? "drive" : "coast";
}

/// Hand of the helix; for a spur gear (beta = 0) it has no effect.
enum class Hand
{
  right,
  left
};

/// One point of a flank surface r(u, v) with what tooth contact analysis needs: the position,
/// the unit outward normal (out of the tooth material) and the first derivatives. All in metres,
/// in the member frame (member axis = z).
struct FlankPoint
{
  Vec3 position;
  Vec3 normal;
  Vec3 d_du;
  Vec3 d_dv;
};

/// Parameter ranges of a flank: u is the profile parameter (root to tip), v the face parameter.
struct FlankDomain
{
  double u_min, u_max;
  double v_min, v_max;
};

/// A tooth flank as a parametric surface. Implementations: involute (spur and helical) flanks;
/// later generated spiral bevel flanks. The derivatives of the normal, needed for curvatures,
/// come from central differences of the exact normal (relative error about 1e-10).
class Flank
{
public:
  virtual ~Flank() = default;
  virtual FlankPoint
  evaluate(double u, double v) const = 0;
  virtual FlankDomain
  domain() const = 0;
  /// False where the flank has no material inside its domain (e.g. a chipped region).
  virtual bool
  contains(double /*u*/, double /*v*/) const
  {
    return true;
  }

  /// d n / d u and d n / d v by second-order central differences of the exact unit normal.
  std::pair<Vec3, Vec3>
  normal_derivatives(double u, double v) const;
};
} // namespace gearkit

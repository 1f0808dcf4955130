// Plain types shared by every stage: vectors, flank identification, the flank surface interface.
#pragma once

#include <Eigen/Core>

#include <stdexcept>
#include <string>

namespace gearkit
{
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

constexpr double pi = 3.14159265358979323846;

/// Thrown for user input that cannot be used (a parameter out of range, a malformed file).
/// The message names the parameter or file and what is allowed; the driver prints it and exits
/// non-zero.
class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Throws InputError("<context>: <parameter> = <value> is not allowed; expected <allowed>")
/// unless ok: the one form of a bad-parameter message.
void
require_value(bool ok, const std::string &context, const std::string &parameter, double value,
              const std::string &allowed);

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

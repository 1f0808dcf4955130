// What every library shares: small vectors, pi, and the one error type for unusable input
// (with the one form of its message). No gear knowledge here.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <stdexcept>
#include <string>

namespace gearkit
{
/// a mod n in [0, n) for either sign of a (n > 0): the tooth of index a counted either way round,
/// a periodic sample's index. The one rule (tooth pairings, segments' teeth, periodic tables).
template <typename Int>
inline Int
mod(Int a, Int n)
{
  return ((a % n) + n) % n;
}

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

constexpr double pi = 3.14159265358979323846;

/// A small rigid motion: a point x moves by at(x) = translation + rotation x (x - 0), the
/// translation being that of the point at the origin [m], the rotation a vector [rad].
struct RigidMotion
{
  Vec3 translation = Vec3::Zero(), rotation = Vec3::Zero();
  Vec3
  at(const Vec3 &x) const
  {
    return translation + rotation.cross(x);
  }
};

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
} // namespace gearkit

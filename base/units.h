// Unit factors for the input boundary only: a scene value times its factor is SI
// (`prm.get_double("face width") * mm`). Inside the libraries everything is SI already.
#pragma once

#include "base/types.h"

namespace gearkit::units
{
constexpr double mm       = 1e-3;            ///< millimetre [m]
constexpr double um       = 1e-6;            ///< micrometre [m]
constexpr double deg      = pi / 180;        ///< degree [rad]
constexpr double mrad     = 1e-3;            ///< milliradian [rad]
constexpr double urad     = 1e-6;            ///< microradian [rad]
constexpr double GPa      = 1e9;             ///< [Pa]
constexpr double N_per_um = 1e6;             ///< stiffness N/um [N/m]
constexpr double inch     = 0.0254;          ///< [m]
constexpr double lbf      = 4.4482216152605; ///< pound-force [N]
constexpr double ms       = 1e-3;            ///< millisecond [s]

/// Revolutions per minute to rad/s (as x * 2 pi / 60, the rounding every stored result has).
constexpr double
from_rpm(double x)
{
  return x * 2 * pi / 60;
}
} // namespace gearkit::units

// A small valid CMM point file and one mutation of it per class of malformed input. Shared by
// the reader's tests (message, line) and the driver's tests (exit code, no result file).
#pragma once

#include <string>
#include <vector>

namespace gearkit::test_data
{
inline const std::string &
valid_cmm()
{
  static const std::string text = R"(format = gearkit-cmm 1
member = pinion
teeth = 3
units = mm
normals = no

begin flank
tooth = 1
side = drive
grid = 2 2
0 0 10.0 1.0 -1.0
0 1 10.0 1.2 1.0
1 0 11.0 0.9 -1.0
1 1 11.0 1.1 1.0
end flank
)";
  return text;
}

/// Replace the first match of `from` by `to` in valid_cmm(); the reader must then fail at
/// "<file><line>" with a message containing `expected`.
struct MalformedCmm
{
  const char *what, *from, *to, *line, *expected;
};

inline const std::vector<MalformedCmm> &
malformed_cmm_cases()
{
  static const std::vector<MalformedCmm> cases = {
      {"missing header key", "member = pinion\n", "", ":", "'member"},
      {"unknown header key", "units = mm\n", "units = mm\ncolour = red\n",
       ":5:", "documented keys"},
      {"wrong count", "1 1 11.0 1.1 1.0\n", "", ":14:", "4 = 2 x 2"},
      {"non-numeric", "11.0 1.1 1.0", "11.0 one 1.0", ":14:", "a decimal number"},
      {"NaN", "11.0 1.1 1.0", "11.0 nan 1.0", ":14:", "finite"},
      // finite to the parser, but a distance of "inf um" from the flank later
      {"point at infinity", "11.0 1.1 1.0", "11.0 1e308 1.0",
       ":14:", "y '1e308' is not a finite number a point can have"},
      {"duplicate index", "1 1 11.0", "1 0 11.0", ":14:", "each grid index once"},
      {"duplicate point", "1 1 11.0 1.1 1.0", "1 1 11.0 0.9 -1.0", ":14:", "line 13"},
      {"index outside the grid", "1 1 11.0", "2 1 11.0", ":14:", "[0, 1]"},
      {"mixed units", "grid = 2 2\n", "grid = 2 2\nunits = m\n", ":11:", "one unit"},
      {"tooth beyond z", "tooth = 1", "tooth = 3", ":8:", "[0, 2]"},
      {"unknown side", "side = drive", "side = left", ":9:", "drive or coast"},
      {"missing end", "end flank\n", "", ":7:", "'end flank'"},
      {"wrong column count", "0 0 10.0 1.0 -1.0", "0 0 10.0 1.0", ":11:", "5 (i j x y z)"},
      {"bad units", "units = mm", "units = inch", ":", "units = mm or units = m"},
      {"bad format", "gearkit-cmm 1", "gearkit-cmm 7", ":1:", "'gearkit-cmm 1'"},
  };
  return cases;
}
} // namespace gearkit::test_data

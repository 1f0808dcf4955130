#include "measured_flank.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>

namespace gearkit
{
namespace
{
// --- reading: one small line reader for both formats ----------------------------------------

/// The content lines of a text file (comments after '#' and blank lines dropped), with line
/// numbers, and the error messages "<file>:<line>: <what>; expected <what>".
class TextReader
{
public:
  explicit TextReader(const std::string &path)
      : path(path)
  {
    std::ifstream in(path);
    if (!in)
      throw InputError(path + ": cannot open the file; expected a readable text file");
    std::string text;
    for (int number = 1; std::getline(in, text); ++number)
      {
        text         = text.substr(0, text.find('#'));
        const auto b = text.find_first_not_of(" \t\r"), e = text.find_last_not_of(" \t\r");
        if (b != std::string::npos)
          lines.push_back({number, text.substr(b, e - b + 1)});
      }
    if (lines.empty())
      throw InputError(path + ":1: the file is empty; expected a header (format = ...)");
  }

  bool
  done() const
  {
    return next_line >= lines.size();
  }
  const std::string &
  peek() const
  {
    return lines.at(next_line).text;
  }
  const std::string &
  take()
  {
    current = lines.at(next_line).number;
    return lines.at(next_line++).text;
  }
  int
  line() const
  {
    return current;
  }
  /// Report the following errors at this line (e.g. the line of a key read earlier).
  TextReader &
  at(int line)
  {
    current = line;
    return *this;
  }

  [[noreturn]] void
  fail(const std::string &what, const std::string &expected) const
  {
    throw InputError(path + ":" + std::to_string(current) + ": " + what + "; expected " + expected);
  }

  /// "key = value" -> (key, value); fails on other lines.
  std::pair<std::string, std::string>
  key_value(const std::string &text) const
  {
    const auto eq = text.find('=');
    if (eq == std::string::npos)
      fail("'" + text + "' is not a 'key = value' line", "a 'key = value' line");
    auto trim = [](std::string s) {
      const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
      return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
    };
    return {trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
  }

  double
  number(const std::string &token, const std::string &what) const
  {
    char        *end   = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (token.empty() || *end != '\0')
      fail(what + " '" + token + "' is not a number", "a decimal number");
    if (!std::isfinite(value))
      fail(what + " is " + token, "a finite number (no NaN or inf)");
    return value;
  }

  int
  integer(const std::string &token, const std::string &what, int lo, int hi) const
  {
    const double v = number(token, what);
    if (v != std::floor(v) || v < lo || v > hi)
      fail(what + " " + token + " is out of range",
           "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
  }

  std::vector<double>
  numbers(const std::string &text, const std::string &what) const
  {
    std::istringstream  s(text);
    std::vector<double> values;
    for (std::string token; s >> token;)
      values.push_back(number(token, what));
    return values;
  }

  std::string path;

private:
  struct Line
  {
    int         number;
    std::string text;
  };
  std::vector<Line> lines;
  std::size_t       next_line = 0;
  int               current   = 0;
};

/// A "key = value" line's value and where it stood.
struct Entry
{
  std::string value;
  int         line;
};
using Entries = std::map<std::string, Entry>;

/// Header "key = value" lines up to the first "begin flank": every required key once, nothing
/// unknown.
Entries
read_header(TextReader &in, const std::set<std::string> &required,
            const std::set<std::string> &optional)
{
  Entries header;
  while (!in.done() && in.peek() != "begin flank")
    {
      const auto [key, value] = in.key_value(in.take());
      if (!required.count(key) && !optional.count(key))
        in.fail("unknown header key '" + key + "'", "one of the documented keys");
      if (!header.emplace(key, Entry{value, in.line()}).second)
        in.fail("header key '" + key + "' appears twice", "each key once");
    }
  for (const std::string &key : required)
    if (!header.count(key))
      in.fail("the header has no '" + key + "' key", "'" + key + " = ...' before 'begin flank'");
  return header;
}

FlankSide
parse_side(const TextReader &in, const std::string &value)
{
  if (value == "drive")
    return FlankSide::drive;
  if (value == "coast")
    return FlankSide::coast;
  in.fail("side '" + value + "' is unknown", "drive or coast");
}

/// Key lines at the top of a flank block (up to the first line without '=').
Entries
read_block_keys(TextReader &in, const std::set<std::string> &required,
                const std::set<std::string> &optional, int begin_line)
{
  Entries keys;
  while (!in.done() && in.peek().find('=') != std::string::npos)
    {
      const auto [key, value] = in.key_value(in.take());
      if (!required.count(key) && !optional.count(key))
        in.fail("unknown flank key '" + key + "'", "one of the documented keys");
      if (!keys.emplace(key, Entry{value, in.line()}).second)
        in.fail("flank key '" + key + "' appears twice", "each key once per block");
    }
  for (const std::string &key : required)
    if (!keys.count(key))
      throw InputError(in.path + ":" + std::to_string(begin_line) + ": the flank block has no '" +
                       key + "' key; expected '" + key + " = ...' after 'begin flank'");
  return keys;
}

void
check_format(TextReader &in, const Entry &format, const std::string &expected)
{
  if (format.value != expected)
    in.at(format.line).fail("format '" + format.value + "' is not supported", "'" + expected + "'");
}

// --- writing -----------------------------------------------------------------------------------

/// Writes through a temporary file that is renamed into place; removes it on failure.
void
write_atomically(const std::string &path, const std::function<void(std::ostream &)> &body)
{
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out)
      throw InputError(path + ": cannot write (is the directory there and writable?)");
    body(out);
    out.flush();
    if (!out)
      {
        std::remove(tmp.c_str());
        throw InputError(path + ": writing failed");
      }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    {
      std::remove(tmp.c_str());
      throw InputError(path + ": cannot rename the temporary file into place");
    }
}

std::string
fixed(double v, int decimals)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

// --- random numbers, the same on every platform ------------------------------------------------

class Random
{
public:
  explicit Random(std::uint64_t seed)
      : engine(seed)
  {
  }
  double
  uniform() // [0, 1)
  {
    return (engine() >> 11) * 0x1.0p-53;
  }
  double
  normal() // Box-Muller
  {
    const double u = 1 - uniform(), v = uniform();
    return std::sqrt(-2 * std::log(u)) * std::cos(2 * pi * v);
  }

private:
  std::mt19937_64 engine;
};
} // namespace

// --- virtual CMM -------------------------------------------------------------------------------

MeasuredMember
virtual_cmm(const InvoluteGear &gear, const std::string &member, int n_profile, int n_face,
            double margin, const std::vector<int> &teeth)
{
  std::vector<int> list = teeth;
  if (list.empty())
    {
      list.resize(gear.teeth());
      std::iota(list.begin(), list.end(), 0);
    }
  MeasuredMember m{member, gear.teeth(), {}};
  for (int k : list)
    for (FlankSide side : {FlankSide::drive, FlankSide::coast})
      {
        const FlankGrid g = sample_flank(gear.flank(k, side), n_profile, n_face, margin);
        m.flanks.push_back({k, side, n_profile, n_face, g.positions, g.normals});
      }
  return m;
}

// --- CMM point files ---------------------------------------------------------------------------

void
write_cmm_file(const std::string &path, const MeasuredMember &m, const CmmWriteOptions &o)
{
  const bool normals = o.normals && !m.flanks.empty() &&
                       std::all_of(m.flanks.begin(), m.flanks.end(),
                                   [](const MeasuredFlank &f) { return !f.normals.empty(); });
  const double scale = o.millimetres ? 1e3 : 1;
  write_atomically(path, [&](std::ostream &out) {
    out << "# gearkit CMM point file (docs/cmm-format.md)\n"
        << "format = gearkit-cmm 1\n"
        << "member = " << m.member << "\n"
        << "teeth = " << m.teeth << "\n"
        << "units = " << (o.millimetres ? "mm" : "m") << "\n"
        << "frame = member axis z, tooth 0 centred on +x at z = 0, right-handed\n"
        << "normals = " << (normals ? "yes" : "no") << "\n";
    for (const MeasuredFlank &f : m.flanks)
      {
        out << "\nbegin flank\ntooth = " << f.tooth << "\nside = " << to_string(f.side)
            << "\ngrid = " << f.n_profile << " " << f.n_face << "\n"
            << (normals ? "# i_profile i_face x y z nx ny nz\n" : "# i_profile i_face x y z\n");
        for (int i = 0; i < f.n_profile; ++i)
          for (int j = 0; j < f.n_face; ++j)
            {
              const std::size_t k = std::size_t(i) * f.n_face + j;
              out << i << " " << j;
              for (int c = 0; c < 3; ++c)
                out << " " << fixed(f.points[k][c] * scale, o.decimals);
              if (normals)
                for (int c = 0; c < 3; ++c)
                  out << " " << fixed(f.normals[k][c], 15);
              out << "\n";
            }
        out << "end flank\n";
      }
  });
}

MeasuredMember
read_cmm_file(const std::string &path)
{
  TextReader in(path);
  const auto header = read_header(in, {"format", "member", "teeth", "units", "normals"}, {"frame"});
  check_format(in, header.at("format"), "gearkit-cmm 1");
  MeasuredMember m;
  m.member           = header.at("member").value;
  const Entry &teeth = header.at("teeth"), &units = header.at("units");
  m.teeth = in.at(teeth.line).integer(teeth.value, "teeth", 1, 1000000);
  if (units.value != "mm" && units.value != "m")
    in.at(units.line)
        .fail("units '" + units.value + "' are not supported", "units = mm or units = m");
  const double scale         = units.value == "mm" ? 1e-3 : 1;
  const Entry &normals_entry = header.at("normals");
  if (normals_entry.value != "yes" && normals_entry.value != "no")
    in.at(normals_entry.line)
        .fail("normals = '" + normals_entry.value + "'", "normals = yes or normals = no");
  const bool normals = normals_entry.value == "yes";

  std::set<std::pair<int, int>> seen_flanks;
  while (!in.done())
    {
      if (in.take() != "begin flank")
        in.fail("a line outside a flank block", "'begin flank'");
      const int  begin      = in.line();
      const auto keys       = read_block_keys(in, {"tooth", "side", "grid"}, {"units"}, begin);
      const int  after_keys = in.line();
      if (keys.count("units") && keys.at("units").value != units.value)
        in.at(keys.at("units").line)
            .fail("the block's units '" + keys.at("units").value + "' differ from the header's '" +
                      units.value + "' (mixed units)",
                  "one unit for the whole file");
      const Entry  &tooth = keys.at("tooth"), &side = keys.at("side"), &grid = keys.at("grid");
      MeasuredFlank f;
      f.tooth = in.at(tooth.line).integer(tooth.value, "tooth index", 0, m.teeth - 1);
      f.side  = parse_side(in.at(side.line), side.value);
      if (!seen_flanks.insert({f.tooth, int(f.side)}).second)
        in.fail("tooth " + tooth.value + " " + side.value + " appears twice",
                "one block per tooth and side");
      std::istringstream       g(grid.value);
      std::vector<std::string> shape{std::istream_iterator<std::string>(g), {}};
      if (shape.size() != 2)
        in.at(grid.line).fail("grid = '" + grid.value + "'",
                              "grid = <profile points> <face points>");
      f.n_profile = in.at(grid.line).integer(shape[0], "profile points", 1, 100000);
      f.n_face    = in.integer(shape[1], "face points", 1, 100000);
      in.at(after_keys);
      const std::size_t count = std::size_t(f.n_profile) * f.n_face;
      f.points.assign(count, Vec3::Zero());
      if (normals)
        f.normals.assign(count, Vec3::Zero());

      std::vector<int>                     filled(count, 0);
      std::map<std::array<double, 3>, int> positions; // exact duplicates -> first line
      const std::size_t                    columns = normals ? 8 : 5;
      std::size_t                          read    = 0;
      for (;;)
        {
          if (in.done())
            throw InputError(path + ":" + std::to_string(begin) +
                             ": the flank block has no 'end flank'; expected 'end flank' after "
                             "its points");
          const std::string &text = in.take();
          if (text == "end flank")
            break;
          std::istringstream       s(text);
          std::vector<std::string> t;
          for (std::string token; s >> token;)
            t.push_back(token);
          if (t.size() != columns)
            in.fail(std::to_string(t.size()) + " values on a point line",
                    std::to_string(columns) + (normals ? " (i j x y z nx ny nz)" : " (i j x y z)"));
          const int         i = in.integer(t[0], "profile index", 0, f.n_profile - 1);
          const int         j = in.integer(t[1], "face index", 0, f.n_face - 1);
          const std::size_t k = std::size_t(i) * f.n_face + j;
          if (filled[k]++)
            in.fail("grid point (" + t[0] + ", " + t[1] + ") appears twice",
                    "each grid index once");
          const std::array<double, 3> p = {in.number(t[2], "x"), in.number(t[3], "y"),
                                           in.number(t[4], "z")};
          if (const auto [it, fresh] = positions.emplace(p, in.line()); !fresh)
            in.fail("the point duplicates the one on line " + std::to_string(it->second),
                    "distinct points");
          f.points[k] = Vec3(p[0], p[1], p[2]) * scale;
          if (normals)
            {
              const Vec3 n(in.number(t[5], "nx"), in.number(t[6], "ny"), in.number(t[7], "nz"));
              if (std::abs(n.norm() - 1) > 1e-6)
                in.fail("the normal has length " + fixed(n.norm(), 9), "a unit normal (|n| = 1)");
              f.normals[k] = n;
            }
          ++read;
        }
      if (read != count)
        in.fail("the block has " + std::to_string(read) + " points",
                std::to_string(count) + " = " + std::to_string(f.n_profile) + " x " +
                    std::to_string(f.n_face) + " (the declared grid)");
      m.flanks.push_back(std::move(f));
    }
  if (m.flanks.empty())
    in.fail("the file has no flank blocks", "at least one 'begin flank' ... 'end flank'");
  return m;
}

// --- topography files --------------------------------------------------------------------------

void
write_topography_file(const std::string &path, const TopographyMember &m)
{
  write_atomically(path, [&](std::ostream &out) {
    out << "# gearkit flank topography file (docs/cmm-format.md)\n"
        << "format = gearkit-topography 1\nmember = " << m.member << "\nteeth = " << m.teeth
        << "\nposition units = mm\ndeviation units = um\n";
    for (const FlankTopography &f : m.flanks)
      {
        out << "\nbegin flank\ntooth = " << f.tooth << "\nside = " << to_string(f.side)
            << "\ndiameters =";
        for (double d : f.diameters)
          out << " " << fixed(d * 1e3, 6);
        out << "\nface =";
        for (double z : f.face)
          out << " " << fixed(z * 1e3, 6);
        out << "\n# one line per diameter (root to tip): deviations at the face positions [um]\n";
        for (std::size_t i = 0; i < f.diameters.size(); ++i)
          {
            for (std::size_t j = 0; j < f.face.size(); ++j)
              out << (j ? " " : "") << fixed(f.deviations[i * f.face.size() + j] * 1e6, 6);
            out << "\n";
          }
        out << "end flank\n";
      }
  });
}

TopographyMember
read_topography_file(const std::string &path)
{
  TextReader in(path);
  const auto header =
      read_header(in, {"format", "member", "teeth", "position units", "deviation units"}, {});
  check_format(in, header.at("format"), "gearkit-topography 1");
  TopographyMember m;
  m.member           = header.at("member").value;
  const Entry &teeth = header.at("teeth");
  m.teeth            = in.at(teeth.line).integer(teeth.value, "teeth", 1, 1000000);
  const std::map<std::string, double> lengths = {{"m", 1}, {"mm", 1e-3}, {"um", 1e-6}};
  auto                                unit    = [&](const std::string &key) {
    const auto it = lengths.find(header.at(key).value);
    if (it == lengths.end())
      in.at(header.at(key).line)
          .fail(key + " '" + header.at(key).value + "' are not supported", "m, mm or um");
    return it->second;
  };
  const double position = unit("position units"), deviation = unit("deviation units");

  std::set<std::pair<int, int>> seen;
  while (!in.done())
    {
      if (in.take() != "begin flank")
        in.fail("unexpected line outside a flank block", "'begin flank'");
      const int       begin = in.line();
      const auto      keys = read_block_keys(in, {"tooth", "side", "diameters", "face"}, {}, begin);
      const int       after_keys = in.line();
      FlankTopography f;
      f.tooth = in.at(keys.at("tooth").line)
                    .integer(keys.at("tooth").value, "tooth index", 0, m.teeth - 1);
      f.side = parse_side(in.at(keys.at("side").line), keys.at("side").value);
      if (!seen.insert({f.tooth, int(f.side)}).second)
        in.fail("tooth " + keys.at("tooth").value + " " + keys.at("side").value + " appears twice",
                "one block per tooth and side");
      for (auto [key, axis] : {std::pair{"diameters", &f.diameters}, {"face", &f.face}})
        {
          in.at(keys.at(key).line);
          for (double v : in.numbers(keys.at(key).value, key))
            axis->push_back(v * position);
          if (axis->size() < 2 || !std::is_sorted(axis->begin(), axis->end()) ||
              std::adjacent_find(axis->begin(), axis->end()) != axis->end())
            in.fail(std::string(key) + " are not strictly increasing",
                    "at least two increasing values");
        }
      in.at(after_keys);
      for (std::size_t i = 0;; ++i)
        {
          if (in.done())
            throw InputError(path + ":" + std::to_string(begin) +
                             ": the flank block has no 'end flank'; expected 'end flank' after "
                             "its deviation rows");
          const std::string &text = in.take();
          if (text == "end flank")
            {
              if (i != f.diameters.size())
                in.fail("the block has " + std::to_string(i) + " deviation rows",
                        std::to_string(f.diameters.size()) + " (one per diameter)");
              break;
            }
          const std::vector<double> row = in.numbers(text, "deviation");
          if (row.size() != f.face.size())
            in.fail(std::to_string(row.size()) + " deviations on the row",
                    std::to_string(f.face.size()) + " (one per face position)");
          if (i >= f.diameters.size())
            in.fail("more deviation rows than diameters",
                    std::to_string(f.diameters.size()) + " rows");
          for (double v : row)
            f.deviations.push_back(v * deviation);
        }
      m.flanks.push_back(std::move(f));
    }
  if (m.flanks.empty())
    in.fail("the file has no flank blocks", "at least one 'begin flank' ... 'end flank'");
  return m;
}

MeasuredMember
topography_to_points(const InvoluteGear &gear, const TopographyMember &t)
{
  if (t.teeth != gear.teeth())
    throw InputError("topography of " + t.member + ": " + std::to_string(t.teeth) +
                     " teeth, but the gear has " + std::to_string(gear.teeth()));
  MeasuredMember m{t.member, t.teeth, {}};
  for (const FlankTopography &f : t.flanks)
    {
      MeasuredFlank       out{f.tooth, f.side, int(f.diameters.size()), int(f.face.size()), {}, {}};
      const InvoluteFlank flank = gear.flank(f.tooth, f.side);
      for (std::size_t i = 0; i < f.diameters.size(); ++i)
        {
          const double r = f.diameters[i] / 2;
          if (r < gear.base_radius || r > gear.tip_radius * (1 + 1e-9))
            throw InputError("topography of " + t.member + ", tooth " + std::to_string(f.tooth) +
                             ": diameter " + std::to_string(2e3 * r) +
                             " mm lies outside the involute [d_b, d_a]");
          for (std::size_t j = 0; j < f.face.size(); ++j)
            {
              const FlankPoint p = flank.nominal(gear.roll_angle(r), f.face[j]);
              out.points.push_back(p.position + f.deviations[i * f.face.size() + j] * p.normal);
              out.normals.push_back(p.normal);
            }
        }
      m.flanks.push_back(std::move(out));
    }
  return m;
}

// --- synthesiser -------------------------------------------------------------------------------

MeasuredMember
synthesise_measured(const MeasuredMember &theory, const SynthesisOptions &o)
{
  Random rng(o.seed);
  // Pitch: one single pitch deviation per tooth of the member, closed to zero sum.
  std::vector<double> cumulative(std::max(theory.teeth, 1), 0.0);
  if (o.pitch_error > 0)
    {
      std::vector<double> fp(theory.teeth);
      for (double &f : fp)
        f = o.pitch_error * rng.normal();
      const double mean = std::accumulate(fp.begin(), fp.end(), 0.0) / theory.teeth;
      for (int k = 1; k < theory.teeth; ++k)
        cumulative[k] = cumulative[k - 1] + fp[k] - mean;
    }

  MeasuredMember out = theory;
  for (MeasuredFlank &f : out.flanks)
    {
      if (f.normals.size() != f.points.size())
        throw InputError("synthesising measured flanks of " + theory.member +
                         ": the theoretical flanks need normals");
      const int np = f.n_profile, nf = f.n_face;
      auto      at = [nf](int i, int j) { return std::size_t(i) * nf + j; };
      // Arc lengths along the profile (middle column) and the face (middle row).
      std::vector<double> s(np, 0.0), t(nf, 0.0);
      for (int i = 1; i < np; ++i)
        s[i] = s[i - 1] + (f.points[at(i, nf / 2)] - f.points[at(i - 1, nf / 2)]).norm();
      for (int j = 1; j < nf; ++j)
        t[j] = t[j - 1] + (f.points[at(np / 2, j)] - f.points[at(np / 2, j - 1)]).norm();

      const double c1 = 2 * rng.uniform() - 1, c2 = 2 * rng.uniform() - 1,
                   c3             = 2 * rng.uniform() - 1;
      const double        phase_s = 2 * pi * rng.uniform(), phase_t = 2 * pi * rng.uniform();
      std::vector<double> white(f.points.size()), rough(f.points.size(), 0.0);
      for (double &w : white)
        w = rng.normal();
      if (o.roughness > 0) // average with the four neighbours; variance 1/5 of white -> rescale
        for (int i = 0; i < np; ++i)
          for (int j = 0; j < nf; ++j)
            {
              double sum = white[at(i, j)];
              int    n   = 1;
              for (auto [di, dj] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}})
                if (i + di >= 0 && i + di < np && j + dj >= 0 && j + dj < nf)
                  sum += white[at(i + di, j + dj)], ++n;
              rough[at(i, j)] = o.roughness * sum / std::sqrt(double(n));
            }

      double r_mean = 0;
      for (const Vec3 &p : f.points)
        r_mean += p.head<2>().norm() / f.points.size();
      const double turn = cumulative[f.tooth] / r_mean;
      const double c = std::cos(turn), sn = std::sin(turn);

      for (int i = 0; i < np; ++i)
        for (int j = 0; j < nf; ++j)
          {
            const std::size_t k  = at(i, j);
            const double      xs = np > 1 ? 2.0 * i / (np - 1) - 1 : 0;
            const double      xt = nf > 1 ? 2.0 * j / (nf - 1) - 1 : 0;
            double            d  = o.form_error / 3 * (c1 * xs + c2 * xt + c3 * (2 * xs * xs - 1));
            if (o.waviness_wavelength > 0)
              d += o.waviness_amplitude / 2 *
                   (std::sin(2 * pi * s[i] / o.waviness_wavelength + phase_s) +
                    std::sin(2 * pi * t[j] / o.waviness_wavelength + phase_t));
            d += rough[k];
            d += o.noise * rng.normal();
            Vec3 p       = f.points[k] + d * f.normals[k];
            f.points[k]  = Vec3(c * p.x() - sn * p.y(), sn * p.x() + c * p.y(), p.z());
            const Vec3 n = f.normals[k];
            f.normals[k] = Vec3(c * n.x() - sn * n.y(), sn * n.x() + c * n.y(), n.z());
          }
    }
  return out;
}
} // namespace gearkit

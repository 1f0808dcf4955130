#include "geometry/measured_flank.h"

#include "geometry/member_flanks.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <set>

namespace gearkit
{
namespace
{
// --- text: one tokenizer and one number parser for both formats -------------------------------

const char *const blanks = " \t\r";

std::string
trim(const std::string &s)
{
  const auto b = s.find_first_not_of(blanks), e = s.find_last_not_of(blanks);
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string>
tokens(const std::string &text)
{
  std::vector<std::string> t;
  for (auto b = text.find_first_not_of(blanks); b != std::string::npos;)
    {
      const auto e = text.find_first_of(blanks, b);
      t.push_back(text.substr(b, e - b));
      b = text.find_first_not_of(blanks, e);
    }
  return t;
}

/// Text from a file, quoted for a message: control and non-ASCII bytes as \xHH (a NUL would
/// cut the message short), at most 40 characters.
std::string
quoted(const std::string &s)
{
  std::string q = "'";
  for (const char c : s.substr(0, 40))
    if (c >= ' ' && c <= '~')
      q += c;
    else
      {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(static_cast<unsigned char>(c)));
        q += hex;
      }
  return q + (s.size() > 40 ? "...'" : "'");
}

/// Shortest decimal that reads back to exactly v (digits = -1), or v with that many decimals.
/// Locale-independent.
std::string
decimal(double v, int digits = -1)
{
  char buffer[400];
  const auto [end, error] =
      digits < 0
          ? std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed)
          : std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, digits);
  if (error != std::errc())
    throw InputError("cannot print " + std::to_string(v) + "; expected a finite value");
  return std::string(buffer, end);
}

struct Line
{
  int         number;
  std::string text; ///< without comment and surrounding blanks; never empty
};

/// A "key = value" line's value and where it stood.
struct Entry
{
  std::string value;
  int         line;
};
using Entries = std::map<std::string, Entry>;

/// The content lines of a text file and the parsing of its values; every error is an InputError
/// "<file>:<line>: <what is wrong>; expected <what is allowed>".
class Reader
{
public:
  /// Reads every content line of `in`; `path` names the input in messages.
  Reader(std::istream &in, const std::string &path)
      : path(path)
  {
    std::string text;
    for (int number = 1; std::getline(in, text); ++number)
      if (std::string t = trim(text.substr(0, text.find('#'))); !t.empty())
        lines.push_back({number, std::move(t)});
    if (lines.empty())
      fail(1, "the file is empty (nothing but comments and blank lines)",
           "a header starting with 'format = ...'");
  }

  bool
  done() const
  {
    return next == lines.size();
  }
  const Line &
  peek() const
  {
    return lines.at(next);
  }
  const Line &
  take()
  {
    return lines.at(next++);
  }
  /// The line where the current list ended: the next line, or the last one at the end.
  int
  here() const
  {
    return done() ? lines.back().number : peek().number;
  }

  [[noreturn]] void
  fail(int line, const std::string &what, const std::string &expected) const
  {
    throw InputError(path + ":" + std::to_string(line) + ": " + what + "; expected " + expected);
  }

  double
  number(int line, const std::string &token, const std::string &what) const
  {
    const char *b = token.data(), *e = b + token.size();
    if (e - b > 1 && b[0] == '+' && b[1] != '-') // from_chars does not take a leading '+'
      ++b;
    double v          = 0;
    const auto [p, r] = std::from_chars(b, e, v);
    if (r == std::errc::result_out_of_range)
      fail(line, what + " " + quoted(token) + " is out of range", "a finite number");
    if (r != std::errc() || p != e)
      fail(line, what + " " + quoted(token) + " is not a number",
           "a decimal number such as -12.345");
    if (!std::isfinite(v))
      fail(line, what + " " + quoted(token) + " is not a finite number",
           "a finite number (no NaN or inf)");
    return v;
  }

  int
  integer(int line, const std::string &token, const std::string &what, int lo, int hi) const
  {
    int v             = 0;
    const auto [p, r] = std::from_chars(token.data(), token.data() + token.size(), v);
    const std::string range =
        "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (r != std::errc() || p != token.data() + token.size())
      fail(line, what + " " + quoted(token) + " is not an integer", range);
    if (v < lo || v > hi)
      fail(line, what + " " + token + " is out of range", range);
    return v;
  }

  /// The value of `key` if it is one of `allowed`.
  const std::string &
  choice(const Entries &keys, const std::string &key, const std::set<std::string> &allowed,
         const std::string &expected) const
  {
    const Entry &e = keys.at(key);
    if (!allowed.count(e.value))
      fail(e.line, key + " " + quoted(e.value) + " is not allowed", expected);
    return e.value;
  }

  /// Consecutive "key = value" lines: each key once, all of `required`, others from `optional`;
  /// then the line `next` or the end of the file, if `next` is given.
  Entries
  keys(const std::string &where, const std::set<std::string> &required,
       const std::set<std::string> &optional, const std::string &next = "")
  {
    Entries found;
    while (!done() && peek().text.find('=') != std::string::npos)
      {
        const Line       &l   = take();
        const auto        eq  = l.text.find('=');
        const std::string key = trim(l.text.substr(0, eq)), value = trim(l.text.substr(eq + 1));
        if (!required.count(key) && !optional.count(key))
          {
            std::string known;
            for (const auto *set : {&required, &optional})
              for (const std::string &k : *set)
                known += (known.empty() ? "" : ", ") + k;
            fail(l.number, "unknown " + where + " key " + quoted(key),
                 "one of the documented keys (" + known + ")");
          }
        if (value.empty())
          fail(l.number, quoted(key) + " has no value", "'" + key + " = <value>'");
        if (!found.emplace(key, Entry{value, l.number}).second)
          fail(l.number, where + " key " + quoted(key) + " appears twice", "each key once");
      }
    if (!next.empty() && !done() && peek().text != next)
      fail(here(), quoted(peek().text) + " is not a 'key = value' line",
           "the " + where + " keys, then '" + next + "'");
    for (const std::string &key : required)
      if (!found.count(key))
        fail(here(), "the " + where + " has no '" + key + "' key",
             "'" + key + " = ...' among the " + where + " keys");
    return found;
  }

  const std::string path;

private:
  std::vector<Line> lines;
  std::size_t       next = 0;
};

/// The file as a stream, or InputError naming it.
std::ifstream
open_for_reading(const std::string &path)
{
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the file; expected a readable text file");
  return in;
}

// The `frame` header line (free text for readers of the file; docs/cmm-format.md). CMM files
// hold cylindrical or bevel members, topography files only involute (cylindrical) ones.
const std::string cmm_frame_description =
    "member axis +z, tooth 0 centred on +x; cylindrical: at z = 0, face z = -b/2 .. b/2; "
    "bevel: cone apex at z = 0, teeth toward +z, at the mean point";
const std::string topography_frame_description = "member axis z, tooth 0 centred on +x at z = 0";

/// The header both formats share: format, member, teeth, frame (optional), units, and `more`.
struct Header
{
  Entries     keys;
  std::string member;
  int         teeth;
};

Header
read_header(Reader &in, const std::string &format, const std::set<std::string> &more)
{
  std::set<std::string> required = {"format", "member", "teeth", "units"};
  required.insert(more.begin(), more.end());
  Header h{in.keys("header", required, {"frame"}, "begin flank"), "", 0};
  in.choice(h.keys, "format", {format}, "'" + format + "'");
  h.member = h.keys.at("member").value;
  h.teeth  = in.integer(h.keys.at("teeth").line, h.keys.at("teeth").value, "teeth", 1, 100000);
  return h;
}

/// One "begin flank" ... "end flank" block: its keys with tooth, side and units checked, and the
/// lines in between.
struct Block
{
  int               begin, end;
  int               tooth;
  FlankSide         side;
  Entries           keys;
  std::vector<Line> body;
};

Block
read_block(Reader &in, const Header &h, const std::set<std::string> &more,
           std::set<std::pair<int, FlankSide>> &seen)
{
  const Line &first = in.take();
  if (first.text != "begin flank")
    in.fail(first.number, quoted(first.text) + " outside a flank block", "'begin flank'");
  std::set<std::string> required = {"tooth", "side"};
  required.insert(more.begin(), more.end());
  Block b{first.number, 0, 0, FlankSide::drive, in.keys("flank block", required, {"units"}), {}};
  const std::string &units = h.keys.at("units").value;
  if (const auto u = b.keys.find("units"); u != b.keys.end() && u->second.value != units)
    in.fail(u->second.line,
            "the block's units " + quoted(u->second.value) +
                " differ from the header's (mixed units)",
            "one unit for the whole file (units = " + units + ")");
  const Entry &tooth = b.keys.at("tooth");
  b.tooth            = in.integer(tooth.line, tooth.value, "tooth index", 0, h.teeth - 1);
  b.side             = in.choice(b.keys, "side", {"drive", "coast"}, "drive or coast") == "drive"
                           ? FlankSide::drive
                           : FlankSide::coast;
  if (!seen.emplace(b.tooth, b.side).second)
    in.fail(tooth.line, "tooth " + tooth.value + " " + to_string(b.side) + " appears twice",
            "one block per tooth and side");
  for (;;)
    {
      if (in.done() || in.peek().text == "begin flank")
        in.fail(b.begin,
                "the flank block has no 'end flank'" +
                    (in.done() ? std::string(" (the file ends first)")
                               : " before the 'begin flank' on line " + std::to_string(in.here())),
                "'end flank' after the block's data");
      const Line &l = in.take();
      if (l.text == "end flank")
        {
          b.end = l.number;
          return b;
        }
      b.body.push_back(l);
    }
}

// --- writing ----------------------------------------------------------------------------------

/// Writes through `path + ".tmp"` renamed into place; on any failure removes it and throws.
void
write_atomically(const std::string &path, const std::function<void(std::ostream &)> &body)
{
  const std::string tmp = path + ".tmp";
  std::ofstream     out(tmp);
  if (!out)
    throw InputError(path + ": cannot create '" + tmp + "'; expected a writable directory");
  try
    {
      body(out);
      out.close();
      if (!out)
        throw InputError(path + ": writing '" + tmp + "' failed; expected room on the disk");
      if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw InputError(path + ": cannot rename '" + tmp + "' to it; expected a replaceable file");
    }
  catch (...)
    {
      out.close();
      std::remove(tmp.c_str());
      throw;
    }
}

/// A member name that reads back unchanged (no comment character, one line, no outer blanks).
void
check_name(const std::string &path, const std::string &name)
{
  if (name.empty() || name != trim(name) || name.find_first_of("#\n") != std::string::npos)
    throw InputError(path + ": member name " + quoted(name) +
                     " cannot be written; expected a non-empty name without '#', line breaks "
                     "or surrounding blanks");
}

} // namespace

void
check_member(const MeasuredMember &m, const std::string &context, bool need_normals)
{
  auto fail = [&](const std::string &what, const std::string &expected) {
    throw InputError(context + ": " + what + "; expected " + expected);
  };
  if (m.teeth < 1)
    fail("member with " + std::to_string(m.teeth) + " teeth", "at least one tooth");
  std::set<std::pair<int, FlankSide>> seen;
  for (const MeasuredFlank &f : m.flanks)
    {
      const std::string name = "tooth " + std::to_string(f.tooth) + " " + to_string(f.side);
      if (f.tooth < 0 || f.tooth >= m.teeth || !seen.emplace(f.tooth, f.side).second)
        fail(name + " is out of range or repeated",
             "distinct flanks of teeth in [0, " + std::to_string(m.teeth - 1) + "]");
      if (f.n_profile < 1 || f.n_face < 1 || f.points.size() != std::size_t(f.n_profile) * f.n_face)
        fail(name + " has " + std::to_string(f.points.size()) + " points on a " +
                 std::to_string(f.n_profile) + " x " + std::to_string(f.n_face) + " grid",
             "n_profile x n_face >= 1 points");
      if (f.normals.size() != (need_normals || !f.normals.empty() ? f.points.size() : 0))
        fail(name + " has " + std::to_string(f.normals.size()) + " normals",
             std::string(need_normals ? "" : "none or ") + "one per point");
      for (std::size_t k = 0; k < f.points.size(); ++k)
        if (!f.points[k].allFinite() ||
            (!f.normals.empty() && !(std::abs(f.normals[k].norm() - 1) <= 1e-6)))
          fail(name + " point " + std::to_string(k) + " is not finite or its normal not unit",
               "finite points and unit normals");
    }
}

namespace
{

bool
strictly_increasing(const std::vector<double> &v)
{
  return !v.empty() && std::adjacent_find(v.begin(), v.end(), std::greater_equal<>()) == v.end();
}

void
check_topography(const TopographyMember &t, const std::string &context)
{
  if (t.teeth < 1)
    throw InputError(context + ": member with " + std::to_string(t.teeth) +
                     " teeth; expected at least one tooth");
  std::set<std::pair<int, FlankSide>> seen;
  for (const FlankTopography &f : t.flanks)
    if (f.tooth < 0 || f.tooth >= t.teeth || !seen.emplace(f.tooth, f.side).second ||
        !strictly_increasing(f.diameters) || !strictly_increasing(f.face) ||
        f.deviations.size() != f.diameters.size() * f.face.size() ||
        !std::all_of(f.deviations.begin(), f.deviations.end(),
                     [](double d) { return std::isfinite(d); }))
      throw InputError(context + ": tooth " + std::to_string(f.tooth) + " " + to_string(f.side) +
                       " is inconsistent; expected distinct flanks of teeth in [0, " +
                       std::to_string(t.teeth - 1) +
                       "], strictly increasing diameters and face positions, and one finite "
                       "deviation per grid point");
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
  uniform() ///< [0, 1), 53 random bits
  {
    return double(engine() >> 11) * 0x1.0p-53;
  }
  double
  normal() ///< standard normal, Box-Muller (cosine branch)
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
virtual_cmm(const std::string &member, int teeth,
            const std::function<FlankGrid(int tooth, FlankSide side)> &sample,
            const std::vector<int> &teeth_to_measure, bool both_sides)
{
  std::vector<int> list = teeth_to_measure;
  if (list.empty())
    {
      list.resize(std::max(teeth, 0));
      std::iota(list.begin(), list.end(), 0);
    }
  MeasuredMember m{member, teeth, {}};
  for (int k : list)
    for (FlankSide side : {FlankSide::drive, FlankSide::coast})
      if (side == FlankSide::drive || both_sides)
        {
          if (k < 0 || k >= teeth)
            throw InputError("virtual CMM of " + member + ": tooth " + std::to_string(k) +
                             "; expected a tooth in [0, " + std::to_string(teeth - 1) + "]");
          const FlankGrid g = sample(k, side);
          m.flanks.push_back({k, side, g.n_u, g.n_v, g.positions, g.normals});
        }
  check_member(m, "virtual CMM of " + member, false);
  return m;
}

MeasuredMember
virtual_cmm(const InvoluteGear &gear, const std::string &member, int n_profile, int n_face,
            double margin, const std::vector<int> &teeth_to_measure, bool both_sides)
{
  return virtual_cmm(InvoluteMemberFlanks(gear.shared_from_this()), member, n_profile, n_face,
                     margin, teeth_to_measure, both_sides);
}

// --- CMM point files ---------------------------------------------------------------------------

void
write_cmm_file(const std::string &path, const MeasuredMember &m, const CmmWriteOptions &o)
{
  check_name(path, m.member);
  check_member(m, path, false);
  if (o.decimals < 0 || o.decimals > 20)
    throw InputError(path + ": " + std::to_string(o.decimals) +
                     " decimals; expected 0 to 20 decimals");
  const bool normals = o.normals && !m.flanks.empty() &&
                       std::all_of(m.flanks.begin(), m.flanks.end(),
                                   [](const MeasuredFlank &f) { return !f.normals.empty(); });
  const double scale = o.millimetres ? 1e3 : 1;
  write_atomically(path, [&](std::ostream &out) {
    out << "# gearkit CMM point file (docs/cmm-format.md)\n"
        << "format = gearkit-cmm 1\nmember = " << m.member << "\nteeth = " << m.teeth
        << "\nframe = " << cmm_frame_description << "\nunits = " << (o.millimetres ? "mm" : "m")
        << "\nnormals = " << (normals ? "yes" : "no") << "\n";
    for (const MeasuredFlank &f : m.flanks)
      {
        out << "\nbegin flank\ntooth = " << f.tooth << "\nside = " << to_string(f.side)
            << "\ngrid = " << f.n_profile << " " << f.n_face << "\n# i_profile i_face x y z"
            << (normals ? " nx ny nz\n" : "\n");
        for (int i = 0; i < f.n_profile; ++i)
          for (int j = 0; j < f.n_face; ++j)
            {
              const std::size_t k = std::size_t(i) * f.n_face + j;
              out << i << " " << j;
              for (int c = 0; c < 3; ++c)
                out << " " << decimal(f.points[k][c] * scale, o.decimals);
              for (int c = 0; normals && c < 3; ++c)
                out << " " << decimal(f.normals[k][c]);
              out << "\n";
            }
        out << "end flank\n";
      }
  });
}

MeasuredMember
read_cmm_file(const std::string &path)
{
  std::ifstream in = open_for_reading(path);
  return read_cmm(in, path);
}

MeasuredMember
read_cmm(std::istream &stream, const std::string &path)
{
  Reader       in(stream, path);
  const Header h = read_header(in, "gearkit-cmm 1", {"normals"});
  // file units per metre; dividing by an exact power of ten rounds once
  const double per_metre =
      in.choice(h.keys, "units", {"mm", "m"}, "units = mm or units = m") == "mm" ? 1e3 : 1;
  const bool normals =
      in.choice(h.keys, "normals", {"yes", "no"}, "normals = yes or normals = no") == "yes";
  const std::size_t columns = normals ? 8 : 5;
  const std::string layout  = normals ? "8 (i j x y z nx ny nz)" : "5 (i j x y z)";
  const char *const names[] = {"x", "y", "z", "nx", "ny", "nz"};

  MeasuredMember                      m{h.member, h.teeth, {}};
  std::set<std::pair<int, FlankSide>> seen;
  while (!in.done())
    {
      const Block  b     = read_block(in, h, {"grid"}, seen);
      const Entry &grid  = b.keys.at("grid");
      const auto   shape = tokens(grid.value);
      if (shape.size() != 2)
        in.fail(grid.line, "grid = " + quoted(grid.value), "grid = <profile points> <face points>");
      MeasuredFlank     f{b.tooth,
                      b.side,
                      in.integer(grid.line, shape[0], "profile points", 1, 1000000),
                      in.integer(grid.line, shape[1], "face points", 1, 1000000),
                      {},
                      {}};
      const std::size_t count     = std::size_t(f.n_profile) * f.n_face;
      const std::string grid_size = std::to_string(count) + " = " + std::to_string(f.n_profile) +
                                    " x " + std::to_string(f.n_face) + " points";

      std::map<std::size_t, std::array<double, 6>> by_index;    // grid index -> x y z nx ny nz
      std::map<std::array<double, 3>, int>         by_position; // -> line
      for (const Line &l : b.body)
        {
          if (by_index.size() == count)
            in.fail(l.number, "more point lines than the declared grid has points", grid_size);
          const auto t = tokens(l.text);
          if (t.size() != columns)
            in.fail(l.number, std::to_string(t.size()) + " values on a point line", layout);
          const int             i = in.integer(l.number, t[0], "profile index", 0, f.n_profile - 1);
          const int             j = in.integer(l.number, t[1], "face index", 0, f.n_face - 1);
          std::array<double, 6> v{};
          for (std::size_t c = 2; c < columns; ++c)
            v[c - 2] = in.number(l.number, t[c], names[c - 2]);
          // A coordinate beyond 1 km is a point at infinity for any gear (a CMM's marker of a
          // missing value, an overflow): said here, with its line, not later as a distance
          // of "inf um" from the flank.
          for (std::size_t c = 0; c < 3; ++c)
            if (std::abs(v[c]) / per_metre > 1e3)
              in.fail(l.number,
                      std::string(names[c]) + " " + quoted(t[c + 2]) +
                          " is not a finite number a point can have (" +
                          (per_metre == 1 ? "m" : "mm") +
                          ", beyond 1 km from the axis: a point at infinity)",
                      "finite coordinates within 1 km of the member's axis");
          if (!by_index.emplace(std::size_t(i) * f.n_face + j, v).second)
            in.fail(l.number, "grid point (" + t[0] + ", " + t[1] + ") appears twice",
                    "each grid index once");
          if (const auto [p, fresh] = by_position.emplace(std::array{v[0], v[1], v[2]}, l.number);
              !fresh)
            in.fail(l.number, "the point duplicates the one on line " + std::to_string(p->second),
                    "distinct points");
          if (const double n = Vec3(v[3], v[4], v[5]).norm(); normals && std::abs(n - 1) > 1e-6)
            in.fail(l.number, "the normal has length " + decimal(n, 9),
                    "a unit normal (| |n| - 1 | <= 1e-6)");
        }
      if (by_index.size() < count)
        {
          std::size_t missing = 0;
          for (auto it = by_index.begin(); it != by_index.end() && it->first == missing; ++it)
            ++missing;
          in.fail(b.end,
                  std::to_string(by_index.size()) + " point lines, grid point (" +
                      std::to_string(missing / f.n_face) + ", " +
                      std::to_string(missing % f.n_face) + ") is missing",
                  grid_size + ", every grid index once");
        }
      for (const auto &[k, v] : by_index)
        {
          f.points.emplace_back(Vec3(v[0], v[1], v[2]) / per_metre);
          if (normals)
            f.normals.emplace_back(v[3], v[4], v[5]);
        }
      m.flanks.push_back(std::move(f));
    }
  if (m.flanks.empty())
    in.fail(in.here(), "the file has no flank blocks", "at least one 'begin flank' block");
  return m;
}

// --- topography files --------------------------------------------------------------------------

void
write_topography_file(const std::string &path, const TopographyMember &m)
{
  check_name(path, m.member);
  check_topography(m, path);
  auto row = [](std::ostream &out, const double *v, std::size_t n, double scale, int digits) {
    for (std::size_t j = 0; j < n; ++j)
      out << (j ? " " : "") << decimal(v[j] * scale, digits);
    out << "\n";
  };
  write_atomically(path, [&](std::ostream &out) {
    out << "# gearkit flank topography file (docs/cmm-format.md)\n"
        << "format = gearkit-topography 1\nmember = " << m.member << "\nteeth = " << m.teeth
        << "\nframe = " << topography_frame_description << "\nunits = mm\ndeviation units = um\n";
    for (const FlankTopography &f : m.flanks)
      {
        const std::size_t nf = f.face.size();
        out << "\nbegin flank\ntooth = " << f.tooth << "\nside = " << to_string(f.side)
            << "\ndiameters = ";
        row(out, f.diameters.data(), f.diameters.size(), 1e3, 9);
        out << "face = ";
        row(out, f.face.data(), nf, 1e3, 9);
        out << "# deviations [um], one row per diameter, one column per face position\n";
        for (std::size_t i = 0; i < f.diameters.size(); ++i)
          row(out, f.deviations.data() + i * nf, nf, 1e6, 6);
        out << "end flank\n";
      }
  });
}

TopographyMember
read_topography_file(const std::string &path)
{
  std::ifstream in = open_for_reading(path);
  return read_topography(in, path);
}

TopographyMember
read_topography(std::istream &stream, const std::string &path)
{
  Reader       in(stream, path);
  const Header h = read_header(in, "gearkit-topography 1", {"deviation units"});
  in.choice(h.keys, "units", {"mm"}, "units = mm (diameters and face positions)");
  in.choice(h.keys, "deviation units", {"um"}, "deviation units = um");
  // values beyond 1 km are points at infinity (as in read_cmm): said here with their line
  auto values = [&](int line, const std::string &text, const std::string &what, double per_metre) {
    std::vector<double> v;
    for (const std::string &t : tokens(text))
      {
        v.push_back(in.number(line, t, what) / per_metre);
        if (std::abs(v.back()) > 1e3)
          in.fail(line,
                  what + " " + quoted(t) +
                      " is not a finite number a flank can have (beyond 1 "
                      "km: a point at infinity)",
                  "finite values within 1 km");
      }
    return v;
  };

  TopographyMember                    m{h.member, h.teeth, {}};
  std::set<std::pair<int, FlankSide>> seen;
  while (!in.done())
    {
      const Block     b = read_block(in, h, {"diameters", "face"}, seen);
      FlankTopography f{b.tooth, b.side, {}, {}, {}};
      for (auto [key, axis] : {std::pair{"diameters", &f.diameters}, {"face", &f.face}})
        {
          const Entry &e = b.keys.at(key);
          *axis          = values(e.line, e.value, key, 1e3);
          if (!strictly_increasing(*axis))
            in.fail(e.line, std::string(key) + " are not strictly increasing",
                    "one or more strictly increasing values [mm]");
        }
      const std::size_t rows = f.diameters.size(), nf = f.face.size();
      if (b.body.size() != rows)
        in.fail(b.body.size() > rows ? b.body[rows].number : b.end,
                std::to_string(b.body.size()) + " deviation rows",
                std::to_string(rows) + " rows, one per diameter");
      for (const Line &l : b.body)
        {
          const std::vector<double> row = values(l.number, l.text, "deviation", 1e6);
          if (row.size() != nf)
            in.fail(l.number, std::to_string(row.size()) + " deviations on the row",
                    std::to_string(nf) + " (one per face position)");
          f.deviations.insert(f.deviations.end(), row.begin(), row.end());
        }
      m.flanks.push_back(std::move(f));
    }
  if (m.flanks.empty())
    in.fail(in.here(), "the file has no flank blocks", "at least one 'begin flank' block");
  return m;
}

MeasuredMember
topography_to_points(const InvoluteGear &gear, const TopographyMember &t)
{
  const std::string context = "topography of " + t.member;
  check_topography(t, context);
  if (t.teeth != gear.teeth())
    throw InputError(context + ": " + std::to_string(t.teeth) + " teeth; expected the gear's " +
                     std::to_string(gear.teeth()));
  const double   tol = 1e-9, half_face = gear.data().face_width / 2;
  MeasuredMember m{t.member, t.teeth, {}};
  for (const FlankTopography &f : t.flanks)
    {
      const std::string name =
          context + ", tooth " + std::to_string(f.tooth) + " " + to_string(f.side) + ": ";
      if (f.diameters.front() < 2 * gear.form_radius * (1 - tol) ||
          f.diameters.back() > 2 * gear.tip_radius * (1 + tol))
        throw InputError(name + "diameters " + decimal(f.diameters.front() * 1e3, 6) + " to " +
                         decimal(f.diameters.back() * 1e3, 6) + " mm; expected the involute [" +
                         decimal(2e3 * gear.form_radius, 6) + ", " +
                         decimal(2e3 * gear.tip_radius, 6) + "] mm (form to tip diameter)");
      if (f.face.front() < -half_face * (1 + tol) || f.face.back() > half_face * (1 + tol))
        throw InputError(name + "face positions " + decimal(f.face.front() * 1e3, 6) + " to " +
                         decimal(f.face.back() * 1e3, 6) + " mm; expected [-b/2, b/2] = +-" +
                         decimal(half_face * 1e3, 6) + " mm");
      const InvoluteFlank flank = gear.flank(f.tooth, f.side);
      MeasuredFlank       out{f.tooth, f.side, int(f.diameters.size()), int(f.face.size()), {}, {}};
      for (std::size_t i = 0; i < f.diameters.size(); ++i)
        for (std::size_t j = 0; j < f.face.size(); ++j)
          {
            const double     xi = gear.roll_angle(std::max(f.diameters[i] / 2, gear.base_radius));
            const FlankPoint p  = flank.nominal(xi, f.face[j]);
            out.points.push_back(p.position + f.deviations[i * f.face.size() + j] * p.normal);
            out.normals.push_back(p.normal);
          }
      m.flanks.push_back(std::move(out));
    }
  return m;
}

// --- synthesiser -------------------------------------------------------------------------------

MeasuredMember
synthesise_measured(const MeasuredMember &theory, const SynthesisOptions &o)
{
  const std::string context = "synthesising measured flanks of " + theory.member;
  for (double v : {o.form_error, o.waviness_amplitude, o.waviness_wavelength, o.roughness, o.noise,
                   o.pitch_error})
    if (!(v >= 0 && std::isfinite(v)))
      throw InputError(context + ": an amplitude or wavelength is " + std::to_string(v) +
                       "; expected finite values >= 0");
  check_member(theory, context, true);
  Random rng(o.seed);

  // Pitch: f_p of every tooth, zero sum, standard deviation pitch_error (the mean removed from z
  // draws shrinks it by sqrt(1 - 1/z), undone here); positions F_k = f_p1 + ... + f_pk, zero mean.
  const int           z = theory.teeth;
  std::vector<double> draw(z), position(z, 0.0);
  for (double &g : draw)
    g = rng.normal();
  const double mean_draw = std::accumulate(draw.begin(), draw.end(), 0.0) / z;
  const double spread    = z > 1 ? o.pitch_error / std::sqrt(1 - 1.0 / z) : 0;
  for (int k = 1; k < z; ++k)
    position[k] = position[k - 1] + spread * (draw[k] - mean_draw);
  const double mean_position = std::accumulate(position.begin(), position.end(), 0.0) / z;
  for (double &p : position)
    p -= mean_position;

  MeasuredMember out = theory;
  for (MeasuredFlank &f : out.flanks)
    {
      const int         np = f.n_profile, nf = f.n_face;
      const std::size_t n  = f.points.size();
      auto              at = [nf](int i, int j) { return std::size_t(i) * nf + j; };
      // Every draw, in this order, whatever the amplitudes.
      std::array<double, 4> form_coefficient;
      for (double &c : form_coefficient)
        c = 2 * rng.uniform() - 1;
      const double phase_profile = 2 * pi * rng.uniform(), phase_face = 2 * pi * rng.uniform();
      std::vector<double> white(n), noise(n);
      for (double &g : white)
        g = rng.normal();
      for (double &g : noise)
        g = rng.normal();

      std::vector<double> d(n, 0.0);
      // Form: slopes and crownings over the grid mapped to [-1, 1]^2, peak scaled to form_error.
      auto unit     = [](int i, int count) { return count > 1 ? 2.0 * i / (count - 1) - 1 : 0.0; };
      const auto &c = form_coefficient;
      double      peak = 0;
      for (int i = 0; i < np; ++i)
        for (int j = 0; j < nf; ++j)
          {
            const double x = unit(i, np), y = unit(j, nf);
            d[at(i, j)] = c[0] * x + c[1] * y + c[2] * (2 * x * x - 1) + c[3] * (2 * y * y - 1);
            peak        = std::max(peak, std::abs(d[at(i, j)]));
          }
      for (double &v : d)
        v = peak > 0 ? o.form_error * v / peak : 0;
      // Waviness along the arc length of the middle column (profile) and middle row (face).
      if (o.waviness_wavelength > 0)
        {
          std::vector<double> s(np, 0.0), t(nf, 0.0);
          for (int i = 1; i < np; ++i)
            s[i] = s[i - 1] + (f.points[at(i, nf / 2)] - f.points[at(i - 1, nf / 2)]).norm();
          for (int j = 1; j < nf; ++j)
            t[j] = t[j - 1] + (f.points[at(np / 2, j)] - f.points[at(np / 2, j - 1)]).norm();
          const double k = 2 * pi / o.waviness_wavelength;
          for (int i = 0; i < np; ++i)
            for (int j = 0; j < nf; ++j)
              d[at(i, j)] += o.waviness_amplitude / 2 *
                             (std::sin(k * s[i] + phase_profile) + std::sin(k * t[j] + phase_face));
        }
      // Roughness (white noise averaged with the four neighbours, unit variance) and noise.
      for (int i = 0; i < np; ++i)
        for (int j = 0; j < nf; ++j)
          {
            double sum   = 0;
            int    count = 0;
            for (auto [di, dj] : {std::pair{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}})
              if (i + di >= 0 && i + di < np && j + dj >= 0 && j + dj < nf)
                sum += white[at(i + di, j + dj)], ++count;
            d[at(i, j)] += o.roughness * sum / std::sqrt(double(count)) + o.noise * noise[at(i, j)];
          }

      double radius = 0;
      for (const Vec3 &p : f.points)
        radius += p.head<2>().norm() / double(n);
      const double turn = radius > 0 ? position[f.tooth] / radius : 0;
      const double cos = std::cos(turn), sin = std::sin(turn);
      auto         rotate = [cos, sin](const Vec3 &v) {
        return Vec3(cos * v.x() - sin * v.y(), sin * v.x() + cos * v.y(), v.z());
      };
      for (std::size_t k = 0; k < n; ++k)
        {
          f.points[k]  = rotate(f.points[k] + d[k] * f.normals[k]);
          f.normals[k] = rotate(f.normals[k]);
        }
    }
  return out;
}
} // namespace gearkit

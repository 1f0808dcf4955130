// Measured flanks: the virtual CMM, CMM and topography files (round trips, every class of
// malformed input, fuzzing, atomic writes), topography to points, and the synthesiser.
#include "geometry/measured_flank.h"
#include "tests/malformed_cmm.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <regex>
#include <sstream>

using namespace gearkit;
using test_data::MalformedCmm;
namespace fs = std::filesystem;

namespace
{
std::shared_ptr<const InvoluteGear>
test_gear()
{
  InvoluteGearData d;
  d.name                              = "test";
  d.teeth                             = 23;
  d.normal_module                     = 2.54e-3;
  d.helix_angle                       = 15 * pi / 180;
  d.face_width                        = 12.7e-3;
  d.drive_modifications.lead_crowning = 6e-6;
  return InvoluteGear::create(d);
}

/// A fresh temporary directory per test (unique, so parallel test runs cannot collide).
class TempDir : public ::testing::Test
{
protected:
  void
  SetUp() override
  {
    std::random_device random;
    do
      dir = fs::temp_directory_path() / ("gearkit-measured-" + std::to_string(random()));
    while (!fs::create_directory(dir));
  }
  void
  TearDown() override
  {
    fs::remove_all(dir);
  }
  std::string
  file(const std::string &name, const std::string &text) const
  {
    std::ofstream((dir / name).string(), std::ios::binary) << text;
    return (dir / name).string();
  }
  std::string
  text(const std::string &path) const
  {
    std::ifstream      in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir;
};

class CmmFile : public TempDir
{
};
class TopographyFile : public TempDir
{
};
class CmmFuzz : public TempDir
{
};

/// The message of the InputError that f throws, "" if it does not throw (other exceptions fail
/// the test).
template <typename F>
std::string
error_of(F &&f)
{
  try
    {
      f();
    }
  catch (const InputError &e)
    {
      return e.what();
    }
  return "";
}

/// The message starts with "<path><line>" (line = ":14:" names line 14, ":" any) and states what
/// is expected.
void
expect_error(const std::string &msg, const std::string &path, const std::string &line,
             const std::string &expected)
{
  EXPECT_EQ(msg.rfind(path + line, 0), 0u) << msg;
  EXPECT_NE(msg.find("; expected "), std::string::npos) << msg;
  EXPECT_NE(msg.find(expected), std::string::npos) << msg;
}

std::string
mutate(const std::string &text, const MalformedCmm &c)
{
  return std::regex_replace(text, std::regex(c.from), c.to,
                            std::regex_constants::format_first_only);
}

std::string
case_name(const ::testing::TestParamInfo<MalformedCmm> &info)
{
  std::string name = info.param.what;
  for (char &c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)))
      c = '_';
  return name;
}
} // namespace

// --- virtual CMM -------------------------------------------------------------------------------

TEST(VirtualCmm, DefaultGridPointsLieOnTheFlank)
{
  const auto g = test_gear();
  // the default is all teeth, both sides, 29 profile x 9 face points, no margin
  const MeasuredMember all = virtual_cmm(*g, "gear");
  ASSERT_EQ(all.flanks.size(), 46u);
  EXPECT_EQ(all.flanks[4 * 2].points, virtual_cmm(*g, "gear", 29, 9, 0, {4}).flanks[0].points);
  EXPECT_EQ(all.flanks[0].n_profile, 29);
  for (double margin : {0.0, 0.05})
    {
      const MeasuredMember m = virtual_cmm(*g, "gear", 9, 29, margin, {4, 11});
      ASSERT_EQ(m.flanks.size(), 4u);
      for (const MeasuredFlank &f : m.flanks)
        {
          ASSERT_EQ(f.points.size(), 261u);
          ASSERT_EQ(f.normals.size(), 261u);
          const InvoluteFlank flank = g->flank(f.tooth, f.side);
          const FlankDomain   d     = flank.domain();
          for (int i = 0; i < 9; ++i)
            for (int j = 0; j < 29; ++j)
              {
                // the grid parameters, computed independently of sample_flank (rounding ~1e-18 m)
                const double u =
                    d.u_min + (margin + (1 - 2 * margin) * i / 8) * (d.u_max - d.u_min);
                const double v =
                    d.v_min + (margin + (1 - 2 * margin) * j / 28) * (d.v_max - d.v_min);
                const FlankPoint p = flank.evaluate(u, v);
                EXPECT_LT((p.position - f.points[i * 29 + j]).norm(), 1e-12);
                EXPECT_LT((p.normal - f.normals[i * 29 + j]).norm(), 1e-12);
              }
        }
    }
}

TEST(VirtualCmm, GenericSamplerMeasuresTheListedTeethAndSides)
{
  std::vector<std::pair<int, FlankSide>> calls;
  auto                                   sample = [&](int k, FlankSide s) {
    calls.emplace_back(k, s);
    FlankGrid g;
    g.n_u = 1, g.n_v = 2;
    g.positions = {Vec3(k, 1, 0), Vec3(k, 1, 1)};
    g.normals   = {Vec3(0, 1, 0), Vec3(0, 1, 0)};
    return g;
  };
  const MeasuredMember some = virtual_cmm("pinion", 5, sample, {3, 1}, false);
  ASSERT_EQ(some.flanks.size(), 2u);
  EXPECT_EQ(some.flanks[0].tooth, 3);
  EXPECT_EQ(some.flanks[1].tooth, 1);
  EXPECT_EQ(some.flanks[1].side, FlankSide::drive);
  EXPECT_EQ(some.flanks[1].points[1], Vec3(1, 1, 1));
  EXPECT_EQ(some.flanks[1].n_face, 2);

  calls.clear();
  const MeasuredMember all = virtual_cmm("pinion", 5, sample);
  EXPECT_EQ(all.flanks.size(), 10u);
  EXPECT_EQ(calls.size(), 10u);
  EXPECT_EQ(calls.back(), std::make_pair(4, FlankSide::coast));

  EXPECT_NE(error_of([&] { virtual_cmm("pinion", 5, sample, {5}); }).find("tooth 5"),
            std::string::npos);
  EXPECT_NE(error_of([&] { virtual_cmm("pinion", 5, sample, {-1}); }).find("[0, 4]"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              virtual_cmm("pinion", 5, sample, {2, 2});
            }).find("repeated"),
            std::string::npos);
  auto bad_grid = [](int, FlankSide) {
    FlankGrid g;
    g.n_u = 2, g.n_v = 2;
    g.positions.resize(3, Vec3::Zero());
    return g;
  };
  EXPECT_NE(error_of([&] { virtual_cmm("pinion", 5, bad_grid); }).find("3 points on a 2 x 2"),
            std::string::npos);
}

// --- CMM files: round trip, reading, writing ---------------------------------------------------

TEST_F(CmmFile, RoundTripKeepsPointsToThePrintedPrecision)
{
  const auto           g = test_gear();
  const MeasuredMember m = virtual_cmm(*g, "pinion", 9, 29, 0, {0, 5, 22});
  ASSERT_EQ(m.flanks.size(), 6u);
  for (const auto &[mm, decimals] : {std::pair{true, 9}, {false, 12}})
    {
      // 9 decimals of mm and 12 of m both print to 1e-12 m: rounding moves a coordinate by at
      // most half of that, 5e-13 m; the scaling by 1e3 and the parse add relative errors ~1e-16
      // of |x| < 0.04 m, below 1e-17 m. So |delta| <= 5.1e-13 m, inside the 1e-12 m asked for.
      const std::string path = (dir / "pinion.cmm").string();
      write_cmm_file(path, m, {mm, decimals, true});
      EXPECT_NE(text(path).find(mm ? "\nunits = mm\n" : "\nunits = m\n"), std::string::npos);
      const MeasuredMember r = read_cmm_file(path);
      EXPECT_EQ(r.member, "pinion");
      EXPECT_EQ(r.teeth, 23);
      ASSERT_EQ(r.flanks.size(), m.flanks.size());
      double worst = 0;
      for (std::size_t f = 0; f < m.flanks.size(); ++f)
        {
          EXPECT_EQ(r.flanks[f].tooth, m.flanks[f].tooth);
          EXPECT_EQ(r.flanks[f].side, m.flanks[f].side);
          EXPECT_EQ(r.flanks[f].n_profile, 9);
          EXPECT_EQ(r.flanks[f].n_face, 29);
          ASSERT_EQ(r.flanks[f].points.size(), 261u);
          for (std::size_t k = 0; k < 261; ++k)
            worst = std::max(
                worst, (r.flanks[f].points[k] - m.flanks[f].points[k]).lpNorm<Eigen::Infinity>());
          // normals are printed in the shortest form that reads back exactly
          EXPECT_EQ(r.flanks[f].normals, m.flanks[f].normals);
        }
      EXPECT_LE(worst, 5.1e-13) << (mm ? "mm" : "m");
      EXPECT_GT(worst, 0) << "the test should see the rounding";
    }
  // without normals
  write_cmm_file((dir / "bare.cmm").string(), m, {true, 9, false});
  const MeasuredMember bare = read_cmm_file((dir / "bare.cmm").string());
  EXPECT_TRUE(bare.flanks[0].normals.empty());
  EXPECT_EQ(bare.flanks[3].points.size(), 261u);
}

TEST_F(CmmFile, HandWrittenFileReadsInAnyPointOrder)
{
  const MeasuredMember m = read_cmm_file(file("ok.cmm", test_data::valid_cmm()));
  ASSERT_EQ(m.flanks.size(), 1u);
  EXPECT_EQ(m.member, "pinion");
  EXPECT_EQ(m.teeth, 3);
  EXPECT_EQ(m.flanks[0].tooth, 1);
  EXPECT_EQ(m.flanks[0].side, FlankSide::drive);
  EXPECT_EQ(m.flanks[0].points[3], Vec3(11.0, 1.1, 1.0) / 1e3);
  EXPECT_TRUE(m.flanks[0].normals.empty());
  // point lines reversed, comments, blanks, CRLF, a leading '+', a frame line and block units
  const std::string    shuffled = R"(# measured 2026-11-22
format = gearkit-cmm 1
member = pinion
teeth  = 3
frame = member axis z, tooth 0 centred on +x at z = 0
units = mm
normals = no
begin flank
tooth = 1
side = drive
grid = 2 2   # profile x face
units = mm
1 1 11.0 1.1 +1.0
1 0 11.0 0.9 -1.0

0 1 10.0 1.2 1.0
0 0 10.0 1.0 -1.0
end flank
)";
  const MeasuredMember s =
      read_cmm_file(file("crlf.cmm", std::regex_replace(shuffled, std::regex("\n"), "\r\n")));
  EXPECT_EQ(s.flanks[0].points, m.flanks[0].points);
}

TEST_F(CmmFile, NormalsMustBeUnitVectors)
{
  const std::string with_normals = std::regex_replace(
      std::regex_replace(test_data::valid_cmm(), std::regex("normals = no"), "normals = yes"),
      std::regex("(\\d+ \\d+ [-0-9.]+ [-0-9.]+ [-0-9.]+)\n"), "$1 0 0 1\n");
  const MeasuredMember m = read_cmm_file(file("n.cmm", with_normals));
  EXPECT_EQ(m.flanks[0].normals[2], Vec3(0, 0, 1));
  // within the tolerance 1e-6 on |n| - 1 ...
  EXPECT_NO_THROW(read_cmm_file(file(
      "n1.cmm", std::regex_replace(with_normals, std::regex("0 0 1\nend"), "0 0 1.0000009\nend"))));
  // ... and outside it, on line 14
  const std::string path = file(
      "n2.cmm", std::regex_replace(with_normals, std::regex("0 0 1\nend"), "0 0 1.0000011\nend"));
  expect_error(error_of([&] { read_cmm_file(path); }), path, ":14:", "a unit normal");
  // a point line without its normal
  const std::string short_line =
      file("n3.cmm", std::regex_replace(with_normals, std::regex("1.0 0 0 1\nend"), "1.0\nend"));
  expect_error(error_of([&] { read_cmm_file(short_line); }), short_line,
               ":14:", "8 (i j x y z nx ny nz)");
}

TEST_F(CmmFile, EmptyOrMissingFilesAreNamed)
{
  const std::string empty = file("empty.cmm", "# nothing but a comment\n\n   \n");
  expect_error(error_of([&] { read_cmm_file(empty); }), empty, ":1:", "a header");
  EXPECT_NE(error_of([&] { read_cmm_file(empty); }).find("empty"), std::string::npos);
  const std::string none = (dir / "none.cmm").string();
  expect_error(error_of([&] { read_cmm_file(none); }), none, ":", "a readable text file");
  EXPECT_NE(error_of([&] { read_topography_file(none); }).find(none + ": cannot open"),
            std::string::npos);
}

TEST_F(CmmFile, FailedWritesLeaveNoFileBehind)
{
  const MeasuredMember m = virtual_cmm(*test_gear(), "pinion", 3, 3, 0, {0});
  // into a directory that does not exist: nothing is created
  const std::string nowhere = (dir / "missing-dir" / "x.cmm").string();
  EXPECT_NE(error_of([&] { write_cmm_file(nowhere, m); }).find(nowhere), std::string::npos);
  EXPECT_FALSE(fs::exists(nowhere));
  EXPECT_FALSE(fs::exists(nowhere + ".tmp"));
  // onto a directory: the temporary is written, the rename fails, the temporary is removed
  fs::create_directory(dir / "taken.cmm");
  const std::string taken = (dir / "taken.cmm").string();
  EXPECT_NE(error_of([&] { write_cmm_file(taken, m); }), "");
  EXPECT_TRUE(fs::is_directory(taken));
  EXPECT_FALSE(fs::exists(taken + ".tmp"));
  // an inconsistent member leaves an earlier file as it was
  const std::string path = (dir / "p.cmm").string();
  write_cmm_file(path, m);
  const std::string before = text(path);
  MeasuredMember    broken = m;
  broken.flanks[1].points.pop_back();
  EXPECT_NE(error_of([&] { write_cmm_file(path, broken); }).find("8 points on a 3 x 3 grid"),
            std::string::npos);
  broken        = m;
  broken.member = "pin#ion";
  EXPECT_NE(error_of([&] { write_cmm_file(path, broken); }).find("'#'"), std::string::npos);
  broken                         = m;
  broken.flanks[0].points[4].x() = std::nan("");
  EXPECT_NE(error_of([&] { write_cmm_file(path, broken); }), "");
  EXPECT_EQ(text(path), before);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  // topography files alike
  const std::string topo = (dir / "missing-dir" / "x.topo").string();
  EXPECT_NE(error_of([&] { write_topography_file(topo, {"pinion", 23, {}}); }), "");
  EXPECT_FALSE(fs::exists(topo + ".tmp"));
}

// --- every class of malformed CMM input --------------------------------------------------------

class CmmMalformed : public TempDir, public ::testing::WithParamInterface<MalformedCmm>
{
};

TEST_P(CmmMalformed, IsRefusedWithFileLineAndExpectation)
{
  const std::string bad = mutate(test_data::valid_cmm(), GetParam());
  ASSERT_NE(bad, test_data::valid_cmm());
  const std::string path = file("bad.cmm", bad);
  expect_error(error_of([&] { read_cmm_file(path); }), path, GetParam().line, GetParam().expected);
}

// The classes shared with the driver's tests (tests/malformed_cmm.h) ...
INSTANTIATE_TEST_SUITE_P(Shared, CmmMalformed,
                         ::testing::ValuesIn(test_data::malformed_cmm_cases()), case_name);

// ... and more, each at its exact line of valid_cmm() (format 1 ... end flank 15).
const std::vector<MalformedCmm> more_malformed_cmm = {
    {"missing header key at the end of the header", "member = pinion\n", "",
     ":6:", "'member = ...'"},
    {"missing block key", "grid = 2 2\n", "", ":10:", "'grid = ...'"},
    {"unknown block key", "side = drive\n", "side = drive\ncolour = red\n",
     ":10:", "documented keys"},
    {"key without value", "member = pinion", "member =", ":2:", "'member = <value>'"},
    {"header key twice", "teeth = 3\n", "teeth = 3\nteeth = 3\n", ":4:", "each key once"},
    {"not a key line in the header", "teeth = 3", "teeth 3", ":3:", "then 'begin flank'"},
    {"bad normals flag", "normals = no", "normals = maybe", ":5:", "normals = yes or normals = no"},
    {"teeth not a number", "teeth = 3", "teeth = three", ":3:", "an integer in [1, 100000]"},
    {"too many points", "end flank", "1 1 11.5 1.1 1.0\nend flank", ":15:", "4 = 2 x 2 points"},
    {"missing grid point", "0 1 10.0 1.2 1.0\n", "", ":14:", "(0, 1) is missing"},
    {"inf", "11.0 1.1 1.0", "11.0 -inf 1.0", ":14:", "finite"},
    {"overflow", "11.0 1.1 1.0", "11.0 1e999 1.0", ":14:", "a finite number"},
    {"number with trailing garbage", "11.0 1.1 1.0", "11.0 1.1x 1.0", ":14:", "a decimal number"},
    {"negative index", "1 1 11.0", "1 -1 11.0", ":14:", "[0, 1]"},
    {"fractional index", "1 1 11.0", "1 0.5 11.0", ":14:", "an integer in [0, 1]"},
    {"negative tooth", "tooth = 1", "tooth = -1", ":8:", "[0, 2]"},
    {"fractional tooth", "tooth = 1", "tooth = 1.5", ":8:", "an integer in [0, 2]"},
    {"grid with one number", "grid = 2 2", "grid = 2",
     ":10:", "grid = <profile points> <face points>"},
    {"empty grid", "grid = 2 2", "grid = 0 2", ":10:", "[1, 1000000]"},
    {"missing end before the next block", "end flank\n",
     "begin flank\ntooth = 2\nside = drive\ngrid = 1 1\n0 0 1 2 3\nend flank\n",
     ":7:", "'end flank'"},
    {"the same flank twice", "end flank\n",
     "end flank\nbegin flank\ntooth = 1\nside = drive\ngrid = 1 1\n0 0 1 2 3\nend flank\n",
     ":17:", "one block per tooth and side"},
    {"a line outside the blocks", "end flank\n", "end flank\n0 0 1 2 3\n", ":16:", "'begin flank'"},
    {"no flank block", "\nbegin flank[\\s\\S]*", "\n", ":5:", "at least one 'begin flank' block"},
};
INSTANTIATE_TEST_SUITE_P(More, CmmMalformed, ::testing::ValuesIn(more_malformed_cmm), case_name);

// --- topography files ---------------------------------------------------------------------------

TEST(Topography, ConstantDeviationIsTheNominalFlankPlusCTimesTheNormal)
{
  const auto       g = test_gear();
  const double     c = 2.5e-6, b = g->data().face_width;
  TopographyMember t{"pinion", 23, {}};
  for (FlankSide side : {FlankSide::drive, FlankSide::coast})
    {
      FlankTopography f{3, side, {}, {-b / 2, -b / 6, b / 6, b / 2}, {}};
      for (int i = 0; i < 5; ++i)
        f.diameters.push_back(2 * (g->form_radius + (g->tip_radius - g->form_radius) * i / 4));
      f.deviations.assign(20, c);
      t.flanks.push_back(f);
    }
  const MeasuredMember m = topography_to_points(*g, t);
  ASSERT_EQ(m.flanks.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s)
    {
      const MeasuredFlank &f = m.flanks[s];
      EXPECT_EQ(f.n_profile, 5);
      EXPECT_EQ(f.n_face, 4);
      const InvoluteFlank flank = g->flank(3, f.side);
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 4; ++j)
          {
            const FlankPoint p =
                flank.nominal(g->roll_angle(t.flanks[s].diameters[i] / 2), t.flanks[s].face[j]);
            EXPECT_EQ(f.points[i * 4 + j], p.position + c * p.normal);
            EXPECT_EQ(f.normals[i * 4 + j], p.normal);
            EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), t.flanks[s].diameters[i] / 2,
                        1e-12);
          }
    }
  // nominal means without the drive flank's lead crowning (6 um removed at the face ends)
  const InvoluteFlank drive = g->flank(3, FlankSide::drive);
  const FlankPoint    p     = drive.evaluate(g->roll_angle(t.flanks[0].diameters[2] / 2), b / 2);
  EXPECT_NEAR((m.flanks[0].points[2 * 4 + 3] - p.position).dot(p.normal), c + 6e-6, 1e-8);
}

TEST_F(TopographyFile, LinearProfileDeviationRoundTrips)
{
  const auto       g = test_gear();
  TopographyMember t{"pinion", 23, {}};
  FlankTopography  f{2, FlankSide::coast, {}, {-5e-3, 0, 5e-3}, {}};
  for (int i = 0; i < 5; ++i)
    f.diameters.push_back(2 * (g->form_radius + (g->tip_radius - g->form_radius) * i / 4));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 3; ++j)
      f.deviations.push_back(-2e-6 + 1.25e-6 * i); // linear along the profile
  t.flanks.push_back(f);
  const std::string path = (dir / "pinion.topo").string();
  write_topography_file(path, t);
  const TopographyMember r = read_topography_file(path);
  ASSERT_EQ(r.flanks.size(), 1u);
  EXPECT_EQ(r.member, "pinion");
  EXPECT_EQ(r.teeth, 23);
  EXPECT_EQ(r.flanks[0].tooth, 2);
  EXPECT_EQ(r.flanks[0].side, FlankSide::coast);
  // 9 decimals of mm and 6 of um: positions and deviations within 5e-13 m (+ parse rounding)
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(r.flanks[0].diameters[i], f.diameters[i], 5.1e-13);
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(r.flanks[0].face[j], f.face[j], 5.1e-13);
  ASSERT_EQ(r.flanks[0].deviations.size(), 15u);
  for (int k = 0; k < 15; ++k)
    EXPECT_NEAR(r.flanks[0].deviations[k], f.deviations[k], 5.1e-13);
  const MeasuredMember a = topography_to_points(*g, t), b = topography_to_points(*g, r);
  for (int k = 0; k < 15; ++k)
    EXPECT_LT((a.flanks[0].points[k] - b.flanks[0].points[k]).norm(), 2e-12);
}

TEST(Topography, PositionsOffTheFlankAreRefused)
{
  const auto       g = test_gear();
  const double     b = g->data().face_width;
  TopographyMember t{"gear", 23, {{7, FlankSide::drive, {2 * g->reference_radius}, {0}, {0}}}};
  EXPECT_NO_THROW(topography_to_points(*g, t));
  for (double d : {2 * g->form_radius * 0.999, 2 * g->tip_radius * 1.001})
    {
      t.flanks[0].diameters = {d};
      EXPECT_NE(error_of([&] { topography_to_points(*g, t); }).find("tooth 7 drive: diameters"),
                std::string::npos);
    }
  t.flanks[0].diameters = {2 * g->reference_radius};
  t.flanks[0].face      = {b / 2 * 1.001};
  EXPECT_NE(error_of([&] { topography_to_points(*g, t); }).find("expected [-b/2, b/2]"),
            std::string::npos);
  t.flanks[0].face = {0};
  t.teeth          = 24;
  EXPECT_NE(error_of([&] { topography_to_points(*g, t); }).find("expected the gear's 23"),
            std::string::npos);
}

namespace
{
const std::string valid_topography = R"(format = gearkit-topography 1
member = pinion
teeth = 23
units = mm
deviation units = um

begin flank
tooth = 2
side = coast
diameters = 56 57 58
face = -5 0 5
0.5 1.0 1.5
0.4 0.9 1.4
0.3 0.8 1.3
end flank
)";
}

class TopographyMalformed : public TempDir, public ::testing::WithParamInterface<MalformedCmm>
{
};

TEST_P(TopographyMalformed, IsRefusedWithFileLineAndExpectation)
{
  const std::string bad = mutate(valid_topography, GetParam());
  ASSERT_NE(bad, valid_topography);
  const std::string path = file("bad.topo", bad);
  expect_error(error_of([&] { read_topography_file(path); }), path, GetParam().line,
               GetParam().expected);
}

TEST_F(TopographyFile, ValidTextReads)
{
  const TopographyMember t = read_topography_file(file("ok.topo", valid_topography));
  ASSERT_EQ(t.flanks.size(), 1u);
  EXPECT_EQ(t.flanks[0].diameters, (std::vector<double>{56e-3, 57e-3, 58e-3}));
  EXPECT_EQ(t.flanks[0].face, (std::vector<double>{-5e-3, 0, 5e-3}));
  EXPECT_EQ(t.flanks[0].deviations[5], 1.4 / 1e6);
}

// The stream readers (used by the fuzz target tests/fuzz/fuzz_cmm.cc) read what the file readers
// read, and their messages name the stream as the file readers name the file.
TEST_F(TopographyFile, StreamsReadAsFiles)
{
  std::istringstream   cmm(test_data::valid_cmm());
  const MeasuredMember m = read_cmm(cmm, "in memory");
  EXPECT_EQ(m.flanks.at(0).points,
            read_cmm_file(file("ok.cmm", test_data::valid_cmm())).flanks.at(0).points);
  std::istringstream bad_cmm(std::regex_replace(test_data::valid_cmm(), std::regex("1\\.1"), "x"));
  expect_error(error_of([&] { read_cmm(bad_cmm, "in memory"); }), "in memory",
               ":14:", "a decimal number");

  std::istringstream     topography(valid_topography);
  const TopographyMember t = read_topography(topography, "in memory");
  EXPECT_EQ(t.flanks.at(0).deviations,
            read_topography_file(file("ok.topo", valid_topography)).flanks.at(0).deviations);
  std::istringstream empty("# nothing\n");
  expect_error(error_of([&] { read_topography(empty, "in memory"); }), "in memory",
               ":1:", "a header");
}

const std::vector<MalformedCmm> malformed_topography = {
    {"row too short", "0.4 0.9 1.4", "0.4 0.9", ":13:", "3 (one per face position)"},
    {"too many rows", "end flank", "0.2 0.7 1.2\nend flank", ":15:", "3 rows, one per diameter"},
    {"too few rows", "0.3 0.8 1.3\n", "", ":14:", "3 rows, one per diameter"},
    {"diameters not increasing", "56 57 58", "56 58 57", ":10:", "strictly increasing"},
    {"face position twice", "-5 0 5", "-5 0 0", ":11:", "strictly increasing"},
    {"non-numeric deviation", "0.4 0.9 1.4", "0.4 O.9 1.4", ":13:", "a decimal number"},
    {"NaN deviation", "0.4 0.9 1.4", "0.4 NaN 1.4", ":13:", "finite"},
    {"positions in metres", "units = mm", "units = m", ":4:", "units = mm"},
    {"deviations in mm", "deviation units = um", "deviation units = mm",
     ":5:", "deviation units = um"},
    {"mixed units", "side = coast\n", "side = coast\nunits = m\n", ":10:", "one unit"},
    {"missing deviation units", "deviation units = um\n", "", ":6:", "'deviation units = ...'"},
    {"tooth beyond z", "tooth = 2", "tooth = 23", ":8:", "[0, 22]"},
    {"unknown side", "side = coast", "side = both", ":9:", "drive or coast"},
    {"missing end", "end flank\n", "", ":7:", "'end flank'"},
    {"bad format", "topography 1", "topography 2", ":1:", "'gearkit-topography 1'"},
};
INSTANTIATE_TEST_SUITE_P(Cases, TopographyMalformed, ::testing::ValuesIn(malformed_topography),
                         case_name);

// --- fuzzing -------------------------------------------------------------------------------------

TEST_F(CmmFuzz, RandomMutationsParseOrThrowInputError)
{
  // Character replacements and insertions (NUL and 0xff included), deleted, repeated and swapped
  // lines, truncation: every result must read or throw InputError, never crash or throw anything
  // else (error_of lets other exceptions fail the test).
  const std::string written = (dir / "w.cmm").string();
  write_cmm_file(written, virtual_cmm(*test_gear(), "pinion", 2, 3, 0, {0, 1}));
  const std::string alphabet = std::string(" =#\n\r\t.-+e0123456789abcdefginx") + '\0' + '\xff';
  std::mt19937      rng(7);
  auto              pick = [&](std::size_t n) { return std::size_t(rng() % n); };
  const std::function<void(const std::string &)> cmm =
                                                     [](const std::string &p) { read_cmm_file(p); },
                                                 topo = [](const std::string &p) {
                                                   read_topography_file(p);
                                                 };
  for (const auto &[base, reader] :
       {std::pair{test_data::valid_cmm(), cmm}, {text(written), cmm}, {valid_topography, topo}})
    {
      int parsed = 0, refused = 0;
      for (int trial = 0; trial < 400; ++trial)
        {
          std::string bad = base;
          switch (trial % 4)
            {
            case 0:
              for (int m = 0; m < 3; ++m)
                bad[pick(bad.size())] = alphabet[pick(alphabet.size())];
              break;
            case 1:
              bad.insert(pick(bad.size()), 1, alphabet[pick(alphabet.size())]);
              break;
            case 2:
              {
                std::vector<std::string> lines;
                std::istringstream       s(bad);
                for (std::string l; std::getline(s, l);)
                  lines.push_back(l);
                const std::size_t a = pick(lines.size()), b = pick(lines.size());
                switch (pick(3))
                  {
                  case 0:
                    lines.erase(lines.begin() + a);
                    break;
                  case 1:
                    {
                      const std::string copy = lines[b];
                      lines.insert(lines.begin() + a, copy);
                      break;
                    }
                  default:
                    std::swap(lines[a], lines[b]);
                  }
                bad.clear();
                for (const std::string &l : lines)
                  bad += l + "\n";
                break;
              }
            default:
              bad.resize(pick(bad.size()));
            }
          const std::string path = file("fuzz.txt", bad);
          const std::string msg  = error_of([&] { reader(path); });
          ++(msg.empty() ? parsed : refused);
          EXPECT_TRUE(msg.empty() || msg.find("; expected ") != std::string::npos) << msg;
        }
      EXPECT_GT(parsed, 0);
      EXPECT_GT(refused, 100);
    }
}

// --- synthesiser -------------------------------------------------------------------------------

namespace
{
/// (measured - theoretical) . n of every point of every flank.
std::vector<double>
normal_displacements(const MeasuredMember &m, const MeasuredMember &theory)
{
  std::vector<double> d;
  for (std::size_t f = 0; f < m.flanks.size(); ++f)
    for (std::size_t k = 0; k < m.flanks[f].points.size(); ++k)
      d.push_back(
          (m.flanks[f].points[k] - theory.flanks[f].points[k]).dot(theory.flanks[f].normals[k]));
  return d;
}

SynthesisOptions
only(double SynthesisOptions::*part, double value)
{
  SynthesisOptions o;
  o.noise = 0;
  o.*part = value;
  return o;
}
} // namespace

TEST(Synthesiser, SameSeedSameFlanksOtherSeedOtherFlanks)
{
  const MeasuredMember   theory = virtual_cmm(*test_gear(), "pinion", 9, 29, 0, {0, 1});
  const SynthesisOptions o{42, 2e-6, 0.5e-6, 1e-3, 0.3e-6, 1e-6, 3e-6};
  const MeasuredMember   a = synthesise_measured(theory, o), b = synthesise_measured(theory, o);
  SynthesisOptions       other = o;
  other.seed                   = 43;
  const MeasuredMember c       = synthesise_measured(theory, other);
  for (std::size_t f = 0; f < theory.flanks.size(); ++f)
    {
      EXPECT_EQ(a.flanks[f].points, b.flanks[f].points);
      EXPECT_EQ(a.flanks[f].normals, b.flanks[f].normals);
      for (std::size_t k = 0; k < a.flanks[f].points.size(); ++k)
        EXPECT_NE(a.flanks[f].points[k], c.flanks[f].points[k]);
    }
}

TEST(Synthesiser, NothingToAddIsTheIdentity)
{
  const MeasuredMember theory = virtual_cmm(*test_gear(), "pinion", 9, 29, 0, {0, 7});
  const MeasuredMember same   = synthesise_measured(theory, only(&SynthesisOptions::noise, 0));
  for (std::size_t f = 0; f < theory.flanks.size(); ++f)
    {
      EXPECT_EQ(same.flanks[f].points, theory.flanks[f].points);
      EXPECT_EQ(same.flanks[f].normals, theory.flanks[f].normals);
    }
  // the default options carry 1 um of measurement noise
  EXPECT_NE(synthesise_measured(theory, {}).flanks[0].points, theory.flanks[0].points);
  MeasuredMember bare = theory;
  bare.flanks[1].normals.clear();
  EXPECT_NE(error_of([&] { synthesise_measured(bare, {}); }).find("normals"), std::string::npos);
}

TEST(Synthesiser, NoiseAloneHasTheRequestedSpread)
{
  // 46 flanks x 261 points = 12006 samples. The sample standard deviation has a relative standard
  // error 1/sqrt(2 N) = 0.65 %, so the 5 % tolerance is ~8 standard errors; the mean's standard
  // error is 1e-6 / sqrt(N) = 9.1e-9 m, tested at 5 of them; the share within one sigma
  // (0.6827 for a Gaussian) has a standard error sqrt(p (1 - p) / N) = 0.0042, tested at 0.02.
  const MeasuredMember      theory = virtual_cmm(*test_gear(), "pinion");
  const MeasuredMember      m = synthesise_measured(theory, only(&SynthesisOptions::noise, 1e-6));
  const std::vector<double> d = normal_displacements(m, theory);
  ASSERT_EQ(d.size(), 12006u);
  double sum = 0, sum2 = 0, within = 0;
  for (double v : d)
    sum += v, sum2 += v * v, within += std::abs(v) < 1e-6;
  const double n = double(d.size()), mean = sum / n,
               sd = std::sqrt((sum2 - n * mean * mean) / (n - 1));
  EXPECT_NEAR(sd / 1e-6, 1, 0.05);
  EXPECT_LT(std::abs(mean), 4.6e-8);
  EXPECT_NEAR(within / n, 0.6827, 0.02);
  // the points move along the normals only
  for (std::size_t f = 0; f < m.flanks.size(); ++f)
    for (std::size_t k = 0; k < m.flanks[f].points.size(); ++k)
      {
        const Vec3 move = m.flanks[f].points[k] - theory.flanks[f].points[k];
        EXPECT_LT(
            (move - move.dot(theory.flanks[f].normals[k]) * theory.flanks[f].normals[k]).norm(),
            2e-17); // the rounding of q + d n: half an ulp of |q| ~ 0.03 m per coordinate
      }
}

TEST(Synthesiser, PitchErrorTurnsEachFlankRigidlyAndTheTurnsSumToZero)
{
  const MeasuredMember theory = virtual_cmm(*test_gear(), "pinion", 5, 7);
  const MeasuredMember m = synthesise_measured(theory, only(&SynthesisOptions::pitch_error, 5e-6));
  auto                 turn_of = [](const Vec3 &a, const Vec3 &b) { // angle from b to a about z
    return std::atan2(b.x() * a.y() - b.y() * a.x(), b.x() * a.x() + b.y() * a.y());
  };
  std::vector<double> arc(23, 0.0); // cumulative pitch deviation F_k per tooth
  for (std::size_t f = 0; f < m.flanks.size(); ++f)
    {
      const auto  &p = m.flanks[f].points, &q = theory.flanks[f].points;
      const double angle  = turn_of(p[0], q[0]);
      double       radius = 0;
      for (std::size_t k = 0; k < p.size(); ++k) // every point and normal turned alike
        {
          EXPECT_NEAR(turn_of(p[k], q[k]), angle, 1e-12);
          EXPECT_NEAR(turn_of(m.flanks[f].normals[k], theory.flanks[f].normals[k]), angle, 1e-12);
          EXPECT_NEAR(p[k].head<2>().norm(), q[k].head<2>().norm(), 1e-15);
          EXPECT_EQ(p[k].z(), q[k].z());
          radius += q[k].head<2>().norm() / p.size();
        }
      if (m.flanks[f].side == FlankSide::drive)
        arc[m.flanks[f].tooth] = angle * radius;
      else // both flanks of a tooth move by the same arc
        EXPECT_NEAR(angle * radius, arc[m.flanks[f].tooth], 1e-15);
    }
  double sum = 0, largest = 0;
  for (double a : arc)
    sum += a, largest = std::max(largest, std::abs(a));
  EXPECT_LT(std::abs(sum), 1e-15);
  EXPECT_GT(largest, 2e-6); // 23 turns of a 5 um random walk are not all small
  EXPECT_LT(largest, 100e-6);
}

TEST(Synthesiser, PitchDeviationsHaveTheRequestedSpread)
{
  // 5000 teeth with one point each: the single pitch deviations f_p = F_k - F_(k-1) have a
  // sample standard deviation with relative standard error 1/sqrt(2 z) = 1 %, tested at 5 %.
  const int      z = 5000;
  const double   r = 0.5;
  MeasuredMember theory{"ring", z, {}};
  for (int k = 0; k < z; ++k)
    {
      const Vec3 e(std::cos(2 * pi * k / z), std::sin(2 * pi * k / z), 0);
      theory.flanks.push_back({k, FlankSide::drive, 1, 1, {r * e}, {Vec3(-e.y(), e.x(), 0)}});
    }
  const MeasuredMember m = synthesise_measured(theory, only(&SynthesisOptions::pitch_error, 3e-6));
  std::vector<double>  arc(z);
  for (int k = 0; k < z; ++k)
    {
      const Vec3 &p = m.flanks[k].points[0], &q = theory.flanks[k].points[0];
      arc[k] = r * std::atan2(q.x() * p.y() - q.y() * p.x(), q.dot(p));
    }
  double sum2 = 0, sum = 0;
  for (int k = 0; k < z; ++k)
    {
      const double fp = arc[k] - arc[(k + z - 1) % z];
      sum += arc[k], sum2 += fp * fp;
    }
  EXPECT_NEAR(std::sqrt(sum2 / z) / 3e-6, 1, 0.05);
  EXPECT_LT(std::abs(sum), 1e-12);
}

TEST(Synthesiser, FormWavinessAndRoughnessHaveTheirDocumentedSize)
{
  const MeasuredMember theory = virtual_cmm(*test_gear(), "pinion", 9, 29);
  auto mixed_difference       = [](const std::vector<double> &d, std::size_t flank, int i, int j) {
    const std::size_t k = flank * 261 + i * 29 + j;
    return d[k + 30] - d[k + 29] - d[k + 1] + d[k];
  };
  // form: per flank a quadratic without a cross term whose largest |value| is form_error
  {
    const std::vector<double> d = normal_displacements(
        synthesise_measured(theory, only(&SynthesisOptions::form_error, 2e-6)), theory);
    for (std::size_t f = 0; f < 46; ++f)
      {
        double peak = 0;
        for (std::size_t k = 0; k < 261; ++k)
          peak = std::max(peak, std::abs(d[f * 261 + k]));
        EXPECT_NEAR(peak, 2e-6, 1e-15);
        for (int i = 0; i < 8; ++i)
          for (int j = 0; j < 28; ++j)
            EXPECT_NEAR(mixed_difference(d, f, i, j), 0, 5e-17); // 4 x the rounding of q + d n
      }
  }
  // waviness: a profile sinusoid plus a face sinusoid (no cross term), |d| <= amplitude
  {
    SynthesisOptions o             = only(&SynthesisOptions::waviness_amplitude, 1e-6);
    o.waviness_wavelength          = 2e-3;
    const std::vector<double> d    = normal_displacements(synthesise_measured(theory, o), theory);
    double                    peak = 0;
    for (double v : d)
      peak = std::max(peak, std::abs(v));
    EXPECT_LE(peak, 1e-6 + 1e-17);
    EXPECT_GT(peak, 0.8e-6);
    EXPECT_NEAR(mixed_difference(d, 5, 3, 10), 0, 5e-17);
  }
  // roughness: standard deviation `roughness`, neighbours correlated 2/5 inside the grid (the
  // five-point stencils of neighbours share two points). The correlations leave about
  // 12006 / 2.4 independent samples: 5 % on the standard deviation is ~5 standard errors.
  {
    const std::vector<double> d = normal_displacements(
        synthesise_measured(theory, only(&SynthesisOptions::roughness, 0.3e-6)), theory);
    double sum2 = 0, cross = 0, inner = 0;
    for (double v : d)
      sum2 += v * v;
    for (std::size_t f = 0; f < 46; ++f)
      for (int i = 1; i < 8; ++i)
        for (int j = 1; j < 27; ++j)
          {
            const std::size_t k = f * 261 + i * 29 + j;
            cross += d[k] * d[k + 1], inner += d[k] * d[k];
          }
    EXPECT_NEAR(std::sqrt(sum2 / d.size()) / 0.3e-6, 1, 0.05);
    EXPECT_NEAR(cross / inner, 0.4, 0.05);
  }
}

// Measured flanks: CMM and topography files (round trips and every malformed-input class), the
// virtual CMM, and the synthesiser.
#include "../malformed_cmm.h"
#include "measured_flank.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

using namespace gearkit;
using namespace gearkit::test_data;
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

class MeasuredFiles : public ::testing::Test
{
protected:
  void
  SetUp() override
  {
    dir = fs::temp_directory_path() /
          ("gearkit-measured-" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void
  TearDown() override
  {
    fs::remove_all(dir);
  }
  std::string
  file(const std::string &name, const std::string &text) const
  {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  }
  std::string
  text(const std::string &name) const
  {
    std::ifstream      in((dir / name).string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir;
};

// The message of the InputError a call throws ("" if it does not throw).
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
} // namespace

TEST_F(MeasuredFiles, CmmRoundTripKeepsPointsToPrintedPrecision)
{
  const auto           g = test_gear();
  const MeasuredMember m = virtual_cmm(*g, "pinion", 9, 29, 0, {0, 5, 22});
  ASSERT_EQ(m.flanks.size(), 6u);
  ASSERT_EQ(m.flanks[0].points.size(), 261u);
  for (bool mm : {true, false})
    {
      // 9 decimals in mm round to 5e-13 m; 12 decimals in m to 5e-13 m as well.
      const std::string path = (dir / "pinion.cmm").string();
      write_cmm_file(path, m, {mm, mm ? 9 : 12, true});
      const MeasuredMember r = read_cmm_file(path);
      EXPECT_EQ(r.member, "pinion");
      EXPECT_EQ(r.teeth, 23);
      ASSERT_EQ(r.flanks.size(), m.flanks.size());
      for (std::size_t f = 0; f < m.flanks.size(); ++f)
        {
          EXPECT_EQ(r.flanks[f].tooth, m.flanks[f].tooth);
          EXPECT_EQ(r.flanks[f].side, m.flanks[f].side);
          for (std::size_t k = 0; k < m.flanks[f].points.size(); ++k)
            {
              EXPECT_LE((r.flanks[f].points[k] - m.flanks[f].points[k]).lpNorm<Eigen::Infinity>(),
                        5.1e-13);
              // 15 decimals: half a unit of the last (5e-16) plus one rounding of the parse
              EXPECT_LE((r.flanks[f].normals[k] - m.flanks[f].normals[k]).lpNorm<Eigen::Infinity>(),
                        6.2e-16);
            }
        }
    }
}

TEST(VirtualCmm, PointsLieOnTheFlank)
{
  const auto           g = test_gear();
  const MeasuredMember m = virtual_cmm(*g, "gear", 9, 29, 0.05, {4});
  for (const MeasuredFlank &f : m.flanks)
    {
      const InvoluteFlank flank = g->flank(4, f.side);
      const FlankDomain   d     = flank.domain();
      for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 29; ++j)
          {
            const double u = d.u_min + (0.05 + 0.9 * i / 8) * (d.u_max - d.u_min);
            const double v = d.v_min + (0.05 + 0.9 * j / 28) * (d.v_max - d.v_min);
            EXPECT_LT((flank.evaluate(u, v).position - f.points[i * 29 + j]).norm(), 1e-15);
          }
    }
}

TEST_F(MeasuredFiles, SmallHandWrittenFileReads)
{
  const MeasuredMember m = read_cmm_file(file("ok.cmm", valid_cmm()));
  ASSERT_EQ(m.flanks.size(), 1u);
  EXPECT_EQ(m.flanks[0].tooth, 1);
  EXPECT_NEAR(m.flanks[0].points[3].y(), 1.1e-3, 1e-18);
  EXPECT_TRUE(m.flanks[0].normals.empty());
}

TEST_F(MeasuredFiles, EveryMalformedCmmFileIsRejectedWithFileLineAndExpectation)
{
  for (const MalformedCmm &c : malformed_cmm_cases())
    {
      const std::string bad = std::regex_replace(valid_cmm(), std::regex(c.from), c.to,
                                                 std::regex_constants::format_first_only);
      ASSERT_NE(bad, valid_cmm()) << c.what;
      const std::string path = file("bad.cmm", bad);
      const std::string msg  = error_of([&] { read_cmm_file(path); });
      EXPECT_NE(msg.find(path + c.line), std::string::npos) << c.what << ": " << msg;
      EXPECT_NE(msg.find(c.expected), std::string::npos) << c.what << ": " << msg;
    }
  // normals that are not unit vectors
  const std::string with_normals = std::regex_replace(
      std::regex_replace(valid_cmm(), std::regex("normals = no"), "normals = yes"),
      std::regex("(\\d+ \\d+ [-0-9.]+ [-0-9.]+ [-0-9.]+)\n"), "$1 0 0 1\n");
  EXPECT_NO_THROW(read_cmm_file(file("n.cmm", with_normals)));
  const std::string long_normal =
      std::regex_replace(with_normals, std::regex("0 0 1\nend"), "0 0 1.01\nend");
  EXPECT_NE(error_of([&] { read_cmm_file(file("n2.cmm", long_normal)); }).find("unit normal"),
            std::string::npos);
  // empty and missing files
  EXPECT_NE(error_of([&] { read_cmm_file(file("empty.cmm", "# nothing\n")); }).find("empty"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_cmm_file((dir / "none.cmm").string()); }).find("none.cmm"),
            std::string::npos);
}

TEST_F(MeasuredFiles, GarbageNeverCrashesTheReader)
{
  // Random single-character mutations of a valid file: each parses or throws InputError.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial)
    {
      std::string bad = valid_cmm();
      for (int m = 0; m < 3; ++m)
        bad[rng() % bad.size()] = " =#\n.-0123456789abcdefgnx"[rng() % 24];
      const std::string path = file("fuzz.cmm", bad);
      try
        {
          read_cmm_file(path);
        }
      catch (const InputError &)
        {
        }
    }
}

TEST_F(MeasuredFiles, FailedWriteLeavesNoFile)
{
  const MeasuredMember m    = virtual_cmm(*test_gear(), "pinion", 3, 3, 0, {0});
  const std::string    path = (dir / "missing-dir" / "x.cmm").string();
  EXPECT_THROW(write_cmm_file(path, m), InputError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(MeasuredFiles, TopographyConstantAndLinearDeviations)
{
  const auto       g = test_gear();
  TopographyMember t{"pinion", 23, {}};
  FlankTopography  f;
  f.tooth = 2;
  f.side  = FlankSide::coast;
  for (int i = 0; i < 5; ++i)
    f.diameters.push_back(2 * (g->form_radius + (g->tip_radius - g->form_radius) * i / 4));
  f.face = {-5e-3, 0, 5e-3};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 3; ++j)
      f.deviations.push_back(3e-6 + 1e-6 * i); // linear along the profile
  t.flanks.push_back(f);
  const std::string path = (dir / "pinion.topo").string();
  write_topography_file(path, t);
  const TopographyMember r = read_topography_file(path);
  ASSERT_EQ(r.flanks.size(), 1u);
  const MeasuredMember pts = topography_to_points(*g, r);
  const InvoluteFlank  fl  = g->flank(2, FlankSide::coast);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 3; ++j)
      {
        // the file keeps 6 decimals of mm and um: positions to 5e-10 m, deviations 5e-13 m
        EXPECT_NEAR(r.flanks[0].deviations[i * 3 + j], 3e-6 + 1e-6 * i, 5e-13);
        const FlankPoint p = fl.nominal(g->roll_angle(r.flanks[0].diameters[i] / 2), f.face[j]);
        EXPECT_LT(
            (pts.flanks[0].points[i * 3 + j] - (p.position + (3e-6 + 1e-6 * i) * p.normal)).norm(),
            1e-12);
      }
  // malformed: a row too short names the line and what was expected
  std::string       bad = std::regex_replace(text("pinion.topo"), std::regex("\n[0-9.]+ [0-9.]+ "),
                                             "\n1.0 ", std::regex_constants::format_first_only);
  const std::string msg = error_of([&] { read_topography_file(file("bad.topo", bad)); });
  EXPECT_NE(msg.find("bad.topo:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("one per face position"), std::string::npos) << msg;
}

TEST(Synthesiser, DeterministicPerSeedAndIdentityWithoutErrors)
{
  const MeasuredMember theory = virtual_cmm(*test_gear(), "pinion", 9, 29, 0, {0, 1});
  SynthesisOptions     o;
  o.form_error = 2e-6, o.waviness_amplitude = 0.5e-6, o.roughness = 0.3e-6, o.noise = 1e-6;
  o.pitch_error          = 3e-6;
  const MeasuredMember a = synthesise_measured(theory, o), b = synthesise_measured(theory, o);
  o.seed                 = 2;
  const MeasuredMember c = synthesise_measured(theory, o);
  EXPECT_EQ(a.flanks[1].points, b.flanks[1].points);
  EXPECT_NE(a.flanks[1].points, c.flanks[1].points);
  const MeasuredMember same = synthesise_measured(theory, SynthesisOptions{});
  for (std::size_t f = 0; f < theory.flanks.size(); ++f)
    EXPECT_EQ(same.flanks[f].points, theory.flanks[f].points);
}

TEST(Synthesiser, NoiseHasTheRequestedStandardDeviation)
{
  // 46 flanks x 261 points = 12006 samples: the sample standard deviation has a relative
  // standard error 1/sqrt(2 N) = 0.65 %, so 5 % is ~8 sigma; the mean's standard error is
  // 1e-6/sqrt(N) = 9e-9 m, tested at 5e-8.
  const MeasuredMember theory = virtual_cmm(*test_gear(), "pinion", 9, 29);
  SynthesisOptions     o;
  o.noise                  = 1e-6;
  const MeasuredMember m   = synthesise_measured(theory, o);
  double               sum = 0, sum2 = 0;
  std::size_t          n = 0;
  for (std::size_t f = 0; f < m.flanks.size(); ++f)
    for (std::size_t k = 0; k < m.flanks[f].points.size(); ++k)
      {
        const double d =
            (m.flanks[f].points[k] - theory.flanks[f].points[k]).dot(theory.flanks[f].normals[k]);
        sum += d, sum2 += d * d, ++n;
      }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sd / 1e-6, 1, 0.05);
  EXPECT_LT(std::abs(mean), 5e-8);
}

TEST(Synthesiser, PitchErrorsAreRigidTurnsThatClose)
{
  const auto           g      = test_gear();
  const MeasuredMember theory = virtual_cmm(*g, "pinion", 5, 7);
  SynthesisOptions     o;
  o.pitch_error          = 5e-6;
  const MeasuredMember m = synthesise_measured(theory, o);
  std::vector<double>  turn(23, 0.0);
  for (std::size_t f = 0; f < m.flanks.size(); ++f)
    {
      const auto &p = m.flanks[f].points, &q = theory.flanks[f].points;
      auto        turn_of = [](const Vec3 &a, const Vec3 &b) { // angle from b to a about z
        return std::atan2(b.x() * a.y() - b.y() * a.x(), b.x() * a.x() + b.y() * a.y());
      };
      const double a0 = turn_of(p[0], q[0]);
      for (std::size_t k = 0; k < p.size(); ++k) // every point of the flank turned alike
        {
          EXPECT_NEAR(turn_of(p[k], q[k]), a0, 1e-12);
          EXPECT_NEAR(p[k].head<2>().norm(), q[k].head<2>().norm(), 1e-15);
        }
      turn[m.flanks[f].tooth] = a0;
    }
  // Tooth 0 is the reference; the turns, times the mean flank radius, are cumulative pitch
  // deviations whose last step back to tooth 0 closes the circle: they are not all zero and
  // stay within a few pitch errors of each other.
  double spread = 0;
  for (double t : turn)
    spread = std::max(spread, std::abs(t * g->reference_radius));
  EXPECT_GT(spread, 1e-6);
  EXPECT_LT(spread, 60e-6);
  EXPECT_EQ(turn[0], 0);
}

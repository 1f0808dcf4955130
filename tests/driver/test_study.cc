// The study stage: a micro-geometry map of the FZG C pair on coarse segments. Each variant of
// the map equals the stiffness stage's standalone run of the same modified scene (its own
// compliance computed again, its zones fitted to each load) within the fixed zones' error;
// the map's tables, its best variant and the classical relief are consistent; the design torque
// joins the torques; bad study sections are refused by name.
#include "driver/h5_file.h"
#include "driver/pair_contact.h"
#include "tests/driver/driver_fixture.h"
#include "tests/driver/small_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>

using namespace gearkit;

namespace
{
/// The FZG C pair (reference-data.md section 5) on coarse 5-tooth segments, 8 positions, with
/// `flank_extra` in both members' Flanks subsections and `rest` appended (Study, outputs).
std::string
fzg_scene(const std::string &name, const std::string &outputs, const std::string &pinion_extra,
          const std::string &gear_extra, const std::string &rest)
{
  return test_data::scene_section(name, outputs, "fzg") +
         test_data::flanks_section({{"fzg", 16, 24, 4.5, 14, 0, 0,
                                     "      set profile shift coefficient = 0.1817\n"
                                     "      set bore diameter             = 30\n" +
                                         pinion_extra,
                                     "      set profile shift coefficient = 0.1715\n"
                                     "      set bore diameter             = 40\n" +
                                         gear_extra}}) +
         R"(subsection Finite elements
  subsection fzg
    set segment teeth      = 5
    set flank element size = 0.5
    set degree             = 1
  end
end
subsection Loaded contact
  subsection fzg
    set torques                  = 150
    set positions per mesh cycle = 8
  end
end
)" + rest;
}

const std::string relief_20 = "      subsection Drive flank modifications\n"
                              "        set tip relief        = 20\n"
                              "        set tip relief length = 5.5\n"
                              "      end\n";

const std::string map_section = R"(subsection Study
  subsection fzg
    set torques                  = 100
    set design torque            = 150
    set positions per mesh cycle = 8
    set tip relief               = 0, 20, 40
    set tip relief length        = 5.5
  end
end
)";

double
peak_to_peak(const std::vector<double> &x)
{
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  return *hi - *lo;
}
} // namespace

class StudyStage : public test_data::GearkitRun
{
};

TEST_F(StudyStage, MapVariantEqualsTheStandaloneModifiedScene)
{
  const std::string map = file("map.prm", fzg_scene("map", "study", "", "", map_section));
  ASSERT_EQ(run({map}), 0) << err.str();
  test_data::expect_contains(out.str(), {"3 variants x 2 torques x 8 positions"});
  const H5File  f = H5File::open((dir / "out/map/results.h5").string());
  const H5Group g = f.root().group("study/fzg");
  // the design torque joined the torques, ascending
  EXPECT_EQ(g.read_doubles("torques"), (std::vector<double>{100, 150}));
  std::vector<hsize_t> shape;
  const auto           pp = g.read_doubles("te_peak_to_peak", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{3, 2}));
  const auto grid = g.read_doubles("grid", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{3, 2})); // tip relief, tip relief length
  const auto eL = g.read_doubles("loaded_te", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{3, 2, 8}));
  const auto K     = g.read_doubles("mesh_stiffness");
  const auto K_bar = g.read_doubles("stiffness_mean");
  const auto edge  = g.read_ints("zone_edge");
  EXPECT_EQ(std::count(edge.begin(), edge.end(), 1), 0);
  EXPECT_EQ(g.read_ints("unmodified_variant"), (std::vector<int>{0}));
  // the summaries are those of the tables
  for (std::size_t v = 0; v < 3; ++v)
    for (std::size_t m = 0; m < 2; ++m)
      {
        const std::vector<double> e(eL.begin() + long((v * 2 + m) * 8),
                                    eL.begin() + long((v * 2 + m + 1) * 8));
        EXPECT_DOUBLE_EQ(pp[v * 2 + m], peak_to_peak(e));
        double mean = 0;
        for (std::size_t i = 0; i < 8; ++i)
          mean += K[(v * 2 + m) * 8 + i] / 8;
        EXPECT_NEAR(K_bar[v * 2 + m], mean, 1e-9 * mean);
      }
  // the best variant per torque is the least TE p-p; the relief helps at the design torque
  const auto best = g.read_ints("best_variant");
  for (std::size_t m = 0; m < 2; ++m)
    for (std::size_t v = 0; v < 3; ++v)
      EXPECT_LE(pp[std::size_t(best[m]) * 2 + m], pp[v * 2 + m]);
  EXPECT_LT(pp[1 * 2 + 1], pp[0 * 2 + 1]);
  // the classical relief: F_bt / (b c_gamma) with ISO 6336-1's c_gamma times b
  const double r_b = 36e-3 * std::cos(20 * pi / 180);
  EXPECT_NEAR(g.read_double("classical_relief_iso"), 150 / r_b / g.read_double("iso_c_gamma_alpha"),
              1e-15);
  const double deflection = 150 / r_b / K_bar[0 * 2 + 1];
  EXPECT_NEAR(g.read_double("mesh_deflection_design"), deflection, 1e-9 * deflection);
  EXPECT_GE(g.read_double("best_relief_design"), 0);
  EXPECT_LE(g.read_double("best_relief_design"), 40e-6);

  // The variant with 20 um of tip relief on its own on the map's compliance: the stiffness
  // stage's loaded contact (its zones fitted to each load) of the modified members. The fixed
  // zones' error: < 0.1 % in the TE peak-to-peak and in K_m at every position.
  const Scene         scene = read_scene(map);
  std::ostringstream  log;
  const StageUpstream up(scene, std::vector<std::string>{"flanks", "compliance"},
                         (dir / "out").string(), log);
  test_data::expect_contains(log.str(), {"stage compliance: reused"}); // the map's
  const LoadedPair lp =
      loaded_pair(scene, scene.pair("fzg"), up.upstream().at("flanks")->group("fzg"),
                  up.upstream().at("compliance")->group("fzg"));
  const auto relieved = [](const MemberFlanks &m) {
    InvoluteGearData d                      = involute(m).data();
    d.drive_modifications.tip_relief        = 20e-6;
    d.drive_modifications.tip_relief_length = 5.5e-3;
    return std::make_shared<const InvoluteMemberFlanks>(InvoluteGear::create(d));
  };
  const UnloadedTca      tca(relieved(*lp.members.pinion), relieved(*lp.members.gear),
                             lp.members.assembly, lp.theory->options_data());
  const MeshCycleContact c =
      loaded_contact_cycle(tca, 8, {150}, lp.options, lp.pinion_compliance, lp.gear_compliance);
  // The two differ by where their cells lie (the map's zone is the unmodified pair's, widened;
  // the stage's is fitted to each load): e_L within 0.1 % of the approach e_L - e_0 and K_m
  // within 0.1 % at every position, so the TE peak-to-peak within twice the largest such
  // difference (on 35 x 48 cells the map's e_L lies nearer the converged one than the stage's
  // at the position where they differ most: 636.60 and 637.03 against 636.42 urad).
  const std::size_t         k0 = (1 * 2 + 1) * 8; // variant 1 (20 um), torque 150 N m
  const std::vector<double> e(eL.begin() + long(k0), eL.begin() + long(k0 + 8));
  const auto                e0      = g.read_doubles("unloaded_te");
  double                    worst_K = 0, worst_e = 0, bound = 0;
  for (std::size_t i = 0; i < 8; ++i)
    {
      const double approach = c.loaded_te[i] - c.unloaded_te[i];
      EXPECT_NEAR(e0[8 + i], c.unloaded_te[i], 1e-12) << i; // the variant's own TCA
      EXPECT_NEAR((e[i] - c.loaded_te[i]) / approach, 0, 1e-3) << i;
      EXPECT_NEAR(K[k0 + i] / c.mesh_stiffness[i], 1, 1e-3) << i;
      worst_K = std::max(worst_K, std::abs(K[k0 + i] / c.mesh_stiffness[i] - 1));
      worst_e = std::max(worst_e, std::abs(e[i] - c.loaded_te[i]) / approach);
      bound   = std::max(bound, 2e-3 * approach);
    }
  EXPECT_LE(std::abs(peak_to_peak(e) - peak_to_peak(c.loaded_te)), bound);
  std::printf("study variant against the standalone loaded contact: e_L within %.2e of the "
              "approach, K_m within %.2e, TE p-p %+.3e\n",
              worst_e, worst_K, peak_to_peak(e) / peak_to_peak(c.loaded_te) - 1);
}

TEST_F(StudyStage, AModifiedSceneComputesItsUnmodifiedPairsCompliance)
{
  // The compliance follows the macro-geometry: a 50 um tip relief on both members takes no
  // tooth out of the segments and moves no unit load off the mesh's surface (on the relieved
  // flanks they lay 50 um inside it, the tables' structural part came out negative and the
  // loaded contact refused the torque), so the map's variants reuse the modified scene's own
  // compliance; its loaded contact solves.
  const std::string relief_50 = std::regex_replace(relief_20, std::regex("= 20"), "= 50");
  ASSERT_EQ(run({file("plain.prm", fzg_scene("plain", "stiffness", "", "", ""))}), 0) << err.str();
  ASSERT_EQ(
      run({file("relieved.prm", fzg_scene("relieved", "stiffness", relief_50, relief_50, ""))}), 0)
      << err.str();
  EXPECT_EQ(out.str().find("refused"), std::string::npos) << out.str();
  const H5File plain    = H5File::open((dir / "out/plain/results.h5").string());
  const H5File relieved = H5File::open((dir / "out/relieved/results.h5").string());
  for (const char *member : {"pinion", "gear"})
    {
      const std::string name = std::string("compliance/fzg/") + member;
      const auto        a    = plain.root().group(name).read_doubles("compliance");
      EXPECT_EQ(relieved.root().group(name).read_doubles("compliance"), a) << member;
      EXPECT_EQ(relieved.root().group(name).read_ints("grid_teeth"),
                plain.root().group(name).read_ints("grid_teeth"))
          << member;
    }
  // the relief lowers the TE's variation at the scene's torque: it was solved, not skipped
  const auto pp = [](const H5File &f) {
    return peak_to_peak(f.root().group("stiffness/fzg").read_doubles("transmission_error_loaded"));
  };
  EXPECT_NE(pp(relieved), pp(plain));
}

TEST_F(StudyStage, BadSectionsAreRefusedByName)
{
  const auto refused = [&](const std::string &rest, const std::vector<std::string> &pieces) {
    const std::string path = file("bad.prm", fzg_scene("bad", "study", "", "", rest));
    EXPECT_NE(run({path}), 0);
    test_data::expect_contains(err.str(), pieces);
  };
  refused(std::regex_replace(map_section, std::regex("set positions per mesh cycle = 8"),
                             "set positions per mesh cycle = 8\n    set harmonics = 5"),
          {"Study/fzg/harmonics = 5", "Nyquist"});
  refused(std::regex_replace(map_section, std::regex("set torques                  = 100"),
                             "set torques                  = 100000"),
          {"Study/fzg/torques"});
  refused(std::regex_replace(map_section, std::regex("set tip relief               = 0, 20, 40"),
                             "set tip relief               = 0, -20"),
          {"tip relief"});
}

TEST_F(StudyStage, ToleranceSamplesWithoutDeviationsAreTheDesignAndWithThemSpreadAboveIt)
{
  const std::string tolerances  = R"(subsection Study
  subsection fzg
    set kind                     = tolerances
    set torques                  = 150
    set positions per mesh cycle = 4
    set harmonics                = 2
    set mesh cycles              = 3
    set tip relief               = 20
    set tip relief length        = 5.5
    set pinion class             = CLASS
    set gear class               = CLASS
    set samples                  = 6
  end
end
)";
  const auto        run_classes = [&](const std::string &name, int c) {
    const std::string rest = std::regex_replace(tolerances, std::regex("CLASS"), std::to_string(c));
    ASSERT_EQ(run({file(name + ".prm", fzg_scene(name, "study", "", "", rest))}), 0) << err.str();
  };
  run_classes("perfect", 0);
  {
    const H5File  f = H5File::open((dir / "out/perfect/results.h5").string());
    const H5Group g = f.root().group("study/fzg");
    EXPECT_EQ(g.read_attribute("kind"), "tolerances");
    const auto pp      = g.read_doubles("te_peak_to_peak");
    const auto nominal = g.group("nominal").read_doubles("te_peak_to_peak");
    ASSERT_EQ(pp.size(), 6u);
    for (const double x : pp)
      EXPECT_EQ(x, nominal[0]); // a point: the design itself
    for (const double x : g.group("percentiles").read_doubles("te_peak_to_peak"))
      EXPECT_EQ(x, nominal[0]);
    for (const double x : g.read_doubles("features"))
      EXPECT_EQ(x, 0);
  }
  run_classes("class8", 8);
  const H5File  f       = H5File::open((dir / "out/class8/results.h5").string());
  const H5Group g       = f.root().group("study/fzg");
  const auto    pp      = g.read_doubles("te_peak_to_peak");
  const auto    nominal = g.group("nominal").read_doubles("te_peak_to_peak");
  const auto    pct     = g.group("percentiles").read_doubles("te_peak_to_peak");
  ASSERT_EQ(pct.size(), 3u);
  EXPECT_LE(pct[0], pct[1]);
  EXPECT_LE(pct[1], pct[2]);
  // class 8 pitch deviations and runout (F_p about 40 um) outweigh the design's own TE p-p
  EXPECT_GT(pct[0], nominal[0]);
  std::vector<double> sorted = pp;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_DOUBLE_EQ(pct[1], (sorted[2] + sorted[3]) / 2); // the median of six
  // the features are those of the samples drawn again
  const Scene scene = read_scene((dir / "class8.prm").string());
  const auto [p, q] = scene.pair("fzg").involute_members();
  const auto feats  = g.read_doubles("features");
  for (std::size_t k = 0; k < 6; ++k)
    {
      const ToleranceSample s =
          draw_tolerance_sample(*p, *q, FlankSide::drive, scene.study.at("fzg").sampling, {}, k);
      for (std::size_t j = 0; j < s.features.size(); ++j)
        EXPECT_DOUBLE_EQ(feats[k * s.features.size() + j], s.features[j]);
    }
  EXPECT_EQ(g.group("sensitivity").group("te_peak_to_peak").read_doubles("coefficient").size(),
            tolerance_feature_names().size());
}

TEST_F(StudyStage, MisalignedAssembliesEqualTheStiffnessStageOfTheMisalignedScene)
{
  // A misalignment check of the FZG pair over crossing and intersecting angles (f_Sigma_beta,
  // f_Sigma_delta), then the stiffness stage of the scene misaligned as the grid's last point:
  // a misalignment moves the members, not their material, so the same compliance serves both
  // and the two are one computation.
  const std::string check = R"(subsection Study
  subsection fzg
    set kind                     = misalignments
    set torques                  = 150
    set positions per mesh cycle = 8
    set crossing angle           = 0, 0.3
    set intersecting angle       = 0, -0.3
  end
end
)";
  ASSERT_EQ(run({file("vh.prm", fzg_scene("vh", "study", "", "", check))}), 0) << err.str();
  test_data::expect_contains(out.str(), {"4 misaligned assemblies x 1 torques x 8 positions"});
  const H5File  f = H5File::open((dir / "out/vh/results.h5").string());
  const H5Group g = f.root().group("study/fzg");
  EXPECT_EQ(g.read_attribute("kind"), "misalignments");
  std::vector<hsize_t> shape;
  const auto           grid = g.read_doubles("grid", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{4, 2}));
  EXPECT_EQ(grid, (std::vector<double>{0, 0, 0, -0.3e-3, 0.3e-3, 0, 0.3e-3, -0.3e-3}));
  const auto eL = g.read_doubles("loaded_te", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{4, 1, 8}));
  const auto K       = g.read_doubles("mesh_stiffness");
  const auto pattern = g.read_doubles("pattern", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{4, 1, 16, 40}));
  const auto centre = g.read_doubles("pattern_centre");
  const auto extent = g.read_doubles("pattern_extent");
  const auto edge   = g.read_doubles("max_edge_share");
  const auto e0_pp  = g.read_doubles("unloaded_te_peak_to_peak");
  // The aligned spur pair: its pattern lies symmetric about the middle of the face (to the
  // cells' size) over the whole face width (14 mm), e_0 of unmodified flanks is 0.
  EXPECT_NEAR(centre[1], 0, 0.1e-3);
  EXPECT_NEAR(extent[2], -7e-3, 0.3e-3);
  EXPECT_NEAR(extent[3], 7e-3, 0.3e-3);
  EXPECT_LT(e0_pp[0], 1e-9);
  // Tilted, the pattern walks toward one end of the face (0.26 to 0.84 mm at this load) and
  // its pressure rises; the TE of involutes stays constant (the contact is conjugate wherever
  // it lies along the face).
  const auto p_max = g.read_doubles("max_pressure");
  for (std::size_t k = 1; k < 4; ++k)
    {
      EXPECT_GT(std::abs(centre[2 * k + 1]), 0.2e-3) << k;
      EXPECT_GT(p_max[k], p_max[0]) << k;
      EXPECT_LT(e0_pp[k], 1e-7) << k;
    }
  EXPECT_EQ(edge.size(), 4u);
  // Each grid point's pattern is its cells' pressures binned: the largest bin is the largest
  // pressure of the cycle.
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_DOUBLE_EQ(
        *std::max_element(pattern.begin() + long(k * 640), pattern.begin() + long((k + 1) * 640)),
        p_max[k]);

  // The stiffness stage of the scene misaligned as grid point 3.
  std::string scene = fzg_scene("tilted", "stiffness", "", "", "");
  scene += R"(subsection TCA
  subsection fzg
    set crossing angle     = 0.3
    set intersecting angle = -0.3
  end
end
)";
  ASSERT_EQ(run({file("tilted.prm", scene)}), 0) << err.str();
  const H5File  s   = H5File::open((dir / "out/tilted/results.h5").string());
  const H5Group st  = s.root().group("stiffness/fzg");
  const auto    eL1 = st.read_doubles("transmission_error_loaded");
  const auto    K1  = st.read_doubles("mesh_stiffness");
  ASSERT_EQ(eL1.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i)
    {
      EXPECT_NEAR(eL[3 * 8 + i], eL1[i], 1e-9 * std::abs(eL1[i])) << i;
      EXPECT_NEAR(K[3 * 8 + i], K1[i], 1e-9 * K1[i]) << i;
    }
}

TEST_F(StudyStage, MisalignmentsBeyondTheFaceWidthAreRefusedAsAUnitSlip)
{
  const std::string check = R"(subsection Study
  subsection fzg
    set kind   = misalignments
    set torques = 150
    set offset = 0, 20000
  end
end
)";
  EXPECT_NE(run({file("slip.prm", fzg_scene("slip", "study", "", "", check))}), 0);
  test_data::expect_contains(err.str(), {"Study/fzg/offset = 20000", "unit slip"});
  const std::string mixed = R"(subsection Study
  subsection fzg
    set kind       = misalignments
    set torques    = 150
    set offset     = 0, 20
    set tip relief = 10
  end
end
)";
  EXPECT_NE(run({file("mixed.prm", fzg_scene("mixed", "study", "", "", mixed))}), 0);
  test_data::expect_contains(err.str(), {"Study/fzg/tip relief", "kind = misalignments"});
}

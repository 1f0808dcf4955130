// Notes (section Notes/<name>): caveats carried with the numbers. Each names a pair or a train of
// the scene (another name is refused like any bad input), reaches results.h5 as the root
// attribute `notes` (one line per note: name, area and text, tab-separated) and enters no
// stage's cache key: changing only a note recomputes nothing.
#include "base/types.h"
#include "driver/driver.h"
#include "driver/h5_file.h"
#include "driver/scene.h"
#include "driver/stages.h"
#include "tests/driver/driver_fixture.h"
#include "tests/driver/small_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

using namespace gearkit;
using test_data::expect_contains;
using test_data::refusal;
namespace fs = std::filesystem;

namespace
{
const std::string notes_source_dir = GEARKIT_SOURCE_DIR;

class SceneNotes : public test_data::GearkitRun
{
};

// Two spur pairs of m 2 mm, 19/37 and 21/40 teeth: their flanks alone.
const std::string two_pairs =
    test_data::scene_section("small", "flanks", "p1, p2") +
    test_data::flanks_section({test_data::SpurPair{}, test_data::SpurPair{"p2", 21, 40}});

// p2 before p1 in the file, a comment after a note, a note continued on the next line.
const std::string notes = R"(
subsection Notes
  subsection p2
    set loaded contact = K_m of held 7-tooth segments: 42 % above the whole bodies  # why
  end
  subsection p1
    set dynamics  = supports fitted \
                    to the seed's resonances
    set gear data = tip diameters from the addendum factor
    set gear train =
  end
end
)";

const std::string notes_changed = R"(
subsection Notes
  subsection p2
    set loaded contact = another caveat
    set unloaded TCA   = and one more
  end
end
)";

std::map<std::string, std::string>
stage_keys(const Scene &scene)
{
  std::map<std::string, std::string> keys;
  for (const StageDefinition &s : stage_definitions())
    keys[s.name] = stage_key(scene, s.name);
  return keys;
}

// The text without its top-level subsection Notes.
std::string
without_notes(const std::string &text)
{
  std::istringstream in(text);
  std::string        out;
  int                depth    = 0;
  bool               in_notes = false;
  for (std::string line; std::getline(in, line);)
    {
      const auto        b       = line.find_first_not_of(" \t");
      const std::string trimmed = b == std::string::npos ? "" : line.substr(b);
      const bool        opens   = trimmed.rfind("subsection ", 0) == 0;
      const bool        closes  = trimmed == "end" || trimmed.rfind("end ", 0) == 0;
      if (opens && depth == 0 && trimmed.substr(11) == "Notes")
        in_notes = true;
      depth += opens ? 1 : closes ? -1 : 0;
      if (!in_notes)
        out += line + "\n";
      else if (closes && depth == 0)
        in_notes = false;
    }
  return out;
}
} // namespace

TEST_F(SceneNotes, NotesAreReadInTheOrderOfThePairsAndOfTheAreas)
{
  const Scene scene = read_scene(file("scene.prm", two_pairs + notes));
  ASSERT_EQ(scene.notes.size(), 3u);
  const std::vector<std::vector<std::string>> expected = {
      {"p1", "gear data", "tip diameters from the addendum factor"},
      {"p1", "dynamics", "supports fitted to the seed's resonances"},
      {"p2", "loaded contact", "K_m of held 7-tooth segments: 42 % above the whole bodies"}};
  for (std::size_t i = 0; i < expected.size(); ++i)
    {
      EXPECT_EQ(scene.notes[i].name, expected[i][0]) << i;
      EXPECT_EQ(scene.notes[i].area, expected[i][1]) << i;
      EXPECT_EQ(scene.notes[i].text, expected[i][2]) << i;
    }
  EXPECT_EQ(notes_text(scene.notes),
            "p1\tgear data\ttip diameters from the addendum factor\n"
            "p1\tdynamics\tsupports fitted to the seed's resonances\n"
            "p2\tloaded contact\tK_m of held 7-tooth segments: 42 % above the whole bodies\n");
  EXPECT_EQ(note_areas(), (std::vector<std::string>{"gear data", "unloaded TCA", "loaded contact",
                                                    "dynamics", "gear train"}));

  // Without notes: none, and no Notes block among the parameters as run.
  const Scene plain = read_scene(file("plain.prm", two_pairs));
  EXPECT_TRUE(plain.notes.empty());
  EXPECT_EQ(plain.sections.count("Notes"), 0u);
  EXPECT_EQ(notes_text(plain.notes), "");
  // An empty Notes section reads too.
  EXPECT_EQ(refusal(file("empty.prm", two_pairs + "subsection Notes\nend\n")), "");

  // JSON: a tab or a line break in a note reads as a space (the attribute's separators).
  const std::string json      = R"({
  "Scene": {"name": "small", "outputs": "flanks", "pairs": "p1"},
  "Flanks": {"p1": {"Pinion": {"number of teeth": 19, "normal module": 2},
                    "Gear": {"number of teeth": 37, "normal module": 2}}},
  "Notes": {"p1": {"gear train": " a\tb\nc "}}
}
)";
  const Scene       from_json = read_scene(file("scene.json", json));
  ASSERT_EQ(from_json.notes.size(), 1u);
  EXPECT_EQ(notes_text(from_json.notes), "p1\tgear train\ta b c\n");
}

TEST_F(SceneNotes, ChangingOnlyANoteLeavesEveryStageKey)
{
  // No stage reads the Notes section.
  for (const StageDefinition &s : stage_definitions())
    EXPECT_EQ(std::count(s.sections.begin(), s.sections.end(), "Notes"), 0) << s.name;

  const Scene plain   = read_scene(file("plain.prm", two_pairs));
  const Scene noted   = read_scene(file("noted.prm", two_pairs + notes));
  const Scene changed = read_scene(file("changed.prm", two_pairs + notes_changed));
  // the parameters as run do differ, in the Notes block alone
  ASSERT_EQ(noted.sections.count("Notes"), 1u);
  ASSERT_EQ(changed.sections.count("Notes"), 1u);
  EXPECT_NE(noted.sections.at("Notes"), changed.sections.at("Notes"));
  for (const char *section : {"Scene", "Flanks"})
    EXPECT_EQ(noted.sections.at(section), plain.sections.at(section)) << section;
  const auto keys = stage_keys(plain);
  EXPECT_EQ(keys.size(), stage_definitions().size());
  EXPECT_EQ(stage_keys(noted), keys);
  EXPECT_EQ(stage_keys(changed), keys);

  // The shipped cases with notes, among them trains' (seed002_*), against themselves without.
  int                   noted_cases = 0;
  std::set<std::string> noted_areas;
  for (const auto &entry : fs::recursive_directory_iterator(notes_source_dir + "/cases"))
    if (entry.path().extension() == ".prm")
      {
        std::ifstream     in(entry.path());
        const std::string text((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
        if (text.find("subsection Notes") == std::string::npos)
          continue;
        ++noted_cases;
        const fs::path folder = dir / entry.path().stem();
        fs::create_directories(folder);
        const std::string with = (folder / entry.path().filename()).string();
        std::ofstream(with) << text;
        const std::string without =
            (folder / ("without_" + entry.path().filename().string())).string();
        std::ofstream(without) << without_notes(text);
        const Scene a = read_scene(with), b = read_scene(without);
        EXPECT_FALSE(a.notes.empty()) << entry.path();
        EXPECT_TRUE(b.notes.empty()) << entry.path();
        EXPECT_EQ(stage_keys(a), stage_keys(b)) << entry.path();
        for (const SceneNote &n : a.notes)
          noted_areas.insert(n.area);
      }
  EXPECT_GE(noted_cases, 3);
  EXPECT_EQ(noted_areas.count("gear train"), 1u) << "a train case with a note";
  EXPECT_EQ(noted_areas.count("loaded contact"), 1u) << "a finite-element case with a note";
}

TEST_F(SceneNotes, ANoteNamingNoPairOrTrainIsRefused)
{
  const std::string unknown = two_pairs + R"(
subsection Notes
  subsection p3
    set gear data = a pair this scene does not have
  end
end
)";
  const std::string path    = file("scene.prm", unknown);
  expect_contains(refusal(path), {path, "Notes/p3", "'p3' names no pair or train",
                                  "Scene/pairs: p1, p2", "Scene/trains: none"});
  // the command line: exit 1, the message, no result file
  EXPECT_EQ(run({path}), 1);
  expect_contains(err.str(), {"gearkit: error:", "Notes/p3", "'p3'"});
  EXPECT_FALSE(fs::exists(dir / "out/small/results.h5"));
  // a name in another letter case names another thing
  expect_contains(refusal(file("case.prm", two_pairs + "subsection Notes\n  subsection P1\n  "
                                                       "end\nend\n")),
                  {"Notes/P1", "'P1' names no pair or train"});
  // in JSON alike
  const std::string json = R"({
  "Scene": {"name": "small", "outputs": "flanks", "pairs": "p1"},
  "Flanks": {"p1": {"Pinion": {"number of teeth": 19, "normal module": 2},
                    "Gear": {"number of teeth": 37, "normal module": 2}}},
  "Notes": {"q": {"gear data": "x"}}
}
)";
  expect_contains(refusal(file("scene.json", json)),
                  {"scene.json", "Notes/q", "'q' names no pair or train", "Scene/pairs: p1"});

  // An area that is none of the five, and a note outside a pair's or train's subsection: refused
  // as any unknown entry, by name.
  expect_contains(refusal(file("area.prm", two_pairs + "subsection Notes\n  subsection p1\n    set "
                                                       "remark = x\n  end\nend\n")),
                  {"area.prm", "remark"});
  expect_contains(
      refusal(file("loose.prm", two_pairs + "subsection Notes\n  set gear data = x\nend\n")),
      {"loose.prm", "gear data"});
}

TEST_F(SceneNotes, NotesReachTheResultFileAndRecomputeNothing)
{
  const std::string  root = (dir / "out").string();
  std::ostringstream log;
  const RunSummary   first = run_scene(read_scene(file("scene.prm", two_pairs + notes)), root, log);
  EXPECT_NE(log.str().find("stage flanks: running"), std::string::npos) << log.str();
  EXPECT_EQ(H5File::open(first.results_file).root().read_attribute("notes"),
            "p1\tgear data\ttip diameters from the addendum factor\n"
            "p1\tdynamics\tsupports fitted to the seed's resonances\n"
            "p2\tloaded contact\tK_m of held 7-tooth segments: 42 % above the whole bodies\n");

  // another note: the flanks are reused, the new note is written
  log.str("");
  const RunSummary second =
      run_scene(read_scene(file("scene.prm", two_pairs + notes_changed)), root, log);
  EXPECT_NE(log.str().find("stage flanks: reused"), std::string::npos) << log.str();
  EXPECT_EQ(log.str().find("running"), std::string::npos) << log.str();
  ASSERT_EQ(second.stages.size(), 1u);
  EXPECT_TRUE(second.stages[0].reused);
  const H5Group results = H5File::open(second.results_file).root();
  EXPECT_EQ(results.read_attribute("notes"),
            "p2\tunloaded TCA\tand one more\np2\tloaded contact\tanother caveat\n");
  // and the parameters as run show the Notes section
  EXPECT_NE(results.read_attribute("scene_parameters").find("subsection Notes\n"),
            std::string::npos);

  // no notes: the attribute is there, empty
  log.str("");
  const RunSummary plain = run_scene(read_scene(file("scene.prm", two_pairs)), root, log);
  EXPECT_NE(log.str().find("stage flanks: reused"), std::string::npos) << log.str();
  EXPECT_EQ(H5File::open(plain.results_file).root().read_attribute("notes"), "");
}

TEST_F(SceneNotes, TheParameterListDescribesTheNotesAndReadsAsAScene)
{
  ASSERT_EQ(run({"--print-parameters"}), 0) << err.str();
  const std::string listing = out.str();
  expect_contains(listing, {"# Notes/<name> (optional)", "subsection Notes\n  subsection pair\n",
                            "    set gear data = \n", "    set unloaded TCA = \n",
                            "    set loaded contact = \n", "    set dynamics = \n",
                            "    set gear train = \n",
                            "A caveat the report shows next to the loaded contact",
                            "root attribute notes", "recomputes nothing"});
  // after the stages' sections, before the commented train
  EXPECT_LT(listing.find("subsection TCA\n"), listing.find("subsection Notes\n"));
  EXPECT_LT(listing.find("subsection Notes\n"), listing.find("# subsection Train"));
  // the listing is itself a valid scene, with no notes (all empty)
  const Scene scene = read_scene(file("listing.prm", listing));
  EXPECT_TRUE(scene.notes.empty());
}

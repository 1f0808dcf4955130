// The scene file's syntax (driver/scene_text.h): the variants deal.II tolerates or a user's
// editor writes (CRLF, a byte-order mark, keyword case, tabs) read exactly as the plain file;
// includes are followed with cycles, depth and missing files refused; a parameter set twice is
// refused naming both lines; JSON and XML scenes pass the same checks as .prm ones.
#include "base/types.h"
#include "driver/driver.h"
#include "driver/scene.h"
#include "driver/scene_text.h"
#include "driver/stages.h"
#include "tests/driver/driver_fixture.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

using namespace gearkit;
using test_data::expect_contains;
using test_data::refusal;
namespace fs = std::filesystem;

namespace
{
class SceneSyntax : public test_data::GearkitRun
{
protected:
  // Writes bytes exactly (no text-mode translation); returns the path.
  std::string
  bytes(const std::string &name, const std::string &content) const
  {
    std::ofstream(dir / name, std::ios::binary) << content;
    return (dir / name).string();
  }

  // Runs a scene that must be refused: exit 1, every expected piece in the message, no result.
  void
  expect_refused(const std::string &path, const std::vector<std::string> &expected)
  {
    EXPECT_EQ(run({path}), 1) << path << "\n" << out.str() << err.str();
    for (const std::string &e : expected)
      EXPECT_NE(err.str().find(e), std::string::npos) << "'" << e << "' in: " << err.str();
    // nothing written for any scene name: no results.h5, no temporary file
    if (fs::exists(dir / "out"))
      {
        for (const auto &f : fs::recursive_directory_iterator(dir / "out"))
          EXPECT_EQ(f.path().filename().string().rfind("results.h5", 0), std::string::npos)
              << f.path();
      }
  }
};

// The first line is a comment: a byte-order mark in front of it made deal.II refuse "the line
// <# small scene>".
const std::string plain = R"(# small scene
subsection Scene
  set name    = small
  set outputs = flanks, measured
  set pairs   = p1
end
subsection Flanks
  subsection p1
    set grid profile points = 3
    set grid face points    = 4
    subsection Pinion
      set number of teeth = 19
      set normal module   = 2    # mm
    end
    subsection Gear
      set number of teeth = 37
      set normal module   = 2
    end
  end
end
subsection Measured flanks
  subsection p1
    set source         = synthesised
    set profile points = 5
    set face points    = 7
    set pinion teeth   = 0, 3
  end
end
)";

std::string
replace_all(std::string s, const std::string &from, const std::string &to)
{
  for (std::size_t p = 0; (p = s.find(from, p)) != std::string::npos; p += to.size())
    s.replace(p, from.size(), to);
  return s;
}

// Line (from 1) of the first occurrence of `what` at or after character `from`.
int
line_of(const std::string &text, const std::string &what, std::size_t from = 0)
{
  const std::size_t p = text.find(what, from);
  EXPECT_NE(p, std::string::npos) << what;
  return int(std::count(text.begin(), text.begin() + std::ptrdiff_t(p), '\n')) + 1;
}

std::string
upper_keywords(const std::string &s)
{
  return replace_all(replace_all(replace_all(s, "subsection ", "SUBSECTION "), "set ", "SET "),
                     "end\n", "END\n");
}

std::string
mixed_keywords(const std::string &s)
{
  return replace_all(replace_all(replace_all(s, "subsection ", "SubSection "), "set ", "Set "),
                     "end\n", "End\n");
}

// Two-space indents and the spaces after keywords and around = as tabs.
std::string
tabs(const std::string &s)
{
  return replace_all(
      replace_all(replace_all(replace_all(s, "  ", "\t"), "set ", "set\t"), " = ", "\t=\t"),
      "subsection ", "subsection\t");
}
} // namespace

TEST_F(SceneSyntax, LineBreaksByteOrderMarkKeywordCaseAndTabsReadAsThePlainFile)
{
  const Scene reference = read_scene(bytes("plain.prm", plain));
  ASSERT_EQ(reference.pairs.size(), 1u);
  ASSERT_EQ(reference.pairs[0].pinion.teeth, 19);
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"crlf", replace_all(plain, "\n", "\r\n")},
      {"bom", "\xEF\xBB\xBF" + plain},
      {"upper case", upper_keywords(plain)},
      {"mixed case", mixed_keywords(plain)},
      {"tabs", tabs(plain)},
      {"all at once", "\xEF\xBB\xBF" + replace_all(tabs(mixed_keywords(plain)), "\n", "\r\n")},
      {"continued line in upper case",
       replace_all(upper_keywords(plain), "SET pinion teeth   = 0, 3",
                   "SET pinion teeth = 0, \\\r\n3")},
  };
  for (const auto &[what, text] : variants)
    {
      ASSERT_NE(text, plain) << what;
      Scene s;
      try
        {
          s = read_scene(bytes("variant.prm", text));
        }
      catch (const InputError &e)
        {
          ADD_FAILURE() << what << ": " << e.what();
          continue;
        }
      EXPECT_EQ(s.name, "small") << what;
      EXPECT_EQ(s.sections, reference.sections) << what;
      ASSERT_EQ(s.pairs.size(), 1u) << what;
      EXPECT_EQ(s.pairs[0].name, "p1") << what;
      EXPECT_EQ(s.pairs[0].pinion.teeth, 19) << what;
      EXPECT_EQ(s.pairs[0].gear.teeth, 37) << what;
      EXPECT_EQ(s.measured.at("p1").pinion_teeth, (std::vector<int>{0, 3})) << what;
      for (const std::string &stage : required_stages(s))
        EXPECT_EQ(stage_key(s, stage), stage_key(reference, stage)) << what << ", " << stage;
    }
}

TEST_F(SceneSyntax, AWindowsFileRunsAndReusesThePlainFilesCache)
{
  const std::string flanks_only = replace_all(plain, "flanks, measured", "flanks");
  ASSERT_EQ(run({bytes("plain.prm", flanks_only)}), 0) << err.str();
  EXPECT_NE(out.str().find("stage flanks: ran"), std::string::npos) << out.str();
  const std::string windows =
      "\xEF\xBB\xBF" + replace_all(tabs(upper_keywords(flanks_only)), "\n", "\r\n");
  ASSERT_EQ(run({bytes("windows.prm", windows)}), 0) << err.str();
  EXPECT_NE(out.str().find("stage flanks: reused"), std::string::npos) << out.str();
  EXPECT_TRUE(fs::exists(dir / "out/small/results.h5"));
}

TEST_F(SceneSyntax, WhatCannotBeNormalisedIsRefusedByName)
{
  expect_refused(bytes("utf16.prm", "\xFF\xFE" + plain), {"utf16.prm", "UTF-16"});
  expect_refused(bytes("mac.prm", replace_all(plain, "\n", "\r")),
                 {"mac.prm:1", "carriage return"});
  std::string nul              = plain;
  nul[plain.find("set pairs")] = '\0';
  expect_refused(bytes("nul.prm", nul), {"nul.prm:5", "NUL byte"});
  expect_refused(bytes("scene.txt", plain), {"scene.txt", "'.txt'", ".prm"});
  // invisible characters outside comments looked right in deal.II's messages; in comments fine
  expect_refused(bytes("nbsp.prm", replace_all(plain, "set pairs   = p1", "set pairs\xC2\xA0= p1")),
                 {"nbsp.prm:5", "no-break space (U+00A0) after 'set pairs'"});
  EXPECT_EQ(refusal(bytes("comment.prm", replace_all(plain, "# mm", "# mm\xC2\xA0\xE2\x80\x8B"))),
            "");
}

// deal.II refused these too, but the pre-reader reads the file first: it refuses them at their
// line, so that the first mistake in the file is the one reported.
TEST_F(SceneSyntax, AStatementThatIsNoneIsRefusedAtItsLine)
{
  struct Case
  {
    std::string from, to, at, expected; // `at` begins the line refused
  };
  const std::vector<Case> cases = {
      {"  set pairs   = p1", "  sett pairs   = p1", "sett",
       "'sett pairs   = p1' is not a statement"},
      {"  set pairs   = p1", "  set pairs p1", "set pairs p1", "'set pairs p1': 'set' needs"},
      {"    end\n    subsection Gear", "    END SUBSECTION\n    subsection Gear", "END SUB",
       "'END SUBSECTION': 'end' stands alone"},
      {"end\nsubsection Measured", "end\nend\nsubsection Measured", "end\nsubsection Measured",
       "this 'end' closes no subsection"},
      {"subsection Measured flanks", "subsection\nsubsection Measured flanks", "subsection\n",
       "'subsection' is not a statement"},
  };
  for (const Case &c : cases)
    {
      const std::string text = replace_all(plain, c.from, c.to);
      ASSERT_NE(text, plain) << c.to;
      expect_refused(bytes("scene.prm", text),
                     {"scene.prm:" + std::to_string(line_of(text, c.at)) + ": ", c.expected});
    }
}

TEST_F(SceneSyntax, IncludesReadAsTheirTextWithLinesNamedInTheirFiles)
{
  // The pair's flanks in an included file written on Windows, included from inside the Flanks
  // section by an upper-case INCLUDE in a subfolder's file.
  const std::size_t flanks_begin = plain.find("  subsection p1");
  const std::size_t flanks_end   = plain.find("end\nsubsection Measured");
  const std::string pair_text    = plain.substr(flanks_begin, flanks_end - flanks_begin);
  fs::create_directories(dir / "parts");
  bytes("parts/p1.prm", "\xEF\xBB\xBF" + replace_all(pair_text, "\n", "\r\n"));
  const std::string with_include = plain.substr(0, flanks_begin) +
                                   "  INCLUDE parts/p1.prm   # the pair\n" +
                                   plain.substr(flanks_end);
  const Scene reference = read_scene(bytes("plain.prm", plain));
  const Scene s         = read_scene(bytes("scene.prm", with_include));
  EXPECT_EQ(s.sections, reference.sections);

  // deal.II's messages name the included file and its line, and lines after the include keep
  // their numbers.
  bytes("parts/p1.prm", replace_all(pair_text, "= 37", "= 1"));
  const std::string included = (dir / "parts/p1.prm").string();
  std::string       message  = refusal((dir / "scene.prm").string());
  EXPECT_NE(message.find("Line <" + std::to_string(line_of(pair_text, "= 37")) + "> of file <" +
                         included + " (included at " + (dir / "scene.prm").string() + ":" +
                         std::to_string(line_of(with_include, "INCLUDE")) + ")"),
            std::string::npos)
      << message;
  bytes("parts/p1.prm", pair_text);
  bytes("scene.prm", replace_all(with_include, "= synthesised", "= coffee"));
  message = refusal((dir / "scene.prm").string());
  EXPECT_NE(message.find("Line <" + std::to_string(line_of(with_include, "= synthesised")) +
                         "> of file <" + (dir / "scene.prm").string() + ">"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("coffee"), std::string::npos) << message;

  // An included file closes the subsections it opens, and only those (deal.II's rule).
  bytes("parts/p1.prm", pair_text + "  end\n");
  EXPECT_NE(refusal((dir / "scene.prm").string()).find("did not open"), std::string::npos);
  bytes("parts/p1.prm", "  subsection p1\n");
  message = refusal((dir / "scene.prm").string());
  EXPECT_NE(message.find(included + ":1"), std::string::npos) << message;
  EXPECT_NE(message.find("has no 'end'"), std::string::npos) << message;
}

TEST_F(SceneSyntax, IncludeCyclesDepthAndMissingFilesAreRefusedWithTheChain)
{
  const std::string head = plain; // a valid scene, the includes after it
  const auto        at   = [&](const std::string &file, const std::string &text) {
    return file + ":" + std::to_string(line_of(text, "include"));
  };
  // a scene including itself crashed deal.II (unbounded recursion)
  const std::string self = head + "include self.prm\n";
  expect_refused(bytes("self.prm", self), {"include cycle", at("self.prm", self) + " includes " +
                                                                (dir / "self.prm").string()});
  // a includes b includes a
  bytes("b.prm", "# b\ninclude a.prm\n");
  const std::string a = head + "include b.prm\n";
  expect_refused(bytes("a.prm", a),
                 {"include cycle", at("a.prm", a) + " includes " + (dir / "b.prm").string(),
                  "b.prm:2 includes " + (dir / "a.prm").string()});
  // nine nested includes, one more than allowed
  for (int i = 1; i <= SceneText::max_include_depth + 1; ++i)
    bytes("level" + std::to_string(i) + ".prm",
          i <= SceneText::max_include_depth ? "include level" + std::to_string(i + 1) + ".prm\n"
                                            : "# deepest\n");
  const std::string deep = head + "include level1.prm\n";
  expect_refused(bytes("deep.prm", deep),
                 {"nested more than 8 deep", at("deep.prm", deep) + " includes",
                  "level8.prm:1 includes " + (dir / "level9.prm").string()});
  // eight levels are allowed
  bytes("level8.prm", "# deepest allowed\n");
  EXPECT_EQ(refusal((dir / "deep.prm").string()), "");
  // a missing file, no file
  const std::string missing = head + "\ninclude nowhere.prm\n";
  expect_refused(bytes("missing.prm", missing),
                 {at("missing.prm", missing), (dir / "nowhere.prm").string(), "does not exist"});
  const std::string empty = head + "include   # nothing\n";
  expect_refused(bytes("empty.prm", empty), {at("empty.prm", empty), "names no file"});
}

TEST_F(SceneSyntax, AParameterSetTwiceIsRefusedNamingBothLines)
{
  // twice in the same subsection
  const std::string twice =
      replace_all(plain, "      set number of teeth = 19\n",
                  "      set number of teeth = 19\n      set number of teeth = 21\n");
  expect_refused(bytes("scene.prm", twice),
                 {"Flanks/p1/Pinion/number of teeth is set twice",
                  "scene.prm:" + std::to_string(line_of(twice, "= 19")),
                  "scene.prm:" + std::to_string(line_of(twice, "= 21"))});
  // the subsection opened twice: allowed (deal.II merges them), but not the same parameter
  const std::string reopened = plain + "SUBSECTION Flanks\n  subsection p1\n    subsection Pinion\n"
                                       "      set number of teeth  =  21\n    end\n  end\nend\n";
  expect_refused(bytes("scene.prm", reopened),
                 {"Flanks/p1/Pinion/number of teeth is set twice",
                  "scene.prm:" + std::to_string(line_of(reopened, "= 19")),
                  "scene.prm:" + std::to_string(line_of(reopened, "=  21"))});
  const std::string other_parameter =
      replace_all(reopened, "set number of teeth  =  21", "set profile shift coefficient = 0.1");
  EXPECT_EQ(refusal(bytes("scene.prm", other_parameter)), "");
  // in the scene and a file it includes
  bytes("more.prm", "subsection Scene\n  set pairs = p1\nend\n");
  expect_refused(bytes("scene.prm", plain + "include more.prm\n"),
                 {"Scene/pairs is set twice",
                  "scene.prm:" + std::to_string(line_of(plain, "set pairs")),
                  "more.prm:2 (included at " + (dir / "scene.prm").string()});
}

namespace
{
const std::string xml_scene = R"(<?xml version="1.0" encoding="utf-8"?>
<ParameterHandler>
  <!-- deal.II's XML form: names mangled (a space as _20) -->
  <Scene>
    <name>small</name>
    <outputs>flanks, measured</outputs>
    <pairs>p1</pairs>
  </Scene>
  <Flanks>
    <p1>
      <grid_20profile_20points>3</grid_20profile_20points>
      <grid_20face_20points><value>4</value><default_value>29</default_value></grid_20face_20points>
      <Pinion>
        <number_20of_20teeth>19</number_20of_20teeth>
        <normal_20module>2</normal_20module>
      </Pinion>
      <Gear>
        <number_20of_20teeth>37</number_20of_20teeth>
        <normal_20module>2</normal_20module>
      </Gear>
    </p1>
  </Flanks>
  <Measured_20flanks>
    <p1>
      <source>synthesised</source>
      <profile_20points>5</profile_20points>
      <face_20points>7</face_20points>
      <pinion_20teeth>0, 3</pinion_20teeth>
    </p1>
  </Measured_20flanks>
</ParameterHandler>
)";

const std::string json_scene = R"({
  "Scene": {"name": "small", "outputs": "flanks, measured", "pairs": "p1"},
  "Flanks": {
    "p1": {
      "grid profile points": "3",
      "grid face points": {"value": "4", "default_value": "29"},
      "Pinion": {"number of teeth": "19", "normal module": 2},
      "Gear": {"number of teeth": 37, "normal module": "2"}
    }
  },
  "Measured_20flanks": {
    "p1": {"source": "synthesised", "profile points": "5", "face points": "7",
           "pinion teeth": "0, 3"}
  }
}
)";
} // namespace

TEST_F(SceneSyntax, XmlAndJsonScenesReadAsThePlainFileAndPassTheSameChecks)
{
  const Scene reference = read_scene(bytes("plain.prm", plain));
  for (const auto &[name, text] : {std::pair{"scene.xml", xml_scene}, {"scene.json", json_scene}})
    {
      const std::string path = bytes(name, text);
      ASSERT_EQ(refusal(path), "") << name;
      EXPECT_EQ(read_scene(path).sections, reference.sections) << name;
      EXPECT_EQ(refusal(bytes(name, "\xEF\xBB\xBF" + replace_all(text, "\n", "\r\n"))), "")
          << name << " with a byte-order mark and CRLF";
    }

  // A pair named but not described: with XML it silently ran with a default pair.
  expect_refused(bytes("scene.xml", replace_all(xml_scene, "<pairs>p1<", "<pairs>p1, q<")),
                 {"scene.xml", "the pair 'q' has no subsection Flanks/q"});
  expect_refused(
      bytes("scene.json", replace_all(json_scene, "\"pairs\": \"p1\"", "\"pairs\": \"p1, q\"")),
      {"scene.json", "the pair 'q' has no subsection Flanks/q"});
  // a pair name with - or _ is described in its mangled form
  const std::string dashed = replace_all(replace_all(xml_scene, "p1<", "p-1<"), "<p1>", "<p_2d1>");
  const std::string dashed_end = replace_all(dashed, "</p1>", "</p_2d1>");
  EXPECT_EQ(refusal(bytes("dashed.xml", dashed_end)), "");

  // A parameter given twice: boost's trees keep both, deal.II took the second.
  expect_refused(bytes("scene.xml", replace_all(xml_scene, "<number_20of_20teeth>37",
                                                "<number_20of_20teeth>21</number_20of_20teeth>"
                                                "<number_20of_20teeth>37")),
                 {"scene.xml", "Flanks/p1/Gear/number of teeth is given twice"});
  expect_refused(bytes("scene.json", replace_all(json_scene, "\"number of teeth\": 37",
                                                 "\"number of teeth\": 37, "
                                                 "\"number of teeth\": 21")),
                 {"scene.json", "Flanks/p1/Gear/number of teeth is given twice"});
  // and in a section given twice
  expect_refused(
      bytes("scene.json", replace_all(json_scene, "\"Flanks\": {",
                                      "\"Scene\": {\"pairs\": \"p1\"},\n  \"Flanks\": {")),
      {"scene.json", "Scene/pairs is given twice"});

  // names deal.II cannot demangle, arrays, syntax errors
  const std::string bare = replace_all(json_scene, "\"p1\"", "\"p_1\"");
  expect_refused(bytes("scene.json", bare), {"scene.json", "'p_1'", "'p_5f1'"});
  expect_refused(bytes("scene.json", replace_all(json_scene, "\"p1\"}", "[\"p1\"]}")),
                 {"scene.json", "Scene", "JSON array"});
  expect_refused(bytes("scene.json", replace_all(json_scene, "\"Flanks\": {", "\"Flanks\" {")),
                 {"scene.json:3"});
  // boost's parsers and deal.II's reader recurse once per level: a bound before them
  const std::string deep_json =
      "{\"a\": " + std::string(20000, '[') + std::string(20000, ']') + "}";
  expect_refused(bytes("scene.json", deep_json), {"scene.json", "nested 20001 deep", "at most 64"});
  std::string deep_xml = "<ParameterHandler>";
  for (int i = 0; i < 100; ++i)
    deep_xml += "<a" + std::to_string(i) + " >";
  expect_refused(bytes("scene.xml", deep_xml), {"scene.xml", "elements nested 101 deep"});
  expect_refused(bytes("scene.xml", replace_all(xml_scene, "<Gear>", "<Gear teeth=\"37\">")),
                 {"scene.xml, in Flanks/p1/Gear", "XML attribute (teeth=\"37\")"});
}

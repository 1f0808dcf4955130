// The results schema (driver/results_schema.h): every dataset named once, well formed; writes
// take their units and description from it and refuse a dataset it lacks; --print-results.
// (That every case writes only datasets of the schema, with its units and descriptions:
// tests/cases/check_results_schema.py on every case's results.h5.)
#include "driver/driver.h"
#include "driver/h5_file.h"
#include "driver/results_schema.h"
#include "tests/driver/driver_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

using namespace gearkit;

namespace
{
/// A string attribute of the dataset at `path` in `file`.
std::string
dataset_attribute(const H5File &file, const std::string &path, const std::string &name)
{
  H5Handle attr(
      hdf5_check(H5Aopen_by_name(file.id(), path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                 "attribute " + path + "@" + name),
      H5Aclose);
  H5Handle type(hdf5_check(H5Aget_type(attr.id()), "attribute type"), H5Tclose);
  char    *text = nullptr;
  hdf5_check(H5Aread(attr.id(), type.id(), &text), "attribute read");
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

/// The message of the std::logic_error `f` throws ("" if none).
template <typename F>
std::string
logic_error_of(F &&f)
{
  try
    {
      f();
    }
  catch (const std::logic_error &e)
    {
      return e.what();
    }
  return "";
}
} // namespace

TEST(ResultsSchema, EveryDatasetOnceAndWellFormed)
{
  const std::vector<ResultDataset> &all = results_schema();
  ASSERT_GT(all.size(), 300u);
  std::set<std::pair<std::string, std::string>> seen;
  std::set<std::string>                         stages;
  for (const ResultDataset &d : all)
    {
      const std::string what = d.group + "/" + d.name;
      EXPECT_TRUE(seen.insert({d.group, d.name}).second) << what << " twice";
      stages.insert(d.group.substr(0, d.group.find('/')));
      // a group pattern below a stage's group, its placeholders whole levels or names
      EXPECT_FALSE(d.group.empty() || d.group.front() == '/' || d.group.back() == '/') << what;
      EXPECT_EQ(d.group.find("//"), std::string::npos) << what;
      EXPECT_EQ(std::count(d.group.begin(), d.group.end(), '<'),
                std::count(d.group.begin(), d.group.end(), '>'))
          << what;
      EXPECT_FALSE(d.name.empty() || d.name.find_first_of("/<>{}") != std::string::npos) << what;
      EXPECT_FALSE(d.shape.empty() || d.units.empty() || d.description.empty()) << what;
      EXPECT_EQ(d.shape.find("  "), std::string::npos) << what;
      // a choice is one pair of braces with at least two alternatives; the description as
      // written never keeps a brace
      const auto open = d.description.find('{');
      if (open == std::string::npos)
        {
          EXPECT_EQ(d.description.find('}'), std::string::npos) << what;
          EXPECT_EQ(result_description(d), d.description);
        }
      else
        {
          const auto close = d.description.find('}');
          ASSERT_NE(close, std::string::npos) << what;
          EXPECT_LT(open, close) << what;
          EXPECT_NE(d.description.substr(open, close - open).find('|'), std::string::npos) << what;
          EXPECT_EQ(d.description.find_first_of("{}", close + 1), std::string::npos) << what;
          for (int v : {0, 1})
            EXPECT_EQ(result_description(d, v).find_first_of("{}|"), std::string::npos) << what;
          EXPECT_NE(logic_error_of([&] { result_description(d); }), "") << what;
          EXPECT_GE(result_descriptions(d).size(), 2u) << what;
        }
      EXPECT_EQ(&result_dataset(d.group, d.name), &d);
    }
  EXPECT_EQ(stages, (std::set<std::string>{"flanks", "measured", "ste", "compliance", "stiffness",
                                           "dynamics", "train", "study"}));
  // shapes: words between " x ", "scalar" for one value, integers marked
  const ResultDataset &k = result_dataset("stiffness/<pair>", "mesh_stiffness");
  EXPECT_EQ(k.shape, "torques x positions");
  EXPECT_EQ(k.units, "N/m");
  EXPECT_EQ(result_rank(k), 2u);
  EXPECT_FALSE(result_integers(k));
  const ResultDataset &z = result_dataset("flanks/<involute pair>/<member>", "number_of_teeth");
  EXPECT_EQ(result_rank(z), 0u);
  EXPECT_TRUE(result_integers(z));
  EXPECT_EQ(result_rank(result_dataset("ste/<pair>", "contact_in_gear_frame")), 4u);
}

TEST(ResultsSchema, MissingDatasetIsAProgrammingError)
{
  const std::string message = logic_error_of([] { result_dataset("stiffness/<pair>", "K_m"); });
  EXPECT_NE(message.find("'K_m'"), std::string::npos) << message;
  EXPECT_NE(message.find("'stiffness/<pair>'"), std::string::npos) << message;
  EXPECT_NE(message.find("driver/results_schema.cc"), std::string::npos) << message;
}

class ResultsSchemaWrite : public test_data::TempDirectoryTest
{
};

TEST_F(ResultsSchemaWrite, AttributesFromTheSchemaAndMistakesRefused)
{
  const std::string path = (dir / "r.h5").string();
  {
    H5File        file  = H5File::create(path);
    const H5Group stage = file.root().group("stiffness");
    const H5Group pair  = stage.group("p1", "<pair>");
    EXPECT_EQ(file.root().schema_path(), "");
    EXPECT_EQ(stage.schema_path(), "stiffness");
    EXPECT_EQ(pair.schema_path(), "stiffness/<pair>");
    EXPECT_EQ(pair.group("error_estimate").schema_path(), "stiffness/<pair>/error_estimate");
    EXPECT_EQ(pair.path(), "/stiffness/p1/");
    pair.write("mesh_stiffness", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3});
    pair.write("mean_pairs_in_contact", 1.5);
    pair.write("pinion_tooth", std::vector<int>{0, -1}, {1, 2});

    // a dataset (or a group pattern) the schema lacks, a rank or type other than its entry's,
    // a choice not made or not there: logic errors naming the pattern and the dataset
    std::string m = logic_error_of([&] { pair.write("K_m", 1.0); });
    EXPECT_NE(m.find("'K_m'"), std::string::npos) << m;
    EXPECT_NE(m.find("'stiffness/<pair>'"), std::string::npos) << m;
    m = logic_error_of([&] { stage.group("p2").write("torque", std::vector<double>{1}, {1}); });
    EXPECT_NE(m.find("'stiffness/p2'"), std::string::npos) << m;
    m = logic_error_of([&] { pair.write("torque", 200.0); });
    EXPECT_NE(m.find("stiffness/<pair>/torque"), std::string::npos) << m;
    EXPECT_NE(m.find("'torques'"), std::string::npos) << m;
    EXPECT_NE(logic_error_of([&] { pair.write("lever", std::vector<int>{1}, {1, 1}); }), "");
    const H5Group member =
        file.root().group("compliance").group("p1", "<pair>").group("gear", "<member>");
    EXPECT_NE(logic_error_of([&] {
                member.write("compliance", std::vector<double>{1}, {1, 1});
              }),
              "");
    EXPECT_NE(logic_error_of([&] {
                member.write("compliance", std::vector<double>{1}, {1, 1}, 2);
              }),
              "");
    EXPECT_NE(logic_error_of([&] { pair.write("lever", std::vector<double>{1}, {1, 1}, 0); }), "");
    member.write("compliance", std::vector<double>{1e-9}, {1, 1}, 1);
    file.commit();
  }
  const H5File file = H5File::open(path);
  const auto   in   = [](const ResultDataset &d, const std::string &attribute) {
    return attribute == "units" ? d.units : result_description(d);
  };
  for (const auto &[dataset, entry] : std::map<std::string, const ResultDataset *>{
           {"/stiffness/p1/mesh_stiffness", &result_dataset("stiffness/<pair>", "mesh_stiffness")},
           {"/stiffness/p1/mean_pairs_in_contact",
            &result_dataset("stiffness/<pair>", "mean_pairs_in_contact")},
           {"/stiffness/p1/pinion_tooth", &result_dataset("stiffness/<pair>", "pinion_tooth")}})
    for (const char *attribute : {"units", "description"})
      EXPECT_EQ(dataset_attribute(file, dataset, attribute), in(*entry, attribute)) << dataset;
  EXPECT_EQ(dataset_attribute(file, "/stiffness/p1/mesh_stiffness", "description"),
            "K_m = F / (lambda (e_L - e_0))");
  EXPECT_EQ(dataset_attribute(file, "/compliance/p1/gear/compliance", "description"),
            "structural compliance S(i, j) (column-major: load j on the load points, response i "
            "on the grid), half-space part below the response depth removed");
  // nothing of the refused writes was left behind
  const H5Group pair = file.root().group("stiffness/p1");
  for (const char *name : {"K_m", "torque", "lever"})
    EXPECT_FALSE(pair.has(name)) << name;
}

class ResultsSchemaPrint : public test_data::GearkitRun
{
};

TEST_F(ResultsSchemaPrint, TableAndJson)
{
  ASSERT_EQ(run({"--print-results"}), 0) << err.str();
  const std::string  table = out.str();
  std::istringstream lines(table);
  std::string        line;
  std::getline(lines, line);
  test_data::expect_contains(line, {"group", "dataset", "shape", "units", "description"});
  std::size_t rows = 0;
  while (std::getline(lines, line))
    ++rows;
  EXPECT_EQ(rows, results_schema().size());
  test_data::expect_contains(
      table, {"stiffness/<pair>/error_estimate", "dynamics/<pair>/<excitation>/<sweep>",
              "train/<train>/meshes/<mesh>", "flanks/<involute pair>/<member>/<side>",
              "torques x positions", "K_m = F / (lambda (e_L - e_0))"});

  ASSERT_EQ(run({"--print-results", "json"}), 0) << err.str();
  const std::string json = out.str();
  EXPECT_EQ(json.rfind("[\n", 0), 0u) << json.substr(0, 100);
  EXPECT_EQ(json.substr(json.size() - 2), "]\n");
  test_data::expect_contains(
      json, {R"({"group": "stiffness/<pair>", "dataset": "mesh_stiffness", "shape": )"
             R"("torques x positions", "units": "N/m", "description": )"
             R"x("K_m = F / (lambda (e_L - e_0))"})x"});
  std::size_t objects = 0;
  for (std::size_t at = json.find("{\"group\""); at != std::string::npos;
       at             = json.find("{\"group\"", at + 1))
    ++objects;
  EXPECT_EQ(objects, results_schema().size());

  ASSERT_EQ(run({"--help"}), 0);
  EXPECT_NE(out.str().find("--print-results"), std::string::npos);
}

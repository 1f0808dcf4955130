#include "driver/scene.h"

#include "driver/scene_parameters.h"
#include "driver/scene_text.h"
#include "driver/stages.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>
#include <sstream>

namespace gearkit
{
namespace fs = std::filesystem;

// --- what the sections share -----------------------------------------------------------------

std::vector<std::string>
split_list(const std::string &text)
{
  std::vector<std::string> items;
  std::stringstream        s(text);
  std::string              item;
  while (std::getline(s, item, ','))
    {
      const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
      if (b != std::string::npos)
        items.push_back(item.substr(b, e - b + 1));
    }
  return items;
}

std::vector<double>
get_doubles(const ParameterHandler &prm, const std::string &entry, double factor)
{
  // strtod, not std::stod: the pattern has accepted the text, and a subnormal number such as
  // 1e-310 is a number (std::stod throws out_of_range for it, as strtod sets ERANGE).
  std::vector<double> values;
  for (const std::string &v : split_list(prm.get(entry)))
    values.push_back(std::strtod(v.c_str(), nullptr) * factor);
  return values;
}

std::vector<int>
get_integers(const ParameterHandler &prm, const std::string &entry)
{
  std::vector<int> values;
  for (const std::string &v : split_list(prm.get(entry)))
    {
      const long x = std::strtol(v.c_str(), nullptr, 10);
      if (x < std::numeric_limits<int>::min() || x > std::numeric_limits<int>::max())
        throw InputError(entry + " = " + v + " is not allowed; expected integers of at most " +
                         std::to_string(std::numeric_limits<int>::max()));
      values.push_back(int(x));
    }
  return values;
}

void
check_identifier(const std::string &name, const std::string &where)
{
  constexpr std::size_t longest = 64;
  const bool            allowed = std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (name.empty() || !allowed || name.size() > longest)
    throw InputError(where + ": '" + (name.size() > longest ? name.substr(0, 20) + "..." : name) +
                     "' (" + std::to_string(name.size()) +
                     " characters) is not allowed; use 1 to 64 letters, digits, _ and -");
}

namespace
{
const char *output_names = "flanks|measured|ste|stiffness|dynamics|train|study";

// The stage sections in the order of the data flow, each with one subsection per pair.
struct SectionDeclaration
{
  const char *name;
  void (*declare)(ParameterHandler &);
};
const SectionDeclaration pair_sections[] = {{"Flanks", PairScene::declare},
                                            {"Measured flanks", MeasuredScene::declare},
                                            {"TCA", TcaScene::declare},
                                            {"Finite elements", FeScene::declare},
                                            {"Loaded contact", LoadedScene::declare},
                                            {"Dynamics", DynamicsScene::declare},
                                            {"Study", StudyScene::declare}};

/// A train's name with the names of its bodies and meshes (they name its subsections).
struct TrainNames
{
  std::string              name;
  std::vector<std::string> bodies, meshes;
};

/// The names a scene's Notes section holds (`section`: the scene has one, possibly empty).
struct NotesNames
{
  bool                     section = false;
  std::vector<std::string> names;
};

void
declare_all(ParameterHandler &prm, const std::vector<std::string> &pairs,
            const std::vector<TrainNames> &trains = {}, const NotesNames &notes = {})
{
  in_subsection(prm, {"Scene"}, [&] { Scene::declare(prm); });
  for (const SectionDeclaration &s : pair_sections)
    for (const std::string &pair : pairs)
      in_subsection(prm, {s.name, pair}, [&] { s.declare(prm); });
  for (const TrainNames &t : trains)
    in_subsection(prm, {"Train", t.name}, [&] { TrainScene::declare(prm, t.bodies, t.meshes); });
  // Notes only where the scene has them (no empty Notes blocks in every scene's parameters),
  // for the names it opens there (each a pair or a train: checked before).
  if (notes.section)
    in_subsection(prm, {"Notes"}, [] {});
  for (const std::string &n : notes.names)
    in_subsection(prm, {"Notes", n}, [&] { NotesScene::declare(prm); });
}

/// Names of a list entry, each checked as an identifier, unique, at most `most`.
std::vector<std::string>
names_of(const std::string &text, const std::string &where, std::size_t most)
{
  const std::vector<std::string> names = split_list(text);
  for (const std::string &n : names)
    check_identifier(n, where + ": the name");
  if (names.size() > most)
    throw InputError(where + ": " + std::to_string(names.size()) +
                     " names is not allowed; at most " + std::to_string(most));
  if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
    throw InputError(where + ": a name appears twice; each needs its own name");
  return names;
}

// Top-level "subsection X ... end" blocks of a ShortPRM print, keyed by X.
std::map<std::string, std::string>
section_blocks(const std::string &prm_text)
{
  std::map<std::string, std::string> blocks;
  std::istringstream                 in(prm_text);
  std::string                        line, current, body;
  int                                depth = 0;
  while (std::getline(in, line))
    {
      const auto        b       = line.find_first_not_of(" \t");
      const std::string trimmed = b == std::string::npos ? "" : line.substr(b);
      if (trimmed.rfind("subsection ", 0) == 0)
        {
          if (depth++ == 0)
            {
              current = trimmed.substr(11);
              body.clear();
              continue;
            }
        }
      else if (trimmed == "end" && --depth == 0)
        {
          blocks[current] = body;
          continue;
        }
      if (depth > 0 && !trimmed.empty())
        body += trimmed + "\n";
    }
  return blocks;
}

// The pairs of `pairs` that have no Flanks/<pair> subsection in the scene: a pair named but not
// described would silently run with default gears. The scene's text knows the subsections it
// opens, in every format (.prm, JSON, XML with deal.II's mangled names).
std::vector<std::string>
undescribed_pairs(const SceneText &text, const std::vector<std::string> &pairs)
{
  std::vector<std::string> missing;
  for (const std::string &p : pairs)
    if (!text.has_subsection("Flanks/" + p))
      missing.push_back(p);
  return missing;
}
} // namespace

void
Scene::declare(ParameterHandler &prm)
{
  prm.declare_entry(
      "name", "", Patterns::Anything(),
      "Name of the scene; results go to <output root>/<name>/. Empty = the scene "
      "file name without extension (letters, digits, _ and -, at most 64 characters).");
  prm.declare_entry("outputs", "flanks", Patterns::MultipleSelection(output_names),
                    "What to compute; the driver runs only the stages these need.");
  prm.declare_entry("pairs", "pair", Patterns::List(Patterns::Anything(), 1),
                    "Names of the gear pairs in this scene; each has a subsection of that name "
                    "in every stage subsection (letters, digits, _ and -, at most 64 characters).");
  prm.declare_entry("trains", "", Patterns::List(Patterns::Anything(), 0),
                    "Names of the gear trains in this scene (output train), each with a "
                    "subsection Train/<name> whose meshes use pairs of this scene.");
}

namespace
{
/// Step 1 of read_scene: the pair names of Scene/pairs, each a valid name, at most 20, none
/// twice, each described under Flanks.
std::vector<std::string>
read_pair_names(const SceneText &text, ParameterHandler &header)
{
  std::vector<std::string> pairs;
  in_subsection(header, {"Scene"}, [&] { pairs = split_list(header.get("pairs")); });
  for (const std::string &p : pairs)
    check_identifier(p, "Scene/pairs: the pair name");
  // Each pair costs its members' construction and checks when the scene is read (tenths of a
  // second); a gearbox has a handful. Bounded, so no input makes the reader run for long.
  if (pairs.size() > 20)
    throw InputError("Scene/pairs: " + std::to_string(pairs.size()) +
                     " pairs is not allowed; at most 20 in one scene (split it)");
  if (std::set<std::string>(pairs.begin(), pairs.end()).size() != pairs.size())
    throw InputError("Scene/pairs: a pair name appears twice; each pair needs its own name");
  if (const auto missing = undescribed_pairs(text, pairs); !missing.empty())
    throw InputError("Scene/pairs: the pair '" + missing.front() + "' has no subsection Flanks/" +
                     missing.front() + "; describe every pair named in pairs (or remove the name)");
  return pairs;
}

/// Step 1b: the trains of Scene/trains and the names of their bodies and meshes (which name
/// subsections).
std::vector<TrainNames>
read_train_names(const SceneText &text, ParameterHandler &header)
{
  std::vector<TrainNames> trains;
  in_subsection(header, {"Scene"}, [&] {
    for (const std::string &t : names_of(header.get("trains"), "Scene/trains", 20))
      trains.push_back({t, {}, {}});
  });
  if (trains.empty())
    return trains;
  ParameterHandler names;
  in_subsection(names, {"Scene"}, [&] { Scene::declare(names); });
  for (const TrainNames &t : trains)
    in_subsection(names, {"Train", t.name}, [&] { TrainScene::declare(names, {}, {}); });
  text.parse(names, true);
  for (TrainNames &t : trains)
    in_subsection(names, {"Train", t.name}, [&] {
      t.bodies = names_of(names.get("bodies"), "Train/" + t.name + "/bodies", 50);
      t.meshes = names_of(names.get("meshes"), "Train/" + t.name + "/meshes", 50);
    });
  return trains;
}

/// Step 3: each section parses itself into `scene` (input files relative to `dir`).
void
parse_sections(ParameterHandler &prm, const std::string &file, const std::string &dir,
               const std::vector<std::string> &pairs, const std::vector<TrainNames> &trains,
               const std::vector<std::string> &train_names, const NotesNames &notes, Scene &scene)
{
  in_subsection(prm, {"Scene"}, [&] {
    scene.name    = prm.get("name");
    scene.outputs = split_list(prm.get("outputs"));
  });
  if (scene.name.empty())
    scene.name = fs::path(file).stem().string();
  check_identifier(scene.name, "Scene/name");
  if (scene.outputs.empty())
    throw InputError(std::string("Scene/outputs is empty; name what to compute, from: ") +
                     output_names);
  for (const std::string &p : pairs)
    {
      PairScene pair;
      pair.name = p;
      in_subsection(prm, {"Flanks", p}, [&] { pair.parse(prm); });
      in_subsection(prm, {"Measured flanks", p}, [&] { scene.measured[p].parse(prm, dir); });
      in_subsection(prm, {"TCA", p}, [&] { scene.tca[p].parse(prm); });
      in_subsection(prm, {"Finite elements", p}, [&] { scene.fe[p].parse(prm); });
      in_subsection(prm, {"Loaded contact", p}, [&] { scene.loaded[p].parse(prm); });
      in_subsection(prm, {"Dynamics", p}, [&] { scene.dynamics[p].parse(prm); });
      in_subsection(prm, {"Study", p}, [&] { scene.study[p].parse(prm); });
      scene.pairs.push_back(pair);
    }
  for (const TrainNames &t : trains)
    {
      TrainScene train;
      train.name = t.name;
      in_subsection(prm, {"Train", t.name}, [&] { train.parse(prm); });
      scene.trains.push_back(train);
    }
  // the pairs' notes in the order of Scene/pairs, then the trains' (a name may be both)
  std::vector<std::string> noted = pairs;
  noted.insert(noted.end(), train_names.begin(), train_names.end());
  for (std::size_t i = 0; i < noted.size(); ++i)
    if (std::count(noted.begin(), noted.begin() + std::ptrdiff_t(i), noted[i]) == 0 &&
        std::count(notes.names.begin(), notes.names.end(), noted[i]) > 0)
      in_subsection(prm, {"Notes", noted[i]}, [&] {
        for (SceneNote &n : NotesScene::parse(prm, noted[i]))
          scene.notes.push_back(std::move(n));
      });
}

/// The torques a K_m table is asked at (the dynamics' pinion torque, a train mesh's stiffness
/// torque) against those the loaded contact computes: K_m is the secant stiffness at one load, so
/// another torque's table is a different stiffness; a warning names both (the run takes the
/// nearest, nearest_torque).
void
check_stiffness_torques(Scene &scene, bool dynamics_runs, bool trains_run)
{
  const auto check = [&](const std::string &parameter, double wanted, const std::string &pair) {
    const std::vector<double> &torques = scene.loaded.at(pair).torques;
    if (wanted <= 0 || torques.empty())
      return;
    const double taken = torques[nearest_torque(torques, wanted)];
    if (std::abs(taken - wanted) > 1e-9 * wanted)
      {
        std::ostringstream w;
        w << parameter << " = " << wanted << " N m is not a torque of Loaded contact/" << pair
          << "/torques; K_m is the secant stiffness at one load, so the run takes the table at "
          << "the nearest, " << taken << " N m (" << std::showpos << (taken / wanted - 1) * 100
          << std::noshowpos << " %); add the torque there to run on its own K_m";
        scene.warnings.push_back(w.str());
      }
  };
  if (dynamics_runs)
    for (const auto &[pair, d] : scene.dynamics)
      if (d.fe_stiffness)
        check("Dynamics/" + pair + "/pinion torque", d.torque, pair);
  if (trains_run)
    for (const TrainScene &t : scene.trains)
      for (const TrainMeshScene &m : t.meshes)
        if (m.fe_stiffness)
          check("Train/" + t.name + "/Meshes/" + m.name + "/stiffness torque", m.stiffness_torque,
                m.pair);
}

/// Step 4: each section checks itself against the rest of the scene: everything the scene
/// alone can tell is refused here, before any stage runs. Implausible values a real design can
/// have go to scene.warnings; the dynamics' and the trains' plausibility (masses, speeds, cost)
/// only where they run. A section is judged against its pair only where its stage runs (the
/// stage graph, driver/stages.cc): its defaults suit no particular pair (the finite elements'
/// 7 segment teeth refused the unloaded TCA of a 6-tooth pinion).
void
check_sections(Scene &scene)
{
  const std::vector<std::string> stages = required_stages(scene);
  auto                           runs   = [&](const char *stage) {
    return std::find(stages.begin(), stages.end(), stage) != stages.end();
  };
  for (const PairScene &pair : scene.pairs)
    {
      const std::string &p = pair.name;
      pair.check(scene.warnings);
      scene.measured.at(p).check(pair);
      scene.tca.at(p).complete_and_check(pair, scene.measured.at(p), scene.warnings);
      scene.fe.at(p).check(pair, runs("compliance"), scene.warnings);
      scene.loaded.at(p).check(pair, scene.measured.at(p), runs("stiffness"), scene.warnings);
      scene.dynamics.at(p).check(pair, scene.tca.at(p), runs("dynamics"), scene.warnings);
      scene.study.at(p).check(pair, scene.loaded.at(p), runs("study"), scene.warnings);
    }
  const bool train_wanted =
      std::find(scene.outputs.begin(), scene.outputs.end(), "train") != scene.outputs.end();
  if (train_wanted && scene.trains.empty())
    throw InputError("Scene/trains is empty with outputs = train; name the trains to run "
                     "(each with a subsection Train/<name>)");
  for (const TrainScene &t : scene.trains)
    t.check(scene, train_wanted, scene.warnings);
  check_stiffness_torques(scene, runs("dynamics"), train_wanted);
}
} // namespace

std::size_t
nearest_torque(const std::vector<double> &torques, double wanted)
{
  std::size_t best = 0;
  for (std::size_t t = 1; t < torques.size(); ++t)
    if (wanted > 0 ? std::abs(torques[t] - wanted) < std::abs(torques[best] - wanted)
                   : torques[t] > torques[best])
      best = t;
  return best;
}

Scene
read_scene(const std::string &file, const std::string &base_directory)
{
  if (!fs::is_regular_file(file))
    throw InputError("scene file " + file + " does not exist or is not a file");
  Scene scene;
  scene.file = file;
  try
    {
      // 0. The file's text, read once and normalised (line breaks, byte-order mark, keyword
      //    case, includes), its structure checked (a parameter set twice); every step below
      //    reads this text.
      const SceneText text(file);

      // 1. The scene header alone, to learn the pair and train names the other sections use,
      //    and the names under Notes (optional: each a pair or a train of the scene).
      ParameterHandler header;
      in_subsection(header, {"Scene"}, [&] { Scene::declare(header); });
      text.parse(header, true);
      const std::vector<std::string> pairs  = read_pair_names(text, header);
      const std::vector<TrainNames>  trains = read_train_names(text, header);
      const NotesNames         notes{text.has_subsection("Notes"), text.subsections_in("Notes")};
      std::vector<std::string> train_names;
      for (const TrainNames &t : trains)
        train_names.push_back(t.name);
      NotesScene::check_names(notes.names, pairs, train_names);

      // 2. Everything, strictly: unknown entries and values outside their patterns are errors.
      ParameterHandler prm;
      declare_all(prm, pairs, trains, notes);
      text.parse(prm);

      // 3. Each section parses itself; 4. and checks itself against the rest of the scene.
      const std::string dir =
          base_directory.empty() ? fs::path(file).parent_path().string() : base_directory;
      parse_sections(prm, file, dir, pairs, trains, train_names, notes, scene);
      check_sections(scene);

      // 5. The parameters as text, one block per section: the cache keys hash these.
      std::ostringstream printed;
      prm.print_parameters(printed, ParameterHandler::ShortPRM);
      scene.sections = section_blocks(printed.str());
    }
  catch (const dealii::ExceptionBase &e)
    {
      throw InputError("scene " + file + ": " + deal_ii_message(e));
    }
  catch (const boost::property_tree::ptree_error &e)
    {
      throw InputError("scene " + file + ": " + e.what());
    }
  catch (const InputError &e)
    {
      const std::string what = e.what();
      throw InputError(what.rfind(file, 0) == 0 ? what : "scene " + file + ": " + what);
    }
  return scene;
}

void
print_parameters(std::ostream &out, const std::vector<std::string> &pairs)
{
  // deal.II's PRM listing omits the allowed values and its Description listing the defaults;
  // this one has both and is itself a valid scene file.
  ParameterHandler prm;
  declare_all(prm, pairs, {{"train", {"input", "output"}, {"stage"}}}, {true, pairs});
  std::stringstream json;
  prm.print_parameters(json, ParameterHandler::JSON);
  boost::property_tree::ptree tree;
  boost::property_tree::read_json(json, tree);

  std::function<void(std::ostream &, const boost::property_tree::ptree &, int)> print =
      [&](std::ostream &to, const boost::property_tree::ptree &node, int depth) {
        const std::string indent(2 * depth, ' ');
        for (const auto &[name, child] : node) // entries first, then subsections
          if (child.count("value"))
            to << indent << "# " << child.get<std::string>("documentation") << "\n"
               << indent << "# allowed: " << child.get<std::string>("pattern_description") << "\n"
               << indent << "set " << name << " = " << child.get<std::string>("default_value")
               << "\n\n";
        for (const auto &[name, child] : node)
          if (!child.count("value"))
            {
              to << indent << "subsection " << name << "\n";
              print(to, child, depth + 1);
              to << indent << "end\n\n";
            }
      };
  out << "# gearkit scene parameters: every entry with its help text, allowed values and default.\n"
      << "# Pair subsections repeat for every name in Scene/pairs (here: the example pair "
         "names).\n\n";
  boost::property_tree::ptree scene_first;
  scene_first.add_child("Scene", tree.get_child("Scene"));
  for (const auto &[name, child] : tree)
    if (name != "Scene" && name != "Train" && name != "Notes")
      scene_first.add_child(name, child);
  print(out, scene_first, 0);
  // The notes after the stages' sections: optional, for the pairs and the trains alike.
  boost::property_tree::ptree notes;
  notes.add_child("Notes", tree.get_child("Notes"));
  out << "# Notes/<name> (optional): caveats the report shows next to the numbers they qualify,\n"
      << "# one line of text per report area, for a pair of Scene/pairs or a train of "
         "Scene/trains\n"
      << "# (another name is refused). No stage reads them: changing a note recomputes nothing.\n"
      << "# results.h5 carries them as its root attribute notes, one line per note:\n"
      << "# <name> TAB <area> TAB <text>.\n";
  print(out, notes, 0);
  // A train's section exists only for the trains Scene/trains names: commented out here (an
  // example train "train" with bodies input, output and mesh stage), so that the listing stays
  // a valid scene.
  boost::property_tree::ptree train;
  train.add_child("Train", tree.get_child("Train"));
  std::stringstream train_text;
  print(train_text, train, 0);
  out << "# Train/<train> (name it in Scene/trains, its bodies in bodies, its meshes in meshes;\n"
      << "# here an example train with bodies input, output and mesh stage):\n";
  for (std::string line; std::getline(train_text, line);)
    out << (line.empty() ? "#" : "# " + line) << "\n";
}
} // namespace gearkit

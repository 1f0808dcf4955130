// Section Notes/<name>: caveats carried with the numbers. A pair (a name of Scene/pairs) or a
// train (Scene/trains) may attach a line of text to each report area; the report shows it next
// to the numbers it qualifies, results.h5 carries it (root attribute `notes`). No stage reads
// the section, so no cache key hashes it: changing a note recomputes nothing.
#include "base/types.h"
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <algorithm>

namespace gearkit
{
const std::vector<std::string> &
note_areas()
{
  static const std::vector<std::string> areas = {"gear data", "unloaded TCA", "loaded contact",
                                                 "dynamics", "gear train"};
  return areas;
}

void
NotesScene::declare(ParameterHandler &prm)
{
  const char *what[] = {
      "the gear data (geometry, contact ratios, masses; stage flanks)",
      "the unloaded tooth contact analysis (e_0, harmonics, contact pattern; stage ste)",
      "the loaded contact (e_L, K_m against ISO 6336, load sharing; stages compliance and "
      "stiffness)",
      "the pair dynamics (modes, DTE, load factors; stage dynamics)",
      "the gear train (impacts, forces, spectra; stage train)"};
  for (std::size_t i = 0; i < note_areas().size(); ++i)
    prm.declare_entry(
        note_areas()[i], "", Patterns::Anything(),
        std::string("A caveat the report shows next to ") + what[i] +
            " of this pair or train: one line of free text (a # starts a comment; "
            "end a line with \\ to continue it on the next line). Empty: none. Changing it "
            "recomputes nothing.");
}

std::vector<SceneNote>
NotesScene::parse(ParameterHandler &prm, const std::string &name)
{
  std::vector<SceneNote> notes;
  for (const std::string &area : note_areas())
    {
      // One line, whatever the format: tabs and line breaks (possible in JSON and XML) read as
      // spaces, so that the attribute's lines and tabs stay its separators.
      std::string text = prm.get(area);
      std::replace_if(
          text.begin(), text.end(),
          [](char c) { return c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; },
          ' ');
      const auto b = text.find_first_not_of(' '), e = text.find_last_not_of(' ');
      if (b != std::string::npos)
        notes.push_back({name, area, text.substr(b, e - b + 1)});
    }
  return notes;
}

void
NotesScene::check_names(const std::vector<std::string> &names,
                        const std::vector<std::string> &pairs,
                        const std::vector<std::string> &trains)
{
  const auto listed = [](const std::vector<std::string> &list) {
    std::string s;
    for (const std::string &n : list)
      s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? std::string("none") : s;
  };
  for (const std::string &n : names)
    if (std::find(pairs.begin(), pairs.end(), n) == pairs.end() &&
        std::find(trains.begin(), trains.end(), n) == trains.end())
      throw InputError("Notes/" + n + ": '" + n +
                       "' names no pair or train of this scene; a subsection of Notes takes the "
                       "name of a pair (Scene/pairs: " +
                       listed(pairs) + ") or of a train (Scene/trains: " + listed(trains) + ")");
}

std::string
notes_text(const std::vector<SceneNote> &notes)
{
  std::string text;
  for (const SceneNote &n : notes)
    text += n.name + '\t' + n.area + '\t' + n.text + '\n';
  return text;
}
} // namespace gearkit

// The text of a scene file as gearkit reads it: read once, normalised, handed to deal.II's
// ParameterHandler and to gearkit's own checks of the scene's structure, so that both see the
// same thing.
//
// deal.II reads a .prm file line by line and tolerates some variants of the syntax that a naive
// scan of the same file does not (a CR before each line break, SUBSECTION/SET/END in upper
// case, tabs); it does not tolerate others (a UTF-8 byte-order mark, keywords in mixed case), and
// it follows `include` without a limit. Here every variant is either normalised away, line by
// line (the line numbers stay), or refused with a message naming the file and the line:
//   * a UTF-8 byte-order mark is dropped, a UTF-16 one refused; NUL bytes are refused;
//   * the CR of a CRLF line break is dropped, a CR inside a line (old Mac line breaks) refused;
//   * tabs become spaces (deal.II reads them so);
//   * the keywords subsection, set, end and include are read in any letter case;
//   * `include <file>` is expanded here (the file relative to the including file's folder), at
//     most max_include_depth deep, cycles and missing files refused with the chain of files and
//     lines; an included file must close the subsections it opens (deal.II's rule);
//   * a parameter set twice in the same subsection (also when the subsection is opened twice,
//     or in an included file) is refused naming the parameter and both places.
// JSON and XML scenes (deal.II reads those too) pass the same checks where they apply: the
// duplicate parameters, and the subsections they open; names must be mangled as deal.II reads
// them (any character but a letter or digit as _ and two hex digits: a space as _20).
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
class ParameterHandler;
class ExceptionBase;
} // namespace dealii

namespace gearkit
{
class SceneText
{
public:
  enum class Format
  {
    prm,
    json,
    xml
  };

  /// Includes nested deeper than this are refused (a scene and its includes are a handful of
  /// files; a deeper chain is a mistake, and each level costs stack in the reader).
  static constexpr int max_include_depth = 8;
  /// At most this many include statements in the scene and its includes together (a file
  /// including another twice, at every level, would otherwise grow as 2^depth).
  static constexpr int max_includes = 100;
  /// JSON objects or XML elements nested at most this deep (a scene's sections nest a few
  /// levels; the parsers recurse once per level).
  static constexpr int max_nesting = 64;
  /// The scene's files together hold at most this many bytes.
  static constexpr std::size_t max_bytes = 16 << 20;

  /// Reads the scene file (and the files it includes) and checks its structure. Throws
  /// InputError naming the file and the line.
  explicit SceneText(const std::string &file);

  Format
  format() const
  {
    return format_;
  }

  /// The normalised text: a .prm file with its includes expanded in place (deal.II reads it
  /// without including anything), a JSON or XML file without its byte-order mark.
  const std::string &
  text() const
  {
    return text_;
  }

  /// Where line `line` (from 1) of text() comes from: "file:line", and for an included file the
  /// include statement that brought it in ("inc.prm:3 (included at scene.prm:7)").
  std::string
  where(unsigned int line) const;

  /// Parses the text into prm (deal.II's parse_input for the format, skip_undefined as there).
  /// A deal.II error becomes an InputError whose "Line <n> of file <f>" names the file and line
  /// the text came from.
  void
  parse(dealii::ParameterHandler &prm, bool skip_undefined = false) const;

  /// Whether the scene opens the subsection with this path ("Flanks/p1", names as deal.II reads
  /// them: demangled in JSON and XML).
  bool
  has_subsection(const std::string &path) const
  {
    return subsections_.count(path) > 0;
  }

  /// The names of the subsections the scene opens directly inside the subsection `path`
  /// ("Notes": the names under Notes), in name order (a name with a / in it by its part before
  /// the /).
  std::vector<std::string>
  subsections_in(const std::string &path) const;

private:
  struct Source
  {
    std::string name;              ///< the file as given, or resolved against its includer
    int         includer     = -1; ///< index of the including file (-1: the scene file)
    int         include_line = 0;  ///< line of the include statement in the includer
  };
  struct Reader; // the .prm reader (scene_text.cc)

  void
  read_tree();
  /// " (included at a.prm:2, included at scene.prm:3)" for an included file, else "".
  std::string
  included_at(int file) const;
  /// "file:line" and where the file was included.
  std::string
  location(int file, int line) const;
  std::string
  rewrite_locations(const std::string &message) const;

  Format                           format_ = Format::prm;
  std::string                      text_;
  std::vector<Source>              files_;
  std::vector<std::pair<int, int>> origin_; ///< per line of text_: file, line
  std::set<std::string>            subsections_;
};

/// The "Additional information" of a deal.II exception (it names the file, the line and the
/// pattern), on one line, without the stack trace.
std::string
deal_ii_message(const dealii::ExceptionBase &e);
} // namespace gearkit

#include "driver/scene_text.h"

#include "base/types.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

namespace gearkit
{
namespace fs = std::filesystem;
namespace pt = boost::property_tree;

namespace
{
// deal.II's Utilities::trim: every isspace character at either end (CR, form feed, ...).
std::string
trim(const std::string &s)
{
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b])))
    ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1])))
    --e;
  return s.substr(b, e - b);
}

std::string
to_lower(std::string s)
{
  for (char &c : s)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string
join(const std::vector<std::string> &path, const std::string &last = "")
{
  std::string s;
  for (const std::string &p : path)
    s += (s.empty() ? "" : "/") + p;
  if (!last.empty())
    s += (s.empty() ? "" : "/") + last;
  return s;
}

/// The bytes of a file, at most `budget` of them (the budget shrinks by what was read).
std::string
read_bytes(const std::string &name, std::size_t &budget)
{
  std::ifstream in(name, std::ios::binary);
  if (!in)
    throw InputError(name + ": cannot be opened (is it readable?)");
  std::string bytes;
  char        buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    {
      if (bytes.size() + std::size_t(in.gcount()) > budget)
        throw InputError(name + ": the scene and its included files hold more than " +
                         std::to_string(SceneText::max_bytes >> 20) +
                         " MB; a scene file is a short text (is this the right file?)");
      bytes.append(buffer, std::size_t(in.gcount()));
    }
  if (in.bad())
    throw InputError(name + ": cannot be read");
  budget -= bytes.size();
  return bytes;
}

/// Drops a UTF-8 byte-order mark; refuses what is not 8-bit text (deal.II would read a UTF-8
/// mark as part of the first line, and UTF-16 as garbage).
void
check_encoding(std::string &bytes, const std::string &name)
{
  if (bytes.rfind("\xEF\xBB\xBF", 0) == 0)
    bytes.erase(0, 3);
  else if (bytes.rfind("\xFF\xFE", 0) == 0 || bytes.rfind("\xFE\xFF", 0) == 0)
    throw InputError(name + ": the file is UTF-16 encoded (it starts with a UTF-16 byte-order "
                            "mark); save it as UTF-8 or plain ASCII");
  if (const auto nul = bytes.find('\0'); nul != std::string::npos)
    throw InputError(
        name + ":" + std::to_string(std::count(bytes.begin(), bytes.begin() + nul, '\n') + 1) +
        ": a NUL byte; a scene is a text file (UTF-8 or ASCII), not a binary or UTF-16/32 file");
}

/// The lines of a .prm file, each without the CR of a CRLF line break and with tabs as spaces
/// (deal.II reads a tab as a space); a CR inside a line is refused.
std::vector<std::string>
split_lines(const std::string &bytes, const std::string &name)
{
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < bytes.size();)
    {
      const std::size_t end  = bytes.find('\n', start);
      std::string       line = bytes.substr(start, end == std::string::npos ? end : end - start);
      if (!line.empty() && line.back() == '\r')
        line.pop_back();
      if (line.find('\r') != std::string::npos)
        throw InputError(name + ":" + std::to_string(lines.size() + 1) +
                         ": a carriage return (CR) inside the line - old Mac line breaks? Save "
                         "the file with LF or CRLF line breaks");
      std::replace(line.begin(), line.end(), '\t', ' ');
      lines.push_back(line);
      if (end == std::string::npos)
        break;
      start = end + 1;
    }
  return lines;
}

/// Refuses the invisible characters a word processor or a joined file leaves in a statement,
/// where deal.II would read them as part of a keyword, name or value that then looks right in
/// its message but is not (comments may hold anything).
void
check_invisible(const std::string &statement, const std::string &where)
{
  static const std::pair<const char *, const char *> invisible[] = {
      {"\xC2\xA0", "a no-break space (U+00A0)"},
      {"\xE2\x80\x8B", "a zero-width space (U+200B)"},
      {"\xEF\xBB\xBF", "a byte-order mark (U+FEFF; files joined?)"}};
  for (const auto &[bytes, what] : invisible)
    if (const auto p = statement.find(bytes); p != std::string::npos)
      throw InputError(where + ": " + what + " after '" +
                       statement.substr(0, std::min<std::size_t>(p, 60)) +
                       "'; write plain spaces (or nothing) there");
}

bool
is_hex(char c)
{
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
}

// deal.II's name mangling in JSON and XML files: every character but a letter or a digit as _
// and two lower-case hex digits. deal.II demangles every name it reads (without checking it in
// a release build), so a name with a bare _ is refused here.
std::string
mangle(const std::string &s)
{
  static const char hex[] = "0123456789abcdef";
  std::string       m;
  for (const char c : s)
    if (std::isalnum(static_cast<unsigned char>(c)) && static_cast<unsigned char>(c) < 128)
      m += c;
    else
      m += {'_', hex[static_cast<unsigned char>(c) / 16], hex[static_cast<unsigned char>(c) % 16]};
  return m;
}

std::string
demangle(const std::string &s, const std::string &where)
{
  std::string d;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] != '_')
      d += s[i];
    else if (i + 2 < s.size() && is_hex(s[i + 1]) && is_hex(s[i + 2]))
      {
        d += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
        i += 2;
      }
    else
      throw InputError(where + ": the name '" + s +
                       "' is not one deal.II can read: in JSON and XML scenes every character "
                       "but a letter or a digit is written as _ and two hex digits (a space as "
                       "_20, _ as _5f, - as _2d), here '" +
                       mangle(s) + "'");
  return d;
}
/// The deepest nesting of JSON objects and arrays, or of XML elements (a scan that skips
/// strings, comments and declarations; an attribute value holding '>' may miscount, which a
/// bound needs no better). boost's parsers and deal.II's reader recurse once per level.
int
nesting_depth(const std::string &text, const bool json)
{
  int depth = 0, deepest = 0;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (json)
      {
        if (text[i] == '"')
          for (++i; i < text.size() && text[i] != '"'; ++i)
            i += text[i] == '\\';
        else if (text[i] == '{' || text[i] == '[')
          deepest = std::max(deepest, ++depth);
        else if (text[i] == '}' || text[i] == ']')
          --depth;
      }
    else if (text[i] == '<')
      {
        const auto skip_to = [&](const char *end) {
          const std::size_t e = text.find(end, i);
          i                   = e == std::string::npos ? text.size() : e + std::strlen(end) - 1;
        };
        if (text.compare(i, 4, "<!--") == 0)
          skip_to("-->");
        else if (text.compare(i, 9, "<![CDATA[") == 0)
          skip_to("]]>");
        else if (text.compare(i, 2, "<?") == 0)
          skip_to("?>");
        else if (text.compare(i, 2, "</") == 0 || text.compare(i, 2, "<!") == 0)
          {
            depth -= text[i + 1] == '/';
            skip_to(">");
          }
        else
          {
            skip_to(">");
            if (i < text.size() && text[i - 1] != '/')
              deepest = std::max(deepest, ++depth);
          }
      }
  return deepest;
}
} // namespace

std::string
deal_ii_message(const dealii::ExceptionBase &e)
{
  std::string       text = e.what();
  const std::string key  = "Additional information:";
  if (const auto p = text.find(key); p != std::string::npos)
    text = text.substr(p + key.size());
  if (const auto p = text.find("Stacktrace:"); p != std::string::npos)
    text = text.substr(0, p);
  std::string out;
  for (char c : text) // collapse whitespace and line breaks
    if (!std::isspace(static_cast<unsigned char>(c)) || (!out.empty() && out.back() != ' '))
      out += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
  while (!out.empty() && (out.back() == ' ' || out.back() == '-'))
    out.pop_back();
  return out;
}

// The .prm reader: one file's lines, statement by statement as deal.II's parse_input joins and
// classifies them, with the subsections open, the parameters set so far and the includes being
// read.
struct SceneText::Reader
{
  explicit Reader(SceneText &text)
      : t(text)
  {
  }

  SceneText  &t;
  std::size_t budget   = max_bytes;
  int         includes = 0;
  /// The subsections open, each with the file and line that opened it.
  std::vector<std::string>         open;
  std::vector<std::pair<int, int>> opened_at;
  /// Each parameter set, by its path, with the file and line.
  std::map<std::string, std::pair<int, int>> set_at;
  /// The include statements being followed ("scene.prm:3 includes a.prm") and their files.
  std::vector<std::string> chain;
  std::vector<fs::path>    chain_files;

  std::string
  at(int file, int line) const
  {
    return t.location(file, line);
  }

  void
  emit(const std::string &line, int file, int number)
  {
    t.text_ += line + "\n";
    t.origin_.push_back({file, number});
  }

  void
  read(int file, int depth);
  bool
  statement(int file, int line, const std::string &content, const std::string &as_written,
            std::size_t base_depth, int depth);
  void
  include(int file, int line, const std::string &target, int depth);
};

void
SceneText::Reader::read(const int file, const int depth)
{
  const std::string name  = t.files_[file].name;
  std::string       bytes = read_bytes(name, budget);
  check_encoding(bytes, name);
  std::vector<std::string> lines      = split_lines(bytes, name);
  const std::size_t        base_depth = open.size();
  for (std::size_t i = 0; i < lines.size();)
    {
      // One statement: a line ending in a backslash continues on the next (deal.II reports the
      // statement at its first line).
      const std::size_t first = i;
      std::string       joined;
      for (bool continued = true; i < lines.size() && continued; ++i)
        {
          std::string part = trim(lines[i]);
          continued        = !part.empty() && part.back() == '\\';
          if (continued)
            part.pop_back();
          joined += part;
        }
      const int         line       = int(first) + 1;
      const std::string as_written = trim(joined.substr(0, joined.find('#')));
      check_invisible(as_written, at(file, line));
      std::string content = as_written;

      // Keywords in any letter case, written in lower case (deal.II reads lower and upper case).
      const std::string word  = content.substr(0, content.find(' '));
      const std::string lower = to_lower(word);
      if (word != lower &&
          (lower == "subsection" || lower == "set" || lower == "end" || lower == "include"))
        {
          std::string &l = lines[first];
          const auto   b =
              std::find_if_not(l.begin(), l.end(),
                               [](char c) { return std::isspace(static_cast<unsigned char>(c)); }) -
              l.begin();
          if (l.compare(std::size_t(b), word.size(), word) == 0)
            {
              l.replace(std::size_t(b), word.size(), lower);
              content.replace(0, word.size(), lower);
            }
        }

      if (statement(file, line, content, as_written, base_depth, depth))
        {
          // ends a continued last line of the included file, as deal.II's reading of the file
          // on its own would
          emit("", file, line);
          continue;
        }
      for (std::size_t k = first; k < i; ++k)
        emit(lines[k], file, int(k) + 1);
    }
  if (open.size() > base_depth)
    throw InputError(at(opened_at[base_depth].first, opened_at[base_depth].second) +
                     ": the subsection " + join({open.begin(), open.begin() + base_depth + 1}) +
                     " has no 'end' in " + name +
                     (file == 0 ? "" : " (an included file closes the subsections it opens)"));
}

// A statement as deal.II's scan_line classifies it. What deal.II would refuse is refused here,
// at its line, so that the first mistake in the file is the one reported (deal.II only reads
// the text after this reader). True for an include (its file already read).
bool
SceneText::Reader::statement(const int file, const int line, const std::string &content,
                             const std::string &as_written, const std::size_t base_depth,
                             const int depth)
{
  const auto starts = [&](const char *a, const char *b) {
    return content.rfind(a, 0) == 0 || content.rfind(b, 0) == 0;
  };
  const std::string quoted =
      "'" + (as_written.size() > 80 ? as_written.substr(0, 80) + "..." : as_written) + "'";
  if (content.empty())
    return false;
  if (starts("subsection ", "SUBSECTION "))
    {
      open.push_back(trim(content.substr(11)));
      opened_at.push_back({file, line});
      t.subsections_.insert(join(open));
    }
  else if (starts("end", "END"))
    {
      if (!trim(content.substr(3)).empty())
        throw InputError(at(file, line) + ": " + quoted + ": 'end' stands alone on its line");
      if (open.size() > base_depth)
        {
          open.pop_back();
          opened_at.pop_back();
        }
      else if (open.empty())
        throw InputError(at(file, line) +
                         ": this 'end' closes no subsection (one 'end' too many?)");
      else
        throw InputError(at(file, line) + ": this 'end' closes the subsection " + join(open) +
                         ", which the included file did not open; an included file closes the "
                         "subsections it opens, and only those");
    }
  else if (starts("set ", "SET "))
    {
      const std::size_t equals = content.find('=');
      if (equals == std::string::npos)
        throw InputError(at(file, line) + ": " + quoted + ": 'set' needs 'set <name> = <value>'");
      const std::string entry    = trim(content.substr(4, equals - 4));
      const std::string key      = open.empty() ? entry : join(open) + "/" + entry;
      const auto [p, first_time] = set_at.emplace(key, std::pair{file, line});
      if (!first_time)
        throw InputError(key + " is set twice, at " + at(p->second.first, p->second.second) +
                         " and at " + at(file, line) +
                         " (deal.II would keep the second value without a word); set it once");
    }
  else if (content == "include" || content == "INCLUDE")
    throw InputError(at(file, line) + ": 'include' names no file");
  else if (starts("include ", "INCLUDE "))
    {
      include(file, line, trim(content.substr(8)), depth);
      return true;
    }
  else
    throw InputError(at(file, line) + ": " + quoted +
                     " is not a statement: a line is empty, a # comment, or starts with "
                     "subsection <name>, set <name> = <value>, end or include <file>");
  return false;
}

void
SceneText::Reader::include(const int file, const int line, const std::string &target,
                           const int depth)
{
  if (target.empty())
    throw InputError(at(file, line) + ": 'include' names no file");
  if (++includes > max_includes)
    throw InputError(at(file, line) + ": more than " + std::to_string(max_includes) +
                     " include statements in the scene and its included files");
  fs::path path(target);
  if (path.is_relative())
    path = fs::path(t.files_[file].name).parent_path() / path;
  const std::string name = path.lexically_normal().string();
  std::error_code   error;
  if (!fs::is_regular_file(path, error))
    throw InputError(at(file, line) + ": the included file " + name +
                     " does not exist or is not a file (include names a file relative to the "
                     "folder of the file that includes it)");
  const fs::path    canonical = fs::weakly_canonical(path, error);
  const std::string step = t.files_[file].name + ":" + std::to_string(line) + " includes " + name;
  std::string       chain_text;
  for (const std::string &s : chain)
    chain_text += s + ", ";
  chain_text += step;
  if (std::find(chain_files.begin(), chain_files.end(), canonical) != chain_files.end())
    throw InputError("include cycle: " + chain_text +
                     "; a file cannot include itself, directly or through other files");
  if (depth + 1 > max_include_depth)
    throw InputError("includes nested more than " + std::to_string(max_include_depth) +
                     " deep: " + chain_text);
  t.files_.push_back({name, file, line});
  chain.push_back(step);
  chain_files.push_back(canonical);
  read(int(t.files_.size()) - 1, depth + 1);
  chain.pop_back();
  chain_files.pop_back();
}

SceneText::SceneText(const std::string &file)
{
  files_.push_back({file, -1, 0});
  const std::string extension = to_lower(fs::path(file).extension().string());
  if (extension == ".json")
    format_ = Format::json;
  else if (extension == ".xml")
    format_ = Format::xml;
  else if (extension != ".prm")
    throw InputError(file + ": the file name ends in '" + extension +
                     "'; a scene is a deal.II parameter file: .prm (or .json, .xml)");
  if (format_ == Format::prm)
    {
      Reader          reader(*this);
      std::error_code error;
      reader.chain_files.push_back(fs::weakly_canonical(file, error));
      reader.read(0, 0);
    }
  else
    {
      std::size_t budget = max_bytes;
      text_              = read_bytes(file, budget);
      check_encoding(text_, file);
      read_tree();
    }
}

// JSON and XML: the tree as deal.II reads it (ParameterHandler::parse_input_from_json/xml): a
// node without children, or with a child "value", is a parameter; one with a child "alias" an
// alias; any other a subsection.
void
SceneText::read_tree()
{
  const std::string &file = files_[0].name;
  if (const int depth = nesting_depth(text_, format_ == Format::json); depth > max_nesting)
    throw InputError(file + ": " + (format_ == Format::json ? "objects and arrays" : "elements") +
                     " nested " + std::to_string(depth) + " deep; a scene nests at most " +
                     std::to_string(max_nesting) + " (its sections are a few levels deep)");
  pt::ptree tree;
  try
    {
      std::istringstream in(text_);
      if (format_ == Format::json)
        pt::read_json(in, tree);
      else
        pt::read_xml(in, tree, pt::xml_parser::no_comments);
    }
  catch (const pt::file_parser_error &e)
    {
      throw InputError(file + ":" + std::to_string(e.line()) + ": " + e.message());
    }
  // deal.II reads an XML comment as a parameter "<xmlcomment>": the file without them.
  if (format_ == Format::xml && text_.find("<!--") != std::string::npos)
    {
      std::ostringstream out;
      pt::write_xml(out, tree);
      text_ = out.str();
    }
  const pt::ptree *root = &tree;
  if (format_ == Format::xml)
    {
      const auto top = tree.get_child_optional("ParameterHandler");
      if (!top)
        return; // deal.II says what is missing
      root = &*top;
    }

  std::set<std::string>                                                    parameters;
  std::function<void(const pt::ptree &, const std::vector<std::string> &)> walk =
      [&](const pt::ptree &node, const std::vector<std::string> &path) {
        for (const auto &[key, child] : node)
          {
            const std::string in = path.empty() ? file : file + ", in " + join(path);
            if (format_ == Format::xml && key == "<xmlattr>" && !child.empty())
              throw InputError(in + ": an XML attribute (" + child.begin()->first + "=\"" +
                               child.begin()->second.data() +
                               "\"); deal.II reads a parameter as an element only");
            if (key.empty())
              throw InputError(in + ": a JSON array; give a list as one string of "
                                    "comma-separated values (\"pairs\": \"p, q\")");
            const std::string name = demangle(key, in);
            if (child.empty() || child.count("value") > 0)
              {
                if (!parameters.insert(join(path, name)).second || child.count("value") > 1)
                  throw InputError(file + ": " + join(path, name) +
                                   " is given twice (deal.II would keep the second value "
                                   "without a word); give it once");
              }
            else if (child.count("alias") == 0)
              {
                std::vector<std::string> inner = path;
                inner.push_back(name);
                subsections_.insert(join(inner));
                walk(child, inner);
              }
          }
      };
  walk(*root, {});
}

std::string
SceneText::included_at(const int file) const
{
  std::string s;
  for (int f = file; files_[f].includer >= 0; f = files_[f].includer)
    s += std::string(f == file ? " (" : ", ") + "included at " + files_[files_[f].includer].name +
         ":" + std::to_string(files_[f].include_line);
  return s.empty() ? s : s + ")";
}

std::string
SceneText::location(const int file, const int line) const
{
  return files_[file].name + ":" + std::to_string(line) + included_at(file);
}

std::string
SceneText::where(const unsigned int line) const
{
  if (line == 0 || line > origin_.size())
    return files_[0].name + ":" + std::to_string(line);
  return location(origin_[line - 1].first, origin_[line - 1].second);
}

// deal.II names the line of the text it was given: "Line <n> of file <scene>"; the line of the
// file that text came from replaces it.
std::string
SceneText::rewrite_locations(const std::string &message) const
{
  if (format_ != Format::prm)
    return message;
  const std::string prefix = "Line <", middle = "> of file <" + files_[0].name;
  std::string       out;
  std::size_t       p = 0;
  for (std::size_t q; (q = message.find(prefix, p)) != std::string::npos;)
    {
      std::size_t e = q + prefix.size();
      while (e < message.size() && std::isdigit(static_cast<unsigned char>(message[e])))
        ++e;
      out += message.substr(p, q - p);
      if (e == q + prefix.size() || e - q > 16 || message.compare(e, middle.size(), middle) != 0)
        {
          out += prefix;
          p = q + prefix.size();
          continue;
        }
      const unsigned long line =
          std::stoul(message.substr(q + prefix.size(), e - q - prefix.size()));
      if (line == 0 || line > origin_.size())
        out += message.substr(q, e + middle.size() - q);
      else
        {
          const auto [file, number] = origin_[line - 1];
          out += prefix + std::to_string(number) + "> of file <" + files_[file].name +
                 included_at(file);
        }
      p = e + middle.size();
    }
  return out + message.substr(p);
}

std::vector<std::string>
SceneText::subsections_in(const std::string &path) const
{
  const std::string     prefix = path + "/";
  std::set<std::string> names;
  for (auto it = subsections_.lower_bound(prefix);
       it != subsections_.end() && it->compare(0, prefix.size(), prefix) == 0; ++it)
    names.insert(it->substr(prefix.size(), it->find('/', prefix.size()) - prefix.size()));
  return {names.begin(), names.end()};
}

void
SceneText::parse(dealii::ParameterHandler &prm, const bool skip_undefined) const
{
  std::istringstream in(text_);
  try
    {
      if (format_ == Format::prm)
        prm.parse_input(in, files_[0].name, "", skip_undefined);
      else if (format_ == Format::json)
        prm.parse_input_from_json(in, skip_undefined);
      else
        prm.parse_input_from_xml(in, skip_undefined);
    }
  catch (const dealii::ExceptionBase &e)
    {
      throw InputError(rewrite_locations(deal_ii_message(e)));
    }
}
} // namespace gearkit

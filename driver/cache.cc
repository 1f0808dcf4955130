#include "driver/cache.h"

#include <hdf5.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace gearkit
{
namespace
{
// The integrity record in the root of a cache file (not part of the manifest itself).
const char *stage_attribute = "gearkit_stage", *key_attribute = "gearkit_key",
           *manifest_attribute = "gearkit_manifest", *digest_attribute = "gearkit_digest";

bool
integrity_attribute(const std::string &name)
{
  return name == stage_attribute || name == key_attribute || name == manifest_attribute ||
         name == digest_attribute;
}

// FNV-1a, 64 bit, over 8-byte words (then the remaining bytes): a check against accidents at
// memory speed. Pieces added one after the other digest as their concatenation when every
// piece but the last is a multiple of 8 bytes long.
class Digest
{
public:
  void
  add(const void *data, std::size_t size)
  {
    const unsigned char       *c = static_cast<const unsigned char *>(data);
    const unsigned char *const e = c + size;
    for (; e - c >= 8; c += 8)
      {
        std::uint64_t word;
        std::memcpy(&word, c, 8);
        mix(word);
      }
    for (; c != e; ++c)
      mix(*c);
  }
  std::string
  hex() const
  {
    std::ostringstream text;
    text << std::hex << std::setw(16) << std::setfill('0') << h;
    return text.str();
  }

private:
  void
  mix(std::uint64_t word)
  {
    h ^= word;
    h *= 1099511628211ull;
  }
  std::uint64_t h = 1469598103934665603ull;
};

std::string
digest(const void *data, std::size_t size)
{
  Digest d;
  d.add(data, size);
  return d.hex();
}

void
check(long status, const std::string &what)
{
  hdf5_check(hid_t(status), what);
}

// The manifest of one file: a line per group, dataset and attribute, in name order.
class Manifest
{
public:
  explicit Manifest(hid_t file) { walk(file, "/"); }
  std::string
  text() const
  {
    return lines.str();
  }
  /// The first dataset with values the stage did not promise (empty: none).
  const std::string &
  non_finite() const
  {
    return first_non_finite;
  }

private:
  std::ostringstream lines;
  std::string        first_non_finite;

  static std::vector<std::string>
  names(hid_t group, bool attributes)
  {
    std::vector<std::string> n;
    if (attributes)
      check(H5Aiterate2(
                group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
                [](hid_t, const char *name, const H5A_info_t *, void *data) -> herr_t {
                  static_cast<std::vector<std::string> *>(data)->push_back(name);
                  return 0;
                },
                &n),
            "listing attributes");
    else
      check(H5Literate(
                group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
                [](hid_t, const char *name, const H5L_info_t *, void *data) -> herr_t {
                  static_cast<std::vector<std::string> *>(data)->push_back(name);
                  return 0;
                },
                &n),
            "listing a group");
    return n;
  }

  // The bytes of a dataset or attribute in its native type; the type's class and size in `kind`.
  static std::vector<char>
  bytes(hid_t object, bool attribute, std::string &kind, hsize_t &count, std::vector<hsize_t> &dims,
        bool &variable_text)
  {
    H5Handle type(attribute ? H5Aget_type(object) : H5Dget_type(object), H5Tclose);
    H5Handle space(attribute ? H5Aget_space(object) : H5Dget_space(object), H5Sclose);
    check(type.id(), "reading a type");
    check(space.id(), "reading a shape");
    const int rank = H5Sget_simple_extent_ndims(space.id());
    check(rank, "reading a shape");
    dims.assign(std::size_t(rank), 0);
    H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
    count = 1;
    for (hsize_t d : dims)
      count *= d;
    variable_text                = H5Tis_variable_str(type.id()) > 0;
    const H5T_class_t type_class = H5Tget_class(type.id());
    if (variable_text)
      {
        // variable-length text (our attributes): the characters themselves
        std::vector<char *> texts(count, nullptr);
        if (count > 0)
          check(attribute ? H5Aread(object, type.id(), texts.data())
                          : H5Dread(object, type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()),
                "reading text");
        std::vector<char> all;
        for (char *t : texts)
          {
            const std::string s = t ? t : "";
            all.insert(all.end(), s.begin(), s.end());
            all.push_back('\0');
            H5free_memory(t);
          }
        kind = "text";
        return all;
      }
    if (type_class == H5T_VLEN || H5Tdetect_class(type.id(), H5T_VLEN) > 0)
      throw std::runtime_error("variable-length data the cache does not hold");
    H5Handle native(H5Tget_native_type(type.id(), H5T_DIR_ASCEND), H5Tclose);
    check(native.id(), "reading a type");
    const std::size_t size = H5Tget_size(native.id());
    std::vector<char> data(std::size_t(count) * size);
    if (count > 0)
      check(attribute ? H5Aread(object, native.id(), data.data())
                      : H5Dread(object, native.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
            "reading values");
    kind = std::to_string(int(type_class)) + "/" + std::to_string(size);
    return data;
  }

  void
  attributes(hid_t object, const std::string &path, bool root)
  {
    for (const std::string &name : names(object, true))
      {
        if (root && integrity_attribute(name))
          continue;
        H5Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
        check(attribute.id(), "opening attribute " + path + "@" + name);
        std::string          kind;
        hsize_t              count = 0;
        std::vector<hsize_t> dims;
        bool                 text = false;
        const auto           data = bytes(attribute.id(), true, kind, count, dims, text);
        lines << "A " << path << "@" << name << " " << kind << " " << count << " "
              << digest(data.data(), data.size()) << "\n";
      }
  }

  void
  dataset(hid_t set, const std::string &path)
  {
    std::string          kind;
    hsize_t              count = 0;
    std::vector<hsize_t> dims;
    bool                 text = false;
    const auto           data = bytes(set, false, kind, count, dims, text);
    lines << "D " << path << " " << kind << " [";
    for (std::size_t i = 0; i < dims.size(); ++i)
      lines << (i ? "," : "") << dims[i];
    lines << "] " << digest(data.data(), data.size()) << "\n";
    // never a NaN or an infinity (H5Group::write refuses them)
    if (first_non_finite.empty() && !text && kind == std::to_string(int(H5T_FLOAT)) + "/8")
      {
        const double *v = reinterpret_cast<const double *>(data.data());
        for (hsize_t i = 0; i < count; ++i)
          if (!std::isfinite(v[i]))
            {
              first_non_finite = path;
              break;
            }
      }
  }

  void
  walk(hid_t group, const std::string &path)
  {
    lines << "G " << path << "\n";
    attributes(group, path, path == "/");
    for (const std::string &name : names(group, false))
      {
        const std::string child = path + (path == "/" ? "" : "/") + name;
        H5Handle          object(H5Oopen(group, name.c_str(), H5P_DEFAULT), H5Oclose);
        check(object.id(), "opening " + child);
        switch (H5Iget_type(object.id()))
          {
          case H5I_GROUP:
            walk(object.id(), child);
            break;
          case H5I_DATASET:
            dataset(object.id(), child);
            attributes(object.id(), child, false);
            break;
          default:
            lines << "O " << child << "\n";
          }
      }
  }
};

// path -> its manifest line
std::map<std::string, std::string>
by_path(const std::string &manifest)
{
  std::map<std::string, std::string> lines;
  std::istringstream                 in(manifest);
  for (std::string line; std::getline(in, line);)
    {
      std::istringstream words(line);
      std::string        kind, path;
      words >> kind >> path;
      lines[path] = line;
    }
  return lines;
}

// The first difference between what the manifest lists and what the file holds.
std::string
difference(const std::string &recorded, const std::string &found)
{
  const auto was = by_path(recorded), is = by_path(found);
  for (const auto &[path, line] : was)
    if (!is.count(path))
      return "it lacks " + path + ", which its manifest lists";
  for (const auto &[path, line] : is)
    if (!was.count(path))
      return "it holds " + path + ", which its manifest does not list";
  for (const auto &[path, line] : was)
    if (is.at(path) != line)
      return path + " changed after it was written";
  return "its contents differ from its manifest";
}

// The size and digest of a file's bytes ("<size> <digest>"), read in blocks.
std::string
file_digest(const std::string &path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("cannot read " + path + " (" + std::strerror(errno) + ")");
  Digest            d;
  std::size_t       size = 0;
  std::vector<char> block(std::size_t(1) << 22); // a multiple of 8 bytes
  while (in.read(block.data(), std::streamsize(block.size())) || in.gcount() > 0)
    {
      d.add(block.data(), std::size_t(in.gcount()));
      size += std::size_t(in.gcount());
    }
  return std::to_string(size) + " " + d.hex();
}

const char *digest_header = "gearkit cache digest 1";
} // namespace

std::string
text_digest(const std::string &text)
{
  return digest(text.data(), text.size());
}

void
seal_cache_file(const H5File &file, const std::string &stage, const std::string &key)
{
  const std::string manifest = Manifest(file.id()).text();
  const H5Group     root     = file.root();
  root.attribute(stage_attribute, stage);
  root.attribute(key_attribute, key);
  root.attribute(manifest_attribute, manifest);
  root.attribute(digest_attribute, text_digest(stage + "\n" + key + "\n" + manifest));
}

void
record_cache_digest(const std::string &path)
{
  const std::string record = path + ".digest", tmp = record + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << digest_header << "\n" << file_digest(path) << "\n";
    out.close();
    if (!out)
      {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot write " + tmp + " (" + std::strerror(errno) + ")");
      }
  }
  if (std::rename(tmp.c_str(), record.c_str()) != 0)
    {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot rename " + tmp + " to " + record + " (" +
                               std::strerror(errno) + ")");
    }
}

std::string
cache_file_problem(const std::string &path, const std::string &stage, const std::string &key)
{
  try
    {
      // 1. The bytes, before HDF5 reads any of them (a damaged file could mislead it).
      std::ifstream record(path + ".digest");
      std::string   header, recorded;
      if (!std::getline(record, header) || header != digest_header ||
          !std::getline(record, recorded))
        return "it has no digest record (" + path + ".digest)";
      if (const std::string now = file_digest(path); now != recorded)
        return "its bytes are not those written by the stage (size and digest " + now +
               ", recorded " + recorded + "): changed, damaged or replaced since";
      // 2. What it holds: the stage, the key and the manifest recorded inside it.
      const H5File  file = H5File::open(path);
      const H5Group root = file.root();
      for (const char *a : {stage_attribute, key_attribute, manifest_attribute, digest_attribute})
        if (H5Aexists(root.id(), a) <= 0)
          return std::string("it has no integrity record (") + a +
                 "): written by an older gearkit, or damaged";
      const std::string was_stage = root.read_attribute(stage_attribute),
                        was_key   = root.read_attribute(key_attribute),
                        manifest  = root.read_attribute(manifest_attribute);
      if (root.read_attribute(digest_attribute) !=
          text_digest(was_stage + "\n" + was_key + "\n" + manifest))
        return "its integrity record is damaged (the digest of its manifest differs)";
      if (was_stage != stage)
        return "it holds the results of stage '" + was_stage + "', not '" + stage + "'";
      if (was_key != key)
        return "it was made for key " + was_key +
               " (another scene, its inputs or code), not this one's";
      if (!root.has(stage))
        return "it lacks the group /" + stage;
      const Manifest now(file.id());
      if (now.text() != manifest)
        return difference(manifest, now.text());
      if (!now.non_finite().empty())
        return now.non_finite() + " holds values that are not finite";
      return "";
    }
  catch (const std::exception &e)
    {
      return std::string("it cannot be read: ") + e.what();
    }
}
} // namespace gearkit

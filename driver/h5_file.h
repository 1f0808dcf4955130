// A small RAII layer over the HDF5 C API: files, groups, datasets with `units` and
// `description` attributes (from the results schema, driver/results_schema.h), and whole-group
// copies between files (stage cache -> results.h5).
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

namespace gearkit
{
/// Owns one HDF5 identifier and closes it with the matching H5*close.
class H5Handle
{
public:
  H5Handle() = default;
  H5Handle(hid_t id, herr_t (*close)(hid_t));
  H5Handle(H5Handle &&other) noexcept;
  H5Handle &
  operator=(H5Handle &&other) noexcept;
  H5Handle(const H5Handle &) = delete;
  H5Handle &
  operator=(const H5Handle &) = delete;
  ~H5Handle();
  hid_t
  id() const
  {
    return handle;
  }
  /// Closes now (the status of the H5*close: negative when it failed, e.g. a file whose
  /// buffers could not be written); the handle is empty afterwards either way.
  herr_t
  close();

private:
  hid_t handle            = -1;
  herr_t (*closer)(hid_t) = nullptr;
};

/// Why the last HDF5 call failed, from HDF5's error stack (the system's message where there is
/// one: "No space left on device"); clears the stack. Empty when HDF5 recorded nothing.
std::string
hdf5_error_cause();

/// `id` when it is valid (>= 0); else throws "HDF5: <what> failed [in <file of `where`>]
/// (<cause>)" with the cause from hdf5_error_cause().
hid_t
hdf5_check(hid_t id, const std::string &what, hid_t where = -1);

/// A group (or the root of a file) to write to and read from. It knows its pattern in the
/// results schema (driver/results_schema.h): its path with placeholders for the names that vary.
class H5Group
{
public:
  explicit H5Group(H5Handle handle, std::string path = "/", std::string schema_path = "");

  /// Child group, created when missing; `name` is a literal level of its schema pattern
  /// ("error_estimate").
  H5Group
  group(const std::string &name) const;
  /// The same for a name that varies: `placeholder` stands for it in the schema pattern
  /// (`out.group(pair.name, "<pair>")`).
  H5Group
  group(const std::string &name, const std::string &placeholder) const;
  bool
  has(const std::string &name) const;
  const std::string &
  path() const
  {
    return group_path;
  }
  /// The group's pattern in the results schema ("stiffness/<pair>"; "" for the root).
  const std::string &
  schema_path() const
  {
    return schema;
  }
  /// The file the group lives in.
  std::string
  file_name() const;
  hid_t
  id() const
  {
    return handle.id();
  }

  /// Dataset of doubles with the given shape (row-major); shape {} writes a scalar. Its `units`
  /// and `description` attributes come from the results schema's entry (schema_path(), name);
  /// `variant` picks the alternative of a description that offers a choice ("{a|b}": 0 or 1).
  /// A dataset the schema lacks, or one whose rank or type differs from its entry, is a
  /// std::logic_error.
  void
  write(const std::string &name, const std::vector<double> &values,
        const std::vector<hsize_t> &shape, int variant = -1) const;
  void
  write(const std::string &name, double value) const;
  void
  write(const std::string &name, const std::vector<int> &values, const std::vector<hsize_t> &shape,
        int variant = -1) const;
  /// A string attribute on this group.
  void
  attribute(const std::string &name, const std::string &value) const;

  std::vector<double>
  read_doubles(const std::string &name, std::vector<hsize_t> *shape = nullptr) const;
  std::vector<int>
  read_ints(const std::string &name, std::vector<hsize_t> *shape = nullptr) const;
  double
  read_double(const std::string &name) const;
  std::string
  read_attribute(const std::string &name) const;
  /// Names of the children (groups and datasets) in creation order.
  std::vector<std::string>
  children() const;

private:
  H5Handle    handle;
  std::string group_path;
  std::string schema;
};

/// An HDF5 file. Writing goes to `<path>.tmp`; commit() closes it and renames it into place, so
/// a failed run never leaves a half-written file under the final name.
class H5File
{
public:
  static H5File
  create(const std::string &path);
  static H5File
  open(const std::string &path);
  H5File(H5File &&) = default;
  ~H5File();

  H5Group
  root() const;
  /// Copies group `source_path` of `source` (with everything below it) to `target_path` here.
  void
  copy_from(const H5File &source, const std::string &source_path, const std::string &target_path);
  /// Close and rename the temporary into place (files opened for writing only).
  void
  commit();
  /// The file's name (the final one for a file being written).
  const std::string &
  path() const
  {
    return final_path;
  }
  /// The file's identifier (for walks over all of it: driver/cache.h).
  hid_t
  id() const
  {
    return handle.id();
  }

private:
  H5File(H5Handle handle, std::string path, bool writing);
  H5Handle    handle;
  std::string final_path;
  bool        writing   = false;
  bool        committed = false;
};
} // namespace gearkit

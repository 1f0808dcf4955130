#include "driver/h5_file.h"

#include "driver/results_schema.h"
#include "geometry/types.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace gearkit
{
namespace
{
// HDF5 prints its own error stack by default; we report our own message instead.
struct SilenceHdf5
{
  SilenceHdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
};
const SilenceHdf5 silence_hdf5;

} // namespace

std::string
hdf5_error_cause()
{
  // HDF5 records the failure on its error stack (printing is off): its innermost entry that
  // carries the system's error message ("errno = 28, error message = 'No space left on
  // device'") says why, else the innermost description.
  std::vector<std::string> descriptions;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t *e, void *data) -> herr_t {
        static_cast<std::vector<std::string> *>(data)->push_back(e->desc ? e->desc : "");
        return 0;
      },
      &descriptions);
  H5Eclear2(H5E_DEFAULT);
  for (const std::string &d : descriptions)
    if (const auto p = d.find("error message = '"); p != std::string::npos)
      {
        const auto b = p + 17, e = d.find('\'', b);
        return d.substr(b, e == std::string::npos ? std::string::npos : e - b);
      }
  return descriptions.empty() ? "" : descriptions.front();
}

hid_t
hdf5_check(hid_t id, const std::string &what, hid_t where)
{
  if (id >= 0)
    return id;
  const std::string cause   = hdf5_error_cause(); // before any other HDF5 call clears it
  std::string       message = "HDF5: " + what + " failed";
  if (where >= 0)
    {
      const ssize_t n = H5Fget_name(where, nullptr, 0);
      std::string   file(std::size_t(std::max<ssize_t>(n, 0)), '\0');
      if (n > 0 && H5Fget_name(where, file.data(), std::size_t(n) + 1) > 0)
        message += " in " + file;
    }
  if (!cause.empty())
    message += " (" + cause + ")";
  throw std::runtime_error(message);
}

namespace
{
hid_t
check(hid_t id, const std::string &what, hid_t where = -1)
{
  return hdf5_check(id, what, where);
}

// Variable-length UTF-8 strings: h5py reads them as str.
void
write_string_attribute(hid_t object, const std::string &name, const std::string &value)
{
  H5Handle type(check(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  H5Tset_size(type.id(), H5T_VARIABLE);
  H5Tset_cset(type.id(), H5T_CSET_UTF8);
  H5Handle space(check(H5Screate(H5S_SCALAR), "scalar space"), H5Sclose);
  if (H5Aexists(object, name.c_str()) > 0)
    H5Adelete(object, name.c_str());
  H5Handle attr(
      check(H5Acreate2(object, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
            "attribute " + name, object),
      H5Aclose);
  const char *text = value.c_str();
  check(H5Awrite(attr.id(), type.id(), &text), "write attribute " + name, object);
}

/// A dataset with its attributes from the results schema's entry (`schema`, `name`).
template <typename T>
void
write_dataset(hid_t group, const std::string &path, const std::string &schema,
              const std::string &name, hid_t mem_type, hid_t file_type,
              const std::vector<T> &values, const std::vector<hsize_t> &shape, int variant)
{
  const ResultDataset &entry       = result_dataset(schema, name);
  const std::string    description = result_description(entry, variant);
  const bool           integers    = std::is_integral_v<T>;
  if (result_rank(entry) != shape.size() || result_integers(entry) != integers)
    throw std::logic_error("HDF5 dataset " + path + name + ": written as " +
                           std::to_string(shape.size()) + "-dimensional " +
                           (integers ? "integers" : "doubles") + ", but its schema entry " +
                           schema + "/" + name + " has the shape '" + entry.shape + "'");
  hsize_t count = 1;
  for (hsize_t s : shape)
    count *= s;
  if (count != values.size())
    throw std::logic_error("HDF5 dataset " + path + name + ": shape does not match the data");
  H5Handle space(check(shape.empty() ? H5Screate(H5S_SCALAR)
                                     : H5Screate_simple(int(shape.size()), shape.data(), nullptr),
                       "data space"),
                 H5Sclose);
  H5Handle set(check(H5Dcreate2(group, name.c_str(), file_type, space.id(), H5P_DEFAULT,
                                H5P_DEFAULT, H5P_DEFAULT),
                     "create dataset " + path + name, group),
               H5Dclose);
  if (count > 0)
    check(H5Dwrite(set.id(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "write dataset " + path + name, group);
  write_string_attribute(set.id(), "units", entry.units);
  write_string_attribute(set.id(), "description", description);
}

template <typename T>
std::vector<T>
read_dataset(hid_t group, const std::string &path, const std::string &name, hid_t mem_type,
             std::vector<hsize_t> *shape)
{
  H5Handle set(
      check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open dataset " + path + name, group),
      H5Dclose);
  H5Handle             space(check(H5Dget_space(set.id()), "data space"), H5Sclose);
  const int            rank = H5Sget_simple_extent_ndims(space.id());
  std::vector<hsize_t> dims(rank);
  H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t s : dims)
    count *= s;
  std::vector<T> values(count);
  if (count > 0)
    check(H5Dread(set.id(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "read dataset " + path + name, group);
  if (shape)
    *shape = dims;
  return values;
}
} // namespace

H5Handle::H5Handle(hid_t id, herr_t (*close)(hid_t))
    : handle(id)
    , closer(close)
{
}

H5Handle::H5Handle(H5Handle &&o) noexcept
    : handle(o.handle)
    , closer(o.closer)
{
  o.handle = -1;
}

H5Handle &
H5Handle::operator=(H5Handle &&o) noexcept
{
  std::swap(handle, o.handle);
  std::swap(closer, o.closer);
  return *this;
}

H5Handle::~H5Handle() { close(); }

herr_t
H5Handle::close()
{
  herr_t status = 0;
  if (handle >= 0 && closer)
    status = closer(handle);
  handle = -1;
  return status;
}

H5Group::H5Group(H5Handle h, std::string path, std::string schema_path)
    : handle(std::move(h))
    , group_path(std::move(path))
    , schema(std::move(schema_path))
{
}

bool
H5Group::has(const std::string &name) const
{
  return H5Lexists(handle.id(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string
H5Group::file_name() const
{
  const ssize_t n = H5Fget_name(id(), nullptr, 0);
  std::string   name(std::size_t(std::max<ssize_t>(n, 0)), '\0');
  if (n > 0)
    H5Fget_name(id(), name.data(), std::size_t(n) + 1);
  return name;
}

H5Group
H5Group::group(const std::string &name) const
{
  const hid_t id =
      has(name) ? H5Gopen2(handle.id(), name.c_str(), H5P_DEFAULT)
                : H5Gcreate2(handle.id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  return H5Group(H5Handle(check(id, "group " + group_path + name, handle.id()), H5Gclose),
                 group_path + name + "/", schema.empty() ? name : schema + "/" + name);
}

H5Group
H5Group::group(const std::string &name, const std::string &placeholder) const
{
  H5Group g = group(name);
  g.schema  = schema.empty() ? placeholder : schema + "/" + placeholder;
  return g;
}

void
H5Group::write(const std::string &name, const std::vector<double> &values,
               const std::vector<hsize_t> &shape, int variant) const
{
  for (double v : values)
    if (!std::isfinite(v))
      throw std::runtime_error("refusing to write a non-finite value to " + group_path + name);
  write_dataset(handle.id(), group_path, schema, name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, values,
                shape, variant);
}

void
H5Group::write(const std::string &name, double value) const
{
  write(name, std::vector<double>{value}, {});
}

void
H5Group::write(const std::string &name, const std::vector<int> &values,
               const std::vector<hsize_t> &shape, int variant) const
{
  write_dataset(handle.id(), group_path, schema, name, H5T_NATIVE_INT, H5T_STD_I32LE, values, shape,
                variant);
}

void
H5Group::attribute(const std::string &name, const std::string &value) const
{
  write_string_attribute(handle.id(), name, value);
}

std::vector<double>
H5Group::read_doubles(const std::string &name, std::vector<hsize_t> *shape) const
{
  return read_dataset<double>(handle.id(), group_path, name, H5T_NATIVE_DOUBLE, shape);
}

std::vector<int>
H5Group::read_ints(const std::string &name, std::vector<hsize_t> *shape) const
{
  return read_dataset<int>(handle.id(), group_path, name, H5T_NATIVE_INT, shape);
}

double
H5Group::read_double(const std::string &name) const
{
  const std::vector<double> v = read_doubles(name);
  if (v.size() != 1)
    throw std::runtime_error("HDF5 dataset " + group_path + name + " is not a scalar");
  return v[0];
}

std::string
H5Group::read_attribute(const std::string &name) const
{
  H5Handle attr(check(H5Aopen(handle.id(), name.c_str(), H5P_DEFAULT),
                      "attribute " + group_path + name, handle.id()),
                H5Aclose);
  H5Handle type(check(H5Aget_type(attr.id()), "attribute type"), H5Tclose);
  if (!H5Tis_variable_str(type.id()))
    throw std::runtime_error("HDF5 attribute " + group_path + name + " is not a text");
  char *text = nullptr;
  check(H5Aread(attr.id(), type.id(), &text), "attribute read");
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

std::vector<std::string>
H5Group::children() const
{
  std::vector<std::string> names;
  H5Literate(
      handle.id(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr,
      [](hid_t, const char *name, const H5L_info_t *, void *data) -> herr_t {
        static_cast<std::vector<std::string> *>(data)->push_back(name);
        return 0;
      },
      &names);
  return names;
}

H5File::H5File(H5Handle h, std::string path, bool w)
    : handle(std::move(h))
    , final_path(std::move(path))
    , writing(w)
{
}

H5File
H5File::create(const std::string &path)
{
  // The file is built in memory and written out whole when it is flushed (HDF5's core driver
  // with a backing store): a disk that fills fails that one write, with the system's reason.
  // Writes that fail half-way through HDF5's own operations are not safe in HDF5 1.10: a
  // failing destination crashed H5Ocopy (SIGSEGV in its clean-up).
  const std::string tmp = path + ".tmp";
  H5Handle          access(check(H5Pcreate(H5P_FILE_ACCESS), "file access list"), H5Pclose);
  check(H5Pset_fapl_core(access.id(), std::size_t(16) << 20, 1), "in-memory file driver");
  const hid_t id = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.id());
  if (id < 0)
    {
      const std::string cause = hdf5_error_cause();
      std::remove(tmp.c_str());
      throw InputError("cannot create " + tmp + (cause.empty() ? "" : " (" + cause + ")") +
                       "; is the folder there and writable, with space left?");
    }
  return H5File(H5Handle(id, H5Fclose), path, true);
}

H5File
H5File::open(const std::string &path)
{
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0)
    {
      const std::string cause = hdf5_error_cause();
      throw InputError("cannot open HDF5 file " + path + (cause.empty() ? "" : " (" + cause + ")"));
    }
  return H5File(H5Handle(id, H5Fclose), path, false);
}

H5File::~H5File()
{
  if (writing && !committed)
    {
      // A failed write: the file may not close cleanly (no space left); it goes either way.
      handle.close();
      H5Eclear2(H5E_DEFAULT);
      std::remove((final_path + ".tmp").c_str());
    }
}

H5Group
H5File::root() const
{
  return H5Group(H5Handle(check(H5Gopen2(handle.id(), "/", H5P_DEFAULT), "root"), H5Gclose), "/");
}

void
H5File::copy_from(const H5File &source, const std::string &source_path,
                  const std::string &target_path)
{
  check(H5Ocopy(source.handle.id(), source_path.c_str(), handle.id(), target_path.c_str(),
                H5P_DEFAULT, H5P_DEFAULT),
        "copy " + source_path + " from " + source.final_path, handle.id());
}

void
H5File::commit()
{
  // Everything onto the disk before the rename: a write that fails (no space left) fails here,
  // naming the file, and leaves nothing under the final name.
  const std::string tmp = final_path + ".tmp";
  check(H5Fflush(handle.id(), H5F_SCOPE_GLOBAL), "write", handle.id());
  if (handle.close() < 0)
    {
      const std::string cause = hdf5_error_cause();
      throw std::runtime_error("HDF5: closing " + tmp + " failed" +
                               (cause.empty() ? "" : " (" + cause + ")"));
    }
  if (std::rename(tmp.c_str(), final_path.c_str()) != 0)
    throw std::runtime_error("cannot rename " + tmp + " to " + final_path + " (" +
                             std::strerror(errno) + ")");
  committed = true;
}
} // namespace gearkit

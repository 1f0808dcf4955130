// A grid over named parameters: every combination of each axis's values, the first axis
// slowest. The micro-geometry map (modification_grid.h) and the misalignment check
// (misalignment_study.h) are such grids over fields of their own structs.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace gearkit
{
struct GridAxis
{
  std::string         name;   ///< one of the grid's known names
  std::vector<double> values; ///< SI, at least one, finite
};

class ParameterGrid
{
public:
  /// `what` names the grid in messages ("modification grid"). Throws InputError for a name
  /// not among `known` (the message lists them), an axis named twice or without values, a
  /// non-finite value, and a grid of more than `most` points.
  ParameterGrid(std::vector<GridAxis> axes, const std::vector<std::string> &known,
                const std::string &what, std::size_t most = 100000);
  ParameterGrid() = default;
  /// Points: the product of the axes' sizes (1 without axes).
  std::size_t
  size() const;
  /// The value index of each axis at point g, the first axis slowest.
  std::vector<std::size_t>
  index(std::size_t g) const;
  /// Every point's values [size()][axes], in order.
  std::vector<double>
  points() const;
  const std::vector<GridAxis> &
  axes() const
  {
    return grid_axes;
  }

private:
  std::vector<GridAxis> grid_axes;
};

/// The name among `known`, else an InputError naming `what` and the known ones.
void
check_known(const std::string &name, const std::vector<std::string> &known,
            const std::string &what);

/// The fields of a struct a grid can vary (double members), by the names results use.
template <class T> class GridFields
{
public:
  using Field = double T::*;
  GridFields(std::string what, std::vector<std::pair<std::string, Field>> fields)
      : what(std::move(what))
      , fields(std::move(fields))
  {
    for (const auto &f : this->fields)
      list.push_back(f.first);
  }
  const std::vector<std::string> &
  names() const
  {
    return list;
  }
  /// The field of a name; throws InputError naming `what` and the known names.
  Field
  field(const std::string &name) const
  {
    for (const auto &[n, f] : fields)
      if (n == name)
        return f;
    check_known(name, list, what); // throws
    return nullptr;
  }

private:
  std::string                                what;
  std::vector<std::pair<std::string, Field>> fields;
  std::vector<std::string>                   list;
};
} // namespace gearkit

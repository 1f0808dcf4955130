#include "study/parameter_grid.h"

#include "base/types.h"

#include <algorithm>
#include <cmath>

namespace gearkit
{
void
check_known(const std::string &name, const std::vector<std::string> &known, const std::string &what)
{
  if (std::find(known.begin(), known.end(), name) != known.end())
    return;
  std::string list;
  for (const std::string &n : known)
    list += (list.empty() ? "" : ", ") + n;
  throw InputError(what + ": '" + name + "' is not a parameter of it; known: " + list);
}

ParameterGrid::ParameterGrid(std::vector<GridAxis> axes, const std::vector<std::string> &known,
                             const std::string &what, std::size_t most)
    : grid_axes(std::move(axes))
{
  double points = 1;
  for (std::size_t k = 0; k < grid_axes.size(); ++k)
    {
      const GridAxis &a = grid_axes[k];
      check_known(a.name, known, what);
      for (std::size_t j = 0; j < k; ++j)
        if (grid_axes[j].name == a.name)
          throw InputError(what + ": the axis " + a.name + " is given twice");
      if (a.values.empty())
        throw InputError(what + ": the axis " + a.name + " has no values");
      for (const double v : a.values)
        if (!std::isfinite(v))
          throw InputError(what + ": the axis " + a.name + " has a non-finite value");
      points *= double(a.values.size());
    }
  if (points > double(most))
    throw InputError(what + ": " + std::to_string(std::llround(points)) +
                     " combinations exceed the most allowed (" + std::to_string(most) +
                     "); use fewer values per axis");
}

std::size_t
ParameterGrid::size() const
{
  std::size_t n = 1;
  for (const GridAxis &a : grid_axes)
    n *= a.values.size();
  return n;
}

std::vector<std::size_t>
ParameterGrid::index(std::size_t g) const
{
  std::vector<std::size_t> at(grid_axes.size());
  for (std::size_t k = grid_axes.size(); k-- > 0;)
    at[k] = g % grid_axes[k].values.size(), g /= grid_axes[k].values.size();
  return at;
}

std::vector<double>
ParameterGrid::points() const
{
  std::vector<double> v;
  for (std::size_t g = 0; g < size(); ++g)
    {
      const std::vector<std::size_t> at = index(g);
      for (std::size_t k = 0; k < grid_axes.size(); ++k)
        v.push_back(grid_axes[k].values[at[k]]);
    }
  return v;
}
} // namespace gearkit

// What the scene sections share when they declare and parse their parameters (driver-internal).
#pragma once

#include "base/units.h"

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace gearkit
{
namespace Patterns = dealii::Patterns;
using namespace units;

/// The items of a comma-separated list, trimmed; empty items dropped.
std::vector<std::string>
split_list(const std::string &text);

/// The doubles of a list entry (already checked by its Patterns::List), times `factor`.
std::vector<double>
get_doubles(const ParameterHandler &prm, const std::string &entry, double factor = 1);

/// The integers of a list entry (already checked by its Patterns::List).
std::vector<int>
get_integers(const ParameterHandler &prm, const std::string &entry);

/// Runs f with prm inside the subsection path (e.g. {"Flanks", "spur", "Pinion"}).
template <typename F>
void
in_subsection(ParameterHandler &prm, const std::vector<std::string> &path, F &&f)
{
  for (const std::string &s : path)
    prm.enter_subsection(s);
  f();
  for (std::size_t i = 0; i < path.size(); ++i)
    prm.leave_subsection();
}

/// Scene and pair names: letters, digits, _ and -, at most 64 characters (they become folder
/// and group names). Throws InputError naming `where` otherwise.
void
check_identifier(const std::string &name, const std::string &where);
} // namespace gearkit

// The results schema: every dataset the stages write (their cache files, copied into
// results.h5), named once with its group, shape, units and description. H5Group::write takes
// the `units` and `description` attributes from here; `gearkit --print-results` prints it.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace gearkit
{
/// One dataset of the results.
///
/// `group` is the group's path below the file's root, with a placeholder in angle brackets for
/// each name that varies: "stiffness/<pair>/error_estimate", "dynamics/<pair>/<excitation>/
/// <sweep>", "measured/<pair>/<member>/tooth_<k>_<side>" (H5Group::group(name, placeholder)).
/// `shape` names the dimensions in words, " x " between them ("torques x positions";
/// "scalar" for one value), and ends in ", integers" (", integer") for integer data.
/// A `description` may offer one choice, "{first|second}": the writer picks one (variant).
struct ResultDataset
{
  std::string group, name, shape, units, description;
};

/// Every dataset, stage by stage in the order of the work (flanks, measured, ste, compliance,
/// stiffness, dynamics, train).
const std::vector<ResultDataset> &
results_schema();

/// The dataset `name` of the group pattern `group`; a std::logic_error naming both where the
/// schema has none (a programming error: add it to driver/results_schema.cc).
const ResultDataset &
result_dataset(const std::string &group, const std::string &name);

/// The dataset's dimensions (0: scalar) and whether it holds integers, from its shape text.
std::size_t
result_rank(const ResultDataset &d);
bool
result_integers(const ResultDataset &d);

/// The description as written: `variant` picks the alternative of its choice "{...|...}"
/// (counted from 0; -1 for a description without one). A std::logic_error where they do not fit.
std::string
result_description(const ResultDataset &d, int variant = -1);
/// Every description the dataset may be written with (one per variant; one without a choice).
std::vector<std::string>
result_descriptions(const ResultDataset &d);

/// The schema as a table (format "table": group, dataset, shape, units, description) or as JSON
/// ("json": an array of objects with those keys). A std::invalid_argument for another format.
void
print_results_schema(std::ostream &out, const std::string &format = "table");
} // namespace gearkit

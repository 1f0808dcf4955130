// Typed results of the dynamics stage's sweeps, group dynamics/<pair>/<excitation>/<sweep> (up,
// down): a sweep's points as the dynamics library returns them, written and read here alone (the
// dataset names, units and descriptions: driver/results_schema.cc).
#pragma once

#include "driver/h5_file.h"
#include "dynamics/sweep.h"

#include <vector>

namespace gearkit
{
/// Writes the sweep's points, in the order swept, to `g`.
void
write_sweep(const H5Group &g, const std::vector<SweepPoint> &points);

/// The points write_sweep wrote to `g`: what it stores of them (speeds back in rad/s; not
/// stored, so 0: relative_rms and events; CVODE sweeps: error_estimate NaN and steps 0;
/// record_cycles from the spectrum's resolution), the time series with the point of their speed.
std::vector<SweepPoint>
read_sweep(const H5Group &g);
} // namespace gearkit

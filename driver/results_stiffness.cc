#include "driver/results_stiffness.h"

namespace gearkit
{
std::vector<double>
StiffnessRecord::mesh_stiffness_at(std::size_t k) const
{
  const auto begin = cycle.mesh_stiffness.begin() + long(k * cycle.positions);
  return std::vector<double>(begin, begin + long(cycle.positions));
}

void
write_mesh_cycle(const H5Group &g, const MeshCycleContact &c, const std::vector<double> &torques,
                 const std::vector<double> &refused)
{
  const hsize_t N = c.positions, M = c.torques, S = c.slots, C = c.cells;
  g.write("torque", torques, {M});
  if (!refused.empty())
    g.write("refused_torque", refused, {refused.size()});
  g.write("pinion_angle", c.pinion_angle, {N});
  g.write("transmission_error_unloaded", c.unloaded_te, {N});
  g.write("transmission_error_loaded", c.loaded_te, {M, N});
  g.write("mesh_stiffness", c.mesh_stiffness, {M, N});
  g.write("normal_force", c.normal_force, {M, N});
  g.write("lever", c.lever, {M, N});
  g.write("pair_force", c.pair_force, {M, N, S});
  g.write("pinion_tooth", c.slot_tooth, {N, S});
  g.write("peak_pressure", c.peak_pressure, {M, N});
  g.write("interior_peak_pressure", c.interior_peak_pressure, {M, N});
  g.write("edge_load_share", c.edge_load_share, {M, N});
  g.write("edge_position", c.edge_position, {M, N, 2});
  g.write("gap_band", c.gap_band, {M, N});
  g.write("contact_cells", c.cell_pressure, {M, N, C, 4});
  g.write("mean_pairs_in_contact", c.mean_pairs_in_contact);
}

StiffnessRecord
read_mesh_cycle(const H5Group &g)
{
  StiffnessRecord   r;
  MeshCycleContact &c = r.cycle;
  r.torques           = g.read_doubles("torque");
  if (g.has("refused_torque"))
    r.refused = g.read_doubles("refused_torque");
  c.pinion_angle = g.read_doubles("pinion_angle");
  c.unloaded_te  = g.read_doubles("transmission_error_unloaded");
  c.loaded_te    = g.read_doubles("transmission_error_loaded");
  std::vector<hsize_t> shape;
  c.mesh_stiffness = g.read_doubles("mesh_stiffness", &shape);
  c.torques = shape.at(0), c.positions = shape.at(1);
  c.normal_force           = g.read_doubles("normal_force");
  c.lever                  = g.read_doubles("lever");
  c.pair_force             = g.read_doubles("pair_force", &shape);
  c.slots                  = shape.at(2);
  c.slot_tooth             = g.read_ints("pinion_tooth");
  c.peak_pressure          = g.read_doubles("peak_pressure");
  c.interior_peak_pressure = g.read_doubles("interior_peak_pressure");
  c.edge_load_share        = g.read_doubles("edge_load_share");
  c.edge_position          = g.read_doubles("edge_position");
  c.gap_band               = g.read_doubles("gap_band");
  c.cell_pressure          = g.read_doubles("contact_cells", &shape);
  c.cells                  = shape.at(2);
  c.mean_pairs_in_contact  = g.read_double("mean_pairs_in_contact");
  c.torque_failure.assign(c.torques, "");
  if (r.torques.size() != c.torques || c.pinion_angle.size() != c.positions)
    throw std::runtime_error("HDF5 group " + g.path() +
                             ": torque and pinion_angle do not match mesh_stiffness's shape");
  return r;
}
} // namespace gearkit

#include "driver/results_compliance.h"

namespace gearkit
{
void
write_compliance(const H5Group &m, const FlankCompliance &table, const MemberComplianceInfo &info,
                 int central_tooth, bool analytic_near_field)
{
  const std::vector<int> &teeth = table.grid_spec().teeth;
  const hsize_t           n = table.points().size(), loads = table.load_points().size();
  std::vector<double>     S(table.matrix().data(), table.matrix().data() + n * loads);
  // the description's variant: 0 the analytic near field, 1 a response depth
  m.write("compliance", S, {loads, n}, analytic_near_field ? 0 : 1);
  m.write("teeth", teeth, {teeth.size()});
  const std::vector<int> &grid = table.grid_teeth();
  m.write("grid_teeth", grid, {grid.size()});
  m.write("cyclic_tooth", double(table.grid_spec().cyclic_tooth));
  m.write("cyclic_reach", double(table.grid_teeth().size() / 2));
  m.write("central_tooth", double(central_tooth));
  m.write("hexahedra", double(info.hexahedra));
  m.write("dofs", double(info.dofs));
  if (analytic_near_field)
    m.write("min_near_field_radius", info.min_near_field_radius);
  else
    {
      m.write("response_depth", info.depth);
      m.write("shallow_points", double(info.shallow_points));
      m.write("min_response_depth", info.min_depth);
    }
  m.write("seconds", info.mesh_seconds + info.setup_seconds + info.solve_seconds);
}

ComplianceRecord
read_compliance(const H5Group &m, bool matrix)
{
  ComplianceRecord r;
  r.teeth         = m.read_ints("teeth");
  r.grid_teeth    = m.read_ints("grid_teeth");
  r.cyclic_tooth  = int(m.read_double("cyclic_tooth"));
  r.cyclic_reach  = int(m.read_double("cyclic_reach"));
  r.central_tooth = int(m.read_double("central_tooth"));
  if (matrix)
    {
      std::vector<hsize_t>      shape;
      const std::vector<double> S = m.read_doubles("compliance", &shape);
      // stored [load][point] row-major: the column-major points x loads matrix
      r.compliance = Eigen::Map<const Eigen::MatrixXd>(S.data(), Eigen::Index(shape[1]),
                                                       Eigen::Index(shape[0]));
    }
  r.info.hexahedra      = std::size_t(m.read_double("hexahedra"));
  r.info.dofs           = std::size_t(m.read_double("dofs"));
  r.analytic_near_field = m.has("min_near_field_radius");
  if (r.analytic_near_field)
    r.info.min_near_field_radius = m.read_double("min_near_field_radius");
  else
    {
      r.info.depth          = m.read_double("response_depth");
      r.info.shallow_points = std::size_t(m.read_double("shallow_points"));
      r.info.min_depth      = m.read_double("min_response_depth");
    }
  r.info.mesh_seconds = m.read_double("seconds");
  return r;
}

FlankCompliance
compliance_table(const MemberFlanks &flanks, const ComplianceRecord &record, FlankGridSpec spec)
{
  spec.teeth        = record.teeth;
  spec.cyclic_tooth = record.cyclic_tooth;
  spec.cyclic_reach = record.cyclic_reach;
  FlankCompliance t(flanks, spec);
  t.set(record.compliance);
  return t;
}
} // namespace gearkit

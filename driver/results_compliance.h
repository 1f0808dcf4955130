// Typed results of the compliance stage, group compliance/<pair>/<member> (and its coarse/
// subgroup): one member's finite-element compliance table with what it took, written and read
// here alone (the dataset names, units and descriptions: driver/results_schema.cc).
#pragma once

#include "driver/h5_file.h"
#include "stiffness/flank_compliance.h"
#include "stiffness/member_compliance.h"

#include <Eigen/Core>

#include <vector>

namespace gearkit
{
/// One member's table as stored: the grid it was computed on, the segment's middle tooth and
/// the figures of the computation (MemberComplianceInfo: the ones stored; `analytic_near_field`
/// says which depth figures apply).
struct ComplianceRecord
{
  std::vector<int> teeth;      ///< teeth that can carry load (FlankGridSpec::teeth)
  std::vector<int> grid_teeth; ///< teeth with a grid of points
  int              cyclic_tooth = -1, cyclic_reach = 0, central_tooth = 0;
  /// S(j, k) [m/N]: grid point j, unit load k (FlankCompliance::matrix).
  Eigen::MatrixXd compliance;
  bool            analytic_near_field = true;
  MemberComplianceInfo
      info; ///< hexahedra, dofs, near-field radius or depths; seconds in mesh_seconds
};

/// Writes `table` of a segment whose middle tooth is `central_tooth` to `member` (a group
/// compliance/<pair>/<member>).
void
write_compliance(const H5Group &member, const FlankCompliance &table,
                 const MemberComplianceInfo &info, int central_tooth, bool analytic_near_field);

/// The record write_compliance wrote to `member`; without the matrix (left empty) where
/// `matrix` is false.
ComplianceRecord
read_compliance(const H5Group &member, bool matrix = true);

/// The table of `record` on `flanks` with the reading options of `spec` (its teeth and cyclic
/// tooth and reach taken from the record).
FlankCompliance
compliance_table(const MemberFlanks &flanks, const ComplianceRecord &record, FlankGridSpec spec);
} // namespace gearkit

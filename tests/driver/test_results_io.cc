// The typed results (driver/results_*.h): what a group's writer stores its reader gives back -
// the compliance table (read back, it interpolates as the table written), the loaded mesh cycle,
// a sweep (speeds through rpm to the last bits; time series with the point of their speed), the
// TCA tables the dynamics reads.
#include "driver/h5_file.h"
#include "driver/results_compliance.h"
#include "driver/results_dynamics.h"
#include "driver/results_stiffness.h"
#include "tests/fzg_c_pair.h"
#include "tests/temp_directory_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gearkit;

namespace
{
class ResultsIo : public test_data::TempDirectoryTest
{
};

std::vector<double>
random_values(std::size_t n, std::mt19937 &rng, double scale = 1)
{
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double>                    v(n);
  for (double &x : v)
    x = scale * u(rng);
  return v;
}
} // namespace

TEST_F(ResultsIo, ComplianceTableReadBackInterpolatesAsWritten)
{
  const auto                 gear = InvoluteGear::create(test_data::fzg_c_pair().first);
  const InvoluteMemberFlanks flanks(gear);
  FlankGridSpec              spec;
  spec.teeth        = {15, 0, 1};
  spec.cyclic_tooth = 0;
  spec.cyclic_reach = 1;
  spec.n_u = 5, spec.n_v = 6;
  FlankCompliance table(flanks, spec);
  std::mt19937    rng(7);
  const auto      n = Eigen::Index(table.points().size()),
             loads  = Eigen::Index(table.load_points().size());
  ASSERT_LT(loads, n); // the cyclic tooth's loads alone: a matrix that is not square
  Eigen::MatrixXd           S(n, loads);
  const std::vector<double> values = random_values(std::size_t(n * loads), rng, 1e-9);
  std::copy(values.begin(), values.end(), S.data());
  table.set(S);
  MemberComplianceInfo info;
  info.hexahedra = 1234, info.dofs = 56789, info.min_near_field_radius = 0.7e-3;
  info.mesh_seconds = 1, info.setup_seconds = 2, info.solve_seconds = 3;

  const std::string path = (dir / "c.h5").string();
  {
    H5File f = H5File::create(path);
    write_compliance(f.root().group("compliance").group("p", "<pair>").group("pinion", "<member>"),
                     table, info, 0, true);
    f.commit();
  }
  const H5File           f = H5File::open(path);
  const ComplianceRecord r =
      read_compliance(f.root().group("compliance").group("p").group("pinion"));
  EXPECT_EQ(r.teeth, spec.teeth);
  EXPECT_EQ(r.grid_teeth, table.grid_teeth());
  EXPECT_EQ(r.cyclic_tooth, 0);
  EXPECT_EQ(r.central_tooth, 0);
  EXPECT_TRUE(r.analytic_near_field);
  EXPECT_EQ(r.info.hexahedra, 1234u);
  EXPECT_EQ(r.info.dofs, 56789u);
  EXPECT_EQ(r.info.min_near_field_radius, 0.7e-3);
  EXPECT_EQ(r.info.mesh_seconds, 6); // the three phases' sum, as stored
  ASSERT_EQ(r.compliance.rows(), n);
  ASSERT_EQ(r.compliance.cols(), loads);
  EXPECT_EQ((r.compliance - S).cwiseAbs().maxCoeff(), 0);
  // the table rebuilt from the record reads as the one written, between the grid points and
  // across teeth (the cyclic tooth's table turned)
  FlankGridSpec reading;
  reading.n_u = spec.n_u, reading.n_v = spec.n_v;
  const FlankCompliance back = compliance_table(flanks, r, reading);
  const FlankDomain     d    = flanks.flank(0, FlankSide::drive).domain();
  for (const auto &[ti, tj] : {std::pair{0, 0}, {0, 1}, {1, 0}, {15, 0}})
    for (const double a : {0.17, 0.5, 0.83})
      {
        const double ui = d.u_min + a * (d.u_max - d.u_min), vi = d.v_min + a * (d.v_max - d.v_min),
                     uj = d.u_min + (1 - a) * (d.u_max - d.u_min),
                     vj = d.v_min + 0.4 * (d.v_max - d.v_min);
        EXPECT_EQ(back(ti, ui, vi, tj, uj, vj), table(ti, ui, vi, tj, uj, vj)) << ti << " " << tj;
      }
}

TEST_F(ResultsIo, MeshCycleReadBackWhole)
{
  std::mt19937     rng(11);
  MeshCycleContact c;
  c.torques = 2, c.positions = 5, c.slots = 3, c.cells = 4;
  const std::size_t M = c.torques, N = c.positions, S = c.slots, C = c.cells;
  c.pinion_angle                    = random_values(N, rng);
  c.unloaded_te                     = random_values(N, rng, 1e-5);
  c.loaded_te                       = random_values(M * N, rng, 1e-4);
  c.mesh_stiffness                  = random_values(M * N, rng, 4e8);
  c.normal_force                    = random_values(M * N, rng, 1e4);
  c.lever                           = random_values(M * N, rng, 0.03);
  c.pair_force                      = random_values(M * N * S, rng, 1e4);
  c.slot_tooth                      = {0, 1, -1, 0, 1, -1, 1, 2, -1, 1, 2, 3, 2, 3, -1};
  c.peak_pressure                   = random_values(M * N, rng, 1e9);
  c.interior_peak_pressure          = random_values(M * N, rng, 1e9);
  c.edge_load_share                 = random_values(M * N, rng);
  c.edge_position                   = random_values(M * N * 2, rng, 0.05);
  c.gap_band                        = random_values(M * N, rng, 1e-5);
  c.cell_pressure                   = random_values(M * N * C * 4, rng, 1e9);
  c.mean_pairs_in_contact           = 1.43;
  const std::vector<double> torques = {100, 300}, refused = {500};

  const std::string path = (dir / "s.h5").string();
  {
    H5File f = H5File::create(path);
    write_mesh_cycle(f.root().group("stiffness").group("p", "<pair>"), c, torques, refused);
    f.commit();
  }
  const H5File            f = H5File::open(path);
  const StiffnessRecord   r = read_mesh_cycle(f.root().group("stiffness").group("p"));
  const MeshCycleContact &b = r.cycle;
  EXPECT_EQ(r.torques, torques);
  EXPECT_EQ(r.refused, refused);
  EXPECT_EQ(b.torques, M);
  EXPECT_EQ(b.positions, N);
  EXPECT_EQ(b.slots, S);
  EXPECT_EQ(b.cells, C);
  EXPECT_EQ(b.pinion_angle, c.pinion_angle);
  EXPECT_EQ(b.unloaded_te, c.unloaded_te);
  EXPECT_EQ(b.loaded_te, c.loaded_te);
  EXPECT_EQ(b.mesh_stiffness, c.mesh_stiffness);
  EXPECT_EQ(b.normal_force, c.normal_force);
  EXPECT_EQ(b.lever, c.lever);
  EXPECT_EQ(b.pair_force, c.pair_force);
  EXPECT_EQ(b.slot_tooth, c.slot_tooth);
  EXPECT_EQ(b.peak_pressure, c.peak_pressure);
  EXPECT_EQ(b.interior_peak_pressure, c.interior_peak_pressure);
  EXPECT_EQ(b.edge_load_share, c.edge_load_share);
  EXPECT_EQ(b.edge_position, c.edge_position);
  EXPECT_EQ(b.gap_band, c.gap_band);
  EXPECT_EQ(b.cell_pressure, c.cell_pressure);
  EXPECT_EQ(b.mean_pairs_in_contact, 1.43);
  EXPECT_EQ(b.torque_failure, std::vector<std::string>(M, ""));
  // K_m at the second torque: its row
  EXPECT_EQ(r.mesh_stiffness_at(1),
            std::vector<double>(c.mesh_stiffness.begin() + long(N), c.mesh_stiffness.end()));
}

TEST_F(ResultsIo, SweepReadBackWithItsTimeSeries)
{
  std::mt19937            rng(5);
  std::vector<SweepPoint> points(4);
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      SweepPoint &p     = points[i];
      p.speed           = 2 * pi * (1000 + 377.7 * double(i)) / 60; // rad/s, through rpm
      p.dte_pp          = 1e-6 * double(i + 1);
      p.dte_rms         = 3e-7 * double(i + 1);
      p.relative_pp     = 2e-6;
      p.max_force       = 5e3 + double(i);
      p.load_factor     = 1.2 + 0.1 * double(i);
      p.contact_loss    = i == 2 ? 0.25 : 0;
      p.settled_cycles  = 40 + int(i);
      p.steps_per_cycle = 64 * int(i + 1);
      p.error_estimate  = 1e-3 * double(i + 1);
      p.period          = i == 2 ? 0 : 1;
      p.record_cycles   = 8;
      p.spectrum        = random_values(8 * 10 + 1, rng, 1e-6);
    }
  points[3].diverged                  = true;
  points[3].diverged_time             = 0.125;
  points[1].series_time               = {0, 1e-4, 2e-4};
  points[1].series_dte                = {1e-6, 2e-6, 3e-6};
  points[1].series_transmission_error = {4e-6, 5e-6, 6e-6};
  points[1].series_force              = {7e3, 8e3, 9e3};

  const std::string path = (dir / "d.h5").string();
  {
    H5File f = H5File::create(path);
    write_sweep(f.root()
                    .group("dynamics")
                    .group("p", "<pair>")
                    .group("theoretical", "<excitation>")
                    .group("up", "<sweep>"),
                points);
    f.commit();
  }
  const H5File                  f = H5File::open(path);
  const std::vector<SweepPoint> r =
      read_sweep(f.root().group("dynamics").group("p").group("theoretical").group("up"));
  ASSERT_EQ(r.size(), points.size());
  for (std::size_t i = 0; i < r.size(); ++i)
    {
      const SweepPoint &a = points[i], &b = r[i];
      EXPECT_NEAR(b.speed, a.speed, 4e-16 * a.speed);
      EXPECT_EQ(b.dte_pp, a.dte_pp);
      EXPECT_EQ(b.dte_rms, a.dte_rms);
      EXPECT_EQ(b.relative_pp, a.relative_pp);
      EXPECT_EQ(b.max_force, a.max_force);
      EXPECT_EQ(b.load_factor, a.load_factor);
      EXPECT_EQ(b.contact_loss, a.contact_loss);
      EXPECT_EQ(b.settled_cycles, a.settled_cycles);
      EXPECT_EQ(b.steps_per_cycle, a.steps_per_cycle);
      EXPECT_EQ(b.error_estimate, a.error_estimate);
      EXPECT_EQ(b.period, a.period);
      EXPECT_EQ(b.diverged, a.diverged);
      EXPECT_EQ(b.diverged_time, a.diverged_time);
      EXPECT_EQ(b.record_cycles, 8);
      EXPECT_EQ(b.spectrum, a.spectrum);
      EXPECT_EQ(b.series_time, a.series_time) << i;
      EXPECT_EQ(b.series_dte, a.series_dte) << i;
      EXPECT_EQ(b.series_transmission_error, a.series_transmission_error) << i;
      EXPECT_EQ(b.series_force, a.series_force) << i;
    }
}

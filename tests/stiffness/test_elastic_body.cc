// ElasticBody against exact and classical solutions: the patch test (uniform tension reproduced
// exactly with hanging nodes, degree 1 and 2, iterative and direct; reactions and moments), a
// cantilever read from a gmsh file against Timoshenko beam theory, a patch load on a half-space
// against Boussinesq, direct against iterative solutions with one factorisation for many loads,
// run-time PETSc options, bad input. ElasticBodyParallel.* also runs on two MPI processes (CTest
// stiffness_mpi_np2) and compares the distributed results with a serial solve of the same body.
#include "../temp_directory_test.h"
#include "elastic_body.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

using namespace gearkit;
using dealii::Triangulation;

namespace
{
const Material steel{210e9, 0.3};

/// Tests that write files get a fresh directory.
using ElasticBodyFiles = gearkit::test_data::TempDirectoryTest;

/// Largest |a_i - b_i| over all entries (all processes).
double
max_difference(const ElasticBody::Displacement &a, const ElasticBody::Displacement &b)
{
  double m = 0;
  for (const auto i : a.locally_owned_elements())
    m = std::max(m, std::abs(a(i) - b(i)));
  return dealii::Utilities::MPI::max(m, MPI_COMM_WORLD);
}

/// Largest |a_i| over all entries (all processes).
double
max_abs(const ElasticBody::Displacement &a)
{
  double m = 0;
  for (const auto i : a.locally_owned_elements())
    m = std::max(m, std::abs(a(i)));
  return dealii::Utilities::MPI::max(m, MPI_COMM_WORLD);
}

bool
root()
{
  return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
}

/// Block [0, size] in cells[0] x cells[1] x cells[2] hexahedra; boundary ids 0 (x = 0),
/// 1 (x = Lx), 2 (y = 0), 3 (y = Ly), 4 (z = 0), 5 (z = Lz).
std::unique_ptr<Triangulation<3>>
block(const Vec3 &size, unsigned nx, unsigned ny, unsigned nz)
{
  auto mesh = std::make_unique<Triangulation<3>>();
  dealii::GridGenerator::subdivided_hyper_rectangle(
      *mesh, {nx, ny, nz}, dealii::Point<3>(), dealii::Point<3>(size.x(), size.y(), size.z()),
      true);
  return mesh;
}

/// The same block as a gmsh 2.2 ASCII file with physical surface tags 1 (x = 0), 2 (x = Lx)
/// and 3 (the four other sides).
void
write_block_msh(const std::string &path, const Vec3 &size, int nx, int ny, int nz)
{
  auto node = [&](int i, int j, int k) { return 1 + i + (nx + 1) * (j + (ny + 1) * k); };
  std::ostringstream elements;
  int                count = 0;
  auto quad = [&](int tag, int a, int b, int c, int d) {
    elements << ++count << " 3 2 " << tag << " " << tag << " " << a << " " << b << " " << c << " "
             << d << "\n";
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        elements << ++count << " 5 2 1 1 " << node(i, j, k) << " " << node(i + 1, j, k) << " "
                 << node(i + 1, j + 1, k) << " " << node(i, j + 1, k) << " "
                 << node(i, j, k + 1) << " " << node(i + 1, j, k + 1) << " "
                 << node(i + 1, j + 1, k + 1) << " " << node(i, j + 1, k + 1) << "\n";
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      {
        quad(1, node(0, j, k), node(0, j + 1, k), node(0, j + 1, k + 1), node(0, j, k + 1));
        quad(2, node(nx, j, k), node(nx, j + 1, k), node(nx, j + 1, k + 1), node(nx, j, k + 1));
      }
  for (int i = 0; i < nx; ++i)
    {
      for (int k = 0; k < nz; ++k)
        {
          quad(3, node(i, 0, k), node(i + 1, 0, k), node(i + 1, 0, k + 1), node(i, 0, k + 1));
          quad(3, node(i, ny, k), node(i + 1, ny, k), node(i + 1, ny, k + 1), node(i, ny, k + 1));
        }
      for (int j = 0; j < ny; ++j)
        {
          quad(3, node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0));
          quad(3, node(i, j, nz), node(i + 1, j, nz), node(i + 1, j + 1, nz), node(i, j + 1, nz));
        }
    }
  std::ofstream out(path);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << (nx + 1) * (ny + 1) * (nz + 1) << "\n";
  out.precision(17);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        out << node(i, j, k) << " " << size.x() * i / nx << " " << size.y() * j / ny << " "
            << size.z() * k / nz << "\n";
  out << "$EndNodes\n$Elements\n" << count << "\n" << elements.str() << "$EndElements\n";
}

double
relative_difference(const Vec3 &a, const Vec3 &b)
{
  return (a - b).norm() / std::max(a.norm(), b.norm());
}

/// Expects an InputError whose message contains `text`.
void
expect_input_error(const std::function<void()> &make, const std::string &text)
{
  try
    {
      make();
      ADD_FAILURE() << "no InputError; expected one mentioning \"" << text << "\"";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos)
          << "message \"" << e.what() << "\" does not mention \"" << text << "\"";
    }
}

/// Cantilever 100 x 10 x 10 mm clamped at x = 0 (id 0), shear traction of total P on x = L
/// (id 1), degree 2, 20 x 2 x 2 cells.
struct Cantilever
{
  Vec3   size{100e-3, 10e-3, 10e-3};
  double force = 1000; ///< P, along -z [N]
  double E = steel.youngs_modulus, G = E / (2 * (1 + steel.poisson_ratio));
  double I = size.y() * std::pow(size.z(), 3) / 12, A = size.y() * size.z();
  /// Timoshenko: P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6.
  double
  tip_deflection() const
  {
    return force * std::pow(size.x(), 3) / (3 * E * I) + force * size.x() / (5.0 / 6 * G * A);
  }
  /// Cross-section rotation at the tip, P L^2 / (2 E I) (about +y for a load along -z).
  double
  tip_rotation() const
  {
    return force * size.x() * size.x() / (2 * E * I);
  }
  LoadSet
  loads(dealii::types::boundary_id tip) const
  {
    return {{{tip, Vec3(0, 0, -force / A)}}, {}};
  }
};
} // namespace

TEST(ElasticBody, PatchTestIsExactWithHangingNodes)
{
  // Rollers u_x = 0 on x = 0, u_y = 0 on y = 0, u_z = 0 on z = 0, traction sigma on x = L:
  // u = (sigma x, -nu sigma y, -nu sigma z) / E everywhere, also across hanging nodes (one local
  // refinement sweep around an interior point).
  const Vec3   L(30e-3, 20e-3, 10e-3);
  const double sigma = 80e6, E = steel.youngs_modulus, nu = steel.poisson_ratio;
  const auto   exact = [&](const Vec3 &x) -> Vec3 {
    return Vec3(sigma * x.x(), -nu * sigma * x.y(), -nu * sigma * x.z()) / E;
  };
  const double scale = sigma * L.x() / E;
  const std::vector<Vec3> points{Vec3(1e-3, 2e-3, 3e-3), Vec3(12.3e-3, 7.7e-3, 5.1e-3),
                                 Vec3(29e-3, 19e-3, 9e-3), L};
  for (unsigned degree : {1u, 2u})
    {
      ElasticBodyOptions o;
      o.degree             = degree;
      o.material           = steel;
      o.fixed_components   = {{0, 0}, {2, 1}, {4, 2}};
      o.local_refinements  = {{Vec3(12e-3, 8e-3, 5e-3), 6e-3}};
      o.relative_tolerance = 1e-12;
      ElasticBody         body(*block(L, 3, 2, 2), o);
      const AssembledLoad f = body.assemble({{{1, Vec3(sigma, 0, 0)}}, {}});
      EXPECT_GT(body.n_cells(), 12u) << "the local refinement made no hanging nodes";
      for (const bool direct : {false, true})
        {
          const auto u = direct ? body.solve_direct(f) : body.solve_iterative(f);
          const auto v = body.displacements(u, points);
          for (std::size_t k = 0; k < points.size(); ++k)
            EXPECT_LT((v[k] - exact(points[k])).norm(), 1e-10 * scale)
                << "degree " << degree << (direct ? " direct" : " iterative") << " point " << k;
          // The support at x = 0 pulls back with -sigma W H at the face centre.
          const Wrench r = body.reaction(u, f, 0, Vec3::Zero());
          const double F = sigma * L.y() * L.z();
          EXPECT_LT((r.force - Vec3(-F, 0, 0)).norm(), 1e-10 * F);
          EXPECT_LT((r.moment - Vec3(0, -F * L.z() / 2, F * L.y() / 2)).norm(), 1e-10 * F * L.y());
          // The loaded face moves rigidly by the exact displacement of its centre, no rotation.
          const Vec3        centre(L.x(), L.y() / 2, L.z() / 2);
          const RigidMotion m = body.rigid_motion(u, 1, centre);
          EXPECT_LT((m.translation - exact(centre)).norm(), 1e-10 * scale);
          EXPECT_LT(m.rotation.norm(), 1e-10 * scale / L.y());
          EXPECT_LT((body.patch_average(u, {1, centre, 1.0}) - exact(centre)).norm(),
                    1e-10 * scale);
          if (root())
            std::printf("  degree %u %s: %zu cells, %zu dofs, reaction %.12g N (exact %.12g), "
                        "%s%u iterations\n",
                        degree, direct ? "direct" : "iterative", body.n_cells(), body.n_dofs(),
                        r.force.x(), -F, direct ? "" : body.statistics().iterative_method.c_str(),
                        direct ? 0 : body.statistics().last_iterations);
        }
    }
}

TEST_F(ElasticBodyFiles, CantileverFromGmshAgainstTimoshenko)
{
  // Mesh: 20 x 2 x 2 hexahedra (5 mm), degree 2, read from a gmsh 2.2 file (tags 1: clamp,
  // 2: tip). Tip deflection = work-conjugate mean of u_z over the tip face.
  const Cantilever  beam;
  const std::string mesh = (dir / "cantilever.msh").string();
  write_block_msh(mesh, beam.size, 20, 2, 2);
  ElasticBodyOptions o;
  o.degree   = 2;
  o.material = steel;
  o.clamped  = {1};
  ElasticBody         body(mesh, o);
  const AssembledLoad f = body.assemble(beam.loads(2));
  const auto          u = body.solve_direct(f);
  const Vec3          tip(beam.size.x(), beam.size.y() / 2, beam.size.z() / 2);
  const double        w = -body.patch_average(u, {2, tip, 1.0}).z();
  const double        w_centre = -body.displacements(u, {tip})[0].z();
  const double        psi = body.rigid_rotation(u, 2, tip, Vec3::UnitY());
  EXPECT_NEAR(w / beam.tip_deflection(), 1, 0.02);
  EXPECT_NEAR(psi / beam.tip_rotation(), 1, 0.02);
  // Equilibrium: the clamp carries +P and the moment -P L about its centre (y).
  const Wrench r = body.reaction(u, f, 1, Vec3(0, tip.y(), tip.z()));
  EXPECT_LT((r.force - Vec3(0, 0, beam.force)).norm(), 1e-9 * beam.force);
  EXPECT_LT((r.moment - Vec3(0, -beam.force * beam.size.x(), 0)).norm(),
            1e-9 * beam.force * beam.size.x());
  std::printf("  cantilever %zu cells, %zu dofs: tip mean deflection %.6e m, centre %.6e m, "
              "Timoshenko %.6e m (%+.2f %%); tip rotation %.6e rad, beam %.6e rad (%+.2f %%)\n",
              body.n_cells(), body.n_dofs(), w, w_centre, beam.tip_deflection(),
              100 * (w / beam.tip_deflection() - 1), psi, beam.tip_rotation(),
              100 * (psi / beam.tip_rotation() - 1));
}

namespace
{
/// Quarter of a half-space: the block [0, 64 a]^3, symmetry on x = 0 and y = 0, bottom clamped,
/// a force F/4 on the quarter patch of radius a (and, as a second load set, 2 a) at the corner
/// (0, 0, 64 a) of the top face; the mesh (8^3 cells of 8 a) refined `sweeps` times in balls of
/// three cells around the corner, so the finest cells are 8 a / 2^sweeps.
struct Boussinesq
{
  double a = 1e-3, F = 1000;
  double mean_a = 0, mean_2a = 0;   ///< FE patch mean displacements (down) [m]
  double reaction = 0, work_gap = 0; ///< clamp force / (F / 4); |f.u - F/4 w| / (F/4 w)
  double exact = 0;                  ///< 16 (1 - nu^2) F / (3 pi^2 E a)
  std::size_t cells = 0, dofs = 0;
  double      seconds = 0;

  explicit Boussinesq(unsigned sweeps)
  {
    const double D = 64 * a;
    const Vec3   corner(0, 0, D);
    ElasticBodyOptions o;
    o.degree           = 2;
    o.material         = steel;
    o.clamped          = {4};
    o.fixed_components = {{0, 0}, {2, 1}};
    for (unsigned k = 0; k < sweeps; ++k)
      o.local_refinements.push_back({corner, 3 * 8 * a / std::pow(2.0, k)});
    ElasticBody body(*block(Vec3(D, D, D), 8, 8, 8), o);
    const PatchForce small{{5, corner, a}, Vec3(0, 0, -F / 4)};
    const PatchForce large{{5, corner, 2 * a}, Vec3(0, 0, -F / 4)};
    const AssembledLoad f_small = body.assemble({{}, {small}});
    const AssembledLoad f_large = body.assemble({{}, {large}});
    const auto          u_small = body.solve_direct(f_small);
    const auto          u_large = body.solve_direct(f_large);
    mean_a   = -body.patch_average(u_small, small.patch).z();
    mean_2a  = -body.patch_average(u_large, large.patch).z();
    reaction = body.reaction(u_small, f_small, 4, corner).force.z() / (F / 4);
    work_gap = std::abs((f_small.nodal * u_small) / (F / 4 * mean_a) - 1);
    const double nu = steel.poisson_ratio;
    exact   = 16 * (1 - nu * nu) * F / (3 * pi * pi * steel.youngs_modulus * a);
    cells   = body.n_cells();
    dofs    = body.n_dofs();
    seconds = body.statistics().setup_seconds + body.statistics().factorisation_seconds;
    if (root())
      std::printf("  %u sweeps (finest %.3g a): %zu cells, %zu dofs, %.2f s: mean w(a) / exact "
                  "%.4f, (w(a) - w(2a)) / (exact / 2) %.4f\n",
                  sweeps, 8 / std::pow(2.0, sweeps), cells, dofs, seconds, mean_a / exact,
                  (mean_a - mean_2a) / (exact / 2));
  }
};
} // namespace

TEST(ElasticBody, PatchLoadAgainstBoussinesqCoarse)
{
  // Mean displacement of a uniformly loaded circle on a half-space (Johnson, Contact Mechanics,
  // eq. 3.41 averaged over the circle): 16 (1 - nu^2) F / (3 pi^2 E a). Coarse: 4 sweeps,
  // finest cells a / 2; the finite block (bottom 64 a deep) adds a nearly uniform stiffening
  // that the difference of the two patch radii removes.
  const Boussinesq b(4);
  EXPECT_NEAR(b.reaction, 1, 1e-12); // the applied total equals F exactly
  EXPECT_LT(b.work_gap, 1e-12);      // load and patch mean are work-conjugate
  EXPECT_NEAR(b.mean_a / b.exact, 1, 0.05);
  EXPECT_NEAR((b.mean_a - b.mean_2a) / (b.exact / 2), 1, 0.05);
}

TEST(ElasticBody, PatchLoadAgainstBoussinesqFine)
{
  // The same with 6 sweeps (finest cells a / 8); CTest label "slow".
  const Boussinesq b(6);
  EXPECT_NEAR(b.reaction, 1, 1e-12);
  EXPECT_NEAR(b.mean_a / b.exact, 1, 0.02);
  EXPECT_NEAR((b.mean_a - b.mean_2a) / (b.exact / 2), 1, 0.02);
}

TEST(ElasticBody, DirectAndIterativeAgreeOnOneFactorisation)
{
  // 60 x 60 x 30 mm block, 24 x 24 x 12 cells of degree 1, bottom clamped, five patch loads
  // (oblique forces at five places of the top face): MUMPS once for all five, against CG with
  // BoomerAMG and with GAMG.
  const Vec3         L(60e-3, 60e-3, 30e-3);
  ElasticBodyOptions o;
  o.material           = steel;
  o.clamped            = {4};
  o.relative_tolerance = 1e-12;
  ElasticBody body(*block(L, 24, 24, 12), o);
  std::vector<AssembledLoad> loads;
  for (int k = 0; k < 5; ++k)
    loads.push_back(body.assemble(
        {{}, {{{5, Vec3(10e-3 + 10e-3 * k, 15e-3 + 6e-3 * k, L.z()), 4e-3}, Vec3(200, -100 * k, -1000)}}}));
  std::vector<ElasticBody::Displacement> direct;
  std::vector<double>                    seconds;
  for (const AssembledLoad &f : loads)
    {
      direct.push_back(body.solve_direct(f));
      seconds.push_back(body.statistics().last_direct_seconds);
    }
  const double factorisation = body.statistics().factorisation_seconds;
  // The first solve factorised; the four others reuse the factorisation.
  for (std::size_t k = 1; k < seconds.size(); ++k)
    EXPECT_LT(seconds[k], 0.25 * seconds[0]) << "solve " << k;
  for (const std::string pc : {"boomeramg", "gamg"})
    {
      ElasticBodyOptions oi = o;
      oi.preconditioner     = pc;
      ElasticBody iterative_body(*block(L, 24, 24, 12), oi);
      for (std::size_t k = 0; k < loads.size(); ++k)
        {
          const auto u = iterative_body.solve_iterative(loads[k]);
          if (k == 0 && root())
            std::printf("  %s: %u iterations, first solve %.3f s\n",
                        iterative_body.statistics().iterative_method.c_str(),
                        iterative_body.statistics().last_iterations,
                        iterative_body.statistics().last_iterative_seconds);
          EXPECT_LT(max_difference(u, direct[k]), 1e-8 * max_abs(direct[k]))
              << pc << " load " << k;
        }
    }
  if (root())
    std::printf("  block %zu cells, %zu dofs: set-up %.3f s, factorisation %.3f s, direct solves "
                "%.4f (with the factorisation) %.4f %.4f %.4f %.4f s\n",
                body.n_cells(), body.n_dofs(), body.statistics().setup_seconds, factorisation,
                seconds[0], seconds[1], seconds[2], seconds[3], seconds[4]);
}

TEST(ElasticBody, RunTimeSolverOptionsAreHonoured)
{
  // PETSC_OPTIONS (CTest stiffness_petsc_options sets "-ksp_type minres -pc_type jacobi") or,
  // when absent, the same options set here reach the iterative solver; the direct solver, with
  // its prefix, keeps MUMPS and agrees.
  char      ksp[64] = "", pc[64] = "";
  PetscBool has_ksp = PETSC_FALSE, has_pc = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-ksp_type", ksp, sizeof ksp, &has_ksp);
  PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc, sizeof pc, &has_pc);
  const bool set_here = !has_ksp && !has_pc;
  if (set_here)
    {
      PetscOptionsSetValue(nullptr, "-ksp_type", "minres");
      PetscOptionsSetValue(nullptr, "-pc_type", "jacobi");
    }
  const std::string expected_ksp = has_ksp ? ksp : (set_here ? "minres" : "cg");
  const std::string expected_pc  = has_pc ? pc : (set_here ? "jacobi" : "hypre");
  ElasticBodyOptions o;
  o.material           = steel;
  o.clamped            = {0};
  o.relative_tolerance = 1e-12;
  ElasticBody         body(*block(Vec3(40e-3, 8e-3, 8e-3), 10, 2, 2), o);
  const AssembledLoad f = body.assemble({{{1, Vec3(1e6, 2e6, -3e6)}}, {}});
  const auto          u = body.solve_iterative(f);
  if (set_here)
    {
      PetscOptionsClearValue(nullptr, "-ksp_type");
      PetscOptionsClearValue(nullptr, "-pc_type");
    }
  EXPECT_EQ(body.statistics().iterative_method, expected_ksp + " + " + expected_pc);
  const auto v = body.solve_direct(f);
  EXPECT_LT(max_difference(u, v), 1e-7 * max_abs(v));
  std::printf("  PETSC_OPTIONS \"%s\": iterative %s, %u iterations\n",
              std::getenv("PETSC_OPTIONS") ? std::getenv("PETSC_OPTIONS") : "",
              body.statistics().iterative_method.c_str(), body.statistics().last_iterations);
}

TEST_F(ElasticBodyFiles, BadInputIsRefused)
{
  ElasticBodyOptions o;
  o.clamped = {0};
  expect_input_error([&] { ElasticBody{(dir / "missing.msh").string(), o}; }, "missing.msh");
  // one tetrahedron, gmsh 2.2 ASCII
  const std::string tet = file("tet.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n"
                                          "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
                                          "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n");
  expect_input_error([&] { ElasticBody{tet, o}; }, "hexahedra");
  const auto mesh = block(Vec3(1e-2, 1e-2, 1e-2), 2, 2, 2);
  auto       with = [&](const std::function<void(ElasticBodyOptions &)> &change) {
    ElasticBodyOptions changed = o;
    change(changed);
    return [&mesh, changed] { ElasticBody{*mesh, changed}; };
  };
  expect_input_error(with([](auto &p) { p.material.poisson_ratio = 0.5; }), "Poisson's ratio");
  expect_input_error(with([](auto &p) { p.material.youngs_modulus = 0; }), "Young's modulus");
  expect_input_error(with([](auto &p) { p.degree = 3; }), "degree = 3");
  expect_input_error(with([](auto &p) { p.preconditioner = "ilu"; }), "preconditioner");
  expect_input_error(with([](auto &p) { p.clamped = {42}; }), "boundary id 42");
  expect_input_error(with([](auto &p) { p.fixed_components = {{1, 3}}; }), "component 3");
  expect_input_error(with([](auto &p) { p.clamped.clear(); }), "no boundary is held");
  ElasticBody body(*mesh, o);
  expect_input_error([&] { body.assemble({{{7, Vec3(1, 0, 0)}}, {}}); }, "boundary id 7");
  expect_input_error([&] { body.assemble({{}, {{{5, Vec3(0, 0, 0.02), 1e-4}, Vec3(0, 0, 1)}}}); },
                     "no face quadrature point");
  const auto u = body.solve_direct(body.assemble({{{1, Vec3(1e6, 0, 0)}}, {}}));
  expect_input_error([&] { body.displacements(u, {Vec3(0.5, 0, 0)}); }, "outside");
  expect_input_error([&] { body.write_vtu(u, (dir / "no" / "such").string(), "x"); },
                     "cannot write");
  // nothing was left behind: the directory holds the tetrahedral mesh only
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
}

namespace
{
/// The same body on all processes (distributed) and on each process alone (serial).
struct TwoWays
{
  std::unique_ptr<ElasticBody> parallel, serial;
  TwoWays(const Triangulation<3> &mesh, ElasticBodyOptions o)
  {
    o.communicator = MPI_COMM_WORLD;
    parallel       = std::make_unique<ElasticBody>(mesh, o);
    o.communicator = MPI_COMM_SELF;
    serial         = std::make_unique<ElasticBody>(mesh, o);
  }
};

/// A directory known to every rank (named after rank 0's process id).
std::filesystem::path
shared_directory(const std::string &name)
{
  const unsigned id = dealii::Utilities::MPI::broadcast(MPI_COMM_WORLD, unsigned(::getpid()), 0);
  return std::filesystem::temp_directory_path() /
         ("gearkit-" + name + "-" + std::to_string(id));
}
} // namespace

TEST(ElasticBodyParallel, CantileverSameAsSerial)
{
  const Cantilever   beam;
  ElasticBodyOptions o;
  o.degree             = 2;
  o.material           = steel;
  o.clamped            = {0};
  o.relative_tolerance = 1e-12;
  TwoWays     body(*block(beam.size, 20, 2, 2), o);
  const Vec3  tip(beam.size.x(), beam.size.y() / 2, beam.size.z() / 2);
  const auto  f_parallel = body.parallel->assemble(beam.loads(1));
  const auto  f_serial   = body.serial->assemble(beam.loads(1));
  const auto  u_parallel = body.parallel->solve_direct(f_parallel);
  const auto  u_serial   = body.serial->solve_direct(f_serial);
  const auto  u_iterative = body.parallel->solve_iterative(f_parallel);

  const Vec3 mean_parallel = body.parallel->patch_average(u_parallel, {1, tip, 1.0});
  const Vec3 mean_serial   = body.serial->patch_average(u_serial, {1, tip, 1.0});
  const Vec3 mean_iterative = body.parallel->patch_average(u_iterative, {1, tip, 1.0});
  EXPECT_NEAR(-mean_parallel.z() / beam.tip_deflection(), 1, 0.02);
  EXPECT_LT(relative_difference(mean_parallel, mean_serial), 1e-10);
  EXPECT_LT(relative_difference(mean_iterative, mean_serial), 1e-8);
  const std::vector<Vec3> points{Vec3(1e-3, 1e-3, 1e-3), Vec3(50e-3, 5e-3, 5e-3), tip,
                                 Vec3(77.7e-3, 2.5e-3, 9.9e-3)};
  const auto              v_parallel = body.parallel->displacements(u_parallel, points);
  const auto              v_serial   = body.serial->displacements(u_serial, points);
  for (std::size_t k = 0; k < points.size(); ++k)
    EXPECT_LT(relative_difference(v_parallel[k], v_serial[k]), 1e-10) << "point " << k;

  // Tip rotation about y: the fit, serial and distributed, against beam theory and against
  // an independent fit of point values at 3 x 3 Gauss points of each of the 2 x 2 tip faces
  // (exact for the biquadratic displacement times the linear lever).
  const double psi_parallel = body.parallel->rigid_rotation(u_parallel, 1, tip, Vec3::UnitY());
  const double psi_serial   = body.serial->rigid_rotation(u_serial, 1, tip, Vec3::UnitY());
  EXPECT_NEAR(psi_parallel / beam.tip_rotation(), 1, 0.02);
  EXPECT_NEAR(psi_parallel / psi_serial, 1, 1e-10);
  const double      g[3] = {-std::sqrt(0.6), 0, std::sqrt(0.6)}, w[3] = {5. / 9, 8. / 9, 5. / 9};
  std::vector<Vec3> gauss;
  std::vector<double> weight;
  for (int cy = 0; cy < 2; ++cy)
    for (int cz = 0; cz < 2; ++cz)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          {
            const double h = beam.size.y() / 2; // face cells are h x h
            gauss.emplace_back(beam.size.x(), h * (cy + 0.5 + g[i] / 2), h * (cz + 0.5 + g[j] / 2));
            weight.push_back(w[i] * w[j] * h * h / 4);
          }
  const auto                  u_gauss = body.parallel->displacements(u_parallel, gauss);
  Eigen::Matrix<double, 6, 6> N       = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b       = Eigen::Matrix<double, 6, 1>::Zero();
  for (std::size_t q = 0; q < gauss.size(); ++q)
    {
      const Vec3                  r = gauss[q] - tip;
      Eigen::Matrix<double, 3, 6> A;
      A.leftCols<3>().setIdentity();
      for (int k = 0; k < 3; ++k) // column k: d(omega x r) / d omega_k = e_k x r
        A.col(3 + k) = Vec3::Unit(k).cross(r);
      N += weight[q] * A.transpose() * A;
      b += weight[q] * A.transpose() * u_gauss[q];
    }
  const double psi_independent = N.ldlt().solve(b)(4);
  EXPECT_NEAR(psi_parallel / psi_independent, 1, 1e-10);

  const Wrench r_parallel = body.parallel->reaction(u_parallel, f_parallel, 0, Vec3::Zero());
  const Wrench r_serial   = body.serial->reaction(u_serial, f_serial, 0, Vec3::Zero());
  EXPECT_LT(relative_difference(r_parallel.force, r_serial.force), 1e-10);
  EXPECT_LT(relative_difference(r_parallel.moment, r_serial.moment), 1e-10);
  EXPECT_NEAR(r_parallel.force.z() / beam.force, 1, 1e-9);
  if (root())
    std::printf("  %u processes, %zu dofs: tip mean %.10e m (serial %.10e), rotation %.10e rad "
                "(serial %.10e, independent %.10e, beam %.6e); direct %.3f s, %s %u its %.3f s\n",
                dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD), body.parallel->n_dofs(),
                -mean_parallel.z(), -mean_serial.z(), psi_parallel, psi_serial, psi_independent,
                beam.tip_rotation(), body.parallel->statistics().last_direct_seconds,
                body.parallel->statistics().iterative_method.c_str(),
                body.parallel->statistics().last_iterations,
                body.parallel->statistics().last_iterative_seconds);
}

TEST(ElasticBodyParallel, PatchLoadSameAsSerialAndVtu)
{
  // 40 x 40 x 20 mm block clamped below, a 1 kN oblique force on a 5 mm patch on top.
  const Vec3         L(40e-3, 40e-3, 20e-3);
  ElasticBodyOptions o;
  o.degree  = 2;
  o.material = steel;
  o.clamped = {4};
  TwoWays           body(*block(L, 8, 8, 4), o);
  const PatchForce  load{{5, Vec3(17e-3, 22e-3, L.z()), 5e-3}, Vec3(300, -200, -1000)};
  const auto        f_parallel = body.parallel->assemble({{}, {load}});
  const auto        f_serial   = body.serial->assemble({{}, {load}});
  const auto        u_parallel = body.parallel->solve_direct(f_parallel);
  const auto        u_serial   = body.serial->solve_direct(f_serial);
  const Wrench      r = body.parallel->reaction(u_parallel, f_parallel, 4, load.patch.centre);
  EXPECT_LT((r.force + load.force).norm(), 1e-12 * load.force.norm());
  const Vec3 mean_parallel = body.parallel->patch_average(u_parallel, load.patch);
  const Vec3 mean_serial   = body.serial->patch_average(u_serial, load.patch);
  EXPECT_LT(relative_difference(mean_parallel, mean_serial), 1e-10);
  EXPECT_NEAR((f_parallel.nodal * u_parallel) / load.force.dot(mean_parallel), 1, 1e-12);
  EXPECT_NEAR(body.parallel->patch_area(load.patch) / body.serial->patch_area(load.patch), 1,
              1e-14);

  const auto dir = shared_directory("elastic-body-vtu");
  if (root())
    std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string written = body.parallel->write_vtu(u_parallel, dir.string(), "block");
  const unsigned    size    = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  std::size_t       files   = 0;
  for (const auto &entry : std::filesystem::directory_iterator(dir))
    {
      ++files;
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
      EXPECT_GT(std::filesystem::file_size(entry.path()), 0u) << entry.path();
    }
  EXPECT_EQ(files, size == 1 ? 1u : size + 1);
  EXPECT_TRUE(std::filesystem::exists(written)) << written;
  MPI_Barrier(MPI_COMM_WORLD);
  if (root())
    std::filesystem::remove_all(dir);
  // A directory that does not exist: an error on every rank, nothing written.
  EXPECT_THROW(body.parallel->write_vtu(u_parallel, (dir / "missing").string(), "block"),
               InputError);
  if (root())
    std::printf("  %u processes, %zu cells, %zu dofs: patch mean (%.6e %.6e %.6e) m, serial "
                "difference %.2e, reaction + F %.2e N\n",
                size, body.parallel->n_cells(), body.parallel->n_dofs(), mean_parallel.x(),
                mean_parallel.y(), mean_parallel.z(),
                relative_difference(mean_parallel, mean_serial), (r.force + load.force).norm());
}

// Reference mode on the Hertz line contact (two cylinder slices, plane strain): half-width and
// peak pressure against the exact solution for a sequence of element sizes at the contact, with
// the observed convergence rate. usage: bench_hertz_convergence [degree = 2]
#include "base/blas_kernels.h"
#include "stiffness/hertz_reference.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace gearkit;

int
main(int argc, char **argv)
{
  gearkit::use_fitting_blas_kernels(argv); // before MPI: may run the program again
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const int                                degree = argc > 1 ? std::atoi(argv[1]) : 2;
  std::filesystem::create_directories("/tmp/gearkit-bench-hertz");
  std::printf(
      "| a / h | cells | dofs | a error | p0 error | time [s] |\n|---|---|---|---|---|---|\n");
  double previous = 0;
  for (int k : {4, 8, 16})
    {
      HertzCase c;
      c.degree             = degree;
      c.element_size       = c.half_width / k;
      const HertzResult r  = solve_hertz_reference(c, "/tmp/gearkit-bench-hertz");
      const double      ea = r.half_width / c.half_width - 1,
                   ep      = r.peak_pressure / r.exact_peak_pressure - 1;
      std::printf("| %d | %d | %zu | %+.2f %% | %+.2f %% | %.1f |", k, r.cells, r.dofs, 100 * ea,
                  100 * ep, r.seconds);
      if (previous > 0)
        std::printf(" rate %.2f", std::log2(previous / std::abs(ep)));
      std::printf("\n");
      previous = std::abs(ep);
    }
}

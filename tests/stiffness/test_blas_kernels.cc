// OpenBLAS's kernels in a process whose main asked for fitting ones (mpi_gtest_main.cc, as the
// gearkit executable does): not the generic fallback where the processor runs better ones, and
// right on this processor (a product in every transpose against a plain loop); one BLAS thread
// inside jobs on threads of the program's own.
#include "base/blas_kernels.h"
#include "base/parallel.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <dlfcn.h>
#include <random>
#include <vector>

using namespace gearkit;

TEST(BlasKernels, FittingKernelsUnlessTheEnvironmentChoseOthers)
{
  const std::string core = blas_core_name();
  ASSERT_FALSE(core.empty()) << "the BLAS is not OpenBLAS (packages.txt installs it)";
  // kept: a setting of the user's or the machine's; else OpenBLAS's own choice must fit
  if (!std::getenv("OPENBLAS_CORETYPE"))
    {
      EXPECT_EQ(fitting_blas_core(core), "") << "OpenBLAS runs its " << core << " kernels";
    }
  EXPECT_EQ(fitting_blas_core("Haswell"), ""); // only a fallback is replaced
  EXPECT_EQ(fitting_blas_core("SkylakeX"), "");
  std::printf("OpenBLAS kernels: %s (OPENBLAS_CORETYPE %s)\n", core.c_str(),
              std::getenv("OPENBLAS_CORETYPE") ? std::getenv("OPENBLAS_CORETYPE") : "not set");
}

TEST(BlasKernels, ProductsAgreeWithAPlainLoop)
{
  using Dgemm      = void (*)(const char *, const char *, const int *, const int *, const int *,
                         const double *, const double *, const int *, const double *, const int *,
                         const double *, double *, const int *);
  const auto dgemm = reinterpret_cast<Dgemm>(dlsym(RTLD_DEFAULT, "dgemm_"));
  ASSERT_NE(dgemm, nullptr);
  std::mt19937                           random(17);
  std::uniform_real_distribution<double> value(-1, 1);
  // odd sizes: the kernels' edge cases; small ones take OpenBLAS's small-matrix paths
  for (const auto &[m, n, k] :
       std::vector<std::array<int, 3>>{{{157, 93, 211}}, {{7, 5, 3}}, {{64, 1, 33}}})
    for (const char ta : {'N', 'T'})
      for (const char tb : {'N', 'T'})
        {
          const int           lda = ta == 'N' ? m : k, ldb = tb == 'N' ? k : n;
          std::vector<double> a(std::size_t(lda) * (ta == 'N' ? k : m)),
              b(std::size_t(ldb) * (tb == 'N' ? n : k)), c(std::size_t(m) * n);
          for (std::vector<double> *v : {&a, &b, &c})
            for (double &x : *v)
              x = value(random);
          std::vector<double> expected(c);
          const double        alpha = 1.5, beta = -0.5;
          for (int i = 0; i < m; ++i)
            for (int j = 0; j < n; ++j)
              {
                double sum = 0;
                for (int l = 0; l < k; ++l)
                  sum += (ta == 'N' ? a[i + std::size_t(l) * lda] : a[l + std::size_t(i) * lda]) *
                         (tb == 'N' ? b[l + std::size_t(j) * ldb] : b[j + std::size_t(l) * ldb]);
                expected[i + std::size_t(j) * m] = alpha * sum + beta * c[i + std::size_t(j) * m];
              }
          dgemm(&ta, &tb, &m, &n, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &m);
          double worst = 0;
          for (std::size_t i = 0; i < c.size(); ++i)
            worst = std::max(worst, std::abs(c[i] - expected[i]));
          EXPECT_LT(worst, 1e-12 * k) << m << " x " << n << " x " << k << " " << ta << tb;
        }
}

TEST(BlasKernels, OneBlasThreadInsideJobsOnThreadsThenAsBefore)
{
  ASSERT_FALSE(blas_core_name().empty()) << "the BLAS is not OpenBLAS";
  const int before = blas_threads();
  set_blas_threads(2);
  ASSERT_EQ(blas_threads(), 2);
  std::vector<int> inside(6, 0);
  parallel_for(inside.size(), 2, [&](std::size_t i) { inside[i] = blas_threads(); });
  EXPECT_EQ(inside, std::vector<int>(6, 1)); // two threads of ours, one of OpenBLAS's each
  EXPECT_EQ(blas_threads(), 2);              // restored
  parallel_for(inside.size(), 1, [&](std::size_t i) { inside[i] = blas_threads(); });
  EXPECT_EQ(inside, std::vector<int>(6, 2)); // on the calling thread alone: unchanged
  int in_task = 0;
  parallel_for_beside([&] { in_task = blas_threads(); }, inside.size(), 2, [] { return 0; },
                      [&](int, std::size_t i) { inside[i] = blas_threads(); });
  EXPECT_EQ(in_task, 1); // a task beside jobs on threads: one OpenBLAS thread too
  EXPECT_EQ(inside, std::vector<int>(6, 1));
  EXPECT_EQ(blas_threads(), 2);
  {
    const BlasThreads one(1);
    EXPECT_EQ(blas_threads(), 1);
  }
  EXPECT_EQ(blas_threads(), 2);
  set_blas_threads(before);
}

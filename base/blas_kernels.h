// OpenBLAS's kernels for the processor it runs on. OpenBLAS picks them at load time from the
// processor's model; Debian 12's OpenBLAS 0.3.21 does not know models newer than it (an Intel
// Emerald Rapids, family 6 model 207, say) and falls back to its generic Prescott (SSE3) kernels,
// whose dgemm runs at a fifth of the AVX-512 kernels' speed on such a processor: the direct
// solver's dense fronts, and so every finite-element stage, run up to twice as long
// (bench/README.md, "The BLAS kernels").
#pragma once

#include <string>

namespace gearkit
{
/// The kernels OpenBLAS uses in this process ("SkylakeX", "Haswell", "Prescott", ...); empty
/// where the BLAS is not OpenBLAS.
std::string
blas_core_name();

/// OpenBLAS's threads in this process (nothing where the BLAS is not OpenBLAS).
void
set_blas_threads(int threads);

/// OpenBLAS's threads in this process (1 where the BLAS is not OpenBLAS).
int
blas_threads();

/// While it lives, OpenBLAS runs on the given number of threads; then on as many as before.
/// One for jobs side by side on threads of the program's own (parallel_for): their BLAS calls
/// would otherwise queue for the one pool of BLAS threads, the waiting threads spinning.
class BlasThreads
{
public:
  explicit BlasThreads(int threads);
  ~BlasThreads();
  BlasThreads(const BlasThreads &) = delete;
  BlasThreads &
  operator=(const BlasThreads &) = delete;

private:
  int previous;
};

/// The kernels that suit this processor where OpenBLAS fell back to Prescott: "SkylakeX" with
/// AVX-512 (F, CD, BW, DQ, VL), "Haswell" with AVX2 and FMA, else empty (keep OpenBLAS's choice).
std::string
fitting_blas_core(const std::string &chosen);

/// Call first in main, before MPI starts: where OpenBLAS fell back to Prescott on a processor
/// that runs better kernels and OPENBLAS_CORETYPE is not set (a setting of the user's or the
/// machine's is always kept), runs the program again in the same process (exec) with
/// OPENBLAS_CORETYPE naming them; else, or where that fails, returns and nothing changes.
/// Results do not depend on the kernels beyond rounding.
void
use_fitting_blas_kernels(char **argv);
} // namespace gearkit

#include "base/blas_kernels.h"

#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <unistd.h>

namespace gearkit
{
std::string
blas_core_name()
{
  using CoreName   = char *(*)();
  const auto  name = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  const char *core = name ? name() : nullptr;
  return core ? core : "";
}

void
set_blas_threads(int threads)
{
  using SetThreads = void (*)(int);
  if (const auto set =
          reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
    set(threads);
}

int
blas_threads()
{
  using GetThreads = int (*)();
  const auto get   = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : 1;
}

BlasThreads::BlasThreads(int threads)
    : previous(blas_threads())
{
  if (threads != previous)
    set_blas_threads(threads);
}

BlasThreads::~BlasThreads()
{
  if (blas_threads() != previous)
    set_blas_threads(previous);
}

std::string
fitting_blas_core(const std::string &chosen)
{
  if (chosen != "Prescott")
    return "";
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    return "Haswell";
  return "";
}

void
use_fitting_blas_kernels(char **argv)
{
  if (std::getenv("OPENBLAS_CORETYPE"))
    return;
  // under valgrind the program run again would run without it
  if (const char *preload = std::getenv("LD_PRELOAD"); preload && std::strstr(preload, "vgpreload"))
    return;
  const std::string core = fitting_blas_core(blas_core_name());
  if (core.empty() || setenv("OPENBLAS_CORETYPE", core.c_str(), 1) != 0)
    return;
  execv("/proc/self/exe", argv);
  unsetenv("OPENBLAS_CORETYPE"); // exec failed: go on with OpenBLAS's choice
}
} // namespace gearkit

#!/usr/bin/env bash
# scripts/fuzz.sh [seconds] — fuzz the input readers with libFuzzer (clang from Debian).
#
# Builds the targets of tests/fuzz in build-fuzz/ (clang, -O1 -g, GEARKIT_FUZZ=ON: libFuzzer,
# AddressSanitizer, UndefinedBehaviorSanitizer) and runs each for `seconds` (default 60), one
# after the other:
#   fuzz_cmm    CMM point files and flank topography files (geometry/measured_flank.h)
#   fuzz_scene  scene files (gearkit::read_scene, driver/scene.h)
#   fuzz_cache  stage cache files and their digest records (gearkit::cache_file_problem,
#               driver/cache.h)
# Every input must end normally or with gearkit::InputError. Anything else (another exception, a
# crash, a sanitizer report, an input running longer than 10 s, more than 2 GB) is a finding: its
# input lands in build-fuzz/findings/<target>/, and the run goes on (fork mode, -ignore_crashes)
# so that one known finding does not end it. Seeds come from tests/fuzz/corpus/<target>/ (read
# only); what the fuzzer adds goes to build-fuzz/corpus/<target>/ and is reused by the next run.
# Log per target: build-fuzz/fuzz_<target>.log. Exit status 1 when a target has findings.
#
# Environment: JOBS (build jobs, default nproc), FUZZ_TARGETS (default "fuzz_cmm fuzz_scene fuzz_cache").
# CI does not run this script; it installs its own packages (clang, libFuzzer and the sanitizer
# runtimes) when they are missing.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
build=$top/build-fuzz
targets=${FUZZ_TARGETS:-fuzz_cmm fuzz_scene fuzz_cache}

# clang-14 and libclang-rt-14-dev (libFuzzer, ASan and UBSan runtimes) on Debian bookworm; the
# project's own packages (packages.txt) are assumed present (./test or ./run installs them).
"$top/scripts/install_packages.sh" clang-14 libclang-rt-14-dev

# Release as far as deal.II's set-up macro is concerned (it knows only Debug and Release), but
# -O1 -g without NDEBUG: assertions stay on, and reports have line numbers.
cmake -S "$top" -B "$build" -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O1 -g" -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g" \
  -DGEARKIT_FUZZ=ON >/dev/null
# shellcheck disable=SC2086
cmake --build "$build" --parallel "${JOBS:-$(nproc 2>/dev/null || echo 2)}" --target $targets

# The scene dictionary from the reader's own declarations (subsections, entries, selections), so
# that it follows driver/scene*.cc, plus the syntax and boundary numbers (as in tests/fuzz/cmm.dict),
# and what the pre-reader (driver/scene_text.cc) normalises or refuses: keyword case, include and
# the target's file marker "#=== <name>" (tests/fuzz/fuzz_scene.cc), CR, byte-order marks, line
# continuation, JSON and XML with deal.II's mangled names.
{
  printf '"subsection "\n"set "\n"end"\n" = "\n"true"\n"false"\n", "\n"\\x0a"\n"#"\n'
  printf '"SUBSECTION "\n"SET "\n"END"\n"Subsection "\n"include "\n"INCLUDE "\n"\\x0d"\n"\\x09"\n'
  printf '"\\\\\\x0a"\n"\\xef\\xbb\\xbf"\n"\\xff\\xfe"\n"\\x0a#=== a.prm\\x0a"\n"\\x0a#=== fuzz.prm\\x0a"\n'
  printf '"include a.prm"\n"include fuzz.prm"\n"{"\n"}"\n"\\"value\\""\n"\\"alias\\""\n"_20"\n"_5f"\n"_"\n'
  printf '"<ParameterHandler>"\n"</ParameterHandler>"\n"<value>"\n"<!--"\n"-->"\n"[]"\n'
  printf '"%s"\n' 0 -1 1e308 1e-320 nan inf 2147483647 2147483648 100000
  grep -ohE '(declare_entry|enter_subsection)\("[^"]*"' "$top"/driver/scene*.cc |
    sed -E 's/^[a-z_]+\(//'
  grep -ohE 'Patterns::Selection\("[^"]*"' "$top"/driver/scene*.cc |
    sed -E 's/^Patterns::Selection\("//; s/"$//' | tr '|' '\n' | sed 's/.*/"&"/'
  for w in mass "axial inertia" "transverse inertia" "bearing positions"; do
    printf '"pinion %s"\n"gear %s"\n' "$w" "$w"
  done
} | sort -u >"$build/scene.dict"

declare -A max_len=([fuzz_cmm]=4096 [fuzz_scene]=20000 [fuzz_cache]=262144)
declare -A dict=([fuzz_cmm]="$top/tests/fuzz/cmm.dict" [fuzz_scene]="$build/scene.dict"
  [fuzz_cache]="$top/tests/fuzz/cache.dict")
# Every report fatal and symbolised; UBSan's with a stack.
export ASAN_OPTIONS=${ASAN_OPTIONS:-symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TMPDIR=$build/tmp # the scene target's temporary files
status=0
summary=()
for target in $targets; do
  name=${target#fuzz_}
  corpus=$build/corpus/$name findings=$build/findings/$name log=$build/fuzz_$name.log
  mkdir -p "$corpus" "$findings" "$TMPDIR"
  echo "fuzz: $target for $seconds s (log: $log)"
  start=$(date +%s)
  # Fork mode with one job: a crash, timeout or OOM ends only the child; the parent saves the
  # input and starts the next child.
  "$build/$target" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="${max_len[$target]}" \
    -dict="${dict[$target]}" -artifact_prefix="$findings/" -print_funcs=0 \
    "$corpus" "$top/tests/fuzz/corpus/$name" >"$log" 2>&1 || true
  elapsed=$(($(date +%s) - start))
  last=$(grep -E '^#[0-9]+: cov:' "$log" | tail -n 1 || true)
  execs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$last")
  cov=$(sed -nE 's/.* cov: ([0-9]+) ft: ([0-9]+) .*/\1 edges, \2 features/p' <<<"$last")
  counts=$(sed -nE 's#.*oom/timeout/crash: ([0-9/]+).*#\1#p' <<<"$last")
  files=$(find "$findings" -type f | wc -l)
  ((files == 0)) || status=1
  summary+=("$target: ${elapsed} s, ${execs:-?} executions, coverage ${cov:-?}, corpus $(find "$corpus" -type f | wc -l) files (+ $(find "$top/tests/fuzz/corpus/$name" -type f | wc -l) seeds), oom/timeout/crash ${counts:-?}, findings in $findings: $files")
  rm -rf "${TMPDIR:?}"/gearkit-fuzz-*
done
printf '%s\n' "${summary[@]}"
exit $status

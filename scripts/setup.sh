#!/usr/bin/env bash
# Shared set-up for ./run and ./test: install the Debian packages listed in packages.txt that are
# missing (apt, through sudo when not root; nothing is touched when all are present), then
# configure and build into build/ (Release unless CMAKE_BUILD_TYPE is set).
#   scripts/setup.sh           the gearkit executable and the Python module (./run)
#   scripts/setup.sh --tests   also packages-tests.txt (the report's browser check) and every
#                              target of `all`: the tests (./test; not the benchmarks)
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

lists=("$top/packages.txt") targets=(--target gearkit --target gearkit_python)
if [[ "${1:-}" == "--tests" ]]; then
  lists+=("$top/packages-tests.txt") targets=()
fi
packages=()
for list in "${lists[@]}"; do
  while read -r pkg; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    packages+=("$pkg")
  done < "$list"
done
"$top/scripts/install_packages.sh" "${packages[@]}"

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$top" -B "$top/build" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" >/dev/null
cmake --build "$top/build" --parallel "$jobs" "${targets[@]}"

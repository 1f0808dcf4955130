#!/usr/bin/env bash
# scripts/install_packages.sh PKG... — installs those of the named Debian packages that are
# missing (apt, through sudo when not root); touches nothing when all are present. Used by
# setup.sh (packages.txt) and fuzz.sh (clang and its fuzzer runtimes).
set -euo pipefail
missing=()
for pkg in "$@"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done
if ((${#missing[@]})); then
  echo "gearkit: installing missing Debian packages: ${missing[*]}"
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

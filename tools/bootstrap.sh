#!/usr/bin/env bash
# Install what rollsense needs from Debian 12's archive (when missing) and
# build it into ./build. Idempotent: a second run only rebuilds what changed.
#   tools/bootstrap.sh            install + build
#   ROLLSENSE_NO_APT=1 ...        build only (dependencies already installed)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config liblua5.4-dev libeigen3-dev libgpiod-dev libmodbus-dev
          libboost-dev catch2 zlib1g-dev python3 python3-sklearn python3-numpy chromium
          clang)  # clang: the libFuzzer harnesses of .ci/run and tools/fuzz.sh

if [[ -z "${ROLLSENSE_NO_APT:-}" ]]; then
  missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "bootstrap: installing ${missing[*]}" >&2
    if [[ $(id -u) -ne 0 ]]; then sudo=sudo; else sudo=; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$jobs"

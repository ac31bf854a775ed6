#!/usr/bin/env bash
# Runs a test program that needs Debian's chromium (ctest live_view_chromium):
# installs the package when it is missing and this is root with apt-get, and
# exits 77 (ctest: skipped) with the reason only where it cannot be installed.
#   bash tests/live/with_chromium.sh TEST_PROGRAM [ARGS...]
set -euo pipefail
chromium=$(command -v chromium || true)
if [[ -z $chromium ]]; then
  if [[ $(id -u) -ne 0 ]] || ! command -v apt-get >/dev/null; then
    echo "SKIPPED: chromium is not installed and cannot be installed here (not root, or no apt-get): apt-get install chromium"
    exit 77
  fi
  echo "installing Debian's chromium for the live view's test"
  if ! DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium >/dev/null; then
    apt-get update -qq >/dev/null || true
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium >/dev/null ||
      { echo "SKIPPED: chromium is not installed and apt-get could not install it (see above)"; exit 77; }
  fi
  chromium=$(command -v chromium)
fi
export ROLLSENSE_CHROMIUM=$chromium
exec "$@"

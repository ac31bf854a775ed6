#!/usr/bin/env bash
# The stock experiment on etroll-virtual (1,350 trials: the whole Dynamixel
# stack on emulated servos, virtual clock, with the stock analysis) recorded by
# this build and by a reference build (the previous main), side by side in one
# script; prints both wall times and their ratio, and whether the datasets
# (trials/, manifest.csv, dataset-info.csv, features.csv) are byte-identical.
#   bench/dynamixel/virtual_rig.sh REFERENCE-BUILD-DIR [build-dir] [repeats] [seed]
# e.g. bench/dynamixel/virtual_rig.sh /work/prev-main/build build 1
# The reference gets a 1 s reply timeout (devices.hand.params.timeout_ms=1000):
# before issue 25 the in-process emulator answered from a polling thread, and on a
# loaded machine a 30 ms timeout could end its run; the timeout changes no data.
set -euo pipefail
reference=${1:?usage: virtual_rig.sh REFERENCE-BUILD-DIR [build-dir] [repeats] [seed]}
build=${2:-build}
repeats=${3:-1}
seed=${4:-11}
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/same_dataset.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
now() { date +%s.%N; }
# The stock script of the source tree BUILD was configured from (an older build may
# lack a call today's script makes); this tree's if its CMakeCache.txt does not say.
stock_script() {
  local src
  src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$1/CMakeCache.txt" 2>/dev/null || true)
  if [ -n "$src" ] && [ -f "$src/scripts/paper_experiment.lua" ]; then echo "$src/scripts/paper_experiment.lua"
  else echo "$root/scripts/paper_experiment.lua"; fi
}
run() {  # BUILD OUT [extra args]: prints the wall time in s
  local bin=$1/bin/rollsense dir=$2 script
  script=$(stock_script "$1")
  shift 2
  local start
  start=$(now)
  "$bin" run "$script" --profile etroll-virtual --seed "$seed" -q --no-progress \
    --out "$dir" "$@" 2>"$dir.log" || { echo "$bin failed, see below" >&2; cat "$dir.log" >&2; exit 1; }
  awk -v a="$(now)" -v b="$start" 'BEGIN { printf "%.2f", a - b }'
}

for i in $(seq 1 "$repeats"); do
  ref=$(run "$reference" "$out/ref$i" --set devices.hand.params.timeout_ms=1000)
  new=$(run "$build" "$out/new$i")
  # A reference from before a deliberate change of the recorded data (the
  # simulation's calibration) records different data: then it times similar,
  # not identical, work, and says so.
  same="dataset byte-identical"
  same_dataset "$out/ref$i" "$out/new$i" || same="datasets DIFFER (a reference from before a deliberate data change)"
  trials=$(($(wc -l <"$out/new$i/manifest.csv") - 1))
  awk -v r="$ref" -v n="$new" -v t="$trials" -v i="$i" -v cores="$(nproc)" -v same="$same" 'BEGIN {
    printf "run %d: %d trials on etroll-virtual: reference %.1f s, this build %.1f s = %.2fx the reference'"'"'s time (%.1fx faster) on %d cores; %s\n",
      i, t, r, n, n / r, r / n, cores, same }'
  rm -rf "$out"/ref$i "$out"/new$i
done

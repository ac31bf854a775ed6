#!/usr/bin/env bash
# Times the whole stock experiment (1,350 simulated trials, recording and the
# durable dataset writes included, analysis off) and prints trials per second
# and the ratio to the robot time the run stands for.
#   bench/experiment/stock_experiment.sh [build-dir] [repeats]
set -euo pipefail
build=${1:-build}
repeats=${2:-3}
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq 1 "$repeats"); do
  start=$(date +%s.%N)
  "$build/bin/rollsense" run "$root/scripts/paper_experiment.lua" --set analyse=false --out "$out/run$i" -q \
    2> "$out/log$i"
  end=$(date +%s.%N)
  robot=$(awk -F, '$1=="run_time_s"{print $2}' "$out/run$i/run-info.csv")
  trials=$(($(wc -l < "$out/run$i/manifest.csv") - 1))
  awk -v s="$start" -v e="$end" -v r="$robot" -v n="$trials" -v i="$i" 'BEGIN {
    w = e - s; printf "run %d: %d trials in %.2f s wall = %.0f trials/s; %.0f s of robot time = %.0fx real time\n",
    i, n, w, n / w, r, r / w }'
done

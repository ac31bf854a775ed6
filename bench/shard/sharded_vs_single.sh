#!/usr/bin/env bash
# The stock experiment (1,350 simulated trials) recorded by one process and by
# N shards running side by side plus their merge, in the same script on the
# same machine; prints both times and their ratio, and checks the merged
# dataset is byte-identical to the single run (docs/cluster.md).
#   bench/shard/sharded_vs_single.sh [build-dir] [shards] [repeats]
# Both sides stop where the dataset and its features are on disk: the single
# run records with analysis off, then `rollsense features`; the sharded side
# records N shards in parallel, then `rollsense merge` (which extracts the
# same features). The whole-run analysis after it is the same for both.
set -euo pipefail
build=${1:-build}
shards=${2:-4}
repeats=${3:-3}
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/same_dataset.sh"
rollsense=$build/bin/rollsense
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
now() { date +%s.%N; }
minus() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a - b }'; }
experiment=("$root/scripts/paper_experiment.lua" --seed 11 -q --no-progress)

for i in $(seq 1 "$repeats"); do
  start=$(now)
  "$rollsense" run "${experiment[@]}" --set analyse=false --out "$out/single$i" 2>"$out/single$i.log"
  "$rollsense" features "$out/single$i" -o "$out/single$i/features.csv" >/dev/null
  single=$(minus "$(now)" "$start")

  start=$(now)
  pids=()
  for ((k = 0; k < shards; k++)); do
    "$rollsense" run "${experiment[@]}" --shard "$k/$shards" --out "$out/shard$i-$k" 2>"$out/shard$i-$k.log" &
    pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid"; done
  recorded=$(now)
  dirs=()
  for ((k = 0; k < shards; k++)); do dirs+=("$out/shard$i-$k"); done
  "$rollsense" merge "$out/merged$i" "${dirs[@]}" >/dev/null
  end=$(now)
  sharded=$(minus "$end" "$start")
  merge=$(minus "$end" "$recorded")

  same_dataset "$out/single$i" "$out/merged$i" || { echo "run $i: the merged dataset differs from the single run" >&2; exit 1; }
  trials=$(($(wc -l <"$out/merged$i/manifest.csv") - 1))
  awk -v s="$single" -v p="$sharded" -v m="$merge" -v n="$shards" -v t="$trials" -v i="$i" -v cores="$(nproc)" 'BEGIN {
    printf "run %d: %d trials; single process %.2f s; %d shards in parallel + merge %.2f s (merge %.2f s) = %.2fx the single run'"'"'s time on %d cores; merged dataset byte-identical\n",
      i, t, s, n, p, m, p / s, cores }'
  rm -rf "$out"/single$i "$out"/shard$i-* "$out"/merged$i
done

#!/usr/bin/env bash
# Times the user-facing stages of this build against another commit's build on
# the same machine in the same run, interleaved (base, new, new, base, ...) so
# both sides see the same load, and prints medians and the ratio new/base:
#   stock run        scripts/paper_experiment.lua on the sim, record only
#   stock + analysis the same with its analysis (features, 10 x 5-fold CV, model, report)
#   features         `rollsense features DS` on a recorded stock dataset
#   evaluate         `rollsense evaluate DS` (bagged trees, 10 x 5-fold CV)
# A ratio below 1 is faster than the base. Asserts nothing.
#
#   bench/layers/compare_to_base.sh BASE_REV [repeats=5] [build-dir=build]
#
# The base is built once into a worktree under ${TMPDIR:-/tmp} (tests and
# benchmarks off) and reused by later calls with the same revision.
set -euo pipefail
base_rev=${1:?usage: compare_to_base.sh BASE_REV [repeats] [build-dir]}
repeats=${2:-5}
root=$(cd "$(dirname "$0")/../.." && pwd)
new_build=$(cd "${3:-$root/build}" && pwd)
base_sha=$(git -C "$root" rev-parse --short "$base_rev")
base_tree=${TMPDIR:-/tmp}/rollsense-bench-base-$base_sha
if [[ ! -x $base_tree/build/bin/rollsense ]]; then
  echo "building base $base_sha in $base_tree (once)" >&2
  git -C "$root" worktree add --force --detach "$base_tree" "$base_sha" >/dev/null 2>&1 || true
  cmake -S "$base_tree" -B "$base_tree/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DROLLSENSE_BUILD_TESTS=OFF -DROLLSENSE_BUILD_BENCH=OFF >/dev/null
  cmake --build "$base_tree/build" -j"$(nproc)" >/dev/null
fi
declare -A bin=([base]=$base_tree/build/bin/rollsense [new]=$new_build/bin/rollsense)
declare -A scripts=([base]=$base_tree/scripts [new]=$root/scripts)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# One dataset both sides read (the formats are the same before and after).
"${bin[new]}" run "${scripts[new]}/paper_experiment.lua" --seed 11 --set analyse=false --out "$work/ds" -q 2>/dev/null

seconds() {  # "wall cpu" seconds a command takes (cpu = user + system), its output discarded
  local TIMEFORMAT='%R %U %S' t
  t=$({ time "$@" >/dev/null 2>&1; } 2>&1)
  awk '{ printf "%.4f %.4f\n", $1, $2 + $3 }' <<< "$t"
}

stages=(stock_record stock_full features evaluate)
run_stage() {  # side stage round
  local side=$1 stage=$2 i=$3 b=${bin[$1]} s=${scripts[$1]}
  case $stage in
    stock_record) seconds "$b" run "$s/paper_experiment.lua" --seed 11 --set analyse=false --out "$work/$side-r$i" -q ;;
    stock_full) seconds "$b" run "$s/paper_experiment.lua" --seed 11 --out "$work/$side-f$i" -q ;;
    features) seconds "$b" features "$work/ds" -o "$work/$side-features-$i.csv" ;;
    evaluate) seconds "$b" evaluate "$work/ds" ;;
  esac
}

for i in $(seq 1 "$repeats"); do
  if ((i % 2)); then order=(base new); else order=(new base); fi
  for stage in "${stages[@]}"; do
    for side in "${order[@]}"; do
      echo "$stage $side $(run_stage "$side" "$stage" "$i")" >> "$work/times"
    done
  done
done
# Same seed, same bytes: the recorded datasets and features of both sides must agree.
if cmp -s "$work/base-r1/manifest.csv" "$work/new-r1/manifest.csv" &&
   diff -rq "$work/base-r1/trials" "$work/new-r1/trials" >/dev/null &&
   cmp -s "$work/base-f1/features.csv" "$work/new-f1/features.csv"; then
  identical="yes"
else
  identical="NO"
fi

median() {  # stage side column
  awk -v s="$1" -v d="$2" -v c="$3" '$1==s && $2==d {print $c}' "$work/times" | sort -g |
    awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'
}
echo "base $base_sha vs this build, $repeats interleaved rounds, medians (s); CPU = user + system,"
echo "the steadier figure on a shared machine:"
printf '  %-14s %9s %9s %8s   %9s %9s %8s\n' stage "wall base" new new/base "cpu base" new new/base
for stage in "${stages[@]}"; do
  awk -v s="$stage" -v bw="$(median "$stage" base 3)" -v nw="$(median "$stage" new 3)" \
      -v bc="$(median "$stage" base 4)" -v nc="$(median "$stage" new 4)" \
      'BEGIN { printf "  %-14s %9.3f %9.3f %8.2f   %9.3f %9.3f %8.2f\n", s, bw, nw, nw / bw, bc, nc, nc / bc }'
done
echo "stock dataset, manifest and features byte-identical between the two: $identical"

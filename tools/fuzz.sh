#!/usr/bin/env bash
# Build the libFuzzer harnesses (fuzz/, clang, ASan+UBSan) into ./build-fuzz
# and run each one for SECONDS (default 60), niced, as many at once as there
# are cores (ROLLSENSE_FUZZ_JOBS to change it): each harness is one process on
# one core, so a core per harness gives each the time it is given.
#   tools/fuzz.sh                 60 s per harness (~5 minutes on 2 cores)
#   tools/fuzz.sh 600             a longer run
#   tools/fuzz.sh 20 fuzz_catalogue fuzz_manifest   only these harnesses
# The committed seed corpus (fuzz/corpus/<harness>) is copied into
# build-fuzz/fuzz/work/<harness> (kept between runs, so coverage accumulates);
# a finding is written to build-fuzz/fuzz/findings/ and makes the script fail.
# Prints the executions per harness and in total. docs/fuzzing.md has more.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
shift || true
if ! [[ $seconds =~ ^[0-9]+$ ]] || ((seconds < 1)); then
  echo "usage: tools/fuzz.sh [seconds-per-harness] [harness...]" >&2
  exit 2
fi
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found: apt-get install -y clang" >&2; exit 2; }

export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROLLSENSE_BUILD_FUZZ=ON \
  -DROLLSENSE_BUILD_TESTS=OFF -DROLLSENSE_BUILD_BENCH=OFF >/dev/null
nice cmake --build build-fuzz --target rollsense_fuzzers -j"$(nproc 2>/dev/null || echo 2)"

harnesses=("$@")
if ((${#harnesses[@]} == 0)); then
  for d in fuzz/corpus/*/; do harnesses+=("$(basename "$d")"); done
fi

findings=build-fuzz/fuzz/findings
mkdir -p "$findings"
# One harness, its output in build-fuzz/fuzz/<harness>.log, its outcome (ok or
# FINDING) in <harness>.status.
fuzz_one() {
  local h=$1 work=build-fuzz/fuzz/work/$1 log=build-fuzz/fuzz/$1.log status=ok
  mkdir -p "$work"
  cp -n fuzz/corpus/"$h"/* "$work"/ 2>/dev/null || true
  # 2 GiB per process: a parser that tries to allocate more is a finding.
  nice build-fuzz/fuzz/"$h" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$findings/$h-" "$work" >"$log" 2>&1 || status=FINDING
  echo "$status" >build-fuzz/fuzz/"$h".status
}
jobs=${ROLLSENSE_FUZZ_JOBS:-$(nproc 2>/dev/null || echo 2)}
[[ $jobs =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: ROLLSENSE_FUZZ_JOBS=$jobs: give a number of harnesses to run at once, 1 or more" >&2; exit 2; }
running=0
for h in "${harnesses[@]}"; do
  rm -f build-fuzz/fuzz/"$h".status
  if ((running >= jobs)); then
    wait -n || true
    running=$((running - 1))
  fi
  fuzz_one "$h" &
  running=$((running + 1))
done
wait

total=0
failed=()
for h in "${harnesses[@]}"; do
  log=build-fuzz/fuzz/$h.log
  status=$(cat build-fuzz/fuzz/"$h".status 2>/dev/null || echo FINDING)
  [[ $status == ok ]] || failed+=("$h")
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  runs=${runs:-0}
  total=$((total + runs))
  printf '%-30s %12s executions  %s\n' "$h" "$runs" "$status"
done
printf '%-30s %12s executions\n' total "$total"
if ((${#failed[@]})); then
  echo "fuzz.sh: findings in ${failed[*]}: see build-fuzz/fuzz/<harness>.log and $findings/" >&2
  exit 1
fi

#!/usr/bin/env bash
# tools/slurm/submit.sh refuses a bad -n before it needs Slurm or writes
# anything (ctest slurm_submit_usage): -n 1 would make every task --shard 0/1,
# which rollsense run refuses (one shard is the whole run).
#
#   bash tests/slurm/test_submit_usage.sh SOURCE_DIR
set -euo pipefail
src=${1:?usage: test_submit_usage.sh SOURCE_DIR}
work=$(mktemp -d "${TMPDIR:-/tmp}/rollsense-submit.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

fail() { echo "FAILED: $*" >&2; exit 1; }

# expect_refusal N MESSAGE: submit.sh -n N exits 2, says MESSAGE, creates no results folder.
expect_refusal() {
  local rc=0
  bash "$src/tools/slurm/submit.sh" -n "$1" -o "$work/out" "$src/scripts/paper_experiment.lua" --seed 11 \
    >"$work/stdout" 2>"$work/stderr" || rc=$?
  ((rc == 2)) || fail "-n $1: exit $rc, expected 2: $(cat "$work/stderr")"
  grep -qF -- "$2" "$work/stderr" || fail "-n $1: '$2' not in: $(cat "$work/stderr")"
  [[ ! -s $work/stdout ]] || fail "-n $1: printed job ids: $(cat "$work/stdout")"
  [[ ! -e $work/out ]] || fail "-n $1: created $work/out"
}

expect_refusal 1 "submit.sh: -n 1: --shard K/N needs N >= 2; run without --shard for one process"
expect_refusal 0 "a whole number >= 2, got '0'"
expect_refusal x "a whole number >= 2, got 'x'"
echo "submit.sh refuses -n 1, 0 and x"

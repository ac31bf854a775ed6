#!/usr/bin/env bash
# tools/slurm/submit.sh refuses a bad -n before it needs Slurm or writes
# anything (ctest slurm_submit_usage): -n 1 would make every task --shard 0/1,
# which rollsense run refuses (one shard is the whole run).
#
# So are, without Slurm too, the shards' own options among the run options and
# a script rollsense cannot read or parse, and a --set it refuses (review: all
# were submitted, and failed in every queued task); --help is no error.
#
#   bash tests/slurm/test_submit_usage.sh SOURCE_DIR ROLLSENSE
set -euo pipefail
src=${1:?usage: test_submit_usage.sh SOURCE_DIR ROLLSENSE}
rollsense=${2:?usage: test_submit_usage.sh SOURCE_DIR ROLLSENSE}
work=$(mktemp -d "${TMPDIR:-/tmp}/rollsense-submit.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

fail() { echo "FAILED: $*" >&2; exit 1; }

# expect_refusal N SCRIPT MESSAGE [RUN OPTIONS...]: submit.sh -n N ... SCRIPT exits 2, says MESSAGE, creates no
# results folder and submits nothing.
expect_refusal() {
  local rc=0 n=$1 script=$2 message=$3
  shift 3
  bash "$src/tools/slurm/submit.sh" -n "$n" -o "$work/out" --rollsense "$rollsense" "$script" --seed 11 "$@" \
    >"$work/stdout" 2>"$work/stderr" || rc=$?
  ((rc == 2)) || fail "-n $n $*: exit $rc, expected 2: $(cat "$work/stderr")"
  grep -qF -- "$message" "$work/stderr" || fail "-n $n $*: '$message' not in: $(cat "$work/stderr")"
  [[ ! -s $work/stdout ]] || fail "-n $n $*: printed job ids: $(cat "$work/stdout")"
  [[ ! -e $work/out ]] || fail "-n $n $*: created $work/out"
}

stock=$src/scripts/paper_experiment.lua
expect_refusal 1 "$stock" "submit.sh: -n 1: --shard K/N needs N >= 2; run without --shard for one process"
expect_refusal 0 "$stock" "a whole number >= 2, got '0'"
expect_refusal x "$stock" "a whole number >= 2, got 'x'"
expect_refusal 4 "$stock" "submit.sh: --out in the run options: each shard's task sets it" --out "$work/mine"
expect_refusal 4 "$stock" "submit.sh: --shard in the run options" --shard=1/2
expect_refusal 4 "$stock" "submit.sh: --resume in the run options" --resume
expect_refusal 4 "$work/nosuch.lua" "no such script"
printf 'local rs = require "rollsense"\nfunction(\n' >"$work/broken.lua"
expect_refusal 4 "$work/broken.lua" "submit.sh: $work/broken.lua: refused by rollsense (above); nothing submitted"
# A mistyped --set, and a value the script refuses (rollsense run --check).
expect_refusal 4 "$stock" "--set runz: no such setting" --set runz=2
expect_refusal 4 "$stock" "'X9' is not an object of" --set objects=C1,X9
bash "$src/tools/slurm/submit.sh" --help >"$work/stdout" || fail "--help: exit $?"
grep -qF "tools/slurm/submit.sh -n N -o OUT" "$work/stdout" || fail "--help printed no usage: $(cat "$work/stdout")"
echo "submit.sh refuses -n 1, 0 and x, the shards' options, a missing or broken script, a refused --set; --help is no error"

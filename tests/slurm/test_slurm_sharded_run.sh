#!/usr/bin/env bash
# A 4-shard stock experiment through a real Slurm (ctest slurm_sharded_stock_run):
#   1. Slurm and MUNGE from Debian's packages (installed when missing, as root);
#   2. a one-node cluster in a temporary folder (tools/slurm/local-slurm.sh);
#   3. tools/slurm/submit.sh: a job array of 4 shards of scripts/paper_experiment.lua
#      and the merge-and-analyse job that depends on it;
#   4. the merged dataset byte-identical to a single-process run with the same seed:
#      trials/, manifest.csv, dataset-info.csv, features.csv, and the model.rsm the
#      script's analysis trains on it.
# Torn down on every exit (trap). Exit 77 (ctest: skipped) only when the
# packages cannot be installed or the daemons cannot start for want of root.
#
#   bash tests/slurm/test_slurm_sharded_run.sh SOURCE_DIR ROLLSENSE_PROGRAM
set -euo pipefail
src=${1:?usage: test_slurm_sharded_run.sh SOURCE_DIR ROLLSENSE_PROGRAM}
rollsense=${2:?usage: test_slurm_sharded_run.sh SOURCE_DIR ROLLSENSE_PROGRAM}
slurm_tools=$src/tools/slurm
started=$SECONDS

skip() { echo "SKIPPED: $*"; exit 77; }
fail() { echo "FAILED: $*" >&2; exit 1; }

# 1. The packages.
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v sbatch >/dev/null ||
   ! command -v munged >/dev/null; then
  rc=0
  "$slurm_tools/install-slurm.sh" || rc=$?
  if ((rc == 3)); then skip "Slurm and MUNGE are not installed and cannot be installed here (see above)"; fi
  ((rc == 0)) || fail "installing Slurm and MUNGE failed (exit $rc)"
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/rollsense-slurm.XXXXXX")
chmod 711 "$work"  # munged's socket lies below it: every folder above must be searchable
cleanup() {
  "$slurm_tools/local-slurm.sh" down "$work/cluster" || true
  rm -rf -- "$work"
}
trap cleanup EXIT

# 2. The cluster.
if ! "$slurm_tools/local-slurm.sh" up "$work/cluster" >"$work/up.txt"; then
  [[ $(id -u) -ne 0 ]] && skip "the one-node Slurm did not start as $(id -un), not root (slurmd starts jobs as root)"
  fail "the one-node Slurm did not start (its logs are above)"
fi
export SLURM_CONF=$work/cluster/slurm.conf
echo "slurm: one node up after $((SECONDS - started)) s"

# The reference: the same experiment in one process.
experiment=(--seed 11 --set runs=2 -q)
"$rollsense" run "$src/scripts/paper_experiment.lua" "${experiment[@]}" --out "$work/single" --no-progress 2>"$work/single.txt" ||
  { cat "$work/single.txt" >&2; fail "the single-process run failed"; }

# 3. Through Slurm.
submitted=$("$slurm_tools/submit.sh" -n 4 -o "$work/sharded" --rollsense "$rollsense" \
  "$src/scripts/paper_experiment.lua" "${experiment[@]}")
eval "$submitted"
[[ -n ${ROLLSENSE_SHARDS_JOB:-} && -n ${ROLLSENSE_MERGE_JOB:-} ]] || fail "submit.sh printed no job ids: '$submitted'"

job_state() { scontrol show job --oneliner "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 | sort -u | paste -sd, -; }
deadline=$((SECONDS + 600))
while :; do
  state=$(job_state "$ROLLSENSE_MERGE_JOB")
  case $state in
    COMPLETED) break ;;
    PENDING | RUNNING | CONFIGURING | COMPLETING | "") ;;
    *)
      for log in "$work"/sharded/logs/*; do echo "--- $log"; cat "$log"; done >&2
      fail "the merge job $ROLLSENSE_MERGE_JOB ended $state (shards: $(job_state "$ROLLSENSE_SHARDS_JOB"))" ;;
  esac
  ((SECONDS < deadline)) || fail "the merge job $ROLLSENSE_MERGE_JOB is still $state after 600 s"
  sleep 1
done
[[ $(job_state "$ROLLSENSE_SHARDS_JOB") == COMPLETED ]] || fail "array job $ROLLSENSE_SHARDS_JOB: $(job_state "$ROLLSENSE_SHARDS_JOB")"
tasks=$(ls "$work"/sharded/logs/rollsense-shard-*.out | wc -l)
((tasks == 4)) || fail "$tasks array tasks ran, not 4"

# 4. Byte for byte.
merged=$work/sharded/merged
for file in manifest.csv dataset-info.csv features.csv model.rsm; do
  cmp "$work/single/$file" "$merged/$file" || fail "$file of the merged dataset differs from the single-process run's"
done
diff -r "$work/single/trials" "$merged/trials" >/dev/null || fail "trials/ of the merged dataset differ from the single-process run's"
trials=$(($(wc -l <"$merged/manifest.csv") - 1))
shards_listed=$(($(wc -l <"$merged/shards.csv") - 1))
((shards_listed == 4)) || fail "shards.csv lists $shards_listed shards, not 4"
echo "ok: 4 shards (job array $ROLLSENSE_SHARDS_JOB) and the merge-and-analyse job $ROLLSENSE_MERGE_JOB:" \
     "$trials trials, byte-identical to the single-process run; $((SECONDS - started)) s in all"

#!/usr/bin/env bash
# Submit a rollsense run to Slurm as N shards and a merge (docs/cluster.md):
#
#   tools/slurm/submit.sh -n N -o OUT [options] SCRIPT [run options: --seed, --set, --profile ...]
#
#   -n N               shards (N >= 2): one array task each (sbatch --array=0-(N-1))
#   -o OUT             results: OUT/shard-K per shard, OUT/merged the merged and
#                      analysed dataset, OUT/logs the jobs' output
#   --rollsense PATH   the program (default: rollsense on PATH, else this
#                      checkout's build/bin/rollsense)
#   --sbatch OPTION    passed to both sbatch calls (repeatable), e.g.
#                      --sbatch --partition=short --sbatch --time=10
#
# Submits tools/slurm/shard.sbatch as a job array and tools/slurm/merge.sbatch
# with --dependency=afterok on it. Prints on stdout, for scripts:
#   ROLLSENSE_SHARDS_JOB=<array job id>
#   ROLLSENSE_MERGE_JOB=<merge job id>
# Refused before anything is submitted (exit 2): --out, --shard or --resume in
# the run options (each task sets them), a SCRIPT rollsense cannot read or parse,
# and run options it refuses (`rollsense run SCRIPT --check`: a --set the script
# or the profile refuses, a profile that does not load).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
  exit 0
}

n= out= rollsense= sbatch_options=()
while (($#)); do
  case $1 in
    -n) n=${2:?-n needs a number}; shift 2 ;;
    -o) out=${2:?-o needs a folder}; shift 2 ;;
    --rollsense) rollsense=${2:?--rollsense needs a path}; shift 2 ;;
    --sbatch) sbatch_options+=("${2:?--sbatch needs an option}"); shift 2 ;;
    -h|--help) usage ;;
    --) shift; break ;;
    -*) echo "submit.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) break ;;
  esac
done
(($# >= 1)) || { echo "submit.sh: give the SCRIPT to run (see --help)" >&2; exit 2; }
[[ -n $out ]] || { echo "submit.sh: give -o OUT, the results folder" >&2; exit 2; }
if ! [[ $n =~ ^[1-9][0-9]*$ ]]; then
  echo "submit.sh: -n expects the number of shards, a whole number >= 2, got '$n'" >&2
  exit 2
fi
if ((n == 1)); then
  # rollsense run refuses --shard 0/1: one shard is the whole run.
  echo "submit.sh: -n 1: --shard K/N needs N >= 2; run without --shard for one process" \
       "(e.g. sbatch --wrap 'rollsense run SCRIPT --out OUT ...')" >&2
  exit 2
fi
script=$1
shift
# The shards' own options: each task sets them (a second --out would win over the task's: review).
for a in "$@"; do
  case $a in
    --out|--out=*|--shard|--shard=*|--resume)
      echo "submit.sh: ${a%%=*} in the run options: each shard's task sets it (OUT/shard-K, --shard K/N," \
           "--resume when requeued); give the results folder as -o OUT before SCRIPT" >&2
      exit 2 ;;
  esac
done
if [[ -z $rollsense ]]; then
  rollsense=$(command -v rollsense || true)
  [[ -n $rollsense ]] || rollsense=$here/../../build/bin/rollsense
fi
[[ -x $rollsense ]] || { echo "submit.sh: no rollsense program at '$rollsense'; give --rollsense PATH" >&2; exit 2; }
# A script that is missing or does not parse, or a --set it refuses, fails here, not in N queued tasks
# (`run SCRIPT --check` runs no trial).
"$rollsense" run "$script" --check "$@" >/dev/null ||
  { echo "submit.sh: $script: refused by rollsense (above); nothing submitted" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "submit.sh: sbatch not found: run this on a Slurm login node" >&2; exit 2; }

# The jobs run on other nodes, in other folders: absolute paths only.
rollsense=$(realpath "$rollsense")
[[ -f $script ]] && script=$(realpath "$script")  # else a stock script the program finds by name
mkdir -p "$out/logs"
out=$(realpath "$out")

export ROLLSENSE=$rollsense
unset ROLLSENSE_SHARD_COUNT  # the array below is the whole 0-(N-1): shard.sbatch reads N from Slurm
# ${a[@]+"${a[@]}"}: an empty array under set -u, which bash before 4.4 refuses as unbound.
shards_job=$(sbatch --parsable --array="0-$((n - 1))" --output="$out/logs/%x-%A_%a.out" \
  ${sbatch_options[@]+"${sbatch_options[@]}"} "$here/shard.sbatch" "$out" "$script" "$@")
shards_job=${shards_job%%;*}  # "id;cluster" on a federation
echo "ROLLSENSE_SHARDS_JOB=$shards_job"
merge=(sbatch --parsable --dependency="afterok:$shards_job" --kill-on-invalid-dep=yes --output="$out/logs/%x-%j.out"
       ${sbatch_options[@]+"${sbatch_options[@]}"} "$here/merge.sbatch" "$out" "$n" "$script" "$@")
if ! merge_job=$("${merge[@]}"); then
  echo "submit.sh: the shards run as job array $shards_job, but the merge job was not submitted (sbatch's error" \
       "above); submit it by hand: ROLLSENSE=$(printf '%q' "$rollsense") $(printf '%q ' "${merge[@]}")" \
       "(or stop the shards: scancel $shards_job)" | sed 's/--parsable //' >&2
  exit 1
fi
merge_job=${merge_job%%;*}

echo "submit.sh: $n shards as job array $shards_job (0-$((n - 1))), merge and analysis as job $merge_job;" \
     "results in $out/merged, logs in $out/logs" >&2
echo "ROLLSENSE_MERGE_JOB=$merge_job"

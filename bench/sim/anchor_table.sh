#!/bin/sh
# The anchor table of docs/simulation.md "Anchors": for every random source of
# the sim sensor, its default, where its size comes from, and how much the
# identification owes to it: the stock calibration run (sim_calibration --runs
# 50, seed 2024) with that one source switched off, judged by the reference
# classifier (check_classifier.py: bagged trees, 5-fold CV, overall and on the
# cylinders alone), beside the same run with every default.
#
#   bench/sim/anchor_table.sh BUILD_DIR [REPEATS]
#
# Prints one markdown row per source; about 10 s per row.
set -eu
build=${1:?usage: anchor_table.sh BUILD_DIR [REPEATS]}
repeats=${2:-1}
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

figures() {  # --set arguments → "overall | cylinders only"
    "$build/bin/sim_calibration" --runs 50 --features "$tmp/f.csv" "$@" >/dev/null
    /usr/bin/python3 "$here/check_classifier.py" "$tmp/f.csv" --repeats "$repeats" --cylinders >"$tmp/out.txt"
    overall=$(sed -n 's/^bagged trees 5-fold CV accuracy *\([0-9.]*\) %.*/\1/p' "$tmp/out.txt")
    cylinders=$(sed -n 's/^cylinders only, bagged trees 5-fold CV: \([0-9.]*\) %.*/\1/p' "$tmp/out.txt")
    echo "$overall % | $cylinders %"
}

echo "| source (switched off with) | default | where its size comes from | overall, with it off | cylinders only, with it off |"
echo "|---|---|---|---|---|"
echo "| (every default) | | | $(figures) |"
row() {  # label default source --set...
    label=$1 default=$2 source=$3
    shift 3
    echo "| $label | $default | $source | $(figures "$@") |"
}
row "white noise (noise_kpa=0)" "0.03 kPa" "paper: smoothed noise within +-0.005 (bench noise rows)" --set noise_kpa=0
row "quantisation (count_kpa=0.001)" "0.0635 kPa" "MPL115A2 datasheet: 10-bit Pcomp over 50-115 kPa" --set count_kpa=0.001
row "start spread (start_range=0)" "20 mm" "paper/brief: winch start spread" --set start_range=0
row "clamping force spread (force_log_sigma=0)" "0.17" "brief estimate; no source" --set force_log_sigma=0
row "palm oscillation (palm_oscillation=0)" "0.06" "brief estimate; no source" --set palm_oscillation=0
row "cylinder slip (cylinder_slip_max=0)" "0.04" "brief estimate; no source" --set cylinder_slip_max=0
row "polygon slip (polygon_slip=0)" "0.3 mm" "brief estimate; no source" --set polygon_slip=0
row "start tilt (start_tilt=0)" "1 deg" "brief estimate; no source" --set start_tilt=0
row "specimen size (specimen_size_tolerance=0)" "0.2 mm" "FDM printing tolerance +-0.2 mm" --set specimen_size_tolerance=0
row "edge radii per trial instead of per specimen (specimen_edges=false)" "per specimen" "paper: one printed specimen per object" --set specimen_edges=false
row "per-device gain (gain_jitter=0)" "0.10" "brief estimate; no source" --set gain_jitter=0

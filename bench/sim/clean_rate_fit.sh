#!/bin/sh
# The fit of T (finger_offset_sum) in docs/simulation.md "How the free
# parameters were fitted": the clean-trial rates of the calibration run
# (sim_calibration --runs 50) for each candidate T, as the mean over SEEDS
# run seeds. One run's count varies by about 12 trials (sd) from seed to seed,
# as much as 0.6 mm of T moves it, so one seed cannot fit T; the paper's
# single run (1164/1350 clean, 714/900 polygons) is compared with the mean.
#
#   bench/sim/clean_rate_fit.sh BUILD_DIR [SEEDS] [T ...]
#
# Prints one markdown row per T; about 0.5 s per run (SEEDS runs per row).
set -eu
build=${1:?usage: clean_rate_fit.sh BUILD_DIR [SEEDS] [T ...]}
seeds=${2:-20}
shift $(($# < 2 ? $# : 2))
[ $# -gt 0 ] || set -- 41 41.5 42 42.5 43

echo "| T (mm) | clean trials, mean over $seeds seeds (sd, range) | clean polygons, mean | paper |"
echo "|---|---|---|---|"
for t in "$@"; do
    seed=1
    counts=""
    while [ "$seed" -le "$seeds" ]; do
        # "clean trials overall   1163/1350 = ..." and "clean polygon trials   713/900 = ..."
        counts="$counts $("$build/bin/sim_calibration" --runs 50 --seed "$seed" --set finger_offset_sum="$t" |
            sed -n 's/^clean \(trials overall\|polygon trials\) *\([0-9]*\)\/.*/\2/p' | tr '\n' ' ')"
        seed=$((seed + 1))
    done
    echo "$counts" | awk -v t="$t" '{
        n = NF / 2
        for (i = 1; i <= NF; i += 2) { c = $i; p = $(i + 1); s += c; ss += c * c; sp += p
                                       if (min == "" || c < min) min = c; if (c > max) max = c }
        mean = s / n
        printf "| %s | %.1f / 1350 = %.1f %% (sd %.1f, %d-%d) | %.1f / 900 = %.1f %% | 1164 (86.2 %%), 714 (79.3 %%) |\n",
               t, mean, 100 * mean / 1350, sqrt((ss - n * mean * mean) / (n - 1)), min, max, sp / n, 100 * sp / n / 900
    }'
done

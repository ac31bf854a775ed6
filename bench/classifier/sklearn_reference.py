#!/usr/bin/python3
"""scikit-learn reference for bench_classifier: 5-fold CV of
BaggingClassifier(DecisionTreeClassifier(), n_estimators=30) on the same
features file and the same folds, single-threaded (n_jobs=1; run with
OMP_NUM_THREADS=1). Prints one line per model seed and a summary line:
    sklearn seed=<s> seconds=<cv wall time> cpu=<cv CPU time> accuracy=<fraction>
Only numpy and scikit-learn (Debian python3-sklearn) are needed."""
import csv
import sys
import time

import numpy as np
from sklearn.ensemble import BaggingClassifier
from sklearn.tree import DecisionTreeClassifier


def main(features_path, folds_path, seeds):
    fold_of = {}
    with open(folds_path, newline="") as f:
        for row in csv.DictReader(f):
            fold_of[row["trial_id"]] = int(row["fold"])
    xs, ys, folds = [], [], []
    with open(features_path, newline="") as f:
        for row in csv.DictReader(f):
            if row["clean"] != "1":
                continue
            xs.append([float(row["F%d" % k]) for k in range(1, 14)])
            ys.append(row["object"])
            folds.append(fold_of[row["trial_id"]])
    x = np.asarray(xs)
    y = np.asarray(ys)
    folds = np.asarray(folds)
    k = folds.max() + 1
    for seed in seeds:
        start = time.perf_counter()
        cpu_start = time.process_time()
        correct = 0
        for f in range(k):
            train, test = folds != f, folds == f
            model = BaggingClassifier(DecisionTreeClassifier(), n_estimators=30, random_state=seed, n_jobs=1)
            model.fit(x[train], y[train])
            correct += int((model.predict(x[test]) == y[test]).sum())
        seconds = time.perf_counter() - start
        cpu = time.process_time() - cpu_start
        print("sklearn seed=%d seconds=%.6f cpu=%.6f accuracy=%.6f" % (seed, seconds, cpu, correct / len(y)),
              flush=True)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: sklearn_reference.py FEATURES.csv FOLDS.csv [SEEDS...]")
    main(sys.argv[1], sys.argv[2], [int(s) for s in sys.argv[3:]] or [1])

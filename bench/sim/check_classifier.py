#!/usr/bin/python3
"""Reference classifier check for the sim sensor's calibration.

Reads the features CSV written by `sim_calibration --features FILE` and runs
the paper's classifier as classifier.md §4 maps it to scikit-learn
(BaggingClassifier of fully grown trees, 30 learners), 5-fold stratified CV on
the clean trials. Prints the rows of simulation.md §6 that concern the
classifier beside the paper's values.

    /usr/bin/python3 bench/sim/check_classifier.py features.csv [--repeats 3] [--cylinders]

--cylinders adds the diagnostic behind docs/simulation.md "What is not
reproduced": how far apart the three cylinder diameters are on each feature
(difference of class means in pooled within-class standard deviations) and how
well bagged trees tell C1/C2/C3 apart when trained on the cylinders alone.

(Debian's python3-sklearn and python3-numpy; no pandas needed.)
"""
import argparse
import sys

import numpy as np
import csv
from sklearn.ensemble import BaggingClassifier
from sklearn.model_selection import StratifiedKFold, cross_val_predict
from sklearn.tree import DecisionTreeClassifier

parser = argparse.ArgumentParser()
parser.add_argument("features")
parser.add_argument("--repeats", type=int, default=3, help="CV repetitions with different fold seeds")
parser.add_argument("--cylinders", action="store_true",
                    help="per-feature separation of the cylinder diameters and a cylinders-only classifier")
args = parser.parse_args()

with open(args.features, newline="") as f:
    table = list(csv.DictReader(f))
clean = [row for row in table if row["clean"] == "1"]
X = np.array([[float(row[f"F{i}"]) for i in range(1, 14)] for row in clean])
y = np.array([row["object"] for row in clean])
if len(clean) < 50:
    sys.exit(f"only {len(clean)} clean trials: not enough for 5-fold CV")

accs, cyl_wrong, edge_ok, ph = [], [], [], []
for r in range(args.repeats):
    model = BaggingClassifier(DecisionTreeClassifier(), n_estimators=30, random_state=r, n_jobs=1)
    pred = cross_val_predict(model, X, y, cv=StratifiedKFold(5, shuffle=True, random_state=r))
    accs.append(np.mean(pred == y))
    cyl = np.char.startswith(y.astype(str), "C")
    cyl_wrong.append(int(np.sum(pred[cyl] != y[cyl])))
    poly = ~cyl
    size = lambda labels: np.array([s[-1] for s in labels])
    edge_ok.append(np.mean((size(pred[poly]) == size(y[poly])) & ~np.char.startswith(pred[poly].astype(str), "C")))
    hexa = np.char.startswith(y.astype(str), "H")
    pent = np.char.startswith(y.astype(str), "P")
    h_wrong = np.sum(pred[hexa] != y[hexa]); h_as_p = np.sum(np.char.startswith(pred[hexa].astype(str), "P"))
    p_wrong = np.sum(pred[pent] != y[pent]); p_as_h = np.sum(np.char.startswith(pred[pent].astype(str), "H"))
    ph.append((h_wrong, h_as_p, p_wrong, p_as_h))

n_cyl = int(np.sum(np.char.startswith(y.astype(str), "C")))
print(f"clean trials: {len(clean)} of {len(table)}")
print(f"{'observable':44s} {'simulation':26s} paper")
print(f"{'bagged trees 5-fold CV accuracy':44s} {np.mean(accs)*100:5.1f} % (+- {np.std(accs)*100:.1f})       90.5 %")
print(f"{'cylinders misclassified':44s} {np.mean(cyl_wrong):5.1f} of {n_cyl:<15d} 7 of 450")
print(f"{'polygons with the right base edge':44s} {np.mean(edge_ok)*100:5.1f} %                   95.1 %")
hw, hp, pw, pp = np.mean(ph, axis=0)
print(f"{'hexagons wrong / of those called pentagons':44s} {hw:.0f} / {hp:.0f}                    45 / 33")
print(f"{'pentagons wrong / of those called hexagons':44s} {pw:.0f} / {pp:.0f}                    47 / 31")
labels = sorted(set(y))
model = BaggingClassifier(DecisionTreeClassifier(), n_estimators=30, random_state=0, n_jobs=1)
pred = cross_val_predict(model, X, y, cv=StratifiedKFold(5, shuffle=True, random_state=0))
print("confusion (rows true, cols predicted):", " ".join(labels))
for t in labels:
    print(f"  {t}: " + " ".join(f"{np.sum((y == t) & (pred == p)):3d}" for p in labels))

if args.cylinders:
    # Separation in units of the pooled within-class sd: a feature that moves by
    # less than ~1 sd per diameter step cannot carry a 98 % identification alone.
    cyl_names = [c for c in ("C1", "C2", "C3") if np.any(y == c)]
    if len(cyl_names) < 2:
        sys.exit("--cylinders: fewer than two cylinder classes among the clean trials")
    print("cylinders: feature means and separation in pooled within-class sd")
    print("  feature " + " ".join(f"{c:>8s}" for c in cyl_names) + "       sd   step-to-step separations")
    for j in range(13):
        groups = [X[y == c, j] for c in cyl_names]
        means = [g.mean() for g in groups]
        sd = float(np.sqrt(np.mean([g.var(ddof=1) for g in groups])))
        steps = " ".join(f"{(means[k + 1] - means[k]) / sd:+6.2f}" for k in range(len(means) - 1))
        print(f"  F{j + 1:<6d} " + " ".join(f"{m:8.4f}" for m in means) + f" {sd:8.4f}   {steps}")
    cyl_rows = np.isin(y, cyl_names)
    accs = []
    for r in range(args.repeats):
        model = BaggingClassifier(DecisionTreeClassifier(), n_estimators=30, random_state=r, n_jobs=1)
        pred = cross_val_predict(model, X[cyl_rows], y[cyl_rows], cv=StratifiedKFold(5, shuffle=True, random_state=r))
        accs.append(np.mean(pred == y[cyl_rows]))
    print(f"cylinders only, bagged trees 5-fold CV: {np.mean(accs)*100:.1f} % (+- {np.std(accs)*100:.1f}) "
          f"on {int(np.sum(cyl_rows))} trials; paper: 443 of 450 right within all 9 classes")

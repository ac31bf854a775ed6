#!/usr/bin/env python3
"""MiniRocket reference for bench_minirocket, written the way the authors'
implementation is organised (compiled numba loops over examples, no Python loop
per sample; scaler + RidgeClassifierCV from scikit-learn), from the paper's
description, on the series and folds the C++ bench wrote.

usage: minirocket_reference.py DIR SEED   (DIR holds x.f64 and meta.txt)
prints "key value" lines: compile_s transform_s evaluate_s predict_s accuracy_mean accuracy_sd
"""
import sys
import time
from itertools import combinations

import numpy as np
from numba import njit, prange
from sklearn.linear_model import RidgeClassifierCV
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

TWOS = np.array(list(combinations(range(9), 3)), dtype=np.int32)  # 84 × 3


def plan(n_channels, length, num_features=10000, max_dilations=32, seed=1):
    """Dilations, features per dilation, channel subsets per combination."""
    per_kernel = num_features // 84
    count = min(per_kernel, max_dilations)
    max_exp = np.log2((length - 1) / 8)
    raw = np.floor(2.0 ** np.linspace(0, max_exp, count)).astype(np.int32)
    dilations, copies = np.unique(raw, return_counts=True)
    fpd = np.floor(copies * (per_kernel / count)).astype(np.int32)
    i = 0
    while fpd.sum() < per_kernel:
        fpd[i] += 1
        i = (i + 1) % len(fpd)
    rng = np.random.default_rng(seed)
    max_ch = min(n_channels, 9)
    n_comb = len(dilations) * 84
    counts = np.clip(np.floor(2.0 ** rng.uniform(0, np.log2(max_ch + 1), n_comb)), 1, max_ch).astype(np.int32)
    channels = np.concatenate([np.sort(rng.choice(n_channels, c, replace=False)) for c in counts]).astype(np.int32)
    return dilations.astype(np.int32), fpd, counts, channels


@njit(fastmath=True, cache=True)
def _bases(x, d, alpha, gamma):
    # A = sum of the nine shifted −X, G_j = 3X shifted for position j (zero outside).
    C, L = x.shape
    alpha[:] = 0.0
    gamma[:] = 0.0
    for c in range(C):
        for j in range(9):
            s = (j - 4) * d
            for t in range(max(0, -s), min(L, L - s)):
                alpha[c, t] -= x[c, t + s]
                gamma[c, j, t] = 3.0 * x[c, t + s]


@njit(fastmath=True, cache=True)
def _combine(alpha, gamma, twos, chans, out):
    out[:] = 0.0
    for c in chans:
        out += alpha[c] + gamma[c, twos[0]] + gamma[c, twos[1]] + gamma[c, twos[2]]


@njit(cache=True)
def _quantiles(n):
    phi = (np.sqrt(5.0) + 1.0) / 2.0
    q = np.empty(n)
    for i in range(n):
        v = (i + 1) * phi
        q[i] = v - np.floor(v)
    return q


@njit(fastmath=True, cache=True)
def fit_biases(X, dilations, fpd, counts, channels, twos, examples):
    n, C, L = X.shape
    nf = 84 * fpd.sum()
    q = _quantiles(nf)
    biases = np.empty(nf, dtype=np.float32)
    alpha = np.empty((C, L), dtype=np.float32)
    gamma = np.empty((C, 9, L), dtype=np.float32)
    conv = np.empty(L, dtype=np.float32)
    f = 0
    comb = 0
    ch0 = 0
    for di in range(len(dilations)):
        for k in range(84):
            chans = channels[ch0:ch0 + counts[comb]]
            _bases(X[examples[comb]], dilations[di], alpha, gamma)
            _combine(alpha, gamma, twos[k], chans, conv)
            biases[f:f + fpd[di]] = np.quantile(conv, q[f:f + fpd[di]])
            f += fpd[di]
            ch0 += counts[comb]
            comb += 1
    return biases


@njit(fastmath=True, parallel=True, cache=True)
def transform(X, dilations, fpd, counts, channels, twos, biases):
    n, C, L = X.shape
    nf = 84 * fpd.sum()
    out = np.empty((n, nf), dtype=np.float32)
    starts = np.zeros(len(counts) + 1, dtype=np.int64)
    starts[1:] = np.cumsum(counts)
    for i in prange(n):
        alpha = np.empty((C, L), dtype=np.float32)
        gamma = np.empty((C, 9, L), dtype=np.float32)
        conv = np.empty(L, dtype=np.float32)
        f = 0
        comb = 0
        for di in range(len(dilations)):
            d = dilations[di]
            _bases(X[i], d, alpha, gamma)
            for k in range(84):
                _combine(alpha, gamma, twos[k], channels[starts[comb]:starts[comb + 1]], conv)
                pad = 0 if (di + k) % 2 == 0 else 4 * d
                v = conv[pad:L - pad]
                for j in range(fpd[di]):
                    out[i, f + j] = (v > biases[f + j]).mean()
                f += fpd[di]
                comb += 1
    return out


class MiniRocket:
    def __init__(self, seed):
        self.seed = seed

    def fit(self, X, y):
        self.layout = plan(X.shape[1], X.shape[2], seed=self.seed)
        dil, fpd, counts, ch = self.layout
        examples = np.random.default_rng(self.seed + 1).integers(0, X.shape[0], len(counts))
        self.biases = fit_biases(X, dil, fpd, counts, ch, TWOS, examples)
        F = transform(X, dil, fpd, counts, ch, TWOS, self.biases)
        self.ridge = make_pipeline(StandardScaler(), RidgeClassifierCV(alphas=np.logspace(-3, 3, 10)))
        self.ridge.fit(F, y)
        return self

    def features(self, X):
        dil, fpd, counts, ch = self.layout
        return transform(X, dil, fpd, counts, ch, TWOS, self.biases)

    def predict(self, X):
        return self.ridge.predict(self.features(X))


def main():
    d, seed = sys.argv[1], int(sys.argv[2])
    with open(f"{d}/meta.txt") as f:
        rows, C, L, K, repeats, folds = map(int, f.readline().split())
        y = np.array(f.readline().split(), dtype=np.int64)
        fold_ids = [np.array(f.readline().split(), dtype=np.int64) for _ in range(repeats)]
    X = np.fromfile(f"{d}/x.f64").reshape(rows, C, L).astype(np.float32)

    t0 = time.perf_counter()
    MiniRocket(seed).fit(X[:30], y[:30]).predict(X[:2])  # JIT compile (cached afterwards)
    print("compile_s", time.perf_counter() - t0)

    t0 = time.perf_counter()
    dil, fpd, counts, ch = plan(C, L, seed=seed)
    ex = np.random.default_rng(seed + 1).integers(0, rows, len(counts))
    b = fit_biases(X, dil, fpd, counts, ch, TWOS, ex)
    transform(X, dil, fpd, counts, ch, TWOS, b)
    print("transform_s", time.perf_counter() - t0)

    acc = []
    t0 = time.perf_counter()
    for fid in fold_ids:
        for k in range(folds):
            tr, te = fid != k, fid == k
            m = MiniRocket(seed).fit(X[tr], y[tr])
            acc.append((m.predict(X[te]) == y[te]).mean())
    print("evaluate_s", time.perf_counter() - t0)
    print("accuracy_mean", np.mean(acc))
    print("accuracy_sd", np.std(acc, ddof=1))

    m = MiniRocket(seed).fit(X, y)
    times = []
    for i in range(100):
        t0 = time.perf_counter()
        m.predict(X[i % rows:i % rows + 1])
        times.append(time.perf_counter() - t0)
    print("predict_s", float(np.median(times)))


if __name__ == "__main__":
    main()

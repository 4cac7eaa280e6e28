#!/usr/bin/env python3
"""NumPy baseline for `cargo bench -p uncertainty --bench monte_carlo`: the same Monte Carlo,
vectorised as a user would write it.

Twenty inputs: eight readings z_j (Type A, u = 1e-3, nu = 9, drawn from the scaled-and-shifted
t), eight rectangular biases b_j (half-width 2e-4), a normal scale factor s (1 +- 1e-4) and
offset c (0 +- 1e-4), a rectangular drift d (half-width 1e-4) and a normal quadratic gain g
(0 +- 1e-3). Eight corrected points obs_j = s (z_j - b_j) + c + d j/7 + g z_j^2 are fitted
with six polynomial coefficients through the fixed 8 x 6 design A_jk = tau_j^k by its
pseudo-inverse, y = P obs. Per output: mean, standard deviation and the probabilistically
symmetric 95 % coverage interval (JCGM 101 7.7, order statistics by np.partition), as the
Rust side computes them.

    python3 bench/uncertainty_numpy.py [--trials M] [--repeat R] [--chunk C]

Prints JSON: the best time of R runs, trials/s, and the results of the last run.
"""
import argparse
import json
import math
import time

import numpy as np

POINTS, COEFFICIENTS = 8, 6


def setup():
    tau = (np.arange(POINTS) - 3.5) / 3.5
    design = np.vander(tau, COEFFICIENTS, increasing=True)
    p = np.linalg.pinv(design)
    z = 1.0 + 0.5 * tau + 0.1 * tau**2 - 0.02 * tau**3
    return p, z


def draw_and_evaluate(rng, p, z, m):
    zs = z + 1e-3 * rng.standard_t(9.0, size=(m, POINTS))
    b = rng.uniform(-2e-4, 2e-4, size=(m, POINTS))
    s = rng.normal(1.0, 1e-4, size=(m, 1))
    c = rng.normal(0.0, 1e-4, size=(m, 1))
    d = rng.uniform(-1e-4, 1e-4, size=(m, 1))
    g = rng.normal(0.0, 1e-3, size=(m, 1))
    j = np.arange(POINTS) / 7.0
    obs = s * (zs - b) + c + d * j + g * zs * zs
    return obs @ p.T  # m x 6


def coverage(y, prob=0.95):
    m = y.shape[0]
    q = int(math.floor(prob * m + 0.5))
    r = max((m - q + 1) // 2, 1)  # ceil((m - q)/2), 1-based
    lo, hi = r - 1, min(r + q - 1, m - 1)
    part = np.partition(y, [lo, hi], axis=0)
    return part[lo], part[hi]


def run(m, chunk, seed):
    rng = np.random.default_rng(seed)
    p, z = setup()
    ys = [draw_and_evaluate(rng, p, z, min(chunk, m - start)) for start in range(0, m, chunk)]
    y = np.concatenate(ys)
    mean = y.mean(axis=0)
    u = y.std(axis=0, ddof=1)
    low, high = coverage(y)
    return mean, u, low, high


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--chunk", type=int, default=100_000)
    args = ap.parse_args()
    best = math.inf
    for r in range(args.repeat):
        t0 = time.perf_counter()
        mean, u, low, high = run(args.trials, args.chunk, r)
        best = min(best, time.perf_counter() - t0)
    print(json.dumps({
        "numpy": np.__version__,
        "trials": args.trials,
        "best_s": best,
        "trials_per_s": args.trials / best,
        "mean": mean.tolist(),
        "u": u.tolist(),
        "low": low.tolist(),
        "high": high.tolist(),
    }, indent=1))


if __name__ == "__main__":
    main()

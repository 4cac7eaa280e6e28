#!/usr/bin/env python3
"""NumPy baseline for `cargo bench -p pipeline --bench calibration_monte_carlo`: the Monte Carlo
of the PIGA calibration's measurement model (pipeline::CalibrationModel), vectorised as a user
would write it, on the inputs the Rust bench writes:

    CALIBRATION_MC_JSON=$PWD/target/perf/calibration_mc.json \
        cargo bench -p pipeline --bench calibration_monte_carlo
    python3 bench/calibration_numpy.py target/perf/calibration_mc.json [--trials M] [--repeat R]

Fourteen inputs, drawn as uncertainty::monte_carlo draws them (JCGM 101 6.4): normal Type B
inputs N(x, u^2) (an input with u = 0 is constant), C_r from the scaled-and-shifted t
(x + u t_nu), and the six eq. 18 coefficients as one multivariate t group,
x = mu + diag(u) L z sqrt(nu / w), z ~ N(0, I), w ~ chi^2_nu drawn once per trial, L the
Cholesky factor of their correlation. The model: beta' = beta / diag(1, s, s^2, s^3, rho^2,
rho^3) with rho = (R s^2 / g) / (R0 / g0); k1 = beta'_2 g / R (fitted);
C_r,true = C_r gain (lever / lever0) / s^2; dk2 = k1 C_r,true g / R^2; outputs k0 = beta'_0,
k1, k2 = beta'_4 - dk2, k3 = beta'_5, k2_uncompensated = beta'_4, delta_k2 = dk2.
Per output: mean, standard deviation and the probabilistically symmetric 95 % coverage
interval (JCGM 101 7.7, order statistics by np.partition), as the Rust side computes them.

Prints JSON: the best time of R runs, trials/s, the last run's results, and for each output
the difference from the Rust run in the file in units of its Monte Carlo standard error.
"""
import argparse
import json
import math
import time

import numpy as np

OUTPUTS = ["k0", "k1", "k2", "k3", "k2_uncompensated", "delta_k2"]
FIRST_COEFFICIENT = 8


def draw(rng, spec, m):
    """m trials of the fourteen inputs, m x 14."""
    q = spec["inputs"]
    n = len(q)
    x = np.empty((m, n))
    for i in range(FIRST_COEFFICIENT):
        value, u = q[i]["value"], q[i]["u"]
        if u == 0.0:
            x[:, i] = value
        elif q[i]["distribution"] == "normal":
            x[:, i] = rng.normal(value, u, size=m)
        elif q[i]["distribution"] == "t":
            x[:, i] = value + u * rng.standard_t(q[i]["dof"], size=m)
        else:  # rectangular
            h = u * math.sqrt(3.0)
            x[:, i] = rng.uniform(value - h, value + h, size=m)
    group = range(FIRST_COEFFICIENT, n)
    corr = np.array(spec["correlation"])[np.ix_(group, group)]
    chol = np.linalg.cholesky(corr)
    mu = np.array([q[i]["value"] for i in group])
    u = np.array([q[i]["u"] for i in group])
    nu = q[FIRST_COEFFICIENT]["dof"]
    z = rng.standard_normal((m, len(mu))) @ chol.T
    scale = np.sqrt(nu / rng.chisquare(nu, size=m))
    x[:, FIRST_COEFFICIENT:] = mu + u * z * scale[:, None]
    return x


def evaluate(spec, x):
    """The six outputs of pipeline::CalibrationModel, m x 6."""
    q = spec["inputs"]
    r0, g0 = q[0]["value"], q[1]["value"]
    lever0 = (q[3]["value"] + q[4]["value"]) / q[3]["value"]
    radius, g, s = x[:, 0], x[:, 1], x[:, 2]
    h_p, h_a, gain, c_r, k1_given = x[:, 3], x[:, 4], x[:, 5], x[:, 6], x[:, 7]
    rho = (radius * s * s / g) / (r0 / g0)
    d = np.stack([np.ones_like(s), s, s * s, s * s * s, rho * rho, rho * rho * rho], axis=1)
    beta = x[:, FIRST_COEFFICIENT:] / d
    k1 = beta[:, 2] * g / radius if spec["k1_fitted"] else k1_given
    lever = (h_p + h_a) / h_p
    c_r_true = c_r * gain * (lever / lever0) / (s * s)
    delta_k2 = k1 * c_r_true * g / (radius * radius)
    return np.stack(
        [beta[:, 0], k1, beta[:, 4] - delta_k2, beta[:, 5], beta[:, 4], delta_k2], axis=1
    )


def coverage(y, prob=0.95):
    m = y.shape[0]
    q = int(math.floor(prob * m + 0.5))
    r = max((m - q + 1) // 2, 1)  # ceil((m - q)/2), 1-based
    lo, hi = r - 1, min(r + q - 1, m - 1)
    part = np.partition(y, [lo, hi], axis=0)
    return part[lo], part[hi]


def run(spec, m, chunk, seed):
    rng = np.random.default_rng(seed)
    y = np.concatenate(
        [evaluate(spec, draw(rng, spec, min(chunk, m - start))) for start in range(0, m, chunk)]
    )
    mean = y.mean(axis=0)
    u = y.std(axis=0, ddof=1)
    low, high = coverage(y)
    # Standard errors of the mean and of the standard deviation (from the kurtosis).
    kurtosis = ((y - mean) ** 4).mean(axis=0) / u**4
    se_mean = u / math.sqrt(m)
    se_u = u * np.sqrt((kurtosis - 1.0) / (4.0 * m))
    return mean, u, low, high, se_mean, se_u


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("spec", help="the JSON written by the Rust bench (CALIBRATION_MC_JSON)")
    ap.add_argument("--trials", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--chunk", type=int, default=100_000)
    args = ap.parse_args()
    with open(args.spec) as f:
        spec = json.load(f)
    best = math.inf
    for r in range(args.repeat):
        t0 = time.perf_counter()
        mean, u, low, high, _, _ = run(spec, args.trials, args.chunk, r)
        best = min(best, time.perf_counter() - t0)
    # The statistics' noise, from a run outside the timing.
    _, _, _, _, se_mean, se_u = run(spec, args.trials, args.chunk, 1000)
    rust = {o["name"]: o for o in spec["rust"]["outputs"]}
    rust_m = spec["rust"]["trials"]
    comparison = {}
    for k, name in enumerate(OUTPUTS):
        o = rust[name]
        # Both runs are noisy: the difference's standard error is sqrt(se_a^2 + se_b^2).
        sm = se_mean[k] * math.sqrt(1.0 + args.trials / rust_m)
        su = se_u[k] * math.sqrt(1.0 + args.trials / rust_m)
        comparison[name] = {
            "rust_mean": o["mean"],
            "numpy_mean": mean[k],
            "mean_diff_in_se": (mean[k] - o["mean"]) / sm,
            "rust_u": o["u"],
            "numpy_u": u[k],
            "u_diff_in_se": (u[k] - o["u"]) / su,
            "rust_interval": [o["low95"], o["high95"]],
            "numpy_interval": [low[k], high[k]],
        }
    print(json.dumps({
        "numpy": np.__version__,
        "trials": args.trials,
        "best_s": best,
        "trials_per_s": args.trials / best,
        "comparison": comparison,
    }, indent=1))


if __name__ == "__main__":
    main()

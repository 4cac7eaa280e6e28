#!/usr/bin/env python3
"""NumPy baseline for `cargo xtask harmonics`: what a user writes.

Reads a probe recording (CSV with a header row, `#` comments) with numpy.loadtxt, cuts it
into revolutions from the rate (theta = omega * (t - t0)), fits eq. 20 up to order N to each
complete revolution with numpy.linalg.lstsq on the explicit design matrix, and averages the
coefficients.

    python3 bench/numpy_baseline.py FILE --rate-deg-s W [--order N] [--json]
    python3 bench/numpy_baseline.py FILE --rate-deg-s W --time-fit [--repeat R]

With --time-fit the file is loaded once and the in-memory fit (segmentation, design matrices,
lstsq, statistics) is timed R times; the best time and the throughput are printed as JSON.
Without it the script runs once, as a user would (time the whole process from outside).
"""
import argparse
import json
import time

import numpy as np


def load(path):
    # Skip comment lines and the header row, as a user reading this format would.
    skip = 0
    with open(path) as f:
        for line in f:
            skip += 1
            if line.strip() and not line.lstrip().startswith("#"):
                header = [h.strip() for h in line.split(",")]
                break
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=skip)
    return data[:, header.index("time_s")], data[:, header.index("gap_um")]


def fit(t, y, rate_rad_s, order):
    theta = rate_rad_s * (t - t[0])
    rev = np.floor(theta / (2 * np.pi)).astype(np.int64)
    coefs = []
    for r in range(rev[-1] + 1):
        sel = rev == r
        th = theta[sel]
        # The last revolution counts when it closes to within a few samples.
        if th[-1] - th[0] < 2 * np.pi - 3 * rate_rad_s * np.median(np.diff(t[:1025])):
            continue
        k = np.arange(1, order + 1)
        a = np.column_stack([np.ones_like(th), np.cos(np.outer(th, k)), np.sin(np.outer(th, k))])
        x, *_ = np.linalg.lstsq(a, y[sel], rcond=None)
        coefs.append(x)
    coefs = np.array(coefs)
    mean = coefs.mean(axis=0)
    std = coefs.std(axis=0, ddof=1) if len(coefs) > 1 else None
    return len(coefs), mean, std


def main():
    p = argparse.ArgumentParser()
    p.add_argument("file")
    p.add_argument("--rate-deg-s", type=float, required=True)
    p.add_argument("--order", type=int, default=4)
    p.add_argument("--json", action="store_true")
    p.add_argument("--time-fit", action="store_true")
    p.add_argument("--repeat", type=int, default=5)
    a = p.parse_args()
    w = np.deg2rad(a.rate_deg_s)
    t, y = load(a.file)
    n = a.order
    if a.time_fit:
        best = float("inf")
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            fit(t, y, w, n)
            best = min(best, time.perf_counter() - t0)
        print(json.dumps({"samples": len(t), "order": n, "best_s": best, "samples_per_s": len(t) / best,
                          "numpy": np.__version__}))
        return
    used, mean, std = fit(t, y, w, n)
    h_c1, h_s1 = mean[1], mean[n + 1]
    out = {
        "order": n,
        "revolutions_used": used,
        "mean": {"l0": mean[0], "c": list(mean[1:n + 1]), "s": list(mean[n + 1:])},
        "std": None if std is None else {"l0": std[0], "c": list(std[1:n + 1]), "s": list(std[n + 1:])},
        "first_harmonic": {"amplitude": float(np.hypot(h_c1, h_s1)),
                           "beta_deg": float(np.degrees(np.arctan2(h_s1, -h_c1)))},
    }
    if a.json:
        print(json.dumps(out, default=float))
    else:
        print(f"{a.file}: {len(t)} samples, {used} revolutions, order {n}")
        print(f"c = {mean[1:n + 1]}\ns = {mean[n + 1:]}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The harmonic fit from Python: centrifuge_cal.fit_harmonics against the per-revolution
numpy.linalg.lstsq a lab writes (bench/numpy_baseline.py's `fit`), on the same arrays in one
run, one thread each; and the binding's overhead (array checks, conversion of the results)
as a share of the Rust call it wraps.

    python bench/python_binding.py [--samples 2880000] [--repeat 5] [--json]

The recording is docs/PERFORMANCE.md's: 10 deg/s sampled at 1 kHz (2 880 000 samples = 80
revolutions), order 4, Gaussian noise 0.05 µm, the angle from the declared rate. Threads:
RAYON_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1 are set before either library loads.
"""
import os

os.environ["RAYON_NUM_THREADS"] = "1"
os.environ["OPENBLAS_NUM_THREADS"] = "1"
os.environ["OMP_NUM_THREADS"] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from numpy_baseline import fit as numpy_fit  # noqa: E402

import centrifuge_cal as cc  # noqa: E402


def recording(samples, rate_deg_s=10.0, rate_hz=1000.0, seed=1):
    t = np.arange(samples) / rate_hz
    theta = np.radians(rate_deg_s) * t
    c = (-3.2385, 0.21, -0.05, 0.012)
    s = (-1.1406, 0.33, 0.02, -0.007)
    gap = np.full(samples, 47.3)
    for k in range(4):
        gap += c[k] * np.cos((k + 1) * theta) + s[k] * np.sin((k + 1) * theta)
    gap += np.random.default_rng(seed).normal(0.0, 0.05, samples)
    return t, gap


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--samples", type=int, default=2_880_000)
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--json", action="store_true")
    a = p.parse_args()
    t, gap = recording(a.samples)
    w = np.radians(10.0)
    ours, overhead, rust, lab = [], [], [], []
    for _ in range(a.repeat):
        # side by side: one of each per round
        t0 = time.perf_counter()
        fit = cc.fit_harmonics(t, gap, rate_deg_s=10.0)
        total = time.perf_counter() - t0
        ours.append(total)
        rust.append(fit.rust_seconds)
        overhead.append(total - fit.rust_seconds)
        t0 = time.perf_counter()
        used, mean, _ = numpy_fit(t, gap, w, 4)
        lab.append(time.perf_counter() - t0)
    # the same numbers
    assert used == fit.revolutions_used, (used, fit.revolutions_used)
    diff = max(abs(mean[1] - fit.mean.c[0]), abs(mean[5] - fit.mean.s[0]))
    best = min(ours)
    i = ours.index(best)
    out = {
        "samples": a.samples,
        "revolutions": fit.revolutions_used,
        "centrifuge_cal_best_s": best,
        "rust_call_s": rust[i],
        "binding_overhead_s": overhead[i],
        "binding_overhead_share_of_rust_call": overhead[i] / rust[i],
        "binding_overhead_share_median": float(np.median(np.array(overhead) / np.array(rust))),
        "numpy_lstsq_best_s": min(lab),
        "speed_ratio": min(lab) / best,
        "max_first_harmonic_difference_um": diff,
        "numpy": np.__version__,
        "python": sys.version.split()[0],
    }
    if a.json:
        print(json.dumps(out, indent=2))
    else:
        print(f"{a.samples} samples, {fit.revolutions_used} revolutions, one thread each, best of {a.repeat}")
        print(f"centrifuge_cal.fit_harmonics  {best * 1e3:9.2f} ms "
              f"(Rust call {rust[i] * 1e3:.2f} ms, binding {overhead[i] * 1e3:.3f} ms = "
              f"{100 * overhead[i] / rust[i]:.2f} %)")
        print(f"numpy.linalg.lstsq per rev.   {min(lab) * 1e3:9.2f} ms")
        print(f"ratio                         {min(lab) / best:9.1f}x")
        print(f"largest difference of d_c1, d_s1: {diff:.2e} um")


if __name__ == "__main__":
    main()

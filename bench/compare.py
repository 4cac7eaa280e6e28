#!/usr/bin/env python3
"""Side-by-side timing of `xtask harmonics` and the NumPy baseline on the same recordings.

    python3 bench/compare.py [--runs R] FILE:RATE_DEG_S ...

For each recording: wall time of the whole process (median and best of R runs) for the
xtask binary, for `cargo xtask harmonics` (adds cargo's start-up and freshness check), and
for `python3 bench/numpy_baseline.py` (interpreter, numpy import, loadtxt, fit); then the
NumPy in-memory fit throughput (--time-fit). The in-memory throughput of the Rust fit comes
from `cargo bench -p harmonics --bench fit`.
"""
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
XTASK = ROOT / "target" / "debug" / "xtask"


def wall(cmd, runs):
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=ROOT)
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times)


def main():
    args = sys.argv[1:]
    runs = 10
    if args[:1] == ["--runs"]:
        runs, args = int(args[1]), args[2:]
    subprocess.run(["cargo", "build", "-q", "-p", "xtask"], check=True, cwd=ROOT)
    for spec in args:
        path, rate = spec.rsplit(":", 1)
        xt = [str(XTASK), "harmonics", path, "--rate-deg-s", rate, "--json"]
        cx = ["cargo", "xtask", "harmonics", path, "--rate-deg-s", rate, "--json"]
        np_cmd = [sys.executable, "bench/numpy_baseline.py", path, "--rate-deg-s", rate, "--json"]
        rows = [("xtask binary", wall(xt, runs)), ("cargo xtask", wall(cx, runs)), ("numpy", wall(np_cmd, runs))]
        fits = {}
        for label, env in [("default threads", {}), ("one thread", {"OPENBLAS_NUM_THREADS": "1"})]:
            fits[label] = json.loads(subprocess.run(
                [sys.executable, "bench/numpy_baseline.py", path, "--rate-deg-s", rate, "--time-fit"],
                check=True, capture_output=True, text=True, cwd=ROOT, env={**os.environ, **env}).stdout)
        fit = fits["one thread"]
        print(f"{path} ({fit['samples']} samples, order {fit['order']}, runs {runs})")
        base = rows[2][1][0]
        for name, (med, best) in rows:
            print(f"  {name:<14} median {med * 1e3:8.1f} ms  best {best * 1e3:8.1f} ms  numpy/this {base / med:6.1f}x")
        for label, f in fits.items():
            print(f"  numpy in-memory fit ({label}): best {f['best_s'] * 1e3:.1f} ms, "
                  f"{f['samples_per_s'] / 1e6:.2f} M samples/s (numpy {f['numpy']})")


if __name__ == "__main__":
    main()

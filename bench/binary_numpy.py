#!/usr/bin/env python3
"""NumPy baseline for the binary readers: what a user writes to read the same files.

Reads the files `cargo bench -p recording --bench binary` writes into $BINARY_BENCH_DIR
(probe_10m.tdms, probe_10m.mat, probe_10m_v7.mat: 3 400 000 rows of float64 `time_s`,
`gap_um`, `angle_deg`) with npTDMS (TdmsFile.read, then the three channels as arrays) and
scipy.io.loadmat, R times each, and prints the best time and the throughput in samples
(values of all three channels) per second as JSON lines.

    pip install npTDMS scipy numpy
    python3 bench/binary_numpy.py DIR [--repeat R]
"""
import argparse
import json
import os
import time

import numpy as np
import scipy
import scipy.io
import nptdms
from nptdms import TdmsFile

CHANNELS = ("time_s", "gap_um", "angle_deg")


def read_tdms(path):
    f = TdmsFile.read(path)
    g = f["probe"]
    return [np.asarray(g[c][:], dtype=np.float64) for c in CHANNELS]


def read_mat(path):
    m = scipy.io.loadmat(path)
    return [np.asarray(m[c], dtype=np.float64).ravel() for c in CHANNELS]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dir")
    p.add_argument("--repeat", type=int, default=5)
    a = p.parse_args()
    cases = [("tdms", "probe_10m.tdms", read_tdms),
             ("mat_v5", "probe_10m.mat", read_mat),
             ("mat_v7", "probe_10m_v7.mat", read_mat)]
    for name, file, read in cases:
        path = os.path.join(a.dir, file)
        best = float("inf")
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            cols = read(path)
            # A user checks the samples as the Rust reader does: finite, time increasing.
            ok = all(np.isfinite(c).all() for c in cols) and bool((np.diff(cols[0]) > 0).all())
            best = min(best, time.perf_counter() - t0)
        samples = sum(len(c) for c in cols)
        print(json.dumps({"file": name, "samples": samples, "best_s": best,
                          "samples_per_s": samples / best, "checked": ok,
                          "numpy": np.__version__, "scipy": scipy.__version__,
                          "npTDMS": nptdms.__version__}))


if __name__ == "__main__":
    main()

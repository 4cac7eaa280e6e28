#!/usr/bin/env python3
"""Independent NumPy fit of simulated five-mounting campaigns (issue 29): the IEEE 836 model's
joint fit over several mountings, written from docs/MODEL.md without the Rust code, and
checked against the Rust fit (`calibration::fit_mountings`) of the same data to 1e-9 relative
in every chosen term and its u.

    MODEL_NUMPY_DIR=target/model-numpy cargo test -p calibration --test mountings numpy
    python3 -m venv target/venv && target/venv/bin/pip install numpy
    target/venv/bin/python bench/model_numpy.py target/model-numpy/campaign_*.json

Each JSON file holds one campaign (written by the Rust test
`crates/calibration/tests/mountings/numpy_data.rs`): the kind, g, the vertical Earth rate, the
probe's drift (static and C_r along the arm, static and C_ry across it), the rates, the
chosen terms, each mounting's declared case axes IA, PA, OA in the spindle frame (X2 out along
the arm, Y2 tangential, Z2 up), its radius, whether it has its own bias and ω term, its
outputs, and the Rust fit's terms (value, u) and arm-stretch coefficient γ.

The fit, as docs/MODEL.md states it:

1. nominal inputs along each case axis v: A = (−v_x)·a + (−v_y)·b + v_z, with
   a = (R + Δr_xs + C_r·ω²)·ω²/g and b = (Δr_ys + C_ry·ω²)·ω²/g (in numpy.longdouble);
2. columns: each chosen term's regressor of (A_i, A_p, A_o) (k0 on the rows of mountings
   without their own bias; a misalignment's column A_p or −A_o, coefficient k1·δ), each
   remounted mounting's bias indicator, each mounting's ω term (±ω, the sign of its IA's
   radial component), the shared ω³ and arm-stretch columns c_i·ω³ and c_i·ω⁴ (c_i = −IA_x);
3. for a PIGA the known rate about IA, (ω + Ω_v)·IA_z, added to the output (in double
   precision: the outputs a fit takes are doubles);
4. least squares on the norm-scaled columns (numpy.linalg.lstsq), refined with residuals in
   numpy.longdouble; covariance s²·(XᵀX)⁻¹ from the SVD, s² = Σr²/(n − p);
5. δ = (k1·δ)/k1 with its u by the gradient.

Exit status 1 when a term or its u disagrees with the Rust fit beyond 1e-9 relative.

    target/venv/bin/python bench/model_numpy.py --time 20 target/model-numpy/campaign_piga.json

times one fit and the 46 refits of the GUM budget (`cargo bench -p calibration --bench
mountings`, `gum_budget`), best of 20.
"""
import json
import sys

import numpy as np

TOLERANCE = 1e-9
LD = np.longdouble


def regressor(term, i, p, o):
    return {
        "k0": np.ones_like(i),
        "k1": i,
        "k2": i * i,
        "k3": i * i * i,
        "k4": i * i * i * i,
        "k_oq": i * np.abs(i),
        "k_ip": i * p,
        "k_io": i * o,
        "k_pp": p * p,
        "k_oo": o * o,
        "k_po": p * o,
        "delta_o": p,
        "delta_p": -o,
    }[term]


def design(c):
    w = np.array(c["rates_rad_s"], dtype=LD)
    g = LD(c["g_m_s2"])
    pr = c["probe"]
    a_rad = (LD(0) + LD(pr["c_r_m_s2"]) * w**2) * w**2 / g
    b_across = (LD(pr["static_across_m"]) + LD(pr["c_ry_m_s2"]) * w**2) * w**2 / g
    blocks, ys, labels = [], [], []
    ms = c["mountings"]
    n_m = len(ms)
    for m, mt in enumerate(ms):
        radial = (LD(mt["radius_m"]) + LD(pr["static_m"])) * w**2 / g + a_rad
        axes = [np.array(mt[k], dtype=LD) for k in ("ia", "pa", "oa")]
        i, p, o = (-v[0] * radial - v[1] * b_across + v[2] for v in axes)
        cols = []
        for t in c["terms"]:
            col = regressor(t, i, p, o)
            if t == "k0" and mt["own_bias"]:
                col = np.zeros_like(w)
            cols.append(col)
        c_i = -axes[0][0]
        for k in range(n_m):
            if k > 0 and ms[k]["own_bias"]:
                cols.append(np.ones_like(w) if k == m else np.zeros_like(w))
        for k in range(n_m):
            if ms[k]["tilt_rate"]:
                sign = LD(-1) if -ms[k]["ia"][0] < 0 else LD(1)
                cols.append(sign * w if k == m else np.zeros_like(w))
        cols.append(c_i * w**3)
        cols.append(c_i * w**4)
        blocks.append(np.stack(cols, axis=1))
        y = np.array(mt["outputs"], dtype=np.float64)
        if c["kind"] == "piga" and mt["ia"][2] != 0.0:
            # the known rate moved to the left in double precision, as the data a fit takes
            w64 = np.array(c["rates_rad_s"], dtype=np.float64)
            y = y + (w64 + c["earth_rate_vertical_rad_s"]) * mt["ia"][2]
        ys.append(y.astype(LD))
    return np.concatenate(blocks), np.concatenate(ys)


def fit(x_ld, y_ld):
    norms = np.sqrt(np.sum(x_ld.astype(np.float64) ** 2, axis=0))
    b_ld = x_ld / norms.astype(LD)
    b = b_ld.astype(np.float64)
    z = np.linalg.lstsq(b, y_ld.astype(np.float64), rcond=None)[0].astype(LD)
    for _ in range(8):  # refinement with residuals in extended precision
        r = y_ld - b_ld @ z
        dz = np.linalg.lstsq(b, r.astype(np.float64), rcond=None)[0]
        z = z + dz.astype(LD)
    r = y_ld - b_ld @ z
    n, k = b.shape
    s2 = float(np.sum(r * r)) / (n - k)
    _, sv, vt = np.linalg.svd(b, full_matrices=False)
    inv = (vt.T / sv**2) @ vt
    cov = s2 * inv / np.outer(norms, norms)
    return (z / norms.astype(LD)).astype(np.float64), cov


def check(path):
    with open(path, encoding="utf-8") as f:
        c = json.load(f)
    x, y = design(c)
    beta, cov = fit(x, y)
    terms = c["terms"]
    k1_j = terms.index("k1")
    ok = True
    print(f"{path}: {c['kind']}, {x.shape[0]} points, {x.shape[1]} columns")
    for j, t in enumerate(terms):
        value, u = beta[j], np.sqrt(cov[j, j])
        if t.startswith("delta"):
            k1 = beta[k1_j]
            grad = np.zeros(len(beta))
            grad[j], grad[k1_j] = 1 / k1, -beta[j] / k1**2
            value, u = beta[j] / k1, np.sqrt(grad @ cov @ grad)
        rv, ru = c["rust"][t]
        dv, du = abs(value / rv - 1), abs(u / ru - 1)
        flag = "" if max(dv, du) <= TOLERANCE else "  <-- beyond 1e-9"
        ok &= max(dv, du) <= TOLERANCE
        print(f"  {t:8s} {value: .15e} ± {u:.6e}   Rust {rv: .15e} ± {ru:.6e}   rel {dv:.1e}, {du:.1e}{flag}")
    g, gu = beta[-1], np.sqrt(cov[-1, -1])
    rg, rgu = c["rust"]["arm_stretch_gamma"]
    dv, du = abs(g / rg - 1), abs(gu / rgu - 1)
    ok &= max(dv, du) <= TOLERANCE
    print(f"  gamma    {g: .15e} ± {gu:.6e}   Rust {rg: .15e} ± {rgu:.6e}   rel {dv:.1e}, {du:.1e}")
    return ok


def time_budget(path, repeat):
    """The NumPy side of `cargo bench -p calibration --bench mountings`: one fit and the 46
    refits of the Rust GUM budget (23 Type B inputs, each moved by ± its u: here each mounting's
    radius in turn, the cost of a refit being the same whichever input moved), best of
    `repeat`."""
    import time

    with open(path, encoding="utf-8") as f:
        c = json.load(f)
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        x, y = design(c)
        fit(x, y)
        for j in range(46):
            moved = json.loads(json.dumps(c))
            m = moved["mountings"][j % len(moved["mountings"])]
            m["radius_m"] += 5e-6 if j % 2 == 0 else -5e-6
            x, y = design(moved)
            fit(x, y)
        best = min(best, time.perf_counter() - start)
    print(f"{path}: one fit and 46 refits (the GUM budget's count), best of {repeat}: "
          f"{best * 1e3:.1f} ms")


def main():
    args = sys.argv[1:]
    if args[:1] == ["--time"]:
        repeat = int(args[1])
        for p in args[2:]:
            time_budget(p, repeat)
        return 0
    paths = args
    if not paths:
        print(__doc__)
        return 2
    results = [check(p) for p in paths]
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())

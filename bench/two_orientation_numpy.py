#!/usr/bin/env python3
"""NumPy baseline for `cargo bench -p pipeline --bench two_orientation_study` (issue 20): the
two-orientation study on raw recordings, `fixtures/studies/two_orientation_recordings.ron`, written
the way a lab writes it in NumPy, timed best of N, and checked against a results.json of the
Rust study:

    cargo xtask study --config fixtures/studies/two_orientation_recordings.ron --out target/sym-rec
    python3 -m venv target/venv && target/venv/bin/pip install numpy
    OPENBLAS_NUM_THREADS=1 target/venv/bin/python bench/two_orientation_numpy.py \
        target/sym-rec/results.json [--repeat 5] [--json]

(`TWO_ORIENTATION_STUDY_JSON=path cargo bench -p pipeline --bench two_orientation_study` writes the
bench's own run's results.json, which serves as well.)

The job, from the 36 CSV files to k2 and C with their uncertainties:

1. `numpy.loadtxt` of the 12 probe recordings (time_s, gap_um, angle_deg) and the 24 PIGA
   output recordings (time_s, output_rad, angle_deg; 12 rates with the IA in, 12 out).
2. Whole spindle revolutions from the encoder angle (a revolution starts where the angle
   passes the first sample's angle again; the trailing one counts when at most 3 sample
   steps short of a turn) and the rate measured over them.
3. Probe: per revolution, `numpy.linalg.lstsq` of `1, cos kθ, sin kθ (k ≤ 4), t − t_mid`
   (eq. 20 with the drift term, the study's `fit: (order: 4)`); the mean first harmonic
   over the revolutions; the radius error at the PIGA plane `−d_c1·(h_p + h_a)/h_p`
   (probe against O1X1, eq. 21–22) with the white-noise σ of the mean d_c1 (pooled residual
   variance, `2s²/n` per revolution, the drift term's inflation along sin θ₀).
4. C_r: the weighted fit of `a + C_r·ω²` (inverse variance, Birge ratio applied above 1).
5. PIGA recordings (as `recording::reduce_piga_recording`): the output less its end-to-end
   trend, per revolution `lstsq` of `1, t − t_mid, cos kφ, sin kφ (k ≤ 2)`, the mean slope
   over the revolutions plus the trend; σ from the pooled residual variance times each
   revolution's exact `[(XᵀX)⁻¹]` of the slope; the standard error across revolutions when
   the slopes scatter beyond white noise (χ² 99 % limit, Wilson–Hilferty).
6. The joint eq. 23 fit of both mountings (the columns of `calibration::two_orientation_row`),
   weighted by 1/σ, columns scaled, covariance `(XᵀWX)⁻¹` times the squared Birge ratio
   when above 1; k2, γ and C = γ·g/k̄1.
7. The measurement model of `calibration::TwoOrientationModel` (the ten coefficients, g, the rate
   scale, both radii, the probe's lever heights, gain and C_r), its GUM u by a numerical
   Jacobian, and a vectorised Monte Carlo of it (the coefficients as one multivariate t group
   with ν = n − 10, C_r a t with the phase's ν, Type B inputs normal) with as many trials as
   the Rust adaptive run reached (`two_orientation.monte_carlo.trials`).

It prints k2, C, their u (GUM and Monte Carlo) and the Rust values, and fails (exit 1) when
they disagree beyond the tolerances stated in TOLERANCES below. The script declares the
study as the study file does (DECLARED, TYPE_B) and refuses a results.json whose budget
carries a Type B input it does not model. numpy only (scipy is not needed).
"""
import argparse
import glob
import json
import math
import os
import sys
import time

import numpy as np

TAU = 2.0 * math.pi

# The study's declarations (fixtures/studies/two_orientation_recordings.ron).
DECLARED = {
    "radius_m": {"ia_in": 2.5, "ia_out": 2.54},
    "g_m_s2": 9.8,
    "pivot_to_probe_mm": 700.0,
    "probe_to_piga_mm": 510.0,
    "probe_sign": -1.0,  # probe_direction: against_o1_x1
    "probe_order": 4,  # phases[0].points.fit.order (drift: true, the study's default)
    "piga_order": 2,  # two_orientation.orientations[*].recordings.order (default 2)
    "max_gap_intervals": 3.0,
}
# Type B standard uncertainties (the study's `uncertainty:`), as the budget
# in results.json names them.
TYPE_B = {
    "g (gravity)": 1.0e-5,
    "rate scale (common to every rate)": 1.0e-6,
    "R of the IA-in mounting (independent of the IA-out one)": 5.0e-6,
    "R of the IA-out mounting (independent of the IA-in one)": 5.0e-6,
    "pivot-to-probe height": 0.5,
    "probe-to-PIGA height": 0.5,
    "probe gain": 2.0e-3,
}

# Agreement with the Rust results.json. Deterministic quantities (the fits, the GUM) in
# relative terms or in units of the quantity's u; the Monte Carlo mean and u in units of
# the standard error of the difference of two independent runs.
TOLERANCES = {
    "value_in_u": 1e-6,  # |k2 − k2_rust| / u(k2), |C − C_rust| / u(C), C_r likewise
    "u_relative": 1e-6,  # GUM u(k2), u(C), u(C_r)
    "point_relative": 1e-9,  # each PIGA point's output rate and its σ, each probe point
    "mc_se": 4.5,  # Monte Carlo mean and u of k2 and C, in standard errors of the difference
}


# ---------------------------------------------------------------------------------------
# Revolutions and per-revolution fits


def revolutions(angle_rad, max_gap_intervals):
    """Whole revolutions (start, stop) from an encoder angle that may wrap at 2π."""
    x = angle_rad - angle_rad[0]
    phase = x - np.floor(x / TAU) * TAU
    d = np.diff(angle_rad)
    step = d - np.round(d / TAU) * TAU
    starts = np.flatnonzero(phase[:-1] + step >= TAU) + 1
    bounds = np.concatenate([[0], starts, [len(angle_rad)]])
    nominal_step = (TAU * (len(bounds) - 2) + phase[-1]) / (len(angle_rad) - 1)
    ranges = []
    for r, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        last = r == len(bounds) - 2
        if last and TAU - (phase[b - 1] - phase[a]) > max_gap_intervals * nominal_step:
            continue  # the trailing revolution is incomplete
        ranges.append((int(a), int(b)))
    return ranges


def measured_rate(time_s, angle_rad, ranges, declared_rad_s):
    """The encoder's mean rate over the whole revolutions, rad/s, within 2 % of the
    declared one (else the file is attached to the wrong rate)."""
    first = ranges[0][0]
    last = min(ranges[-1][1], len(angle_rad) - 1)
    u = np.unwrap(angle_rad[first : last + 1])
    rate = (u[-1] - u[0]) / (time_s[last] - time_s[first])
    if abs(rate - declared_rad_s) > 0.02 * declared_rad_s:
        raise SystemExit(f"measured rate {rate} rad/s is not the declared {declared_rad_s}")
    return rate


def harmonic_design(t, phi, order, slope_first):
    """Columns 1, [t − t_mid], cos kφ, sin kφ (k ≤ order), [t − t_mid]."""
    k = np.arange(1, order + 1)
    kp = np.outer(phi, k)
    ramp = (t - 0.5 * (t[0] + t[-1]))[:, None]
    one = np.ones((len(t), 1))
    if slope_first:
        return np.hstack([one, ramp, np.cos(kp), np.sin(kp)])
    return np.hstack([one, np.cos(kp), np.sin(kp), ramp])


# ---------------------------------------------------------------------------------------
# The probe phase


def lever_ratio():
    """(h_p + h_a)/h_p: the probe plane's first harmonic carried to the PIGA plane."""
    h_p, h_a = DECLARED["pivot_to_probe_mm"], DECLARED["probe_to_piga_mm"]
    return (h_p + h_a) / h_p


def probe_point(rec, declared_rate_rad_s):
    """Radius error at the PIGA plane (µm) and its σ, and the measured rate, of one probe
    recording."""
    t, gap, angle = rec[:, 0], rec[:, 1], np.deg2rad(rec[:, 2])
    order = DECLARED["probe_order"]
    ranges = revolutions(angle, DECLARED["max_gap_intervals"])
    coef, rss, n = [], 0.0, []
    for a, b in ranges:
        X = harmonic_design(t[a:b], angle[a:b], order, slope_first=False)
        c, res, _, _ = np.linalg.lstsq(X, gap[a:b], rcond=None)
        coef.append(c)
        rss += float(res[0]) if res.size else float(np.sum((gap[a:b] - X @ c) ** 2))
        n.append(b - a)
    coef = np.array(coef)
    n = np.array(n, dtype=float)
    params = 2 * order + 2
    s2 = rss / max(np.sum(np.maximum(n - params, 0)), 1)
    # The drift term's variance inflation along sin(θ − θ₀): (2 + v)/v,
    # v = π²/3 − 2Σ1/k².
    v = math.pi**2 / 3 - 2 * sum(1.0 / k**2 for k in range(1, order + 1))
    inflation = (2 + v) / v
    sin0 = np.sin(angle[[a for a, _ in ranges]])
    var_c1 = np.sum(2 * s2 / n * (1 + (inflation - 1) * sin0**2))
    k_rev = len(ranges)
    dc1 = coef[:, 1].mean()
    lever = lever_ratio()
    return {
        "rate_rad_s": measured_rate(t, angle, ranges, declared_rate_rad_s),
        "radius_error_um": DECLARED["probe_sign"] * dc1 * lever,
        "sigma_um": math.sqrt(var_c1) / k_rev * lever,
        "revolutions": k_rev,
    }


def weighted_lstsq(X, y, sigma):
    """Weighted least squares with scaled columns: coefficients, covariance (XᵀWX)⁻¹ times
    the squared Birge ratio when above 1, Birge ratio, dof, and the unscaled pieces."""
    w = 1.0 / sigma
    Xw, yw = X * w[:, None], y * w
    scale = 1.0 / np.linalg.norm(Xw, axis=0)
    Xs = Xw * scale
    cs, _, rank, sv = np.linalg.lstsq(Xs, yw, rcond=None)
    if rank < X.shape[1]:
        raise SystemExit("rank-deficient design")
    coef = cs * scale
    _, s, vt = np.linalg.svd(Xs, full_matrices=False)
    unscaled = (vt.T / s**2) @ vt * np.outer(scale, scale)
    dof = X.shape[0] - X.shape[1]
    birge = math.sqrt(np.sum((yw - Xw @ coef) ** 2) / dof)
    return {
        "coef": coef,
        "cov": unscaled * max(birge, 1.0) ** 2,
        "birge": birge,
        "dof": dof,
        "Xs": Xs,
        "scale": scale,
        "w": w,
    }


def c_r_fit(points):
    w = np.array([p["rate_rad_s"] for p in points])
    r = np.array([p["radius_error_um"] for p in points]) * 1e-6
    s = np.array([p["sigma_um"] for p in points]) * 1e-6
    f = weighted_lstsq(np.column_stack([np.ones_like(w), w * w]), r, s)
    return {"c_r": f["coef"][1], "u": math.sqrt(f["cov"][1, 1]), "dof": f["dof"]}


# ---------------------------------------------------------------------------------------
# The PIGA recordings


def chi_square_ratio_99(nu):
    """99 % quantile of χ²(ν)/ν (Wilson–Hilferty)."""
    a = 2.0 / (9.0 * nu)
    return (1.0 - a + 2.326348 * math.sqrt(a)) ** 3


def piga_point(rec, declared_rate_rad_s):
    """Mean output rate over whole revolutions, its σ, and the measured rate."""
    t, y, angle = rec[:, 0], rec[:, 1], np.deg2rad(rec[:, 2])
    order = DECLARED["piga_order"]
    trend = (y[-1] - y[0]) / (t[-1] - t[0])
    yd = y - (y[0] + trend * (t - t[0]))
    ranges = revolutions(angle, DECLARED["max_gap_intervals"])
    slopes, factors, rss, dof = [], [], 0.0, 0
    for a, b in ranges:
        X = harmonic_design(t[a:b], angle[a:b], order, slope_first=True)
        c, res, _, _ = np.linalg.lstsq(X, yd[a:b], rcond=None)
        slopes.append(c[1])
        rss += float(res[0]) if res.size else float(np.sum((yd[a:b] - X @ c) ** 2))
        dof += max(b - a - (2 * order + 2), 0)
        factors.append(np.linalg.inv(X.T @ X)[1, 1])
    slopes, factors = np.array(slopes), np.array(factors)
    k = len(slopes)
    s2 = rss / max(dof, 1)
    white = math.sqrt(np.sum(s2 * factors)) / k
    per_revolution_white = math.sqrt(np.sum(s2 * factors) / k)
    sd = slopes.std(ddof=1)
    se = sd / math.sqrt(k)
    u = white if math.isfinite(white) else se
    spread = False
    limit = chi_square_ratio_99(k - 1)
    if k >= 3 and per_revolution_white > 0 and (sd / per_revolution_white) ** 2 > limit:
        spread = True
        u = max(u, se)
    return {
        "rate_rad_s": measured_rate(t, angle, ranges, declared_rate_rad_s),
        "output_rad_s": trend + slopes.mean(),
        "u_rad_s": u,
        "revolutions": k,
        "output_spread": spread,
    }


# ---------------------------------------------------------------------------------------
# The joint fit of eq. 23 and its measurement model

K2, K3, GAMMA, B3 = 7, 8, 9, 6


def two_orientation_rows(sign, radius_m, g, w):
    """Rows of eq. 23 (calibration::two_orientation_row) for one mounting at rates w (rad/s)."""
    a = radius_m * w * w / g
    X = np.zeros((len(w), 10))
    base = 0 if sign > 0 else 3
    X[:, base] = 1.0
    X[:, base + 1] = sign * w
    X[:, base + 2] = sign * a
    X[:, B3] = sign * w**3
    X[:, K2] = a * a
    X[:, K3] = sign * a**3
    X[:, GAMMA] = sign * w**4
    return X


def joint_fit(mountings, g):
    rows, y, sigma, w_all = [], [], [], []
    for name, sign in (("ia_in", 1.0), ("ia_out", -1.0)):
        pts = mountings[name]
        w = np.array([p["rate_rad_s"] for p in pts])
        rows.append(two_orientation_rows(sign, DECLARED["radius_m"][name], g, w))
        y.append([p["output_rad_s"] for p in pts])
        sigma.append([p["u_rad_s"] for p in pts])
        w_all.append(w)
    X, y = np.vstack(rows), np.concatenate(y)
    sigma, w = np.concatenate(sigma), np.concatenate(w_all)
    f = weighted_lstsq(X, y, sigma)
    # The response to a common ω⁶ through the same weighted, scaled design (the model's
    # correction for a change of shape of the s·a³ column).
    f["omega6"] = np.linalg.lstsq(f["Xs"], w**6 * f["w"], rcond=None)[0] * f["scale"]
    return f


def model(x, fit, g0, c_r_lever0):
    """k2, C and C − C_r (3 × m) of calibration::TwoOrientationModel for inputs x (18 × m: one
    contiguous row per input, so that each operation runs over a contiguous array)."""
    r_in0 = DECLARED["radius_m"]["ia_in"] / g0
    r_out0 = DECLARED["radius_m"]["ia_out"] / g0
    c = x[:10]
    g, scale, r_in, r_out = x[10], x[11], x[12], x[13]
    h_p, h_a, gain, c_r = x[14], x[15], x[16], x[17]
    s2 = scale * scale
    rho_in = (r_in * s2 / g) / r_in0
    rho_out = (r_out * s2 / g) / r_out0
    a0_in, a0_out = r_in0**2, r_out0**2
    e_in = c[K2] * a0_in + c[GAMMA]
    e_out = c[K2] * a0_out - c[GAMMA]
    a_in, a_out = rho_in**2 * a0_in, rho_out**2 * a0_out
    k2 = (e_in + e_out) / (a_in + a_out)
    gamma = (e_in * a_out - e_out * a_in) / ((a_in + a_out) * s2 * s2)
    p_in, p_out = a0_in * r_in0, a0_out * r_out0
    q_in, q_out = rho_in**3 * p_in, rho_out**3 * p_out
    d = (p_in * q_out - p_out * q_in) / (q_in + q_out)
    k3d = c[K3] * d
    o6 = fit["omega6"]
    k1_in = c[2] / rho_in + k3d * o6[2]
    k1_out = c[5] / rho_out + k3d * o6[5]
    k2 = k2 + k3d * o6[K2]
    gamma = gamma + k3d * o6[GAMMA]
    c_total = gamma * g / (0.5 * (k1_in + k1_out))
    lever = (h_p + h_a) / h_p
    c_r_true = c_r * gain * (lever / c_r_lever0) / s2
    return np.stack([k2, c_total, c_total - c_r_true])


OUTPUTS = ["k2", "C", "C − C_r"]


def inputs_of(fit, probe):
    """Values, standard uncertainties and degrees of freedom of the model's 18 inputs, and
    the coefficients' correlation."""
    se = np.sqrt(np.diag(fit["cov"]))
    values = np.concatenate(
        [
            fit["coef"],
            [DECLARED["g_m_s2"], 1.0],
            [DECLARED["radius_m"]["ia_in"], DECLARED["radius_m"]["ia_out"]],
            [DECLARED["pivot_to_probe_mm"], DECLARED["probe_to_piga_mm"], 1.0, probe["c_r"]],
        ]
    )
    b = list(TYPE_B.values())
    u = np.concatenate([se, b[:4], b[4:7], [probe["u"]]])
    corr = fit["cov"] / np.outer(se, se)
    return values, u, corr


def gum(values, u, corr, fit, lever0):
    """GUM standard uncertainties of the outputs: central differences, u = √(J V Jᵀ)."""
    n = len(values)
    V = np.diag(u**2)
    V[:10, :10] = corr * np.outer(u[:10], u[:10])
    h = np.where(u > 0, u * 1e-3, 0.0)
    x = np.tile(values[:, None], (1, 2 * n + 1))
    for i in range(n):
        x[i, 1 + 2 * i] += h[i]
        x[i, 2 + 2 * i] -= h[i]
    y = model(x, fit, DECLARED["g_m_s2"], lever0)
    J = np.zeros((y.shape[0], n))
    for i in range(n):
        if h[i] > 0:
            J[:, i] = (y[:, 1 + 2 * i] - y[:, 2 + 2 * i]) / (2 * h[i])
    return y[:, 0], np.sqrt(np.einsum("oi,ij,oj->o", J, V, J))


def monte_carlo(values, u, corr, fit, probe, lever0, trials, seed, chunk=1 << 17):
    """Vectorised Monte Carlo of the model (JCGM 101): per output the mean, u, the
    probabilistically symmetric 95 % interval, and the standard errors of mean and u."""
    rng = np.random.default_rng(seed)
    nu = fit["dof"]
    chol = np.linalg.cholesky(corr)
    out = []
    for start in range(0, trials, chunk):
        m = min(chunk, trials - start)
        x = np.empty((len(values), m))
        x[:] = values[:, None]
        z = chol @ rng.standard_normal((10, m))
        x[:10] += u[:10, None] * z * np.sqrt(nu / rng.chisquare(nu, m))
        for i in range(10, 17):
            if u[i] > 0:
                x[i] += u[i] * rng.standard_normal(m)
        x[17] += u[17] * rng.standard_t(probe["dof"], m)
        out.append(model(x, fit, DECLARED["g_m_s2"], lever0))
    y = np.concatenate(out, axis=1)
    mean = y.mean(axis=1)
    sd = y.std(axis=1, ddof=1)
    q = int(math.floor(0.95 * trials + 0.5))
    r = max((trials - q + 1) // 2, 1)
    lo, hi = r - 1, min(r + q - 1, trials - 1)
    part = np.partition(y, [lo, hi], axis=1)
    kurtosis = ((y - mean[:, None]) ** 4).mean(axis=1) / sd**4
    return {
        "mean": mean,
        "u": sd,
        "low95": part[:, lo],
        "high95": part[:, hi],
        "se_mean": sd / math.sqrt(trials),
        "se_u": sd * np.sqrt((kurtosis - 1.0) / (4.0 * trials)),
    }


# ---------------------------------------------------------------------------------------
# The job, timed


def files_of(folder):
    probe = sorted(glob.glob(os.path.join(folder, "probe_*deg_s.csv")))
    piga = {
        o: sorted(glob.glob(os.path.join(folder, f"piga_{o}_*deg_s.csv")))
        for o in ("ia_in", "ia_out")
    }
    if len(probe) != 12 or any(len(v) != 12 for v in piga.values()):
        raise SystemExit(f"{folder}: expected 12 probe and 2 × 12 PIGA recordings")
    return probe, piga


def declared_rate_rad_s(path):
    """The declared rate from the file name (`…_035.0000deg_s.csv`), rad/s."""
    return math.radians(float(os.path.basename(path).rsplit("_", 2)[-2].replace("deg", "")))


def study(folder, trials, seed):
    stages = {}
    t0 = time.perf_counter()
    probe_files, piga_files = files_of(folder)
    load = lambda f: np.loadtxt(f, delimiter=",", skiprows=1)
    probe_recs = [load(f) for f in probe_files]
    piga_recs = {o: [load(f) for f in fs] for o, fs in piga_files.items()}
    t1 = time.perf_counter()
    stages["loadtxt (36 files)"] = t1 - t0
    probe_points = [probe_point(r, declared_rate_rad_s(f)) for r, f in zip(probe_recs, probe_files)]
    probe = c_r_fit(probe_points)
    t2 = time.perf_counter()
    stages["probe: per-revolution lstsq, C_r fit"] = t2 - t1
    mountings = {
        o: [piga_point(r, declared_rate_rad_s(f)) for r, f in zip(recs, piga_files[o])]
        for o, recs in piga_recs.items()
    }
    t3 = time.perf_counter()
    stages["PIGA: per-revolution lstsq (24 files)"] = t3 - t2
    fit = joint_fit(mountings, DECLARED["g_m_s2"])
    lever0 = lever_ratio()
    values, u, corr = inputs_of(fit, probe)
    estimate, u_gum = gum(values, u, corr, fit, lever0)
    t4 = time.perf_counter()
    stages["joint eq. 23 fit, GUM"] = t4 - t3
    mc = monte_carlo(values, u, corr, fit, probe, lever0, trials, seed)
    t5 = time.perf_counter()
    stages[f"Monte Carlo ({trials} trials)"] = t5 - t4
    return {
        "probe_points": probe_points,
        "probe": probe,
        "mountings": mountings,
        "fit": fit,
        "estimate": estimate,
        "u_gum": u_gum,
        "mc": mc,
        "stages": stages,
        "total_s": t5 - t0,
    }


def compare(res, rust):
    """Checks against the Rust results.json; returns (rows, failures)."""
    s = rust["two_orientation"]
    rows, failures = [], []

    def check(name, ok, detail):
        rows.append((name, "ok" if ok else "FAIL", detail))
        if not ok:
            failures.append(name)

    # Type B inputs the script models, against the budget the Rust study used.
    seen = set()
    for line in s["budget"]["k2"] + s["budget"]["c"]:
        if line["evaluation"] != "B" or line["quantity"] in seen:
            continue
        seen.add(line["quantity"])
        mine = TYPE_B.get(line["quantity"])
        check(
            f"Type B input `{line['quantity']}`",
            mine is not None and math.isclose(mine, line["u"], rel_tol=1e-12, abs_tol=0.0),
            f"script u = {mine}, Rust u = {line['u']}",
        )
    # Each point.
    worst = 0.0
    for o, m in zip(("ia_in", "ia_out"), s["mountings"]):
        for mine, theirs in zip(res["mountings"][o], m["recordings"]):
            for a, b in (
                (mine["output_rad_s"], theirs["output_rad_s"]),
                (mine["u_rad_s"], theirs["u_rad_s"]),
                (math.degrees(mine["rate_rad_s"]), theirs["rate_deg_s"]),
            ):
                worst = max(worst, abs(a / b - 1.0))
    check(
        "24 PIGA points (output, σ, rate)",
        worst <= TOLERANCES["point_relative"],
        f"largest relative difference {worst:.1e}",
    )
    phase = next(p for p in rust["phases"] if p["name"] == s["probe"]["phase"])
    worst = 0.0
    for mine, theirs in zip(res["probe_points"], phase["points"]):
        for a, b in (
            (mine["radius_error_um"], theirs["radius_error_um"]),
            (mine["sigma_um"], theirs["radius_error_sigma_um"]),
            (mine["rate_rad_s"], theirs["rate_rad_s"]),
        ):
            worst = max(worst, abs(a / b - 1.0))
    check(
        "12 probe points (radius error, σ, rate)",
        worst <= TOLERANCES["point_relative"],
        f"largest relative difference {worst:.1e}",
    )
    c_r = s["probe"]["c_r_m_s2"]
    d = abs(res["probe"]["c_r"] - c_r["value"]) / c_r["u"]
    check("C_r", d <= TOLERANCES["value_in_u"], f"|Δ| = {d:.1e} u")
    d = abs(res["probe"]["u"] / c_r["u"] - 1.0)
    check("u(C_r)", d <= TOLERANCES["u_relative"], f"relative Δ = {d:.1e}")
    # k2 and C, GUM.
    for k, key in ((0, "k2"), (1, "c_m_s2")):
        r = s[key]
        d = abs(res["estimate"][k] - r["value"]) / r["u"]
        check(f"{OUTPUTS[k]} value", d <= TOLERANCES["value_in_u"], f"|Δ| = {d:.1e} u")
        d = abs(res["u_gum"][k] / r["u"] - 1.0)
        check(f"u({OUTPUTS[k]}) GUM", d <= TOLERANCES["u_relative"], f"relative Δ = {d:.1e}")
    # k2 and C, Monte Carlo: two independent runs, so the SE of the difference is √2 SE.
    mc, mc_rust = res["mc"], s["monte_carlo"]
    for k, key in ((0, "k2"), (1, "c")):
        r = mc_rust[key]
        z_mean = (mc["mean"][k] - r["mean"]) / (math.sqrt(2) * mc["se_mean"][k])
        z_u = (mc["u"][k] - r["u"]) / (math.sqrt(2) * mc["se_u"][k])
        limit = TOLERANCES["mc_se"]
        check(f"{OUTPUTS[k]} Monte Carlo mean", abs(z_mean) <= limit, f"{z_mean:+.2f} SE")
        check(f"u({OUTPUTS[k]}) Monte Carlo", abs(z_u) <= limit, f"{z_u:+.2f} SE")
    return rows, failures


def output_summary(res, s, k, key, mc_key):
    """Output k of the script beside the Rust study's (JSON)."""
    return {
        "value": res["estimate"][k],
        "u_gum": res["u_gum"][k],
        "u_mc": res["mc"]["u"][k],
        "mc_interval": [res["mc"]["low95"][k], res["mc"]["high95"][k]],
        "rust": {
            "value": s[key]["value"],
            "u_gum": s[key]["u"],
            "u_mc": s["monte_carlo"][mc_key]["u"],
            "mc_interval": [s["monte_carlo"][mc_key]["low95"], s["monte_carlo"][mc_key]["high95"]],
        },
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "results", help="results.json of the Rust study: compared with, and its trial count used"
    )
    ap.add_argument(
        "--data", help="folder of the 36 CSV files (default: fixtures/two_orientation_recordings)"
    )
    ap.add_argument("--repeat", type=int, default=5, help="runs of the whole job; best reported")
    ap.add_argument("--trials", type=int, help="Monte Carlo trials (default: the Rust run's)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the first run (run r: seed + r)")
    ap.add_argument("--json", action="store_true", help="print JSON instead of text")
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    folder = args.data or os.path.join(root, "fixtures", "two_orientation_recordings")
    with open(args.results) as f:
        rust = json.load(f)
    trials = args.trials or rust["two_orientation"]["monte_carlo"]["trials"]

    times, best = [], None
    for r in range(args.repeat):
        res = study(folder, trials, args.seed + r)
        times.append(res["total_s"])
        if best is None or res["total_s"] < best["total_s"]:
            best = res
    rows, failures = compare(res, rust)  # the last run's numbers
    s = rust["two_orientation"]
    summary = {
        "numpy": np.__version__,
        "trials": trials,
        "repeat": args.repeat,
        "best_s": min(times),
        "times_s": times,
        "best_stages_s": best["stages"],
        "k2": output_summary(res, s, 0, "k2", "k2"),
        "C": output_summary(res, s, 1, "c_m_s2", "c"),
        "c_r": {"value": res["probe"]["c_r"], "u": res["probe"]["u"]},
        "checks": [{"check": n, "result": v, "detail": d} for n, v, d in rows],
        "agrees": not failures,
    }
    if args.json:
        print(json.dumps(summary, indent=1))
    else:
        runs = ", ".join(f"{t:.4f}" for t in times)
        print(
            f"numpy {np.__version__}; {trials} Monte Carlo trials; "
            f"best of {args.repeat}: {min(times):.4f} s (runs: {runs})"
        )
        for name, t in best["stages"].items():
            print(f"  {name:<42} {t * 1e3:8.2f} ms")
        for k, key, mkey in ((0, "k2", "k2"), (1, "c_m_s2", "c")):
            print(f"{OUTPUTS[k]:>3} = {res['estimate'][k]:.10e}  u(GUM) = {res['u_gum'][k]:.6e}  "
                  f"u(MC) = {res['mc']['u'][k]:.6e}")
            print(f"{'Rust':>3} = {s[key]['value']:.10e}  u(GUM) = {s[key]['u']:.6e}  "
                  f"u(MC) = {s['monte_carlo'][mkey]['u']:.6e}")
        print(f"C_r = {res['probe']['c_r']:.10e}  u = {res['probe']['u']:.6e}")
        for name, verdict, detail in rows:
            print(f"  [{verdict}] {name}: {detail}")
        if failures:
            print(f"DISAGREES: {', '.join(failures)}")
        else:
            print("agrees with the Rust results")
    sys.exit(0 if not failures else 1)


if __name__ == "__main__":
    main()

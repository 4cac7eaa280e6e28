//! The terms of eq. 23: the orientations, the coefficients in the fit's order, the limits
//! the evaluation applies, one data set, and one design row.

/// Which way the PIGA's input axis points on the arm (one home: `accel_model`, shared with
/// the simulator's mountings).
pub use accel_model::Orientation;

/// Position of an orientation in the fit's mountings: IA in, then IA out.
pub(super) const fn index(o: Orientation) -> usize {
    match o {
        Orientation::IaIn => 0,
        Orientation::IaOut => 1,
    }
}

/// Least number of distinct rates per orientation: the six of a single eq. 18 fit, so that
/// each mounting could also be fitted on its own (the joint fit itself needs four).
pub const MIN_RATES_PER_ORIENTATION: usize = 6;

/// Number of coefficients of eq. 23.
pub const TWO_ORIENTATION_TERMS: usize = 10;

/// The coefficients of eq. 23 in the fit's order.
pub const TWO_ORIENTATION_TERM_NAMES: [&str; TWO_ORIENTATION_TERMS] = [
    "k0 (IA in)",
    "b1 (IA in)",
    "k1 (IA in)",
    "k0 (IA out)",
    "b1 (IA out)",
    "k1 (IA out)",
    "b3",
    "k2",
    "k3",
    "gamma = k1·C/g",
];

/// Index of the b3 (`s·ω³`) coefficient.
pub const B3_TERM: usize = 6;
/// Index of the k2 coefficient.
pub const K2_TERM: usize = 7;
/// Index of the k3 (`s·a_s³`) coefficient.
pub const K3_TERM: usize = 8;
/// Index of the `s·ω⁴` coefficient γ = k1·C/g.
pub const GAMMA_TERM: usize = 9;

/// The variance inflation factor of the `s·ω⁴` term named by issue 20 (1e4). Kept as a
/// reference for the diagnostic only: the ordinary design (35–200 °/s, both mountings) has a
/// VIF of 1.2e6 and gives C with 3 % relative U, so no warning is based on it (see
/// [`K2_INFLATION_LIMIT`]).
pub const GAMMA_VIF_LIMIT: f64 = 1e4;

/// The factor by which fitting C (the `s·ω⁴` column) may widen u(k2) over the same fit with
/// C known before the study says k2 and C cannot be told apart: the limit of the
/// single-orientation calibration's warning (`crate::INFLATION_LIMIT`, 3), i.e. the
/// correlation of the k2 and C estimates above √(8/9) ≈ 0.943.
pub const K2_INFLATION_LIMIT: f64 = crate::INFLATION_LIMIT;

/// The |z| above which `C − C_r` is reported as a disagreement between the PIGA and the probe.
pub const Z_LIMIT: f64 = 3.0;

/// One orientation's data set: a PIGA table (or the points reduced from raw recordings).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientationData<'a> {
    /// Where it came from, for errors (`two_orientation.orientations[1]`).
    pub field: &'a str,
    /// IA in or out (`None`: not declared).
    pub orientation: Option<Orientation>,
    /// The mounting's static radius, m (`None`: not declared).
    pub radius_m: Option<f64>,
    /// Spindle rates, rad/s.
    pub rates_rad_s: &'a [f64],
    /// Mean PIGA outputs, rad/s.
    pub output_rad_s: &'a [f64],
    /// Standard uncertainties of the outputs, rad/s (raw recordings); `None`: unweighted.
    pub sigma_rad_s: Option<&'a [f64]>,
}

/// Number of distinct rates.
pub(super) fn distinct(rates: &[f64]) -> usize {
    let mut v: Vec<f64> = rates.to_vec();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.len()
}

/// One row of eq. 23's design for a point of orientation `o` at radius `radius_m`.
#[must_use]
pub fn two_orientation_row(
    o: Orientation,
    radius_m: f64,
    g_m_s2: f64,
    rate_rad_s: f64,
) -> [f64; TWO_ORIENTATION_TERMS] {
    let s = o.sign();
    let w = rate_rad_s;
    let a = radius_m * w * w / g_m_s2;
    let mut row = [0.0; TWO_ORIENTATION_TERMS];
    let base = 3 * index(o);
    row[base] = 1.0;
    row[base + 1] = s * w;
    row[base + 2] = s * a;
    row[B3_TERM] = s * w * w * w;
    row[K2_TERM] = a * a;
    row[K3_TERM] = s * a * a * a;
    row[GAMMA_TERM] = s * w * w * w * w;
    row
}

/// Eq. 23's design row at a rate as `(constant, power of ω)` per column (`None`: zero): the
/// form the fit builds its design from, in double-double. With `k = R/g`: `1`, `s·ω`,
/// `s·k·ω²` (= s·a), `s·ω³`, `k²·ω⁴` (= a²), `s·k³·ω⁶` (= s·a³), `s·ω⁴`; the constants are
/// those the joint fit over several mountings forms for IA in and IA out
/// (`crate::fit_mountings`), bit for bit.
pub(super) fn two_orientation_terms(
    o: Orientation,
    radius_m: f64,
    g_m_s2: f64,
) -> [Option<(f64, u32)>; TWO_ORIENTATION_TERMS] {
    let s = o.sign();
    let k = radius_m / g_m_s2;
    let sk = s * k;
    let mut row = [None; TWO_ORIENTATION_TERMS];
    let base = 3 * index(o);
    row[base] = Some((1.0, 0));
    row[base + 1] = Some((s, 1));
    row[base + 2] = Some((sk, 2));
    row[B3_TERM] = Some((s, 3));
    row[K2_TERM] = Some((sk * sk, 4));
    row[K3_TERM] = Some((sk * sk * sk, 6));
    row[GAMMA_TERM] = Some((s, 4));
    row
}

//! Before any fit: which chosen terms the chosen mountings cannot separate. The rank of the
//! (weighted, column-normalised) design by its singular values; for each direction the data
//! cannot see, the columns it mixes; for each chosen term the u inflation against a design
//! that separates every term (the same mountings with every preset added, at the same number
//! of points); and, for each problem, the preset mounting whose addition fixes it.

use accel_model::{Mounting, MountingPreset};
use nalgebra::DMatrix;

use super::column::Column;
use super::design::build;
use super::error::MountingsError;
use super::report::{Confounded, PoorlySeparated, Separability};
use super::spec::{JointSpec, MountingData, Nuisances};
use crate::INFLATION_LIMIT;

/// A singular value below this fraction of the largest (columns scaled to unit norm) is a
/// direction the data cannot see: a condition number above 1e9 leaves no digit of the
/// coefficients it mixes at the noise of any real test.
pub const RANK_TOLERANCE: f64 = 1e-9;

/// A component of a null direction above this fraction of its largest names its column as
/// one of those mixed.
const INVOLVED: f64 = 0.05;

/// The weighted design's SVD summary: unit-noise variances of the columns (∞ for a column in
/// a null direction), the null directions, the condition number, the unit covariance.
struct Svd {
    variance: Vec<f64>,
    nulls: Vec<Vec<f64>>,
    condition: f64,
    correlation: Option<DMatrix<f64>>,
}

fn svd_of(x: &DMatrix<f64>) -> Svd {
    let n = x.ncols();
    let norms: Vec<f64> = (0..n)
        .map(|j| x.column(j).norm().max(f64::MIN_POSITIVE))
        .collect();
    let b = DMatrix::from_fn(x.nrows(), n, |i, j| x[(i, j)] / norms[j]);
    let svd = b.svd(false, true);
    let s = &svd.singular_values;
    let smax = s.iter().fold(0.0_f64, |a, &v| a.max(v));
    let Some(vt) = svd.v_t else {
        return Svd {
            variance: vec![f64::INFINITY; n],
            nulls: Vec::new(),
            condition: f64::INFINITY,
            correlation: None,
        };
    };
    let mut nulls = Vec::new();
    let mut inv: DMatrix<f64> = DMatrix::zeros(n, n);
    let mut smin = f64::INFINITY;
    for k in 0..s.len() {
        let v: Vec<f64> = (0..n).map(|j| vt[(k, j)]).collect();
        if s[k] <= RANK_TOLERANCE * smax {
            nulls.push(v);
        } else {
            smin = smin.min(s[k]);
            for a in 0..n {
                for c in 0..n {
                    inv[(a, c)] += v[a] * v[c] / (s[k] * s[k]);
                }
            }
        }
    }
    let mut variance: Vec<f64> = (0..n)
        .map(|j| inv[(j, j)] / (norms[j] * norms[j]))
        .collect();
    for null in &nulls {
        let big = null.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for (j, v) in null.iter().enumerate() {
            if v.abs() > INVOLVED * big {
                variance[j] = f64::INFINITY;
            }
        }
    }
    let correlation = nulls.is_empty().then(|| {
        DMatrix::from_fn(n, n, |a, c| {
            inv[(a, c)] / (inv[(a, a)] * inv[(c, c)]).sqrt()
        })
    });
    Svd {
        variance,
        nulls,
        condition: if nulls_empty(s, smax) {
            smax / smin
        } else {
            f64::INFINITY
        },
        correlation,
    }
}

fn nulls_empty(s: &nalgebra::DVector<f64>, smax: f64) -> bool {
    s.iter().all(|&v| v > RANK_TOLERANCE * smax)
}

/// The design of `data` weighted by its σ, as doubles.
fn weighted(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    arm_stretch: bool,
) -> Result<(Vec<Column>, DMatrix<f64>), MountingsError> {
    let d = build(spec, data, arm_stretch)?;
    let mut x = d.design.to_matrix();
    for (r, &(m, i)) in d.rows.iter().enumerate() {
        if let Some(s) = data[m].sigma {
            let w = 1.0 / s[i];
            for j in 0..x.ncols() {
                x[(r, j)] *= w;
            }
        }
    }
    Ok((d.columns, x))
}

/// `data` with the preset `p` added (the first mounting's rates, σ and radius; its own bias
/// and ω term).
fn with_preset<'a>(data: &[MountingData<'a>], p: MountingPreset) -> Vec<MountingData<'a>> {
    let first = &data[0];
    let mut out = data.to_vec();
    out.push(MountingData {
        field: format!("added {}", p.tag()),
        mounting: Mounting::preset(p, first.mounting.radius_m, first.mounting.angle_u_deg),
        nuisances: Nuisances::REMOUNTED,
        rates_rad_s: first.rates_rad_s,
        outputs: first.outputs,
        sigma: first.sigma,
    });
    out
}

fn points(data: &[MountingData<'_>]) -> f64 {
    data.iter().map(|d| d.rates_rad_s.len()).sum::<usize>() as f64
}

/// The unit-noise variance per point of each column (variance × points), by column.
fn per_point(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    arm_stretch: bool,
) -> Result<(Vec<Column>, Svd, f64), MountingsError> {
    let (cols, x) = weighted(spec, data, arm_stretch)?;
    Ok((cols, svd_of(&x), points(data)))
}

fn variance_of(cols: &[Column], svd: &Svd, n: f64, c: Column) -> f64 {
    cols.iter()
        .position(|k| *k == c)
        .map_or(f64::INFINITY, |j| svd.variance[j] * n)
}

/// The separability of a declaration's chosen terms by its mountings (checked data; the
/// outputs are not used), with the arm-stretch column when `arm_stretch`.
///
/// # Errors
/// [`MountingsError`] for a declaration or data the fit would refuse.
pub fn separability(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    arm_stretch: bool,
) -> Result<Separability, MountingsError> {
    super::check::check(spec, data)?;
    let (cols, svd, n) = per_point(spec, data, arm_stretch)?;
    let labels: Vec<String> = cols.iter().map(|c| c.label(data)).collect();
    let mut reference = data.to_vec();
    for p in MountingPreset::ALL {
        reference = with_preset(&reference, p);
    }
    let (rcols, rsvd, rn) = per_point(spec, &reference, arm_stretch)?;
    let reported: Vec<Column> = cols
        .iter()
        .copied()
        .filter(|c| matches!(c, Column::Term(_) | Column::ArmStretch))
        .collect();
    let inflation_in = |cs: &[Column], s: &Svd, n: f64, c: Column| {
        (variance_of(cs, s, n, c) / variance_of(&rcols, &rsvd, rn, c)).sqrt()
    };
    let inflation: Vec<(Column, f64)> = reported
        .iter()
        .map(|&c| (c, inflation_in(&cols, &svd, n, c)))
        .collect();
    // the best preset to add for a set of columns: full rank, smallest worst inflation
    let best_fix = |targets: &[Column]| -> Result<Option<MountingPreset>, MountingsError> {
        let mut best: Option<(MountingPreset, f64)> = None;
        for p in MountingPreset::ALL {
            let added = with_preset(data, p);
            let (acols, asvd, an) = per_point(spec, &added, arm_stretch)?;
            if !asvd.nulls.is_empty() {
                continue;
            }
            let worst = targets
                .iter()
                .map(|&c| inflation_in(&acols, &asvd, an, c))
                .fold(0.0_f64, f64::max);
            if worst.is_finite() && best.is_none_or(|(_, b)| worst < b) {
                best = Some((p, worst));
            }
        }
        Ok(best.map(|(p, _)| p))
    };
    let mut confounded = Vec::new();
    for null in &svd.nulls {
        let big = null.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let columns: Vec<Column> = null
            .iter()
            .enumerate()
            .filter(|(_, v)| v.abs() > INVOLVED * big)
            .map(|(j, _)| cols[j])
            .collect();
        let fix = best_fix(&columns)?;
        confounded.push(Confounded {
            labels: columns.iter().map(|c| c.label(data)).collect(),
            columns,
            fix,
        });
    }
    let mut poorly = Vec::new();
    if let Some(corr) = &svd.correlation {
        for &(c, inf) in &inflation {
            if inf <= INFLATION_LIMIT {
                continue;
            }
            let j = cols.iter().position(|k| *k == c).unwrap_or(0);
            let (partner, correlation) = (0..cols.len())
                .filter(|&k| k != j)
                .map(|k| (k, corr[(j, k)]))
                .fold(
                    (j, 0.0_f64),
                    |a, b| if b.1.abs() > a.1.abs() { b } else { a },
                );
            poorly.push(PoorlySeparated {
                column: c,
                label: c.label(data),
                inflation: inf,
                partner: cols[partner].label(data),
                correlation,
                fix: best_fix(&[c])?,
            });
        }
    }
    Ok(Separability {
        labels,
        rank: cols.len() - svd.nulls.len(),
        condition_number: svd.condition,
        confounded,
        poorly,
        inflation,
    })
}

/// Whether the design of `data` has full rank (one SVD; the fit's quick check).
pub(super) fn full_rank(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    arm_stretch: bool,
) -> Result<bool, MountingsError> {
    let (_, x) = weighted(spec, data, arm_stretch)?;
    Ok(svd_of(&x).nulls.is_empty())
}

//! The joint design, once: the columns (the chosen terms, each mounting's nuisance terms, the
//! shared ω³ and arm-stretch terms) and their entries, polynomials in the rate formed in
//! double-double (`identify::Design::polynomials`).
//!
//! The nominal input along case axis j of mounting m at rate ω is `A_j = c_j·a + t_j·b + z_j`
//! (`accel_model::CaseAxes::nominal`) with the radial input
//! `a = (R_m + Δr_xs + C_r·ω²)·ω²/g` and the input across the arm `b = (Δr_ys + C_ry·ω²)·ω²/g`:
//! the declared radius grown by the probe's static drift and C_r, and the drift across the
//! arm (the compensation along each mounting's axes; without a probe both drifts are 0). Every
//! term's column is its regressor of these (`accel_model::Term::regressor`), multiplied out
//! as a polynomial in ω. For a PIGA the known rate about IA, `(ω + Ω_v)·z_i` (the spindle's
//! rate and the vertical Earth rate seen by IA's vertical component), is moved to the left.

use accel_model::Term;
use identify::Design;

use super::column::Column;
use super::error::MountingsError;
use super::spec::{JointSpec, MountingData};

/// The joint design of a declaration and its data.
#[derive(Debug, Clone, PartialEq)]
pub struct JointDesign {
    /// The columns, in the design's order.
    pub columns: Vec<Column>,
    /// The design (unweighted), entries in double-double.
    pub design: Design,
    /// The outputs with a PIGA's known rate about IA moved to the left, in the design's row
    /// order (mounting by mounting, each in its data's order).
    pub y: Vec<f64>,
    /// Each row's mounting and point.
    pub rows: Vec<(usize, usize)>,
}

/// A polynomial in ω: coefficient of ω^p at index p.
type Poly = Vec<f64>;

fn mul(a: &Poly, b: &Poly) -> Poly {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (p, &x) in a.iter().enumerate() {
        if x == 0.0 {
            continue;
        }
        for (q, &y) in b.iter().enumerate() {
            if y != 0.0 {
                out[p + q] += x * y;
            }
        }
    }
    out
}

fn scale(a: &Poly, s: f64) -> Poly {
    a.iter().map(|x| x * s).collect()
}

fn monomial(c: f64, p: usize) -> Poly {
    let mut v = vec![0.0; p + 1];
    v[p] = c;
    v
}

fn eval(a: &Poly, w: f64) -> f64 {
    a.iter().rev().fold(0.0, |acc, c| acc * w + c)
}

/// The nominal inputs `[A_i, A_p, A_o]` of a mounting as polynomials in ω.
fn nominal_inputs(spec: &JointSpec, d: &MountingData<'_>) -> [Poly; 3] {
    let (static_m, c_r, static_y, c_ry) = spec.probe.map_or((0.0, 0.0, 0.0, 0.0), |p| {
        (p.static_m, p.c_r_m_s2, p.static_across_m, p.c_ry_m_s2)
    });
    let g = spec.g_m_s2;
    let k = (d.mounting.radius_m + static_m) / g;
    let (kappa, k_y, kappa_y) = (c_r / g, static_y / g, c_ry / g);
    d.mounting.axes.nominal().map(|n| {
        let mut p = vec![0.0; 5];
        p[0] = n.vertical;
        // the across terms are exactly 0 without a probe (eq. 18 and eq. 23 to the last digit)
        p[2] = n.radial * k + n.across * k_y;
        p[4] = n.radial * kappa + n.across * kappa_y;
        p
    })
}

/// A term's regressor as a polynomial of the nominal inputs (`sign_i`: the sign of `A_i` at
/// the row's rate, for `a_i·|a_i|`).
fn term_poly(t: Term, a: &[Poly; 3], sign_i: f64) -> Poly {
    let [i, p, o] = a;
    match t {
        Term::K0 => monomial(1.0, 0),
        Term::K1 => i.clone(),
        Term::K2 => mul(i, i),
        Term::K3 => mul(&mul(i, i), i),
        Term::K4 => mul(&mul(&mul(i, i), i), i),
        Term::Koq => scale(&mul(i, i), sign_i),
        Term::Kip => mul(i, p),
        Term::Kio => mul(i, o),
        Term::Kpp => mul(p, p),
        Term::Koo => mul(o, o),
        Term::Kpo => mul(p, o),
        Term::DeltaO => p.clone(),
        Term::DeltaP => scale(o, -1.0),
    }
}

/// The columns of a declaration: the chosen terms, each mounting's nuisance terms (none of
/// the first's own bias or scale), the ω³ term and, with `arm_stretch`, the arm stretch.
pub(super) fn columns(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    arm_stretch: bool,
) -> Vec<Column> {
    let mut cols: Vec<Column> = spec.chosen_terms().into_iter().map(Column::Term).collect();
    for (m, d) in data.iter().enumerate() {
        if m > 0 && d.nuisances.own_bias {
            cols.push(Column::OwnBias(m));
        }
        if m > 0 && d.nuisances.own_scale {
            cols.push(Column::OwnScale(m));
        }
        if d.nuisances.tilt_rate {
            cols.push(Column::TiltRate(m));
        }
    }
    if spec.omega3 {
        cols.push(Column::Omega3);
    }
    if arm_stretch {
        cols.push(Column::ArmStretch);
    }
    cols
}

/// The entry polynomial of column `col` for a row of mounting `m` at rate `w`.
fn entry(col: Column, m: usize, d: &MountingData<'_>, a: &[Poly; 3], w: f64) -> Poly {
    let own_bias = m > 0 && d.nuisances.own_bias;
    let own_scale = m > 0 && d.nuisances.own_scale;
    let c_i = d.mounting.axes.nominal()[0].radial;
    let zero = vec![0.0];
    match col {
        Column::Term(Term::K0) if own_bias => zero,
        Column::Term(Term::K1) if own_scale => zero,
        Column::Term(t) => {
            let sign = if eval(&a[0], w) < 0.0 { -1.0 } else { 1.0 };
            term_poly(t, a, sign)
        }
        Column::OwnBias(k) if k == m => monomial(1.0, 0),
        Column::OwnScale(k) if k == m => a[0].clone(),
        Column::TiltRate(k) if k == m => monomial(if c_i < 0.0 { -1.0 } else { 1.0 }, 1),
        Column::Omega3 => monomial(c_i, 3),
        Column::ArmStretch => monomial(c_i, 4),
        _ => zero,
    }
}

/// The design of a declaration and its data (checked), with the arm-stretch column or not.
pub(super) fn build(
    spec: &JointSpec,
    data: &[MountingData<'_>],
    arm_stretch: bool,
) -> Result<JointDesign, MountingsError> {
    let columns = columns(spec, data, arm_stretch);
    let mut rows = Vec::new();
    let mut rates = Vec::new();
    let mut y = Vec::new();
    let mut inputs = Vec::with_capacity(data.len());
    let omega_v = spec.earth_rate_vertical_rad_s;
    let factor = spec.kind.omega_i_factor();
    for (m, d) in data.iter().enumerate() {
        inputs.push(nominal_inputs(spec, d));
        let z_i = d.mounting.axes.ia_vertical();
        for (i, (&w, &out)) in d.rates_rad_s.iter().zip(d.outputs).enumerate() {
            rows.push((m, i));
            rates.push(w);
            // a PIGA's −(ω + Ω_v)·z_i, known, moved to the left (exactly 0 for z_i = 0)
            let known = factor * (w + omega_v) * z_i;
            y.push(if known == 0.0 { out } else { out - known });
        }
    }
    let design = Design::polynomials(&rates, columns.len(), |r, j| {
        let (m, _) = rows[r];
        entry(columns[j], m, &data[m], &inputs[m], rates[r])
            .into_iter()
            .enumerate()
            .filter(|(_, c)| *c != 0.0)
            .map(|(p, c)| (c, u32::try_from(p).unwrap_or(u32::MAX)))
            .collect()
    })
    .map_err(MountingsError::Fit)?;
    Ok(JointDesign {
        columns,
        design,
        y,
        rows,
    })
}

/// The joint design of a declaration and its data, checked, with the arm-stretch column when
/// the declaration fits it (`ArmStretch::Fit` or `Auto`).
///
/// # Errors
/// [`MountingsError`] for a declaration or data the fit refuses.
pub fn joint_design(
    spec: &JointSpec,
    data: &[MountingData<'_>],
) -> Result<JointDesign, MountingsError> {
    super::check::check(spec, data)?;
    build(
        spec,
        data,
        !matches!(spec.arm_stretch, super::spec::ArmStretch::Off),
    )
}

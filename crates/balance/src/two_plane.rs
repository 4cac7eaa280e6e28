//! Two probe planes: the spindle axis as a line (translation and tilt), static and couple
//! unbalance, and the two-plane correction (eq. 1–5, without the cone of eq. 22).
//!
//! The model is the simulator's: the chain of eq. 5 translates the spindle by `T` at the
//! PIGA plane (the `O2` origin) and tilts it about that point, so the axis point at height
//! `z` (m, along `Z2`, negative below the PIGA plane) is `p(z) = T + z·L`, with `L` the lean
//! of the axis (rad, towards the azimuth the top leans to: `L = Δφ_y − i·Δφ_x`). A mass `m`
//! at radius `r`, azimuth `θ` and height `l` adds `m·r·ω²·e^{iθ}/k_r` to `T` (eq. 1) and
//! `m·r·l·ω²·e^{iθ}/k_θ` to `L` (eq. 2). Hence the static unbalance `U_s = Σ m·r·e^{iθ}`
//! (kg·m) is `k_r·D_T` and the couple unbalance `U_c = Σ m·r·l·e^{iθ}` (kg·m², about the
//! PIGA plane) is `k_θ·D_L`, with `D_T`, `D_L` the dynamic (∝ ω²) parts of `T` and `L`.

use crate::correction::{
    CalibrationContext, Correction, CorrectionPlane, Prediction, TrialMass, correction_from,
    predict_unbalance, validate_context, validate_plane,
};
use crate::error::{BalanceError, Result, finite_result};
use crate::phasor::{Complex, Phasor, PhasorFit};

/// Micrometres per metre.
const UM_PER_M: f64 = 1e6;

/// A 4-vector `(a_x, a_y, b_x, b_y)` of two phasors with its full 4×4 covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhasorPair {
    /// The first phasor (its own 2×2 block of the covariance).
    pub a: Phasor,
    /// The second phasor.
    pub b: Phasor,
    /// Covariance of `(a_x, a_y, b_x, b_y)`.
    pub covariance: [[f64; 4]; 4],
}

impl PhasorPair {
    fn from_parts(a: Complex, b: Complex, covariance: [[f64; 4]; 4]) -> Self {
        let block = |o: usize| {
            [
                [covariance[o][o], covariance[o][o + 1]],
                [covariance[o + 1][o], covariance[o + 1][o + 1]],
            ]
        };
        Self {
            a: Phasor {
                x: a.re,
                y: a.im,
                covariance: block(0),
            },
            b: Phasor {
                x: b.re,
                y: b.im,
                covariance: block(2),
            },
            covariance,
        }
    }

    fn values(&self) -> [Complex; 2] {
        [self.a.value(), self.b.value()]
    }

    /// `M·self` for a complex 2×2 matrix `M` taken as exact.
    fn mapped(&self, m: &[[Complex; 2]; 2]) -> Self {
        let v = self.values();
        let out = [
            m[0][0].mul(v[0]).add(m[0][1].mul(v[1])),
            m[1][0].mul(v[0]).add(m[1][1].mul(v[1])),
        ];
        Self::from_parts(out[0], out[1], propagate4(&real4(m), &self.covariance))
    }

    /// `c·self` for a complex scalar `c` taken as exact.
    fn times(&self, c: Complex) -> Self {
        let zero = Complex::new(0.0, 0.0);
        self.mapped(&[[c, zero], [zero, c]])
    }

    fn plus_independent(&self, o: &Self) -> Self {
        let v = self.values();
        let w = o.values();
        let mut c = self.covariance;
        for (row, other) in c.iter_mut().zip(&o.covariance) {
            for (x, y) in row.iter_mut().zip(other) {
                *x += y;
            }
        }
        Self::from_parts(v[0].add(w[0]), v[1].add(w[1]), c)
    }

    fn is_finite(&self) -> bool {
        self.a.is_finite() && self.b.is_finite()
    }
}

/// The real 4×4 matrix of a complex 2×2 matrix acting on `(a_x, a_y, b_x, b_y)`.
fn real4(m: &[[Complex; 2]; 2]) -> [[f64; 4]; 4] {
    let mut r = [[0.0; 4]; 4];
    for i in 0..2 {
        for j in 0..2 {
            let c = m[i][j];
            r[2 * i][2 * j] = c.re;
            r[2 * i][2 * j + 1] = -c.im;
            r[2 * i + 1][2 * j] = c.im;
            r[2 * i + 1][2 * j + 1] = c.re;
        }
    }
    r
}

/// `M·C·Mᵀ`.
fn propagate4(m: &[[f64; 4]; 4], c: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut mc = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            mc[i][j] = (0..4).map(|k| m[i][k] * c[k][j]).sum();
        }
    }
    let mut out = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            out[i][j] = (0..4).map(|k| mc[i][k] * m[j][k]).sum();
        }
    }
    out
}

/// One probe plane: a probe phase's phasor fit and the height of its plane.
#[derive(Debug, Clone, Copy)]
pub struct ProbePlane<'a> {
    /// The phase's fit ([`crate::fit_phasors`]); only its probe-plane phasors are used.
    pub fit: &'a PhasorFit,
    /// Height of the probe plane above the PIGA plane along `Z2`, m (negative below: the
    /// paper's probe is at −0.51 m).
    pub height_m: f64,
}

/// Translation and tilt of the axis at one rate, from the two probes' measured points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisPoint {
    /// Spindle rate, rad/s.
    pub rate_rad_s: f64,
    /// Translation at the PIGA plane, µm.
    pub translation_um: Phasor,
    /// Lean of the axis, µrad (µm per m).
    pub tilt_urad: Phasor,
}

/// The motion of the spindle axis from two probe planes: translation at the PIGA plane and
/// tilt, each static and dynamic (∝ ω²), without the cone assumption.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisMotion {
    /// Static translation `S_T` at the PIGA plane, µm.
    pub static_translation_um: Phasor,
    /// Static lean `S_L`, µrad.
    pub static_tilt_urad: Phasor,
    /// `(D_T, D_L)`: dynamic translation at the PIGA plane, µm·s², and dynamic lean,
    /// µrad·s², with their joint covariance. `Re D_T` is `C_r` (in µm·s²).
    pub dynamic: PhasorPair,
    /// Per rate given by both probes, in the first probe's order.
    pub per_rate: Vec<AxisPoint>,
    /// Heights of the two probe planes, m.
    pub heights_m: [f64; 2],
}

impl AxisMotion {
    /// The radius error at any height `z` (m above the PIGA plane) the axis line gives, as a
    /// dynamic phasor in µm·s²: `D_T + z·D_L` (with the heights in m and `L` in µrad).
    #[must_use]
    pub fn dynamic_at_um_s2(&self, height_m: f64) -> Phasor {
        let d = self.dynamic;
        let m = [
            [Complex::new(1.0, 0.0), Complex::new(height_m, 0.0)],
            [Complex::new(0.0, 0.0), Complex::new(0.0, 0.0)],
        ];
        d.mapped(&m).a
    }
}

/// Splits two probe planes' phasors into the translation of the axis at the PIGA plane and
/// its tilt: with `p_k = T + z_k·L`, `L = (p₁ − p₂)/(z₁ − z₂)` and
/// `T = (z₁·p₂ − z₂·p₁)/(z₁ − z₂)`, for the fitted static and dynamic phasors (the two
/// probes' fits independent) and per rate.
///
/// # Errors
/// [`BalanceError::InvalidField`] naming `<field>.height_m` for a height that is not finite,
/// or equal to the other probe's (`<field>` is `second_probe`); [`BalanceError::NonFiniteResult`].
pub fn axis_motion(
    first: &ProbePlane<'_>,
    second: &ProbePlane<'_>,
    field: &str,
) -> Result<AxisMotion> {
    units::finite("first_probe.height_m", first.height_m)?;
    units::finite(format!("{field}.height_m"), second.height_m)?;
    let (z1, z2) = (first.height_m, second.height_m);
    let dz = z1 - z2;
    if dz == 0.0 {
        return Err(BalanceError::SameHeight {
            field: format!("{field}.height_m"),
            value: z2,
        });
    }
    // (T, L) = M·(p₁, p₂), heights in m, phasors in µm: L in µm/m = µrad
    let r = |v: f64| Complex::new(v, 0.0);
    let m = [[r(-z2 / dz), r(z1 / dz)], [r(1.0 / dz), r(-1.0 / dz)]];
    let split = |p1: &Phasor, p2: &Phasor| {
        let mut c = [[0.0; 4]; 4];
        for i in 0..2 {
            for j in 0..2 {
                c[i][j] = p1.covariance[i][j];
                c[2 + i][2 + j] = p2.covariance[i][j];
            }
        }
        PhasorPair::from_parts(p1.value(), p2.value(), c).mapped(&m)
    };
    let f1 = first.fit;
    let f2 = second.fit;
    let s = split(&f1.static_probe_um, &f2.static_probe_um);
    let dynamic = split(&f1.dynamic_probe_um_s2, &f2.dynamic_probe_um_s2);
    let per_rate = f1
        .measured_probe_um
        .iter()
        .filter_map(|(w, p1)| {
            let (_, p2) = f2.measured_probe_um.iter().find(|(v, _)| v == w)?;
            let pair = split(p1, p2);
            Some(AxisPoint {
                rate_rad_s: *w,
                translation_um: pair.a,
                tilt_urad: pair.b,
            })
        })
        .collect();
    let out = AxisMotion {
        static_translation_um: s.a,
        static_tilt_urad: s.b,
        dynamic,
        per_rate,
        heights_m: [z1, z2],
    };
    let ok = s.is_finite() && dynamic.is_finite();
    finite_result(field, if ok { 0.0 } else { f64::NAN })?;
    Ok(out)
}

/// Static and couple unbalance from the axis motion and the bearing's stiffnesses (eq. 1–2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticCouple {
    /// Static unbalance `U_s = k_r·D_T`, kg·m, towards its azimuth.
    pub static_kg_m: Phasor,
    /// Couple unbalance `U_c = k_θ·D_L` about the PIGA plane, kg·m² (a mass `m` at radius `r`
    /// and height `l` contributes `m·r·l` towards its azimuth).
    pub couple_kg_m2: Phasor,
}

/// The bearing's stiffnesses (eq. 1–2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stiffness {
    /// Radial stiffness `k_r`, N/m (> 0).
    pub radial_n_m: f64,
    /// Angular stiffness `k_θ`, N·m/rad (> 0).
    pub angular_n_m_rad: f64,
}

/// `U_s = k_r·D_T` and `U_c = k_θ·D_L` (eq. 1–2 inverted).
///
/// # Errors
/// [`BalanceError::InvalidField`] naming `<field>.radial_stiffness_n_m` or
/// `<field>.angular_stiffness_n_m_rad`; [`BalanceError::NonFiniteResult`].
pub fn static_couple(
    motion: &AxisMotion,
    stiffness: &Stiffness,
    field: &str,
) -> Result<StaticCouple> {
    units::positive(
        format!("{field}.radial_stiffness_n_m"),
        stiffness.radial_n_m,
    )?;
    units::positive(
        format!("{field}.angular_stiffness_n_m_rad"),
        stiffness.angular_n_m_rad,
    )?;
    let out = StaticCouple {
        static_kg_m: motion.dynamic.a.scaled(stiffness.radial_n_m / UM_PER_M),
        couple_kg_m2: motion
            .dynamic
            .b
            .scaled(stiffness.angular_n_m_rad / UM_PER_M),
    };
    let ok = out.static_kg_m.is_finite() && out.couple_kg_m2.is_finite();
    finite_result(field, if ok { 0.0 } else { f64::NAN })?;
    Ok(out)
}

/// A correction plane of a two-plane correction: its height and where masses go in it.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightPlane {
    /// Height of the plane above the PIGA plane along `Z2`, m.
    pub height_m: f64,
    /// Radius and optional fixed positions.
    pub plane: CorrectionPlane,
}

/// A two-plane correction and what it leaves.
#[derive(Debug, Clone, PartialEq)]
pub struct TwoPlaneCorrection {
    /// The influence matrix `α` (µm·s² and µrad·s² per kg·m): column `k` is the response
    /// `(D_T, D_L)` to a unit unbalance in plane `k`, as `(re, im)` pairs, row-major.
    pub influence: [[(f64, f64); 2]; 2],
    /// The correction in each plane (mass, radius, azimuth), plane A first.
    pub planes: [Correction; 2],
    /// What it leaves at the PIGA plane (`C_r`, Δk2, residual static unbalance, grade).
    pub predicted: Prediction,
    /// The residual dynamic lean, µrad·s² (nominally zero; its covariance).
    pub residual_tilt_urad_s2: Phasor,
    /// `(U_A, U_B)`, kg·m, with their joint covariance.
    pub unbalance_kg_m: PhasorPair,
    /// Heights of planes A and B, m.
    pub heights_m: [f64; 2],
}

impl TwoPlaneCorrection {
    /// The unbalance the correction cancels: static `U_s = −(U_A + U_B)` (kg·m) and couple
    /// about the PIGA plane `U_c = −(z_A·U_A + z_B·U_B)` (kg·m²), with the joint covariance
    /// of `(U_A, U_B)` propagated (the model-free reading of static and couple unbalance).
    #[must_use]
    pub fn cancelled_unbalance(&self) -> StaticCouple {
        let r = |v: f64| Complex::new(v, 0.0);
        let [za, zb] = self.heights_m;
        let m = [[r(-1.0), r(-1.0)], [r(-za), r(-zb)]];
        let sc = self.unbalance_kg_m.mapped(&m);
        StaticCouple {
            static_kg_m: sc.a,
            couple_kg_m2: sc.b,
        }
    }
}

/// Paths of the two-plane inputs, for errors.
#[derive(Debug, Clone, Copy)]
pub struct TwoPlaneFields<'a> {
    /// The trial runs in planes A and B.
    pub trials: [&'a str; 2],
    /// Their trial masses.
    pub trial_masses: [&'a str; 2],
    /// The two correction planes.
    pub planes: [&'a str; 2],
    /// The calibration context.
    pub context: &'a str,
}

impl Default for TwoPlaneFields<'_> {
    fn default() -> Self {
        Self {
            trials: ["trial_a", "trial_b"],
            trial_masses: ["trial_mass_a", "trial_mass_b"],
            planes: ["plane_a", "plane_b"],
            context: "calibration",
        }
    }
}

fn validate_planes(planes: &[HeightPlane; 2], fields: &TwoPlaneFields<'_>) -> Result<()> {
    for (p, f) in planes.iter().zip(fields.planes) {
        units::finite(format!("{f}.height_m"), p.height_m)?;
        validate_plane(&p.plane, f)?;
    }
    if planes[0].height_m == planes[1].height_m {
        return Err(BalanceError::SameHeight {
            field: format!("{}.height_m", fields.planes[1]),
            value: planes[1].height_m,
        });
    }
    Ok(())
}

/// `U = −α⁻¹·y` and the corrections it stands for; `None` when `α` is singular.
fn solve(alpha: &[[Complex; 2]; 2]) -> Option<[[Complex; 2]; 2]> {
    let det = alpha[0][0]
        .mul(alpha[1][1])
        .sub(alpha[0][1].mul(alpha[1][0]));
    let scale = (alpha[0][0].abs() + alpha[1][0].abs()) * (alpha[0][1].abs() + alpha[1][1].abs());
    if det.abs() <= 1e-9 * scale || !det.abs().is_finite() {
        return None;
    }
    let one = Complex::new(1.0, 0.0);
    let inv = one.div(det);
    Some([
        [alpha[1][1].mul(inv), alpha[0][1].neg().mul(inv)],
        [alpha[1][0].neg().mul(inv), alpha[0][0].mul(inv)],
    ])
}

fn finish(
    alpha: [[Complex; 2]; 2],
    alpha_inv: &[[Complex; 2]; 2],
    unbalance: PhasorPair,
    residual: PhasorPair,
    planes: &[HeightPlane; 2],
    context: &CalibrationContext,
    fields: &TwoPlaneFields<'_>,
) -> Result<TwoPlaneCorrection> {
    let a = correction_from(unbalance.a, &planes[0].plane, fields.planes[0])?;
    let b = correction_from(unbalance.b, &planes[1].plane, fields.planes[1])?;
    // residual plane unbalances α⁻¹·y_res; the static residual is their sum
    let u_res = residual.mapped(alpha_inv);
    let one = Complex::new(1.0, 0.0);
    let static_res = u_res.mapped(&[[one, one], [Complex::new(0.0, 0.0); 2]]).a;
    let predicted = predict_unbalance(residual.a, static_res, context)?;
    let out = TwoPlaneCorrection {
        influence: [
            [alpha[0][0].parts(), alpha[0][1].parts()],
            [alpha[1][0].parts(), alpha[1][1].parts()],
        ],
        planes: [a, b],
        predicted,
        residual_tilt_urad_s2: residual.b,
        unbalance_kg_m: unbalance,
        heights_m: [planes[0].height_m, planes[1].height_m],
    };
    let ok = out
        .influence
        .iter()
        .flatten()
        .all(|(x, y)| x.is_finite() && y.is_finite())
        && out.residual_tilt_urad_s2.is_finite();
    finite_result("two-plane correction", if ok { 0.0 } else { f64::NAN })?;
    Ok(out)
}

/// The two-plane correction by the stiffness model: the unbalances `U_A`, `U_B` in two planes
/// at heights `z_A ≠ z_B` that cancel the static and the couple unbalance,
/// `U_A + U_B = −U_s`, `z_A·U_A + z_B·U_B = −U_c`. The prediction's covariance is the
/// measured `(D_T, D_L)`'s.
///
/// # Errors
/// As [`static_couple`]; [`BalanceError::InvalidField`] for a bad plane (two planes at the
/// same height name the second's `height_m`) or context; [`BalanceError::CannotSplit`];
/// [`BalanceError::NonFiniteResult`].
pub fn two_plane_stiffness_correction(
    motion: &AxisMotion,
    stiffness: &Stiffness,
    stiffness_field: &str,
    planes: &[HeightPlane; 2],
    context: &CalibrationContext,
    fields: &TwoPlaneFields<'_>,
) -> Result<TwoPlaneCorrection> {
    static_couple(motion, stiffness, stiffness_field)?;
    validate_planes(planes, fields)?;
    validate_context(context, fields.context)?;
    // response per kg·m in plane k: D_T = 1e6/k_r µm·s², D_L = 1e6·z_k/k_θ µrad·s²
    let t = UM_PER_M / stiffness.radial_n_m;
    let l = UM_PER_M / stiffness.angular_n_m_rad;
    let r = |v: f64| Complex::new(v, 0.0);
    let alpha = [
        [r(t), r(t)],
        [r(l * planes[0].height_m), r(l * planes[1].height_m)],
    ];
    let Some(inv) = solve(&alpha) else {
        return Err(BalanceError::NonFiniteResult {
            field: fields.planes[1].to_owned(),
        });
    };
    let neg = motion.dynamic.times(Complex::new(-1.0, 0.0)).mapped(&inv);
    let residual = PhasorPair::from_parts(
        Complex::new(0.0, 0.0),
        Complex::new(0.0, 0.0),
        motion.dynamic.covariance,
    );
    finish(alpha, &inv, neg, residual, planes, context, fields)
}

/// The two-plane correction by influence coefficients (model-free): from the run as found
/// and one trial run per correction plane (the trial mass of plane `k` mounted alone in it),
/// the 2×2 complex influence matrix `α_{·k} = (y_k − y_0)/(m_k·r_k·e^{iθ_k})` of the
/// responses `y = (D_T, D_L)`, and the correction `U = −α⁻¹·y_0`, mounted with the trial
/// masses removed.
///
/// The prediction propagates the three runs' covariances to the residual `y_0 + α·U` (with
/// `U` as mounted, exact): `δy_res = (1 − c_A − c_B)·δy_0 + c_A·δy_A + c_B·δy_B` with
/// `c_k = U_k/(m_k r_k e^{iθ_k})`.
///
/// # Errors
/// [`BalanceError::InvalidField`] for a trial mass, a plane or the context out of domain;
/// [`BalanceError::SingularInfluence`] naming a trial run whose response does not differ
/// from the initial one by more than 3σ, or the second trial when the two responses are
/// parallel; [`BalanceError::CannotSplit`]; [`BalanceError::NonFiniteResult`].
pub fn two_plane_influence_correction(
    initial: &AxisMotion,
    trials: [&AxisMotion; 2],
    trial_masses: [&TrialMass; 2],
    planes: &[HeightPlane; 2],
    context: &CalibrationContext,
    fields: &TwoPlaneFields<'_>,
) -> Result<TwoPlaneCorrection> {
    for (m, f) in trial_masses.iter().zip(fields.trial_masses) {
        units::positive(format!("{f}.mass_kg"), m.mass_kg)?;
        units::positive(format!("{f}.radius_m"), m.radius_m)?;
        units::finite(format!("{f}.azimuth_deg"), m.azimuth_deg)?;
    }
    validate_planes(planes, fields)?;
    validate_context(context, fields.context)?;
    let y0 = initial.dynamic;
    let mut alpha = [[Complex::new(0.0, 0.0); 2]; 2];
    let mut t = [Complex::new(0.0, 0.0); 2];
    for k in 0..2 {
        let change = trials[k]
            .dynamic
            .plus_independent(&y0.times(Complex::new(-1.0, 0.0)));
        // significant when the change exceeds 3σ along its direction in either component
        let significant = [change.a, change.b].iter().any(|p| {
            let m = p.magnitude();
            m > 0.0 && m > 3.0 * p.max_sigma()
        });
        if !significant {
            return Err(BalanceError::SingularInfluence {
                field: fields.trials[k].to_owned(),
                change_um_s2: change.a.magnitude(),
                three_sigma_um_s2: 3.0 * change.a.max_sigma(),
            });
        }
        let m = trial_masses[k];
        t[k] = Complex::from_polar(m.mass_kg * m.radius_m, m.azimuth_deg.to_radians());
        let v = change.values();
        alpha[0][k] = v[0].div(t[k]);
        alpha[1][k] = v[1].div(t[k]);
    }
    let Some(inv) = solve(&alpha) else {
        let change = trials[1].dynamic.a.value().sub(y0.a.value());
        return Err(BalanceError::SingularInfluence {
            field: fields.trials[1].to_owned(),
            change_um_s2: change.abs(),
            three_sigma_um_s2: 3.0 * trials[1].dynamic.a.max_sigma(),
        });
    };
    let y = y0.values();
    let neg = [y[0].neg(), y[1].neg()];
    let u = [
        inv[0][0].mul(neg[0]).add(inv[0][1].mul(neg[1])),
        inv[1][0].mul(neg[0]).add(inv[1][1].mul(neg[1])),
    ];
    let one = Complex::new(1.0, 0.0);
    let c = [u[0].div(t[0]), u[1].div(t[1])];
    // the residual's covariance, and U's: δU = −α⁻¹·δy_res
    let residual_cov = y0
        .times(one.sub(c[0]).sub(c[1]))
        .plus_independent(&trials[0].dynamic.times(c[0]))
        .plus_independent(&trials[1].dynamic.times(c[1]));
    let residual = PhasorPair::from_parts(
        Complex::new(0.0, 0.0),
        Complex::new(0.0, 0.0),
        residual_cov.covariance,
    );
    let u_cov = residual.mapped(&inv).covariance;
    let unbalance = PhasorPair::from_parts(u[0], u[1], u_cov);
    finish(alpha, &inv, unbalance, residual, planes, context, fields)
}

//! The probe recordings: the spindle axis read by one probe (through the cone of eq. 22) or
//! two (at their own heights), the spindle angle with its speed ripple, and the noise.

use std::f64::consts::TAU;

use harmonics::{FirstHarmonic, LeverGeometry};
use kinematics::{Point, Spindle, SpindleOffsets, spindle_transform};
use rand_distr::Distribution;
use units::m_to_um;

use super::noise::{PROBE_STREAM, SECOND_PROBE_STREAM, normal, stream};
use super::simulation::{ProbeTruth, SimulatedRecording};
use crate::scenario::{ProbeSpec, Scenario, recording_file_name, second_recording_file_name};

/// The probe geometry as the simulator uses it, both numbers from `harmonics`' conventions.
#[derive(Debug, Clone, Copy)]
pub(super) struct Lever {
    /// `(h_probe + h_piga)/h_probe` ([`LeverGeometry::lever_ratio`]).
    pub(super) ratio: f64,
    /// `+1` for a probe that measures along `O1X1` (the gap opens as the axis moves to `+X1`),
    /// `−1` against it (the paper's set-up: the gap closes).
    sign: f64,
}

impl Lever {
    pub(super) fn new(
        lever: &LeverGeometry,
    ) -> std::result::Result<Self, harmonics::HarmonicsError> {
        let ratio = lever.lever_ratio()?;
        // Eq. 21–22 as `harmonics` reads them: a unit d_c1 stands for a radius error of
        // ±ratio at the PIGA plane, + along O1X1 and − against it.
        let sign = lever
            .project(FirstHarmonic { c1: 1.0, s1: 0.0 })?
            .radius_error
            .signum();
        Ok(Self { ratio, sign })
    }
}

/// How one probe reads the spindle axis at one rate: the axis point in its plane at spindle
/// angle 0 (in `O1`, which then turns with the spindle), its sign and its noise stream.
#[derive(Debug, Clone)]
pub(super) struct Reader {
    /// `(x, y)` of the axis point in the probe plane at θ = 0, µm.
    point_um: [f64; 2],
    /// `+1` along `O1X1`, `−1` against.
    sign: f64,
    /// Noise stream tag.
    purpose: u64,
    file_name: String,
}

impl Reader {
    /// The exact first harmonic of the gap: the axis point in the probe plane turned by θ,
    /// `x cos θ − y sin θ` along `O1X1`, read with the probe's sign.
    pub(super) fn truth(&self, offsets: &SpindleOffsets) -> ProbeTruth {
        let dc1_um = self.sign * self.point_um[0];
        let ds1_um = -self.sign * self.point_um[1];
        ProbeTruth {
            dc1_um,
            ds1_um,
            amplitude_um: dc1_um.hypot(ds1_um),
            beta_deg: offsets.drift_azimuth_rad().to_degrees(),
        }
    }
}

/// The readers of a scenario's probes at one rate. One probe: the spindle-axis point at the
/// PIGA plane carried down the cone of eq. 22 (`/ratio`). Two probes: each reads the axis
/// line of the chain (eq. 5) at its own height, `T₂¹(0)·[0 0 −h 1]ᵀ` (translation plus tilt
/// times height), with no cone.
pub(super) fn readers(
    s: &Scenario,
    lever: Lever,
    offsets: &SpindleOffsets,
    rate_deg_s: f64,
) -> (Reader, Option<Reader>) {
    let at_height = |below_piga_mm: f64| {
        let p = spindle_transform(0.0, offsets)
            .apply(Point::<Spindle>::new([0.0, 0.0, -below_piga_mm * 1e-3]))
            .coords_m;
        [m_to_um(p[0]), m_to_um(p[1])]
    };
    let Some(q) = &s.second_probe else {
        let p0 = axis_point_at_piga(offsets, 0.0);
        let first = Reader {
            point_um: [m_to_um(p0[0]) / lever.ratio, m_to_um(p0[1]) / lever.ratio],
            sign: lever.sign,
            purpose: PROBE_STREAM,
            file_name: recording_file_name(rate_deg_s),
        };
        return (first, None);
    };
    let first = Reader {
        point_um: at_height(s.probe.lever.probe_to_piga_mm),
        sign: lever.sign,
        purpose: PROBE_STREAM,
        file_name: recording_file_name(rate_deg_s),
    };
    let second = Reader {
        point_um: at_height(q.probe_to_piga_mm),
        sign: match q.probe_direction {
            harmonics::ProbeDirection::AlongO1X1 => 1.0,
            harmonics::ProbeDirection::AgainstO1X1 => -1.0,
        },
        purpose: SECOND_PROBE_STREAM,
        file_name: second_recording_file_name(rate_deg_s),
    };
    (first, Some(second))
}

/// Number of samples that cover `revolutions` whole turns at `rate_deg_s`: every sample
/// time `i/f_s` is below the end time `revolutions·360/rate` (an end time that falls on a
/// sample to within 1e-6 of an interval counts as falling on it).
pub(crate) fn sample_count(sample_rate_hz: f64, rate_deg_s: f64, revolutions: usize) -> usize {
    let x = revolutions as f64 * 360.0 / rate_deg_s * sample_rate_hz;
    let n = if (x - x.round()).abs() < 1e-6 {
        x.round()
    } else {
        x.ceil()
    };
    // a validated scenario keeps this well below usize::MAX (MAX_TOTAL_SAMPLES)
    n as usize
}

/// The spindle angle `θ(t) = θ₀ + ωt + A·(sin(ωt + φ) − sin φ)`, rad (not wrapped).
pub(super) fn spindle_angle_rad(probe: &ProbeSpec, rate_rad_s: f64, t_s: f64) -> f64 {
    let theta0 = probe.start_angle_deg.to_radians();
    let wt = rate_rad_s * t_s;
    let ripple = probe.speed_ripple.map_or(0.0, |r| {
        let (a, phi) = (r.amplitude_deg.to_radians(), r.phase_deg.to_radians());
        a * ((wt + phi).sin() - phi.sin())
    });
    theta0 + wt + ripple
}

/// One probe's recording at one rate.
pub(super) fn record(
    s: &Scenario,
    reader: &Reader,
    rate_rad_s: f64,
    rate_deg_s: f64,
) -> SimulatedRecording {
    let probe = &s.probe;
    let n = sample_count(
        probe.sample_rate_hz,
        rate_deg_s,
        s.revolutions_at(rate_deg_s),
    );
    let sign = reader.sign;
    let mut rng = stream(s.seed, reader.purpose, rate_deg_s.to_bits());
    let noise = normal(probe.noise_um);
    // The spindle-axis point in the probe plane, in the sleeve frame. Eq. 5 begins with
    // Rot(z₁, θ), so T₂¹(θ) = Rot(z₁, θ)·T₂¹(0) and the point at angle θ is the chain's point
    // at θ = 0 turned by θ (equal to evaluating the chain at θ; tested).
    let p0 = reader.point_um;
    let harmonics: Vec<(usize, f64, f64)> = probe
        .sleeve_harmonics
        .iter()
        .map(|h| (h.order, h.c_um, h.s_um))
        .collect();
    let highest = harmonics.iter().map(|h| h.0).max().unwrap_or(1);
    let mut cos_k = vec![0.0; highest + 1];
    let mut sin_k = vec![0.0; highest + 1];

    let mut time_s = Vec::with_capacity(n);
    let mut gap_um = Vec::with_capacity(n);
    let mut angle_deg = probe.encoder_angle.then(|| Vec::with_capacity(n));
    for i in 0..n {
        let t = i as f64 / probe.sample_rate_hz;
        let theta = spindle_angle_rad(probe, rate_rad_s, t);
        let (sin1, cos1) = theta.sin_cos();
        // X1 component of Rot(z, θ)·p0
        let x_probe_um = p0[0] * cos1 - p0[1] * sin1;
        // cos kθ, sin kθ by the angle-addition recurrence
        (cos_k[0], sin_k[0]) = (1.0, 0.0);
        for k in 1..=highest {
            cos_k[k] = cos_k[k - 1] * cos1 - sin_k[k - 1] * sin1;
            sin_k[k] = sin_k[k - 1] * cos1 + cos_k[k - 1] * sin1;
        }
        let sleeve: f64 = harmonics
            .iter()
            .map(|&(k, c, s)| c * cos_k[k] + s * sin_k[k])
            .sum();
        let e = noise.as_ref().map_or(0.0, |d| d.sample(&mut rng));
        time_s.push(t);
        gap_um.push(probe.l0_um + sign * x_probe_um + sleeve + e);
        if let Some(a) = angle_deg.as_mut() {
            a.push(theta.rem_euclid(TAU).to_degrees() % 360.0);
        }
    }
    SimulatedRecording {
        rate_deg_s,
        file_name: reader.file_name.clone(),
        time_s,
        gap_um,
        angle_deg,
    }
}

/// The spindle-axis point at the PIGA plane (the `O2` origin) in the sleeve frame at spindle
/// angle θ, from the chain of eq. 5: `T₂¹(θ)·[0 0 0 1]ᵀ`, m.
pub(super) fn axis_point_at_piga(offsets: &SpindleOffsets, theta_rad: f64) -> [f64; 3] {
    spindle_transform(theta_rad, offsets)
        .apply(Point::<Spindle>::new([0.0, 0.0, 0.0]))
        .coords_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sample_count_covers_whole_revolutions() {
        // 10 deg/s at 1 kHz: 36 s per revolution, samples 0 … 71999 for two turns
        assert_eq!(sample_count(1000.0, 10.0, 2), 72_000);
        // 200.1234 deg/s: 1798.89 samples per turn, the last sample is inside the turn
        let n = sample_count(1000.0, 200.1234, 1);
        assert_eq!(n, 1799);
        assert!(((n - 1) as f64) / 1000.0 < 360.0 / 200.1234);
    }

    #[test]
    fn the_turned_point_is_the_chain_evaluated_at_the_angle() {
        let offsets = SpindleOffsets {
            dr_x_m: 5.6e-6,
            dr_y_m: -2.0e-6,
            dphi_x_rad: 3e-6,
            dphi_y_rad: -1e-6,
        };
        let p0 = axis_point_at_piga(&offsets, 0.0);
        for k in 0..50 {
            let theta = 0.37 * f64::from(k) - 3.0;
            let (s, c) = theta.sin_cos();
            let turned = [p0[0] * c - p0[1] * s, p0[0] * s + p0[1] * c, p0[2]];
            let direct = axis_point_at_piga(&offsets, theta);
            for (a, b) in turned.iter().zip(&direct) {
                assert!((a - b).abs() < 1e-20, "{theta}: {a} vs {b}");
            }
            // and it is ΔR·(cos(θ+β), sin(θ+β), 0) (eq. 9, corrected)
            let dr = offsets.drift_magnitude_m();
            let beta = offsets.drift_azimuth_rad();
            assert_relative_eq!(direct[0], dr * (theta + beta).cos(), epsilon = 1e-20);
            assert_relative_eq!(direct[1], dr * (theta + beta).sin(), epsilon = 1e-20);
            assert_eq!(direct[2], 0.0);
        }
    }

    #[test]
    fn lever_takes_ratio_and_sign_from_harmonics() {
        use harmonics::ProbeDirection;
        for (direction, sign) in [
            (ProbeDirection::AgainstO1X1, -1.0),
            (ProbeDirection::AlongO1X1, 1.0),
        ] {
            let lever = Lever::new(&LeverGeometry {
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
                probe_direction: direction,
            })
            .unwrap();
            assert_eq!(lever.sign, sign, "{direction:?}");
            assert_relative_eq!(lever.ratio, 1210.0 / 700.0, max_relative = 1e-15);
        }
        let bad = LeverGeometry {
            pivot_to_probe_mm: 0.0,
            probe_to_piga_mm: 510.0,
            probe_direction: ProbeDirection::AlongO1X1,
        };
        assert!(Lever::new(&bad).is_err());
    }

    #[test]
    fn ripple_keeps_the_period_and_the_mean_rate() {
        let probe = ProbeSpec {
            lever: harmonics::LeverGeometry {
                pivot_to_probe_mm: 700.0,
                probe_to_piga_mm: 510.0,
                probe_direction: harmonics::ProbeDirection::AgainstO1X1,
            },
            sample_rate_hz: 1000.0,
            noise_um: 0.0,
            l0_um: 0.0,
            sleeve_harmonics: vec![],
            encoder_angle: true,
            speed_ripple: Some(crate::scenario::SpeedRipple {
                amplitude_deg: 2.0,
                phase_deg: 40.0,
            }),
            start_angle_deg: 15.0,
        };
        let w = 1.3;
        let theta0 = spindle_angle_rad(&probe, w, 0.0);
        assert_relative_eq!(theta0, 15f64.to_radians(), max_relative = 1e-15);
        let one_turn = spindle_angle_rad(&probe, w, TAU / w);
        assert_relative_eq!(one_turn - theta0, TAU, max_relative = 1e-12);
        // but not uniform within the turn
        let quarter = spindle_angle_rad(&probe, w, 0.25 * TAU / w) - theta0;
        assert!((quarter - 0.25 * TAU).abs() > 1e-3);
    }
}

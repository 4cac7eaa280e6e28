//! The paper's centrifuge as a plan (R = 2.5 m, up to 200 deg/s), shared by tests and benches.

use planning::{
    Candidates, CentrifugeSpec, CrSpec, NoiseSpec, PigaSpec, PlanInputs, ProbeSpec, Schedule,
    Search, Target, TypeB,
};

/// The paper's six rates, deg/s.
#[allow(dead_code)]
pub(crate) const PAPER_RATES_DEG_S: [f64; 6] = [10.0, 60.0, 80.1234, 110.1234, 160.1234, 200.1234];

/// 100 candidates from 10 to 200 deg/s, `points` points, one hour of centrifuge time.
pub(crate) fn inputs(points: usize) -> PlanInputs {
    PlanInputs {
        centrifuge: CentrifugeSpec {
            radius_m: 2.5,
            g_m_s2: 9.8,
            min_rate_deg_s: 10.0,
            max_rate_deg_s: 200.1234,
            max_acceleration_g: None,
            candidates: Candidates::Grid {
                from_deg_s: 10.0,
                to_deg_s: 200.0,
                count: 100,
            },
        },
        piga: PigaSpec {
            k0_rad_s: 1e-5,
            k1_rad_s_g: 0.56,
            k2_rad_s_g2: 5e-7,
            k3_rad_s_g3: 2e-8,
            k1_u_rad_s_g: 0.0,
            noise: NoiseSpec::PerRevolution { sigma_rad_s: 2e-8 },
        },
        probe: ProbeSpec {
            noise_um: 0.05,
            sample_rate_hz: 1000.0,
            pivot_to_probe_mm: 700.0,
            probe_to_piga_mm: 510.0,
        },
        c_r: CrSpec {
            expected_m_s2: -4.05e-8,
            u_m_s2: None,
        },
        type_b: TypeB {
            radius_u_m: 5e-5,
            g_u_m_s2: 1e-5,
            rate_u_relative: 1e-6,
            pivot_to_probe_u_mm: 0.5,
            probe_to_piga_u_mm: 0.5,
            probe_gain_u_relative: 0.01,
            ..TypeB::default()
        },
        schedule: Schedule {
            points,
            budget_s: 3600.0,
            settling_s: 60.0,
            min_revolutions: 2,
            allow_repeats: false,
        },
        target: Target {
            u95_k2_rad_s_g2: 1e-6,
            tolerance_k2_rad_s_g2: 5e-6,
            bias_fraction: 0.1,
        },
        search: Search::default(),
        two_orientation: None,
    }
}

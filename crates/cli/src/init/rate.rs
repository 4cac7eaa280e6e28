//! A centrifuge rate from a file's name (`probe_120deg_s.csv`, `run_20,5_dps.txt`,
//! `spindle-600rpm.csv`) or measured from its angle reference.

/// A rate in deg/s read from a file name, with the text it was read from.
pub(crate) fn rate_from_name(stem: &str) -> Option<(f64, String)> {
    let lower = stem.to_lowercase();
    let bytes = lower.as_bytes();
    let mut found = None;
    let mut i = 0;
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() || (i > 0 && bytes[i - 1].is_ascii_digit()) {
            i += 1;
            continue;
        }
        let start = i;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
        // A decimal point, comma or `p` (`20p5`) followed by digits.
        if i + 1 < bytes.len()
            && matches!(bytes[i], b'.' | b',' | b'p')
            && bytes[i + 1].is_ascii_digit()
        {
            i += 1;
            while i < bytes.len() && bytes[i].is_ascii_digit() {
                i += 1;
            }
        }
        let number: f64 = match lower[start..i].replace([',', 'p'], ".").parse() {
            Ok(v) => v,
            Err(_) => continue,
        };
        let rest = lower[i..].trim_start_matches(['_', '-', ' ']);
        const DEG_S: [&str; 8] = [
            "deg_s",
            "degs",
            "deg-s",
            "deg per s",
            "deg_per_s",
            "dps",
            "degps",
            "°_s",
        ];
        const RPM: [&str; 3] = ["rpm", "u_min", "upm"];
        let factor = if DEG_S.iter().any(|u| rest.starts_with(u)) {
            Some(1.0)
        } else if RPM.iter().any(|u| rest.starts_with(u)) {
            Some(6.0)
        } else {
            None
        };
        if let Some(factor) = factor {
            if found.is_some() {
                // Two rates in one name: neither is trusted.
                return None;
            }
            let end = i
                + (lower[i..].len() - rest.len())
                + rest
                    .find(|c: char| !c.is_alphanumeric() && c != '_' && c != '°')
                    .unwrap_or(rest.len())
                    .min(9);
            found = Some((number * factor, stem[start..end.min(stem.len())].to_owned()));
        }
    }
    found
}

/// The mean rate, deg/s, of an unwrapped angle (rad) against time (s): the least-squares
/// slope over every sample.
pub(crate) fn slope_deg_s(time_s: &[f64], angle_rad: &[f64]) -> Option<f64> {
    let n = time_s.len().min(angle_rad.len());
    if n < 3 {
        return None;
    }
    let t0 = time_s[0];
    let a0 = angle_rad[0];
    let (mut st, mut sa) = (0.0, 0.0);
    for k in 0..n {
        st += time_s[k] - t0;
        sa += angle_rad[k] - a0;
    }
    let (mt, ma) = (st / n as f64, sa / n as f64);
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for k in 0..n {
        let dt = time_s[k] - t0 - mt;
        sxy += dt * (angle_rad[k] - a0 - ma);
        sxx += dt * dt;
    }
    let slope = sxy / sxx;
    slope.is_finite().then(|| slope.to_degrees())
}

/// An angle that wraps (at `turn` units per revolution, or anywhere for a counter) made
/// continuous, in radians.
pub(crate) fn unwrap_rad(values: &[f64], rad_per_unit: f64, turn: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(values.len());
    let mut offset = 0.0;
    for (k, &v) in values.iter().enumerate() {
        if k > 0 {
            let step = v - values[k - 1];
            if step < -turn / 2.0 {
                offset += turn;
            } else if step > turn / 2.0 {
                offset -= turn;
            }
        }
        out.push((v + offset) * rad_per_unit);
    }
    out
}

/// The rate, deg/s, from a once-per-revolution pulse (0/1): whole revolutions between the
/// first and last rising edges.
pub(crate) fn pulse_rate_deg_s(time_s: &[f64], pulse: &[f64]) -> Option<(f64, usize)> {
    let edges: Vec<f64> = (1..pulse.len().min(time_s.len()))
        .filter(|&k| pulse[k] > 0.5 && pulse[k - 1] <= 0.5)
        .map(|k| time_s[k])
        .collect();
    let (first, last) = (edges.first()?, edges.last()?);
    let turns = edges.len() - 1;
    (turns >= 1 && last > first).then(|| (360.0 * turns as f64 / (last - first), turns))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_in_names() {
        assert_eq!(rate_from_name("probe_120deg_s").map(|r| r.0), Some(120.0));
        assert_eq!(
            rate_from_name("probe_020.0000deg_s").map(|r| r.0),
            Some(20.0)
        );
        assert_eq!(rate_from_name("run_20,5_dps").map(|r| r.0), Some(20.5));
        assert_eq!(rate_from_name("spindle-600rpm").map(|r| r.0), Some(3600.0));
        assert_eq!(rate_from_name("f0"), None);
        assert_eq!(rate_from_name("probe_2025_03_01"), None);
    }

    #[test]
    fn slope_and_pulses() {
        let t: Vec<f64> = (0..3000).map(|k| f64::from(k) * 0.01).collect();
        let deg: Vec<f64> = t.iter().map(|t| (40.0 * t) % 360.0).collect();
        let rad = unwrap_rad(&deg, 1f64.to_radians(), 360.0);
        assert!((slope_deg_s(&t, &rad).unwrap() - 40.0).abs() < 1e-9);
        let pulse: Vec<f64> = deg.iter().map(|a| f64::from(u8::from(*a < 0.4))).collect();
        let (rate, turns) = pulse_rate_deg_s(&t, &pulse).unwrap();
        assert_eq!(turns, 2);
        assert!((rate - 40.0).abs() < 0.1, "{rate}");
    }
}

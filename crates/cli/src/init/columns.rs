//! What a header's column holds, from its name and unit: the time, the probe gap, the
//! spindle angle (an encoder or an index pulse), the PIGA output, a rate.

use super::sniff::name_and_unit;

/// The role of a column in a lab's file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Role {
    /// Sample times.
    Time,
    /// The probe's gap reading.
    Gap,
    /// The spindle angle from an encoder.
    Angle,
    /// A once-per-revolution index pulse.
    Index,
    /// The PIGA's output (an angle in a recording, a mean rate in a table).
    Output,
    /// The centrifuge rate of a table's row.
    Rate,
    /// A table's standard uncertainty of each output.
    Sigma,
    /// Anything else.
    Other,
}

/// A header column: its name as written, the quantity and unit parsed from it, its role.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Column {
    /// The name as the header writes it (what the study file names).
    pub(crate) name: String,
    /// The unit from the name, as written (`mm`, `ms`, `deg/s`), if any.
    pub(crate) unit: Option<String>,
    /// The role guessed from the quantity's name.
    pub(crate) role: Role,
}

/// Words that name each role (lowercase; English, German, French, Spanish; and the
/// abbreviations DAQ software writes).
const WORDS: &[(Role, &[&str])] = &[
    (
        Role::Time,
        &[
            "time",
            "zeit",
            "t",
            "timestamp",
            "time stamp",
            "temps",
            "tiempo",
            "epoch",
            "elapsed",
        ],
    ),
    (
        Role::Gap,
        &[
            "gap",
            "spalt",
            "displacement",
            "disp",
            "probe",
            "abstand",
            "distance",
            "weg",
            "runout",
            "radial",
            "deplacement",
            "déplacement",
            "x",
        ],
    ),
    (
        Role::Angle,
        &[
            "angle",
            "winkel",
            "encoder",
            "enc",
            "theta",
            "position",
            "pos",
            "phi",
            "azimuth",
            "drehwinkel",
            "spindle angle",
        ],
    ),
    (
        Role::Index,
        &[
            "index",
            "idx",
            "pulse",
            "index pulse",
            "marker",
            "trigger",
            "once per rev",
            "1/rev",
            "nullimpuls",
            "referenz",
            "ref",
            "tach",
            "tacho",
            "keyphasor",
            "z",
        ],
    ),
    (
        Role::Output,
        &[
            "output", "pickoff", "pick-off", "piga", "ausgang", "sortie", "out",
        ],
    ),
    (
        Role::Rate,
        &[
            "rate",
            "speed",
            "omega",
            "drehzahl",
            "drehrate",
            "winkelgeschwindigkeit",
            "vitesse",
            "spindle rate",
        ],
    ),
    (
        Role::Sigma,
        &[
            "sigma",
            "u",
            "std",
            "uncertainty",
            "sd",
            "output sigma",
            "sigma output",
        ],
    ),
];

impl Column {
    /// The column of a header name.
    pub(crate) fn of(name: &str) -> Self {
        let (quantity, unit) = name_and_unit(name);
        let q = quantity
            .to_lowercase()
            .replace(['_', '-'], " ")
            .trim()
            .to_owned();
        let role = WORDS
            .iter()
            .find(|(_, words)| words.contains(&q.as_str()))
            .or_else(|| {
                // `output sigma`, `gap probe 1`: the first word that names a role.
                WORDS
                    .iter()
                    .find(|(_, words)| q.split(' ').next().is_some_and(|w| words.contains(&w)))
            })
            .map_or(Role::Other, |(role, _)| *role);
        // `output_sigma`, `sigma_output_rad_s`: an uncertainty, whatever else it names.
        let role = if q.split(' ').any(|w| w == "sigma" || w == "u" || w == "std") {
            Role::Sigma
        } else {
            role
        };
        Self {
            name: name.trim().trim_matches('"').trim().to_owned(),
            unit,
            role,
        }
    }
}

/// A time unit as the study names it.
pub(crate) fn time_unit(unit: &str) -> Option<&'static str> {
    Some(match unit.trim().to_lowercase().as_str() {
        "s" | "sec" | "secs" | "second" | "seconds" | "sek" => "s",
        "ms" | "msec" | "millisecond" | "milliseconds" => "ms",
        "us" | "µs" | "μs" | "usec" | "microsecond" | "microseconds" => "us",
        "ns" | "nanosecond" | "nanoseconds" => "ns",
        _ => return None,
    })
}

/// A length unit as the study names it.
pub(crate) fn length_unit(unit: &str) -> Option<&'static str> {
    Some(match unit.trim().to_lowercase().as_str() {
        "nm" => "nm",
        "um" | "µm" | "μm" | "micron" | "microns" | "micrometre" | "micrometer" => "um",
        "mm" => "mm",
        "m" => "m",
        _ => return None,
    })
}

/// A unit of an electrical signal (a probe recorded in volts before conversion).
pub(crate) fn is_voltage(unit: &str) -> bool {
    matches!(
        unit.trim().to_lowercase().as_str(),
        "v" | "mv" | "volt" | "volts"
    )
}

/// An angle unit: `deg`, `rad` or `counts` (per revolution still to find).
pub(crate) fn angle_unit(unit: &str) -> Option<&'static str> {
    Some(match unit.trim().to_lowercase().as_str() {
        "deg" | "°" | "degree" | "degrees" | "grad" => "deg",
        "rad" | "radian" | "radians" => "rad",
        "counts" | "count" | "cnt" | "cts" | "inc" | "increments" | "ticks" => "counts",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roles_from_names() {
        let role = |n: &str| Column::of(n).role;
        assert_eq!(role("Zeit [s]"), Role::Time);
        assert_eq!(role("Spalt [mm]"), Role::Gap);
        assert_eq!(role("Winkel"), Role::Angle);
        assert_eq!(role("encoder"), Role::Angle);
        assert_eq!(role("index"), Role::Index);
        assert_eq!(role("time_ms"), Role::Time);
        assert_eq!(role("gap_um"), Role::Gap);
        assert_eq!(role("rate_deg_s"), Role::Rate);
        assert_eq!(role("output_rad_s"), Role::Output);
        assert_eq!(role("output_rad"), Role::Output);
        assert_eq!(role("sigma_rad_s"), Role::Sigma);
        assert_eq!(role("Temperature [C]"), Role::Other);
        assert_eq!(Column::of("Time (ms)").unit.as_deref(), Some("ms"));
    }

    #[test]
    fn units() {
        assert_eq!(time_unit("ms"), Some("ms"));
        assert_eq!(time_unit("µs"), Some("us"));
        assert_eq!(length_unit("µm"), Some("um"));
        assert_eq!(angle_unit("°"), Some("deg"));
        assert!(is_voltage("V"));
        assert_eq!(length_unit("V"), None);
    }
}

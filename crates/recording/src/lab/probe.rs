//! Probe recordings: time, probe gap and, optionally, the spindle encoder's angle, one
//! sample per row (the raw data behind eq. 20).

use std::f64::consts::{PI, TAU};
use std::ops::Range;
use std::path::{Path, PathBuf};

use harmonics::{HarmonicsError, ProbeSignal, SpindleAngle};

use super::format::{
    ANGLE_SLOT, AngleSource, LengthUnit, OnBadSamples, OnOutlier, RecordingFormat,
};
use super::volts::{GapUnit, ProbeSensitivity, volts_to_um};
use crate::error::{RecordingError, Result};
use crate::text::line_table::LineTable;
use crate::text::table::Table;

/// Where a recording's spindle angle came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AngleSourceKind {
    /// The encoder column.
    Encoder,
    /// The index-pulse column, interpolated in time between pulses.
    IndexPulse,
    /// The declared rate and a start angle: nothing measured.
    DeclaredRate,
}

impl AngleSourceKind {
    /// The name written in results (`encoder`, `index_pulse`, `declared_rate`).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Encoder => "encoder",
            Self::IndexPulse => "index_pulse",
            Self::DeclaredRate => "declared_rate",
        }
    }
}

/// A probe recording in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// The file it was read from.
    pub path: PathBuf,
    /// Sample times, s (strictly increasing; without a gap above the format's limit unless
    /// the format drops the revolutions gaps touch).
    pub time_s: Vec<f64>,
    /// Probe gap of each sample, in [`Recording::gap_unit`] (NaN or infinite only with
    /// `on_non_finite: drop_revolution`).
    pub gap: Vec<f64>,
    /// Unit of [`Recording::gap`] (µm for a gap recorded in volts, converted).
    pub gap_unit: LengthUnit,
    /// The probe sensitivity the gap was converted from volts with, when it was recorded
    /// in volts: its relative standard uncertainty is the probe-gain Type B input.
    pub sensitivity: Option<ProbeSensitivity>,
    /// The measured angle of each sample, rad (encoder, or interpolated index pulses).
    pub angle_rad: Option<Vec<f64>>,
    /// Where the angle comes from.
    pub angle_source: AngleSourceKind,
    /// Angle of the first sample when the angle comes from the declared rate, rad.
    pub start_angle_rad: f64,
    /// Columns of the header that were not read (named in the `angle_from_rate` warning:
    /// one of them may be an encoder or index pulse).
    pub unread_columns: Vec<String>,
    /// Largest sample interval, in nominal intervals, before it is a gap.
    pub max_gap_intervals: f64,
    /// What a gap does.
    pub on_gap: OnBadSamples,
    /// What a non-finite sample does.
    pub on_non_finite: OnBadSamples,
    /// What a revolution whose residual RMS is far above the others' does.
    pub on_outlier: OnOutlier,
    /// The line of each sample in the file.
    lines: LineTable,
}

impl Recording {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no samples (never true for a loaded recording).
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// The 1-based line of sample `index` (0-based) in the file, from the row → line table
    /// kept when the file was read (the file is not read again). An index past the last
    /// sample is counted on from it. 0 for a recording read from a binary file (TDMS,
    /// MAT), whose samples have no line: its errors name the channel and sample index.
    pub fn line_of_sample(&self, index: usize) -> usize {
        self.lines.line_of(index)
    }

    /// A recording of checked samples read from a binary file: no row → line table
    /// ([`Recording::line_of_sample`] is 0).
    pub(crate) fn from_samples(
        path: PathBuf,
        time_s: Vec<f64>,
        gap: Vec<f64>,
        gap_unit: LengthUnit,
        sensitivity: Option<ProbeSensitivity>,
        angle_rad: Option<Vec<f64>>,
        (max_gap_intervals, on_gap, on_non_finite): (f64, OnBadSamples, OnBadSamples),
    ) -> Self {
        Self {
            path,
            time_s,
            gap,
            gap_unit,
            sensitivity,
            angle_source: if angle_rad.is_some() {
                AngleSourceKind::Encoder
            } else {
                AngleSourceKind::DeclaredRate
            },
            angle_rad,
            start_angle_rad: 0.0,
            unread_columns: Vec::new(),
            max_gap_intervals,
            on_gap,
            on_non_finite,
            on_outlier: OnOutlier::default(),
            lines: LineTable::default(),
        }
    }

    /// Moves a measured angle's zero to the angle zero of eq. 20–21 (the arm's PIGA end
    /// pointing at the probe, along O1X1): `angle_zero_rad` is what the encoder reads (or
    /// how far the spindle has turned past the index pulse's rising edge) there, and every
    /// measured angle becomes the angle less it. An exact shift of the angle, before any
    /// fit: the revolutions are cut at the same samples (they start a whole turn from the
    /// first sample's angle), and the first harmonic comes out turned by the offset.
    ///
    /// An angle from the declared rate is not moved: its start angle
    /// (`rate(start_angle_deg)`) is already the first sample's angle from the angle zero.
    ///
    /// ```
    /// use recording::{parse_recording, RecordingFormat};
    /// let text = "time_s,gap_um,angle_deg\n0.000,12.5,30.0\n0.001,12.6,31.0\n";
    /// let mut rec = parse_recording(text.as_bytes(), "p.csv".as_ref(), &RecordingFormat::default())?;
    /// rec.shift_angle_zero(30f64.to_radians());
    /// approx::assert_relative_eq!(rec.angle_rad.as_ref().unwrap()[1], 1f64.to_radians(), epsilon = 1e-15);
    /// # Ok::<(), recording::RecordingError>(())
    /// ```
    pub fn shift_angle_zero(&mut self, angle_zero_rad: f64) {
        if angle_zero_rad == 0.0 {
            return;
        }
        if let Some(a) = self.angle_rad.as_mut() {
            for v in a {
                *v -= angle_zero_rad;
            }
        }
    }

    /// The samples as a [`ProbeSignal`]: the measured angle when there is one, else
    /// `θ = ω·(t − t₀) + θ₀` from the declared rate and the format's start angle.
    pub fn signal(&self, declared_rate_rad_s: f64) -> ProbeSignal<'_> {
        self.signal_of(0..self.len(), declared_rate_rad_s)
    }

    /// The samples of `range` as a [`ProbeSignal`] (the rate angle continues from the
    /// recording's first sample).
    pub(crate) fn signal_of(
        &self,
        range: Range<usize>,
        declared_rate_rad_s: f64,
    ) -> ProbeSignal<'_> {
        let angle = match &self.angle_rad {
            Some(a) => SpindleAngle::Encoder(&a[range.clone()]),
            None => SpindleAngle::Rate {
                rate_rad_s: declared_rate_rad_s,
                start_angle_rad: self.start_angle_rad
                    + declared_rate_rad_s
                        * (self.time_s.get(range.start).copied().unwrap_or(0.0) - self.time_s[0]),
            },
        };
        ProbeSignal {
            time_s: &self.time_s[range.clone()],
            gap: &self.gap[range],
            angle,
        }
    }

    /// The angle of sample `index`, rad: measured, or from the declared rate.
    pub fn angle_at(&self, index: usize, declared_rate_rad_s: f64) -> f64 {
        match &self.angle_rad {
            Some(a) => a[index],
            None => {
                self.start_angle_rad + declared_rate_rad_s * (self.time_s[index] - self.time_s[0])
            }
        }
    }

    /// The mean rate of the measured angle, rad/s: its unwrapped span over the time span of
    /// the finite samples (`None` without a measured angle or with fewer than two finite
    /// samples).
    pub fn measured_rate_rad_s(&self) -> Option<f64> {
        self.measured_rate_between(0, self.len().checked_sub(1)?)
    }

    /// The mean rate of the measured angle between samples `from` and `to` (inclusive,
    /// non-finite samples skipped), rad/s. Over whole revolutions, a once-per-revolution
    /// speed ripple averages out.
    pub fn measured_rate_between(&self, from: usize, to: usize) -> Option<f64> {
        let a = self.angle_rad.as_ref()?;
        let to = to.min(a.len().checked_sub(1)?);
        let ok = |i: usize| a[i].is_finite() && self.time_s[i].is_finite();
        let first = (from..=to).find(|&i| ok(i))?;
        let last = (from..=to).rev().find(|&i| ok(i))?;
        if last <= first {
            return None;
        }
        let window = &a[first..=last];
        // The span is the end-to-end difference plus a turn for each step that wraps (a
        // step beyond ±π); a branch-free count that vectorises. Only with non-finite
        // samples (kept to be dropped) are the steps taken one by one around them.
        let span = if self.on_non_finite == OnBadSamples::Error {
            let wraps: i64 = window
                .windows(2)
                .map(|w| {
                    let d = w[1] - w[0];
                    i64::from(d < -PI) - i64::from(d > PI)
                })
                .sum();
            a[last] - a[first] + TAU * wraps as f64
        } else {
            let mut span = 0.0;
            let mut prev = a[first];
            for &v in &window[1..] {
                if v.is_finite() {
                    span += wrapped_step(prev, v);
                    prev = v;
                }
            }
            span
        };
        Some(span / (self.time_s[last] - self.time_s[first]))
    }

    /// The recording in a table read with [`RecordingFormat::table_format`]: time in s, the
    /// angle in radians (or built from index pulses), the time axis checked.
    pub(crate) fn from_table(table: Table, format: &RecordingFormat) -> Result<Self> {
        let Table {
            path,
            mut columns,
            names,
            header,
            header_line,
            lines,
            ..
        } = table;
        let unread_columns = header
            .iter()
            .filter(|h| !names.contains(h))
            .cloned()
            .collect();
        let mut take = |k: usize| columns.get_mut(k).and_then(Option::take);
        // Time and gap are required columns: the table has them.
        let mut time_s = take(0).unwrap_or_default();
        let mut gap = take(1).unwrap_or_default();
        check_gap_header_unit(&header, &path, format, header_line)?;
        let sensitivity = format.gap.unit.sensitivity()?;
        if let Some(s) = &sensitivity {
            volts_to_um(&mut gap, s);
        }
        let raw_angle = take(ANGLE_SLOT);
        let time_scale = format.time.unit.s_per_unit();
        if time_scale != 1.0 {
            for t in &mut time_s {
                *t *= time_scale;
            }
        }
        let mut start_angle_rad = 0.0;
        let (angle_rad, angle_source) = match (&format.angle, raw_angle) {
            (AngleSource::Encoder { unit, .. }, Some(mut a)) => {
                let scale = unit.rad_per_unit();
                if scale != 1.0 {
                    for v in &mut a {
                        *v *= scale;
                    }
                }
                (Some(a), AngleSourceKind::Encoder)
            }
            (AngleSource::IndexPulse { column }, Some(p)) => {
                let a = index_pulse_angle(&time_s, &p).map_err(|edges| {
                    RecordingError::TooFewIndexPulses {
                        path: path.clone(),
                        column: column.clone(),
                        edges,
                    }
                })?;
                (Some(a), AngleSourceKind::IndexPulse)
            }
            (AngleSource::Rate { start_angle_deg }, _) => {
                start_angle_rad = start_angle_deg.to_radians();
                (None, AngleSourceKind::DeclaredRate)
            }
            // An optional encoder column the header lacks.
            (_, None) => (None, AngleSourceKind::DeclaredRate),
        };
        let strict =
            format.on_gap == OnBadSamples::Error && format.on_non_finite == OnBadSamples::Error;
        // The values are finite (unless non-finite ones are kept); what is left is their
        // order, gaps, and intervals that overflow (a single row has no interval to check).
        // A format that drops revolutions leaves gaps and non-finite samples to the
        // analysis.
        let limit = if strict {
            format.max_gap_intervals
        } else {
            f64::MAX
        };
        let finite_times = strict || time_s.iter().all(|t| t.is_finite());
        if time_s.len() > 1 && finite_times {
            harmonics::check_time_axis(&time_s, limit)
                .map_err(|e| time_axis_error(e, &path, &lines))?;
        }
        Ok(Self {
            path,
            time_s,
            gap,
            gap_unit: format.gap.unit.length_unit(),
            sensitivity,
            angle_rad,
            angle_source,
            start_angle_rad,
            unread_columns,
            max_gap_intervals: format.max_gap_intervals,
            on_gap: format.on_gap,
            on_non_finite: format.on_non_finite,
            on_outlier: format.on_outlier,
            lines,
        })
    }
}

/// Refuses a gap column whose header states another unit than the format declares
/// (`Spalt [mm]` declared `um` would make C_r 1000 times too small).
pub(crate) fn check_gap_header_unit(
    header: &[String],
    path: &Path,
    format: &RecordingFormat,
    header_line: usize,
) -> Result<()> {
    let name = format.gap.column.trim();
    let Some(stated) = header
        .iter()
        .find(|h| *h == name)
        .and_then(|h| gap_unit_in_header(h))
    else {
        return Ok(());
    };
    let declared = format.gap.unit;
    let same = match (stated, declared) {
        (None, GapUnit::Volts { .. }) => true,
        (Some(a), b) => GapUnit::from(a) == b,
        _ => false,
    };
    if same {
        return Ok(());
    }
    Err(RecordingError::ColumnUnit {
        path: path.to_owned(),
        line: header_line,
        column: name.to_owned(),
        stated: super::format::header_unit(name)
            .unwrap_or_default()
            .to_owned(),
        declared: gap_unit_key(declared),
        suggested: match stated {
            Some(unit) => gap_unit_key(unit.into()),
            None => "volts(sensitivity: ..., sensitivity_unit: ..., u_sensitivity: ...)",
        },
    })
}

/// The configuration name of a gap unit.
fn gap_unit_key(unit: GapUnit) -> &'static str {
    match unit {
        GapUnit::Nm => "nm",
        GapUnit::Um => "um",
        GapUnit::Mm => "mm",
        GapUnit::M => "m",
        GapUnit::Volts { .. } => "volts(...)",
    }
}

/// The unit a gap column's header states at its end (`Spalt [mm]`, `gap (µm)`): a length
/// unit, or `None` inside for volts; `None` when the header states none it knows.
pub(crate) fn gap_unit_in_header(header: &str) -> Option<Option<LengthUnit>> {
    let unit = super::format::header_unit(header)?;
    Some(match unit {
        "nm" => Some(LengthUnit::Nm),
        "um" | "µm" | "μm" | "micron" => Some(LengthUnit::Um),
        "mm" => Some(LengthUnit::Mm),
        "m" => Some(LengthUnit::M),
        "V" | "v" => None,
        _ => return None,
    })
}

/// The reader's error for a time axis that [`harmonics::check_time_axis`] refused.
pub(crate) fn time_axis_error(e: HarmonicsError, path: &Path, lines: &LineTable) -> RecordingError {
    let path = path.to_owned();
    let line = |index| lines.line_of(index);
    match e {
        HarmonicsError::TimeNotIncreasing {
            index,
            previous_s,
            time_s,
            ..
        } => RecordingError::TimeNotIncreasing {
            path,
            line: line(index),
            previous_s,
            time_s,
        },
        HarmonicsError::SampleGap {
            index,
            interval_s,
            nominal_interval_s,
            max_intervals,
            ..
        } => RecordingError::SampleGap {
            path,
            line: line(index),
            interval_s,
            nominal_interval_s,
            max_intervals,
        },
        source => RecordingError::Samples {
            path,
            line: sample_index(&source).map(line),
            hint: None,
            source,
        },
    }
}

/// An angle step wrapped into `(−π, π]`.
fn wrapped_step(a: f64, b: f64) -> f64 {
    let d = b - a;
    d - TAU * ((d + PI) / TAU).ceil() + TAU
}

/// The angle from a once-per-revolution marker: 0 at each rising edge (the middle of the
/// interval in which the marker crosses ½), `2π` more at each next one, linear in time
/// between edges and extended with the neighbouring period before the first and after the
/// last. `Err(edges)` with fewer than two rising edges. A non-finite marker or time gives
/// a NaN angle (a bad sample).
fn index_pulse_angle(time_s: &[f64], pulse: &[f64]) -> std::result::Result<Vec<f64>, usize> {
    let mut edges = Vec::new();
    for i in 1..pulse.len() {
        if pulse[i - 1] < 0.5
            && pulse[i] >= 0.5
            && time_s[i - 1].is_finite()
            && time_s[i].is_finite()
        {
            edges.push(0.5 * (time_s[i - 1] + time_s[i]));
        }
    }
    if edges.len() < 2 {
        return Err(edges.len());
    }
    let m = edges.len() - 1;
    let mut k = 0;
    Ok(time_s
        .iter()
        .zip(pulse)
        .map(|(&t, &p)| {
            if !(t.is_finite() && p.is_finite()) {
                return f64::NAN;
            }
            while k < m && t >= edges[k + 1] {
                k += 1;
            }
            // Revolution k spans edges[k]..edges[k + 1]; past the last edge the last period
            // is extended (and before the first, the first).
            let (j, period) = if k == m {
                (m, edges[m] - edges[m - 1])
            } else {
                (k, edges[k + 1] - edges[k])
            };
            TAU * (j as f64 + (t - edges[j]) / period)
        })
        .collect())
}

/// The angle from a once-per-revolution marker of a binary recording (see
/// [`index_pulse_angle`]).
pub(crate) fn pulse_angle(
    path: &Path,
    column: &str,
    time_s: &[f64],
    pulse: &[f64],
) -> Result<Vec<f64>> {
    index_pulse_angle(time_s, pulse).map_err(|edges| RecordingError::TooFewIndexPulses {
        path: path.to_path_buf(),
        column: column.to_owned(),
        edges,
    })
}

/// [`parse_recording`] through the reference path of the table parser (every row field by
/// field, [`crate::parse_table_reference`]): the fast path must give the same recording or
/// the same error. For the tests and the fuzz targets; not part of the crate's interface.
#[doc(hidden)]
pub fn parse_recording_reference(
    text: &[u8],
    path: &Path,
    format: &RecordingFormat,
) -> Result<Recording> {
    let table = crate::text::parser::parse_table_reference(text, path, &format.table_format()?)?;
    Recording::from_table(table, format)
}

/// The sample an analysis error names, if any.
pub(crate) fn sample_index(error: &HarmonicsError) -> Option<usize> {
    match error {
        HarmonicsError::NonFinite { index, .. }
        | HarmonicsError::NonFiniteInterval { index, .. }
        | HarmonicsError::TimeNotIncreasing { index, .. }
        | HarmonicsError::SampleGap { index, .. }
        | HarmonicsError::AngleNotIncreasing { index, .. } => Some(*index),
        HarmonicsError::TooFewSamples { first_sample, .. } => Some(*first_sample),
        HarmonicsError::Aliasing { after_sample, .. } => Some(*after_sample),
        _ => None,
    }
}

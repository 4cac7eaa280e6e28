//! The study's shared core, which every section uses and which uses no section: the data
//! source, where the configuration came from and the centrifuge's geometry ([`Core`]), the
//! phase names sections refer to ([`PhaseNames`]), and the field checks that name the
//! configuration file ([`Check`]).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use harmonics::{LeverGeometry, ProbeDirection};
use recording::{
    FileDigest, PigaRecording, PigaRecordingFormat, Recording, RecordingError, RecordingFormat,
    Table, TableFormat,
};

use crate::config::{ProbeDirectionName, StudyConfig};
use crate::error::{InvalidReason, PipelineError, Result};
use crate::results::{AngleZero, ProbeSign};

/// The caller's access to the data files a study names: files at the edge
/// ([`crate::load_study`]), or data held in memory (a test, another program).
pub trait DataSource: Sync {
    /// The probe recording at `path`, read in `format`.
    fn recording(
        &self,
        path: &Path,
        format: &RecordingFormat,
    ) -> std::result::Result<Recording, RecordingError>;

    /// The table at `path`, read in `format`.
    fn table(
        &self,
        path: &Path,
        format: &TableFormat,
    ) -> std::result::Result<Table, RecordingError>;

    /// The raw PIGA output recording at `path`, read in `format`: by default, the file read
    /// as a probe recording ([`DataSource::recording`]) with the output angle in the gap's
    /// place, converted and unwrapped.
    fn piga_recording(
        &self,
        path: &Path,
        format: &PigaRecordingFormat,
    ) -> std::result::Result<PigaRecording, RecordingError> {
        let samples = self.recording(path, &format.probe_format()?)?;
        PigaRecording::from_recording(samples, format.output.unit)
    }

    /// [`DataSource::recording`], with the size and SHA-256 of the bytes read when this
    /// source keeps them (provenance). By default without a digest; [`crate::Files`] hashes
    /// each file as it reads it. The study reads every data file through these `read_`
    /// methods, once.
    fn read_recording(
        &self,
        path: &Path,
        format: &RecordingFormat,
    ) -> std::result::Result<Loaded<Recording>, RecordingError> {
        self.recording(path, format).map(Loaded::undigested)
    }

    /// [`DataSource::table`], with the digest of the bytes read when this source keeps one.
    fn read_table(
        &self,
        path: &Path,
        format: &TableFormat,
    ) -> std::result::Result<Loaded<Table>, RecordingError> {
        self.table(path, format).map(Loaded::undigested)
    }

    /// [`DataSource::piga_recording`], with the digest of the bytes read when this source
    /// keeps one.
    fn read_piga_recording(
        &self,
        path: &Path,
        format: &PigaRecordingFormat,
    ) -> std::result::Result<Loaded<PigaRecording>, RecordingError> {
        self.piga_recording(path, format).map(Loaded::undigested)
    }
}

/// Data a [`DataSource`] read, with the size and SHA-256 of the bytes it read when it keeps
/// them.
#[derive(Debug, Clone)]
pub struct Loaded<T> {
    /// The data.
    pub value: T,
    /// The file's size and SHA-256 as read (`None`: the source keeps none, e.g. data held in
    /// memory).
    pub digest: Option<FileDigest>,
}

impl<T> Loaded<T> {
    /// Data without a digest.
    pub const fn undigested(value: T) -> Self {
        Self {
            value,
            digest: None,
        }
    }
}

/// What an input file is to a study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum InputRole {
    /// A displacement-probe recording of a phase.
    ProbeRecording,
    /// The calibration's PIGA table.
    PigaTable,
    /// A raw PIGA output recording of the calibration.
    PigaRecording,
}

impl InputRole {
    /// The role as results.json writes it (`probe_recording`, `piga_table`,
    /// `piga_recording`).
    #[must_use]
    pub const fn code(self) -> &'static str {
        match self {
            Self::ProbeRecording => "probe_recording",
            Self::PigaTable => "piga_table",
            Self::PigaRecording => "piga_recording",
        }
    }
}

impl std::fmt::Display for InputRole {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::ProbeRecording => "probe recording",
            Self::PigaTable => "PIGA table",
            Self::PigaRecording => "raw PIGA output recording",
        })
    }
}

/// One data file a study read: where, what for, and its size and SHA-256 as read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputFile<'a> {
    /// The path as the study read it (the configuration's folder joined with its path).
    pub path: &'a Path,
    /// What it is.
    pub role: InputRole,
    /// The configuration field that names it (`phases[0].points.files[2]`).
    pub field: String,
    /// Its size and SHA-256 as read (`None` when the data source keeps no digest).
    pub digest: Option<&'a FileDigest>,
}

/// Least number of distinct rates of an eq. 18 calibration (mechanism or measured): six
/// unknowns plus one degree of freedom.
pub(crate) const MIN_CALIBRATION_RATES: usize = identify::MIN_DISTINCT_RATES + 1;

/// What every section knows of a study: where its configuration came from and the
/// centrifuge's geometry, validated.
#[derive(Debug, Clone)]
pub(crate) struct Core {
    /// The configuration file (named in every error; data paths are relative to its folder).
    pub(crate) source: PathBuf,
    pub(crate) name: String,
    pub(crate) radius_m: f64,
    pub(crate) g_m_s2: f64,
    pub(crate) k1_rad_s_g: f64,
    pub(crate) lever: LeverGeometry,
    pub(crate) lever_ratio: f64,
    /// The angle zero the probe recordings' measured angles are taken from
    /// (`lever.angle_zero_deg`, 0 when not stated).
    pub(crate) angle_zero: AngleZero,
}

impl Core {
    /// Validates the study's scalars and lever.
    pub(crate) fn new(config: &StudyConfig, source: &Path) -> Result<Self> {
        let check = Check { path: source };
        if let Some(hidden) = edge_io::hidden_char(&config.name) {
            return Err(PipelineError::HiddenCharacter {
                path: source.to_owned(),
                field: "name".to_owned(),
                hidden,
            });
        }
        let required = |field: &str, value: Option<f64>, what: &str| -> Result<f64> {
            value.ok_or_else(|| PipelineError::MissingField {
                path: source.to_owned(),
                field: field.to_owned(),
                hint: format!(
                    "{what}; or name the lab profile that states it (`profile: \"lab.ron\"`, \
                     `centrifuge: \"…\"`, docs/PROFILE.md)"
                ),
            })
        };
        let mut errors = Vec::new();
        let mut take = |r: Result<f64>| r.map_err(|e| errors.push(e)).unwrap_or(f64::NAN);
        let radius_m = take(required(
            "radius_m",
            config.radius_m,
            "the static working radius R, m",
        ));
        let g_m_s2 = take(required("g_m_s2", config.g_m_s2, "the local gravity, m/s²"));
        let pivot_to_probe_mm = take(required(
            "lever.pivot_to_probe_mm",
            config.lever.pivot_to_probe_mm,
            "the height from the tilt pivot to the probe plane, mm",
        ));
        let probe_to_piga_mm = take(required(
            "lever.probe_to_piga_mm",
            config.lever.probe_to_piga_mm,
            "the height from the probe plane to the PIGA's plane, mm",
        ));
        PipelineError::from_list(errors)?;
        check.positive("radius_m", radius_m)?;
        check.positive("g_m_s2", g_m_s2)?;
        // Plausibility (issue 32): a g off the Earth's surface is a typing or unit error, and
        // one of 1e300 made every bound that scales with it absurd (`[1e198, inf]`).
        if !units::GRAVITY_RANGE_M_S2.contains(&g_m_s2) {
            return Err(check.invalid(
                "g_m_s2".to_owned(),
                g_m_s2,
                InvalidReason::GravityImplausible,
            ));
        }
        check.positive("k1_rad_s_g", config.k1_rad_s_g)?;
        let lever = LeverGeometry {
            pivot_to_probe_mm,
            probe_to_piga_mm,
            probe_direction: probe_direction(config.lever.probe_direction.unwrap_or_default()),
        };
        let lever_ratio = lever
            .lever_ratio()
            .map_err(|source_error| PipelineError::Harmonics {
                path: source.to_owned(),
                field: "lever".to_owned(),
                source: source_error,
            })?;
        let angle_zero = match config.lever.angle_zero_deg {
            Some(deg) => {
                check.finite("lever.angle_zero_deg".to_owned(), deg)?;
                AngleZero {
                    angle_zero_deg: deg,
                    stated: true,
                    // known once the recordings are read
                    measured_angles: false,
                }
            }
            None => AngleZero::default(),
        };
        Ok(Self {
            source: source.to_owned(),
            name: config.name.clone(),
            radius_m,
            g_m_s2,
            k1_rad_s_g: config.k1_rad_s_g,
            lever,
            lever_ratio,
            angle_zero,
        })
    }

    /// The radius and g that turn a rate into the nominal input `a = R·ω²/g`.
    pub(crate) const fn geometry(&self) -> identify::Geometry {
        identify::Geometry {
            radius_m: self.radius_m,
            g_m_s2: self.g_m_s2,
        }
    }

    /// The folder data paths are relative to.
    pub(crate) fn base(&self) -> &Path {
        self.source.parent().unwrap_or_else(|| Path::new("."))
    }

    /// Field checks naming the configuration file.
    pub(crate) fn check(&self) -> Check<'_> {
        Check { path: &self.source }
    }
}

/// The results' name of the library's probe direction (whose words are
/// [`ProbeSign::words`]).
pub(crate) const fn probe_sign(direction: ProbeDirection) -> ProbeSign {
    match direction {
        ProbeDirection::AlongO1X1 => ProbeSign::AlongO1X1,
        ProbeDirection::AgainstO1X1 => ProbeSign::AgainstO1X1,
    }
}

/// The library's probe direction from the file's.
pub(crate) const fn probe_direction(name: ProbeDirectionName) -> ProbeDirection {
    match name {
        ProbeDirectionName::AgainstO1X1 => ProbeDirection::AgainstO1X1,
        ProbeDirectionName::AlongO1X1 => ProbeDirection::AlongO1X1,
    }
}

/// The study's phase names, by index, and which phases hold a second probe's data: what the
/// sections that refer to phases by name need.
#[derive(Debug, Clone)]
pub(crate) struct PhaseNames<'a> {
    pub(crate) names: HashMap<&'a str, usize>,
    /// Phases holding a second probe's data (read with the first probe's lever, their C_r is
    /// not the PIGA plane's; docs/BALANCING.md).
    pub(crate) second_probe: Vec<usize>,
}

impl PhaseNames<'_> {
    /// The index of the phase `name`, or an error naming `field` and the known names.
    pub(crate) fn index(&self, check: &Check<'_>, field: &str, name: &str) -> Result<usize> {
        self.names
            .get(name)
            .copied()
            .ok_or_else(|| PipelineError::UnknownPhase {
                path: check.path.to_owned(),
                field: field.to_owned(),
                name: name.to_owned(),
                known: sorted_names(&self.names),
            })
    }
}

/// Field checks that name the configuration file.
pub(crate) struct Check<'a> {
    /// The configuration file.
    pub(crate) path: &'a Path,
}

impl Check<'_> {
    pub(crate) fn invalid(
        &self,
        field: String,
        value: f64,
        reason: InvalidReason,
    ) -> PipelineError {
        PipelineError::InvalidField {
            path: self.path.to_owned(),
            field,
            value,
            reason,
        }
    }

    pub(crate) fn positive(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field.to_owned(), value, InvalidReason::NotPositive))
        }
    }

    pub(crate) fn finite(&self, field: String, value: f64) -> Result<()> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(self.invalid(field, value, InvalidReason::NotFinite))
        }
    }

    pub(crate) fn rate(&self, field: String, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field, value, InvalidReason::RateNotPositive))
        }
    }

    /// Refuses a rate that appears twice, naming both places (linear time).
    pub(crate) fn unique_rates(&self, items: &str, rates: &[f64]) -> Result<()> {
        let mut seen: HashMap<u64, usize> = HashMap::with_capacity(rates.len());
        for (i, r) in rates.iter().enumerate() {
            // Rates are finite and > 0 here, so equal values have equal bits.
            if let Some(j) = seen.insert(r.to_bits(), i) {
                return Err(PipelineError::DuplicateRate {
                    path: self.path.to_owned(),
                    field: format!("{items}[{i}].rate_deg_s"),
                    first: format!("{items}[{j}].rate_deg_s"),
                    rate_deg_s: *r,
                });
            }
        }
        Ok(())
    }

    pub(crate) fn non_negative(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field.to_owned(), value, InvalidReason::Negative))
        }
    }
}

/// The phase names in the study's order, for a hint.
pub(crate) fn sorted_names(names: &HashMap<&str, usize>) -> Vec<String> {
    let mut list: Vec<(usize, &str)> = names.iter().map(|(n, i)| (*i, *n)).collect();
    list.sort_unstable();
    list.into_iter().map(|(_, n)| n.to_owned()).collect()
}

pub(crate) fn rates_of<T>(items: &[T], rate: impl Fn(&T) -> f64) -> Vec<f64> {
    items.iter().map(rate).collect()
}

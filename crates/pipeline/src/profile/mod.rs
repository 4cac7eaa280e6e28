//! The lab profile (`lab.ron`, `docs/PROFILE.md`) on values: parsed from text the edge read
//! ([`Profile::from_ron`]), validated (every problem at once, each naming the profile's file
//! and field) and resolved into a study's configuration: what the study leaves out is taken
//! from the profile — the centrifuge's radius and probe geometry, g, the Type B inputs with
//! their traceability, the certificate's laboratory, place, equipment, procedure, operator,
//! decision rule and signatory — and what it states overrides the profile. The results say
//! which value came from where ([`ProfileResults`]). Core: used by the study, importing no
//! section.

mod resolve;
mod validate;

use std::path::{Path, PathBuf};

use recording::FileDigest;

use crate::config::{ProfileConfig, StudyConfig};
use crate::error::{PipelineError, Result};
use crate::results::ProfileResults;
use resolve::resolve;

/// A lab profile as read, unvalidated, with the file it came from (named in every error) and
/// its size and SHA-256 when the edge read it from disk.
#[derive(Debug, Clone)]
pub struct Profile {
    config: ProfileConfig,
    source: PathBuf,
    digest: Option<FileDigest>,
}

impl Profile {
    /// A profile from its configuration; `source` names it in errors and results.
    #[must_use]
    pub fn new(config: ProfileConfig, source: &Path) -> Self {
        Self {
            config,
            source: source.to_owned(),
            digest: None,
        }
    }

    /// Parses RON text (the study's dialect, a byte-order mark dropped) into a profile,
    /// unvalidated; errors name `path`, the line and column, and the profile's keys.
    ///
    /// # Errors
    /// [`PipelineError::Parse`] for malformed RON, an unknown or a misspelt field.
    pub fn from_ron(text: &str, path: &Path) -> Result<Self> {
        let config = edge_io::from_ron(text, path).map_err(crate::config::parse_error)?;
        Ok(Self::new(config, path))
    }

    /// The profile with the size and SHA-256 of its bytes as the edge read them.
    #[must_use]
    pub fn with_digest(mut self, digest: FileDigest) -> Self {
        self.digest = Some(digest);
        self
    }

    /// The file it came from.
    pub fn source(&self) -> &Path {
        &self.source
    }

    /// Its size and SHA-256 as read (`None` for a profile built from values).
    pub const fn digest(&self) -> Option<&FileDigest> {
        self.digest.as_ref()
    }

    /// What the file says.
    pub const fn config(&self) -> &ProfileConfig {
        &self.config
    }

    /// Validates the profile and fills `config`'s missing values from it (what the study
    /// states overrides the profile); `study` names the study file in errors. What
    /// [`crate::Inputs::with_profile`] does before it validates the study, for a caller that
    /// shows the study as it will run (`check`).
    ///
    /// # Errors
    /// Those of [`Profile::validate`]; a centrifuge, probe or signatory the profile does not
    /// have, or a study without `centrifuge`.
    pub fn apply(&self, config: &mut StudyConfig, study: &Path) -> Result<ProfileResults> {
        self.validate()?;
        let (used, errors) = resolve(config, &self.config, &self.source, study)?;
        PipelineError::from_list(errors)?;
        Ok(used)
    }

    /// [`Profile::apply`] for showing the study as far as it can be resolved: what the
    /// profile gives is filled in and listed even when some reference of the study (the
    /// signatory it names) is refused; `None` when the profile or the centrifuge is.
    pub fn apply_partly(&self, config: &mut StudyConfig, study: &Path) -> Option<ProfileResults> {
        self.validate().ok()?;
        resolve(config, &self.config, &self.source, study)
            .ok()
            .map(|(used, _)| used)
    }

    /// Validates the profile: every problem at once, each naming the profile's file and
    /// field.
    ///
    /// # Errors
    /// [`PipelineError::MissingField`], [`PipelineError::InvalidField`],
    /// [`PipelineError::InvalidDate`], [`PipelineError::DuplicateName`],
    /// [`PipelineError::UnknownKey`] (a centrifuge naming a probe the profile does not
    /// have); [`PipelineError::Several`] for more than one.
    pub fn validate(&self) -> Result<()> {
        validate::validate(&self.config, &self.source)
    }
}

//! `cargo xtask identify`: the eq. 18 calibration of a PIGA from a table of outputs at several
//! centrifuge rates, optionally compensated for the spindle's dynamic radius error (eq. 19).

use std::path::{Path, PathBuf};

mod from;

use from::FromStudy;

use crate::console::{Console, ConsoleError};
use anyhow::Context as _;
use calibration::{Calibrated, CalibrationError, CalibrationWarning, Points, Weighting};
use identify::{
    Calibration, CompensatedCalibration, Compensation, CrEstimate, Geometry, IdentifyError,
    K1Source,
};
use pipeline::{PigaTableConfig, TableLayoutError};
use recording::{Column, DecimalMark, Delimiter, Hint, PigaTable, PigaTableFormat, RateUnit};

/// An error reading the table, its hint in identify's options.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
struct TableError(String);

/// A reader's hint (which names a key of a study's `format` block) in identify's options.
fn option_hint(hint: Hint) -> String {
    match hint {
        Hint::DecimalComma => {
            "decimal comma? pass `--decimal comma` (with another delimiter than `,`, e.g. \
             `--delimiter ';'`)"
                .to_owned()
        }
        Hint::DecimalPoint => "decimal point? leave out `--decimal comma`".to_owned(),
        Hint::Delimiter => {
            "another delimiter? pass `--delimiter` with the character between the fields".to_owned()
        }
        Hint::HeaderDelimiter { found } => format!(
            "the header looks separated by {found:?}: pass `--delimiter '{found}'` (a blank \
             for runs of blanks)"
        ),
        Hint::SkipLines => "metadata lines above the header? pass `--skip-lines N` with their \
             number, or name the header's columns with `--rate-column` and `--output-column`"
            .to_owned(),
        // Not a table's: the reader gives these for probe recordings only.
        other => other.to_string(),
    }
}

/// A row of the PIGA table whose value takes the eq. 18 design (powers of ω up to ω⁶, or the
/// compensated output) out of double precision, named by its line in the file.
#[derive(Debug, thiserror::Error)]
#[error(
    "{}:{line}: column `{column}` = {value_c}: the eq. 18 design is not finite at this row \
     (powers of the rate up to ω⁶, or the output after the compensation, overflow)",
    path.display(),
    value_c = units::Compact(*value)
)]
struct RowOutOfRange {
    path: PathBuf,
    line: usize,
    column: String,
    value: f64,
}

/// Values of the table's rows the calibration refuses (`calibration::check_points`, as the
/// study refuses them), each named by its line in the file, in the study's words.
#[derive(Debug, thiserror::Error)]
#[error("{}", lines.join("\n"))]
struct RefusedRows {
    lines: Vec<String>,
}

/// Identify k0…k3 from a PIGA output table, read as a study reads its `calibration.table`.
#[derive(Debug, clap::Args)]
pub(crate) struct Identify {
    /// The PIGA table: a header, then one row per rate point (the rate in deg/s and the mean
    /// output over whole revolutions in rad/s); `#` comment lines and blank lines are skipped.
    /// Read by the study's table reader with the same options (the flags below, as a study's
    /// `calibration.table` names them).
    file: PathBuf,
    /// Header name of the rate column (a study's `rate_column`, or `rate.column` of its
    /// `format` block).
    #[arg(long, default_value = "rate_deg_s")]
    rate_column: String,
    /// Unit of the rate column: deg_s, rad_s, rpm or deg_h (`rate.unit`; a unit the header
    /// states at its end, as in `Drehrate [°/s]`, must agree).
    #[arg(long, default_value = "deg_s", value_parser = RATE_UNITS)]
    rate_unit: String,
    /// Header name of the mean-output column (a study's `output_column`, or `output.column`).
    #[arg(long, default_value = "output_rad_s")]
    output_column: String,
    /// Unit of the output column and of the σ column: deg_s, rad_s, rpm or deg_h
    /// (`output.unit`).
    #[arg(long, default_value = "rad_s", value_parser = RATE_UNITS)]
    output_unit: String,
    /// Field delimiter, one character; a blank or a tab means runs of blanks (a study's
    /// `delimiter`).
    #[arg(long, default_value_t = ',')]
    delimiter: char,
    /// Decimal mark of the numbers: `point` or `comma` (a study's `decimal`; with a comma
    /// the delimiter must not be `,`).
    #[arg(long, default_value = "point", value_parser = ["point", "comma"])]
    decimal: String,
    /// Lines before the header, blank ones included, as exports write metadata there (a
    /// study's `skip_lines`).
    #[arg(long, default_value_t = 0)]
    skip_lines: usize,
    /// Header name of each output's standard uncertainty, in the output's unit: the fit is
    /// weighted by 1/σ (a study's `sigma_column`).
    #[arg(long)]
    sigma_column: Option<String>,
    /// Header name of a text column labelling each row (a study's `label_column`).
    #[arg(long)]
    label_column: Option<String>,
    /// Working radius R (m), used to form a = R·ω²/g (required unless --from).
    #[arg(long, required_unless_present = "from")]
    radius_m: Option<f64>,
    /// Gravity g (m/s²), stated: there is no default (required unless --from).
    #[arg(long, required_unless_present = "from", conflicts_with = "from")]
    g: Option<f64>,
    /// A study's results.json: R and g as the study used them, C_r and σ(C_r) of the phase
    /// its calibration compensated with (or the one named by --phase), and k1 as the study
    /// chose it (fitted or given by its calibration;
    /// without one, the k1 of its Δk2). Instead of --radius-m, --g, --k1, --c-r-m-s2,
    /// --c-r-sigma-m-s2.
    #[arg(long, conflicts_with_all = ["radius_m", "k1", "c_r_m_s2", "c_r_sigma_m_s2"])]
    from: Option<PathBuf>,
    /// The phase of --from whose C_r compensates (default: the one the study's calibration
    /// compensated with).
    #[arg(long, requires = "from")]
    phase: Option<String>,
    /// k1 (rad/(s·g)) for the compensation. Without it, k1 is implied by the fitted ω²
    /// coefficient (c₂·g/R).
    #[arg(long, requires = "c_r_m_s2")]
    k1: Option<f64>,
    /// Dynamic radius-error coefficient C_r (m·s²) from the probe analysis: enables the
    /// compensated identification. A negative value (a radius that shrinks with ω²) is read
    /// as a number: `--c-r-m-s2 -4e-8`.
    #[arg(long, requires = "c_r_sigma_m_s2", allow_hyphen_values = true)]
    c_r_m_s2: Option<f64>,
    /// Standard deviation of C_r (m·s²).
    #[arg(long, requires = "c_r_m_s2")]
    c_r_sigma_m_s2: Option<f64>,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// The rate units `--rate-unit` and `--output-unit` take (their configuration names).
const RATE_UNITS: [&str; 4] = ["deg_s", "rad_s", "rpm", "deg_h"];

/// The rate unit named `key` (one of [`RATE_UNITS`], which clap checked).
fn rate_unit(key: &str) -> RateUnit {
    [
        RateUnit::DegS,
        RateUnit::RadS,
        RateUnit::Rpm,
        RateUnit::DegH,
    ]
    .into_iter()
    .find(|u| u.key() == key)
    .unwrap_or(RateUnit::DegS)
}

impl Identify {
    /// The table's settings as a study's `calibration.table` with a `format` block holds
    /// them; the study's own conversion ([`PigaTableConfig::piga_format`]) turns them into
    /// the reader's format, so a table reads here as in the study.
    fn table_config(&self) -> PigaTableConfig {
        let column = |column: &str, unit: &str| Column {
            column: column.to_owned(),
            unit: rate_unit(unit),
        };
        PigaTableConfig {
            file: self.file.clone(),
            rate_column: "rate_deg_s".to_owned(),
            output_column: "output_rad_s".to_owned(),
            delimiter: ',',
            sigma_column: None,
            label_column: None,
            output_sigma_rad_s: None,
            format: Some(PigaTableFormat {
                delimiter: if matches!(self.delimiter, ' ' | '\t') {
                    Delimiter::Whitespace
                } else {
                    Delimiter::Char(self.delimiter)
                },
                decimal: if self.decimal == "comma" {
                    DecimalMark::Comma
                } else {
                    DecimalMark::Point
                },
                skip_lines: self.skip_lines,
                rate: column(&self.rate_column, &self.rate_unit),
                output: column(&self.output_column, &self.output_unit),
                sigma: self
                    .sigma_column
                    .as_deref()
                    .map(|c| column(c, &self.output_unit)),
                label: self.label_column.clone(),
            }),
        }
    }

    /// Reads the table as the study reads its `calibration.table`: rates in deg/s, outputs
    /// and σ in rad/s; a reader's hint names identify's options.
    fn read_table(&self) -> anyhow::Result<PigaTable> {
        let config = self.table_config();
        let layout = config.piga_format()?;
        let format = config.reader_format().map_err(|e| self.located_hint(e))?;
        let table = recording::load_table(&self.file, &format)
            .and_then(|t| PigaTable::from_table(t, &layout))
            .map_err(|e| self.located_hint(TableLayoutError::Recording(e)))?;
        Ok(table)
    }

    /// A reader's error with its hint in identify's options instead of a study's keys.
    fn located_hint(&self, e: TableLayoutError) -> anyhow::Error {
        use recording::RecordingError as E;
        let TableLayoutError::Recording(mut e) = e else {
            return anyhow::Error::new(e);
        };
        let option = |column: &str, rate: &'static str, output: &'static str| {
            if column.trim() == self.rate_column.trim() {
                rate
            } else {
                output
            }
        };
        let hint = e.take_hint().map(option_hint);
        let text = match (&e, hint) {
            (
                E::ColumnUnit {
                    path,
                    line,
                    column,
                    stated,
                    declared,
                    suggested,
                },
                _,
            ) => format!(
                "{}:{line}: column `{column}` states its unit as {stated:?} in the header, but \
                 is read in {declared} (hint: pass `{} {suggested}`)",
                path.display(),
                option(column, "--rate-unit", "--output-unit")
            ),
            (_, Some(hint)) => format!("{e} (hint: {hint})"),
            (E::MissingColumn { column, .. }, None) => {
                let flag = if column.trim() == self.output_column.trim() {
                    "--output-column"
                } else {
                    option(column, "--rate-column", "--sigma-column")
                };
                format!("{e} (hint: name the column as the header writes it with `{flag}`)")
            }
            (_, None) => e.to_string(),
        };
        anyhow::Error::new(TableError(text))
    }

    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let table = self.read_table()?;
        let rate_deg_s = table.rate_deg_s.clone();
        let output = table.output_rad_s.clone();
        let sigma = table.sigma_rad_s.clone();
        let rate_rad_s: Vec<f64> = rate_deg_s
            .iter()
            .map(|&d| units::deg_s_to_rad_s(d))
            .collect();
        let output_rad_s = &output;
        let context = || format!("identifying {}", self.file.display());
        // An error about a row of the design is an error about a line of the file.
        let located = |e: IdentifyError| -> anyhow::Error {
            match e {
                IdentifyError::NonFinite { row, column } if row < table.len() => {
                    let (column, value) = match column {
                        None => (self.output_column.clone(), output[row]),
                        Some(_) => (self.rate_column.clone(), rate_deg_s[row]),
                    };
                    anyhow::Error::new(RowOutOfRange {
                        path: self.file.clone(),
                        line: table.line_of_row(row),
                        column,
                        value,
                    })
                }
                other => anyhow::Error::new(other).context(context()),
            }
        };
        let from = match &self.from {
            Some(path) => Some(FromStudy::read(path, self.phase.as_deref())?),
            None => None,
        };
        let geometry = match &from {
            Some(f) => f.geometry,
            None => Geometry {
                radius_m: self
                    .radius_m
                    .context("--radius-m is required without --from")?,
                g_m_s2: self.g.context("--g is required without --from")?,
            },
        };
        let (c_r, k1) = match &from {
            Some(f) => (Some(f.c_r), f.k1_rad_s_g),
            None => (
                self.c_r_m_s2
                    .zip(self.c_r_sigma_m_s2)
                    .map(|(c_r_m_s2, c_r_sigma_m_s2)| CrEstimate {
                        c_r_m_s2,
                        c_r_sigma_m_s2,
                    }),
                self.k1,
            ),
        };
        let points = Points {
            rates_rad_s: &rate_rad_s,
            outputs_rad_s: output_rad_s,
            sigma_rad_s: sigma.as_deref(),
        };
        // A refused value is named by its line and column, as the study names it.
        let refused = |e: CalibrationError| -> anyhow::Error {
            match e {
                CalibrationError::Points { bad } => {
                    let lines = bad
                        .iter()
                        .map(|b| {
                            let (column, value) = match b.what {
                                calibration::PointValue::Rate => {
                                    (self.rate_column.as_str(), rate_deg_s[b.row])
                                }
                                calibration::PointValue::Output => {
                                    (self.output_column.as_str(), b.value)
                                }
                                calibration::PointValue::Sigma => {
                                    (self.sigma_column.as_deref().unwrap_or("σ"), b.value)
                                }
                            };
                            format!(
                                "{}:{}: column `{column}` = {}: {}",
                                self.file.display(),
                                table.line_of_row(b.row),
                                units::Compact(value),
                                pipeline::InvalidReason::of_point(b)
                            )
                        })
                        .collect();
                    anyhow::Error::new(RefusedRows { lines })
                }
                CalibrationError::Fit(e) => located(e),
                other => anyhow::Error::new(other).context(context()),
            }
        };
        let result = match c_r {
            Some(c_r) => {
                let compensation = Compensation {
                    c_r,
                    k1: k1.map_or(K1Source::Fitted, |k1_rad_s_g| K1Source::Given {
                        k1_rad_s_g,
                    }),
                };
                Identified::Compensated(Box::new(
                    calibration::calibrate_compensated(&points, geometry, &compensation)
                        .map_err(refused)?,
                ))
            }
            None => Identified::Measured(Box::new(
                calibration::calibrate(&points, geometry).map_err(refused)?,
            )),
        };
        let view = result.view()?;
        let k1_words = match (&from, k1) {
            (Some(f), _) => f.k1_words.clone(),
            (None, Some(_)) => "given with --k1".to_owned(),
            (None, None) => "implied by the fit (c₂·g/R); give --k1 to use another".to_owned(),
        };
        let g_words = match &from {
            Some(f) => format!("as the study used it ({})", f.results.display()),
            None => "given with --g".to_owned(),
        };
        let mut console = Console::stdout();
        if self.json {
            let value = to_json(&self.file, &view);
            writeln!(console, "{}", edge_io::to_json_pretty(&value)?)?;
        } else {
            print_report(
                &mut console,
                &self.file,
                &view,
                &Stated {
                    g: &g_words,
                    k1: &k1_words,
                    c_r: from
                        .as_ref()
                        .map_or("given with --c-r-m-s2", |f| f.c_r_words.as_str()),
                },
            )?;
        }
        Ok(())
    }
}

/// The calibration `identify` made: as measured, or compensated (eq. 19).
enum Identified {
    Measured(Box<Calibrated<Calibration>>),
    Compensated(Box<Calibrated<CompensatedCalibration>>),
}

/// What the output shows of a calibration, either kind.
struct View<'a> {
    cal: &'a Calibration,
    comp: Option<&'a CompensatedCalibration>,
    weighting: &'a Weighting,
    residual_sd_rad_s: f64,
    warnings: &'a [CalibrationWarning],
    /// The compensated k2's standard uncertainty as the study's measurement model gives it
    /// without Type B inputs (`calibration::without_type_b`), rad/(s·g²).
    k2_u_rad_s_g2: Option<f64>,
}

impl Identified {
    fn view(&self) -> anyhow::Result<View<'_>> {
        Ok(match self {
            Self::Measured(c) => View {
                cal: &c.calibration,
                comp: None,
                k2_u_rad_s_g2: None,
                weighting: &c.weighting,
                residual_sd_rad_s: c.residual_sd_rad_s,
                warnings: &c.warnings,
            },
            Self::Compensated(c) => View {
                cal: &c.calibration.uncompensated,
                comp: Some(&c.calibration),
                weighting: &c.weighting,
                residual_sd_rad_s: c.residual_sd_rad_s,
                warnings: &c.warnings,
                k2_u_rad_s_g2: Some(
                    calibration::without_type_b(c, None)?.outputs[calibration::output::K2]
                        .standard_uncertainty,
                ),
            },
        })
    }
}

/// Where g, k1 and C_r come from, in words.
struct Stated<'a> {
    g: &'a str,
    k1: &'a str,
    c_r: &'a str,
}

/// The coverage factor for 95 % with `dof` degrees of freedom (Student t; normal for
/// infinitely many).
fn k95(dof: uncertainty::Dof) -> f64 {
    uncertainty::coverage_factor(0.95, dof).unwrap_or(f64::NAN)
}

/// The degrees of freedom by the one formatter (`uncertainty::Dof`'s `Display`): "12", "∞".
fn dof_words(dof: uncertainty::Dof) -> String {
    dof.to_string()
}

fn print_report(
    console: &mut Console,
    path: &Path,
    v: &View<'_>,
    stated: &Stated<'_>,
) -> Result<(), ConsoleError> {
    let cal = v.cal;
    let fit = &cal.fit;
    writeln!(
        console,
        "PIGA calibration from {}: {} points at {} distinct rates; R = {} m, g = {} m/s² ({})",
        path.display(),
        fit.residuals.len(),
        cal.distinct_rates,
        units::Compact(cal.geometry.radius_m),
        units::Compact(cal.geometry.g_m_s2),
        stated.g
    )?;
    writeln!(
        console,
        "design [1, ω, ω², ω³, a², a³], a = R·ω²/g (eq. 18); condition number of the \
         column-scaled design {:.3e}; residual SD {:.4e} rad/s ({} dof); solver: {}",
        fit.condition_number, v.residual_sd_rad_s, fit.dof, fit.path
    )?;
    let w = v.weighting;
    match (w.birge_ratio, w.excess_u_rad_s) {
        (None, _) => writeln!(
            console,
            "unweighted: the coefficients' u come from the residuals"
        )?,
        (Some(b), None) if w.tau_not_found => writeln!(
            console,
            "weighted by the points' σ: Birge ratio √(χ²/ν) {b:.4} (dimensionless); no common \
             τ found, the covariance is scaled by the Birge ratio squared"
        )?,
        (Some(b), None) => writeln!(
            console,
            "weighted by the points' σ: Birge ratio √(χ²/ν) {b:.4} (dimensionless); the σ \
             taken as known"
        )?,
        (Some(b), Some(tau)) => writeln!(
            console,
            "weighted by the points' σ: Birge ratio √(χ²/ν) {b:.4} (dimensionless); a \
             variation τ = {tau:.4e} rad/s common to every point added to each σ \
             (Paule–Mandel)"
        )?,
    }
    for warning in &fit.warnings {
        writeln!(console, "warning: {warning}")?;
    }
    for warning in v.warnings {
        writeln!(console, "warning: {warning}")?;
    }
    let k = k95(w.group_dof);
    let s = &fit.std_errors;
    let rows = [
        ("1: k0 + k1·Δφ_ys", "rad/s", cal.bias_rad_s, s[0]),
        ("ω (nuisance)", "", cal.omega_coeff, s[1]),
        ("ω²", "s", cal.omega2_coeff_s, s[2]),
        ("ω³ (nuisance)", "s²", cal.omega3_coeff_s2, s[3]),
        (
            "a²: apparent k2 = k2 + Δk2",
            "rad/(s·g²)",
            cal.k2_apparent_rad_s_g2,
            s[4],
        ),
        ("a³: k3", "rad/(s·g³)", cal.k3_rad_s_g3, s[5]),
        (
            "k1 implied by ω² (c₂·g/R)",
            "rad/(s·g)",
            cal.k1_implied_rad_s_g,
            cal.k1_implied_sigma_rad_s_g,
        ),
    ];
    writeln!(
        console,
        "{:<30} {:>16} {:>12} {:>12}  unit",
        "coefficient", "value", "u", "U95"
    )?;
    for (label, unit, value, sigma) in rows {
        writeln!(
            console,
            "{label:<30} {value:>16.8e} {sigma:>12.3e} {:>12.3e}  {unit}",
            k * sigma
        )?;
    }
    writeln!(
        console,
        "U95 = k·u with k = {k:.3} (Student t, {} degrees of freedom of the fit's \
         coefficients, as the study takes them); the fit's uncertainty only: the study adds \
         the Type B inputs",
        dof_words(w.group_dof)
    )?;
    if let Some(c) = v.comp {
        writeln!(
            console,
            "compensation: C_r = {:.5e} ± {:.3e} m·s² ({}), k1 = {:.8} rad/(s·g) ({})",
            c.compensation.c_r.c_r_m_s2,
            c.compensation.c_r.c_r_sigma_m_s2,
            stated.c_r,
            c.k1_used_rad_s_g,
            stated.k1
        )?;
        writeln!(
            console,
            "{:<30} {:>16.8e} {:>12.3e} {:>12.3e}  rad/(s·g²)",
            "Δk2 = k1·C_r·g/R² (eq. 19)",
            c.delta_k2.delta_k2_rad_s_g2,
            c.delta_k2.sigma_rad_s_g2,
            k95(uncertainty::Dof::Infinite) * c.delta_k2.sigma_rad_s_g2
        )?;
        // The compensated k2's degrees of freedom: the fit's part has the fit's, C_r's part
        // is taken as known (Welch–Satterthwaite).
        let (u_fit, u_c) = (
            c.compensated.k2_apparent_sigma_rad_s_g2,
            c.k2_sigma_from_c_r_rad_s_g2,
        );
        let u_k2 = v.k2_u_rad_s_g2.unwrap_or(c.k2_sigma_rad_s_g2);
        let nu = match w.group_dof {
            uncertainty::Dof::Finite(dof) if u_fit > 0.0 => {
                uncertainty::Dof::Finite(u_k2.powi(4) / (u_fit.powi(4) / dof))
            }
            _ => uncertainty::Dof::Infinite,
        };
        writeln!(
            console,
            "{:<30} {:>16.8e} {:>12.3e} {:>12.3e}  rad/(s·g²)  (u from the fit {u_fit:.3e}, \
             from C_r {u_c:.3e}; ν_eff {})",
            "compensated k2",
            c.k2_rad_s_g2,
            u_k2,
            k95(nu) * u_k2,
            nu,
        )?;
    }
    Ok(())
}

fn to_json(path: &Path, v: &View<'_>) -> serde_json::Value {
    let cal = v.cal;
    let fit = &cal.fit;
    let s = &fit.std_errors;
    let coefficient = |v: f64, sigma: f64| serde_json::json!({ "value": v, "sigma": sigma });
    let covariance: Vec<Vec<f64>> = (0..fit.covariance.nrows())
        .map(|i| fit.covariance.row(i).iter().copied().collect())
        .collect();
    let compensated = v.comp.map(|c| {
        serde_json::json!({
            "c_r_m_s2": c.compensation.c_r.c_r_m_s2,
            "c_r_sigma_m_s2": c.compensation.c_r.c_r_sigma_m_s2,
            "k1_source": c.compensation.k1,
            "k1_used_rad_s_g": c.k1_used_rad_s_g,
            "delta_k2_rad_s_g2": c.delta_k2.delta_k2_rad_s_g2,
            "delta_k2_sigma_rad_s_g2": c.delta_k2.sigma_rad_s_g2,
            "k2_rad_s_g2": c.k2_rad_s_g2,
            "k2_sigma_rad_s_g2": v.k2_u_rad_s_g2.unwrap_or(c.k2_sigma_rad_s_g2),
            "k2_sigma_fit_rad_s_g2": c.compensated.k2_apparent_sigma_rad_s_g2,
            "k2_sigma_from_c_r_rad_s_g2": c.k2_sigma_from_c_r_rad_s_g2,
        })
    });
    let w = v.weighting;
    serde_json::json!({
        "file": path.display().to_string(),
        "points": fit.residuals.len(),
        "distinct_rates": cal.distinct_rates,
        "radius_m": cal.geometry.radius_m,
        "g_m_s2": cal.geometry.g_m_s2,
        "columns": ["1", "omega", "omega^2", "omega^3", "a^2", "a^3"],
        "coefficients": {
            "bias_rad_s": coefficient(cal.bias_rad_s, s[0]),
            "omega": coefficient(cal.omega_coeff, s[1]),
            "omega2_s": coefficient(cal.omega2_coeff_s, s[2]),
            "omega3_s2": coefficient(cal.omega3_coeff_s2, s[3]),
            "k2_apparent_rad_s_g2": coefficient(cal.k2_apparent_rad_s_g2, s[4]),
            "k3_rad_s_g3": coefficient(cal.k3_rad_s_g3, s[5]),
        },
        "k1_implied_rad_s_g": coefficient(cal.k1_implied_rad_s_g, cal.k1_implied_sigma_rad_s_g),
        "covariance": covariance,
        "weighted": w.birge_ratio.is_some(),
        "birge_ratio": w.birge_ratio,
        "excess_u_rad_s": w.excess_u_rad_s,
        "sigma_used_rad_s": w.sigma_used,
        "coefficients_dof": match w.group_dof {
            uncertainty::Dof::Finite(_) => serde_json::json!(w.noise_dof),
            uncertainty::Dof::Infinite => serde_json::json!("infinite"),
        },
        "residuals_rad_s": cal.residuals_rad_s,
        "residual_sd_rad_s": v.residual_sd_rad_s,
        "dof": fit.dof,
        "condition_number": fit.condition_number,
        "solver_path": fit.path,
        "solver_warnings": fit.warnings,
        "warnings": v.warnings.iter().map(|w| serde_json::json!({
            "code": w.code(),
            "message": w.to_string(),
        })).collect::<Vec<_>>(),
        "compensated": compensated,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file in its own scratch folder, removed on drop.
    struct TempFile(PathBuf, #[allow(dead_code)] test_support::Scratch);

    impl TempFile {
        fn new(name: &str, contents: &str) -> Self {
            let dir = test_support::Scratch::new(&format!("cli-identify-unit-{name}"));
            let path = dir.path().join(format!("{name}.csv"));
            std::fs::write(&path, contents).unwrap();
            Self(path, dir)
        }
    }

    #[test]
    fn table_errors_name_file_and_line() {
        let f = TempFile::new("bad-number", "rate_deg_s,output_rad_s\n10,0.5\n20,abc\n");
        let args = Identify {
            file: f.0.clone(),
            rate_column: "rate_deg_s".into(),
            rate_unit: "deg_s".into(),
            output_column: "output_rad_s".into(),
            output_unit: "rad_s".into(),
            delimiter: ',',
            sigma_column: None,
            label_column: None,
            decimal: "point".into(),
            skip_lines: 0,
            radius_m: Some(2.5),
            g: Some(9.8),
            from: None,
            phase: None,
            k1: None,
            c_r_m_s2: None,
            c_r_sigma_m_s2: None,
            json: true,
        };
        let e = format!("{:#}", args.run().unwrap_err());
        let at = format!("{}:3: column `output_rad_s`", f.0.display());
        assert!(e.contains(&at), "{e}");
    }

    #[test]
    fn identifies_and_compensates_a_synthetic_table() {
        let (r, g, k1, k2, c_r) = (2.5, 9.8, 0.56, 5e-6, 1.6e-6);
        let mut text = String::from("rate_deg_s,output_rad_s\n");
        for d in [10.0, 30.0, 60.0, 80.0, 110.0, 140.0, 160.0, 200.0_f64] {
            let w = d.to_radians();
            let a = r * w * w / g;
            let y = 1e-5 + k1 * a + k2 * a * a + k1 * c_r * w.powi(4) / g;
            text.push_str(&format!("{d},{y:.17e}\n"));
        }
        let f = TempFile::new("synthetic", &text);
        let args = Identify {
            file: f.0.clone(),
            rate_column: "rate_deg_s".into(),
            rate_unit: "deg_s".into(),
            output_column: "output_rad_s".into(),
            output_unit: "rad_s".into(),
            delimiter: ',',
            sigma_column: None,
            label_column: None,
            decimal: "point".into(),
            skip_lines: 0,
            radius_m: Some(r),
            g: Some(g),
            from: None,
            phase: None,
            k1: None,
            c_r_m_s2: Some(c_r),
            c_r_sigma_m_s2: Some(1e-8),
            json: true,
        };
        let table = args.read_table().unwrap();
        let rates: Vec<f64> = table.rate_deg_s.iter().map(|d| d.to_radians()).collect();
        let outputs = table.output_rad_s.clone();
        let comp = Compensation {
            c_r: CrEstimate {
                c_r_m_s2: c_r,
                c_r_sigma_m_s2: 1e-8,
            },
            k1: K1Source::Fitted,
        };
        let geometry = Geometry {
            radius_m: r,
            g_m_s2: g,
        };
        let c = calibration::calibrate_compensated(
            &Points {
                rates_rad_s: &rates,
                outputs_rad_s: &outputs,
                sigma_rad_s: None,
            },
            geometry,
            &comp,
        )
        .unwrap();
        assert!(
            (c.calibration.k2_rad_s_g2 - k2).abs() < 1e-3 * k2,
            "{}",
            c.calibration.k2_rad_s_g2
        );
        let json = to_json(
            &args.file,
            &Identified::Compensated(Box::new(c)).view().unwrap(),
        );
        assert_eq!(json["distinct_rates"], 8);
        assert!(json["compensated"]["k2_rad_s_g2"].as_f64().is_some());
        args.run().unwrap();
    }
}

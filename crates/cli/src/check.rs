//! `centrifuge-cal check CONFIG`: a dry run. It validates the whole configuration, reads
//! every file it names, prints what the study will do, and lists every problem found,
//! grouped (one message for the same fault in several files), each with its hint.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use accel_model::{AccelKind, MountingPreset, Term};
use anyhow::bail;
use edge_io::visible;
use pipeline::{
    CalibrationConfig, K1Config, MountingsConfig, OrientationConfig, OrientationName,
    PigaRecordingSet, PigaTableConfig, Points, StudyConfig, TwoOrientationConfig,
    UncertaintyConfig,
};
use recording::{AngleSource, AngleUnit, DecimalMark, Delimiter, GapUnit, RecordingFormat};

use crate::console::Console;
use crate::init::PLACEHOLDER;
use crate::init::config::{placeholders, split_comment};
use crate::problems;

/// Check a study configuration without running the study.
#[derive(Debug, clap::Args)]
pub(crate) struct Check {
    /// The study configuration (RON).
    config: PathBuf,
}

/// The configuration's text with each placeholder replaced by a value of the right type, so
/// that the rest can be checked; the values chosen never reach a result.
fn stand_ins(text: &str) -> String {
    text.lines()
        .map(|line| {
            let (code, comment) = split_comment(line);
            if !code.contains(PLACEHOLDER) {
                return line.to_owned();
            }
            let value = if code.contains(&format!("\"{PLACEHOLDER}\"")) {
                PLACEHOLDER
            } else if code.contains("probe_direction") {
                "against_o1_x1"
            } else if code.contains("sensitivity") {
                "1.0"
            } else if code.contains("time:") {
                "s"
            } else if code.contains("gap:") {
                "um"
            } else if code.contains("per_rev") {
                "1"
            } else if code.contains("unit:") {
                "deg"
            } else if code.contains("compensate_with") {
                "\"\""
            } else {
                "1.0"
            };
            format!("{}{comment}", code.replace(PLACEHOLDER, value))
        })
        .collect::<Vec<_>>()
        .join("\n")
}

impl Check {
    pub(crate) fn run(&self) -> anyhow::Result<()> {
        let path = &self.config;
        let text = edge_io::read_text_capped(path, pipeline::MAX_STUDY_BYTES)?;
        let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
        let left = placeholders(text);
        let mut found: Vec<String> = left
            .iter()
            .map(|l| match &l.ask {
                Some((field, question)) => format!(
                    "{}:{}: `{field}` is not filled in ({PLACEHOLDER}): {question}",
                    path.display(),
                    l.line
                ),
                None => format!(
                    "{}:{}: `{}` is not filled in (written by init as {PLACEHOLDER}: \
                     the files could not tell it)",
                    path.display(),
                    l.line,
                    l.code
                ),
            })
            .collect();
        // A placeholder's stand-in value may itself be refused (an unknown signatory): that
        // error says nothing the placeholder's line does not.
        let placeholder_fields: Vec<String> = left
            .iter()
            .filter_map(|l| l.ask.as_ref().map(|(field, _)| format!("`{field}`")))
            .collect();
        let about_placeholder = |problem: &String| {
            placeholder_fields
                .iter()
                .any(|f| problem.contains(f.as_str()))
        };
        let direction_unfilled = found.iter().any(|p| p.contains("probe_direction"));
        let filled = stand_ins(text);
        let mut console = Console::stdout();
        let mut warnings = Vec::new();
        match pipeline::StudyConfig::from_ron(&filled, path) {
            Err(e) => found.extend(problems::each(&e)),
            Ok(config) => {
                let profile = match pipeline::load_profile(&config, path) {
                    Ok(p) => p,
                    Err(e) => {
                        found.extend(problems::each(&e));
                        None
                    }
                };
                let mut shown = config.clone();
                // a section under its former name is described as the study runs it (both
                // names at once are a problem the reading below lists)
                let _ = shown.take_deprecated_keys(path);
                let used = profile
                    .as_ref()
                    .and_then(|p| p.apply_partly(&mut shown, path));
                let plan = describe(&shown, path, used.as_ref(), direction_unfilled);
                console.write_str(&plan)?;
                if profile.is_some() || config.profile.is_none() {
                    let files = count_files(&config);
                    let bar =
                        crate::progress::spinner(format!("reading and checking {files} files"));
                    match pipeline::Inputs::with_profile(
                        config,
                        profile.as_ref(),
                        path,
                        &pipeline::Files,
                    ) {
                        Ok(inputs) => warnings = inputs.warnings(),
                        Err(e) => found.extend(
                            problems::each(&e)
                                .into_iter()
                                .filter(|p| !about_placeholder(p)),
                        ),
                    }
                    bar.finish_and_clear();
                }
            }
        }
        let warnings: Vec<_> = warnings
            .into_iter()
            .filter(|w| !about_placeholder(&format!("`{}`", w.location)))
            .filter(|w| left.is_empty() || w.code != pipeline::WarningCode::CalibrationDueUnchecked)
            .collect();
        if !warnings.is_empty() {
            writeln!(console, "\nwarnings:")?;
            for w in &warnings {
                writeln!(console, "  {}: {}", w.code.title(), w.message)?;
            }
        }
        if found.is_empty() {
            writeln!(
                console,
                "\nno problem found: every file named reads with its format"
            )?;
            return Ok(());
        }
        let groups = problems::group(&found);
        writeln!(
            console,
            "\n{} problem{} ({} distinct):",
            found.len(),
            if found.len() == 1 { "" } else { "s" },
            groups.len()
        )?;
        console.write_str(&problems::render(&found))?;
        bail!(
            "{}: {} problem{} found (listed above)",
            path.display(),
            found.len(),
            if found.len() == 1 { "" } else { "s" }
        )
    }
}

/// The number of data files a configuration names: every table and recording of every
/// section (each section named, so that a new one is counted or said not to hold files).
fn count_files(config: &StudyConfig) -> usize {
    let StudyConfig {
        name: _,
        profile: _,
        centrifuge: _,
        probe: _,
        radius_m: _,
        g_m_s2: _,
        k1_rad_s_g: _,
        lever: _,
        radius_model: _,
        phases,
        mechanism: _,
        calibration,
        uncertainty: _,
        balance: _,
        counterweight: _,
        certificate: _,
        two_orientation,
        mountings,
        symmetric_deprecated,
        units,
    } = config;
    let phases: usize = phases
        .iter()
        .map(|p| match &p.points {
            Points::Recordings(set) => set.files.len(),
            Points::FirstHarmonic(_) | Points::RadiusError(_) | Points::RadiusChange { .. } => 0,
        })
        .sum();
    let mountings: usize = mountings
        .iter()
        .flat_map(|m| &m.list)
        .map(|o| usize::from(o.table.is_some()))
        .sum();
    let units: usize = units
        .iter()
        .flatten()
        .map(|u| {
            let pipeline::UnitConfig {
                label: _,
                k1_rad_s_g: _,
                radius_m: _,
                calibration,
                two_orientation,
                certificate: _,
            } = u;
            calibration_files(calibration) + two_orientation.as_ref().map_or(0, orientation_files)
        })
        .sum();
    phases
        + calibration.as_ref().map_or(0, calibration_files)
        + two_orientation.as_ref().map_or(0, orientation_files)
        + symmetric_deprecated.as_ref().map_or(0, orientation_files)
        + mountings
        + units
}

/// The files of a PIGA data set: its table, its recordings.
fn data_files(table: Option<&PigaTableConfig>, recordings: Option<&PigaRecordingSet>) -> usize {
    usize::from(table.is_some()) + recordings.map_or(0, |r| r.files.len())
}

fn calibration_files(cal: &CalibrationConfig) -> usize {
    data_files(cal.table.as_ref(), cal.recordings.as_ref())
}

fn orientation_files(sym: &TwoOrientationConfig) -> usize {
    sym.orientations
        .iter()
        .map(|o| data_files(o.table.as_ref(), o.recordings.as_ref()))
        .sum()
}

/// Most rates of a phase `check` lists one by one.
const CHECK_RATES_SHOWN: usize = 40;

/// A number as written (one that is not finite as it is: `inf`, `NaN`), or `—` when absent.
fn num(v: Option<f64>) -> String {
    // Short in every range: `1e300`, not 301 digits (docs/RELIABILITY.md).
    v.map_or_else(|| "—".to_owned(), |x| units::Compact(x).to_string())
}

/// `n` things: `1 line`, `3 lines` (`one`: the singular, its plural with an `s`).
fn count(n: usize, one: &str) -> String {
    if n == 1 {
        format!("1 {one}")
    } else {
        format!("{n} {one}s")
    }
}

/// A path from the configuration, for the terminal.
fn file(path: &Path) -> String {
    visible(&path.display().to_string()).into_owned()
}

/// What the study will do, in words, from the configuration's own field names (with what
/// its lab profile gives filled in, `used` saying which; `direction_unfilled`: the probe
/// direction is still a placeholder).
fn describe(
    config: &StudyConfig,
    path: &Path,
    used: Option<&pipeline::ProfileResults>,
    direction_unfilled: bool,
) -> String {
    let mut s = String::new();
    // the name in quotes, written visibly (not Rust's `{:?}` escapes); the path as well
    let _ = writeln!(
        s,
        "study \"{}\" ({})",
        edge_io::visible(&config.name),
        edge_io::visible(&path.display().to_string())
    );
    if let Some(used) = used {
        profile(&mut s, used);
    }
    centrifuge_and_probe(&mut s, config, used, direction_unfilled);
    phases(&mut s, &config.phases);
    calibration(&mut s, config.calibration.as_ref());
    two_orientation(&mut s, config.two_orientation.as_ref());
    units(&mut s, config);
    mountings(&mut s, config.mountings.as_ref());
    type_b(&mut s, config.uncertainty.as_ref());
    for (given, words) in [
        (
            config.mechanism.is_some(),
            "the mechanism simulated with each phase's C_r",
        ),
        (config.balance.is_some(), "the balance advisor"),
        (
            config.counterweight.is_some(),
            "the counterweight of the published change",
        ),
    ] {
        if given {
            let _ = writeln!(s, "also: {words}");
        }
    }
    s
}

/// The lab profile the study uses and which values came from it.
fn profile(s: &mut String, used: &pipeline::ProfileResults) {
    let from = |source: pipeline::ValueSource| -> Vec<&str> {
        used.values
            .iter()
            .filter(|o| o.from == source)
            .map(|o| o.field.as_str())
            .collect()
    };
    let _ = writeln!(
        s,
        "lab profile: {}, centrifuge {}{}; from the profile: {}",
        visible(&used.file),
        visible(&used.centrifuge),
        used.probe
            .as_ref()
            .map_or_else(String::new, |p| format!(", probe {}", visible(p))),
        from(pipeline::ValueSource::Profile).join(", ")
    );
    let own = from(pipeline::ValueSource::Study);
    if !own.is_empty() {
        let _ = writeln!(
            s,
            "stated by the study over the profile: {}",
            own.join(", ")
        );
    }
}

/// The centrifuge, the probe's lever, its direction and the angle zero (saying what the lab
/// profile declared).
fn centrifuge_and_probe(
    s: &mut String,
    config: &StudyConfig,
    used: Option<&pipeline::ProfileResults>,
    direction_unfilled: bool,
) {
    let k1_words = if config.units.is_some() {
        "the study's k1 (the top summary's Δk2; each unit states its own below)"
    } else {
        "PIGA k1"
    };
    let _ = writeln!(
        s,
        "centrifuge: R = {} m, g = {} m/s², {k1_words} = {} rad/(s·g)",
        num(config.radius_m),
        num(config.g_m_s2),
        num(Some(config.k1_rad_s_g))
    );
    let lever = &config.lever;
    let _ = writeln!(
        s,
        "probe: {} mm above the tilt pivot, {} mm below the PIGA's plane",
        num(lever.pivot_to_probe_mm),
        num(lever.probe_to_piga_mm)
    );
    let direction = if direction_unfilled {
        format!(
            "not filled in: `against_o1_x1` if {}; `along_o1_x1` if {}",
            pipeline::ProbeDirectionName::AgainstO1X1.words(),
            pipeline::ProbeDirectionName::AlongO1X1.words()
        )
    } else {
        match lever.probe_direction {
            Some(d) => d.words().to_owned(),
            None => format!(
                "not stated, so the paper's set-up is taken: {}",
                pipeline::ProbeDirectionName::AgainstO1X1.words()
            ),
        }
    };
    // a declaration the lab profile made says so, with the profile's field
    let from_profile = |field: &str| {
        used.and_then(|u| u.values.iter().find(|o| o.field == field))
            .filter(|o| o.from == pipeline::ValueSource::Profile)
            .map_or_else(String::new, |o| {
                let at = o
                    .profile_field
                    .rsplit_once(": ")
                    .map_or(o.profile_field.as_str(), |(_, at)| at);
                format!("; stated by the lab profile (`{}`)", visible(at))
            })
    };
    let _ = writeln!(
        s,
        "  direction (`lever.probe_direction`): {direction}{}",
        from_profile("lever.probe_direction")
    );
    let angle_zero = pipeline::AngleZero {
        angle_zero_deg: lever.angle_zero_deg.unwrap_or(0.0),
        stated: lever.angle_zero_deg.is_some(),
        // a recordings phase whose format names an encoder or an index pulse (the default
        // format's encoder column counts: most files have it)
        measured_angles: config.phases.iter().any(|p| match &p.points {
            Points::Recordings(set) => match set.format.angle {
                AngleSource::Encoder { .. } | AngleSource::IndexPulse { .. } => true,
                AngleSource::Rate { .. } => false,
            },
            Points::FirstHarmonic(_) | Points::RadiusError(_) | Points::RadiusChange { .. } => {
                false
            }
        }),
    };
    let _ = writeln!(
        s,
        "  angle zero: {}{}",
        angle_zero.words(),
        from_profile("lever.angle_zero_deg")
    );
}

/// Each probe phase: its data and how it is fitted.
fn phases(s: &mut String, phases: &[pipeline::PhaseConfig]) {
    for phase in phases {
        let line = match &phase.points {
            Points::Recordings(set) => recordings_words(set),
            Points::FirstHarmonic(points) => format!(
                "{} given (taken as fitted against the angle zero: `lever.angle_zero_deg` moves \
                 recorded angles only)",
                count(points.len(), "first-harmonic coefficient")
            ),
            Points::RadiusError(points) => {
                format!("{} given", count(points.len(), "radius error"))
            }
            Points::RadiusChange { .. } => "one published change of radius error".to_owned(),
        };
        let _ = writeln!(
            s,
            "phase {}: {line}; C_r and Δk2 from the radius-error fit",
            visible(&phase.name)
        );
    }
}

/// A phase's probe recordings: their rates, format and per-revolution fit.
fn recordings_words(set: &pipeline::RecordingSet) -> String {
    let rates: Vec<f64> = set.files.iter().map(|f| f.rate_deg_s).collect();
    // Every rate of a phase a lab measures (a few dozen at most); a longer list (issue 32:
    // 10⁵ rates made one 257 kB line) summarised as the first few, the last and the count.
    let rates = if rates.len() <= CHECK_RATES_SHOWN {
        rates
            .iter()
            .map(|r| units::Compact(*r).to_string())
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        let series = units::CompactSeries(&rates).to_string();
        series
            .strip_prefix('[')
            .unwrap_or(&series)
            .replacen(']', "", 1)
    };
    let recordings = if rates.is_empty() {
        "no probe recordings".to_owned()
    } else {
        format!(
            "{} at {rates} deg/s",
            count(set.files.len(), "probe recording")
        )
    };
    format!(
        "{recordings}, read as {}; fitted per revolution (order {}, drift {})",
        format_words(&set.format),
        num(Some(set.fit.order as f64)),
        if set.fit.drift {
            "fitted"
        } else {
            "not fitted"
        }
    )
}

/// The calibration: its data, the compensation and k1.
fn calibration(s: &mut String, cal: Option<&CalibrationConfig>) {
    if let Some(cal) = cal {
        let _ = writeln!(s, "calibration: {}", calibration_words(cal));
    }
}

/// The two orientations: each data set and what C is compared with.
fn two_orientation(s: &mut String, sym: Option<&TwoOrientationConfig>) {
    if let Some(sym) = sym {
        let _ = writeln!(s, "two orientations: {}", two_orientation_words(sym));
    }
}

/// The units calibrated from the study's probe phases, each with its k1, radius, calibration
/// and certificate.
fn units(s: &mut String, config: &StudyConfig) {
    let Some(units) = &config.units else {
        return;
    };
    let _ = writeln!(
        s,
        "{} unit{} calibrated from these probe phases, measured once; each unit's results, \
         report and certificate in units/LABEL/ of the output folder, their summary in it:",
        units.len(),
        if units.len() == 1 { "" } else { "s" }
    );
    for u in units {
        let radius = match u.radius_m {
            Some(r) => format!("R = {} m (its own)", num(Some(r))),
            None => format!("R = {} m (the study's)", num(config.radius_m)),
        };
        let _ = writeln!(
            s,
            "  unit {}: k1 = {} rad/(s·g), {radius}, so its own Δk2 = k1·C_r·g/R²",
            visible(&u.label),
            num(Some(u.k1_rad_s_g))
        );
        let _ = writeln!(s, "    calibration: {}", calibration_words(&u.calibration));
        if let Some(sym) = &u.two_orientation {
            let _ = writeln!(s, "    two orientations: {}", two_orientation_words(sym));
        }
        match &u.certificate {
            Some(c) => {
                let _ = writeln!(
                    s,
                    "    certificate {} for {} {} (serial {}), customer {}",
                    visible(&c.id),
                    visible(&c.item.manufacturer),
                    visible(&c.item.model),
                    visible(&c.item.serial),
                    visible(&c.customer.name)
                );
            }
            None => {
                let _ = writeln!(s, "    no certificate (no `certificate` section)");
            }
        }
    }
}

/// A PIGA data set in words: its table, or how many raw output recordings (`absent`: the
/// words for neither).
fn data_words(
    table: Option<&PigaTableConfig>,
    recordings: Option<&PigaRecordingSet>,
    absent: &str,
) -> String {
    match (table, recordings) {
        (Some(table), _) => format!("the PIGA table {}", file(&table.file)),
        (None, Some(recordings)) => count(recordings.files.len(), "raw PIGA output recording"),
        (None, None) => absent.to_owned(),
    }
}

/// A calibration section in words (`check`).
fn calibration_words(cal: &CalibrationConfig) -> String {
    let data = data_words(
        cal.table.as_ref(),
        cal.recordings.as_ref(),
        "no PIGA data (neither `table` nor `recordings`)",
    );
    let k1 = match cal.k1 {
        K1Config::Fitted => "k1 fitted from the ω² coefficient".to_owned(),
        K1Config::Given { k1_rad_s_g, .. } => {
            format!("k1 given: {} rad/(s·g)", num(Some(k1_rad_s_g)))
        }
    };
    format!(
        "eq. 18 fitted to {data}, compensated with phase {}'s C_r; {k1}; GUM and Monte Carlo \
         uncertainty",
        visible(&cal.compensate_with)
    )
}

/// A two-orientation section in words (`check`).
fn two_orientation_words(sym: &TwoOrientationConfig) -> String {
    let sets: Vec<String> = sym.orientations.iter().map(orientation_words).collect();
    let compare = match &sym.compare_with {
        Some(phase) => format!("phase {}'s C_r", visible(phase)),
        None => "the compensating (or first) phase's C_r".to_owned(),
    };
    format!(
        "eq. 23 fitted jointly to {}; k2 and the radius growth C from the PIGA alone, C \
         compared with {compare}; GUM and Monte Carlo uncertainty",
        sets.join(" and ")
    )
}

/// One orientation's data set in words.
fn orientation_words(o: &OrientationConfig) -> String {
    let which = o
        .orientation
        .map_or("orientation not declared", |n: OrientationName| {
            n.orientation().label()
        });
    let data = data_words(o.table.as_ref(), o.recordings.as_ref(), "no data");
    format!("{which} at {} from {data}", radius_words(o.radius_m))
}

/// A data set's radius, or that it is not declared.
fn radius_words(radius_m: Option<f64>) -> String {
    radius_m.map_or_else(
        || "radius not declared".to_owned(),
        |r| format!("R = {} m", num(Some(r))),
    )
}

/// The IEEE 836 model's mountings, terms and compensation.
fn mountings(s: &mut String, m: Option<&MountingsConfig>) {
    let Some(m) = m else {
        return;
    };
    let list: Vec<String> = m
        .list
        .iter()
        .map(|o| {
            // the lab's label, else the preset's words (as the results name the mounting)
            let which = match (&o.label, &o.preset) {
                (Some(label), _) => visible(label).into_owned(),
                (None, Some(tag)) => MountingPreset::from_tag(tag.trim()).map_or_else(
                    || format!("the preset “{}”", visible(tag)),
                    |p| p.label().to_owned(),
                ),
                (None, None) => "mounting by angles".to_owned(),
            };
            let table = o
                .table
                .as_ref()
                .map_or_else(|| "no table".to_owned(), |t| file(&t.file));
            format!("{which} at {} from {table}", radius_words(o.radius_m))
        })
        .collect();
    let compensation = match (m.compensate, &m.compensate_with) {
        (false, _) => "the probe's C_r not compensated".to_owned(),
        (true, Some(phase)) => format!(
            "phase {}'s C_r compensated along each mounting's axes",
            visible(phase)
        ),
        (true, None) => {
            "the compensating (or first) phase's C_r compensated along each mounting's axes"
                .to_owned()
        }
    };
    // k0 and k1 always, then the chosen terms by their symbols (a tag no term has as written)
    let terms: Vec<String> = [Term::K0.symbol().to_owned(), Term::K1.symbol().to_owned()]
        .into_iter()
        .chain(m.terms.iter().map(|tag| {
            Term::from_tag(tag.trim())
                .map_or_else(|| visible(tag).into_owned(), |t| t.symbol().to_owned())
        }))
        .collect();
    let kind = match m.kind {
        AccelKind::Piga => m.kind.words().to_owned(),
        AccelKind::Pendulous { unit } => {
            format!("{} with its output in {}", m.kind.words(), unit.symbol())
        }
    };
    let _ = writeln!(
        s,
        "mountings: the IEEE 836 model ({}) of a {kind}, fitted jointly to {}; {compensation}; \
         the mountings separate every chosen term (checked before the run)",
        terms.join(", "),
        list.join("; ")
    );
}

/// The Type B inputs, or that there are none.
fn type_b(s: &mut String, u: Option<&UncertaintyConfig>) {
    match u {
        Some(u) => {
            let _ = writeln!(
                s,
                "Type B inputs: u(R) {} m, u(g) {} m/s² ({}), rate {} (relative), pivot-to-probe \
                 {} mm, probe-to-PIGA {} mm, probe gain {} (relative)",
                num(u.radius_u_m),
                num(u.g_u_m_s2),
                visible(&u.g_source),
                num(u.rate_u_relative),
                num(u.pivot_to_probe_u_mm),
                num(u.probe_to_piga_u_mm),
                num(u.probe_gain_u_relative)
            );
        }
        None => {
            let _ = writeln!(
                s,
                "Type B inputs: none given (the budget takes them as zero and says so)"
            );
        }
    }
}

/// A recording format in words.
fn format_words(f: &RecordingFormat) -> String {
    let mut parts = vec![match f.delimiter {
        Delimiter::Char('\t') => "tab-separated".to_owned(),
        Delimiter::Char(d) => format!("`{}`-separated", visible(&d.to_string())),
        Delimiter::Whitespace => "blank-separated (runs of spaces and tabs)".to_owned(),
    }];
    match f.decimal {
        DecimalMark::Comma => parts.push("decimal comma".to_owned()),
        DecimalMark::Point => {}
    }
    if f.skip_lines > 0 {
        parts.push(format!("{} skipped", count(f.skip_lines, "line")));
    }
    parts.push(format!(
        "time `{}` in {}",
        visible(&f.time.column),
        f.time.unit.symbol()
    ));
    let gap_unit = match f.gap.unit {
        GapUnit::Nm | GapUnit::Um | GapUnit::Mm | GapUnit::M => {
            f.gap.unit.length_unit().symbol().to_owned()
        }
        GapUnit::Volts {
            sensitivity,
            sensitivity_unit,
            u_sensitivity,
        } => format!(
            "{}, converted with the probe's sensitivity {} {} ± {} (k = 1)",
            f.gap.unit,
            units::Compact(sensitivity),
            sensitivity_unit.symbol(),
            units::Compact(u_sensitivity)
        ),
    };
    parts.push(format!("gap `{}` in {gap_unit}", visible(&f.gap.column)));
    parts.push(match &f.angle {
        AngleSource::Encoder {
            column,
            unit,
            optional,
        } => format!(
            "angle from the encoder `{}` in {}{}",
            visible(column),
            match unit {
                AngleUnit::Deg | AngleUnit::Rad => unit.symbol().to_owned(),
                AngleUnit::Counts { per_rev } => format!(
                    "{}, {} per revolution",
                    unit.symbol(),
                    num(Some(*per_rev as f64))
                ),
            },
            if *optional {
                " when the file has it (else the declared rate, the first sample taken at 0° \
                 from the angle zero)"
            } else {
                ""
            }
        ),
        AngleSource::IndexPulse { column } => {
            format!("angle from the index pulse `{}`", visible(column))
        }
        AngleSource::Rate { start_angle_deg } => format!(
            "angle from the declared rate, the first sample taken at {}° from the angle zero \
             (nothing measures it; `lever.angle_zero_deg` does not move it)",
            num(Some(*start_angle_deg))
        ),
    });
    parts.join(", ")
}

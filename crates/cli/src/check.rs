//! `centrifuge-cal check CONFIG`: a dry run. It validates the whole configuration, reads
//! every file it names, prints what the study will do, and lists every problem found,
//! grouped (one message for the same fault in several files), each with its hint.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::bail;
use serde_json::Value;

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

/// The number of data files a configuration names.
fn count_files(config: &pipeline::StudyConfig) -> usize {
    let value = serde_json::to_value(config).unwrap_or(Value::Null);
    let mut n = 0;
    count(&value, &mut n);
    n
}

fn count(v: &Value, n: &mut usize) {
    match v {
        Value::Object(map) => {
            if map.contains_key("file") {
                *n += 1;
            }
            map.values().for_each(|v| count(v, n));
        }
        Value::Array(items) => items.iter().for_each(|v| count(v, n)),
        _ => {}
    }
}

/// Most rates of a phase `check` lists one by one.
const CHECK_RATES_SHOWN: usize = 40;

/// A number as written, or `—`.
fn num(v: Option<&Value>) -> String {
    // Short in every range: `1e300`, not 301 digits (docs/RELIABILITY.md).
    v.and_then(Value::as_f64)
        .map_or_else(|| "—".to_owned(), |x| units::Compact(x).to_string())
}

/// What the study will do, in words, from the configuration's own field names (with what
/// its lab profile gives filled in, `used` saying which; `direction_unfilled`: the probe
/// direction is still a placeholder).
fn describe(
    config: &pipeline::StudyConfig,
    path: &Path,
    used: Option<&pipeline::ProfileResults>,
    direction_unfilled: bool,
) -> String {
    let v = serde_json::to_value(config).unwrap_or(Value::Null);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "study {:?} ({})",
        v["name"].as_str().unwrap_or(""),
        path.display()
    );
    if let Some(used) = used {
        profile(&mut s, used);
    }
    centrifuge_and_probe(&mut s, config, &v, used, direction_unfilled);
    phases(&mut s, &v);
    calibration(&mut s, &v);
    two_orientation(&mut s, &v);
    units(&mut s, &v);
    mountings(&mut s, &v);
    type_b(&mut s, &v);
    for (key, words) in [
        ("mechanism", "the mechanism simulated with each phase's C_r"),
        ("balance", "the balance advisor"),
        ("counterweight", "the counterweight of the published change"),
    ] {
        if v.get(key).is_some_and(|x| !x.is_null()) {
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
        used.file,
        used.centrifuge,
        used.probe
            .as_ref()
            .map_or_else(String::new, |p| format!(", probe {p}")),
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
    config: &pipeline::StudyConfig,
    v: &Value,
    used: Option<&pipeline::ProfileResults>,
    direction_unfilled: bool,
) {
    let k1_words = if v.get("units").is_some_and(Value::is_array) {
        "the study's k1 (the top summary's Δk2; each unit states its own below)"
    } else {
        "PIGA k1"
    };
    let _ = writeln!(
        s,
        "centrifuge: R = {} m, g = {} m/s², {k1_words} = {} rad/(s·g)",
        num(v.get("radius_m")),
        num(v.get("g_m_s2")),
        num(v.get("k1_rad_s_g"))
    );
    let lever = &v["lever"];
    let _ = writeln!(
        s,
        "probe: {} mm above the tilt pivot, {} mm below the PIGA's plane",
        num(lever.get("pivot_to_probe_mm")),
        num(lever.get("probe_to_piga_mm"))
    );
    let direction = if direction_unfilled {
        format!(
            "not filled in: `against_o1_x1` if {}; `along_o1_x1` if {}",
            pipeline::ProbeDirectionName::AgainstO1X1.words(),
            pipeline::ProbeDirectionName::AlongO1X1.words()
        )
    } else {
        match config.lever.probe_direction {
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
                format!("; stated by the lab profile (`{at}`)")
            })
    };
    let _ = writeln!(
        s,
        "  direction (`lever.probe_direction`): {direction}{}",
        from_profile("lever.probe_direction")
    );
    let angle_zero = pipeline::AngleZero {
        angle_zero_deg: config.lever.angle_zero_deg.unwrap_or(0.0),
        stated: config.lever.angle_zero_deg.is_some(),
        // a recordings phase whose format names an encoder or an index pulse (the default
        // format's encoder column counts: most files have it)
        measured_angles: config.phases.iter().any(|p| match &p.points {
            pipeline::Points::Recordings(set) => {
                !matches!(set.format.angle, recording::AngleSource::Rate { .. })
            }
            _ => false,
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
fn phases(s: &mut String, v: &Value) {
    for phase in v["phases"].as_array().into_iter().flatten() {
        let name = phase["name"].as_str().unwrap_or("");
        let points = &phase["points"];
        let (kind, body) = match points.as_object().and_then(|m| m.iter().next()) {
            Some((k, b)) => (k.as_str(), b),
            None => ("", &Value::Null),
        };
        let line = match kind {
            "recordings" => {
                let files = body["files"].as_array().map_or(0, Vec::len);
                let rates: Vec<f64> = body["files"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .map(|f| {
                        f.get("rate_deg_s")
                            .and_then(Value::as_f64)
                            .unwrap_or(f64::NAN)
                    })
                    .collect();
                // Every rate of a phase a lab measures (a few dozen at most); a longer list
                // (issue 32: 10⁵ rates made one 257 kB line) summarised as the first few, the
                // last and the count.
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
                format!(
                    "{files} probe recordings at {} deg/s, read as {}; fitted per revolution \
                     (order {}, drift {})",
                    rates,
                    format_words(&body["format"]),
                    num(body["fit"].get("order")),
                    if body["fit"]["drift"].as_bool().unwrap_or(true) {
                        "fitted"
                    } else {
                        "not fitted"
                    }
                )
            }
            "first_harmonic" => format!(
                "{} first-harmonic coefficients given (taken as fitted against the angle zero: \
                 `lever.angle_zero_deg` moves recorded angles only)",
                body.as_array().map_or(0, Vec::len)
            ),
            "radius_error" => format!(
                "{} radius errors given",
                body.as_array().map_or(0, Vec::len)
            ),
            "radius_change" => "one published change of radius error".to_owned(),
            other => other.replace('_', " "),
        };
        let _ = writeln!(
            s,
            "phase {name}: {line}; C_r and Δk2 from the radius-error fit"
        );
    }
}

/// The calibration: its data, the compensation and k1.
fn calibration(s: &mut String, v: &Value) {
    if let Some(cal) = v.get("calibration").filter(|c| !c.is_null()) {
        let _ = writeln!(s, "calibration: {}", calibration_words(cal));
    }
}

/// The two orientations: each data set and what C is compared with.
fn two_orientation(s: &mut String, v: &Value) {
    if let Some(sym) = v.get("two_orientation").filter(|c| !c.is_null()) {
        let _ = writeln!(s, "two orientations: {}", two_orientation_words(sym));
    }
}

/// The units calibrated from the study's probe phases, each with its k1, radius, calibration
/// and certificate.
fn units(s: &mut String, v: &Value) {
    if let Some(units) = v.get("units").and_then(Value::as_array) {
        let _ = writeln!(
            s,
            "{} unit{} calibrated from these probe phases, measured once; each unit's results, \
             report and certificate in units/LABEL/ of the output folder, their summary in it:",
            units.len(),
            if units.len() == 1 { "" } else { "s" }
        );
        for u in units {
            let radius = match u.get("radius_m").filter(|r| !r.is_null()) {
                Some(r) => format!("R = {} m (its own)", num(Some(r))),
                None => format!("R = {} m (the study's)", num(v.get("radius_m"))),
            };
            let _ = writeln!(
                s,
                "  unit {}: k1 = {} rad/(s·g), {radius}, so its own Δk2 = k1·C_r·g/R²",
                u["label"].as_str().unwrap_or(""),
                num(u.get("k1_rad_s_g"))
            );
            if let Some(cal) = u.get("calibration").filter(|c| !c.is_null()) {
                let _ = writeln!(s, "    calibration: {}", calibration_words(cal));
            }
            if let Some(sym) = u.get("two_orientation").filter(|c| !c.is_null()) {
                let _ = writeln!(s, "    two orientations: {}", two_orientation_words(sym));
            }
            match u.get("certificate").filter(|c| !c.is_null()) {
                Some(c) => {
                    let item = &c["item"];
                    let _ = writeln!(
                        s,
                        "    certificate {} for {} {} (serial {}), customer {}",
                        edge_io::visible(c["id"].as_str().unwrap_or("")),
                        edge_io::visible(item["manufacturer"].as_str().unwrap_or("")),
                        edge_io::visible(item["model"].as_str().unwrap_or("")),
                        edge_io::visible(item["serial"].as_str().unwrap_or("")),
                        edge_io::visible(c["customer"]["name"].as_str().unwrap_or(""))
                    );
                }
                None => {
                    let _ = writeln!(s, "    no certificate (no `certificate` section)");
                }
            }
        }
    }
}

/// A calibration section in words (`check`).
fn calibration_words(cal: &Value) -> String {
    let data = if cal["table"].is_object() {
        format!(
            "the PIGA table {}",
            cal["table"]["file"].as_str().unwrap_or("")
        )
    } else {
        format!(
            "{} raw PIGA output recordings",
            cal["recordings"]["files"].as_array().map_or(0, Vec::len)
        )
    };
    let k1 = match &cal["k1"] {
        Value::String(s) if s == "fitted" => "k1 fitted from the ω² coefficient".to_owned(),
        Value::Object(m) if m.contains_key("given") => {
            format!("k1 given: {} rad/(s·g)", num(m["given"].get("k1_rad_s_g")))
        }
        other => format!("k1 {other}"),
    };
    format!(
        "eq. 18 fitted to {data}, compensated with phase {}'s C_r; {k1}; GUM and Monte Carlo \
         uncertainty",
        cal["compensate_with"].as_str().unwrap_or("")
    )
}

/// A two-orientation section in words (`check`).
fn two_orientation_words(sym: &Value) -> String {
    let sets: Vec<String> = sym["orientations"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|o| {
            let which = match o["orientation"].as_str() {
                Some("ia_in") => "IA in",
                Some("ia_out") => "IA out",
                _ => "orientation not declared",
            };
            let radius = o.get("radius_m").filter(|r| !r.is_null()).map_or_else(
                || "radius not declared".to_owned(),
                |r| format!("R = {} m", num(Some(r))),
            );
            let data = if o["table"].is_object() {
                format!(
                    "the PIGA table {}",
                    o["table"]["file"].as_str().unwrap_or("")
                )
            } else if o["recordings"].is_object() {
                format!(
                    "{} raw PIGA output recordings",
                    o["recordings"]["files"].as_array().map_or(0, Vec::len)
                )
            } else {
                "no data".to_owned()
            };
            format!("{which} at {radius} from {data}")
        })
        .collect();
    let compare = match sym["compare_with"].as_str() {
        Some(phase) => format!("phase {phase}'s C_r"),
        None => "the compensating (or first) phase's C_r".to_owned(),
    };
    format!(
        "eq. 23 fitted jointly to {}; k2 and the radius growth C from the PIGA alone, C \
         compared with {compare}; GUM and Monte Carlo uncertainty",
        sets.join(" and ")
    )
}

/// The IEEE 836 model's mountings, terms and compensation.
fn mountings(s: &mut String, v: &Value) {
    if let Some(m) = v.get("mountings").filter(|c| !c.is_null()) {
        let list: Vec<String> = m["list"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|o| {
                let which = o["label"]
                    .as_str()
                    .or_else(|| o["preset"].as_str())
                    .map_or_else(|| "mounting by angles".to_owned(), ToOwned::to_owned);
                let radius = o.get("radius_m").filter(|r| !r.is_null()).map_or_else(
                    || "radius not declared".to_owned(),
                    |r| format!("R = {} m", num(Some(r))),
                );
                format!(
                    "{which} at {radius} from {}",
                    o["table"]["file"].as_str().unwrap_or("no table")
                )
            })
            .collect();
        let terms: Vec<&str> = m["terms"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(Value::as_str)
            .collect();
        let compensation = if m["compensate"].as_bool() == Some(false) {
            "the probe's C_r not compensated".to_owned()
        } else {
            match m["compensate_with"].as_str() {
                Some(phase) => {
                    format!("phase {phase}'s C_r compensated along each mounting's axes")
                }
                None => {
                    "the compensating (or first) phase's C_r compensated along each mounting's axes"
                        .to_owned()
                }
            }
        };
        let _ = writeln!(
            s,
            "mountings: the IEEE 836 model (k0, k1, {}) fitted jointly to {}; {compensation}; \
             the mountings separate every chosen term (checked before the run)",
            terms.join(", "),
            list.join("; ")
        );
    }
}

/// The Type B inputs, or that there are none.
fn type_b(s: &mut String, v: &Value) {
    match v.get("uncertainty").filter(|u| !u.is_null()) {
        Some(u) => {
            let _ = writeln!(
                s,
                "Type B inputs: u(R) {} m, u(g) {} m/s² ({}), rate {} (relative), pivot-to-probe \
                 {} mm, probe-to-PIGA {} mm, probe gain {} (relative)",
                num(u.get("radius_u_m")),
                num(u.get("g_u_m_s2")),
                u["g_source"].as_str().unwrap_or(""),
                num(u.get("rate_u_relative")),
                num(u.get("pivot_to_probe_u_mm")),
                num(u.get("probe_to_piga_u_mm")),
                num(u.get("probe_gain_u_relative"))
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
fn format_words(f: &Value) -> String {
    let mut parts = Vec::new();
    match &f["delimiter"] {
        Value::String(d) if d == "\t" => parts.push("tab-separated".to_owned()),
        Value::String(d) => parts.push(format!("`{d}`-separated")),
        Value::Null => {}
        other => parts.push(format!("{} separated", other.as_str().unwrap_or("blank"))),
    }
    if f["decimal"].as_str() == Some("comma") {
        parts.push("decimal comma".to_owned());
    }
    if let Some(n) = f["skip_lines"].as_u64().filter(|n| *n > 0) {
        parts.push(format!("{n} lines skipped"));
    }
    for key in ["time", "gap"] {
        if let Some(c) = f.get(key).filter(|c| c.is_object()) {
            parts.push(format!(
                "{key} `{}` in {}",
                c["column"].as_str().unwrap_or(""),
                c["unit"].as_str().unwrap_or("?")
            ));
        }
    }
    let angle = &f["angle"];
    if let Some((kind, body)) = angle.as_object().and_then(|m| m.iter().next()) {
        parts.push(match kind.as_str() {
            "encoder" => format!(
                "angle from the encoder `{}` in {}{}",
                body["column"].as_str().unwrap_or(""),
                match &body["unit"] {
                    Value::String(u) => u.clone(),
                    Value::Object(m) => m.get("counts").map_or_else(String::new, |c| format!(
                        "counts, {} per revolution",
                        num(c.get("per_rev"))
                    )),
                    _ => String::new(),
                },
                if body["optional"].as_bool() == Some(true) {
                    " when the file has it (else the declared rate, the first sample taken at 0° \
                     from the angle zero)"
                } else {
                    ""
                }
            ),
            "index_pulse" => format!(
                "angle from the index pulse `{}`",
                body["column"].as_str().unwrap_or("")
            ),
            "rate" => format!(
                "angle from the declared rate, the first sample taken at {}° from the angle \
                 zero (nothing measures it; `lever.angle_zero_deg` does not move it)",
                num(body.get("start_angle_deg"))
            ),
            other => other.to_owned(),
        });
    }
    if parts.is_empty() {
        "the documented time_s,gap_um[,angle_deg]".to_owned()
    } else {
        parts.join(", ")
    }
}

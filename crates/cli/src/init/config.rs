//! The study configuration `init` writes: RON with every guess commented with its evidence
//! and a placeholder, with the one-line question that fills it, for everything neither the
//! files nor the lab profile can say. With a profile the whole study is written: the probe
//! phase(s), the calibration, the two-orientation section when the files hold both mountings,
//! and the certificate section with what the profile does not state.

use std::fmt::Write as _;
use std::path::Path;

use super::file::{Finding, PLACEHOLDER};
use super::orientation::Orientation;
use super::setting::{ASK, ask, comment_text, ron_string};

/// A set of files that becomes one phase (probe recordings) or a set of raw PIGA output
/// recordings.
#[derive(Debug)]
pub(crate) struct Group<'a> {
    /// The phase's name.
    pub(crate) name: String,
    /// The files, by rate.
    pub(crate) files: Vec<&'a Finding>,
}

/// The PIGA's data of the calibration or of one mounting.
#[derive(Debug)]
pub(crate) enum PigaData<'a> {
    /// A table of mean outputs.
    Table(&'a Finding),
    /// Raw output recordings, one per rate.
    Recordings(Group<'a>),
}

/// The lab profile the study names.
pub(crate) struct ProfilePlan {
    /// The profile's file (made relative to the study's folder when written).
    pub(crate) file: std::path::PathBuf,
    /// What it states.
    pub(crate) config: pipeline::ProfileConfig,
    /// The centrifuge used, by its index (`None`: to be asked).
    pub(crate) centrifuge: Option<usize>,
}

/// What the configuration is written from.
pub(crate) struct Plan<'a> {
    /// The study's name.
    pub(crate) name: String,
    /// Where the files were found (for the header comment).
    pub(crate) source: String,
    /// The probe phases.
    pub(crate) phases: Vec<Group<'a>>,
    /// The calibration's data (the IA-in data when both mountings were measured), if any.
    pub(crate) calibration: Option<PigaData<'a>>,
    /// Both mountings' data (IA in, IA out), when the files hold both.
    pub(crate) two_orientation: Option<(PigaData<'a>, PigaData<'a>)>,
    /// The lab profile, if one was given.
    pub(crate) profile: Option<ProfilePlan>,
    /// Both mountings' evidence in words (the files whose names say IA in and IA out), when
    /// the files hold both.
    pub(crate) mountings: Option<String>,
    /// Several units, one PIGA table each (a `units` list), when the files hold several
    /// tables that name no mounting.
    pub(crate) units: Vec<Unit<'a>>,
}

/// One unit of a several-unit study: its label (with where it comes from) and its data.
#[derive(Debug)]
pub(crate) struct Unit<'a> {
    /// Its label (its folder's name).
    pub(crate) label: String,
    /// Where the label comes from, in words.
    pub(crate) evidence: String,
    /// Its PIGA data.
    pub(crate) data: PigaData<'a>,
}

/// A file's path as the configuration names it: relative to the configuration's folder.
pub(crate) type RelativePath<'a> = dyn Fn(&Path) -> String + 'a;

/// A placeholder line: `{indent}{key}: {value},  // ASK field: question`.
fn placeholder(s: &mut String, indent: &str, key: &str, value: &str, field: &str, q: &str) {
    let _ = writeln!(s, "{indent}{key}: {value},  // {}", ask(field, q));
}

/// The configuration's text.
pub(crate) fn render(plan: &Plan<'_>, relative: &RelativePath<'_>) -> String {
    let mut s = String::new();
    let p = PLACEHOLDER;
    let header = format!(
        "Study configuration written by `centrifuge-cal init` from {}{}. Each value {} is \
         {p}, with the question that fills it beside it (`// {ASK} field: question`): answer \
         each before running `centrifuge-cal check` (which lists what is left) and \
         `centrifuge-cal study`, which both refuse a {p}. Each guess is commented with its \
         evidence: check them. Field by field: docs/CONFIGURATION.md{}; the lab formats: \
         docs/YOUR-DATA.md.",
        plan.source,
        plan.profile.as_ref().map_or_else(String::new, |pr| format!(
            " and the lab profile {}",
            relative(&pr.file)
        )),
        if plan.profile.is_some() {
            "that neither the files nor the profile tell"
        } else {
            "that the files cannot tell"
        },
        if plan.profile.is_some() {
            "; the profile: docs/PROFILE.md"
        } else {
            ""
        },
    );
    for line in wrap(&comment_text(&header), 88) {
        let _ = writeln!(s, "// {line}");
    }
    s.push_str("(\n");
    let _ = writeln!(s, "    name: {},", ron_string(&plan.name));
    match &plan.profile {
        Some(profile) => centrifuge_from_profile(&mut s, profile, relative),
        None => centrifuge_to_fill(&mut s),
    }
    s.push_str("    phases: [\n");
    for (i, phase) in plan.phases.iter().enumerate() {
        let first = phase.files[0];
        let _ = writeln!(
            s,
            "        (\n            name: {},\n            points: recordings((\n                \
             // {} probe recordings, one format:",
            ron_string(&phase.name),
            phase.files.len()
        );
        let at = format!("phases[{i}].points");
        format_block(&mut s, first, "                ", &format!("{at}.format"));
        s.push_str("                files: [\n");
        files(
            &mut s,
            &phase.files,
            relative,
            "                    ",
            &format!("{at}.files"),
        );
        s.push_str("                ],\n            )),\n        ),\n");
    }
    s.push_str("    ],\n");
    let compensate = plan
        .phases
        .first()
        .map_or_else(|| PLACEHOLDER.to_owned(), |g| ron_string(&g.name));
    if let Some(data) = &plan.calibration {
        s.push_str("    calibration: (\n");
        if plan.two_orientation.is_some() {
            s.push_str(
                "        // The probe method (eq. 18, compensated with the probe's C_r) on the IA-in data;\n        \
                 // the two-orientation section below checks it.\n",
            );
        }
        piga_data(&mut s, data, relative, "        ", "calibration");
        let _ = writeln!(
            s,
            "        compensate_with: {compensate},  // the phase whose C_r is removed (eq. 19)\n        \
             k1: fitted,  // k1 from the fit's ω² coefficient; or given(k1_rad_s_g: …, u_rad_s_g: …)\n    ),"
        );
    }
    if let Some((ia_in, ia_out)) = &plan.two_orientation {
        two_orientation(&mut s, plan, ia_in, ia_out, &compensate, relative);
    }
    if !plan.units.is_empty() {
        units(&mut s, &plan.units, &compensate, relative);
    }
    match &plan.profile {
        Some(_) if !plan.units.is_empty() => {
            s.push_str(
                "    // Each unit's certificate goes in its entry (`certificate: (id: …, customer: …,\n    \
                 // item: …, dates: …)`); the lab profile states the rest (docs/CONFIGURATION.md).\n",
            );
        }
        Some(profile) => certificate(&mut s, profile),
        None => uncertainty_to_fill(&mut s),
    }
    s.push_str(")\n");
    s
}

/// The centrifuge, g, k1 and the probe's geometry, every one to fill in (no profile).
fn centrifuge_to_fill(s: &mut String) {
    let p = PLACEHOLDER;
    s.push_str("    // The centrifuge and the PIGA (not in the files; a lab profile states them once:\n    // `init --profile lab.ron`, docs/PROFILE.md).\n");
    placeholder(
        s,
        "    ",
        "radius_m",
        p,
        "radius_m",
        "What is the static radius R, in m, from the PIGA's centre of mass to the spindle axis?",
    );
    placeholder(
        s,
        "    ",
        "g_m_s2",
        p,
        "g_m_s2",
        "What is the local gravity g at the centrifuge, in m/s² (from the gravity survey)?",
    );
    k1(s);
    s.push_str("    lever: (\n");
    placeholder(
        s,
        "        ",
        "pivot_to_probe_mm",
        p,
        "lever.pivot_to_probe_mm",
        "What is the height from the spindle's tilt pivot to the probe plane, in mm?",
    );
    placeholder(
        s,
        "        ",
        "probe_to_piga_mm",
        p,
        "lever.probe_to_piga_mm",
        "What is the height from the probe plane to the PIGA's centre-of-mass plane, in mm?",
    );
    let _ = writeln!(
        s,
        "        // Which way the probe's reading moves when the spindle moves towards the PIGA\n        \
         // (the arm's PIGA end pointing at the probe); it sets the sign of C_r:\n        \
         //   against_o1_x1 (or reading_falls_towards_piga): {};\n        \
         //   along_o1_x1 (or reading_rises_towards_piga): {}.",
        pipeline::ProbeDirectionName::AgainstO1X1.words(),
        pipeline::ProbeDirectionName::AlongO1X1.words(),
    );
    placeholder(
        s,
        "        ",
        "probe_direction",
        p,
        "lever.probe_direction",
        "Does the probe's reading fall (against_o1_x1) or rise (along_o1_x1) as the spindle moves towards the PIGA?",
    );
    angle_zero_comment(s, "        ", "// angle_zero_deg: 0.0,");
    s.push_str("    ),\n");
}

/// The angle zero, optional: a comment at `indent` saying what it is and what is taken
/// without it, and the field commented out (`example`).
fn angle_zero_comment(s: &mut String, indent: &str, example: &str) {
    for line in [
        "// The angle zero, deg: what the spindle encoder reads (an index pulse: how far the",
        "// spindle has turned past its rising edge) when the arm's PIGA end points at the",
        "// probe. Not stated, 0 is taken and `check`, the report and the certificate say so;",
        "// an encoder zero elsewhere changes C_r with no other sign (docs/YOUR-DATA.md).",
        example,
    ] {
        let _ = writeln!(s, "{indent}{line}");
    }
}

fn k1(s: &mut String) {
    placeholder(
        s,
        "    ",
        "k1_rad_s_g",
        PLACEHOLDER,
        "k1_rad_s_g",
        "What is the PIGA's nominal scale factor k1, in rad/(s·g), from its data sheet or last certificate?",
    );
}

/// The profile and the centrifuge it names, commented with what the profile states of it.
fn centrifuge_from_profile(s: &mut String, profile: &ProfilePlan, relative: &RelativePath<'_>) {
    let _ = writeln!(
        s,
        "    // The lab profile states the centrifuge's radius and probe geometry, g, the Type B\n    \
         // inputs with their traceability, and the certificate's laboratory, place, equipment,\n    \
         // procedure and signatory; a value written here overrides it (docs/PROFILE.md).\n    \
         profile: {},",
        ron_string(&relative(&profile.file))
    );
    let names: Vec<String> = profile
        .config
        .centrifuges
        .iter()
        .map(|c| c.name.clone())
        .collect();
    match profile.centrifuge.map(|i| &profile.config.centrifuges[i]) {
        Some(c) => {
            let lever = &c.lever;
            let direction = lever.probe_direction.unwrap_or_default().words();
            let angle_zero = lever.angle_zero_deg.map_or_else(
                || "; it states no angle zero, so 0° is taken".to_owned(),
                |deg| {
                    format!(
                        "; its encoder reads {deg}° when the arm's PIGA end points at the probe \
                         (the angle zero)"
                    )
                },
            );
            let num = |v: Option<f64>| v.map_or_else(|| "?".to_owned(), |x| format!("{x}"));
            let _ = writeln!(
                s,
                "    centrifuge: {},  // {}",
                ron_string(&c.name),
                comment_text(&format!(
                    "{} ({}): R = {} m, g = {} m/s²; the probe {} mm above the tilt pivot and \
                     {} mm below the PIGA's plane: {direction}{angle_zero}",
                    c.description,
                    c.identity,
                    num(c.radius_m),
                    num(profile.config.gravity.g_m_s2),
                    num(lever.pivot_to_probe_mm),
                    num(lever.probe_to_piga_mm),
                ))
            );
            if lever.angle_zero_deg.is_none() {
                angle_zero_comment(s, "    ", "// lever: (angle_zero_deg: 0.0),");
            }
        }
        None => placeholder(
            s,
            "    ",
            "centrifuge",
            &format!("{PLACEHOLDER:?}"),
            "centrifuge",
            &format!(
                "Which centrifuge of the profile was used: {}?",
                names.join(", ")
            ),
        ),
    }
    k1(s);
}

/// The calibration's or a mounting's PIGA data: `table: (…)` or `recordings: (…)`.
fn piga_data(
    s: &mut String,
    data: &PigaData<'_>,
    relative: &RelativePath<'_>,
    indent: &str,
    at: &str,
) {
    match data {
        PigaData::Table(table) => {
            let _ = writeln!(
                s,
                "{indent}// The PIGA's mean output at each rate (eq. 18).\n{indent}table: (\n{indent}    file: {},",
                ron_string(&relative(&table.path))
            );
            let inner = if table.table_block {
                let _ = writeln!(
                    s,
                    "{indent}    // The table as exported: recording's PIGA-table format.\n{indent}    format: ("
                );
                format!("{indent}        ")
            } else {
                format!("{indent}    ")
            };
            for setting in &table.format {
                let _ = writeln!(
                    s,
                    "{inner}{},  // {}",
                    setting.ron,
                    comment_text(&setting.evidence)
                );
            }
            if table.table_block {
                let _ = writeln!(s, "{indent}    ),");
            }
            let _ = writeln!(s, "{indent}),");
        }
        PigaData::Recordings(group) => {
            let _ = writeln!(
                s,
                "{indent}// {} raw PIGA output recordings, each reduced to its mean output over\n\
                 {indent}// whole spindle revolutions.\n{indent}recordings: (",
                group.files.len()
            );
            let inner = format!("{indent}    ");
            format_block(
                s,
                group.files[0],
                &inner,
                &format!("{at}.recordings.format"),
            );
            let _ = writeln!(s, "{inner}files: [");
            files(
                s,
                &group.files,
                relative,
                &format!("{inner}    "),
                &format!("{at}.recordings.files"),
            );
            let _ = writeln!(s, "{inner}],\n{indent}),");
        }
    }
}

/// The `units` list: each unit's label, k1 (to fill in) and calibration on its data.
fn units(s: &mut String, units: &[Unit<'_>], compensate: &str, relative: &RelativePath<'_>) {
    let _ = writeln!(
        s,
        "    // {} units calibrated in one run from the phases above (measured once), one table\n    \
         // each; each unit's results, report and certificate go to units/LABEL/ of the output\n    \
         // folder (docs/CONFIGURATION.md, \"Several units\"). A unit's certificate goes in its\n    \
         // entry: `certificate: (…)`, as a single-unit study's.\n    units: [",
        units.len()
    );
    for (i, unit) in units.iter().enumerate() {
        let _ = writeln!(
            s,
            "        (\n            label: {},  // {}",
            ron_string(&unit.label),
            comment_text(&unit.evidence)
        );
        placeholder(
            s,
            "            ",
            "k1_rad_s_g",
            PLACEHOLDER,
            &format!("units[{i}].k1_rad_s_g"),
            &format!(
                "What is unit {}'s nominal scale factor k1, in rad/(s·g), from its data sheet or last certificate?",
                unit.label
            ),
        );
        s.push_str("            calibration: (\n");
        piga_data(
            s,
            &unit.data,
            relative,
            "                ",
            &format!("units[{i}].calibration"),
        );
        let _ = writeln!(
            s,
            "                compensate_with: {compensate},  // the phase whose C_r is removed (eq. 19)\n                \
             k1: fitted,\n            ),\n        ),"
        );
    }
    s.push_str("    ],\n");
}

/// The two-orientation section (eq. 23) on both mountings' data.
fn two_orientation(
    s: &mut String,
    plan: &Plan<'_>,
    ia_in: &PigaData<'_>,
    ia_out: &PigaData<'_>,
    compensate: &str,
    relative: &RelativePath<'_>,
) {
    let centrifuge = plan
        .profile
        .as_ref()
        .and_then(|p| p.centrifuge.map(|i| &p.config.centrifuges[i]));
    s.push_str(
        "    // Both mountings were measured (the file names say IA in and IA out): k2 and the\n    \
         // radius growth C from the PIGA alone (eq. 23), C compared with the probe's C_r\n    \
         // (docs/TWO_ORIENTATION.md).\n    two_orientation: (\n        orientations: [\n",
    );
    for (i, (o, data)) in [(Orientation::In, ia_in), (Orientation::Out, ia_out)]
        .into_iter()
        .enumerate()
    {
        let at = format!("two_orientation.orientations[{i}]");
        let _ = writeln!(
            s,
            "            (\n                orientation: {},",
            o.ron()
        );
        let stated = match (o, centrifuge) {
            (Orientation::In, Some(c)) => c.radius_m.map(|r| (r, "radius_m")),
            (Orientation::Out, Some(c)) => c.radius_ia_out_m.map(|r| (r, "radius_ia_out_m")),
            (_, None) => None,
        };
        match stated {
            Some((r, key)) => {
                let _ = writeln!(
                    s,
                    "                // radius_m: {r} from the profile's centrifuge ({key})"
                );
            }
            None => placeholder(
                s,
                "                ",
                "radius_m",
                PLACEHOLDER,
                &format!("{at}.radius_m"),
                &format!(
                    "What is the static radius with the PIGA mounted {}, in m (its centre of \
                     mass to the spindle axis)?",
                    o.words()
                ),
            ),
        }
        piga_data(s, data, relative, "                ", &at);
        s.push_str("            ),\n");
    }
    let _ = writeln!(
        s,
        "        ],\n        compare_with: {compensate},  // the probe phase whose C_r is compared with C\n    ),"
    );
}

/// The Type B inputs, every one to fill in (no profile).
fn uncertainty_to_fill(s: &mut String) {
    let p = PLACEHOLDER;
    s.push_str(
        "    // Type B standard uncertainties (one standard deviation each, not a tolerance) of\n    \
         // the inputs, from their own calibration certificates; for one that is negligible\n    \
         // write 0 and say why: `zero_reasons: {\"rate_u_relative\": \"…\"},`.\n    \
         uncertainty: (\n",
    );
    for (key, value, question) in [
        (
            "radius_u_m",
            p.to_owned(),
            "What is the standard uncertainty of the radius R, in m?",
        ),
        (
            "g_u_m_s2",
            p.to_owned(),
            "What is the standard uncertainty of g, in m/s²?",
        ),
        (
            "g_source",
            ron_string(p),
            "Where does g come from (the gravity survey and its report)?",
        ),
        (
            "rate_u_relative",
            p.to_owned(),
            "What is the relative standard uncertainty of the rate (a scale error common to every rate)?",
        ),
        (
            "pivot_to_probe_u_mm",
            p.to_owned(),
            "What is the standard uncertainty of the pivot-to-probe height, in mm?",
        ),
        (
            "probe_to_piga_u_mm",
            p.to_owned(),
            "What is the standard uncertainty of the probe-to-PIGA height, in mm?",
        ),
        (
            "probe_gain_u_relative",
            p.to_owned(),
            "What is the relative standard uncertainty of the probe's gain, from its certificate?",
        ),
    ] {
        placeholder(
            s,
            "        ",
            key,
            &value,
            &format!("uncertainty.{key}"),
            question,
        );
    }
    s.push_str("    ),\n");
}

/// The certificate section: what the profile does not state, each with its question.
fn certificate(s: &mut String, profile: &ProfilePlan) {
    let q = format!("{PLACEHOLDER:?}");
    let pc = &profile.config;
    s.push_str(
        "    // The calibration certificate (docs/CERTIFICATE.md). The laboratory, place, equipment,\n    \
         // procedure, traceability, decision rule and signatory come from the profile.\n    \
         certificate: (\n",
    );
    let i8 = "        ";
    let i12 = "            ";
    placeholder(
        s,
        i8,
        "id",
        &q,
        "certificate.id",
        "What is this certificate's number in the laboratory's register?",
    );
    let _ = writeln!(s, "{i8}customer: (");
    placeholder(
        s,
        i12,
        "name",
        &q,
        "certificate.customer.name",
        "Who ordered the calibration (the customer's name)?",
    );
    placeholder(
        s,
        i12,
        "address",
        &q,
        "certificate.customer.address",
        "What is the customer's postal address, on one line?",
    );
    let _ = writeln!(s, "{i8}),\n{i8}item: (");
    let _ = writeln!(
        s,
        "{i12}description: \"pendulous integrating gyroscopic accelerometer (PIGA)\",  // what this tool calibrates: change it if the item is described otherwise"
    );
    for (key, question) in [
        ("manufacturer", "Who made the PIGA (its manufacturer)?"),
        ("model", "What is the PIGA's model, as on its label?"),
        (
            "serial",
            "What is the PIGA's serial number, as on its label?",
        ),
        (
            "condition",
            "In what condition was the PIGA received (damage, seals, cleanliness)?",
        ),
    ] {
        placeholder(
            s,
            i12,
            key,
            &q,
            &format!("certificate.item.{key}"),
            question,
        );
    }
    let _ = writeln!(s, "{i8}),\n{i8}dates: (");
    for (key, question) in [
        ("received", "On what day was the PIGA received, YYYY-MM-DD?"),
        (
            "measured",
            "On what day was it measured, YYYY-MM-DD (or YYYY-MM-DD to YYYY-MM-DD)?",
        ),
        (
            "issued",
            "On what day is the certificate issued, YYYY-MM-DD?",
        ),
    ] {
        placeholder(
            s,
            i12,
            key,
            &q,
            &format!("certificate.dates.{key}"),
            question,
        );
    }
    let _ = writeln!(s, "{i8}),");
    match pc.operators.as_slice() {
        [only] => {
            let _ = writeln!(
                s,
                "{i8}// operator: {} (the profile's only operator)",
                comment_text(&ron_string(only))
            );
        }
        list => placeholder(
            s,
            i8,
            "operator",
            &q,
            "certificate.operator",
            &if list.is_empty() {
                "Who performed the calibration?".to_owned()
            } else {
                format!("Who performed the calibration: {}?", list.join(", "))
            },
        ),
    }
    let _ = writeln!(s, "{i8}conditions: [");
    let quantities: Vec<String> = if pc.conditions.is_empty() {
        vec!["ambient temperature".to_owned()]
    } else {
        pc.conditions.clone()
    };
    for (i, quantity) in quantities.iter().enumerate() {
        let _ = writeln!(
            s,
            "{i12}(quantity: {}, value: {q}),  // {}",
            ron_string(quantity),
            ask(
                &format!("certificate.conditions[{i}].value"),
                &format!(
                    "What was the {quantity} during the measurement, with unit and range{}?",
                    match quantity.to_lowercase() {
                        q if q.contains("temperature") => " (e.g. 20.4 °C to 20.9 °C)",
                        q if q.contains("humidity") => " (e.g. 41 % to 45 %)",
                        _ => "",
                    }
                )
            )
        );
    }
    let _ = writeln!(s, "{i8}],");
    match pc.signatories.as_slice() {
        [only] => {
            let _ = writeln!(
                s,
                "{i8}// authorisation: {} (the profile's only signatory)",
                comment_text(&ron_string(&only.name))
            );
        }
        list => {
            let names: Vec<&str> = list.iter().map(|p| p.name.as_str()).collect();
            let _ = writeln!(
                s,
                "{i8}authorisation: (name: {q}),  // {}",
                ask(
                    "certificate.authorisation.name",
                    &format!(
                        "Who authorises this certificate: {}? (the role comes from the profile)",
                        names.join(", ")
                    )
                )
            );
        }
    }
    let _ = writeln!(
        s,
        "{i8}// Optional: the customer's limits, judged by the profile's decision rule, e.g.\n\
         {i8}// limits: [(coefficient: k2, unit: micro, lower: -20.0, upper: 20.0)],\n    ),"
    );
}

/// The `format: (...)` block of a set, each setting on its own line with its evidence and,
/// for a placeholder, its question; `at` is the block's field.
fn format_block(s: &mut String, f: &Finding, indent: &str, at: &str) {
    let _ = writeln!(s, "{indent}format: (");
    for setting in &f.format {
        match setting.question() {
            Some((field, question)) => {
                let key = setting.ron.split(':').next().unwrap_or("");
                let field = if field.starts_with(key) {
                    format!("{at}.{field}")
                } else {
                    format!("{at}.{key}.{field}")
                };
                let _ = writeln!(
                    s,
                    "{indent}    {},  // {}",
                    setting.ron,
                    ask(&field, question)
                );
            }
            None => {
                let _ = writeln!(s, "{indent}    {},", setting.ron);
            }
        }
        for line in wrap(&comment_text(&setting.evidence), 88 - indent.len()) {
            let _ = writeln!(s, "{indent}        // {line}");
        }
    }
    let _ = writeln!(s, "{indent}),");
}

/// The `files: [...]` entries, each with its rate's evidence; `at` is the list's field.
fn files(s: &mut String, files: &[&Finding], relative: &RelativePath<'_>, indent: &str, at: &str) {
    for (i, f) in files.iter().enumerate() {
        let file = relative(&f.path);
        match &f.rate {
            Some(r) => {
                let _ = writeln!(
                    s,
                    "{indent}(rate_deg_s: {}, file: {}),  // {}",
                    r.deg_s,
                    ron_string(&file),
                    comment_text(&r.evidence)
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "{indent}(rate_deg_s: {PLACEHOLDER}, file: {}),  // {}",
                    ron_string(&file),
                    ask(
                        &format!("{at}[{i}].rate_deg_s"),
                        &format!(
                            "At what rate, in deg/s, was {file} recorded? (nothing in its name \
                             or data says)"
                        )
                    )
                );
            }
        }
    }
}

/// Text cut into lines of at most `width` characters at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split(' ') {
        let last = lines.last_mut().expect("one line");
        if !last.is_empty() && last.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_owned());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    lines
}

/// A line of a configuration that still holds a placeholder outside comments and strings'
/// comment markers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Left {
    /// 1-based line.
    pub(crate) line: usize,
    /// The line's code, trimmed.
    pub(crate) code: String,
    /// The field it fills and the question that fills it (from its `// ASK` comment).
    pub(crate) ask: Option<(String, String)>,
}

impl Left {
    /// `line 12 (certificate.item.serial): What is …?`, or the code when there is no
    /// question.
    pub(crate) fn words(&self) -> String {
        match &self.ask {
            Some((field, question)) => format!("line {} `{field}`: {question}", self.line),
            None => format!("line {}: `{}`", self.line, self.code),
        }
    }
}

/// A line split into its code and its `//` comment (a `//` inside a string is code).
pub(crate) fn split_comment(line: &str) -> (&str, &str) {
    let mut in_string = false;
    let mut escaped = false;
    let bytes = line.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        if in_string {
            match b {
                _ if escaped => escaped = false,
                b'\\' => escaped = true,
                b'"' => in_string = false,
                _ => {}
            }
        } else if b == b'"' {
            in_string = true;
        } else if b == b'/' && bytes.get(i + 1) == Some(&b'/') {
            return line.split_at(i);
        }
    }
    (line, "")
}

/// The lines of a configuration that still hold a placeholder outside comments, with the
/// question beside each.
pub(crate) fn placeholders(text: &str) -> Vec<Left> {
    text.lines()
        .enumerate()
        .filter_map(|(i, line)| {
            let (code, comment) = split_comment(line);
            code.contains(PLACEHOLDER).then(|| Left {
                line: i + 1,
                code: code.trim().to_owned(),
                ask: comment
                    .find(&format!("{ASK} "))
                    .and_then(|at| comment[at + ASK.len() + 1..].split_once(": "))
                    .map(|(field, question)| (field.trim().to_owned(), question.trim().to_owned())),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_carry_their_questions() {
        let text = "(\n    id: \"FILL_IN\",  // ASK certificate.id: What is its number?\n    \
                    url: \"http://x//FILL_IN\",\n    // k1: FILL_IN\n    radius_m: FILL_IN,\n)";
        let left = placeholders(text);
        assert_eq!(left.len(), 3, "{left:?}");
        assert_eq!(
            left[0].ask,
            Some(("certificate.id".into(), "What is its number?".into()))
        );
        assert_eq!(left[1].line, 3, "a `//` in a string is no comment");
        assert_eq!(left[2].ask, None);
        assert_eq!(left[2].words(), "line 5: `radius_m: FILL_IN,`");
    }
}

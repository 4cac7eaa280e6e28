//! The study configuration `init` writes: RON with every guess commented with its evidence
//! and a placeholder for everything the files cannot say.

use std::fmt::Write as _;
use std::path::Path;

use super::file::{Finding, Kind, PLACEHOLDER};

/// A set of files that becomes one phase (probe recordings) or the calibration's recordings.
#[derive(Debug)]
pub(crate) struct Group<'a> {
    /// The phase's name.
    pub(crate) name: String,
    /// The files, by rate.
    pub(crate) files: Vec<&'a Finding>,
}

/// What the configuration is written from.
pub(crate) struct Plan<'a> {
    /// The study's name.
    pub(crate) name: String,
    /// Where the files were found (for the header comment).
    pub(crate) source: String,
    /// The probe phases.
    pub(crate) phases: Vec<Group<'a>>,
    /// The PIGA table, if any.
    pub(crate) table: Option<&'a Finding>,
    /// The raw PIGA output recordings, if any.
    pub(crate) piga: Option<Group<'a>>,
}

/// A file's path as the configuration names it: relative to the configuration's folder.
pub(crate) type RelativePath<'a> = dyn Fn(&Path) -> String + 'a;

/// The configuration's text.
pub(crate) fn render(plan: &Plan<'_>, relative: &RelativePath<'_>) -> String {
    let mut s = String::new();
    let p = PLACEHOLDER;
    let _ = writeln!(
        s,
        "// Study configuration written by `centrifuge-cal init` from {}.\n\
         // Each value the files could not tell is {p}: write it before running\n\
         // `centrifuge-cal check` (which lists what is left) and `centrifuge-cal study`, which\n\
         // both refuse a {p}. Each guess is commented with its evidence: check them.\n\
         // Field by field: docs/CONFIGURATION.md; the lab formats: docs/YOUR-DATA.md.",
        plan.source
    );
    s.push_str("(\n");
    let _ = writeln!(s, "    name: {:?},", plan.name);
    let _ = writeln!(
        s,
        "    // The centrifuge and the PIGA (not in the files).\n\
         \x20   radius_m: {p},    // static working radius R, m: PIGA centre of mass to the spindle axis\n\
         \x20   g_m_s2: {p},      // local gravity, m/s²\n\
         \x20   k1_rad_s_g: {p},  // PIGA scale factor k1, rad/(s·g), for Δk2 = k1·C_r·g/R²\n\
         \x20   lever: (\n\
         \x20       pivot_to_probe_mm: {p},  // height from the spindle's tilt pivot to the probe plane, mm\n\
         \x20       probe_to_piga_mm: {p},   // height from the probe plane to the PIGA's centre-of-mass plane, mm\n\
         \x20       // Which way the probe's reading moves when the spindle moves towards the PIGA\n\
         \x20       // (the arm's PIGA end pointing at the probe); it sets the sign of C_r:\n\
         \x20       //   against_o1_x1 (or reading_falls_towards_piga): {against};\n\
         \x20       //   along_o1_x1 (or reading_rises_towards_piga): {along}.\n\
         \x20       probe_direction: {p},\n\
         \x20   ),",
        against = pipeline::ProbeDirectionName::AgainstO1X1.words(),
        along = pipeline::ProbeDirectionName::AlongO1X1.words(),
    );
    s.push_str("    phases: [\n");
    for phase in &plan.phases {
        let first = phase.files[0];
        let _ = writeln!(
            s,
            "        (\n            name: {:?},\n            points: recordings((\n                \
             // {} probe recordings, one format:",
            phase.name,
            phase.files.len()
        );
        format_block(&mut s, first, Kind::Probe, "                ");
        s.push_str("                files: [\n");
        files(&mut s, &phase.files, relative, "                    ");
        s.push_str("                ],\n            )),\n        ),\n");
    }
    s.push_str("    ],\n");
    let compensate = plan
        .phases
        .first()
        .map_or_else(|| PLACEHOLDER.to_owned(), |g| format!("{:?}", g.name));
    if let Some(table) = plan.table {
        s.push_str(
            "    calibration: (\n        // The PIGA's mean output at each rate (eq. 18).\n",
        );
        let _ = writeln!(
            s,
            "        table: (\n            file: {:?},",
            relative(&table.path)
        );
        let indent = if table.table_block {
            s.push_str("            // The table as exported: recording's PIGA-table format.\n");
            s.push_str("            format: (\n");
            "                "
        } else {
            "            "
        };
        for setting in &table.format {
            let _ = writeln!(s, "{indent}{},  // {}", setting.ron, setting.evidence);
        }
        if table.table_block {
            s.push_str("            ),\n");
        }
        s.push_str("        ),\n");
        calibration_tail(&mut s, &compensate);
    } else if let Some(piga) = &plan.piga {
        let _ = writeln!(
            s,
            "    calibration: (\n        // {} raw PIGA output recordings, each reduced to its mean output over\n        \
             // whole spindle revolutions.\n        recordings: (",
            piga.files.len()
        );
        format_block(&mut s, piga.files[0], Kind::PigaRecording, "            ");
        s.push_str("            files: [\n");
        files(&mut s, &piga.files, relative, "                ");
        s.push_str("            ],\n        ),\n");
        calibration_tail(&mut s, &compensate);
    }
    let _ = writeln!(
        s,
        "    // Type B standard uncertainties (one standard deviation each, not a tolerance) of\n\
         \x20   // the inputs, from their own calibration certificates; for one that is negligible\n\
         \x20   // write 0 and say why: `zero_reasons: {{\"rate_u_relative\": \"…\"}},`.\n\
         \x20   uncertainty: (\n\
         \x20       radius_u_m: {p},            // u(R), m\n\
         \x20       g_u_m_s2: {p},              // u(g), m/s²\n\
         \x20       g_source: \"{p}\",          // where g comes from (a gravity survey, a model)\n\
         \x20       rate_u_relative: {p},       // relative u of the rate (a scale error common to every rate)\n\
         \x20       pivot_to_probe_u_mm: {p},   // u of the pivot-to-probe height, mm\n\
         \x20       probe_to_piga_u_mm: {p},    // u of the probe-to-PIGA height, mm\n\
         \x20       probe_gain_u_relative: {p}, // relative u of the probe's sensitivity\n\
         \x20   ),"
    );
    s.push_str(")\n");
    s
}

fn calibration_tail(s: &mut String, compensate: &str) {
    let _ = writeln!(
        s,
        "        compensate_with: {compensate},  // the phase whose C_r is removed (eq. 19)\n        \
         k1: fitted,  // k1 from the fit's ω² coefficient; or given(k1_rad_s_g: …, u_rad_s_g: …)\n    ),"
    );
}

/// The `format: (...)` block of a set, each setting on its own line with its evidence.
fn format_block(s: &mut String, f: &Finding, _kind: Kind, indent: &str) {
    let _ = writeln!(s, "{indent}format: (");
    for setting in &f.format {
        let _ = writeln!(s, "{indent}    {},", setting.ron);
        for line in wrap(&setting.evidence, 88 - indent.len()) {
            let _ = writeln!(s, "{indent}        // {line}");
        }
    }
    let _ = writeln!(s, "{indent}),");
}

/// The `files: [...]` entries, each with its rate's evidence.
fn files(s: &mut String, files: &[&Finding], relative: &RelativePath<'_>, indent: &str) {
    for f in files {
        let (rate, why) = match &f.rate {
            Some(r) => (format!("{}", r.deg_s), r.evidence.clone()),
            None => (
                PLACEHOLDER.to_owned(),
                "no rate in the file name and nothing in the data measures it: give it, deg/s"
                    .to_owned(),
            ),
        };
        let _ = writeln!(
            s,
            "{indent}(rate_deg_s: {rate}, file: {:?}),  // {why}",
            relative(&f.path)
        );
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

/// The lines of a configuration that still hold a placeholder outside comments: (1-based
/// line, the field's text).
pub(crate) fn placeholders(text: &str) -> Vec<(usize, String)> {
    text.lines()
        .enumerate()
        .filter_map(|(i, line)| {
            let code = line.split("//").next().unwrap_or("");
            code.contains(PLACEHOLDER)
                .then(|| (i + 1, code.trim().to_owned()))
        })
        .collect()
}

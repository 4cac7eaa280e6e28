//! The PIGA table read as the laboratory exported it (issue 19 item 5): the German DAQ
//! export (BOM, CRLF, metadata lines, `;`, decimal comma, units in the headers, code page
//! 1252) read unchanged through the study's `calibration.table.format`.

use pipeline::{Inputs, PipelineError, StudyConfig};

use crate::{chain, root};

/// The campaign study with its raw PIGA recordings replaced by `table`.
fn campaign_with_table(table: &str) -> Result<pipeline::StudyResults, PipelineError> {
    let path = root().join("fixtures/studies/campaign.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let start = text.find("        recordings: (").unwrap();
    let end = start + text[start..].find("\n        ),\n").unwrap() + "\n        ),\n".len();
    let text = format!(
        "{}        table: {table},\n{}",
        &text[..start],
        &text[end..]
    );
    let config = StudyConfig::from_ron(&text, &path)?;
    pipeline::run(&Inputs::new(config, &path, &pipeline::Files)?)
}

const GERMAN_FORMAT: &str = "format: (delimiter: ';', decimal: comma, skip_lines: 5, \
     rate: (column: \"Drehrate [°/s]\", unit: deg_s), \
     output: (column: \"Ausgang [rad/s]\", unit: rad_s), label: \"Lage\")";

#[test]
fn the_german_export_gives_the_same_calibration_as_the_plain_table() {
    // The same 13 points as the first 13 rows of the campaign's plain table.
    let plain = std::fs::read_to_string(root().join("fixtures/campaign/piga.csv")).unwrap();
    let dir = std::env::temp_dir().join(format!("exported-table-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let first13: Vec<&str> = plain.lines().take(14).collect();
    let csv = dir.join("piga13.csv");
    std::fs::write(&csv, first13.join("\n") + "\n").unwrap();
    let reference =
        campaign_with_table(&format!("(file: {:?})", csv.display().to_string())).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    for file in ["piga_export_utf8.csv", "piga_export_cp1252.csv"] {
        let results = campaign_with_table(&format!(
            "(file: \"../recordings/piga-table-de/{file}\", {GERMAN_FORMAT})"
        ))
        .unwrap_or_else(|e| panic!("{file}: {}", chain(&e)));
        let (c, r) = (
            results.calibration.unwrap(),
            reference.calibration.as_ref().unwrap(),
        );
        assert_eq!(c.points, 13, "{file}");
        assert_eq!(c.coefficients, r.coefficients, "{file}");
        // the rows keep their lines in the export (header on line 6) and their labels
        assert_eq!(c.residuals[0].line, Some(7), "{file}");
        assert_eq!(c.residuals[0].label.as_deref(), Some("oben"), "{file}");
    }
}

#[test]
fn columns_beside_a_format_block_are_refused() {
    let e = campaign_with_table(&format!(
        "(file: \"../recordings/piga-table-de/piga_export_utf8.csv\", rate_column: \"x\", {GERMAN_FORMAT})"
    ))
    .unwrap_err();
    let text = chain(&e);
    assert!(
        text.contains("field `calibration.table`") && text.contains("name the columns"),
        "{text}"
    );
}

#[test]
fn a_format_key_out_of_place_names_its_section() {
    let e = campaign_with_table(
        "(file: \"../recordings/piga-table-de/piga_export_utf8.csv\", format: (decimal: comma, separator: ';'))",
    )
    .unwrap_err();
    let text = chain(&e);
    assert!(
        text.contains("`separator`") && text.contains("calibration.table.format"),
        "{text}"
    );
}

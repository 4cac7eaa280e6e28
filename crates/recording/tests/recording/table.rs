//! Tables of named numeric columns and PIGA tables: formats, errors with file and line,
//! bounded reading.

use std::path::{Path, PathBuf};

use recording::{
    MAX_COLUMNS, PigaTable, RecordingError, TableColumn, TableFormat, load_piga_table, load_table,
    parse_piga_table, parse_table,
};

/// A file under the system temp directory, removed on drop.
struct TempFile(PathBuf);

impl TempFile {
    fn new(name: &str, contents: &[u8]) -> Self {
        let path =
            std::env::temp_dir().join(format!("recording-table-{}-{name}", std::process::id()));
        std::fs::write(&path, contents).unwrap();
        Self(path)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

fn piga(text: &str) -> Result<PigaTable, RecordingError> {
    parse_piga_table(text.as_bytes(), Path::new("piga.csv"))
}

#[test]
fn piga_table_with_comments_blanks_quotes_and_crlf() {
    let t = piga("# PIGA 7\r\n\r\n rate_deg_s , \"output_rad_s\"\r\n10, 0.5\r\n# mid\r\n\"20\",1.5e-1\r\n30,-2").unwrap();
    assert_eq!(t.rate_deg_s, [10.0, 20.0, 30.0]);
    assert_eq!(t.output_rad_s, [0.5, 0.15, -2.0]);
    assert_eq!(t.len(), 3);
    let lines: Vec<usize> = (0..3).map(|r| t.line_of_row(r)).collect();
    assert_eq!(lines, [4, 6, 7]);
    // Columns by name, in any order.
    let t = piga("output_rad_s,rate_deg_s\n0.5,10\n").unwrap();
    assert_eq!((t.rate_deg_s[0], t.output_rad_s[0]), (10.0, 0.5));
}

#[test]
fn piga_table_errors_name_the_file_and_line() {
    let e = piga("rate_deg_s,output_rad_s\n10,0.5\n20,abc\n").unwrap_err();
    assert!(
        matches!(&e, RecordingError::Parse { line: 3, column, text, .. } if column == "output_rad_s" && text == "abc"),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        "piga.csv:3: column `output_rad_s`: cannot parse \"abc\" as a number"
    );
    let e = piga("rate,output\n10,0.5\n").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("piga.csv:1: no column `rate_deg_s` in the header"),
        "{e}"
    );
    // Every row has as many fields as the header: a decimal comma is not read as two
    // numbers, nor a missing field as a short row.
    for (text, found) in [
        ("rate_deg_s,output_rad_s\n10,0.5\n20,0,6\n", 3),
        ("rate_deg_s,output_rad_s\n10,0.5\n20\n", 1),
        ("rate_deg_s,output_rad_s\n10,0.5\n20,0.6,\n", 3),
    ] {
        let e = piga(text).unwrap_err();
        assert!(
            matches!(e, RecordingError::FieldCount { line: 3, expected: 2, found: f, .. } if f == found),
            "{text:?}: {e}"
        );
    }
    let e = piga("rate_deg_s,output_rad_s\n10,NaN\n").unwrap_err();
    assert!(
        matches!(&e, RecordingError::NonFinite { line: 2, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("not finite"), "{e}");
    let e = piga("rate_deg_s,output_rad_s\n# none\n").unwrap_err();
    assert!(matches!(e, RecordingError::NoRows { line: 1, .. }), "{e}");
    assert!(e.to_string().contains("no data rows"), "{e}");
    assert!(matches!(piga("# c\n\n"), Err(RecordingError::Empty { .. })));
    let missing = std::env::temp_dir().join("recording-table-does-not-exist.csv");
    let e = load_piga_table(&missing).unwrap_err();
    assert!(matches!(e, RecordingError::Io { .. }), "{e}");
    assert!(
        e.to_string().contains("recording-table-does-not-exist.csv"),
        "{e}"
    );
}

#[test]
fn piga_file_is_read_like_its_text() {
    let text = "rate_deg_s,output_rad_s\n10,0.5\n\n20,0.6\n";
    let f = TempFile::new("piga.csv", text.as_bytes());
    let loaded = load_piga_table(&f.0).unwrap();
    assert_eq!(loaded, parse_piga_table(text.as_bytes(), &f.0).unwrap());
    assert_eq!(loaded.line_of_row(1), 4);
}

fn format(columns: Vec<TableColumn>, flexible: bool) -> TableFormat {
    TableFormat::new(columns, flexible)
}

#[test]
fn optional_columns_and_flexible_rows() {
    let f = format(
        vec![
            TableColumn::required("b"),
            TableColumn::optional("z"),
            TableColumn::required("a"),
        ],
        true,
    );
    let t = parse_table(b"a,x,b\n1,x,2,extra\n3,y,4\n", Path::new("t"), &f).unwrap();
    assert_eq!(t.column("a"), Some(&[1.0, 3.0][..]));
    assert_eq!(t.column("b"), Some(&[2.0, 4.0][..]));
    assert_eq!(t.column("z"), None);
    assert_eq!(t.column("x"), None);
    assert_eq!((t.len(), t.header_line(), t.path()), (2, 1, Path::new("t")));
    let e = parse_table(b"a,x\n1,2\n", Path::new("t"), &f).unwrap_err();
    assert!(
        matches!(&e, RecordingError::MissingColumn { column, .. } if column == "b"),
        "{e}"
    );
    let e = parse_table(b"a,x,b\n1,x\n", Path::new("t"), &f).unwrap_err();
    assert!(
        matches!(&e, RecordingError::MissingField { line: 2, column, .. } if column == "b"),
        "{e}"
    );
}

#[test]
fn unusable_formats_are_refused() {
    let text = b"a,b\n1,2\n";
    let many = (0..=MAX_COLUMNS)
        .map(|i| TableColumn::required(format!("c{i}")))
        .collect();
    for (f, expected) in [
        (format(vec![], false), "count: 0"),
        (
            format(vec![TableColumn::optional("a")], false),
            "required: 0",
        ),
        (format(many, false), "count: 9"),
    ] {
        let e = parse_table(text, Path::new("t"), &f).unwrap_err();
        assert!(matches!(e, RecordingError::InvalidColumns { .. }), "{e}");
        assert!(format!("{e:?}").contains(expected), "{e:?}");
    }
    let f = format(
        vec![TableColumn::required("a"), TableColumn::optional("a")],
        false,
    );
    let e = parse_table(text, Path::new("t"), &f).unwrap_err();
    assert!(
        matches!(&e, RecordingError::DuplicateColumn { field: "columns", name } if name == "a"),
        "{e}"
    );
    for delimiter in ['.', '#', '\n', '5', 'é'] {
        let f = TableFormat {
            delimiter,
            ..PigaTable::format()
        };
        assert!(matches!(
            parse_table(text, Path::new("t"), &f),
            Err(RecordingError::InvalidDelimiter { .. })
        ));
    }
}

#[test]
fn long_table_streams_in_chunks_and_keeps_its_lines() {
    // Several chunks and parallel halves; a comment every 997 rows.
    let mut text = String::from("rate_deg_s,output_rad_s\n");
    let mut lines = Vec::new();
    let mut line = 1;
    for i in 0..200_000 {
        if i % 997 == 3 {
            text += "# note\n";
            line += 1;
        }
        text += &format!("{i},{}\n", f64::from(i) * 1e-3);
        line += 1;
        lines.push(line);
    }
    let f = TempFile::new("long.csv", text.as_bytes());
    let loaded = load_piga_table(&f.0).unwrap();
    assert_eq!(loaded, parse_piga_table(text.as_bytes(), &f.0).unwrap());
    assert_eq!(loaded.len(), 200_000);
    for (row, &line) in lines.iter().enumerate() {
        assert_eq!(loaded.line_of_row(row), line, "row {row}");
    }
    // An error near the end names its line.
    let bad = text.replace("\n199990,", "\n199990;");
    let f = TempFile::new("long-bad.csv", bad.as_bytes());
    let e = load_piga_table(&f.0).unwrap_err();
    assert!(
        matches!(e, RecordingError::FieldCount { line, found: 1, .. } if line == lines[199_990]),
        "{e}"
    );
}

#[test]
fn a_line_without_end_is_refused_not_read_whole() {
    let start = std::time::Instant::now();
    let mut text = b"rate_deg_s,output_rad_s\n10,".to_vec();
    text.resize(text.len() + (16 << 20) + 1, b'7');
    let f = TempFile::new("endless.csv", &text);
    let e = load_piga_table(&f.0).unwrap_err();
    assert!(
        matches!(e, RecordingError::LineTooLong { line: 2, max_bytes, .. } if max_bytes == 16 << 20),
        "{e}"
    );
    assert!(e.to_string().contains("endless.csv:2: no line end"), "{e}");
    // A device that never ends: refused unread, as anything but a regular file (issue 32;
    // before, it was read up to 16 MiB).
    let zero = Path::new("/dev/zero");
    if zero.exists() {
        let e = load_table(zero, &PigaTable::format()).unwrap_err();
        assert!(
            matches!(
                e,
                RecordingError::NotAFile {
                    kind: "a character device",
                    ..
                }
            ),
            "{e}"
        );
        let e = load_piga_table(zero).unwrap_err();
        assert!(
            e.to_string().starts_with("/dev/zero is a character device"),
            "{e}"
        );
    }
    assert!(start.elapsed().as_secs_f64() < 10.0);
}

#[test]
fn a_label_column_is_read_as_text_per_row() {
    let text = b"# repeats\nrate_deg_s,run,output_rad_s\n10,\"cw\",1.5\n\n10, ccw ,1.25\n20,,3\n";
    let f = TableFormat {
        label: Some("run".into()),
        ..PigaTable::format()
    };
    let t = parse_table(text, Path::new("t.csv"), &f).unwrap();
    assert_eq!(t.labels().unwrap(), ["cw", "ccw", ""]);
    assert_eq!(t.column("output_rad_s"), Some(&[1.5, 1.25, 3.0][..]));
    assert_eq!(t.line_of_row(1), 5);
    // Without a label the table has none.
    let plain = parse_table(text, Path::new("t.csv"), &PigaTable::format()).unwrap();
    assert_eq!(plain.labels(), None);
}

#[test]
fn a_named_label_column_the_header_lacks_is_an_error() {
    let text = b"rate_deg_s,output_rad_s\n10,1.5\n";
    let f = TableFormat {
        label: Some("orientation".into()),
        ..PigaTable::format()
    };
    let e = parse_table(text, Path::new("t.csv"), &f).unwrap_err();
    assert!(
        matches!(&e, RecordingError::MissingColumn { column, line: 1, .. } if column == "orientation"),
        "{e}"
    );
    // A label that is also a numeric column is refused.
    let f = TableFormat {
        label: Some("rate_deg_s".into()),
        ..PigaTable::format()
    };
    let e = parse_table(text, Path::new("t.csv"), &f).unwrap_err();
    assert!(
        matches!(e, RecordingError::DuplicateColumn { field: "label", .. }),
        "{e}"
    );
}

#[test]
fn a_large_labelled_table_keeps_every_label_in_order() {
    // Above the two-thread threshold: read on one thread, every label with its row.
    let mut text = String::from("rate_deg_s,output_rad_s,run\n");
    for i in 0..40_000 {
        text.push_str(&format!("{}.5,{}.25,r{i}\n", i + 1, i));
    }
    let f = TableFormat {
        label: Some("run".into()),
        ..PigaTable::format()
    };
    let t = parse_table(text.as_bytes(), Path::new("t.csv"), &f).unwrap();
    let labels = t.labels().unwrap();
    assert_eq!(labels.len(), 40_000);
    assert_eq!(labels[39_999], "r39999");
    assert_eq!(t.column("rate_deg_s").unwrap()[39_999], 40_000.5);
}

#[test]
fn a_table_of_arrays_is_read_as_its_file_is_and_refused_alike() {
    use recording::Table;
    let format = TableFormat {
        label: Some("label".into()),
        ..TableFormat::new(
            vec![
                TableColumn::required("rate_deg_s"),
                TableColumn::required("output_rad_s"),
                TableColumn::optional("sigma_rad_s"),
            ],
            false,
        )
    };
    let path = std::path::Path::new("<arrays>");
    let columns = || {
        vec![
            ("output_rad_s".to_owned(), vec![0.1, 0.2, 0.3]),
            ("rate_deg_s".to_owned(), vec![10.0, 20.0, 30.0]),
        ]
    };
    let labels = || Some(vec!["a".to_owned(), "b".to_owned(), "a".to_owned()]);
    let table = Table::from_columns(path, &format, columns(), labels()).unwrap();
    let text = "rate_deg_s,output_rad_s,label\n10,0.1,a\n20,0.2,b\n30,0.3,a\n";
    let parsed = parse_table(text.as_bytes(), path, &format).unwrap();
    for name in ["rate_deg_s", "output_rad_s", "sigma_rad_s"] {
        assert_eq!(table.column(name), parsed.column(name), "{name}");
    }
    assert_eq!(table.labels(), parsed.labels());
    assert_eq!(table.line_of_row(2), 3, "rows are counted from 1");
    // a required column missing, a short column, a NaN, no labels, no rows
    let missing = Table::from_columns(path, &format, columns()[..1].to_vec(), labels());
    assert!(
        matches!(missing, Err(RecordingError::MissingColumn { ref column, .. }) if column == "rate_deg_s")
    );
    let mut short = columns();
    short[0].1.pop();
    let short = Table::from_columns(path, &format, short, labels());
    assert!(
        matches!(short, Err(RecordingError::MissingField { line: 3, ref column, .. }) if column == "output_rad_s")
    );
    let mut nan = columns();
    nan[1].1[1] = f64::NAN;
    let nan = Table::from_columns(path, &format, nan, labels());
    assert!(
        matches!(nan, Err(RecordingError::NonFinite { line: 2, ref column, .. }) if column == "rate_deg_s")
    );
    let unlabelled = Table::from_columns(path, &format, columns(), None);
    assert!(
        matches!(unlabelled, Err(RecordingError::MissingColumn { ref column, .. }) if column == "label")
    );
    let empty = vec![
        ("output_rad_s".to_owned(), vec![]),
        ("rate_deg_s".to_owned(), vec![]),
    ];
    assert!(matches!(
        Table::from_columns(path, &format, empty, Some(vec![])),
        Err(RecordingError::NoRows { .. })
    ));
}

//! PIGA-table reader: no panic; the same table as the reference (field-by-field) path; an
//! `Ok` has finite numbers and a line for every row.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use recording::{PIGA_OUTPUT_COLUMN, PIGA_RATE_COLUMN, PigaTable};

fuzz_target!(|data: &[u8]| {
    let path = Path::new("piga.csv");
    let fast = recording::parse_piga_table(data, path);
    let reference = recording::parse_table_reference(data, path, &PigaTable::format());
    match (&fast, &reference) {
        (Ok(t), Ok(r)) => {
            assert_eq!(Some(&t.rate_deg_s[..]), r.column(PIGA_RATE_COLUMN));
            assert_eq!(Some(&t.output_rad_s[..]), r.column(PIGA_OUTPUT_COLUMN));
            assert!(t.rate_deg_s.iter().chain(&t.output_rad_s).all(|v| v.is_finite()));
            let mut previous = 0;
            for row in 0..t.len() {
                let line = t.line_of_row(row);
                assert_eq!(line, r.line_of_row(row));
                assert!(line > previous, "lines increase");
                previous = line;
            }
        }
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
        _ => panic!("fast {fast:?} vs reference {reference:?}"),
    }
});

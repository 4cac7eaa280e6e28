//! Every problem of a configuration at once, grouped: the same fault in seven files is one
//! message naming the seven files, not seven messages.

use std::error::Error;
use std::fmt::Write as _;

/// An error and its causes as one line ([`units::ErrorChain`], the one chain printer).
pub(crate) fn full_text(e: &(dyn Error + 'static)) -> String {
    units::ErrorChain(e).to_string()
}

/// The errors of a pipeline error: each of a `Several`, else the one.
pub(crate) fn each(e: &pipeline::PipelineError) -> Vec<String> {
    match e {
        pipeline::PipelineError::Several { errors } => {
            errors.iter().map(|e| full_text(e)).collect()
        }
        e => vec![full_text(e)],
    }
}

/// A problem with the file it concerns taken out: (the text with `FILE` for the file name,
/// the file, line numbers and indices replaced).
fn shape(problem: &str) -> (String, Option<String>) {
    // The recording's path: the last token ending in a data-file name before `:`.
    let mut file = None;
    let mut key = String::with_capacity(problem.len());
    for token in problem.split_inclusive([' ', '`']) {
        let bare = token.trim_end_matches([' ', '`']);
        let path_part = bare.split(':').next().unwrap_or("");
        let is_file = [
            ".csv", ".txt", ".dat", ".tsv", ".tdms", ".mat", ".asc", ".prn",
        ]
        .iter()
        .any(|ext| path_part.to_ascii_lowercase().ends_with(ext));
        if is_file && !path_part.ends_with(".ron") {
            file.get_or_insert_with(|| path_part.to_owned());
            key.push_str("FILE");
            key.push_str(&token[path_part.len()..]);
        } else {
            key.push_str(token);
        }
    }
    // Numbers (lines, indices, values read) differ from file to file for one fault.
    let mut normal = String::with_capacity(key.len());
    let mut in_number = false;
    for c in key.chars() {
        if c.is_ascii_digit() {
            if !in_number {
                normal.push('#');
            }
            in_number = true;
        } else {
            if !(in_number && (c == '.' || c == ',')) {
                normal.push(c);
            }
            in_number = false;
        }
    }
    (normal, file)
}

/// One group of problems: the first message in full, the files that share it.
#[derive(Debug)]
pub(crate) struct Group {
    /// The first problem of the group, as written.
    pub(crate) first: String,
    /// The files with the same fault (in order), when the problems name files.
    pub(crate) files: Vec<String>,
    /// How many problems the group holds.
    pub(crate) count: usize,
}

/// The problems grouped by their shape, in order of first appearance.
pub(crate) fn group(problems: &[String]) -> Vec<Group> {
    let mut groups: Vec<(String, Group)> = Vec::new();
    for p in problems {
        let (key, file) = shape(p);
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, g)) => {
                g.count += 1;
                g.files.extend(file);
            }
            None => groups.push((
                key,
                Group {
                    first: p.clone(),
                    files: file.into_iter().collect(),
                    count: 1,
                },
            )),
        }
    }
    groups.into_iter().map(|(_, g)| g).collect()
}

/// The grouped problems as text: one numbered entry per group.
pub(crate) fn render(problems: &[String]) -> String {
    let groups = group(problems);
    let mut out = String::new();
    for (i, g) in groups.iter().enumerate() {
        let _ = writeln!(out, "{:>3}. {}", i + 1, g.first);
        if g.count > 1 {
            let names: Vec<String> = g
                .files
                .iter()
                .map(|f| {
                    std::path::Path::new(f)
                        .file_name()
                        .map_or_else(|| f.clone(), |n| n.to_string_lossy().into_owned())
                })
                .collect();
            if names.len() == g.count {
                let _ = writeln!(
                    out,
                    "     the same in {} files: {}",
                    g.count,
                    names.join(", ")
                );
            } else {
                let _ = writeln!(out, "     the same {} times", g.count);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seven_files_one_fault_one_group() {
        let problems: Vec<String> = (0..7)
            .map(|i| {
                format!(
                    "/lab/study.ron: `phases[0].points.files[{i}]`: /lab/f{i}.csv:{}: column \
                     \"Zeit [s]\": cannot parse \"0,00{i}\" as a number (hint: decimal comma? \
                     set decimal: comma)",
                    7 + i
                )
            })
            .chain(std::iter::once(
                "/lab/study.ron: `radius_m` must be positive".to_owned(),
            ))
            .collect();
        let groups = group(&problems);
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[0].count, 7);
        assert_eq!(groups[0].files.len(), 7);
        assert_eq!(groups[0].files[6], "/lab/f6.csv");
        let text = render(&problems);
        assert!(
            text.contains(
                "the same in 7 files: f0.csv, f1.csv, f2.csv, f3.csv, f4.csv, f5.csv, f6.csv"
            ),
            "{text}"
        );
        assert_eq!(text.matches("cannot parse").count(), 1, "{text}");
    }
}

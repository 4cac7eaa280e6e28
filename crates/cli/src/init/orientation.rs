//! Which way a PIGA data file was mounted, from its name and folder: input axis in (towards
//! the spindle axis) or out. `ia_in`, `IA-in`, `ia in`, `iain`, or `in` / `out` as a word of
//! the name; the words found are the evidence.

use std::path::Path;

/// A PIGA mounting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Orientation {
    /// Input axis towards the spindle axis (the paper's mounting).
    In,
    /// Input axis away from the spindle axis.
    Out,
}

impl Orientation {
    /// The study file's name of it.
    pub(crate) const fn ron(self) -> &'static str {
        match self {
            Self::In => "ia_in",
            Self::Out => "ia_out",
        }
    }

    /// In words.
    pub(crate) const fn words(self) -> &'static str {
        match self {
            Self::In => "IA in",
            Self::Out => "IA out",
        }
    }
}

/// The mounting `path`'s name (relative to the folder read, subfolders included) states,
/// with the words that state it; `None` when it states none, or both.
pub(crate) fn orientation(path: &Path) -> Option<(Orientation, String)> {
    let text = path.with_extension("").to_string_lossy().to_lowercase();
    let words: Vec<&str> = text
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect();
    let mut found: Option<(Orientation, String)> = None;
    let mut conflict = false;
    let mut note = |o: Orientation, evidence: String| match &found {
        Some((f, _)) if *f != o => conflict = true,
        Some(_) => {}
        None => found = Some((o, evidence)),
    };
    for (i, w) in words.iter().enumerate() {
        let next = words.get(i + 1).copied();
        match (*w, next) {
            ("ia", Some("in")) => note(Orientation::In, "ia in".to_owned()),
            ("ia", Some("out")) => note(Orientation::Out, "ia out".to_owned()),
            ("iain", _) => note(Orientation::In, "iain".to_owned()),
            ("iaout", _) => note(Orientation::Out, "iaout".to_owned()),
            ("in", _) if i == 0 || words[i - 1] != "ia" => note(Orientation::In, "in".to_owned()),
            ("out", _) if i == 0 || words[i - 1] != "ia" => {
                note(Orientation::Out, "out".to_owned());
            }
            _ => {}
        }
    }
    if conflict { None } else { found }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_state_a_mounting() {
        let o = |p: &str| orientation(Path::new(p)).map(|(o, _)| o);
        assert_eq!(o("piga_ia_in.csv"), Some(Orientation::In));
        assert_eq!(o("PIGA_IA-out.csv"), Some(Orientation::Out));
        assert_eq!(o("ia_in/piga_035deg_s.csv"), Some(Orientation::In));
        assert_eq!(o("piga IA in.txt"), Some(Orientation::In));
        assert_eq!(o("piga_iaout.csv"), Some(Orientation::Out));
        assert_eq!(o("table_out.csv"), Some(Orientation::Out));
        assert_eq!(o("in/table.csv"), Some(Orientation::In));
        assert_eq!(o("piga.csv"), None);
        assert_eq!(o("piga_index.csv"), None);
        assert_eq!(o("input_table.csv"), None);
        assert_eq!(o("in/piga_ia_out.csv"), None, "both: neither is trusted");
    }
}

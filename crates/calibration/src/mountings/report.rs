//! What the separability analysis finds, and its words: the confounded columns, the poorly
//! separated terms, the preset that fixes each.

use accel_model::MountingPreset;

use super::column::Column;
use crate::INFLATION_LIMIT;

/// Columns the data cannot tell apart: a direction of the design with no information.
#[derive(Debug, Clone, PartialEq)]
pub struct Confounded {
    /// The columns mixed, in words.
    pub labels: Vec<String>,
    /// The columns mixed.
    pub columns: Vec<Column>,
    /// The preset mounting whose addition separates them (`None`: no single preset does).
    pub fix: Option<MountingPreset>,
}

/// A chosen term the mountings separate only poorly.
#[derive(Debug, Clone, PartialEq)]
pub struct PoorlySeparated {
    /// The term's column and words.
    pub column: Column,
    /// Its words.
    pub label: String,
    /// u of the term over its u in the design that separates every term, at the same
    /// number of points.
    pub inflation: f64,
    /// The column it is most correlated with, in words.
    pub partner: String,
    /// That correlation.
    pub correlation: f64,
    /// The preset mounting whose addition brings the inflation down most.
    pub fix: Option<MountingPreset>,
}

/// The separability of a declaration's terms by its mountings.
#[derive(Debug, Clone, PartialEq)]
pub struct Separability {
    /// The design's columns in words.
    pub labels: Vec<String>,
    /// Rank of the design (columns it separates).
    pub rank: usize,
    /// Condition number of the column-normalised design (∞ when rank deficient).
    pub condition_number: f64,
    /// The groups of columns the data cannot tell apart.
    pub confounded: Vec<Confounded>,
    /// The chosen terms separated only poorly (inflation above [`INFLATION_LIMIT`]).
    pub poorly: Vec<PoorlySeparated>,
    /// The inflation of each chosen term (and the arm stretch), in column order.
    pub inflation: Vec<(Column, f64)>,
}

impl Separability {
    /// Whether every column is separated (full rank).
    #[must_use]
    pub fn full_rank(&self) -> bool {
        self.confounded.is_empty()
    }

    /// The warnings, one per problem, in words.
    #[must_use]
    pub fn warnings(&self) -> Vec<SeparabilityWarning> {
        let mut w: Vec<SeparabilityWarning> = self
            .confounded
            .iter()
            .cloned()
            .map(SeparabilityWarning::Confounded)
            .collect();
        w.extend(self.poorly.iter().cloned().map(SeparabilityWarning::Poorly));
        w
    }
}

/// What the analysis says, one problem each.
#[derive(Debug, Clone, PartialEq)]
pub enum SeparabilityWarning {
    /// Columns the data cannot tell apart.
    Confounded(Confounded),
    /// A term separated only poorly.
    Poorly(PoorlySeparated),
}

fn fix_words(fix: Option<MountingPreset>) -> String {
    fix.map_or_else(
        || "no single preset mounting separates them; add mountings of other angles".to_owned(),
        |p| format!("adding the mounting “{}” separates them", p.label()),
    )
}

impl std::fmt::Display for SeparabilityWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Confounded(c) => write!(
                f,
                "these mountings cannot tell {} apart (one combination of them leaves the \
                 outputs unchanged): {}",
                c.labels.join(", "),
                fix_words(c.fix)
            ),
            Self::Poorly(p) => write!(
                f,
                "{} is separated poorly: its u is {:.1} times what a design separating every \
                 term gives with as many points (limit {INFLATION_LIMIT}); it is correlated \
                 {:.3} with {}; {}",
                p.label,
                p.inflation,
                p.correlation,
                p.partner,
                fix_words(p.fix)
            ),
        }
    }
}

impl std::fmt::Display for Separability {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let w = self.warnings();
        if w.is_empty() {
            return write!(
                f,
                "the mountings separate every chosen term ({} columns, rank {})",
                self.labels.len(),
                self.rank
            );
        }
        write!(
            f,
            "the mountings do not separate every chosen term ({} columns, rank {}): ",
            self.labels.len(),
            self.rank
        )?;
        let parts: Vec<String> = w.iter().map(ToString::to_string).collect();
        f.write_str(&parts.join("; "))
    }
}

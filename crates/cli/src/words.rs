//! The libraries' enums in a user's words for the terminal: a solver path, a fit warning, a
//! planning criterion. Taken from the names results.json and `--json` give them (serde), so
//! a Rust type's name never reaches the terminal.

use serde::Serialize;
use serde_json::Value;

/// The serde name of a unit-like value (`"refined_scaled_col_piv_qr"`), or of the variant of
/// a value with fields (`{"refinement_not_converged": {...}}`) with its fields.
fn name_of<T: Serialize>(value: &T) -> (String, Option<serde_json::Map<String, Value>>) {
    match serde_json::to_value(value) {
        Ok(Value::String(s)) => (s, None),
        Ok(Value::Object(map)) if map.len() == 1 => {
            let (k, v) = map.into_iter().next().expect("one entry");
            (k, v.as_object().cloned())
        }
        Ok(other) => (other.to_string(), None),
        Err(_) => ("—".to_owned(), None),
    }
}

/// A snake_case name as words.
fn spaced(name: &str) -> String {
    name.replace('_', " ")
}

/// The least-squares solver's path.
pub(crate) fn solver<T: Serialize>(path: &T) -> String {
    let (name, _) = name_of(path);
    match name.as_str() {
        "scaled_col_piv_qr" => "column-pivoted QR of the column-scaled design".to_owned(),
        "refined_scaled_col_piv_qr" => {
            "column-pivoted QR of the column-scaled design, refined in double-double".to_owned()
        }
        other => spaced(other),
    }
}

/// A warning of the least-squares fit.
pub(crate) fn fit_warning<T: Serialize>(warning: &T) -> String {
    let (name, fields) = name_of(warning);
    let field = |key: &str| {
        fields
            .as_ref()
            .and_then(|f| f.get(key))
            .map_or_else(|| "—".to_owned(), ToString::to_string)
    };
    match name.as_str() {
        "refinement_not_converged" => format!(
            "the iterative refinement stopped contracting after {} iterations (last relative \
             correction {}): the design is too ill-conditioned for the trailing digits to be \
             established",
            field("iterations"),
            field("relative_correction")
        ),
        other => spaced(other),
    }
}

/// A planning criterion.
pub(crate) fn criterion<T: Serialize>(criterion: &T) -> String {
    let (name, _) = name_of(criterion);
    match name.as_str() {
        "k2" => "smallest u(k2) (c-optimal)".to_owned(),
        "d" => "largest det(XᵀWX) (D-optimal, all six coefficients)".to_owned(),
        other => spaced(other),
    }
}

/// A radius-error model as its formula.
pub(crate) fn radius_model<T: Serialize>(model: &T) -> String {
    let (name, _) = name_of(model);
    match name.as_str() {
        "two_term" => "a + C_r·ω²".to_owned(),
        "three_term" => "a + b·ω + C_r·ω²".to_owned(),
        other => spaced(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_words() {
        assert_eq!(
            solver(&identify::SolverPath::RefinedScaledColPivQr),
            "column-pivoted QR of the column-scaled design, refined in double-double"
        );
        assert_eq!(
            criterion(&planning::Criterion::K2),
            "smallest u(k2) (c-optimal)"
        );
        assert_eq!(radius_model(&"three_term"), "a + b·ω + C_r·ω²");
        let w = identify::FitWarning::RefinementNotConverged {
            iterations: 30,
            relative_correction: 0.5,
        };
        assert!(fit_warning(&w).starts_with("the iterative refinement stopped"));
    }
}

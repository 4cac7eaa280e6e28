//! The fixture scenarios (`fixtures/scenarios/`) and edits of them.

use std::path::Path;

use simulate::{LoadedScenario, Scenario};

/// The text of `fixtures/scenarios/post-balance.ron`.
pub const POST_BALANCE: &str = include_str!("../../../fixtures/scenarios/post-balance.ron");
/// The text of `fixtures/scenarios/pre-balance.ron`.
pub const PRE_BALANCE: &str = include_str!("../../../fixtures/scenarios/pre-balance.ron");

/// The post-balance fixture scenario.
pub fn post_balance() -> LoadedScenario {
    Scenario::parse(POST_BALANCE, Path::new("post-balance.ron")).expect("fixture is valid")
}

/// The pre-balance fixture scenario.
pub fn pre_balance() -> LoadedScenario {
    Scenario::parse(PRE_BALANCE, Path::new("pre-balance.ron")).expect("fixture is valid")
}

/// A modified copy of a scenario, validated again.
pub fn modified(base: &LoadedScenario, edit: impl FnOnce(&mut Scenario)) -> LoadedScenario {
    let mut s = base.scenario.clone();
    edit(&mut s);
    s.check(&base.path).expect("modified scenario is valid")
}

/// The highest sleeve-harmonic order of a scenario (at least 4, the paper's fit order).
pub fn fit_order(s: &Scenario) -> usize {
    s.probe
        .sleeve_harmonics
        .iter()
        .map(|h| h.order)
        .max()
        .unwrap_or(0)
        .max(harmonics::DEFAULT_ORDER)
}

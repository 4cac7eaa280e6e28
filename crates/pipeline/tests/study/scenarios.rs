//! Fixture scenarios and small helpers.

use std::path::Path;

use simulate::{LoadedScenario, Scenario};

pub(crate) const POST_BALANCE: &str =
    include_str!("../../../../fixtures/scenarios/post-balance.ron");
pub(crate) const PRE_BALANCE: &str = include_str!("../../../../fixtures/scenarios/pre-balance.ron");

/// The post-balance fixture scenario.
pub(crate) fn post_balance() -> LoadedScenario {
    Scenario::parse(POST_BALANCE, Path::new("post-balance.ron")).expect("fixture is valid")
}

/// The pre-balance fixture scenario.
pub(crate) fn pre_balance() -> LoadedScenario {
    Scenario::parse(PRE_BALANCE, Path::new("pre-balance.ron")).expect("fixture is valid")
}

/// A modified copy of a scenario, validated again.
pub(crate) fn modified(base: &LoadedScenario, edit: impl FnOnce(&mut Scenario)) -> LoadedScenario {
    let mut s = base.scenario.clone();
    edit(&mut s);
    s.check(&base.path).expect("modified scenario is valid")
}

/// The highest sleeve-harmonic order of a scenario (at least 4, the paper's fit order).
pub(crate) fn fit_order(s: &Scenario) -> usize {
    s.probe
        .sleeve_harmonics
        .iter()
        .map(|h| h.order)
        .max()
        .unwrap_or(0)
        .max(harmonics::DEFAULT_ORDER)
}

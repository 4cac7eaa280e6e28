//! The balance section: the balance advisor (`balance` crate, `docs/BALANCING.md`) on the
//! study's phases — the correction by influence coefficient or stiffness, the residual C_r and
//! Δk2 it leaves, two probe planes — and, in [`counterweight`], what one published change of
//! radius error determines of a counterweight. Validated here; run in [`run`].

pub(crate) mod counterweight;
mod run;
mod validate;

pub(crate) use run::run;
pub(crate) use validate::{BalanceInputs, second_probe_phases, validate};

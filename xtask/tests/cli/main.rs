//! Command-line behaviour of `cargo xtask` subcommands (one binary, a module per subcommand).

mod harmonics;
mod outputs;
mod plan;
mod snapshots;
mod stdout;
mod workflow;

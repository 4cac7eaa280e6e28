//! Command-line behaviour of the `centrifuge-cal` subcommands (one binary, a module per subcommand).

mod harmonics;
mod outputs;
mod plan;
mod snapshots;
mod stdout;
mod workflow;

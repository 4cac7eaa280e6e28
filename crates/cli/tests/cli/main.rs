//! Command-line behaviour of the `centrifuge-cal` subcommands (one binary, a module per subcommand).

mod harmonics;
mod hostile_text;
mod human;
mod identify;
mod init;
mod outputs;
mod plan;
mod progress;
mod readme_path;
mod snapshots;
mod stdout;
mod workflow;

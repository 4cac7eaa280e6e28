//! Command-line behaviour of the `centrifuge-cal` subcommands (one binary, a module per subcommand).

mod check;
mod harmonics;
mod hostile;
mod hostile_text;
mod human;
mod identify;
mod init;
mod lab_folder;
mod one_voice;
mod outputs;
mod plan;
mod progress;
mod readme_path;
mod records;
mod snapshots;
mod stdout;
mod workflow;

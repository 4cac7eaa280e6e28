//! `centrifuge-cal`: the installed command line (`cargo install --path crates/cli`).

fn main() -> std::process::ExitCode {
    cli::run(std::env::args_os())
}

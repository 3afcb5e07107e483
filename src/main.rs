//! The `ssgi` command line.

use clap::Parser;
use ssgi::cli::{Cli, Command};

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Render(args) => ssgi::cli::render(&cli, args),
        Command::Bench(args) => ssgi::cli::bench(&cli, args),
        Command::View(args) => ssgi::cli::view(&cli, args),
        Command::Table(args) => ssgi::cli::table(&cli, args),
        Command::Reference(args) => ssgi::cli::reference(&cli, args),
        Command::Sweep(args) => ssgi::cli::sweep(&cli, args),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

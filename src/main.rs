//! The `ssgi` command line.

use ssgi::cli::Command;

fn main() -> std::process::ExitCode {
    let cli = ssgi::cli::parse::parse();
    ssgi::interrupt::install();
    let result = match &cli.command {
        Command::Render(args) => ssgi::cli::render(&cli, args),
        Command::Bench(args) => ssgi::cli::bench(&cli, args),
        Command::View(args) => ssgi::cli::view(&cli, args),
        Command::Table(args) => ssgi::cli::table(&cli, args),
        Command::Reference(args) => ssgi::cli::reference(&cli, args),
        Command::Sweep(args) => ssgi::cli::sweep(&cli, args),
        Command::Stress(args) => ssgi::cli::stress(&cli, args),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(ssgi::Error::Interrupted) => {
            eprintln!("{}", ssgi::Error::Interrupted);
            std::process::ExitCode::from(ssgi::interrupt::EXIT_CODE)
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

//! The command line as clap reads it, with two changes to what the derive gives:
//! - a value may start with '-': a negative number (or a point such as `-1,2,0`) reaches
//!   the option's value parser, which names the option and the value, where clap would take
//!   `-1` for a flag and say "unexpected argument '-1'". Options whose value is a name or a
//!   path take only negative numbers that way, so `--out --frames` still says that `--out`
//!   lacks a value instead of writing a file called `--frames`;
//! - an argument that is not UTF-8 where text is expected is named (clap says only that one
//!   of them is not).

use super::args::Cli;
use clap::error::ErrorKind;
use clap::{Arg, Command, CommandFactory, FromArgMatches};
use std::any::TypeId;
use std::ffi::OsString;
use std::path::PathBuf;

/// The clap command of `Cli` with the settings above.
pub fn command() -> Command {
    hyphen_values(Cli::command())
}

fn hyphen_values(cmd: Command) -> Command {
    cmd.mut_args(hyphen_value).mut_subcommands(hyphen_values)
}

fn hyphen_value(arg: Arg) -> Arg {
    if arg.is_positional() || !arg.get_action().takes_values() {
        return arg;
    }
    let kind = arg.get_value_parser().type_id();
    let named = [
        TypeId::of::<String>(),
        TypeId::of::<PathBuf>(),
        TypeId::of::<OsString>(),
    ];
    if named.iter().any(|t| kind == *t) {
        arg.allow_negative_numbers(true)
    } else {
        arg.allow_hyphen_values(true)
    }
}

/// A parsed command line and what it should warn about (`unused.rs`).
pub struct Parsed {
    pub cli: Cli,
    pub warnings: Vec<String>,
}

/// Parse `args` (the program name first).
pub fn try_parse_from<I, T>(args: I) -> Result<Parsed, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    let mut cmd = command();
    let matches = cmd
        .try_get_matches_from_mut(args.iter().cloned())
        .map_err(|e| name_invalid_utf8(e, &args, &mut cmd))?;
    let cli = Cli::from_arg_matches(&matches).map_err(|e| e.format(&mut cmd))?;
    let warnings = super::unused::warnings(&cli, &cmd, &matches);
    Ok(Parsed { cli, warnings })
}

/// Parse the process's arguments and print the warnings; exit with clap's message and
/// status on an error (and after `--help` or `--version`).
pub fn parse() -> Cli {
    let parsed = try_parse_from(std::env::args_os()).unwrap_or_else(|e| e.exit());
    for w in &parsed.warnings {
        eprintln!("warning: {w}");
    }
    parsed.cli
}

/// clap's "invalid UTF-8 was detected in one or more arguments", with the argument (and the
/// option it follows) named.
fn name_invalid_utf8(e: clap::Error, args: &[OsString], cmd: &mut Command) -> clap::Error {
    if e.kind() != ErrorKind::InvalidUtf8 {
        return e;
    }
    let Some(i) = args.iter().position(|a| a.to_str().is_none()) else {
        return e;
    };
    let bad = args[i].to_string_lossy();
    let after = match args.get(i.wrapping_sub(1)).and_then(|a| a.to_str()) {
        Some(option) if i > 0 && option.starts_with('-') => format!(" (the value of {option})"),
        _ => String::new(),
    };
    cmd.error(
        ErrorKind::InvalidUtf8,
        format!(
            "argument {i}{after} is not valid UTF-8: {bad:?} (each byte that is not UTF-8 \
             shown as U+FFFD); this option takes text, so name the file by another path (a \
             symbolic link, or a copy)"
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::ffi::OsStringExt;

    fn error(args: &[&str]) -> String {
        let args = std::iter::once("ssgi").chain(args.iter().copied());
        match try_parse_from(args) {
            Ok(_) => panic!("parsed"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn negative_numbers_reach_the_value_parser() {
        let e = error(&["render", "--frames", "-1"]);
        assert!(e.contains("--frames") && e.contains("\"-1\""), "{e}");
        let e = error(&["render", "--fps", "-60"]);
        assert!(e.contains("--fps") && e.contains("\"-60\""), "{e}");
        let e = error(&["render", "--light-intensity", "-1"]);
        assert!(
            e.contains("--light-intensity") && e.contains("\"-1\""),
            "{e}"
        );
        // A point with a negative coordinate is a value too.
        let cli = try_parse_from(["ssgi", "render", "--light", "-1,2,0:0,0,0"])
            .unwrap()
            .cli;
        let super::super::args::Command::Render(r) = cli.command else {
            panic!("render");
        };
        assert_eq!(
            r.scene.light.unwrap().position,
            glam::Vec3::new(-1.0, 2.0, 0.0)
        );
        // A path option still needs its value.
        let e = error(&["render", "--out", "--frames", "2"]);
        assert!(e.contains("--out"), "{e}");
    }

    #[test]
    fn a_non_utf8_argument_is_named() {
        let bad = OsString::from_vec(b"sc\xe8ne.obj".to_vec());
        let args = [
            OsString::from("ssgi"),
            "render".into(),
            "--scene".into(),
            bad,
        ];
        let e = try_parse_from(args).err().unwrap().to_string();
        assert!(
            e.contains(
                "argument 3 (the value of --scene) is not valid UTF-8: \"sc\u{fffd}ne.obj\""
            ),
            "{e}"
        );
    }
}

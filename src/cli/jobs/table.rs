//! `ssgi table <name>`: measure one of the tables of `bench::tables::TABLES`, offscreen or
//! presented, and write its report, CSV and plots.

use super::common::{context_options, finish};
use crate::bench::tables::{find, TableDef};
use crate::bench::warmup::Warmup;
use crate::bench::TableOptions;
use crate::cli::args::{Cli, TableArgs};
use crate::config::{Effects, RenderConfig};
use crate::error::{Error, Result};
use crate::frontend::window_sink::open_sink;
use crate::scene::asset_dir_from_env;
use crate::sweep::keys::{find_key, Key};
use std::path::PathBuf;

/// Most frames a table accepts per row (a typo guard, as for `bench`).
const MAX_FRAMES: u32 = 1_000_000;

/// The command line as typed (arguments with spaces quoted).
fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if a.contains(char::is_whitespace) {
                format!("'{a}'")
            } else {
                a
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A table's `--set` keys as a user reads them: a prefix `svgf.` as `svgf.*`.
fn settable_keys(def: &TableDef) -> String {
    def.settable
        .iter()
        .map(|k| match k.strip_suffix('.') {
            Some(prefix) => format!("{prefix}.*"),
            None => k.to_string(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// `--set KEY=VALUE`s: sweep keys the table lets change, each value checked as `--vary`'s.
fn sets(def: &TableDef, given: &[String]) -> Result<Vec<(Key, String)>> {
    let mut sets: Vec<(Key, String)> = Vec::new();
    for s in given {
        let (name, value) = s.split_once('=').ok_or_else(|| {
            Error::Config(format!(
                "--set takes KEY=VALUE, not {:?} (no '=')",
                s.trim()
            ))
        })?;
        let name = name.trim();
        let key = find_key(name).ok_or_else(|| {
            Error::Config(format!(
                "--set {name:?}: no such key (`ssgi sweep --list-keys` lists them)"
            ))
        })?;
        if !def.settable(key.name) {
            return Err(Error::Config(if def.settable.is_empty() {
                let takers: Vec<String> = crate::bench::tables::TABLES
                    .iter()
                    .filter(|t| !t.settable.is_empty())
                    .map(|t| format!("{}: {}", t.name, settable_keys(t)))
                    .collect();
                format!(
                    "table {} takes no --set keys (its rows set every parameter they use); the \
                     tables that take --set: {}",
                    def.name,
                    takers.join("; ")
                )
            } else {
                format!(
                    "table {} sets {key} itself or does not use it: its --set keys are {}",
                    def.name,
                    settable_keys(def)
                )
            }));
        }
        if sets.iter().any(|(k, _)| *k == key) {
            return Err(Error::Config(format!("--set {key} is given twice")));
        }
        let value = value.trim().to_string();
        (key.set)(&mut RenderConfig::default(), &value).map_err(|why| {
            Error::Config(format!(
                "--set {key}={value}: {why}; expected {}",
                key.syntax
            ))
        })?;
        sets.push((key, value));
    }
    Ok(sets)
}

pub fn table(cli: &Cli, args: &TableArgs) -> Result<()> {
    let def = find(&args.table)
        .ok_or_else(|| Error::Config(format!("no table called {}", args.table)))?;
    let size = args.size.unwrap_or(def.size);
    let frames = args.frames.unwrap_or(def.frames);
    let warmup = args.warmup.unwrap_or(def.warmup);
    if def.effects.is_none() && args.effects.is_some() {
        return Err(Error::Config(format!(
            "{}'s rows choose their effects: leave out --effects",
            def.name
        )));
    }
    let warmup_frames = match warmup {
        Warmup::Frames(n) => n,
        Warmup::Converged => 0,
    };
    if frames == 0 || frames > MAX_FRAMES || warmup_frames > MAX_FRAMES {
        return Err(Error::Config(format!(
            "--frames must be in 1..={MAX_FRAMES} and --warmup at most {MAX_FRAMES}"
        )));
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(def.name));
    let opts = TableOptions {
        size,
        sizes: def.sizes(args.size),
        frames,
        warmup,
        fps: args.fps,
        path: args.path.clone(),
        effects: args.effects.or(def.effects).unwrap_or(Effects::ALL),
        assets: cli.assets.clone().or_else(asset_dir_from_env),
        progress: true,
        command: command_line(),
        sets: sets(def, &args.set)?,
    };
    let window = args.window.then(|| format!("ssgi table {}", def.name));
    let (ctx, mut sink) = open_sink(window, size, context_options(cli))?;
    let written = (def.run)(&ctx, sink.as_mut(), &opts, &out)?;
    if sink.present_mode().is_some() {
        eprintln!("presented {} frames to the window", sink.frames_presented());
    }
    drop(sink);
    for path in written {
        eprintln!("wrote {}", path.display());
    }
    finish(&ctx)
}

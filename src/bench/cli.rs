//! `ssgi table <thesis-4.1|thesis-walkthroughs>`: arguments and the job.

use super::options::TableOptions;
use super::{output, table41, walkthrough};
use crate::cli::{context_options, parse_size, Cli};
use crate::error::{Error, Result};
use crate::frontend::sink;
use crate::renderer::config::Effects;
use crate::scene::asset_dir_from_env;
use clap::{Args, ValueEnum};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TableName {
    /// Venus, Dragon, Bunny, Buddha in a box: reuse vs no reuse (thesis Table 4.1).
    #[value(name = "thesis-4.1")]
    Thesis41,
    /// Sponza, Sibenik, Conference walkthroughs, per-frame (thesis Tables 4.2-4.4, Fig. 4.10).
    #[value(name = "thesis-walkthroughs")]
    ThesisWalkthroughs,
}

impl TableName {
    pub fn name(self) -> &'static str {
        match self {
            TableName::Thesis41 => "thesis-4.1",
            TableName::ThesisWalkthroughs => "thesis-walkthroughs",
        }
    }

    fn title(self) -> &'static str {
        match self {
            TableName::Thesis41 => {
                "Thesis Table 4.1: reuse vs no reuse (Venus, Dragon, Bunny, Buddha in a box)"
            }
            TableName::ThesisWalkthroughs => {
                "Thesis Tables 4.2-4.4 and Figure 4.10: Sponza, Sibenik and Conference walkthroughs"
            }
        }
    }
}

#[derive(Args, Debug)]
pub struct TableArgs {
    /// Which table.
    #[arg(value_enum)]
    pub table: TableName,
    /// Output directory for report.md, report.json, CSV and PNG files (default out/<table>).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "512x512", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Frames measured per row along the camera path.
    #[arg(long, default_value_t = 120)]
    pub frames: u32,
    /// Frames rendered first at the path's first camera and left out of the statistics.
    #[arg(long, default_value_t = 10)]
    pub warmup: u32,
    /// thesis-4.1: static, orbit, dolly, or a keyframe file, for all four scenes (default:
    /// paths/box.json, compiled in). thesis-walkthroughs: a directory holding sponza.json,
    /// sibenik.json and conference.json (default: those of paths/, compiled in).
    #[arg(long, value_name = "P")]
    pub path: Option<String>,
    /// Effects to render, comma-separated: direct, ao, indirect (or all). Leaving one out drops
    /// its columns (e.g. `direct,ao` on a slow device).
    #[arg(long, default_value = "all", value_parser = Effects::parse)]
    pub effects: Effects,
    /// Present every frame to a window (present mode immediate, else mailbox, else fifo) and
    /// time that; Escape or closing the window aborts the table.
    #[arg(long)]
    pub window: bool,
}

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

pub fn run(cli: &Cli, args: &TableArgs) -> Result<()> {
    if args.frames == 0 || args.frames > MAX_FRAMES || args.warmup > MAX_FRAMES {
        return Err(Error::Config(format!(
            "--frames must be in 1..={MAX_FRAMES} and --warmup at most {MAX_FRAMES}"
        )));
    }
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(args.table.name()));
    let opts = TableOptions {
        size: args.size,
        frames: args.frames,
        warmup: args.warmup,
        path: args.path.clone(),
        effects: args.effects,
        assets: cli.assets.clone().or_else(asset_dir_from_env),
        progress: true,
        command: command_line(),
    };
    let window = args
        .window
        .then(|| format!("ssgi table {}", args.table.name()));
    let (ctx, mut sink) = sink::open(window, args.size, context_options(cli))?;
    let (mut report, extra_md) = match args.table {
        TableName::Thesis41 => (table41::run(&ctx, sink.as_mut(), &opts)?, ""),
        TableName::ThesisWalkthroughs => (
            walkthrough::run(&ctx, sink.as_mut(), &opts, &out)?,
            super::markdown::WALKTHROUGH_LEGEND,
        ),
    };
    if sink.present_mode().is_some() {
        eprintln!("presented {} frames to the window", sink.frames_presented());
    }
    drop(sink);
    let images = output::write_last_frames(&out, &report)?;
    for (scene, names) in report.scenes.iter_mut().zip(images) {
        scene.files.extend(names);
    }
    for path in output::write_report(&out, &report, args.table.title(), extra_md)? {
        eprintln!("wrote {}", path.display());
    }
    ctx.wait_idle()?;
    match ctx.validation() {
        Some(log) => log.check(),
        None => Ok(()),
    }
}

//! `ssgi table <thesis-4.1|thesis-walkthroughs|szentandrasi-1|sraa|chang-1|chang-flicker|dynamic>`: measure a table's rows,
//! offscreen or presented, and write its report, CSV and plots.

use super::common::{context_options, finish};
use crate::bench::markdown::WALKTHROUGH_LEGEND;
use crate::bench::warmup::Warmup;
use crate::bench::{
    output, table41, table_chang, table_chang_flicker, table_dynamic, table_sraa,
    table_szentandrasi, walkthrough, TableOptions,
};
use crate::cli::args::{Cli, TableArgs, TableName};
use crate::config::Effects;
use crate::error::{Error, Result};
use crate::frontend::window_sink::open_sink;
use crate::scene::asset_dir_from_env;
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

pub fn table(cli: &Cli, args: &TableArgs) -> Result<()> {
    let (default_size, default_frames, default_warmup) = args.table.defaults();
    let size = args.size.unwrap_or(default_size);
    let frames = args.frames.unwrap_or(default_frames);
    let warmup = args.warmup.unwrap_or(default_warmup);
    if args.table == TableName::Szentandrasi1 && args.effects.is_some() {
        return Err(Error::Config(
            "szentandrasi-1's rows choose their effects (direct light and SSDO): leave out \
             --effects"
                .into(),
        ));
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
        .unwrap_or_else(|| PathBuf::from("out").join(args.table.name()));
    let opts = TableOptions {
        size,
        frames,
        warmup,
        fps: args.fps,
        path: args.path.clone(),
        effects: args.effects.unwrap_or(match args.table {
            TableName::Sraa => Effects {
                direct: true,
                ..Effects::NONE
            },
            TableName::Chang1 => Effects {
                indirect: true,
                ..Effects::NONE
            },
            TableName::ChangFlicker => Effects {
                direct: true,
                indirect: true,
                ..Effects::NONE
            },
            _ => Effects::ALL,
        }),
        assets: cli.assets.clone().or_else(asset_dir_from_env),
        progress: true,
        command: command_line(),
    };
    let window = args
        .window
        .then(|| format!("ssgi table {}", args.table.name()));
    let (ctx, mut sink) = open_sink(window, size, context_options(cli))?;
    let (mut report, extra_md) = match args.table {
        TableName::Thesis41 => (table41::run(&ctx, sink.as_mut(), &opts)?, ""),
        TableName::ThesisWalkthroughs => (
            walkthrough::run(&ctx, sink.as_mut(), &opts, &out)?,
            WALKTHROUGH_LEGEND,
        ),
        TableName::Dynamic => (
            table_dynamic::run(&ctx, sink.as_mut(), &opts, &out)?,
            WALKTHROUGH_LEGEND,
        ),
        // Its own report (rows of configurations, not reuse vs no reuse).
        TableName::Szentandrasi1 => {
            let written = table_szentandrasi::run(&ctx, sink.as_mut(), &opts, &out)?;
            if sink.present_mode().is_some() {
                eprintln!("presented {} frames to the window", sink.frames_presented());
            }
            drop(sink);
            for path in written {
                eprintln!("wrote {}", path.display());
            }
            return finish(&ctx);
        }
        TableName::Sraa => {
            let sizes: Vec<(u32, u32)> = match args.size {
                Some(size) => vec![size],
                None => table_sraa::SIZES.iter().map(|&s| (s, s)).collect(),
            };
            let written = table_sraa::run(&ctx, sink.as_mut(), &opts, &sizes, &out)?;
            drop(sink);
            for path in written {
                eprintln!("wrote {}", path.display());
            }
            return finish(&ctx);
        }
        TableName::Chang1 => {
            let sizes = match args.size {
                Some(size) => vec![size],
                None => table_chang::SIZES.to_vec(),
            };
            let written = table_chang::run(&ctx, sink.as_mut(), &opts, &sizes, &out)?;
            drop(sink);
            for path in written {
                eprintln!("wrote {}", path.display());
            }
            return finish(&ctx);
        }
        TableName::ChangFlicker => {
            let written = table_chang_flicker::run(&ctx, sink.as_mut(), &opts, &out)?;
            drop(sink);
            for path in written {
                eprintln!("wrote {}", path.display());
            }
            return finish(&ctx);
        }
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
    finish(&ctx)
}

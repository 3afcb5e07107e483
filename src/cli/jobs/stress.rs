//! `ssgi stress`: the numerical-stability matrix (`bench::stress`), with validation on; prints
//! a line per case and the table, writes stress.json and stress.md, and fails when any case did.

use super::common::context_options;
use crate::cli::args::{Cli, StressArgs};
use crate::error::{Error, Result};
use crate::files::write_atomic;
use crate::renderer::MAX_SIZE;
use crate::stress::{run_plan, StressOptions, StressReport};
use crate::vk::Context;

/// Long-run frames without `--long-frames`: the 100,000, or 2,000 for the quick subset.
const LONG_FRAMES: u64 = 100_000;
const QUICK_LONG_FRAMES: u64 = 2_000;

pub fn stress(cli: &Cli, args: &StressArgs) -> Result<()> {
    if args.rsm_size == 0 || args.rsm_size > MAX_SIZE {
        return Err(Error::Config(format!(
            "--rsm-size {} is outside 1..={MAX_SIZE}",
            args.rsm_size
        )));
    }
    crate::files::prepare_dir(&args.out, "--out")?;
    let options = StressOptions {
        quick: args.quick,
        long_frames: args.long_frames.unwrap_or(if args.quick {
            QUICK_LONG_FRAMES
        } else {
            LONG_FRAMES
        }),
        only: args.only.clone(),
        rsm_size: args.rsm_size,
        ao_estimator: args.ao_estimator,
    };
    // Validation is part of what is checked: always on.
    let mut context = context_options(cli);
    context.validation = true;
    let ctx = Context::new(&context)?;
    let results = run_plan(&ctx, &options)?;
    if results.is_empty() {
        return Err(Error::Config(format!(
            "--only {:?} matches no stress case",
            args.only.as_deref().unwrap_or("")
        )));
    }
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let report = StressReport::new(command, &ctx.info, args.quick, results);
    let md = report.markdown();
    let json = serde_json::to_string_pretty(&report)
        .map_err(|e| Error::Config(format!("JSON encoding failed: {e}")))?;
    write_atomic(&args.out.join("stress.json"), json.as_bytes())?;
    write_atomic(&args.out.join("stress.md"), md.as_bytes())?;
    println!("{md}");
    eprintln!("wrote {}/stress.json and stress.md", args.out.display());
    let t = &report.totals;
    if t.failures > 0 {
        return Err(Error::Config(format!(
            "{} of {} stress cases failed (see {}/stress.md)",
            t.failures,
            t.cases,
            args.out.display()
        )));
    }
    Ok(())
}

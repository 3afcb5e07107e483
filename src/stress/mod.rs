//! `ssgi stress`: the numerical-stability matrix. Every case (scales, depth ranges, awkward
//! cameras and lights, degenerate geometry, tiny sizes, rotation-limit bounds, a long jittering
//! run) is rendered under every effect set and both reuse modes; after its frames every float
//! target and history is audited on the GPU (NaN, Inf, negative values, largest history
//! value and count), the converged view is compared with a fresh convergence, and the
//! validation messages it caused are counted. Any of those failing fails the run.

pub mod cases;
pub mod report;
pub mod run;

pub use cases::{drift_tolerance, matrix, Case, Program, Variant, DRIFT_TOLERANCE};
pub use report::{CaseResult, StressReport};
pub use run::run_case;

use crate::effects::ao::config::AoEstimator;
use crate::error::Result;
use crate::vk::Context;
use std::sync::Arc;

/// What to run.
#[derive(Clone, Debug)]
pub struct StressOptions {
    /// The small end of every kind of case, one variant each but the first case's (the tests'
    /// subset); otherwise every case under every variant.
    pub quick: bool,
    pub long_frames: u64,
    /// Only cases whose name contains this.
    pub only: Option<String>,
    pub rsm_size: u32,
    /// The AO estimator of the variants with AO.
    pub ao_estimator: AoEstimator,
}

/// The (case, variant) pairs of a run: every variant of every case, or in quick mode the
/// variants taken in turn (so each still runs somewhere) and every variant of the first case.
pub fn plan(options: &StressOptions) -> Vec<(Case, Variant)> {
    let cases = matrix(options.quick, options.long_frames);
    let wanted = |c: &Case| {
        options
            .only
            .as_ref()
            .is_none_or(|o| c.name.contains(o.as_str()))
    };
    let variants = Variant::all();
    let mut plan = Vec::new();
    for (i, case) in cases.into_iter().filter(wanted).enumerate() {
        if options.quick && i > 0 {
            plan.push((case, variants[i % variants.len()]));
        } else {
            for v in variants.iter().copied() {
                plan.push((case.clone(), v));
            }
        }
    }
    plan
}

/// Run the plan on `ctx`, printing a line per row as it finishes; Ctrl-C stops it between
/// frames with `Error::Interrupted` (the unfinished matrix has no report).
pub fn run_plan(ctx: &Arc<Context>, options: &StressOptions) -> Result<Vec<CaseResult>> {
    let plan = plan(options);
    let total = plan.len();
    let mut results = Vec::with_capacity(total);
    // Each case's frames, and the loop between cases, poll for Ctrl-C.
    let _scope = crate::interrupt::graceful();
    for (k, (case, variant)) in plan.iter().enumerate() {
        let r = run_case(ctx, case, *variant, options.rsm_size, options.ao_estimator);
        crate::interrupt::check()?;
        eprintln!("[{:>3}/{total}] {}", k + 1, StressReport::line(&r));
        results.push(r);
    }
    Ok(results)
}

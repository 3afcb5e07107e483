//! Running one case of the stress matrix under one variant (effect set x reuse mode): the
//! camera program, the numerical audits of every target and history, the drift of the
//! converged view against a freshly converged one, and the validation messages it caused.

use super::cases::{
    drift_tolerance, Case, LongRun, Program, Variant, MOVING_FRAMES, STATIC_FRAMES,
    TURN_DEG_PER_FRAME,
};
use super::report::CaseResult;
use crate::config::Accumulate;
use crate::effects::ao::config::AoEstimator;
use crate::error::Result;
use crate::frontend::progress::Progress;
use crate::renderer::audit::AuditKind;
use crate::renderer::{RenderConfig, Renderer};
use crate::resources::random::Rng;
use crate::resources::targets::Target;
use crate::scene::Camera;
use crate::vk::{Context, ImageData};
use glam::{Quat, Vec3};
use std::sync::Arc;
use std::time::Instant;

/// Most host-memory growth per frame the long run may show after its first tenth (bytes): what
/// a leak of one small allocation per frame would pass, far below what a driver keeping a
/// recompiled shader per frame shows (0.6-2.5 MB).
pub const MAX_GROWTH_PER_FRAME: f64 = 4096.0;

/// Frames of the static hold beyond the rotation limit: every accumulating pixel receives all
/// its patterns, and the frames in flight are done.
const HOLD_EXTRA: u32 = 4;

/// Run `case` under `variant` on `ctx`; every failure is in the result, not an error.
pub fn run_case(
    ctx: &Arc<Context>,
    case: &Case,
    variant: Variant,
    rsm_size: u32,
    ao_estimator: AoEstimator,
) -> CaseResult {
    let start = Instant::now();
    let before = ctx.validation().map_or(0, |log| log.count());
    let mut base = variant.config(rsm_size);
    base.ao.estimator = ao_estimator;
    let config = case.config(&base);
    let mut result = CaseResult::new(case, variant, &config);
    if let Err(e) = drive(ctx, case, config, &mut result) {
        result.fail(format!("error: {e}"));
    }
    if let Err(e) = ctx.wait_idle() {
        result.fail(format!("error: {e}"));
    }
    if let Some(log) = ctx.validation() {
        let messages = log.messages();
        let new = &messages[before.min(messages.len())..];
        result.validation_messages = new.len();
        if let Some(first) = new.first() {
            result.fail(format!(
                "{} validation message(s), first: {first}",
                new.len()
            ));
        }
    }
    result.seconds = start.elapsed().as_secs_f64();
    result
}

fn drive(
    ctx: &Arc<Context>,
    case: &Case,
    config: RenderConfig,
    result: &mut CaseResult,
) -> Result<()> {
    let mut r = Renderer::new(ctx, case.scene.clone(), config)?;
    let last = match case.program {
        Program::Short => {
            let base = case.scene.camera;
            for i in 0..STATIC_FRAMES + MOVING_FRAMES {
                let turn = i.saturating_sub(STATIC_FRAMES) as f32 * TURN_DEG_PER_FRAME;
                r.render_frame(&turned(&base, turn))?;
                result.frames += 1;
            }
            audit(&mut r, result)?;
            turned(&base, MOVING_FRAMES as f32 * TURN_DEG_PER_FRAME)
        }
        Program::Long(run) => long_run(&mut r, case, &run, result)?,
    };
    drift(&mut r, &last, result)
}

/// `base` turned by `deg` degrees about the vertical through its target.
fn turned(base: &Camera, deg: f32) -> Camera {
    let q = Quat::from_rotation_y(deg.to_radians());
    Camera {
        position: base.target + q * (base.position - base.target),
        ..*base
    }
}

/// The long program: jitter every frame, now and then a cut between two views, a resize
/// between two sizes, a light move. Returns the last view.
fn long_run(
    r: &mut Renderer,
    case: &Case,
    run: &LongRun,
    result: &mut CaseResult,
) -> Result<Camera> {
    let LongRun {
        frames,
        audit_every,
        cut_every,
        resize_every,
        light_every,
    } = *run;
    let base = case.scene.camera;
    let views = [base, turned(&base, 40.0)];
    let sizes = [case.size, (case.size.0.max(2) - 1, case.size.1 + 3)];
    let light = case.scene.light;
    let reach = 0.05 * base.position.distance(base.target);
    let mut rng = Rng::new(0x5eed_57e5);
    let mut jitter = |scale: f32| {
        Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 * scale - scale
    };
    let mut progress = Progress::new(frames, &format!("{} long run", case.name), true);
    let mut view = 0;
    let mut camera = base;
    // Host memory from the end of the first tenth (allocators and caches warmed up) to the end.
    let measure_from = frames / 10;
    let mut rss_start = None;
    for i in 0..frames {
        if i == measure_from {
            rss_start = resident_bytes();
        }
        if i > 0 && i % cut_every == 0 {
            view ^= 1;
        }
        if i > 0 && i % resize_every == 0 {
            let (w, h) = sizes[((i / resize_every) % 2) as usize];
            r.resize(w, h)?;
            result.resizes += 1;
        }
        if i > 0 && i % light_every == 0 {
            let mut l = light;
            l.position += jitter(4.0 * reach) * Vec3::new(1.0, 0.0, 1.0);
            r.set_light(l);
        }
        let v = views[view];
        let d = jitter(0.2 * reach);
        camera = Camera {
            position: v.position + d,
            target: v.target + d + jitter(reach),
            ..v
        };
        r.render_frame(&camera)?;
        result.frames += 1;
        if (i + 1) % audit_every == 0 || i + 1 == frames {
            audit(r, result)?;
        }
        progress.inc();
    }
    progress.finish();
    let measured = frames - measure_from;
    if let (Some(start), Some(end)) = (rss_start, resident_bytes()) {
        if measured > 0 {
            let growth = (end as f64 - start as f64) / measured as f64;
            result.memory_growth_per_frame = Some(growth);
            if growth > MAX_GROWTH_PER_FRAME {
                result.fail(format!(
                    "host memory grew {:.0} bytes per frame over the last {measured} frames \
                     (bound {MAX_GROWTH_PER_FRAME})",
                    growth
                ));
            }
        }
    }
    Ok(camera)
}

/// The process's resident memory (Linux `VmRSS`), if the platform tells.
fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Audit every target and history and fold the figures into `result`. A history holds at most
/// the rotation limit's patterns, or with the gated mean twice that: a pixel whose mean
/// restarted takes the limit's patterns again before it counts as converged (reproject.comp's
/// `converged`); more would be a mean that keeps restarting on a still view, or a runaway count.
fn audit(r: &mut Renderer, result: &mut CaseResult) -> Result<()> {
    let gated = matches!(r.config.temporal.accumulate, Accumulate::Gated { .. });
    let limit = r.config.temporal.rotation_limit as f32 * if gated { 2.0 } else { 1.0 };
    for a in r.audit()? {
        result.audits += 1;
        result.values_checked += a.texels as u64 * a.channels as u64;
        result.nan += a.nan as u64;
        result.inf += a.inf as u64;
        result.negative += a.negative as u64;
        if a.bad_values() > 0 {
            result.fail(format!(
                "{}: {} NaN, {} infinite, {} negative values",
                a.name, a.nan, a.inf, a.negative
            ));
        }
        if a.kind == AuditKind::History {
            let value = a.max_abs[..3].iter().fold(0.0f32, |m, v| m.max(*v));
            result.max_history_value = result.max_history_value.max(value);
            result.max_history_count = result.max_history_count.max(a.max_abs[3]);
            if a.max_abs[3] > limit {
                result.fail(format!(
                    "{}: {} estimates, more than {limit} (the rotation limit, twice with the \
                     gated mean)",
                    a.name, a.max_abs[3]
                ));
            }
        }
    }
    Ok(())
}

/// Hold `camera` until every accumulating pixel has all its patterns, audit, then converge the
/// same view from scratch and compare the two outputs.
fn drift(r: &mut Renderer, camera: &Camera, result: &mut CaseResult) -> Result<()> {
    let hold = r.config.temporal.rotation_limit + HOLD_EXTRA;
    let converge = |r: &mut Renderer, result: &mut CaseResult| -> Result<ImageData> {
        for _ in 0..hold {
            r.render_frame(camera)?;
            result.frames += 1;
        }
        r.finish()?;
        r.read(Target::Output)
    };
    let kept = converge(r, result)?;
    audit(r, result)?;
    r.reset_history();
    let fresh = converge(r, result)?;
    let rmse = output_rmse(&kept, &fresh);
    result.drift_rmse = Some(rmse);
    let bound = drift_tolerance(r.config.temporal.rotation_limit);
    // A NaN RMSE (no comparable output) fails too.
    if rmse.is_nan() || rmse > bound {
        result.fail(format!(
            "converged view drifted: RMSE {rmse:.4} against a fresh convergence (bound \
             {bound:.4})"
        ));
    }
    Ok(())
}

/// RMSE of the RGB channels of two RGBA8 images of one size, in 0..1.
fn output_rmse(a: &ImageData, b: &ImageData) -> f32 {
    let (Some(a), Some(b)) = (a.rgba8(), b.rgba8()) else {
        return f32::NAN;
    };
    if a.len() != b.len() || a.is_empty() {
        return f32::NAN;
    }
    let mut sum = 0.0f64;
    let mut n = 0u64;
    for (pa, pb) in a.chunks_exact(4).zip(b.chunks_exact(4)) {
        for c in 0..3 {
            let d = (pa[c] as f64 - pb[c] as f64) / 255.0;
            sum += d * d;
            n += 1;
        }
    }
    (sum / n as f64).sqrt() as f32
}

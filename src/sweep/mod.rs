//! `ssgi sweep`: every combination of the varied configuration keys, measured in one process
//! on one device along the same camera path (after a warmup that reaches steady state), each
//! with its median GPU time per pass group and the error of its last frame against the CPU
//! ground truth and against the converged estimator of the same technique.

pub mod answers;
pub mod keys;
pub mod report;

use crate::bench::compare::{group_median, groups};
use crate::bench::ground_truth::{self, reference_buffer, FrameError, TruthQuality};
use crate::bench::measure::{held_at, last_camera, measure, Buffer, LastFrame, RunSpec};
use crate::bench::tables::reuse::rows::{RowKind, REFERENCE_FRAMES};
use crate::error::{Error, Result};
use crate::frontend::sink::Offscreen;
use crate::reference::run::Session;
use crate::renderer::RenderConfig;
use crate::scene::{CameraPath, Scene};
use crate::vk::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use keys::{describe, Label};
use serde::Serialize;
use std::collections::BTreeMap;
use std::rc::Rc;
use std::sync::Arc;

/// One combination's result.
#[derive(Serialize)]
pub struct SweepRow {
    /// The varied keys and values, in --vary order.
    pub label: Vec<(String, String)>,
    pub config: RenderConfig,
    /// Median per-frame GPU milliseconds of each pass group (`compare::groups`).
    pub ms: BTreeMap<String, Option<f64>>,
    /// Median GPU milliseconds of each pass over the measured frames in which it ran.
    pub passes: BTreeMap<String, Option<f64>>,
    /// Per buffer: error against the ground truth.
    pub truth: BTreeMap<String, FrameError>,
    /// Per buffer: error against the converged estimator (same technique, many samples).
    pub converged: BTreeMap<String, FrameError>,
    /// Per buffer: whether this row is on the Pareto front of (time, ground-truth error).
    pub pareto: BTreeMap<String, bool>,
    /// The work counters had settled by the end of the warmup (`warmup::settled`).
    pub warmup_settled: bool,
    #[serde(skip)]
    pub last: Option<LastFrame>,
    /// The converged estimator's frame this row was compared with (shared between rows).
    #[serde(skip)]
    pub converged_last: Option<Rc<LastFrame>>,
}

pub struct SweepSpec<'a> {
    pub scene: &'a Scene,
    pub path: &'a CameraPath,
    pub frames: u32,
    pub warmup: u32,
    /// Warm up along the path before its time 0 (`RunSpec::warmup_along_path`).
    pub warmup_along_path: bool,
    pub fps: f32,
    pub combinations: Vec<(Label, RenderConfig)>,
    pub progress: bool,
}

/// The pass groups the Pareto front and the plots use for a buffer's time axis: its effect's
/// (the whole frame for the final image). Ambient visibility comes from whichever effect
/// darkens the ambient light (`effects::ambient_groups`); they are exclusive, so a row ran one
/// of those groups.
pub fn time_group(b: Buffer) -> Vec<&'static str> {
    match b {
        Buffer::Final => vec!["total"],
        Buffer::Ao => crate::effects::ambient_groups(),
        Buffer::Shadow => vec!["shadow"],
        Buffer::Direct => vec!["shadow", "direct"],
        Buffer::Indirect => vec!["indirect"],
    }
}

/// Milliseconds of `b`'s time axis in `row` (None if a group never ran).
pub fn time_of(row: &SweepRow, b: Buffer) -> Option<f64> {
    time_from(|g| row.ms.get(g).copied().flatten(), b)
}

/// Milliseconds of `b`'s time axis from each group's (`group_ms`; None: it never ran).
pub fn time_from(group_ms: impl Fn(&str) -> Option<f64>, b: Buffer) -> Option<f64> {
    let ms = |g: &&str| group_ms(g);
    if b == Buffer::Ao {
        return time_group(b).iter().find_map(ms);
    }
    time_group(b).iter().map(ms).sum()
}

/// The time axis's name: the groups summed (`shadow + direct`), or either one for AO.
pub fn time_label(b: Buffer) -> String {
    time_group(b).join(if b == Buffer::Ao { " or " } else { " + " })
}

/// The error a buffer's front is drawn over: FLIP for the final image, RMSE otherwise.
pub fn error_of(row: &SweepRow, b: Buffer) -> Option<f64> {
    let e = row.truth.get(b.name())?;
    match b {
        Buffer::Final => e.flip,
        _ => Some(e.error.rmse),
    }
}

/// Run every combination, then the converged estimators, then refine the ground truth until
/// its standard error is under a tenth of the smallest error, and score every row.
pub fn run(
    ctx: &Arc<Context>,
    spec: &SweepSpec<'_>,
    truth: &mut Session<'_>,
) -> Result<(Vec<SweepRow>, BTreeMap<String, TruthQuality>)> {
    let scene = spec.scene;
    let frames = spec.frames.max(1);
    let held = held_at(&last_camera(scene, spec.path, frames, spec.fps));
    let total = spec.combinations.len() as u64;
    let bar = progress_bar(total, spec.progress);
    let mut rows = Vec::new();
    let mut converged: Vec<(RenderConfig, Rc<LastFrame>)> = Vec::new();
    for (label, config) in &spec.combinations {
        let text = describe(label);
        bar.set_message(if text.is_empty() {
            "base".into()
        } else {
            text.clone()
        });
        let measured = measure(
            ctx,
            &mut Offscreen,
            scene,
            &RunSpec {
                label: &text,
                config: *config,
                path: spec.path,
                frames,
                warmup: spec.warmup,
                warmup_along_path: spec.warmup_along_path,
                fps: spec.fps,
                snapshot_after_warmup: false,
                flicker: false,
                progress: false,
            },
        )?;
        // The converged estimator of this technique (shared by combinations that differ only
        // in what convergence removes: reuse, sample counts per frame, ...).
        let cc = RowKind::Reference.config(config);
        if !converged.iter().any(|(c, _)| *c == cc) {
            let mut m = measure(
                ctx,
                &mut Offscreen,
                scene,
                &RunSpec {
                    label: "converged",
                    config: cc,
                    path: &held,
                    frames: REFERENCE_FRAMES,
                    warmup: 1,
                    warmup_along_path: false,
                    fps: spec.fps,
                    snapshot_after_warmup: true,
                    flicker: false,
                    progress: false,
                },
            )?;
            let first = m
                .after_warmup
                .take()
                .ok_or_else(|| Error::Config("the converged run kept no frame".into()))?;
            converged.push((cc, Rc::new(first)));
        }
        let ms = groups()
            .iter()
            .map(|(name, passes)| (name.to_string(), group_median(&measured.report, passes)))
            .collect();
        let passes = measured
            .report
            .passes
            .iter()
            .map(|p| (p.name.clone(), p.median_ms))
            .collect();
        let conv = converged
            .iter()
            .find(|(c, _)| *c == cc)
            .expect("inserted above")
            .1
            .clone();
        rows.push(SweepRow {
            label: label
                .iter()
                .map(|(k, v)| (k.name.to_string(), v.clone()))
                .collect(),
            config: *config,
            ms,
            passes,
            truth: BTreeMap::new(),
            converged: ground_truth::errors_against(&measured.last, &conv)?
                .into_iter()
                .map(|(b, e)| (b.name().to_string(), e))
                .collect(),
            pareto: BTreeMap::new(),
            warmup_settled: measured.warmup_settled,
            last: Some(measured.last),
            converged_last: Some(conv),
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    score(&mut rows, scene, truth)?;
    let quality = refine_truth(&mut rows, scene, truth)?;
    score(&mut rows, scene, truth)?;
    mark_pareto(&mut rows);
    Ok((rows, quality))
}

fn score(rows: &mut [SweepRow], scene: &Scene, truth: &Session<'_>) -> Result<()> {
    for row in rows {
        let Some(last) = &row.last else { continue };
        row.truth = ground_truth::errors(
            last,
            &truth.reference,
            scene,
            crate::effects::estimated_terms(&row.config),
        )?
        .into_iter()
        .map(|(b, e)| (b.name().to_string(), e))
        .collect();
    }
    Ok(())
}

/// Refine each ground-truth buffer until its standard error is at most a tenth of the
/// smallest RMSE any row has against it (the final image follows from the buffers).
fn refine_truth(
    rows: &mut [SweepRow],
    scene: &Scene,
    truth: &mut Session<'_>,
) -> Result<BTreeMap<String, TruthQuality>> {
    let mut quality = BTreeMap::new();
    for b in [Buffer::Ao, Buffer::Shadow, Buffer::Direct, Buffer::Indirect] {
        let Some(rb) = reference_buffer(b) else {
            continue;
        };
        let smallest =
            ground_truth::smallest_rmse(rows.iter().filter_map(|r| r.truth.get(b.name())));
        let geometry = rows
            .iter()
            .find_map(|r| r.last.as_ref())
            .map(|l| ground_truth::mask(b, &truth.reference, scene, &l.geometry));
        let (bound, met) = match (smallest, &geometry) {
            (Some(smallest), Some(m)) => {
                let bound = smallest / 10.0;
                (Some(bound), truth.refine_to(rb, bound, m)?)
            }
            _ => (None, true),
        };
        let e = truth.reference.estimate(rb);
        let se = geometry.as_ref().map_or(0.0, |m| e.standard_error(m));
        quality.insert(
            b.name().to_string(),
            TruthQuality {
                samples_per_pixel: 2 * e.per_half as u64,
                standard_error: se,
                bound,
                bound_met: met,
            },
        );
    }
    Ok(quality)
}

/// Every row's (time axis, error) for buffer `b`; NaN where a row lacks one.
pub fn points(rows: &[SweepRow], b: Buffer) -> Vec<(f64, f64)> {
    rows.iter()
        .map(|r| {
            (
                time_of(r, b).unwrap_or(f64::NAN),
                error_of(r, b).unwrap_or(f64::NAN),
            )
        })
        .collect()
}

/// Mark each row's Pareto optimality per buffer over (time axis, ground-truth error).
pub fn mark_pareto(rows: &mut [SweepRow]) {
    for b in Buffer::ALL {
        let points = points(rows, b);
        let front = crate::plot::pareto::pareto_front(&points);
        for (row, (on, p)) in rows.iter_mut().zip(front.into_iter().zip(&points)) {
            if p.0.is_finite() && p.1.is_finite() {
                row.pareto.insert(b.name().to_string(), on);
            }
        }
    }
}

fn progress_bar(total: u64, enabled: bool) -> ProgressBar {
    let target = if enabled {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(total), target);
    if let Ok(style) =
        ProgressStyle::with_template("sweep [{bar:30}] {pos}/{len} combinations (eta {eta}): {msg}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

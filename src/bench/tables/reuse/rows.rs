//! The rows every table has for a scene: reuse, no reuse + 5x5 blur, and the converged
//! reference, each measured on one context along the same camera path, with the error of its
//! last frame against the reference rendered from the same camera.

use crate::bench::compare::{group_median, groups, in_group};
use crate::bench::ground_truth::{self, FrameError, TruthQuality};
use crate::bench::measure::{held_at, last_camera, measure, Buffer, LastFrame, Measured, RunSpec};
use crate::bench::metrics::{image_error, ImageError};
use crate::bench::report::FrameRow;
use crate::bench::Report;
use crate::config::pcf::{Pcf, PcfKernel};
use crate::config::Effects;
use crate::effects::estimated_terms;
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::passes::PassId;
use crate::reference::compose::Terms;
use crate::reference::run::Session;
use crate::reference::trace::RefBuffer;
use crate::renderer::RenderConfig;
use crate::scene::{CameraPath, Scene};
use crate::vk::{Context, ImageData};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::Arc;

/// Timing groups (of `compare::groups`) shown as table columns, in order: SSAO, indirect
/// light, the reprojection shared by every temporal effect, the whole frame.
pub const COLUMNS: [&str; 4] = ["ao", "indirect", "reproject", "total"];

/// AO patterns of the reference: 32 x 32 samples = 1024 per pixel, no blur, drawn from
/// `REFERENCE_PATTERN_BASE` on (effects::ao::params): points of the same uniform kernel that no
/// accumulation uses, so an accumulation that misses part of the kernel shows as error.
pub const REFERENCE_AO_PATTERNS: u32 = 32;
/// PCF of the reference: the reuse row's disc (Vogel spiral over the same radius) with 1024
/// samples in its fixed pattern 0, without reuse: the uniform disc the 9-sample disc
/// accumulated over frames converges to (tests/patterns.rs compares the radial distributions
/// of the offsets the shader uses), sharing none of its offsets.
pub const REFERENCE_PCF: Pcf = Pcf {
    kernel: PcfKernel::Disc { samples: 1024 },
    radius_texels: Pcf::NINE.radius_texels,
};

/// VPLs per pixel of the reference: 32 x the rows' 512, the most the renderer gathers in one
/// pass (the full gather of every texel is only allowed for RSMs up to 128x128).
pub const REFERENCE_VPLS: u32 = 16384;

/// Samples per half and pixel of the tables' ground truth (AO and indirect light): 512 per
/// pixel keeps a 512x512 walkthrough's reference within minutes on a CPU; its standard error
/// is reported beside the errors (and the cache keeps it for the next run).
pub const TABLE_TRUTH_SAMPLES: u32 = 256;

/// Report names of the GPU counters read here (see the renderer's effect kinds).
pub const SSAO_COMPUTED_PIXELS: &str = "ssao_computed_pixels";
pub const DISOCCLUDED_PIXELS: &str = "disoccluded_pixels";
/// Frames of the reference row, held at the last camera after one warmup frame whose buffers
/// are the reference: it is timed only to show what convergence costs, and its full gather is
/// slow on a CPU device, so one frame.
pub const REFERENCE_FRAMES: u32 = 1;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RowKind {
    Reuse,
    NoReuse,
    Reference,
}

impl RowKind {
    pub const ALL: [RowKind; 3] = [RowKind::Reuse, RowKind::NoReuse, RowKind::Reference];

    /// The row's name in the tables; the reference names only the effects `effects` has.
    pub fn label(self, effects: Effects) -> String {
        match self {
            RowKind::Reuse => "reuse: yes, blur: no (PCF 9, cached)".into(),
            RowKind::NoReuse => "reuse: no, blur: 5x5 Gaussian (PCF 49)".into(),
            RowKind::Reference => {
                let mut l =
                    "reference: no reuse, 1024 AO samples, 1024-sample PCF disc".to_string();
                if effects.indirect {
                    l += &format!(", {REFERENCE_VPLS} VPLs");
                }
                l
            }
        }
    }

    pub fn short(self) -> &'static str {
        match self {
            RowKind::Reuse => "reuse",
            RowKind::NoReuse => "no_reuse",
            RowKind::Reference => "reference",
        }
    }

    /// This row's configuration derived from the table's base configuration.
    pub fn config(self, base: &RenderConfig) -> RenderConfig {
        let mut c = *base;
        match self {
            // The thesis's cached shadows: a 9-sample disc, rotated and scaled every frame.
            RowKind::Reuse => {
                c.temporal.reuse = true;
                c.pcf = Pcf::NINE;
            }
            // One fixed AO pattern per frame (the renderer adds the 5x5 blur), 49-sample PCF.
            RowKind::NoReuse => {
                c.temporal.reuse = false;
                c.ao.patterns = 1;
                c.pcf = Pcf::DEFAULT;
            }
            RowKind::Reference => {
                c.temporal.reuse = false;
                c.ao.patterns = REFERENCE_AO_PATTERNS;
                c.pcf = REFERENCE_PCF;
                c.indirect.vpls = REFERENCE_VPLS;
                // Without reuse CCIPCA's bases restart every frame: projected on last frame's
                // (none) its image would be black. Projected after the update, the one sample
                // of 16384 VPLs is its own first basis: the filter's converged value.
                c.ccipca.project = crate::effects::ccipca::config::CcipcaProject::After;
            }
        }
        c
    }
}

/// The thesis's configuration at `width` x `height` with `effects` (the thesis: all): SSAO
/// 32 samples (8 directions x 4 steps), indirect light with 512 VPLs at half resolution,
/// 512x512 RSM / shadow map; the rows choose reuse and PCF.
pub fn base_config(width: u32, height: u32, effects: Effects) -> RenderConfig {
    RenderConfig {
        width,
        height,
        effects,
        ..RenderConfig::default()
    }
}

/// One measured row.
#[derive(Clone, Debug, Serialize)]
pub struct RowResult {
    pub kind: RowKind,
    pub label: String,
    pub config: RenderConfig,
    pub path: String,
    /// Frames measured (after warmup) and warmup frames of this row's run.
    pub measured_frames: usize,
    pub warmup: u32,
    /// Median per-frame GPU milliseconds of each group of `compare::groups` over the measured
    /// frames (`None`: the group never ran).
    pub ms: BTreeMap<String, Option<f64>>,
    /// 1000 / ms.
    pub fps: BTreeMap<String, Option<f64>>,
    /// Mean SSAO pixels computed per measured frame, and that over width x height.
    pub ssao_pixels_per_frame: Option<f64>,
    pub recomputed_fraction: Option<f64>,
    /// Error of the last frame against the reference, per buffer.
    pub error: BTreeMap<String, ImageError>,
    /// Error of the last frame against the CPU ground truth, per buffer.
    pub truth: BTreeMap<String, FrameError>,
    pub report: Report,
    /// The last frame's output image (written as PNG beside the report, not into JSON).
    #[serde(skip)]
    pub image: Option<ImageData>,
}

/// One frame of a row's run along the path (warmup frames excluded).
#[derive(Clone, Debug, Serialize)]
pub struct FrameSample {
    /// Frame number along the path, from 0.
    pub frame: u64,
    /// GPU milliseconds of each group of `compare::groups` that ran in this frame.
    pub ms: BTreeMap<String, f64>,
    pub ssao_computed_pixels: Option<u64>,
    pub disoccluded_pixels: Option<u64>,
}

impl RowResult {
    /// The measured frames, in path order.
    pub fn samples(&self) -> Vec<FrameSample> {
        let warmup = self.warmup as u64;
        self.report
            .frames
            .iter()
            .filter(|f| f.index >= warmup)
            .map(|f| FrameSample {
                frame: f.index - warmup,
                ms: groups()
                    .iter()
                    .filter_map(|(name, passes)| {
                        group_ms(f, passes).map(|ms| (name.to_string(), ms))
                    })
                    .collect(),
                ssao_computed_pixels: f.counters.get(SSAO_COMPUTED_PIXELS).copied(),
                disoccluded_pixels: f.counters.get(DISOCCLUDED_PIXELS).copied(),
            })
            .collect()
    }
}

/// Sum of `passes` in one frame (every pass when empty), as `compare::group_median` sums;
/// `None` when none of them ran in that frame.
pub fn group_ms(frame: &FrameRow, passes: &[PassId]) -> Option<f64> {
    let mut ran = frame
        .passes
        .iter()
        .filter(|(n, _)| in_group(passes, n))
        .map(|(_, ms)| *ms)
        .peekable();
    ran.peek()?;
    Some(ran.sum())
}

/// How a scene is measured.
pub struct SceneRun<'a> {
    pub base: RenderConfig,
    pub path: &'a CameraPath,
    pub frames: u32,
    pub warmup: u32,
    /// Warm up along the path before its time 0 (`RunSpec::warmup_along_path`).
    pub warmup_along_path: bool,
    pub fps: f32,
    pub progress: bool,
}

/// Measure every row of `scene`. The reference row renders the reference configuration held
/// at the camera of the path's last frame (with moving objects and light where that frame has
/// them): its first frame's buffers are the reference every row's last frame (same camera) is
/// compared to, and its second frame is compared to the first, so its own error is 0 unless
/// rendering is not deterministic.
pub fn measure_rows(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    scene: &Scene,
    run: &SceneRun<'_>,
) -> Result<(Vec<RowResult>, BTreeMap<String, TruthQuality>)> {
    let frames = run.frames.max(1);
    let camera = last_camera(scene, run.path, frames, run.fps);
    let held = held_at(&camera);
    let last = scene.posed(crate::scene::path::frame_time(frames - 1, run.fps));
    let truth = ground_truth_of(&last, run, camera)?;
    let mut reference = measure(
        ctx,
        sink,
        &last,
        &RunSpec {
            label: &format!("{} {}", scene.name, RowKind::Reference.short()),
            config: RowKind::Reference.config(&run.base),
            path: &held,
            frames: REFERENCE_FRAMES,
            warmup: 1,
            warmup_along_path: false,
            fps: run.fps,
            snapshot_after_warmup: true,
            flicker: false,
            progress: run.progress,
        },
    )?;
    let reference_frame = reference
        .after_warmup
        .take()
        .ok_or_else(|| Error::Config("the reference run kept no first frame".into()))?;
    let mut runs = Vec::new();
    for kind in [RowKind::Reuse, RowKind::NoReuse] {
        let config = kind.config(&run.base);
        let measured = measure(
            ctx,
            sink,
            scene,
            &RunSpec {
                label: &format!("{} {}", scene.name, kind.short()),
                config,
                path: run.path,
                frames,
                warmup: run.warmup,
                warmup_along_path: run.warmup_along_path,
                fps: run.fps,
                snapshot_after_warmup: false,
                flicker: false,
                progress: run.progress,
            },
        )?;
        runs.push((kind, config, measured, run.path, run.warmup));
    }
    runs.push((
        RowKind::Reference,
        RowKind::Reference.config(&run.base),
        reference,
        &held,
        1,
    ));
    // The ground truth's standard error must stay under a tenth of the smallest error it is
    // compared with: refine it (from the cache's samples) before scoring the rows.
    let mut truth = truth;
    let frames_last: Vec<&LastFrame> = runs.iter().map(|r| &r.2.last).collect();
    refine_truth_for(&mut truth, &last, &frames_last, estimated_terms(&run.base))?;
    let mut rows = Vec::new();
    for (kind, config, measured, path, warmup) in runs {
        rows.push(summarize(
            kind,
            config,
            measured,
            &reference_frame,
            &truth,
            path,
            warmup,
        )?);
    }
    let quality = truth_quality(&truth, &rows, &last, &reference_frame);
    Ok((rows, quality))
}

/// Refine each ground-truth buffer until its standard error is at most a tenth of the
/// smallest RMSE any of `frames` has against it (capped: `run::MAX_SAMPLES_PER_HALF`).
pub fn refine_truth_for(
    truth: &mut Session<'_>,
    scene: &Scene,
    frames: &[&LastFrame],
    terms: Terms,
) -> Result<()> {
    let mut smallest: BTreeMap<Buffer, f64> = BTreeMap::new();
    for f in frames {
        for (b, e) in ground_truth::errors(f, &truth.reference, scene, terms)? {
            if e.error.rmse > 0.0 {
                let s = smallest.entry(b).or_insert(f64::INFINITY);
                *s = s.min(e.error.rmse);
            }
        }
    }
    let Some(first) = frames.first() else {
        return Ok(());
    };
    for (b, min) in smallest {
        if let Some(rb) = ground_truth::reference_buffer(b) {
            let mask = ground_truth::mask(b, &truth.reference, scene, &first.geometry);
            truth.refine_to(rb, min / 10.0, &mask)?;
        }
    }
    truth.save()
}

/// The ground truth of the table's last camera, from the cache when it has it.
fn ground_truth_of<'a>(
    scene: &'a Scene,
    run: &SceneRun<'_>,
    camera: crate::scene::Camera,
) -> Result<Session<'a>> {
    let settings = crate::reference::Settings::for_render(&run.base, scene);
    let cache = Some(crate::reference::store::default_dir());
    let (w, h) = (run.base.width, run.base.height);
    let mut truth = Session::start(scene, camera, w, h, settings, cache, run.progress)?;
    let terms = estimated_terms(&run.base);
    if terms.ambient_occlusion {
        truth.ensure(RefBuffer::Ao, TABLE_TRUTH_SAMPLES)?;
    }
    if terms.direct {
        truth.ensure(RefBuffer::Direct, 1)?;
    }
    if terms.indirect {
        truth.ensure(RefBuffer::Indirect, TABLE_TRUTH_SAMPLES)?;
    }
    truth.save()?;
    Ok(truth)
}

/// Samples and standard error of each ground-truth buffer the rows were compared with, with
/// the bound a tenth of the smallest error sets.
fn truth_quality(
    truth: &Session<'_>,
    rows: &[RowResult],
    scene: &Scene,
    frame: &LastFrame,
) -> BTreeMap<String, TruthQuality> {
    let mut out = BTreeMap::new();
    for b in [Buffer::Ao, Buffer::Shadow, Buffer::Direct, Buffer::Indirect] {
        let Some(rb) = ground_truth::reference_buffer(b) else {
            continue;
        };
        if !rows.iter().any(|r| r.truth.contains_key(b.name())) {
            continue;
        }
        let mask = ground_truth::mask(b, &truth.reference, scene, &frame.geometry);
        let smallest =
            ground_truth::smallest_rmse(rows.iter().filter_map(|r| r.truth.get(b.name())));
        out.insert(
            b.name().to_string(),
            ground_truth::quality(&truth.reference, rb, &mask, smallest),
        );
    }
    out
}

fn summarize(
    kind: RowKind,
    config: RenderConfig,
    measured: Measured,
    reference: &LastFrame,
    truth: &Session<'_>,
    path: &CameraPath,
    warmup: u32,
) -> Result<RowResult> {
    let Measured { report, last, .. } = measured;
    let ms: BTreeMap<String, Option<f64>> = groups()
        .iter()
        .map(|(name, passes)| (name.to_string(), group_median(&report, passes)))
        .collect();
    let fps = ms
        .iter()
        .map(|(k, v)| (k.clone(), v.map(|ms| 1000.0 / ms)))
        .collect();
    let counts: Vec<u64> = report
        .frames
        .iter()
        .filter(|f| f.index >= warmup as u64)
        .filter_map(|f| f.counters.get(SSAO_COMPUTED_PIXELS).copied())
        .collect();
    let ssao_pixels_per_frame =
        (!counts.is_empty()).then(|| counts.iter().sum::<u64>() as f64 / counts.len() as f64);
    let area = report.width as f64 * report.height as f64;
    let mut error = BTreeMap::new();
    for (buffer, image) in &last.buffers {
        let reference_image = reference.buffer(*buffer).ok_or_else(|| {
            Error::Config(format!("the reference has no {} buffer", buffer.name()))
        })?;
        let e = image_error(
            image,
            reference_image,
            buffer.channels(),
            Some(&reference.geometry),
        )?;
        error.insert(buffer.name().to_string(), e);
    }
    let truth = ground_truth::errors(
        &last,
        &truth.reference,
        truth.scene,
        estimated_terms(&config),
    )?
    .into_iter()
    .map(|(b, e)| (b.name().to_string(), e))
    .collect();
    Ok(RowResult {
        kind,
        label: kind.label(config.effects),
        config,
        path: path.name(),
        measured_frames: report.measured_frames,
        warmup,
        ms,
        fps,
        recomputed_fraction: ssao_pixels_per_frame.map(|p| p / area),
        ssao_pixels_per_frame,
        error,
        truth,
        report,
        image: last.buffer(Buffer::Final).cloned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Effects;

    #[test]
    fn row_configs_are_the_thesis_rows_and_valid() {
        let base = base_config(512, 512, Effects::ALL);
        let reuse = RowKind::Reuse.config(&base);
        assert!(reuse.temporal.reuse);
        assert_eq!((reuse.pcf, reuse.ao.patterns), (Pcf::NINE, 1));
        let no_reuse = RowKind::NoReuse.config(&base);
        assert!(!no_reuse.temporal.reuse);
        assert_eq!((no_reuse.pcf, no_reuse.ao.patterns), (Pcf::DEFAULT, 1));
        let reference = RowKind::Reference.config(&base);
        assert!(!reference.temporal.reuse);
        assert_eq!(reference.ao.patterns * reference.ao.samples, 1024);
        assert_eq!(reference.pcf.samples(), 1024);
        assert_eq!(reference.indirect.vpls, 32 * base.indirect.vpls);
        for c in [reuse, no_reuse, reference] {
            assert_eq!((c.width, c.height, c.effects), (512, 512, Effects::ALL));
            assert_eq!(c.ao.samples, 32);
            c.validate().unwrap();
        }
    }

    #[test]
    fn group_sums_only_what_ran() {
        let frame = FrameRow {
            index: 3,
            warmup: false,
            passes: [("ssao", 2.0), ("blur", 0.5), ("gbuffer", 1.0)]
                .into_iter()
                .map(|(n, ms)| (n.to_string(), ms))
                .collect(),
            skipped: Vec::new(),
            skip_reasons: BTreeMap::new(),
            counters: BTreeMap::new(),
            flicker: None,
        };
        assert_eq!(
            group_ms(
                &frame,
                &[
                    crate::effects::ao::pass::SSAO,
                    crate::effects::ao::pass::BLUR
                ]
            ),
            Some(2.5)
        );
        assert_eq!(group_ms(&frame, &[]), Some(3.5));
        assert_eq!(
            group_ms(&frame, &[crate::effects::indirect::pass::INDIRECT_GATHER]),
            None
        );
    }
}

//! `ssgi table ao`: the AO estimators side by side, the papers' (the thesis's eqs 6-8,
//! Crytek's, Szentandrasi's) and today's (GTAO, Jimenez et al. 2016), each with the cache and
//! without it (one fixed pattern and the 5x5 blur; GTAO: its own denoise), on the built-in
//! Cornell box, the thesis's Table 4.1 scenes and the walkthroughs, each along its table's path: per row the median GPU
//! time of the AO passes, the reprojection and the frame, the last frame's AO against the
//! ray-traced AO (the ground truth of the same radius and attenuation), and the flicker along
//! the path (with AO alone, the output's consecutive-frame MSD follows it). Writes report.json,
//! report.md and ao.csv.
//!
//! JSON, version 1 (later versions only add fields): see docs/formats.md, "ao".

use super::def::TableDef;
use super::reuse::rows::{base_config, refine_truth_for, RowKind, TABLE_TRUTH_SAMPLES};
use super::run::{write_reports, TableRun};
use super::walkthroughs::WALKTHROUGHS;
use crate::bench::compare::{group_median, groups};
use crate::bench::ground_truth::{self, TruthQuality};
use crate::bench::measure::{last_camera, measure, Buffer, Flicker, LastFrame, RunSpec};
use crate::bench::sheet::{notes_section, Cell, Column, Sheet};
use crate::bench::warmup::{before_path, Warmup};
use crate::bench::TableOptions;
use crate::config::sweep_key::value_name;
use crate::config::{Effects, RenderConfig};
use crate::effects::ao::config::AoEstimator;
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::reference::compose::Terms;
use crate::reference::run::Session;
use crate::reference::trace::RefBuffer;
use crate::scene::{cornell_box, CameraPath, Scene};
use crate::vk::Context;
use clap::ValueEnum;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "ao",
    summary: "Every AO estimator (--ao) with and without the cache on \
              the Cornell box, the Table 4.1 scenes and the walkthroughs: time, error against \
              ray-traced AO, flicker.",
    title:
        "AO estimators against ray-traced AO: time, error and flicker, with and without the cache",
    size: (256, 256),
    frames: 60,
    warmup: Warmup::Frames(40),
    sizes: &[],
    effects: None,
    settable: &[
        "ao.samples",
        "ao.steps",
        "ao.position_mips",
        "ao.moving_denoise",
    ],
    run,
};

/// The Cornell box's path (the flicker table's slow orbit).
const CORNELL_PATH: &str = "orbit:60s";

#[derive(Clone, Debug, Serialize)]
pub struct RowResult {
    pub scene: String,
    /// The estimator's name, as `--ao` takes it.
    pub estimator: String,
    pub cache: bool,
    /// Median per-frame GPU ms of the AO passes, the reprojection (with the cache) and the
    /// whole frame over the measured frames.
    pub ao_ms: Option<f64>,
    pub reproject_ms: Option<f64>,
    pub frame_ms: Option<f64>,
    /// RMSE of the last frame's ambient visibility against the ray-traced AO, over the pixels
    /// with geometry.
    pub ao_rmse: Option<f64>,
    /// Mean over consecutive measured frames of the output's MSD (0..1 as encoded).
    pub flicker: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
pub struct SceneTruth {
    pub scene: String,
    pub path: String,
    pub triangles: usize,
    /// RMSE against the ray-traced AO of the AO with only the occluders the camera sees
    /// (reference::visible_occluders): how much occlusion no estimator observes in the G-buffer.
    pub visible_occluders_rmse: Option<f64>,
    pub truth: Option<TruthQuality>,
}

#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    #[serde(flatten)]
    pub run: TableRun,
    pub width: u32,
    pub height: u32,
    pub fps: f32,
    pub frames: u32,
    pub warmup: u32,
    pub warmup_along_path: bool,
    pub notes: Vec<String>,
    pub scenes: Vec<SceneTruth>,
    pub rows: Vec<RowResult>,
}

/// A row's configuration: AO alone with `estimator`, the thesis's reuse row (the cache) or its
/// no-reuse row (one fixed pattern, the 5x5 blur; GTAO: its own denoise).
fn config(opts: &TableOptions, estimator: AoEstimator, cache: bool) -> Result<RenderConfig> {
    let mut base = base_config(
        opts.size.0,
        opts.size.1,
        Effects {
            ao: true,
            ..Effects::NONE
        },
    );
    base.ao.estimator = estimator;
    let base = opts.with_sets(base)?;
    let kind = if cache {
        RowKind::Reuse
    } else {
        RowKind::NoReuse
    };
    Ok(kind.config(&base))
}

/// Every scene with its path: `--path` for all, else each one's table's.
fn scenes(opts: &TableOptions) -> Result<Vec<(Scene, CameraPath, String)>> {
    let given = opts.path.as_deref().map(CameraPath::parse).transpose()?;
    let pick = |own: CameraPath, name: &str| match (&given, opts.path.as_deref()) {
        (Some(p), Some(spec)) => (p.clone(), spec.to_string()),
        _ => (own, name.to_string()),
    };
    let mut out = Vec::new();
    let (path, name) = pick(CameraPath::parse(CORNELL_PATH)?, CORNELL_PATH);
    out.push((cornell_box(), path, name));
    let box_path = super::thesis41::DEFAULT_PATH;
    for s in &super::thesis41::SCENES {
        let (scene, _) = super::thesis41::load(s, opts.assets.as_deref())?;
        let (path, name) = pick(box_path.parse()?, box_path.file);
        out.push((scene, path, name));
    }
    for w in &WALKTHROUGHS {
        let (own, own_name) = w.camera_path(None)?;
        let (path, name) = pick(own, &own_name);
        let scene = w.load(opts.assets.as_deref(), &path)?;
        out.push((scene, path, name));
    }
    Ok(out)
}

fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    if opts.frames < 2 {
        return Err(Error::Config(
            "the flicker measure compares consecutive frames: --frames must be at least 2".into(),
        ));
    }
    // Load every scene before rendering anything: a missing file fails in seconds.
    let loaded = scenes(opts)?;
    super::run::create_out(out)?;
    let base = config(opts, AoEstimator::Thesis, true)?;
    let (warmup, warmup_along_path) = before_path(opts.warmup, base.temporal.rotation_limit);
    let mut rows = Vec::new();
    let mut truths = Vec::new();
    for (scene, path, path_name) in &loaded {
        let (scene_rows, truth, visible_occluders_rmse) =
            measure_scene(ctx, sink, opts, scene, path, (warmup, warmup_along_path))?;
        truths.push(SceneTruth {
            scene: scene.name.clone(),
            path: path_name.clone(),
            triangles: scene.mesh.triangle_count(),
            visible_occluders_rmse,
            truth,
        });
        rows.extend(scene_rows);
    }
    let notes = vec![
        format!(
            "AO alone at {}x{}, each scene along its path at {} fps ({warmup} warmup frames{}, \
             then {} measured): the Cornell box along {CORNELL_PATH}, the Table 4.1 scenes \
             along paths/box.json, the walkthroughs along their own keyframes.",
            opts.size.0,
            opts.size.1,
            opts.fps,
            if warmup_along_path {
                " along the path before its time 0"
            } else {
                " held at its start"
            },
            opts.frames
        ),
        "Cache: the thesis's reuse row (reverse reprojection, rotated patterns, refresh; GTAO \
         denoises each pattern while the camera moves unless ao.moving_denoise=off); no cache: \
         its no-reuse row (one fixed pattern each frame, the 5x5 blur; GTAO: its own \
         edge-aware denoise). Every estimator shares the radius and eq 7's attenuation, which \
         the ground truth's AO follows."
            .into(),
        format!(
            "Parameters changed from the defaults for every row (--set): {}.",
            opts.sets_text()
        ),
        "AO RMSE: the last frame's ambient visibility against the ray-traced AO of the same \
         camera over the pixels with geometry (the truth's standard error per scene is in \
         report.json). Flicker: the mean squared difference of consecutive outputs (0..1 as \
         encoded) along the path, which includes the motion itself: compare rows, not the \
         flicker table's threshold."
            .into(),
    ];
    let report = TableReport {
        run: TableRun::new(
            TABLE.name,
            opts.command.clone(),
            &ctx.info,
            sink.present_mode(),
        ),
        width: opts.size.0,
        height: opts.size.1,
        fps: opts.fps,
        frames: opts.frames,
        warmup,
        warmup_along_path,
        notes,
        scenes: truths,
        rows,
    };
    write_reports(out, TABLE.name, &report, markdown(&report), csv(&report))
}

/// Every estimator with and without the cache on `scene`, then the errors against its ground
/// truth (refined until its standard error is a tenth of the smallest error).
fn measure_scene(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    scene: &Scene,
    path: &CameraPath,
    (warmup, warmup_along_path): (u32, bool),
) -> Result<(Vec<RowResult>, Option<TruthQuality>, Option<f64>)> {
    let base = config(opts, AoEstimator::Thesis, true)?;
    let camera = last_camera(scene, path, opts.frames, opts.fps);
    let settings = crate::reference::Settings::for_render(&base, scene);
    let cache = Some(crate::reference::store::default_dir());
    let mut truth = Session::start(
        scene,
        camera,
        opts.size.0,
        opts.size.1,
        settings,
        cache,
        opts.progress,
    )?;
    truth.ensure(RefBuffer::Ao, TABLE_TRUTH_SAMPLES)?;
    let ao_group = groups()
        .into_iter()
        .find(|(n, _)| *n == "ao")
        .map(|(_, p)| p);
    let reproject = [crate::passes::PassId::REPROJECT];
    let mut measured: Vec<(RowResult, LastFrame)> = Vec::new();
    // Every estimator, in the enum's order (the papers' first).
    for &estimator in AoEstimator::value_variants() {
        for cache in [true, false] {
            let c = config(opts, estimator, cache)?;
            let label = format!(
                "{} {} {}",
                scene.name,
                value_name(estimator),
                if cache { "cache" } else { "no cache" }
            );
            let m = measure(
                ctx,
                sink,
                scene,
                &RunSpec {
                    label: &label,
                    config: c,
                    path,
                    frames: opts.frames,
                    warmup,
                    warmup_along_path,
                    fps: opts.fps,
                    snapshot_after_warmup: false,
                    flicker: true,
                    progress: opts.progress,
                },
            )?;
            let row = RowResult {
                scene: scene.name.clone(),
                estimator: value_name(estimator),
                cache,
                ao_ms: ao_group.as_deref().and_then(|p| group_median(&m.report, p)),
                reproject_ms: cache.then(|| group_median(&m.report, &reproject)).flatten(),
                frame_ms: m.report.total.median_ms,
                ao_rmse: None,
                flicker: m.flicker.as_ref().and_then(|f| Flicker::mean(&f.final_msd)),
            };
            measured.push((row, m.last));
        }
    }
    let lasts: Vec<&LastFrame> = measured.iter().map(|(_, l)| l).collect();
    refine_truth_for(&mut truth, scene, &lasts, Terms::AMBIENT_OCCLUSION)?;
    let mut rows = Vec::new();
    for (row, last) in &measured {
        let errors = ground_truth::errors(last, &truth.reference, scene, Terms::AMBIENT_OCCLUSION)?;
        let row = RowResult {
            ao_rmse: errors.get(&Buffer::Ao).map(|e| e.error.rmse),
            ..row.clone()
        };
        eprintln!("{}", summary_line(&row));
        rows.push(row);
    }
    let smallest = rows
        .iter()
        .filter_map(|r| r.ao_rmse)
        .filter(|e| *e > 0.0)
        .min_by(f64::total_cmp);
    let Some(first) = lasts.first() else {
        return Ok((rows, None, None));
    };
    let mask = ground_truth::mask(Buffer::Ao, &truth.reference, scene, &first.geometry);
    let quality = ground_truth::quality(&truth.reference, RefBuffer::Ao, &mask, smallest);
    let visible = visible_occluders_rmse(&truth.accel, &truth.reference, &mask);
    eprintln!(
        "{}: AO of the visible occluders alone, RMSE {}",
        scene.name,
        visible.map_or("-".into(), |e| format!("{e:.4}"))
    );
    Ok((rows, Some(quality), visible))
}

/// RMSE over `mask` of the visible occluders' AO against the traced AO (None: no pixel).
fn visible_occluders_rmse(
    accel: &crate::reference::Accel,
    reference: &crate::reference::Reference,
    mask: &[bool],
) -> Option<f64> {
    use crate::reference::visible_occluders::{visible_occluder_ao, DIRECTIONS};
    let visible = visible_occluder_ao(accel, reference, &reference.settings.ao, DIRECTIONS);
    let truth = reference.ao.mean();
    let (sum, n) = visible
        .iter()
        .zip(&truth)
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), ((b, t), _)| {
            (s + ((b - t) as f64).powi(2), n + 1)
        });
    (n > 0).then(|| (sum / n as f64).sqrt())
}

fn summary_line(r: &RowResult) -> String {
    let f = |v: Option<f64>, d: usize| v.map_or("-".into(), |v| format!("{v:.d$}"));
    format!(
        "{} {} {}: AO {} ms, frame {} ms, AO RMSE {}, flicker {}",
        r.scene,
        r.estimator,
        if r.cache { "cache" } else { "no cache" },
        f(r.ao_ms, 3),
        f(r.frame_ms, 3),
        f(r.ao_rmse, 4),
        r.flicker.map_or("-".into(), |v| format!("{v:.3e}"))
    )
}

fn sheet() -> Sheet<'static, RowResult> {
    Sheet::new(vec![
        Column::new("scene", "Scene", |r: &RowResult| {
            Cell::text(r.scene.clone())
        }),
        Column::new("estimator", "Estimator", |r: &RowResult| {
            Cell::text(r.estimator.clone())
        }),
        Column::new("cache", "Cache", |r: &RowResult| Cell::Flag(r.cache)),
        Column::new("ao_ms", "AO ms", |r: &RowResult| Cell::num(r.ao_ms, 3)),
        Column::new("reproject_ms", "Reproject ms", |r: &RowResult| {
            Cell::num(r.reproject_ms, 3)
        }),
        Column::new("frame_ms", "Frame ms", |r: &RowResult| {
            Cell::num(r.frame_ms, 3)
        }),
        Column::new("ao_rmse", "AO RMSE vs ray-traced", |r: &RowResult| {
            Cell::num(r.ao_rmse, 4)
        }),
        Column::new("flicker", "Flicker (output MSD)", |r: &RowResult| {
            Cell::sci(r.flicker)
        }),
    ])
}

fn markdown(r: &TableReport) -> String {
    let size = (r.width, r.height);
    let mut md = r.run.markdown_header(TABLE.title, size, r.frames, r.warmup);
    md += &sheet().markdown(&r.rows);
    md += "\nAO RMSE against the ray-traced AO of the AO with only the occluders the camera sees \
           (what no estimator observes in the G-buffer: occluders hidden or off the image; \
           estimators that take surfaces as thick guess part of it) and of the most accurate \
           estimator:\n\n| scene | visible occluders alone | best estimator |\n|---|---|---|\n";
    for s in &r.scenes {
        let best = r
            .rows
            .iter()
            .filter(|row| row.scene == s.scene)
            .filter_map(|row| row.ao_rmse.map(|e| (e, row)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let f = |v: Option<f64>| v.map_or("-".into(), |v| format!("{v:.4}"));
        let best = best.map_or("-".into(), |(e, row)| {
            let cache = if row.cache { "cache" } else { "no cache" };
            format!("{} ({}, {cache})", f(Some(e)), row.estimator)
        });
        md += &format!(
            "| {} | {} | {best} |\n",
            s.scene,
            f(s.visible_occluders_rmse)
        );
    }
    md + "\n" + &notes_section(&r.notes)
}

fn csv(r: &TableReport) -> String {
    sheet().csv(&r.rows)
}

//! `ssgi table szentandrasi-1`: the paper's Table 1 rows on its three scenes, timed per pass,
//! with the paper's frame rates and the ratios between rows beside ours, and each row's error
//! against a 1024-sample reference of its family. Writes report.json, report.md,
//! szentandrasi-1.csv and the last frame of every row as PNG.
//!
//! JSON, version 1 (later versions only add fields):
//! ```text
//! { "version", "table", "command", "ssgi_version", "device", "driver", "device_type",
//!   "window", "present_mode", "width", "height", "frames", "warmup", "fps", "path",
//!   "reference_samples", "notes": [str],
//!   "scenes": [ { "spec", "name", "paper_faces", "triangles", "note",
//!                 "rows": [ { "label", "paper_samples", "form", "samples", "adaptive",
//!                             "subsampling", "filter", "paper_fps", "total_ms", "ssdo_ms",
//!                             "fps", "time_over_first", "paper_time_over_first",
//!                             "samples_per_pixel", "final_rmse", "image",
//!                             "report": <bench report, see report.rs> } ],
//!                 "ratios": [ { "what", "numerator", "denominator", "ours_total",
//!                               "ours_ssdo", "paper" } ] } ] }
//! ```

pub mod paper;

use super::def::TableDef;
use super::run::{write_reports, TableRun};
use crate::bench::compare::group_median;
use crate::bench::measure::{held_at, last_camera, measure, RunSpec};
use crate::bench::metrics::{image_error, Channels};
use crate::bench::output::file_stem;
use crate::bench::sheet::{notes_section, Cell, Column, Sheet};
use crate::bench::warmup::{before_path, Warmup};
use crate::bench::{Report, TableOptions};
use crate::effects::ssdo::config::SsdoForm;
use crate::error::Result;
use crate::frontend::sink::FrameSink;
use crate::scene::{load_scene, CameraPath, Scene};
use crate::vk::{Context, ImageData};
use paper::{PaperRow, PaperScene, RATIOS, REFERENCE_SAMPLES, ROWS, SCENES};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "szentandrasi-1",
    summary: "Szentandrasi et al. Table 1: SSAO and SSDO rows on Pyramids, Cornell box, Dragon.",
    title: "Szentandrási et al. Table 1: SSAO and SSDO frame rates (Pyramids, Cornell box, Dragon)",
    size: paper::PAPER_SIZE,
    frames: 20,
    warmup: Warmup::Frames(2),
    sizes: &[],
    // The rows choose theirs: direct light and SSDO.
    effects: None,
    settable: &[],
    run,
};

#[derive(Clone, Debug, Serialize)]
pub struct RowResult {
    /// The row as the paper states it (label, samples, form, subsampling).
    #[serde(flatten)]
    pub row: PaperRow,
    pub filter: u32,
    pub paper_fps: f64,
    /// Median over the measured frames of the per-frame sum of every pass.
    pub total_ms: Option<f64>,
    /// Median of the SSDO passes' per-frame sum (pre-pass, SSDO, bounce, filter, upsampling).
    pub ssdo_ms: Option<f64>,
    pub fps: Option<f64>,
    /// Frame time over the first row's (SSAO without subsampling).
    pub time_over_first: Option<f64>,
    pub paper_time_over_first: f64,
    /// Mean hemisphere samples per computed pixel (GPU counters).
    pub samples_per_pixel: Option<f64>,
    /// RMSE of the final image (RGB in 0..1, geometry pixels) against the reference.
    pub final_rmse: Option<f64>,
    /// The last frame, relative to the output directory.
    pub image: String,
    pub report: Report,
}

#[derive(Clone, Debug, Serialize)]
pub struct RatioResult {
    pub what: &'static str,
    pub numerator: &'static str,
    pub denominator: &'static str,
    /// Frame time ratio.
    pub ours_total: Option<f64>,
    /// Ratio of the SSDO passes' times alone.
    pub ours_ssdo: Option<f64>,
    /// The paper's, as the inverse ratio of its frame rates, per scene.
    pub paper: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct SceneResult {
    pub spec: &'static str,
    pub name: &'static str,
    pub paper_faces: u32,
    pub triangles: usize,
    pub note: Option<&'static str>,
    pub rows: Vec<RowResult>,
    pub ratios: Vec<RatioResult>,
}

#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    #[serde(flatten)]
    pub run: TableRun,
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    pub warmup: u32,
    pub fps: f32,
    pub path: String,
    pub reference_samples: u32,
    pub notes: Vec<String>,
    pub scenes: Vec<SceneResult>,
}

fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => Some(a / b),
        _ => None,
    }
}

/// Everything measured for one scene.
struct SceneContext<'a> {
    ctx: &'a Arc<Context>,
    opts: &'a TableOptions,
    path: &'a CameraPath,
    warmup: u32,
    warmup_along_path: bool,
    out: &'a Path,
}

fn run_scene(
    c: &SceneContext<'_>,
    sink: &mut dyn FrameSink,
    index: usize,
    paper: &PaperScene,
    scene: &Scene,
) -> Result<SceneResult> {
    let (w, h) = c.opts.size;
    // The references (one per family) at the rows' last camera.
    let camera = last_camera(scene, c.path, c.opts.frames, c.opts.fps);
    let held = held_at(&camera);
    let mut references: Vec<(SsdoForm, ImageData)> = Vec::new();
    for row in &ROWS {
        let config = row.reference_config(w, h);
        if references.iter().any(|(f, _)| *f == config.ssdo.form) {
            continue;
        }
        let label = format!(
            "{}: {REFERENCE_SAMPLES}-sample reference ({:?})",
            paper.name, config.ssdo.form
        );
        let m = measure(
            c.ctx,
            sink,
            scene,
            &RunSpec {
                label: &label,
                config,
                path: &held,
                frames: 1,
                warmup: 0,
                warmup_along_path: false,
                fps: c.opts.fps,
                snapshot_after_warmup: false,
                flicker: false,
                progress: c.opts.progress,
            },
        )?;
        references.push((config.ssdo.form, m.final_image()?.clone()));
    }
    let mut rows: Vec<RowResult> = Vec::new();
    for (i, row) in ROWS.iter().enumerate() {
        let config = row.config(w, h);
        let label = format!("{}: {} ({})", paper.name, row.label, row.paper_samples);
        let m = measure(
            c.ctx,
            sink,
            scene,
            &RunSpec {
                label: &label,
                config,
                path: c.path,
                frames: c.opts.frames,
                warmup: c.warmup,
                warmup_along_path: c.warmup_along_path,
                fps: c.opts.fps,
                snapshot_after_warmup: false,
                flicker: false,
                progress: c.opts.progress,
            },
        )?;
        let image = m.final_image()?;
        let family = row.reference_config(w, h).ssdo.form;
        let reference = &references
            .iter()
            .find(|(f, _)| *f == family)
            .expect("a reference per family")
            .1;
        let error = image_error(image, reference, Channels::Rgb, Some(&m.last.geometry))?;
        let name = format!("{}-{}.png", file_stem(paper.spec), i + 1);
        if let Some(rgba) = image.rgba8() {
            crate::frontend::png::write_rgba8(
                &c.out.join(&name),
                image.width,
                image.height,
                &rgba,
            )?;
        }
        let total_ms = m.report.total.median_ms;
        let first_ms = rows.first().and_then(|r| r.total_ms).or(total_ms);
        rows.push(RowResult {
            row: *row,
            filter: config.ssdo.filter,
            paper_fps: row.paper_fps[index],
            total_ms,
            ssdo_ms: group_median(&m.report, crate::effects::ssdo::pass::ALL),
            fps: total_ms.filter(|t| *t > 0.0).map(|t| 1000.0 / t),
            time_over_first: ratio(total_ms, first_ms),
            paper_time_over_first: row.paper_time_over(&ROWS[0], index),
            samples_per_pixel: m
                .report
                .counter_means
                .get("ssdo_samples_per_pixel")
                .copied(),
            final_rmse: error.rmse,
            image: name,
            report: m.report,
        });
    }
    let ratios = RATIOS
        .iter()
        .map(|r| {
            let (a, b) = (&rows[r.numerator], &rows[r.denominator]);
            let (pa, pb): (&PaperRow, &PaperRow) = (&ROWS[r.numerator], &ROWS[r.denominator]);
            RatioResult {
                what: r.what,
                numerator: a.row.label,
                denominator: b.row.label,
                ours_total: ratio(a.total_ms, b.total_ms),
                ours_ssdo: ratio(a.ssdo_ms, b.ssdo_ms),
                paper: pa.paper_time_over(pb, index),
            }
        })
        .collect();
    Ok(SceneResult {
        spec: paper.spec,
        name: paper.name,
        paper_faces: paper.faces,
        triangles: scene.mesh.triangle_count(),
        note: paper.note,
        rows,
        ratios,
    })
}

/// Measure the table and write its files into `out`; returns the paths written.
fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let (path, path_spec) = match opts.path.as_deref() {
        Some(p) => (CameraPath::parse(p)?, p.to_string()),
        None => (CameraPath::Static, "static".to_string()),
    };
    // Load every scene before rendering anything: a missing file fails in seconds.
    let mut scenes = Vec::new();
    for s in &SCENES {
        scenes.push(load_scene(s.spec, opts.assets.as_deref())?);
    }
    super::run::create_out(out)?;
    let base = ROWS[0].config(opts.size.0, opts.size.1);
    let (warmup, warmup_along_path) = before_path(opts.warmup, base.temporal.rotation_limit);
    let c = SceneContext {
        ctx,
        opts,
        path: &path,
        warmup,
        warmup_along_path,
        out,
    };
    let mut results = Vec::new();
    for (i, (paper, scene)) in SCENES.iter().zip(&scenes).enumerate() {
        let r = run_scene(&c, sink, i, paper, scene)?;
        eprintln!("{}", summary_line(&r));
        results.push(r);
    }
    let mut notes: Vec<String> = vec![
        "Every row renders direct light (spot light, 9-tap PCF) and the SSDO effect, without the \
         cache: every pixel every frame, as the paper measured. Frame time is the sum of the \
         GPU time of every pass; the paper's numbers are whole-frame rates on an ATI Radeon HD \
         4850, so compare the ratios between rows, not absolute rates."
            .into(),
        "Every row has the 11x11 bilateral filter; rows with subsampling run SSAO/SSDO and the \
         filter at half width and height and upsample with a 3x3 joint bilateral kernel. \
         \"SSDO 2 steps\" runs at full resolution (see src/bench/tables/szentandrasi/paper.rs for why)."
            .into(),
        format!(
            "Error: RMSE of the final image (RGB in 0..1 over geometry pixels) against a \
             {REFERENCE_SAMPLES}-sample, full-resolution, unfiltered result of the row's family \
             (SSAO rows against SSAO, SSDO rows against one-step SSDO) at the same camera. It \
             counts noise, the filter's blur and the subsampling's loss, not the screen-space \
             approximation itself."
        ),
    ];
    notes.extend(SCENES.iter().filter_map(|s| s.note).map(str::to_string));
    let report = TableReport {
        run: TableRun::new(
            TABLE.name,
            opts.command.clone(),
            &ctx.info,
            sink.present_mode(),
        ),
        width: opts.size.0,
        height: opts.size.1,
        frames: opts.frames,
        warmup,
        fps: opts.fps,
        path: path_spec,
        reference_samples: REFERENCE_SAMPLES,
        notes,
        scenes: results,
    };
    write_reports(out, TABLE.name, &report, markdown(&report), csv(&report))
}

fn summary_line(s: &SceneResult) -> String {
    let fps: Vec<String> = s
        .rows
        .iter()
        .map(|r| r.fps.map_or("-".into(), |f| format!("{f:.1}")))
        .collect();
    format!("{}: fps per row {}", s.name, fps.join(" / "))
}

/// A row of the sheet: one row of one scene.
struct Line<'a> {
    scene: &'a SceneResult,
    index: usize,
    row: &'a RowResult,
}

fn sheet<'r>() -> Sheet<'static, Line<'r>> {
    Sheet::new(vec![
        Column::csv("scene", |l: &Line| Cell::text(l.scene.spec)),
        Column::csv("row", |l: &Line| Cell::int(l.index + 1)),
        Column::new("label", "Row", |l: &Line| Cell::text(l.row.row.label)),
        Column::new("paper_samples", "Samples (paper)", |l: &Line| {
            Cell::text(l.row.row.paper_samples)
        }),
        Column::new("samples_per_pixel", "Mean samples/px", |l: &Line| {
            Cell::num(l.row.samples_per_pixel, 1)
        }),
        Column::new("subsampling", "Subsampling", |l: &Line| {
            Cell::text(if l.row.row.subsampling { "2x" } else { "no" })
        }),
        Column::csv("form", |l: &Line| {
            Cell::text(format!("{:?}", l.row.row.form))
        }),
        Column::new("ssdo_ms", "SSDO passes ms", |l: &Line| {
            Cell::num(l.row.ssdo_ms, 2)
        }),
        Column::new("total_ms", "Frame ms", |l: &Line| {
            Cell::num(l.row.total_ms, 2)
        }),
        Column::new("fps", "fps", |l: &Line| Cell::num(l.row.fps, 1)),
        Column::new("paper_fps", "Paper fps", |l: &Line| {
            Cell::Num(l.row.paper_fps, 1)
        }),
        Column::new("time_over_first", "Time / first row", |l: &Line| {
            Cell::num(l.row.time_over_first, 2)
        }),
        Column::new("paper_time_over_first", "Paper", |l: &Line| {
            Cell::Num(l.row.paper_time_over_first, 2)
        }),
        Column::new("final_rmse", "Final RMSE", |l: &Line| {
            Cell::num(l.row.final_rmse, 4)
        }),
    ])
}

fn lines(s: &SceneResult) -> Vec<Line<'_>> {
    s.rows
        .iter()
        .enumerate()
        .map(|(index, row)| Line {
            scene: s,
            index,
            row,
        })
        .collect()
}

fn ratio_sheet() -> Sheet<'static, RatioResult> {
    Sheet::new(vec![
        Column::md("Frame time ratio", |q: &RatioResult| Cell::text(q.what)),
        Column::md("Ours (frame)", |q: &RatioResult| Cell::num(q.ours_total, 2)),
        Column::md("Ours (SSDO passes)", |q: &RatioResult| {
            Cell::num(q.ours_ssdo, 2)
        }),
        Column::md("Paper", |q: &RatioResult| Cell::Num(q.paper, 2)),
    ])
}

fn markdown(r: &TableReport) -> String {
    let mut md = format!("# {}\n\nCommand: `{}`\n\n", TABLE.title, r.run.command);
    md += &format!(
        "Device: {} ({}), {}x{}, {} frames measured per row after {} warmup frames, camera path \
         `{}` at {} fps, ssgi {}.\n\n",
        r.run.device,
        r.run.driver,
        r.width,
        r.height,
        r.frames,
        r.warmup,
        r.path,
        r.fps,
        r.run.ssgi_version
    );
    md += &match r.run.present_mode {
        Some(mode) => format!("Frames shown: every frame presented to a window ({mode}).\n\n"),
        None => "Frames shown: none (offscreen).\n\n".to_string(),
    };
    for s in &r.scenes {
        md += &format!(
            "## {} ({} triangles; the paper's: {} faces)\n\n",
            s.name, s.triangles, s.paper_faces
        );
        md += &sheet().markdown(&lines(s));
        md += "\n";
        md += &ratio_sheet().markdown(&s.ratios);
        let images: Vec<String> = s.rows.iter().map(|r| format!("`{}`", r.image)).collect();
        md += &format!("\nLast frames: {}.\n\n", images.join(", "));
    }
    md + &notes_section(&r.notes)
}

fn csv(r: &TableReport) -> String {
    let lines: Vec<Line> = r.scenes.iter().flat_map(lines).collect();
    sheet().csv(&lines)
}

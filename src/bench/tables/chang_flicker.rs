//! `ssgi table chang-flicker`: Chen, Lei & Chang's flicker comparison (section 4.2, Figure 7)
//! and error (Figure 10): CCIPCA, the 11x11 and 17x17 joint bilateral filters, the thesis's
//! accumulation and SVGF (Schied et al. 2017, today's standard), each from 1, 3, 10, 32 and
//! 64 VPLs per pixel, on the Cornell box held still
//! and along a slow orbit. Per row: the flicker measure (mean squared difference of
//! consecutive output frames, and of the indirect light), whether it is under the article's
//! "barely notable" 2.5e-5, and the error of the last frame against the exact gather (every
//! RSM texel). Writes report.json, report.md, chang-flicker.csv and, per motion, PNG plots of
//! flicker and error against VPLs per pixel.
//!
//! JSON, version 1 (later versions only add fields): see docs/formats.md, "chang-flicker".

use super::def::TableDef;
use super::run::{fixed, warmup_frames, write_reports, TableRun};
use crate::bench::measure::{held_at, last_camera, measure, Flicker, RunSpec};
use crate::bench::metrics::{image_error, Channels};
use crate::bench::sheet::{notes_section, Cell, Column, Sheet};
use crate::bench::warmup::Warmup;
use crate::bench::TableOptions;
use crate::config::pcf::Pcf;
use crate::config::Effects;
use crate::config::{IndirectConfig, IndirectFilter, RenderConfig, TemporalConfig};
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::plot::scatter::{write_scatter_plot, ScatterPlot, ScatterSeries};
use crate::renderer::Renderer;
use crate::resources::targets::Target;
use crate::scene::{cornell_box, Camera, CameraPath, Scene};
use crate::vk::{Context, ImageData};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "chang-flicker",
    summary: "Chen et al.'s flicker comparison: CCIPCA, 11x11 and 17x17 joint bilateral filters, \
              accumulation and SVGF from 1-64 VPLs per pixel, static and moving: flicker, error \
              and cost.",
    title: "Chen et al. section 4.2: flicker and error of CCIPCA, joint bilateral filters, accumulation and SVGF against VPLs per pixel (Cornell box)",
    size: (128, 128),
    frames: 16,
    warmup: Warmup::Frames(64),
    sizes: &[],
    effects: Some(Effects {
        direct: true,
        indirect: true,
        ..Effects::NONE
    }),
    settable: &["svgf.", "ccipca."],
    run,
};

/// The article's sample counts.
pub const VPLS: [u32; 5] = [1, 3, 10, 32, 64];
pub const FILTERS: [IndirectFilter; 5] = [
    IndirectFilter::Ccipca,
    IndirectFilter::Jbf11,
    IndirectFilter::Jbf17,
    IndirectFilter::Accumulate,
    IndirectFilter::Svgf,
];
/// "The flickering becomes barely notable when the measured difference is less than 2.5e-5."
pub const THRESHOLD: f64 = 2.5e-5;
/// Small enough for the reference to gather every texel (RenderConfig::validate).
pub const RSM_SIZE: u32 = 128;

#[derive(Clone, Debug, Serialize)]
pub struct RowResult {
    pub motion: &'static str,
    pub filter: IndirectFilter,
    pub vpls: u32,
    /// Mean over the measured frames of the output's consecutive-frame MSD.
    pub final_msd: Option<f64>,
    pub indirect_msd: Option<f64>,
    /// `final_msd` < 2.5e-5.
    pub below_threshold: bool,
    /// RMSE of the last frame's indirect light against the exact gather over geometry pixels,
    /// relative to the exact gather's RMS there.
    pub indirect_relative_rmse: Option<f64>,
    /// RMSE of the last output (RGB as encoded) against the one with the exact gather.
    pub final_rmse: Option<f64>,
    /// Median GPU ms of the frame.
    pub frame_ms: Option<f64>,
    /// Sum of the median GPU ms of the indirect light's passes (the gather and the filter).
    pub indirect_ms: Option<f64>,
    /// The per-frame measures.
    pub flicker: Flicker,
}

#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    #[serde(flatten)]
    pub run: TableRun,
    pub scene: String,
    pub width: u32,
    pub height: u32,
    pub rsm_size: u32,
    pub path: String,
    pub fps: f32,
    pub effects: String,
    pub frames: u32,
    pub warmup: u32,
    pub threshold: f64,
    pub notes: Vec<String>,
    pub rows: Vec<RowResult>,
}

fn config(opts: &TableOptions, filter: IndirectFilter, vpls: u32) -> Result<RenderConfig> {
    opts.with_sets(RenderConfig {
        width: opts.size.0,
        height: opts.size.1,
        rsm_size: RSM_SIZE,
        // Only the indirect light's noise should move from frame to frame.
        pcf: Pcf::HARD,
        effects: opts.effects,
        indirect: IndirectConfig {
            vpls,
            filter,
            ..IndirectConfig::default()
        },
        ..RenderConfig::default()
    })
}

/// The exact gather's indirect light and output at `camera` (every RSM texel, no reuse).
fn reference(
    ctx: &Arc<Context>,
    opts: &TableOptions,
    scene: &Scene,
    camera: &Camera,
) -> Result<(ImageData, ImageData, Vec<bool>)> {
    let mut c = config(opts, IndirectFilter::Accumulate, 0)?;
    c.indirect.half_res = false;
    c.temporal = TemporalConfig {
        reuse: false,
        ..TemporalConfig::default()
    };
    let mut r = Renderer::new(ctx, scene.clone(), c)?;
    r.render_frame(camera)?;
    r.finish()?;
    let mask = crate::bench::metrics::geometry_mask(&r.read(Target::GPosition)?);
    Ok((r.read(Target::Indirect)?, r.read(Target::Output)?, mask))
}

/// RMS of `image`'s RGB where `mask` is set.
fn rms(image: &ImageData, mask: &[bool]) -> Result<Option<f64>> {
    let zero = ImageData {
        bytes: vec![0; image.bytes.len()],
        ..image.clone()
    };
    Ok(image_error(image, &zero, Channels::Rgb, Some(mask))?.rmse)
}

fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    if !opts.effects.indirect {
        return Err(Error::Config(
            "chang-flicker measures indirect light's filters: --effects must include indirect"
                .into(),
        ));
    }
    if opts.frames < 2 {
        return Err(Error::Config(
            "the flicker measure compares consecutive frames: --frames must be at least 2".into(),
        ));
    }
    let moving = CameraPath::parse(opts.path.as_deref().unwrap_or("orbit:60s"))?;
    let scene = cornell_box();
    super::run::create_out(out)?;
    let held = held_at(&scene.camera);
    let warmup = warmup_frames(opts);
    let mut rows = Vec::new();
    for (motion, path, along) in [("static", &held, false), ("moving", &moving, true)] {
        let camera = last_camera(&scene, path, opts.frames, opts.fps);
        let (exact, exact_output, mask) = reference(ctx, opts, &scene, &camera)?;
        let exact_rms = rms(&exact, &mask)?;
        for filter in FILTERS {
            for vpls in VPLS {
                let label = format!("{motion} {} {vpls} VPLs", filter_name(filter));
                let config = config(opts, filter, vpls)?;
                let m = measure(
                    ctx,
                    sink,
                    &scene,
                    &RunSpec {
                        label: &label,
                        config,
                        path,
                        frames: opts.frames,
                        warmup,
                        warmup_along_path: along,
                        fps: opts.fps,
                        snapshot_after_warmup: false,
                        flicker: true,
                        progress: opts.progress,
                    },
                )?;
                let flicker = m.flicker.unwrap_or_default();
                let final_msd = Flicker::mean(&flicker.final_msd);
                let indirect = m.last.buffer(crate::bench::measure::Buffer::Indirect);
                let indirect_relative_rmse = match (indirect, exact_rms) {
                    (Some(i), Some(norm)) if norm > 0.0 => {
                        image_error(i, &exact, Channels::Rgb, Some(&mask))?
                            .rmse
                            .map(|e| e / norm)
                    }
                    _ => None,
                };
                let final_rmse = match m.last.buffer(crate::bench::measure::Buffer::Final) {
                    Some(o) => image_error(o, &exact_output, Channels::Rgb, Some(&mask))?.rmse,
                    None => None,
                };
                let row = RowResult {
                    motion,
                    filter,
                    vpls,
                    final_msd,
                    indirect_msd: Flicker::mean(&flicker.indirect_msd),
                    below_threshold: final_msd.is_some_and(|v| v < THRESHOLD),
                    indirect_relative_rmse,
                    final_rmse,
                    frame_ms: m.report.total.median_ms,
                    indirect_ms: indirect_ms(&m.report, &config),
                    flicker,
                };
                eprintln!("{}", summary_line(&row));
                rows.push(row);
            }
        }
    }
    let notes = vec![
        format!(
            "The built-in Cornell box at {}x{}, RSM {RSM_SIZE}x{RSM_SIZE}, hard shadows, effects \
             {}. Static: the scene's camera, --warmup frames held, then --frames measured. \
             Moving: `{}` at {} fps, --warmup frames along the path before its time 0, then \
             --frames measured; its frame-to-frame difference includes the motion itself, so \
             compare filters with each other there, not with the threshold.",
            opts.size.0,
            opts.size.1,
            opts.effects,
            moving.name(),
            opts.fps
        ),
        "Flicker: mean over consecutive measured frames of the mean squared RGB difference of \
         the output (0..1 as encoded; the article: barely notable below 2.5e-5) and of the \
         indirect light (linear). Error: the last frame against the exact gather (every RSM \
         texel, no reuse) at the same camera, over the pixels with geometry."
            .into(),
        "ccipca, jbf11, jbf17 and svgf filter the same input: a new gather of N VPLs per pixel \
         each frame; accumulate is the thesis's cache (half resolution, N VPLs per pattern, \
         rotated patterns, refresh). Indirect ms: the median GPU time of the indirect light's \
         passes summed (the gather and the filter), beside the whole frame's."
            .into(),
        format!(
            "Parameters changed from the defaults for every row (--set): {}.",
            opts.sets_text()
        ),
    ];
    let report = TableReport {
        run: TableRun::new(
            TABLE.name,
            opts.command.clone(),
            &ctx.info,
            sink.present_mode(),
        ),
        scene: scene.name.clone(),
        width: opts.size.0,
        height: opts.size.1,
        rsm_size: RSM_SIZE,
        path: moving.name(),
        fps: opts.fps,
        effects: opts.effects.to_string(),
        frames: opts.frames,
        warmup,
        threshold: THRESHOLD,
        notes,
        rows,
    };
    let mut written = write_reports(out, TABLE.name, &report, markdown(&report), csv(&report))?;
    written.extend(plots(&report, out)?);
    Ok(written)
}

/// The summed median GPU time of the passes of the indirect light's effect under `config`
/// (None when none of them was timed).
fn indirect_ms(report: &crate::bench::report::Report, config: &RenderConfig) -> Option<f64> {
    let passes: Vec<&str> = crate::effects::REGISTRY
        .iter()
        .filter(|r| r.switch == "indirect" && (r.enabled)(config))
        .flat_map(|r| r.passes.iter().map(|p| p.name()))
        .collect();
    let times: Vec<f64> = report
        .passes
        .iter()
        .filter(|p| passes.contains(&p.name.as_str()))
        .filter_map(|p| p.median_ms)
        .collect();
    (!times.is_empty()).then(|| times.iter().sum())
}

/// Flicker and error against VPLs per pixel, one plot each per motion, log y.
fn plots(r: &TableReport, out: &Path) -> Result<Vec<PathBuf>> {
    type Measure = fn(&RowResult) -> Option<f64>;
    let measures: [(&str, &str, Measure); 2] = [
        ("flicker", "output MSD between frames", |row| row.final_msd),
        ("error", "indirect light, relative RMSE", |row| {
            row.indirect_relative_rmse
        }),
    ];
    let mut written = Vec::new();
    let names: Vec<String> = FILTERS.iter().map(|&f| filter_name(f)).collect();
    for motion in ["static", "moving"] {
        for (name, y_label, value) in measures {
            let series = FILTERS
                .iter()
                .zip(&names)
                .map(|(&f, filter)| ScatterSeries {
                    name: filter,
                    points: r
                        .rows
                        .iter()
                        .filter(|row| row.motion == motion && row.filter == f)
                        .filter_map(|row| value(row).map(|v| (row.vpls as f64, v)))
                        .collect(),
                })
                .collect();
            let title = format!("{name}, {motion} (Cornell box {}x{})", r.width, r.height);
            let path = out.join(format!("{name}-{motion}.png"));
            write_scatter_plot(
                &ScatterPlot {
                    title: &title,
                    x_label: "VPLs per pixel",
                    y_label,
                    series,
                    front: Vec::new(),
                    log_y: true,
                    size: (800, 500),
                },
                &path,
            )?;
            written.push(path);
        }
    }
    Ok(written)
}

/// The filter's name, as `--indirect-filter` takes it.
pub fn filter_name(f: IndirectFilter) -> String {
    crate::config::sweep_key::value_name(f)
}

fn sci(v: Option<f64>) -> String {
    v.map_or("-".into(), |v| format!("{v:.3e}"))
}

fn summary_line(r: &RowResult) -> String {
    format!(
        "{} {} {} VPLs: flicker {} (indirect {}), indirect error {}",
        r.motion,
        filter_name(r.filter),
        r.vpls,
        sci(r.final_msd),
        sci(r.indirect_msd),
        fixed(r.indirect_relative_rmse, 4)
    )
}

fn sheet() -> Sheet<'static, RowResult> {
    Sheet::new(vec![
        Column::new("motion", "Motion", |r: &RowResult| Cell::text(r.motion)),
        Column::new("filter", "Filter", |r: &RowResult| {
            Cell::text(filter_name(r.filter))
        }),
        Column::new("vpls", "VPLs", |r: &RowResult| Cell::int(r.vpls)),
        Column::new("final_msd", "Flicker (output MSD)", |r: &RowResult| {
            Cell::sci(r.final_msd)
        }),
        Column::new("below_threshold", "< 2.5e-5", |r: &RowResult| {
            Cell::Flag(r.below_threshold)
        }),
        Column::new("indirect_msd", "Flicker (indirect MSD)", |r: &RowResult| {
            Cell::sci(r.indirect_msd)
        }),
        Column::new(
            "indirect_relative_rmse",
            "Indirect relative RMSE",
            |r: &RowResult| Cell::num(r.indirect_relative_rmse, 4),
        ),
        Column::new("final_rmse", "Output RMSE", |r: &RowResult| {
            Cell::num(r.final_rmse, 4)
        }),
        Column::new("indirect_ms", "Indirect ms", |r: &RowResult| {
            Cell::num(r.indirect_ms, 2)
        }),
        Column::new("frame_ms", "Frame ms", |r: &RowResult| {
            Cell::num(r.frame_ms, 2)
        }),
    ])
}

fn markdown(r: &TableReport) -> String {
    let size = (r.width, r.height);
    let mut md = r.run.markdown_header(TABLE.title, size, r.frames, r.warmup);
    md += &sheet().markdown(&r.rows);
    md + "\n" + &notes_section(&r.notes)
}

fn csv(r: &TableReport) -> String {
    sheet().csv(&r.rows)
}

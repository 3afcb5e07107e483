//! `ssgi table sraa`: Chiu et al.'s Table 1 and Figure 3 (the SRAA report in
//! `../shared/papers/`, after Chen et al.'s article): on Sponza, at each size, no
//! antialiasing, `sraa`, `sraa-shadow` and 16x supersampling, timed per pass (the geometry
//! pass and the antialiasing pass as their own columns), with the report's milliseconds beside
//! ours, the speed-up over supersampling, and the error against it over all pixels and over
//! edge pixels. Writes report.json, report.md, sraa.csv and every row's last frame as PNG.
//!
//! JSON, version 1 (later versions only add fields): see docs/formats.md, "sraa".

pub mod edges;

use super::def::TableDef;
use super::run::{fixed, pass_ms, warmup_frames, write_reports, TableRun};
use super::walkthroughs::WALKTHROUGHS;
use crate::bench::measure::{held_at, measure, RunSpec};
use crate::bench::sheet::{notes_section, Cell, Column, Sheet};
use crate::bench::warmup::Warmup;
use crate::bench::{Report, TableOptions};
use crate::config::antialias::{AaConfig, AaMode};
use crate::config::pcf::Pcf;
use crate::config::Effects;
use crate::config::RenderConfig;
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::vk::{Context, ImageData};
use edges::{edge_mask, rmse};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "sraa",
    summary: "Chiu et al.'s SRAA Table 1 / Figure 3: no AA, SRAA, shadow-aware SRAA, SSAA 16x on \
              Sponza at 256-1024 (or --size): pass times and error against SSAA 16x.",
    title: "Chiu et al. Table 1 and Figure 3: subpixel reconstruction antialiasing against 16x supersampling (Sponza)",
    size: (512, 512),
    frames: 3,
    warmup: Warmup::Frames(1),
    sizes: &SIZES,
    effects: Some(Effects {
        direct: true,
        ..Effects::NONE
    }),
    settable: &[],
    run,
};

/// The report's output sizes (square).
pub const SIZES: [(u32, u32); 4] = [(256, 256), (512, 512), (768, 768), (1024, 1024)];

/// The report's Table 1, ms on its machine: first pass (subpixel geometry; its number is the
/// ray tracer's), second pass (antialiasing), total.
const PAPER_MS: [(u32, f64, f64, f64); 4] = [
    (256, 18.0, 5.0, 23.0),
    (512, 35.0, 14.0, 49.0),
    (768, 69.0, 28.0, 97.0),
    (1024, 116.0, 49.0, 165.0),
];

/// Figure 3: "about 6x speedup in average compared to the 16x supersampling approach".
pub const PAPER_SPEEDUP: f64 = 6.0;

/// Row order: the reference first (every other row's error is against it).
const MODES: [AaMode; 4] = [
    AaMode::Ssaa16,
    AaMode::None,
    AaMode::Sraa,
    AaMode::SraaShadow,
];

#[derive(Clone, Debug, Serialize)]
pub struct RowResult {
    pub mode: AaMode,
    /// Median ms of the subpixel geometry pass (SRAA rows).
    pub geometry_ms: Option<f64>,
    /// Median ms of the antialiasing pass: the reconstruction, or supersampling's downsample.
    pub aa_ms: Option<f64>,
    /// Median ms of the frame (every pass).
    pub total_ms: Option<f64>,
    /// The report's first pass, second pass and total at this size (SRAA rows).
    pub paper_geometry_ms: Option<f64>,
    pub paper_aa_ms: Option<f64>,
    pub paper_total_ms: Option<f64>,
    /// Supersampling's frame time over this row's.
    pub speedup_over_ssaa: Option<f64>,
    /// RMSE of the output (RGB, 0..1 as encoded) against supersampling's, all pixels.
    pub rmse_all: Option<f64>,
    /// The same over the edge pixels.
    pub rmse_edges: Option<f64>,
    /// The last frame, relative to the output directory.
    pub image: String,
    pub report: Report,
}

#[derive(Clone, Debug, Serialize)]
pub struct SizeResult {
    pub width: u32,
    pub height: u32,
    /// Output pixels whose 16 reference samples are not all on one surface
    /// (`edges::edge_mask`).
    pub edge_pixels: usize,
    pub rows: Vec<RowResult>,
}

#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    #[serde(flatten)]
    pub run: TableRun,
    pub scene: String,
    pub triangles: usize,
    /// The `--effects` list every row renders.
    pub effects: String,
    pub frames: u32,
    pub warmup: u32,
    pub paper_speedup: f64,
    pub notes: Vec<String>,
    pub sizes: Vec<SizeResult>,
}

fn config(opts: &TableOptions, size: (u32, u32), mode: AaMode) -> RenderConfig {
    RenderConfig {
        width: size.0,
        height: size.1,
        effects: opts.effects,
        // The report's shadows are ray traced: hard.
        pcf: Pcf::HARD,
        aa: AaConfig {
            mode,
            ..AaConfig::default()
        },
        ..RenderConfig::default()
    }
}

/// The mode's name, as `--aa` takes it.
fn mode_name(mode: AaMode) -> String {
    crate::config::sweep_key::value_name(mode)
}

/// Every row at one size, the reference first.
fn run_size(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    scene: &crate::scene::Scene,
    size: (u32, u32),
    out: &Path,
) -> Result<SizeResult> {
    let held = held_at(&scene.camera);
    let paper = PAPER_MS.iter().find(|p| p.0 == size.0 && size.0 == size.1);
    let warmup = warmup_frames(opts);
    let mut rows: Vec<RowResult> = Vec::new();
    let mut reference: Option<(ImageData, Vec<bool>)> = None;
    for mode in MODES {
        let label = format!("{}x{} {}", size.0, size.1, mode_name(mode));
        let m = measure(
            ctx,
            sink,
            scene,
            &RunSpec {
                label: &label,
                config: config(opts, size, mode),
                path: &held,
                frames: opts.frames,
                warmup,
                warmup_along_path: false,
                fps: opts.fps,
                snapshot_after_warmup: false,
                flicker: false,
                progress: opts.progress,
            },
        )?;
        let image = m.final_image()?;
        if reference.is_none() {
            let (position, normal) = m.last.supersampled.as_ref().ok_or_else(|| {
                Error::Config("the supersampled run read back no 4x G-buffer".into())
            })?;
            let edges = edge_mask(position, normal, m.last.camera.position)?;
            reference = Some((image.clone(), edges));
        }
        let (ref_image, edges) = reference.as_ref().expect("the reference row runs first");
        let name = format!("sponza-{}x{}-{}.png", size.0, size.1, mode_name(mode));
        if let Some(rgba) = image.rgba8() {
            crate::frontend::png::write_rgba8(&out.join(&name), image.width, image.height, &rgba)?;
        }
        let subpixel = mode.subpixel();
        let aa_pass = if mode == AaMode::Ssaa16 {
            crate::post::ssaa::pass::SSAA_DOWNSAMPLE
        } else {
            crate::post::sraa::pass::SRAA
        };
        let total_ms = m.report.total.median_ms;
        let ssaa_ms = rows.first().and_then(|r| r.total_ms).or(total_ms);
        rows.push(RowResult {
            mode,
            geometry_ms: pass_ms(&m.report, crate::post::sraa::pass::SRAA_GEOMETRY),
            aa_ms: pass_ms(&m.report, aa_pass),
            total_ms,
            paper_geometry_ms: paper.filter(|_| subpixel).map(|p| p.1),
            paper_aa_ms: paper.filter(|_| subpixel).map(|p| p.2),
            paper_total_ms: paper.filter(|_| subpixel).map(|p| p.3),
            speedup_over_ssaa: match (ssaa_ms, total_ms) {
                (Some(s), Some(t)) if t > 0.0 => Some(s / t),
                _ => None,
            },
            rmse_all: rmse(image, ref_image, None)?,
            rmse_edges: rmse(image, ref_image, Some(edges))?,
            image: name,
            report: m.report,
        });
    }
    let edge_pixels = reference.map_or(0, |(_, e)| e.iter().filter(|b| **b).count());
    Ok(SizeResult {
        width: size.0,
        height: size.1,
        edge_pixels,
        rows,
    })
}

/// Run the table at `opts.sizes` (the report's four unless `--size` names one).
fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let sponza = &WALKTHROUGHS[0];
    let (path, _) = sponza.camera_path(None)?;
    let scene = sponza.load(opts.assets.as_deref(), &path)?;
    super::run::create_out(out)?;
    let mut results = Vec::new();
    for &size in &opts.sizes {
        let r = run_size(ctx, sink, opts, &scene, size, out)?;
        eprintln!("{}", summary_line(&r));
        results.push(r);
    }
    let notes = vec![
        "Sponza from the walkthrough's first camera, lit by its spot under the roof, hard \
         shadows (the report ray traces them); effects as --effects says (default: direct \
         light). Each row is one process-wide run of --frames frames after --warmup frames; \
         times are medians of per-pass GPU time."
            .into(),
        "The report's first pass is its ray tracer's (primary rays and the subpixel buffers on \
         a CPU+GPU hybrid); ours rasterizes the four subpixel renders. Compare ratios (speed-up \
         over 16x supersampling; the report: about 6x), not milliseconds."
            .into(),
        format!(
            "Error: RMSE of the encoded RGB output against the 16x supersampled output, over \
             all pixels and over edge pixels: those whose 16 supersampled samples do not all \
             lie on one surface (eye distances within {:.0}%, normals within 25 degrees).",
            100.0 * edges::SAME_SURFACE_DISTANCE
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
        triangles: scene.mesh.triangle_count(),
        effects: opts.effects.to_string(),
        frames: opts.frames,
        warmup: warmup_frames(opts),
        paper_speedup: PAPER_SPEEDUP,
        notes,
        sizes: results,
    };
    write_reports(out, TABLE.name, &report, markdown(&report), csv(&report))
}

fn summary_line(s: &SizeResult) -> String {
    let parts: Vec<String> = s
        .rows
        .iter()
        .map(|r| {
            format!(
                "{} {} ms (edges {})",
                mode_name(r.mode),
                fixed(r.total_ms, 1),
                fixed(r.rmse_edges, 4)
            )
        })
        .collect();
    format!("{}x{}: {}", s.width, s.height, parts.join(", "))
}

/// A row of the sheet: one method at one size.
struct Line<'a> {
    size: &'a SizeResult,
    row: &'a RowResult,
}

fn sheet<'r>() -> Sheet<'static, Line<'r>> {
    Sheet::new(vec![
        Column::md("Size", |l: &Line| {
            let s = l.size;
            Cell::text(format!(
                "{}x{} ({} edge px)",
                s.width, s.height, s.edge_pixels
            ))
        }),
        Column::csv("width", |l: &Line| Cell::int(l.size.width)),
        Column::csv("height", |l: &Line| Cell::int(l.size.height)),
        Column::csv("edge_pixels", |l: &Line| Cell::int(l.size.edge_pixels)),
        Column::new("method", "Method", |l: &Line| {
            Cell::text(mode_name(l.row.mode))
        }),
        Column::new("geometry_ms", "Geometry pass ms", |l: &Line| {
            Cell::num(l.row.geometry_ms, 2)
        }),
        Column::new("aa_ms", "AA pass ms", |l: &Line| Cell::num(l.row.aa_ms, 2)),
        Column::new("total_ms", "Frame ms", |l: &Line| {
            Cell::num(l.row.total_ms, 2)
        }),
        Column::md("Report: 1st / 2nd / total ms", |l: &Line| {
            let r = l.row;
            match (r.paper_geometry_ms, r.paper_aa_ms, r.paper_total_ms) {
                (Some(a), Some(b), Some(c)) => Cell::text(format!("{a} / {b} / {c}")),
                _ => Cell::Empty,
            }
        }),
        Column::csv("paper_geometry_ms", |l: &Line| {
            Cell::num(l.row.paper_geometry_ms, 0)
        }),
        Column::csv("paper_aa_ms", |l: &Line| Cell::num(l.row.paper_aa_ms, 0)),
        Column::csv("paper_total_ms", |l: &Line| {
            Cell::num(l.row.paper_total_ms, 0)
        }),
        Column::new("speedup_over_ssaa", "Speed-up over SSAA 16x", |l: &Line| {
            Cell::num(l.row.speedup_over_ssaa, 2)
        }),
        Column::new("rmse_all", "RMSE, all pixels", |l: &Line| {
            Cell::num(l.row.rmse_all, 4)
        }),
        Column::new("rmse_edges", "RMSE, edge pixels", |l: &Line| {
            Cell::num(l.row.rmse_edges, 4)
        }),
    ])
}

fn lines(r: &TableReport) -> Vec<Line<'_>> {
    r.sizes
        .iter()
        .flat_map(|size| size.rows.iter().map(move |row| Line { size, row }))
        .collect()
}

fn markdown(r: &TableReport) -> String {
    let mut md = format!("# {}\n\nCommand: `{}`\n\n", TABLE.title, r.run.command);
    md += &format!(
        "Device: {} ({}), scene {} ({} triangles), effects {}, {} frames measured per row \
         after {} warmup frames, ssgi {}.\n\n",
        r.run.device,
        r.run.driver,
        r.scene,
        r.triangles,
        r.effects,
        r.frames,
        r.warmup,
        r.run.ssgi_version
    );
    md += &sheet().markdown(&lines(r));
    md += &format!(
        "\nThe report's speed-up of its method over 16x supersampling: about {}x.\n\n",
        r.paper_speedup
    );
    md + &notes_section(&r.notes)
}

fn csv(r: &TableReport) -> String {
    sheet().csv(&lines(r))
}

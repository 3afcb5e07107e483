//! `ssgi table chang-1`: Chen, Lei & Chang's Table 1 (the article in `../shared/papers/`, with
//! the antialiasing report): CCIPCA's milliseconds per frame at
//! five sizes with 3, 5 and 7 bases, split as the article splits them: reprojection (the warp
//! and the orthogonalization, `ccipca_reproject`), incremental PCA (`ccipca_update`) and
//! reconstruction (`ccipca_reconstruct`), with the article's numbers beside ours. The camera
//! orbits the Cornell box, so every measured frame warps; the input is the noisy gather of 3
//! VPLs per pixel (the article's 3 rays), timed apart (`indirect_noisy`, its Table 2's job).
//! The filter runs in the article's form: projection after the updates, no basis filtering.
//! Writes report.json, report.md and chang-1.csv.
//!
//! JSON, version 1 (later versions only add fields): see docs/formats.md, "chang-1".

use super::def::TableDef;
use super::run::{fixed, pass_ms, warmup_frames, write_reports, TableRun};
use crate::bench::measure::{measure, RunSpec};
use crate::bench::sheet::{notes_section, Cell, Column, Sheet};
use crate::bench::warmup::Warmup;
use crate::bench::{Report, TableOptions};
use crate::config::Effects;
use crate::config::{IndirectConfig, IndirectFilter, RenderConfig};
use crate::effects::ccipca::config::{CcipcaConfig, CcipcaProject};
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::scene::{cornell_box, CameraPath};
use crate::vk::Context;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "chang-1",
    summary: "Chen et al.'s CCIPCA Table 1: reprojection, update and reconstruction ms at five \
              sizes (or --size) with 3, 5 and 7 bases, the Cornell box orbiting.",
    title: "Chen et al. Table 1: CCIPCA's reprojection, update and reconstruction per frame (Cornell box orbit)",
    size: (512, 512),
    frames: 8,
    warmup: Warmup::Frames(4),
    sizes: &SIZES,
    effects: Some(Effects {
        indirect: true,
        ..Effects::NONE
    }),
    settable: &[],
    run,
};

/// The article's sizes.
pub const SIZES: [(u32, u32); 5] = [
    (512, 512),
    (640, 480),
    (768, 768),
    (1080, 720),
    (1024, 1024),
];
/// The article's basis counts.
pub const BASES: [u32; 3] = [3, 5, 7];
/// The article's input: 3 rays per pixel.
pub const VPLS: u32 = 3;

/// The article's four numbers for one row, in the order of its columns.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PaperMs {
    pub reproject_ms: f64,
    pub ipca_ms: f64,
    pub reconstruct_ms: f64,
    pub total_ms: f64,
}

/// One row of the article's Table 1: size, bases and its milliseconds.
struct PaperRow {
    size: (u32, u32),
    bases: u32,
    ms: PaperMs,
}

const fn paper_row(size: (u32, u32), bases: u32, ms: [f64; 4]) -> PaperRow {
    PaperRow {
        size,
        bases,
        ms: PaperMs {
            reproject_ms: ms[0],
            ipca_ms: ms[1],
            reconstruct_ms: ms[2],
            total_ms: ms[3],
        },
    }
}

/// Table 1, ms on the article's machine: Reproj., IPCA, Recon., Total.
const PAPER_MS: [PaperRow; 15] = [
    paper_row((512, 512), 3, [1.7, 5.0, 0.18, 6.9]),
    paper_row((512, 512), 5, [2.2, 5.9, 0.26, 8.4]),
    paper_row((512, 512), 7, [2.7, 6.9, 0.36, 10.0]),
    paper_row((640, 480), 3, [1.7, 8.1, 0.22, 10.1]),
    paper_row((640, 480), 5, [2.4, 9.2, 0.31, 11.9]),
    paper_row((640, 480), 7, [3.0, 10.3, 0.42, 13.7]),
    paper_row((768, 768), 3, [2.5, 11.0, 0.39, 13.9]),
    paper_row((768, 768), 5, [3.4, 12.9, 0.57, 16.9]),
    paper_row((768, 768), 7, [4.4, 14.8, 0.79, 20.0]),
    paper_row((1080, 720), 3, [3.0, 14.2, 0.51, 17.6]),
    paper_row((1080, 720), 5, [4.0, 16.7, 0.73, 21.4]),
    paper_row((1080, 720), 7, [5.3, 19.2, 0.97, 25.5]),
    paper_row((1024, 1024), 3, [3.8, 19.5, 0.69, 24.0]),
    paper_row((1024, 1024), 5, [5.3, 22.9, 1.03, 29.2]),
    paper_row((1024, 1024), 7, [6.8, 26.4, 1.42, 34.6]),
];

fn paper(size: (u32, u32), bases: u32) -> Option<PaperMs> {
    PAPER_MS
        .iter()
        .find(|p| p.size == size && p.bases == bases)
        .map(|p| p.ms)
}

#[derive(Clone, Debug, Serialize)]
pub struct RowResult {
    pub width: u32,
    pub height: u32,
    pub bases: u32,
    /// Median ms of the warp and orthogonalization.
    pub reproject_ms: Option<f64>,
    /// Median ms of the k updates (sums and update per basis).
    pub ipca_ms: Option<f64>,
    pub reconstruct_ms: Option<f64>,
    /// The sum of the three medians (the article's Total).
    pub total_ms: Option<f64>,
    /// Median ms of the noisy gather that feeds the filter.
    pub input_ms: Option<f64>,
    pub paper: Option<PaperMs>,
    pub report: Report,
}

#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    #[serde(flatten)]
    pub run: TableRun,
    pub scene: String,
    pub path: String,
    pub fps: f32,
    pub vpls: u32,
    pub effects: String,
    pub frames: u32,
    pub warmup: u32,
    pub notes: Vec<String>,
    pub rows: Vec<RowResult>,
}

fn config(opts: &TableOptions, size: (u32, u32), bases: u32) -> RenderConfig {
    RenderConfig {
        width: size.0,
        height: size.1,
        effects: opts.effects,
        // The article's algorithm: projection after the updates, no basis filtering (our
        // defaults move the projection before the updates, where it costs another pass per
        // basis, and add the filter pass).
        indirect: IndirectConfig {
            vpls: VPLS,
            filter: IndirectFilter::Ccipca,
            ..IndirectConfig::default()
        },
        ccipca: CcipcaConfig {
            bases,
            project: CcipcaProject::After,
            basis_filter: 0,
            ..CcipcaConfig::default()
        },
        ..RenderConfig::default()
    }
}

/// Run the rows at `opts.sizes` (the article's five unless `--size` names one), 3, 5 and 7
/// bases each.
fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    if !opts.effects.indirect {
        return Err(Error::Config(
            "chang-1 times the CCIPCA filter of indirect light: --effects must include indirect"
                .into(),
        ));
    }
    let path = CameraPath::parse(opts.path.as_deref().unwrap_or("orbit"))?;
    let scene = cornell_box();
    super::run::create_out(out)?;
    let warmup = warmup_frames(opts);
    let mut rows = Vec::new();
    for &size in &opts.sizes {
        for bases in BASES {
            let label = format!("{}x{} {bases} bases", size.0, size.1);
            let m = measure(
                ctx,
                sink,
                &scene,
                &RunSpec {
                    label: &label,
                    config: config(opts, size, bases),
                    path: &path,
                    frames: opts.frames,
                    warmup,
                    // The bases enter the measured frames warm and moving.
                    warmup_along_path: true,
                    fps: opts.fps,
                    snapshot_after_warmup: false,
                    flicker: false,
                    progress: opts.progress,
                },
            )?;
            let r = &m.report;
            let (reproject_ms, ipca_ms, reconstruct_ms) = (
                pass_ms(r, crate::effects::ccipca::pass::CCIPCA_REPROJECT),
                pass_ms(r, crate::effects::ccipca::pass::CCIPCA_UPDATE),
                pass_ms(r, crate::effects::ccipca::pass::CCIPCA_RECONSTRUCT),
            );
            let total_ms = match (reproject_ms, ipca_ms, reconstruct_ms) {
                (Some(a), Some(b), Some(c)) => Some(a + b + c),
                _ => None,
            };
            let row = RowResult {
                width: size.0,
                height: size.1,
                bases,
                reproject_ms,
                ipca_ms,
                reconstruct_ms,
                total_ms,
                input_ms: pass_ms(r, crate::effects::ccipca::pass::INDIRECT_NOISY),
                paper: paper(size, bases),
                report: m.report,
            };
            eprintln!("{}", summary_line(&row));
            rows.push(row);
        }
    }
    let notes = vec![
        format!(
            "The built-in Cornell box along `{}` at {} fps (every measured frame warps the \
             bases), only the effects --effects names (default: indirect light); the filter's \
             input is a new gather of {VPLS} VPLs per pixel each frame. Each row: --warmup \
             frames along the path before its time 0, then --frames measured; medians of \
             per-pass GPU time. Total is the sum of the three medians, as the article's.",
            path.name(),
            opts.fps
        ),
        "The article's times are a 2012 GPU's; compare how the columns grow with size and \
         bases, not the milliseconds."
            .into(),
    ];
    let report = TableReport {
        run: TableRun::new(
            TABLE.name,
            opts.command.clone(),
            &ctx.info,
            sink.present_mode(),
        ),
        scene: scene.name.clone(),
        path: path.name(),
        fps: opts.fps,
        vpls: VPLS,
        effects: opts.effects.to_string(),
        frames: opts.frames,
        warmup,
        notes,
        rows,
    };
    write_reports(out, TABLE.name, &report, markdown(&report), csv(&report))
}

fn summary_line(r: &RowResult) -> String {
    format!(
        "{}x{} ({}): reprojection {} ms, IPCA {} ms, reconstruction {} ms, total {} ms",
        r.width,
        r.height,
        r.bases,
        fixed(r.reproject_ms, 2),
        fixed(r.ipca_ms, 2),
        fixed(r.reconstruct_ms, 2),
        fixed(r.total_ms, 2)
    )
}

fn sheet() -> Sheet<'static, RowResult> {
    type Paper = fn(&PaperMs) -> f64;
    let paper = |key: &'static str, value: Paper| {
        Column::csv(key, move |r: &RowResult| {
            Cell::num(r.paper.as_ref().map(value), 2)
        })
    };
    Sheet::new(vec![
        Column::md("Res. (bases)", |r: &RowResult| {
            Cell::text(format!("{}x{} ({})", r.width, r.height, r.bases))
        }),
        Column::csv("width", |r: &RowResult| Cell::int(r.width)),
        Column::csv("height", |r: &RowResult| Cell::int(r.height)),
        Column::csv("bases", |r: &RowResult| Cell::int(r.bases)),
        Column::new("reproject_ms", "Reproj. ms", |r: &RowResult| {
            Cell::num(r.reproject_ms, 2)
        }),
        Column::new("ipca_ms", "IPCA ms", |r: &RowResult| {
            Cell::num(r.ipca_ms, 2)
        }),
        Column::new("reconstruct_ms", "Recon. ms", |r: &RowResult| {
            Cell::num(r.reconstruct_ms, 2)
        }),
        Column::new("total_ms", "Total ms", |r: &RowResult| {
            Cell::num(r.total_ms, 2)
        }),
        Column::md(
            "Article: Reproj. / IPCA / Recon. / Total ms",
            |r: &RowResult| {
                r.paper.map_or(Cell::Empty, |p| {
                    Cell::text(format!(
                        "{} / {} / {} / {}",
                        p.reproject_ms, p.ipca_ms, p.reconstruct_ms, p.total_ms
                    ))
                })
            },
        ),
        Column::new("input_ms", "Input gather ms", |r: &RowResult| {
            Cell::num(r.input_ms, 2)
        }),
        paper("paper_reproject_ms", |p| p.reproject_ms),
        paper("paper_ipca_ms", |p| p.ipca_ms),
        paper("paper_reconstruct_ms", |p| p.reconstruct_ms),
        paper("paper_total_ms", |p| p.total_ms),
    ])
}

fn markdown(r: &TableReport) -> String {
    let mut md = format!("# {}\n\nCommand: `{}`\n\n", TABLE.title, r.run.command);
    md += &format!(
        "Device: {} ({}), scene {}, path {} at {} fps, {} VPLs per pixel, effects {}, {} \
         frames measured per row after {} warmup frames, ssgi {}.\n\n",
        r.run.device,
        r.run.driver,
        r.scene,
        r.path,
        r.fps,
        r.vpls,
        r.effects,
        r.frames,
        r.warmup,
        r.run.ssgi_version
    );
    md += &sheet().markdown(&r.rows);
    md + "\n" + &notes_section(&r.notes)
}

fn csv(r: &TableReport) -> String {
    sheet().csv(&r.rows)
}

//! What the reuse-vs-no-reuse tables (`thesis-4.1`, `thesis-walkthroughs`, `dynamic`) share:
//! the rows' base configuration and warmup from the options, the report's header, each
//! scene's rows measured along its path, and the files at the end.

pub mod columns;
pub mod report;
pub mod rows;
pub mod series;
pub mod thesis;

use crate::bench::ground_truth::TruthQuality;
use crate::bench::output::file_stem;
use crate::bench::TableOptions;
use crate::error::Result;
use crate::frontend::sink::FrameSink;
use crate::renderer::RenderConfig;
use crate::scene::{CameraPath, Scene};
use crate::vk::Context;
use report::{Header, TableReport};
use rows::{measure_rows, RowResult, SceneRun};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use thesis::SETUP;

/// A table's rows setup.
pub struct RowsTable<'a> {
    opts: &'a TableOptions,
    base: RenderConfig,
    warmup: u32,
    warmup_along_path: bool,
}

impl<'a> RowsTable<'a> {
    /// The setup of `table` and its report, empty but for the header and `notes`.
    pub fn start(
        table: &'static str,
        ctx: &Context,
        sink: &dyn FrameSink,
        opts: &'a TableOptions,
        notes: Vec<String>,
    ) -> (Self, TableReport) {
        let base = rows::base_config(opts.size.0, opts.size.1, opts.effects);
        let (warmup, warmup_along_path) =
            crate::bench::warmup::before_path(opts.warmup, base.temporal.rotation_limit);
        let report = TableReport::new(
            Header {
                table,
                command: opts.command.clone(),
                device: &ctx.info,
                present_mode: sink.present_mode(),
                base_config: base,
                frames: opts.frames,
                warmup,
                warmup_along_path,
                fps: opts.fps,
            },
            SETUP,
            notes,
        );
        let setup = Self {
            opts,
            base,
            warmup,
            warmup_along_path,
        };
        (setup, report)
    }

    /// Every row of `scene` along `path` (`rows::measure_rows`).
    pub fn measure(
        &self,
        ctx: &Arc<Context>,
        sink: &mut dyn FrameSink,
        scene: &Scene,
        path: &CameraPath,
    ) -> Result<(Vec<RowResult>, BTreeMap<String, TruthQuality>)> {
        measure_rows(
            ctx,
            sink,
            scene,
            &SceneRun {
                base: self.base,
                path,
                frames: self.opts.frames,
                warmup: self.warmup,
                warmup_along_path: self.warmup_along_path,
                fps: self.opts.fps,
                progress: self.opts.progress,
            },
        )
    }
}

/// The report's files in `out`: every row's last frame as `<scene>-<row>.png` (listed in its
/// scene's files), `report.json`, `report.md` (with `legend` appended) and `<table>.csv`.
pub fn finish(
    out: &Path,
    mut report: TableReport,
    title: &str,
    legend: &str,
) -> Result<Vec<PathBuf>> {
    for s in &mut report.scenes {
        for row in &s.rows {
            let Some(image) = &row.image else { continue };
            let Some(rgba) = image.rgba8() else { continue };
            let name = format!("{}-{}.png", file_stem(&s.spec), row.kind.short());
            crate::frontend::png::write_rgba8(&out.join(&name), image.width, image.height, &rgba)?;
            s.files.push(name);
        }
    }
    let md = columns::markdown(&report, title) + legend;
    let csv = columns::csv(&report);
    super::run::write_reports(out, &report.table, &report, md, csv)
}

//! What the reuse-vs-no-reuse tables (`thesis-4.1`, `thesis-walkthroughs`, `dynamic`) share:
//! the rows' base configuration and warmup from the options, the report's header, and each
//! scene's rows measured along its path.

use super::ground_truth::TruthQuality;
use super::reuse_rows::{measure_rows, RowResult, SceneRun};
use super::table_report::{Header, TableReport};
use super::thesis::SETUP;
use super::TableOptions;
use crate::error::Result;
use crate::frontend::sink::FrameSink;
use crate::renderer::RenderConfig;
use crate::scene::{CameraPath, Scene};
use crate::vk::Context;
use std::collections::BTreeMap;
use std::sync::Arc;

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
        let base = super::reuse_rows::base_config(opts.size.0, opts.size.1, opts.effects);
        let (warmup, warmup_along_path) =
            super::warmup::before_path(opts.warmup, base.temporal.rotation_limit);
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

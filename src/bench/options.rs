//! What a table run was asked for, independent of the command line.

use crate::bench::warmup::Warmup;
use crate::config::Effects;
use std::path::PathBuf;

#[derive(Clone, Debug)]
pub struct TableOptions {
    /// Render size (width, height): `--size`, else the table's default.
    pub size: (u32, u32),
    /// The sizes whose rows a table measures (`TableDef::sizes`).
    pub sizes: Vec<(u32, u32)>,
    /// Frames measured per row along the path, after the warmup (`warmup::before_path`).
    pub frames: u32,
    pub warmup: Warmup,
    /// Frame i of the path is shown at i / fps seconds.
    pub fps: f32,
    /// Camera path override (table-specific meaning; `None`: the table's default).
    pub path: Option<String>,
    /// Effects rendered by every row.
    pub effects: Effects,
    /// Asset directory (`None`: `$SSGI_ASSETS`).
    pub assets: Option<PathBuf>,
    /// Show progress bars on stderr.
    pub progress: bool,
    /// The command line, recorded in the report.
    pub command: String,
}

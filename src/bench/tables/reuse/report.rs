//! The result of a table run: every scene's rows with the run's device, resolution and exact
//! configuration. Serialised as `report.json` and rendered as `report.md` and CSV.
//!
//! JSON, version 1 (later versions only add fields):
//! ```text
//! { "version", "table", "command", "ssgi_version", "device", "driver", "device_type",
//!   "api_version", "window", "present_mode", "width", "height", "frames", "warmup", "fps",
//!   "base_config", "reference",
//!   "thesis_setup", "notes": [str],
//!   "scenes": [ { "spec", "name", "path", "triangles", "note", "thesis", "thesis_speedups",
//!                 "ground_truth": { buffer: { "samples_per_pixel", "standard_error", "bound",
//!                                             "bound_met" } },
//!                 "speedups": { group: no-reuse ms / reuse ms }, "files": [str],
//!                 "rows": [ { "kind", "label", "config", "path", "measured_frames", "warmup",
//!                             "ms": { group: ms }, "fps": { group: fps },
//!                             "ssao_pixels_per_frame", "recomputed_fraction",
//!                             "error": { buffer: { "rmse", "max_abs", "pixels", "non_finite" } },
//!                             "truth": { buffer: { "rmse", "rel_mse", "max_abs", "psnr",
//!                                                  "pixels", "non_finite", "flip" } },
//!                             "report": <bench report, see report.rs> } ] } ] }
//! ```

use super::rows::{RowKind, RowResult};
use super::thesis::{Fps, Scene41};
use crate::bench::compare::groups;
use crate::bench::ground_truth::TruthQuality;
use crate::renderer::RenderConfig;
use crate::vk::DeviceInfo;
use serde::Serialize;
use std::collections::BTreeMap;

pub const TABLE_REPORT_VERSION: u32 = 1;

#[derive(Clone, Debug, Serialize)]
pub struct SceneResult {
    /// The scene as given to the loader (e.g. `box:venus`, `sponza`).
    pub spec: String,
    /// Display name (the thesis's, where it has one).
    pub name: String,
    /// The camera path: `orbit`, or the keyframe file.
    pub path: String,
    pub triangles: usize,
    /// How this scene differs from the thesis's (e.g. a decimated mesh).
    pub note: Option<String>,
    pub thesis: Option<Scene41>,
    pub thesis_speedups: Option<Fps>,
    /// Per group: no-reuse median ms / reuse median ms (how many times faster reuse is).
    pub speedups: BTreeMap<String, Option<f64>>,
    /// Extra files written for this scene (CSV, PNG), relative to the output directory.
    pub files: Vec<String>,
    pub rows: Vec<RowResult>,
    /// The CPU ground truth's samples and standard error per buffer (`rows[].truth`).
    pub ground_truth: BTreeMap<String, TruthQuality>,
}

impl SceneResult {
    pub fn new(
        spec: String,
        name: String,
        path: String,
        triangles: usize,
        thesis: Option<&Scene41>,
        (rows, ground_truth): (Vec<RowResult>, BTreeMap<String, TruthQuality>),
    ) -> Self {
        let ms = |kind: RowKind, group: &str| {
            rows.iter()
                .find(|r| r.kind == kind)
                .and_then(|r| r.ms.get(group).copied().flatten())
        };
        let speedups = groups()
            .iter()
            .map(|(group, _)| {
                let ratio = match (ms(RowKind::Reuse, group), ms(RowKind::NoReuse, group)) {
                    (Some(reuse), Some(no_reuse)) => Some(no_reuse / reuse),
                    _ => None,
                };
                (group.to_string(), ratio)
            })
            .collect();
        Self {
            spec,
            name,
            path,
            triangles,
            note: None,
            thesis: thesis.copied(),
            thesis_speedups: thesis.map(Scene41::speedups),
            speedups,
            files: Vec::new(),
            rows,
            ground_truth,
        }
    }

    pub fn row(&self, kind: RowKind) -> Option<&RowResult> {
        self.rows.iter().find(|r| r.kind == kind)
    }

    /// One line for the terminal once the scene is done.
    pub fn summary_line(&self) -> String {
        let ms = |kind, group: &str| {
            self.row(kind)
                .and_then(|r| r.ms.get(group).copied().flatten())
                .map_or("-".to_string(), |v| format!("{v:.3} ms"))
        };
        let speedup = |group: &str| {
            self.speedups
                .get(group)
                .copied()
                .flatten()
                .map_or("-".to_string(), |v| format!("{v:.2}x"))
        };
        format!(
            "{}: AO {} (reuse) vs {} (no reuse), {}; total {} vs {}, {}",
            self.name,
            ms(RowKind::Reuse, "ao"),
            ms(RowKind::NoReuse, "ao"),
            speedup("ao"),
            ms(RowKind::Reuse, "total"),
            ms(RowKind::NoReuse, "total"),
            speedup("total"),
        )
    }
}

/// Whether a timing group (`compare::groups`) belongs to a run with `config`: the group of an
/// effect the run leaves out is dropped, not printed empty (reprojection and total belong to
/// every run).
pub fn group_present(group: &str, config: &RenderConfig) -> bool {
    crate::effects::REGISTRY
        .iter()
        .find(|r| r.timing_groups.iter().any(|(g, _)| *g == group))
        .is_none_or(|r| (r.enabled)(config))
}

#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    pub version: u32,
    /// `thesis-4.1` or `thesis-walkthroughs`.
    pub table: String,
    /// The command line that produced this report.
    pub command: String,
    pub ssgi_version: String,
    pub device: String,
    pub driver: String,
    pub device_type: String,
    pub api_version: String,
    /// Every frame was presented to a window (`--window`), with this present mode.
    pub window: bool,
    pub present_mode: Option<String>,
    pub width: u32,
    pub height: u32,
    pub frames: u32,
    pub warmup: u32,
    /// The warmup ran along the path before its time 0 (`--warmup converged`).
    pub warmup_along_path: bool,
    /// Path time per frame: frame i at i / fps seconds.
    pub fps: f32,
    /// The configuration every row starts from (rows change reuse, patterns, PCF).
    pub base_config: RenderConfig,
    /// What the error columns compare against.
    pub reference: String,
    pub thesis_setup: String,
    /// What is missing or differs from the thesis (pending effects, absent numbers).
    pub notes: Vec<String>,
    pub scenes: Vec<SceneResult>,
}

/// Run-level facts of a table report.
pub struct Header<'a> {
    pub table: &'a str,
    pub command: String,
    pub device: &'a DeviceInfo,
    /// The window's present mode; `None` offscreen.
    pub present_mode: Option<&'static str>,
    pub base_config: RenderConfig,
    pub frames: u32,
    pub warmup: u32,
    pub warmup_along_path: bool,
    /// Path time per frame: frame i at i / fps seconds.
    pub fps: f32,
}

/// How the error columns are made.
pub const REFERENCE: &str =
    "the reference row's configuration (no temporal reuse; 32 AO patterns = 1024 samples per \
     pixel, no blur; a 1024-sample PCF disc of the reuse row's radius; 16384 VPLs per pixel (32 x \
     512) in the same half-resolution indirect estimator) rendered from the camera of the last \
     frame. The no-reuse row's 7x7 PCF grid has a square footprint, so its shadow error \
     includes that difference of kernel shape. Errors are over the pixels covered by geometry \
     (final image: RGB in 0..1 after tonemapping; AO and shadow: visibility; direct and \
     indirect: linear radiance)";

/// How our columns map to the thesis's.
pub const COLUMN_NOTE: &str =
    "SSAO = the SSAO pass (+ the 5x5 blur without reuse); Indirect = RSM gather + upsampling + \
     full-resolution fix-up; Reproject = the reprojection pass, shared by AO, shadows and \
     indirect light (the thesis counts it inside each effect); Total = every pass of the frame \
     (G-buffer, shadows, direct, reprojection, SSAO, indirect, composite).";

/// Said when the device is a CPU implementation.
pub const CPU_DEVICE_NOTE: &str =
    "This device is a CPU implementation of Vulkan (e.g. lavapipe): its timestamps are the \
     wall-clock times of CPU threads, so anything else running on the machine inflates them \
     (by 20x and more for single passes when other processes compete for the cores). Use \
     these numbers to check the pipeline and the errors, not to claim speed-ups.";

impl TableReport {
    pub fn new(h: Header<'_>, thesis_setup: &str, mut notes: Vec<String>) -> Self {
        if h.device.device_type.eq_ignore_ascii_case("cpu") {
            notes.push(CPU_DEVICE_NOTE.to_string());
        }
        Self {
            version: TABLE_REPORT_VERSION,
            table: h.table.to_string(),
            command: h.command,
            ssgi_version: env!("CARGO_PKG_VERSION").to_string(),
            device: h.device.name.clone(),
            driver: h.device.driver.clone(),
            device_type: h.device.device_type.clone(),
            api_version: h.device.api_version.clone(),
            window: h.present_mode.is_some(),
            present_mode: h.present_mode.map(str::to_string),
            width: h.base_config.width,
            height: h.base_config.height,
            frames: h.frames,
            warmup: h.warmup,
            warmup_along_path: h.warmup_along_path,
            fps: h.fps,
            base_config: h.base_config,
            reference: REFERENCE.to_string(),
            thesis_setup: thesis_setup.to_string(),
            notes,
            scenes: Vec::new(),
        }
    }
}

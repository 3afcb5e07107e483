//! `ssgi table thesis-walkthroughs`: Sponza, Sibenik and Conference walked through along
//! keyframe paths saved in the repository (`paths/*.json`, see paths.rs), with and without
//! reuse: per-frame GPU time and the
//! per-frame fraction of recomputed pixels (the thesis's Tables 4.2-4.4 and Figure 4.10), as
//! CSV and PNG plots, plus the same summary rows and errors as Table 4.1.

use super::paths::{self, EmbeddedPath};
use super::plot::{
    write_line_plot, LinePlot, Series, NO_REUSE_AO_COLOR, NO_REUSE_COLOR, NO_REUSE_INDIRECT_COLOR,
    REUSE_AO_COLOR, REUSE_COLOR, REUSE_INDIRECT_COLOR,
};
use super::reuse_rows::{FrameSample, RowKind};
use super::reuse_tables::RowsTable;
use super::table_report::{SceneResult, TableReport, COLUMN_NOTE};
use super::thesis::WALKTHROUGH_NUMBERS_MISSING;
use super::TableOptions;
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::scene::{build_scene_file, CameraPath, Scene, SceneFile};
use crate::vk::Context;
use plotters::style::RGBColor;
use std::path::Path;
use std::sync::Arc;

/// One walkthrough scene.
pub struct Walkthrough {
    /// Asset folder.
    pub asset: &'static str,
    pub name: &'static str,
    /// The keyframe file (compiled in).
    pub path: EmbeddedPath,
    /// The scene file (compiled in): the model, the walkthrough camera's lens and the light.
    pub scene: EmbeddedScene,
}

/// A scene file of `scenes/`, compiled in so the table runs without the repository.
pub struct EmbeddedScene {
    pub file: &'static str,
    pub text: &'static str,
}

pub const WALKTHROUGHS: [Walkthrough; 3] = [
    Walkthrough {
        asset: "sponza",
        name: "Sponza",
        path: paths::SPONZA,
        scene: EmbeddedScene {
            file: "scenes/sponza.toml",
            text: include_str!("../../scenes/sponza.toml"),
        },
    },
    Walkthrough {
        asset: "sibenik",
        name: "Sibenik",
        path: paths::SIBENIK,
        scene: EmbeddedScene {
            file: "scenes/sibenik.toml",
            text: include_str!("../../scenes/sibenik.toml"),
        },
    },
    Walkthrough {
        asset: "conference",
        name: "Conference",
        path: paths::CONFERENCE,
        scene: EmbeddedScene {
            file: "scenes/conference.toml",
            text: include_str!("../../scenes/conference.toml"),
        },
    },
];

impl Walkthrough {
    /// The compiled-in keyframes, or those of `<dir>/<asset>.json` when a directory is given.
    pub fn camera_path(&self, dir: Option<&Path>) -> Result<(CameraPath, String)> {
        if let Some(dir) = dir {
            let file = dir.join(format!("{}.json", self.asset));
            return Ok((CameraPath::from_file(&file)?, file.display().to_string()));
        }
        Ok((self.path.parse()?, self.path.file.to_string()))
    }

    /// The scene of the walkthrough's scene file (model, lens, the light that stays put while
    /// the camera walks), its camera at the first point of `path`.
    pub fn load(&self, assets: Option<&Path>, path: &CameraPath) -> Result<Scene> {
        let origin = Path::new(self.scene.file);
        let mut file = SceneFile::parse(origin, self.scene.text)?;
        // The table walks `path` (compiled in, or --paths): the file's own path is not read.
        file.camera_path = None;
        let mut scene = build_scene_file(&file, origin, assets)?.scene;
        scene.camera = path.camera_at(&scene.camera, &scene.orbit(), 0.0);
        Ok(scene)
    }
}

pub fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<TableReport> {
    let dir = opts.path.as_deref().map(Path::new);
    if let Some(d) = dir.filter(|d| !d.is_dir()) {
        return Err(Error::Config(format!(
            "--path {} for thesis-walkthroughs must be a directory holding sponza.json, \
             sibenik.json and conference.json",
            d.display()
        )));
    }
    let mut loaded = Vec::new();
    for w in &WALKTHROUGHS {
        let (path, path_name) = w.camera_path(dir)?;
        let scene = w.load(opts.assets.as_deref(), &path)?;
        loaded.push((w, path, path_name, scene));
    }
    let (rows_table, mut report) = RowsTable::start(
        "thesis-walkthroughs",
        ctx,
        sink,
        opts,
        vec![
            COLUMN_NOTE.to_string(),
            WALKTHROUGH_NUMBERS_MISSING.to_string(),
            "Walkthrough scenes: scenes/sponza.toml, sibenik.toml, conference.toml (60° \
             vertical field of view, near/far 0.001 / 1.2 of the bounding-box diagonal; one spot \
             light under the roof aimed straight down, still while the camera walks)."
                .to_string(),
        ],
    );
    for (w, path, path_name, scene) in loaded {
        let rows = rows_table.measure(ctx, sink, &scene, &path)?;
        let mut result = SceneResult::new(
            w.asset.to_string(),
            w.name.to_string(),
            path_name,
            scene.mesh.triangle_count(),
            None,
            rows,
        );
        result.files = write_series(&result, &format!("walkthrough-{}", w.asset), out)?;
        eprintln!("{}", result.summary_line());
        report.scenes.push(result);
    }
    Ok(report)
}

/// `<stem>.csv`, `<stem>-time.png` and `<stem>-recomputed.png` in `out` (the per-frame time
/// and recomputed pixels with and without reuse); returns their names.
pub(super) fn write_series(s: &SceneResult, stem: &str, out: &Path) -> Result<Vec<String>> {
    let samples = |kind| s.row(kind).map(|r| r.samples()).unwrap_or_default();
    let (reuse, no_reuse) = (samples(RowKind::Reuse), samples(RowKind::NoReuse));
    let pixels = s
        .row(RowKind::Reuse)
        .map_or(1, |r| r.report.width as u64 * r.report.height as u64);
    let csv_name = format!("{stem}.csv");
    super::output::write_text(
        &out.join(&csv_name),
        &super::csv::frames(&reuse, &no_reuse, pixels),
    )?;
    let ms = |group: &'static str| move |f: &FrameSample| f.ms.get(group).copied();
    let fraction = |f: &FrameSample| f.ssao_computed_pixels.map(|n| n as f64 / pixels as f64);
    let time_name = format!("{stem}-time.png");
    let title = format!("{}: GPU time per frame", s.name);
    write_line_plot(
        &LinePlot {
            title: &title,
            x_label: "frame",
            y_label: "GPU ms",
            series: vec![
                series("total, reuse", REUSE_COLOR, &reuse, ms("total")),
                series("total, no reuse", NO_REUSE_COLOR, &no_reuse, ms("total")),
                series("AO, reuse", REUSE_AO_COLOR, &reuse, ms("ao")),
                series("AO, no reuse", NO_REUSE_AO_COLOR, &no_reuse, ms("ao")),
                series(
                    "indirect, reuse",
                    REUSE_INDIRECT_COLOR,
                    &reuse,
                    ms("indirect"),
                ),
                series(
                    "indirect, no reuse",
                    NO_REUSE_INDIRECT_COLOR,
                    &no_reuse,
                    ms("indirect"),
                ),
            ],
            size: (900, 480),
        },
        &out.join(&time_name),
    )?;
    let recomputed_name = format!("{stem}-recomputed.png");
    let title = format!("{}: recomputed pixels per frame", s.name);
    write_line_plot(
        &LinePlot {
            title: &title,
            x_label: "frame",
            y_label: "fraction of pixels",
            series: vec![
                series("reuse", REUSE_COLOR, &reuse, fraction),
                series("no reuse", NO_REUSE_COLOR, &no_reuse, fraction),
            ],
            size: (900, 480),
        },
        &out.join(&recomputed_name),
    )?;
    Ok(vec![csv_name, time_name, recomputed_name])
}

/// One plot line: `y` of every sample that has it, against the frame number.
fn series<'a>(
    name: &'a str,
    color: RGBColor,
    samples: &[FrameSample],
    y: impl Fn(&FrameSample) -> Option<f64>,
) -> Series<'a> {
    Series {
        name,
        color,
        points: samples
            .iter()
            .filter_map(|f| y(f).map(|v| (f.frame as f64, v)))
            .collect(),
    }
}

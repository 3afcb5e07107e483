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
use super::rows::{measure_rows, FrameSample, RowKind, SceneRun};
use super::table_report::{Header, SceneResult, TableReport, COLUMN_NOTE};
use super::thesis::{SETUP, WALKTHROUGH_NUMBERS_MISSING};
use super::TableOptions;
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::scene::{load_scene, Camera, CameraPath, Scene, SpotLight};
use crate::vk::Context;
use glam::Vec3;
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
    /// Vertical field of view of the walkthrough camera, degrees.
    pub vfov_deg: f32,
    /// Spot light under the roof, as fractions of the bounding box (0 = min, 1 = max), aimed
    /// straight down at the floor below it, with this outer half-angle (the automatic
    /// headlight of a building follows the camera; the table's light stays put).
    pub light_at: [f32; 3],
    pub light_outer_deg: f32,
}

pub const WALKTHROUGHS: [Walkthrough; 3] = [
    Walkthrough {
        asset: "sponza",
        name: "Sponza",
        path: paths::SPONZA,
        vfov_deg: 60.0,
        light_at: [0.5, 0.95, 0.5],
        light_outer_deg: 60.0,
    },
    Walkthrough {
        asset: "sibenik",
        name: "Sibenik",
        path: paths::SIBENIK,
        vfov_deg: 60.0,
        light_at: [0.5, 0.56, 0.5],
        light_outer_deg: 75.0,
    },
    Walkthrough {
        asset: "conference",
        name: "Conference",
        path: paths::CONFERENCE,
        vfov_deg: 60.0,
        light_at: [0.5, 0.9, 0.5],
        light_outer_deg: 75.0,
    },
];

/// Near and far planes as fractions of the scene's bounding-box diagonal: close enough to
/// walk past columns, far enough to see the whole building, ~1:1000 for the depth buffer.
const NEAR_FRACTION: f32 = 0.001;
const FAR_FRACTION: f32 = 1.2;

impl Walkthrough {
    /// The compiled-in keyframes, or those of `<dir>/<asset>.json` when a directory is given.
    pub fn camera_path(&self, dir: Option<&Path>) -> Result<(CameraPath, String)> {
        if let Some(dir) = dir {
            let file = dir.join(format!("{}.json", self.asset));
            return Ok((CameraPath::from_file(&file)?, file.display().to_string()));
        }
        Ok((self.path.parse()?, self.path.file.to_string()))
    }

    /// The scene with the walkthrough's lens (first keyframe's view) and interior light.
    pub fn load(&self, assets: Option<&Path>, path: &CameraPath) -> Result<Scene> {
        let mut scene = load_scene(self.asset, assets)?;
        let b = scene.mesh.bounds;
        let diagonal = b.diagonal();
        let base = scene.camera;
        scene.camera = Camera::new(
            base.position,
            base.target,
            self.vfov_deg,
            NEAR_FRACTION * diagonal,
            FAR_FRACTION * diagonal,
        );
        scene.camera = path.camera_at(&scene.camera, &scene.orbit(), 0.0);
        let at = b.min + b.extent() * Vec3::from(self.light_at);
        let floor = Vec3::new(at.x, b.min.y, at.z);
        let d = at.distance(floor);
        scene.light = SpotLight::aimed(
            at,
            floor,
            Vec3::splat(d * d),
            0.8 * self.light_outer_deg,
            self.light_outer_deg,
            NEAR_FRACTION * diagonal,
            FAR_FRACTION * diagonal,
        );
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
    let base = super::rows::base_config(opts.size.0, opts.size.1, opts.effects);
    let (warmup, warmup_along_path) =
        super::warmup::before_path(opts.warmup, base.temporal.rotation_limit);
    let mut report = TableReport::new(
        Header {
            table: "thesis-walkthroughs",
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
        vec![
            COLUMN_NOTE.to_string(),
            WALKTHROUGH_NUMBERS_MISSING.to_string(),
            format!(
                "Walkthrough cameras: {}° vertical field of view, near/far {} / {} of the \
                 scene's bounding-box diagonal; one spot light under the roof aimed straight \
                 down (position and cone per scene in walkthrough.rs).",
                WALKTHROUGHS[0].vfov_deg, NEAR_FRACTION, FAR_FRACTION
            ),
        ],
    );
    for (w, path, path_name, scene) in loaded {
        let rows = measure_rows(
            ctx,
            sink,
            &scene,
            &SceneRun {
                base,
                path: &path,
                frames: opts.frames,
                warmup,
                warmup_along_path,
                fps: opts.fps,
                progress: opts.progress,
            },
        )?;
        let mut result = SceneResult::new(
            w.asset.to_string(),
            w.name.to_string(),
            path_name,
            scene.mesh.triangle_count(),
            None,
            rows,
        );
        result.files = write_series(&result, w.asset, out)?;
        eprintln!("{}", result.summary_line());
        report.scenes.push(result);
    }
    Ok(report)
}

/// `walkthrough-<asset>.csv`, `-time.png` and `-recomputed.png` in `out`; returns their names.
fn write_series(s: &SceneResult, asset: &str, out: &Path) -> Result<Vec<String>> {
    let samples = |kind| s.row(kind).map(|r| r.samples()).unwrap_or_default();
    let (reuse, no_reuse) = (samples(RowKind::Reuse), samples(RowKind::NoReuse));
    let pixels = s
        .row(RowKind::Reuse)
        .map_or(1, |r| r.report.width as u64 * r.report.height as u64);
    let csv_name = format!("walkthrough-{asset}.csv");
    super::output::write_text(
        &out.join(&csv_name),
        &super::csv::frames(&reuse, &no_reuse, pixels),
    )?;
    let ms = |group: &'static str| move |f: &FrameSample| f.ms.get(group).copied();
    let fraction = |f: &FrameSample| f.ssao_computed_pixels.map(|n| n as f64 / pixels as f64);
    let time_name = format!("walkthrough-{asset}-time.png");
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
    let recomputed_name = format!("walkthrough-{asset}-recomputed.png");
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

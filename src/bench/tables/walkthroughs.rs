//! `ssgi table thesis-walkthroughs`: Sponza, Sibenik and Conference walked through along
//! keyframe paths saved in the repository (`paths/*.json`, see paths.rs), with and without
//! reuse: per-frame GPU time and the
//! per-frame fraction of recomputed pixels (the thesis's Tables 4.2-4.4 and Figure 4.10), as
//! CSV and PNG plots, plus the same summary rows and errors as Table 4.1.

use super::def::TableDef;
use super::paths::{self, EmbeddedPath};
use super::reuse::columns::WALKTHROUGH_LEGEND;
use super::reuse::report::{SceneResult, COLUMN_NOTE};
use super::reuse::series::write_series;
use super::reuse::thesis::WALKTHROUGH_NUMBERS_MISSING;
use super::reuse::{finish, RowsTable};
use crate::bench::warmup::Warmup;
use crate::bench::TableOptions;
use crate::config::Effects;
use crate::error::{Error, Result};
use crate::frontend::sink::FrameSink;
use crate::scene::{build_scene_file, CameraPath, Scene, SceneFile};
use crate::vk::Context;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "thesis-walkthroughs",
    summary: "Sponza, Sibenik, Conference walkthroughs, per-frame (thesis Tables 4.2-4.4, Fig. \
              4.10).",
    title: "Thesis Tables 4.2-4.4 and Figure 4.10: Sponza, Sibenik and Conference walkthroughs",
    size: (512, 512),
    frames: 120,
    warmup: Warmup::Frames(10),
    sizes: &[],
    effects: Some(Effects::ALL),
    settable: &[],
    run,
};

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
            text: include_str!("../../../scenes/sponza.toml"),
        },
    },
    Walkthrough {
        asset: "sibenik",
        name: "Sibenik",
        path: paths::SIBENIK,
        scene: EmbeddedScene {
            file: "scenes/sibenik.toml",
            text: include_str!("../../../scenes/sibenik.toml"),
        },
    },
    Walkthrough {
        asset: "conference",
        name: "Conference",
        path: paths::CONFERENCE,
        scene: EmbeddedScene {
            file: "scenes/conference.toml",
            text: include_str!("../../../scenes/conference.toml"),
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

fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
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
        TABLE.name,
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
    finish(out, report, TABLE.title, WALKTHROUGH_LEGEND)
}

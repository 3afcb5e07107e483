//! `ssgi table dynamic`: the dynamic scene (scenes/cornell-ball.toml: a ball rolling across the
//! Cornell box while the spot swings) seen by a still camera, and the same with the light held
//! still (only the ball moves), with and without reuse: per-pass GPU time, the per-frame
//! series, and the last frame's error against the converged reference and the ground truth of
//! that moment. The thesis leaves dynamic scenes open (section 5); this measures what the
//! motion-aware reprojection and `--invalidate` keep of the cache.

use super::def::TableDef;
use super::reuse::columns::WALKTHROUGH_LEGEND;
use super::reuse::report::{SceneResult, COLUMN_NOTE};
use super::reuse::series::write_series;
use super::reuse::{finish, RowsTable};
use super::walkthroughs::EmbeddedScene;
use crate::bench::warmup::Warmup;
use crate::bench::TableOptions;
use crate::config::Effects;
use crate::error::Result;
use crate::frontend::sink::FrameSink;
use crate::scene::{build_scene_file, CameraPath, SceneFile};
use crate::vk::Context;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "dynamic",
    summary: "The dynamic scene (scenes/cornell-ball.toml: a ball rolling across the Cornell \
              box while the spot swings), still camera: reuse vs no reuse, time and error per \
              frame.",
    title: "Dynamic scene: a ball rolling across the Cornell box under a swinging light",
    // 4 s at 60 fps: the light's whole swing, the ball's way across.
    size: (256, 256),
    frames: 240,
    warmup: Warmup::Frames(10),
    sizes: &[],
    effects: Some(Effects::ALL),
    settable: &[],
    run,
};

/// The scene file, compiled in.
pub const DYNAMIC: EmbeddedScene = EmbeddedScene {
    file: "scenes/cornell-ball.toml",
    text: include_str!("../../../scenes/cornell-ball.toml"),
};

fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let origin = Path::new(DYNAMIC.file);
    let file = SceneFile::parse(origin, DYNAMIC.text)?;
    let swinging = build_scene_file(&file, origin, opts.assets.as_deref())?.scene;
    let mut still = swinging.clone();
    still.light_path = None;
    // The light where the swing starts (time 0), held there.
    still.light = swinging.posed(0.0).light;
    // What moves is the scene; the camera stays (--path moves it too).
    let path = match &opts.path {
        Some(p) => CameraPath::parse(p)?,
        None => CameraPath::Static,
    };
    let (rows_table, mut report) = RowsTable::start(
        TABLE.name,
        ctx,
        sink,
        opts,
        vec![
            COLUMN_NOTE.to_string(),
            format!(
                "Dynamic scene {}: a 0.2 m ball rolls 0.5 m across the floor and back every 8 s, \
                 the spot swings 1.2 m and back every 4 s (\"light still\": held where the swing \
                 starts); camera path {}. Frame i is at i / fps seconds of both paths (warmup \
                 frames before it). Errors are of the last frame, against the reference and the \
                 ground truth posed at that frame's time.",
                DYNAMIC.file,
                path.name()
            ),
        ],
    );
    let scenes = [
        ("cornell-ball", "Ball & swinging light", swinging),
        ("cornell-ball-still-light", "Ball, light still", still),
    ];
    for (stem, name, scene) in scenes {
        let rows = rows_table.measure(ctx, sink, &scene, &path)?;
        let triangles = scene.mesh.triangle_count()
            + scene
                .objects
                .iter()
                .map(|o| o.mesh.triangle_count())
                .sum::<usize>();
        let mut result = SceneResult::new(
            stem.to_string(),
            name.to_string(),
            path.name(),
            triangles,
            None,
            rows,
        );
        result.files = write_series(&result, &format!("dynamic-{stem}"), out)?;
        eprintln!("{}", result.summary_line());
        report.scenes.push(result);
    }
    finish(out, report, TABLE.title, WALKTHROUGH_LEGEND)
}

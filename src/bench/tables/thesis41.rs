//! `ssgi table thesis-4.1`: Venus, Dragon, Bunny and Buddha, each in a box, on one camera
//! path; reuse vs no reuse + 5x5 blur vs the converged reference, with the thesis's Table 4.1
//! beside ours.

use super::def::TableDef;
use super::paths::EmbeddedPath;
use super::reuse::report::{SceneResult, COLUMN_NOTE};
use super::reuse::thesis::table_4_1;
use super::reuse::{finish, RowsTable};
use crate::bench::warmup::Warmup;
use crate::bench::TableOptions;
use crate::config::Effects;
use crate::error::Result;
use crate::frontend::sink::FrameSink;
use crate::scene::decimate::decimate;
use crate::scene::{box_room, load_model, load_scene, CameraPath, Scene};
use crate::vk::Context;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub const TABLE: TableDef = TableDef {
    name: "thesis-4.1",
    summary: "Venus, Dragon, Bunny, Buddha in a box: reuse vs no reuse (thesis Table 4.1).",
    title: "Thesis Table 4.1: reuse vs no reuse (Venus, Dragon, Bunny, Buddha in a box)",
    size: (512, 512),
    frames: 120,
    warmup: Warmup::Frames(10),
    sizes: &[],
    effects: Some(Effects::ALL),
    settable: &[],
    run,
};

/// A model of Table 4.1, put in the box room.
pub struct BoxScene {
    /// Asset folder of the model.
    pub asset: &'static str,
    /// Name in the thesis's table.
    pub thesis: &'static str,
    /// Decimate to this many triangles first (the thesis's face count, where our file has more).
    pub decimate_to: Option<usize>,
}

pub const SCENES: [BoxScene; 4] = [
    BoxScene {
        asset: "venus",
        thesis: "Venus",
        decimate_to: None,
    },
    BoxScene {
        asset: "dragon",
        thesis: "Dragon",
        decimate_to: Some(6_514),
    },
    BoxScene {
        asset: "bunny",
        thesis: "Bunny",
        decimate_to: None,
    },
    BoxScene {
        asset: "buddha",
        thesis: "Buddha",
        decimate_to: None,
    },
];

/// The default camera path (the thesis used one path for all four scenes): round the model
/// inside the room, from its open side. (`orbit` circles outside the room's walls.)
pub const DEFAULT_PATH: EmbeddedPath = super::paths::BOX;

/// Load `s` in its box; the note says how the scene differs from the thesis's, if it does.
pub fn load(s: &BoxScene, assets: Option<&Path>) -> Result<(Scene, Option<String>)> {
    let Some(target) = s.decimate_to else {
        return Ok((load_scene(&format!("box:{}", s.asset), assets)?, None));
    };
    // The model alone (same file lookup and errors as box:<asset>), decimated, then boxed.
    let (name, model) = load_model(s.asset, assets)?;
    let d = decimate(&model, target)?;
    let note = format!(
        "{}: the thesis's {target}-face mesh is not available. This is the {}-triangle \
         Stanford dragon from the asset directory, decimated with meshoptimizer's edge-collapse \
         simplifier (meshopt crate) to {} triangles (resulting error {:.2}% of the mesh extent).",
        s.thesis,
        d.from_triangles,
        d.to_triangles,
        100.0 * d.relative_error
    );
    Ok((box_room(&d.mesh, &name), Some(note)))
}

fn run(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    opts: &TableOptions,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let (path, path_spec) = match opts.path.as_deref() {
        Some(p) => (CameraPath::parse(p)?, p),
        None => (DEFAULT_PATH.parse()?, DEFAULT_PATH.file),
    };
    // Load every scene before rendering anything: a missing file fails in seconds.
    let mut loaded = Vec::new();
    for s in &SCENES {
        loaded.push((s, load(s, opts.assets.as_deref())?));
    }
    let (rows_table, mut report) =
        RowsTable::start(TABLE.name, ctx, sink, opts, vec![COLUMN_NOTE.to_string()]);
    for (s, (scene, note)) in loaded {
        let rows = rows_table.measure(ctx, sink, &scene, &path)?;
        let mut result = SceneResult::new(
            scene.name.clone(),
            s.thesis.to_string(),
            path_spec.to_string(),
            scene.mesh.triangle_count(),
            table_4_1(s.thesis),
            rows,
        );
        result.note = note;
        eprintln!("{}", result.summary_line());
        report.scenes.push(result);
    }
    finish(out, report, TABLE.title, "")
}

//! The stress matrix's cases: scenes at extreme scales and depth ranges, cameras and lights in
//! awkward places, degenerate geometry, tiny and lopsided image sizes, the rotation limit at
//! its bounds, and one long run with a jittering camera, cuts, resizes and light moves.

use crate::config::Effects;
use crate::config::MAX_PATTERNS;
use crate::renderer::RenderConfig;
use crate::scene::{cornell_box, Camera, MeshBuilder, Scene};
use glam::Vec3;

/// How a case drives the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Program {
    /// `STATIC_FRAMES` frames at the case's camera, then `MOVING_FRAMES` turning it about its
    /// target; then the drift check holds the last view.
    Short,
    /// Many frames with a jittering camera, cuts, resizes and light moves.
    Long(LongRun),
}

/// `frames` frames with a jittering camera and, every so many frames, a cut between two views,
/// a resize and a light move; audited every `audit_every` frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LongRun {
    pub frames: u64,
    pub audit_every: u64,
    pub cut_every: u64,
    pub resize_every: u64,
    pub light_every: u64,
}

pub const STATIC_FRAMES: u32 = 4;
pub const MOVING_FRAMES: u32 = 8;
/// Turn of the camera per moving frame, degrees (30 degrees per second at 60 fps).
pub const TURN_DEG_PER_FRAME: f32 = 0.5;
/// Events of the long run per 100,000 frames (a cut every 1,000 frames, a resize every 5,000,
/// a light move every 700, an audit every 1,000), scaled to shorter runs so they all happen.
const CUTS: u64 = 100;
const RESIZES: u64 = 20;
const LIGHT_MOVES: u64 = 143;
const AUDITS: u64 = 100;

/// An effect set and a reuse mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    /// The effect that darkens the ambient light beside direct and indirect light: each
    /// `--effects` switch of one that does (`ao`, the thesis's set, first).
    pub effects: &'static str,
    pub reuse: bool,
}

impl Variant {
    /// Every ambient effect with and without reuse.
    pub fn all() -> Vec<Variant> {
        crate::effects::ambient_switches()
            .into_iter()
            .flat_map(|effects| [true, false].map(|reuse| Variant { effects, reuse }))
            .collect()
    }

    pub fn config(&self, rsm_size: u32) -> RenderConfig {
        let mut c = RenderConfig {
            rsm_size,
            effects: Effects::ALL,
            ..Default::default()
        };
        for other in crate::effects::ambient_switches() {
            // Switches from the registry: known names.
            let _ = c.effects.set(other, other == self.effects);
        }
        c.temporal.reuse = self.reuse;
        c
    }
}

/// Largest RMSE (8-bit output, 0..1) between the converged view after a case's program and the
/// same view converged from scratch, at the default rotation limit (36). Without reuse both
/// renders are the same computation; with it, what differs is the resampled history of pixels
/// that converged while the camera moved (the refresh replaces it tile by tile, over many
/// frames at small budgets) and the gated mean's order of merging.
pub const DRIFT_TOLERANCE: f32 = 0.02;

/// The drift bound at rotation limit `limit`: below 36 patterns the converged value is itself
/// a noisier mean, and the two convergences may hold different patterns, so the bound grows as
/// that noise does (sqrt(36 / limit): 0.12 for a single pattern).
pub fn drift_tolerance(limit: u32) -> f32 {
    DRIFT_TOLERANCE * (36.0 / limit.clamp(1, 36) as f32).sqrt()
}

/// One case of the matrix (run once per effect set and reuse mode).
#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    /// What it provokes, for the report.
    pub what: &'static str,
    pub scene: Scene,
    pub size: (u32, u32),
    /// Patterns per pixel (the rotation limit) for this case.
    pub rotation_limit: u32,
    pub program: Program,
}

impl Case {
    fn new(name: &str, what: &'static str, scene: Scene) -> Self {
        Self {
            name: name.to_string(),
            what,
            scene,
            size: (32, 32),
            rotation_limit: crate::config::TemporalConfig::default().rotation_limit,
            program: Program::Short,
        }
    }

    fn sized(mut self, w: u32, h: u32) -> Self {
        self.size = (w, h);
        self
    }

    /// The render configuration of this case under `base` (effects and reuse already chosen).
    pub fn config(&self, base: &RenderConfig) -> RenderConfig {
        let mut c = *base;
        (c.width, c.height) = self.size;
        c.temporal.rotation_limit = self.rotation_limit;
        c
    }
}

/// The whole matrix; `quick` keeps every kind of case but at the small end (the tests' subset),
/// and the long run at `long_frames` frames.
pub fn matrix(quick: bool, long_frames: u64) -> Vec<Case> {
    let mut cases = Vec::new();
    for scale in [1e-3f32, 1.0, 1e3, 1e5] {
        cases.push(Case::new(
            &format!("scale-{}", scale_name(scale)),
            "the Cornell box scaled (mesh, camera, light; intensity by scale^2)",
            scaled_cornell(scale),
        ));
    }
    let mut deep = cornell_box();
    // The largest depth range a camera may have (scene::MAX_DEPTH_RATIO).
    deep.camera.near = deep.camera.far / crate::scene::MAX_DEPTH_RATIO;
    cases.push(Case::new(
        "near-far-1e5",
        "far / near = 1e5, the largest accepted (depth precision)",
        deep,
    ));
    cases.push(Case::new(
        "camera-touching-wall",
        "eye one near distance in front of the back wall, looking at it",
        with_camera(Vec3::new(0.2, 1.0, -1.04 + 0.05), Vec3::new(0.2, 1.0, -2.0)),
    ));
    cases.push(Case::new(
        "camera-inside-geometry",
        "eye inside the tall block",
        with_camera(Vec3::new(-0.33, 0.6, -0.29), Vec3::new(0.0, 0.6, 1.0)),
    ));
    cases.push(Case::new(
        "grazing-view",
        "eye 1 mm above the floor looking along it",
        with_camera(Vec3::new(0.6, 0.001, 0.9), Vec3::new(0.6, 0.001, -1.0)),
    ));
    cases.push(Case::new(
        "slivers-and-huge-triangles",
        "needle triangles (1e-6 high) and a ground triangle 1e6 across under the box",
        slivers_and_huge(),
    ));
    let mut inside = cornell_box();
    inside.light.position = Vec3::new(-0.33, 0.6, -0.29);
    cases.push(Case::new(
        "light-inside-geometry",
        "the spot inside the tall block",
        inside,
    ));
    let mut grazing = cornell_box();
    grazing.light.position = Vec3::new(0.9, 0.001, 0.9);
    grazing.light.direction = Vec3::new(-1.0, 0.0, -1.0).normalize();
    cases.push(Case::new(
        "light-grazing-floor",
        "the spot 1 mm above the floor, aimed along it",
        grazing,
    ));
    let large = if quick { (256, 24) } else { (2048, 96) };
    for (w, h) in [(1, 1), (2, 3), (7, 5), large] {
        cases.push(
            Case::new(
                &format!("size-{w}x{h}"),
                "tiny and lopsided image sizes",
                cornell_box(),
            )
            .sized(w, h),
        );
    }
    for limit in [1, MAX_PATTERNS] {
        let mut c = Case::new(
            &format!("rotation-limit-{limit}"),
            "the rotation limit at its bounds (the fp32 count, the refresh's patterns)",
            cornell_box(),
        )
        .sized(8, 8);
        c.rotation_limit = limit;
        cases.push(c);
    }
    let mut long = Case::new(
        "long-jitter",
        "jittering camera with cuts, resizes and light moves",
        cornell_box(),
    )
    .sized(16, 16);
    let every = |events: u64| (long_frames / events).max(1);
    long.program = Program::Long(LongRun {
        frames: long_frames,
        audit_every: every(AUDITS),
        cut_every: every(CUTS),
        resize_every: every(RESIZES),
        light_every: every(LIGHT_MOVES),
    });
    cases.push(long);
    cases
}

fn scale_name(scale: f32) -> String {
    if scale == 1.0 {
        "1".into()
    } else {
        format!("{scale:e}")
    }
}

/// The Cornell box with every length multiplied by `s` about the origin; the light's intensity
/// grows by s² so the irradiance, and the image, stay the same.
pub fn scaled_cornell(s: f32) -> Scene {
    let mut scene = cornell_box();
    let mut b = MeshBuilder::new();
    b.append(&scene.mesh, s, Vec3::ZERO);
    scene.mesh = b.build();
    let c = &mut scene.camera;
    c.position *= s;
    c.target *= s;
    c.near *= s;
    c.far *= s;
    let l = &mut scene.light;
    l.position *= s;
    l.near *= s;
    l.far *= s;
    l.intensity *= s * s;
    scene.orbit = None;
    scene
}

fn with_camera(position: Vec3, target: Vec3) -> Scene {
    let mut scene = cornell_box();
    scene.camera = Camera {
        position,
        target,
        ..scene.camera
    };
    scene
}

/// The Cornell box standing on a ground triangle 1e6 m across, with a fan of needles (1e-6 m
/// high over 1 m) on its floor.
fn slivers_and_huge() -> Scene {
    let mut scene = cornell_box();
    let mut b = MeshBuilder::new();
    b.append(&scene.mesh, 1.0, Vec3::ZERO);
    let white = b.add_material(scene.mesh.materials[0].clone());
    let ground = [
        Vec3::new(-5e5, -0.01, 5e5),
        Vec3::new(5e5, -0.01, 5e5),
        Vec3::new(0.0, -0.01, -5e5),
    ];
    b.add_flat_polygon(white, &ground, Vec3::Y);
    for k in 0..16 {
        let x = -0.8 + 0.1 * k as f32;
        let needle = [
            Vec3::new(x, 0.001, 0.8),
            Vec3::new(x + 1e-6, 0.001, 0.8),
            Vec3::new(x, 0.001, -0.2),
        ];
        b.add_flat_polygon(white, &needle, Vec3::Y);
    }
    scene.mesh = b.build();
    scene
}

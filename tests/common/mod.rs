//! Shared test setup: a lavapipe context with validation + synchronization validation, and a
//! check that no validation message was reported.
#![allow(dead_code)]

pub mod golden;
pub mod rsm;

use ssgi::config::pcf::Pcf;
use ssgi::renderer::{RenderConfig, Renderer};
use ssgi::resources::targets::Target;
use ssgi::scene::{Camera, Scene};
use ssgi::vk::{Context, ContextOptions, FrameTiming, ImageData};
use std::sync::Arc;

pub fn context() -> Arc<Context> {
    Context::new(&ContextOptions {
        validation: true,
        ..Default::default()
    })
    .expect("Vulkan context with validation layers (run tools/setup-vulkan)")
}

/// A counter's value in a frame's timing.
pub fn counter(t: &FrameTiming, name: &str) -> Option<u64> {
    t.counters.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

/// The frames of `timings` that recorded `pass` (a skipped frame records nothing).
pub fn frames_recording(timings: &[FrameTiming], pass: &str) -> Vec<u64> {
    timings
        .iter()
        .filter(|t| t.passes.iter().any(|(p, ms)| *p == pass && ms.is_some()))
        .map(|t| t.frame)
        .collect()
}

/// `c` moved sideways (and a little up and back) without turning: the move the CPU
/// reprojection checks use, which uncovers some of the Cornell box's surfaces.
pub fn moved_sideways(c: Camera) -> Camera {
    let shift = glam::Vec3::new(0.12, 0.03, -0.05);
    Camera {
        position: c.position + shift,
        target: c.target + shift,
        ..c
    }
}

/// Reverse reprojection on the CPU from the G-buffers of two frames of a still scene, seen
/// from `c0` and then `c1`: eq 1 (where a pixel's surface was in the first frame) and eqs 2-3
/// with the facing test (whether a texel of the first frame held it: the default scale-free
/// epsilon of 2 footprints, normals within 60 degrees), as the GPU's reprojections do it.
pub struct CpuReprojection<'a> {
    pos: [&'a ImageData; 2],
    nrm: [&'a ImageData; 2],
    c1: Camera,
    vp0: glam::Mat4,
}

impl<'a> CpuReprojection<'a> {
    pub fn new(
        pos: [&'a ImageData; 2],
        nrm: [&'a ImageData; 2],
        (c0, c1): (Camera, Camera),
    ) -> Self {
        let vp0 = c0.view_proj(pos[1].width as f32 / pos[1].height as f32);
        Self { pos, nrm, c1, vp0 }
    }

    /// Pixel (x, y)'s surface in the second frame: None over the background, else its
    /// continuous pixel coordinates in the first frame (texel centres at half-integers), None
    /// where it was behind that camera or off its image.
    pub fn previous(&self, x: u32, y: u32) -> Option<Option<glam::Vec2>> {
        let p = self.pos[1].texel(x, y);
        if p[3] == 0.0 {
            return None;
        }
        let (width, height) = (self.pos[1].width as f32, self.pos[1].height as f32);
        let clip = self.vp0 * glam::Vec4::new(p[0], p[1], p[2], 1.0);
        // Behind the camera, or NaN: no previous position.
        if clip.w.is_nan() || clip.w <= 0.0 {
            return Some(None);
        }
        let f = glam::Vec2::new(
            (clip.x / clip.w * 0.5 + 0.5) * width,
            (clip.y / clip.w * 0.5 + 0.5) * height,
        );
        let inside = f.x >= 0.0 && f.y >= 0.0 && f.x < width && f.y < height;
        Some(inside.then_some(f))
    }

    /// Whether the first frame's texel (tx, ty) held pixel (x, y)'s surface (false off the
    /// image).
    pub fn holds(&self, (x, y): (u32, u32), (tx, ty): (i64, i64)) -> bool {
        use glam::Vec3;
        let (width, height) = (self.pos[1].width, self.pos[1].height);
        if tx < 0 || ty < 0 || tx >= width as i64 || ty >= height as i64 {
            return false;
        }
        let p = self.pos[1].texel(x, y);
        let w = Vec3::new(p[0], p[1], p[2]);
        let n = Vec3::from_slice(&self.nrm[1].texel(x, y)[..3]);
        let to_eye = self.c1.position - w;
        let dist = to_eye.length();
        let tan_half = (0.5 * self.c1.vfov_deg).to_radians().tan();
        let footprint = 2.0 * dist * tan_half / height as f32;
        let eps = 2.0 * footprint / n.dot(to_eye / dist).abs().max(0.1);
        let h = self.pos[0].texel(tx as u32, ty as u32);
        let facing = Vec3::from_slice(&self.nrm[0].texel(tx as u32, ty as u32)[..3]).dot(n) >= 0.5;
        h[3] != 0.0 && Vec3::new(h[0], h[1], h[2]).distance(w) <= eps && facing
    }
}

/// Per pixel of the frame seen from `c1`, whether it is new to the view since the frame seen
/// from `c0` (None over the background): `CpuReprojection`'s nearest texel does not hold its
/// surface. With `reach` above 0 a pixel is kept where any texel of the (2 reach + 1)-square
/// block around the nearest holds it (SVGF's bilinear tap and its 3x3 fallback: reach 1).
pub fn cpu_disocclusion(
    pos: [&ImageData; 2],
    nrm: [&ImageData; 2],
    cameras: (Camera, Camera),
    reach: i64,
) -> Vec<Option<bool>> {
    let cpu = CpuReprojection::new(pos, nrm, cameras);
    let (width, height) = (pos[1].width, pos[1].height);
    let mut mask = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            mask.push(cpu.previous(x, y).map(|f| {
                let kept = f.is_some_and(|f| {
                    let (tx, ty) = (f.x.floor() as i64, f.y.floor() as i64);
                    (-reach..=reach)
                        .any(|dy| (-reach..=reach).any(|dx| cpu.holds((x, y), (tx + dx, ty + dy))))
                });
                !kept
            }));
        }
    }
    mask
}

/// Fail the test if the validation layers reported anything.
pub fn assert_clean(ctx: &Context) {
    ctx.wait_idle().expect("device idle");
    let log = ctx.validation().expect("validation enabled");
    let messages = log.messages();
    assert!(
        messages.is_empty(),
        "{} validation message(s):\n{}",
        messages.len(),
        messages.join("\n")
    );
}

/// AO alone at `size` x `size` (hard shadows, 128-texel RSM), every frame recorded: a
/// converged frame must run, not be skipped, for the cache's counters to be read
/// (tests/skip.rs covers skipping).
pub fn ao_config(
    size: u32,
    temporal: ssgi::config::TemporalConfig,
    ao: ssgi::effects::ao::config::AoConfig,
) -> RenderConfig {
    RenderConfig {
        width: size,
        height: size,
        rsm_size: 128,
        pcf: Pcf::HARD,
        effects: ssgi::config::Effects {
            ao: true,
            ..ssgi::config::Effects::NONE
        },
        ao,
        temporal,
        skip_unchanged: false,
        ..RenderConfig::default()
    }
}

/// AO visibility and world position of every geometry pixel of the last frame (None for
/// background).
pub fn ao_and_positions(r: &mut Renderer) -> Vec<Option<(f32, glam::Vec3)>> {
    let ao = r.read(Target::Ao).unwrap();
    let pos = r.read(Target::GPosition).unwrap();
    (0..ao.width * ao.height)
        .map(|i| {
            let (x, y) = (i % ao.width, i / ao.width);
            let p = pos.texel(x, y);
            (p[3] != 0.0).then(|| (ao.texel(x, y)[0], glam::Vec3::new(p[0], p[1], p[2])))
        })
        .collect()
}

/// Render `frames` frames of `scene` from its own camera and return the renderer.
pub fn render(ctx: &Arc<Context>, scene: Scene, size: u32, pcf: Pcf, frames: u32) -> Renderer {
    let config = RenderConfig {
        width: size,
        height: size,
        rsm_size: 512,
        pcf,
        ..Default::default()
    };
    let mut r = Renderer::new(ctx, scene, config).expect("renderer");
    let camera: Camera = r.scene.camera;
    for _ in 0..frames {
        r.render_frame(&camera).expect("frame");
    }
    r.finish().expect("finish");
    r
}

/// The Cornell box seen straight down from 1.9 m above (`x`, `z`) with a `vfov_deg` lens, the
/// image's up along -z: the floor and the tall block's shadow fill the view.
pub fn cornell_from_above(x: f32, z: f32, vfov_deg: f32) -> Scene {
    let mut scene = ssgi::scene::cornell_box();
    scene.camera = Camera::new(
        glam::Vec3::new(x, 1.9, z),
        glam::Vec3::new(x, 0.0, z),
        vfov_deg,
        0.05,
        20.0,
    );
    scene.camera.up = glam::Vec3::NEG_Z;
    scene
}

pub fn read(r: &mut Renderer, t: Target) -> ImageData {
    r.read(t).expect("readback")
}

/// A 400 m square ground plane seen from 3 m up, lit by the spot straight down from 10 m
/// above: nothing occludes anything.
pub fn open_plane() -> Scene {
    open_plane_with_normals(glam::Vec3::Y)
}

/// [`open_plane`] with every vertex normal `normal` (a plane whose shading normals lean off its
/// geometric one).
pub fn open_plane_with_normals(normal: glam::Vec3) -> Scene {
    use glam::Vec3;
    use ssgi::scene::{Material, MeshBuilder, SpotLight};
    let mut b = MeshBuilder::new();
    let m = b.add_material(Material::colour("ground", [0.7, 0.7, 0.7]));
    let h = 200.0;
    b.add_flat_polygon(
        m,
        &[
            Vec3::new(-h, 0.0, -h),
            Vec3::new(-h, 0.0, h),
            Vec3::new(h, 0.0, h),
            Vec3::new(h, 0.0, -h),
        ],
        normal,
    );
    let mut scene = ssgi::scene::cornell_box();
    scene.name = "open-plane".into();
    scene.mesh = b.build();
    scene.camera = Camera::new(Vec3::new(0.0, 3.0, 6.0), Vec3::ZERO, 40.0, 0.1, 100.0);
    scene.light = SpotLight {
        position: Vec3::new(0.0, 10.0, 0.0),
        direction: Vec3::NEG_Y,
        ..scene.light
    };
    scene
}

/// Largest accepted difference of one 8-bit channel between two renders of the same state
/// (tests/golden.rs explains the tolerance).
pub const MAX_CHANNEL_DIFF: u8 = 3;
/// Largest accepted fraction of pixels with any difference.
pub const MAX_CHANGED_FRACTION: f64 = 0.02;

/// `None` when the RGBA8 image `got` (`width` pixels wide) matches `want` within the golden
/// tolerance, else what differs.
pub fn golden_compare(got: &[u8], want: &[u8], width: u32) -> Option<String> {
    let mut changed = 0usize;
    let mut worst = (0u8, 0usize);
    for (i, (g, w)) in got.chunks(4).zip(want.chunks(4)).enumerate() {
        let d = g
            .iter()
            .zip(w)
            .map(|(a, b)| a.abs_diff(*b))
            .max()
            .unwrap_or(0);
        if d > 0 {
            changed += 1;
        }
        if d > worst.0 {
            worst = (d, i);
        }
    }
    let fraction = changed as f64 / (got.len() / 4).max(1) as f64;
    if worst.0 <= MAX_CHANNEL_DIFF && fraction <= MAX_CHANGED_FRACTION {
        return None;
    }
    let i = worst.1;
    Some(format!(
        "{changed} pixels differ ({:.2}%), worst {} codes at ({}, {}): got {:?}, want {:?}",
        100.0 * fraction,
        worst.0,
        i as u32 % width,
        i as u32 / width,
        &got[4 * i..4 * i + 4],
        &want[4 * i..4 * i + 4]
    ))
}

/// Mean squared difference of the RGB channels of two RGBA8 frames, in [0, 1] units (Chen,
/// Lei, Chang 2012 call below 2.5e-5 between consecutive frames barely notable flicker).
pub fn msd(a: &ImageData, b: &ImageData) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for (pa, pb) in a.bytes.chunks(4).zip(b.bytes.chunks(4)) {
        for c in 0..3 {
            let d = (pa[c] as f64 - pb[c] as f64) / 255.0;
            sum += d * d;
            n += 1;
        }
    }
    sum / n as f64
}

/// `frames` frames of a held camera (the scene's): every timing, and `target` read back after
/// each frame.
pub fn held_frames(
    r: &mut Renderer,
    frames: usize,
    target: Target,
) -> (Vec<FrameTiming>, Vec<Vec<u8>>) {
    let camera = r.scene.camera;
    let mut timings = Vec::new();
    let mut outputs = Vec::new();
    for _ in 0..frames {
        timings.extend(r.render_frame(&camera).unwrap());
        outputs.push(read(r, target).bytes);
    }
    timings.extend(r.finish().unwrap());
    (timings, outputs)
}

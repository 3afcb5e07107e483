//! The reference of one frame: primary hits through every pixel centre, then the buffers'
//! estimates, refined in parallel over rows (rayon) by adding samples to both halves.

use super::estimate::Estimate;
use super::estimators::{ao_sample, direct_sample, indirect_sample, AoDefinition, Primary};
use super::sampling::{r2, shift};
use super::surface::Surface;
use crate::scene::accel::Accel;
use crate::scene::pixel_to_ndc;
use crate::scene::{Camera, Scene};
use glam::Vec2;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicU64, Ordering};

/// Default samples per half and pixel (so twice this many per pixel): enough for the closed
/// forms of the tests to hold within 1 % and the Cornell box at 256x256 to finish well inside
/// two minutes on two cores; `refine` adds more where the comparison needs them.
pub const DEFAULT_AO_SAMPLES: u32 = 1024;
pub const DEFAULT_INDIRECT_SAMPLES: u32 = 1024;
/// Samples per half for the spherical light's soft shadows (the point light needs one).
pub const DEFAULT_SOFT_SHADOW_SAMPLES: u32 = 256;

/// Check a spherical light's radius against its scene's bounding radius: at most that. The
/// disc is sampled through the light's centre, so a larger light encloses the scene instead
/// of standing in it, and its shadow rays grow so long that the stretch an occlusion test
/// ignores at each end (`OCCLUSION_RELATIVE_OFFSET` of the length) outgrows the scene: at a
/// radius of 1e7 nothing is found occluded, at 1e30 the length overflows f32, and either way
/// the shadow buffer is lit everywhere with a standard error of 0.
pub fn check_light_radius(radius: f32, scene_radius: f32) -> Result<(), String> {
    if radius <= scene_radius {
        return Ok(());
    }
    Err(format!(
        "--light-radius {radius} is larger than the scene's bounding radius {scene_radius}: a \
         spherical light that size encloses the scene (its shadow rays then leave it and find \
         no occluder); give at most {scene_radius}"
    ))
}

/// What the reference computes besides the scene and camera.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    pub ao: AoDefinition,
    /// Radius of the spherical light for soft shadows; 0 = the point light (hard shadows).
    pub light_radius: f32,
    /// Seed of every sample sequence.
    pub seed: u32,
}

impl Settings {
    /// The definition a renderer configuration's AO estimates (radius relative to the scene's
    /// bounding radius, eq 7's attenuation), with the point light.
    pub fn for_render(config: &crate::config::RenderConfig, scene: &Scene) -> Self {
        Settings {
            ao: AoDefinition {
                radius: config.ao.radius * scene.bounds().radius().max(f32::MIN_POSITIVE),
                attenuation: config.ao.attenuation,
            },
            light_radius: 0.0,
            seed: 1,
        }
    }
}

/// The buffers a reference holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RefBuffer {
    Ao,
    Direct,
    Shadow,
    Indirect,
}

impl RefBuffer {
    pub const ALL: [RefBuffer; 4] = [
        RefBuffer::Ao,
        RefBuffer::Direct,
        RefBuffer::Shadow,
        RefBuffer::Indirect,
    ];

    pub fn name(self) -> &'static str {
        match self {
            RefBuffer::Ao => "ao",
            RefBuffer::Direct => "direct",
            RefBuffer::Shadow => "shadow",
            RefBuffer::Indirect => "indirect",
        }
    }

    pub fn channels(self) -> usize {
        match self {
            RefBuffer::Ao | RefBuffer::Shadow => 1,
            RefBuffer::Direct | RefBuffer::Indirect => 3,
        }
    }
}

/// A frame's reference.
pub struct Reference {
    pub width: u32,
    pub height: u32,
    pub camera: Camera,
    pub settings: Settings,
    pub primary: Vec<Option<Primary>>,
    pub ao: Estimate,
    /// Direct radiance and, as a separate estimate of the same samples, light visibility.
    pub direct: Estimate,
    pub shadow: Estimate,
    pub indirect: Estimate,
    /// Rays traced so far, and the seconds spent tracing them (rays per second).
    pub rays: u64,
    pub seconds: f64,
}

/// Rays one sample of each buffer traces.
fn rays_per_sample(buffer: RefBuffer) -> u64 {
    match buffer {
        RefBuffer::Ao | RefBuffer::Direct | RefBuffer::Shadow => 1,
        RefBuffer::Indirect => 2,
    }
}

impl Reference {
    /// Trace the primary rays: pixel centres, the camera's near..far range of view depth
    /// (what the rasterizer keeps), the G-buffer's eye-facing normal.
    pub fn new(
        accel: &Accel,
        scene: &Scene,
        camera: Camera,
        width: u32,
        height: u32,
        settings: Settings,
    ) -> Self {
        let start = std::time::Instant::now();
        let aspect = width as f32 / height.max(1) as f32;
        let (forward, _, _) = camera.frame();
        let primary: Vec<Option<Primary>> = (0..width as usize * height as usize)
            .into_par_iter()
            .map(|i| {
                let (x, y) = ((i % width as usize) as f32, (i / width as usize) as f32);
                let (nx, ny) = pixel_to_ndc(x, y, width, height);
                let (o, d) = camera.ray(nx, ny, aspect);
                let along = d.dot(forward).max(f32::MIN_POSITIVE);
                let hit = accel.closest(o, d, camera.near / along, camera.far / along, None)?;
                let surface = Surface::at(&scene.mesh, &hit);
                Some(Primary {
                    surface,
                    normal: surface.facing(o),
                })
            })
            .collect();
        let pixels = primary.len();
        Self {
            width,
            height,
            camera,
            settings,
            primary,
            ao: Estimate::new(1, pixels),
            direct: Estimate::new(3, pixels),
            shadow: Estimate::new(1, pixels),
            indirect: Estimate::new(3, pixels),
            rays: pixels as u64,
            seconds: start.elapsed().as_secs_f64(),
        }
    }

    /// Pixels with geometry (the G-buffer's coverage).
    pub fn geometry(&self) -> Vec<bool> {
        self.primary.iter().map(Option::is_some).collect()
    }

    pub fn estimate(&self, buffer: RefBuffer) -> &Estimate {
        match buffer {
            RefBuffer::Ao => &self.ao,
            RefBuffer::Direct => &self.direct,
            RefBuffer::Shadow => &self.shadow,
            RefBuffer::Indirect => &self.indirect,
        }
    }

    /// Rays per second over everything traced so far.
    pub fn rays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-9)
    }

    /// Add `samples` per half and pixel to `buffer` (direct and shadow are refined together).
    /// `progress` is called with the number of rows finished, from any thread.
    pub fn refine(
        &mut self,
        accel: &Accel,
        scene: &Scene,
        buffer: RefBuffer,
        samples: u32,
        progress: &(dyn Fn(u64) + Sync),
    ) {
        if samples == 0 {
            return;
        }
        let start = std::time::Instant::now();
        let width = self.width as usize;
        let rays = AtomicU64::new(0);
        let s = self.settings;
        let light = scene.light;
        // The second value of AO and indirect samples is unused.
        let mut scratch = Estimate::new(1, self.primary.len());
        let ctx = Ctx {
            primary: &self.primary,
            width,
            first: self.estimate(buffer).per_half,
            samples,
            seed: s.seed,
            rays: &rays,
        };
        match buffer {
            RefBuffer::Ao => ctx.run(&mut self.ao, &mut scratch, buffer, progress, |p, u| {
                let v = ao_sample(accel, p, &s.ao, u);
                ([v, 0.0, 0.0], 0.0)
            }),
            RefBuffer::Indirect => ctx.run(
                &mut self.indirect,
                &mut scratch,
                buffer,
                progress,
                |p, u| {
                    let c = indirect_sample(accel, &scene.mesh, p, &light, u);
                    (c.to_array(), 0.0)
                },
            ),
            RefBuffer::Direct | RefBuffer::Shadow => ctx.run(
                &mut self.direct,
                &mut self.shadow,
                RefBuffer::Direct,
                progress,
                |p, u| {
                    let (c, v) = direct_sample(accel, p, &light, s.light_radius, u);
                    (c.to_array(), v)
                },
            ),
        }
        self.rays += rays.load(Ordering::Relaxed);
        self.seconds += start.elapsed().as_secs_f64();
    }
}

/// What every row of a refinement shares.
struct Ctx<'a> {
    primary: &'a [Option<Primary>],
    width: usize,
    first: u32,
    samples: u32,
    seed: u32,
    rays: &'a AtomicU64,
}

impl Ctx<'_> {
    /// Add the samples to `main`, and the second value of each sample to `extra` (a
    /// one-channel estimate of the same samples: the shadow visibility beside direct light).
    fn run<F>(
        &self,
        main: &mut Estimate,
        extra: &mut Estimate,
        buffer: RefBuffer,
        progress: &(dyn Fn(u64) + Sync),
        sample: F,
    ) where
        F: Fn(&Primary, Vec2) -> ([f32; 3], f32) + Sync,
    {
        let ch = main.channels;
        let w = self.width.max(1);
        let [m0, m1] = &mut main.sums;
        let [e0, e1] = &mut extra.sums;
        m0.par_chunks_mut(w * ch)
            .zip(m1.par_chunks_mut(w * ch))
            .zip(e0.par_chunks_mut(w).zip(e1.par_chunks_mut(w)))
            .enumerate()
            .for_each(|(y, ((r0, r1), (x0, x1)))| {
                // Ctrl-C: leave the remaining rows; the caller discards the sums.
                if crate::interrupt::requested() {
                    return;
                }
                let mut traced = 0u64;
                for x in 0..w {
                    let pixel = y * w + x;
                    let Some(p) = &self.primary[pixel] else {
                        continue;
                    };
                    for (half, (r, xr)) in [(&mut *r0, &mut *x0), (&mut *r1, &mut *x1)]
                        .into_iter()
                        .enumerate()
                    {
                        let sh = shift(pixel as u32, buffer as u32, half as u32, self.seed);
                        let mut acc = [0.0f64; 3];
                        let mut acc_extra = 0.0f64;
                        for i in self.first..self.first + self.samples {
                            let (v, e) = sample(p, r2(i, sh));
                            for c in 0..ch {
                                acc[c] += v[c] as f64;
                            }
                            acc_extra += e as f64;
                        }
                        for c in 0..ch {
                            r[x * ch + c] += acc[c];
                        }
                        xr[x] += acc_extra;
                    }
                    traced += 2 * self.samples as u64 * rays_per_sample(buffer);
                }
                self.rays.fetch_add(traced, Ordering::Relaxed);
                progress(1);
            });
        main.per_half += self.samples;
        extra.per_half += self.samples;
    }
}

/// Direct radiance's unshadowed part is deterministic; with the point light one sample per
/// half is exact, so the direct buffers need more only with a spherical light.
pub fn direct_is_exact(settings: &Settings) -> bool {
    settings.light_radius <= 0.0
}

//! One configuration of one scene along a camera path: `warmup` frames at the path's first
//! camera (GPU clocks, caches and the light view settle; left out of the statistics), then
//! `frames` frames along the path. Returns the per-frame timings as a [`Report`] and the last
//! frame's buffers for the error columns.

use super::metrics::Channels;
use super::{warmup, Report};
use crate::effects::TermKind;
use crate::error::Result;
use crate::frontend::progress::Progress;
use crate::frontend::sink::FrameSink;
use crate::renderer::{RenderConfig, Renderer};
use crate::resources::targets::Target;
use crate::scene::path::frame_time;
use crate::scene::{Camera, CameraPath, Keyframe, Scene};
use crate::vk::{Context, ImageData};
use serde::Serialize;
use std::sync::Arc;

/// A buffer whose error against the reference is reported.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Buffer {
    /// The tonemapped output image (RGBA8, compared as RGB in 0..1).
    Final,
    /// Ambient visibility as composited (red channel): the term of the effect that darkens the
    /// ambient light (`Registration::ambient`): a visibility, or a modulation factor.
    Ao,
    /// Direct light with PCF shadows (linear RGB radiance).
    Direct,
    /// Shadow visibility as the direct pass reads it (red channel).
    Shadow,
    /// One-bounce indirect light: eq 9's sum, π E₁ for E₁ the bounce's irradiance (linear RGB,
    /// before the composite's albedo / π · 1 / π; docs/REFERENCE.md).
    Indirect,
}

impl Buffer {
    pub const ALL: [Buffer; 5] = [
        Buffer::Final,
        Buffer::Ao,
        Buffer::Indirect,
        Buffer::Direct,
        Buffer::Shadow,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Buffer::Final => "final",
            Buffer::Ao => "ao",
            Buffer::Direct => "direct",
            Buffer::Shadow => "shadow",
            Buffer::Indirect => "indirect",
        }
    }

    pub fn target(self) -> Target {
        match self {
            Buffer::Final => Target::Output,
            Buffer::Ao => Target::Ao,
            Buffer::Direct => Target::Direct,
            Buffer::Shadow => Target::Shadow,
            Buffer::Indirect => Target::Indirect,
        }
    }

    pub fn channels(self) -> Channels {
        match self {
            Buffer::Ao | Buffer::Shadow => Channels::Red,
            Buffer::Final | Buffer::Direct | Buffer::Indirect => Channels::Rgb,
        }
    }

    /// Whether `config` produces this buffer.
    pub fn present(self, config: &RenderConfig) -> bool {
        let effects = &config.effects;
        match self {
            Buffer::Final => true,
            Buffer::Ao => crate::effects::ambient_enabled(config),
            Buffer::Direct | Buffer::Shadow => effects.direct,
            Buffer::Indirect => effects.indirect,
        }
    }
}

/// What to run.
pub struct RunSpec<'a> {
    /// Shown on the progress bar.
    pub label: &'a str,
    pub config: RenderConfig,
    pub path: &'a CameraPath,
    pub frames: u32,
    pub warmup: u32,
    /// Warm up along the path, over the `warmup` frames leading up to its time 0 (at negative
    /// times: orbits and dollies are periodic, keyframe paths are walked backwards), so the
    /// cache enters the measured frames in its moving steady state; otherwise held at the
    /// path's first camera. Either way the measured frames are the same.
    pub warmup_along_path: bool,
    /// Frame i of the path is shown at i / fps seconds.
    pub fps: f32,
    /// Also read the buffers after the warmup frames (the reference row compares its last
    /// frame with them).
    pub snapshot_after_warmup: bool,
    /// Read the output (and indirect light) back after every measured frame and record the
    /// flicker measure (waits for each frame: for error and flicker runs, not timing).
    pub flicker: bool,
    pub progress: bool,
}

/// The last frame of a run.
pub struct LastFrame {
    pub camera: Camera,
    pub buffers: Vec<(Buffer, ImageData)>,
    /// Geometry pixels of the output (G-buffer position alpha != 0; supersampled: any of
    /// the pixel's samples), row order.
    pub geometry: Vec<bool>,
    /// The G-buffer position and normal at the render size when it exceeds the output's
    /// (`--aa ssaa16`): antialiasing's edge pixels come from them.
    pub supersampled: Option<(ImageData, ImageData)>,
}

impl LastFrame {
    pub fn buffer(&self, which: Buffer) -> Option<&ImageData> {
        self.buffers
            .iter()
            .find(|(b, _)| *b == which)
            .map(|(_, d)| d)
    }
}

pub struct Measured {
    pub report: Report,
    pub last: LastFrame,
    /// The buffers after the warmup frames, when asked for.
    pub after_warmup: Option<LastFrame>,
    /// Whether the effects' work counters had settled by the end of the warmup
    /// (`warmup::settled` over its last two rotation limits of frames).
    pub warmup_settled: bool,
    /// With `RunSpec::flicker`: the measured frames' consecutive differences.
    pub flicker: Option<Flicker>,
}

impl Measured {
    /// The last frame's output image (a run always reads it back).
    pub fn final_image(&self) -> Result<&ImageData> {
        self.last
            .buffer(Buffer::Final)
            .ok_or_else(|| crate::error::Error::Config("the run read back no output image".into()))
    }
}

/// Chen et al.'s flicker measure: the mean squared difference between consecutive frames,
/// per pair of consecutive measured frames.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Flicker {
    /// Of the output image (RGB as encoded, 0..1: the measure's "barely notable" threshold
    /// 2.5e-5 is on this scale).
    pub final_msd: Vec<f64>,
    /// Of the indirect light (π E₁, linear RGB), when it is rendered.
    pub indirect_msd: Vec<f64>,
}

impl Flicker {
    pub fn mean(v: &[f64]) -> Option<f64> {
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    }
}

/// Reads the output (and the indirect light) back after each frame and measures its
/// difference from the frame before (waits for every frame: for error and flicker runs, not
/// timing).
#[derive(Default)]
pub struct FlickerProbe {
    previous: Option<(ImageData, Option<ImageData>)>,
    /// (frame index, its measure) of every frame after the first.
    pub measures: Vec<(u64, super::report::FrameFlicker)>,
}

impl FlickerProbe {
    /// After `renderer` has submitted a frame.
    pub fn after_frame(&mut self, renderer: &mut Renderer) -> Result<()> {
        let index = renderer.frame_index().saturating_sub(1);
        let output = renderer.read(Target::Output)?;
        let indirect = if renderer.has_target(Target::Indirect) {
            Some(renderer.read(Target::Indirect)?)
        } else {
            None
        };
        if let Some((o, ind)) = &self.previous {
            let indirect_msd = match (&indirect, ind) {
                (Some(a), Some(b)) => Some(msd(a, b)?),
                _ => None,
            };
            self.measures.push((
                index,
                super::report::FrameFlicker {
                    final_msd: msd(&output, o)?,
                    indirect_msd,
                },
            ));
        }
        self.previous = Some((output, indirect));
        Ok(())
    }

    /// The measures as the tables keep them.
    pub fn into_flicker(self) -> Flicker {
        Flicker {
            final_msd: self.measures.iter().map(|(_, f)| f.final_msd).collect(),
            indirect_msd: self
                .measures
                .iter()
                .filter_map(|(_, f)| f.indirect_msd)
                .collect(),
        }
    }
}

/// Mean squared difference of two images of one size over every pixel's RGB.
pub fn msd(a: &ImageData, b: &ImageData) -> Result<f64> {
    let e = super::metrics::image_error(a, b, Channels::Rgb, None)?;
    Ok(e.rmse.map_or(0.0, |r| r * r))
}

/// The camera of the last frame of a `frames`-frame run along `path` at `fps`.
pub fn last_camera(scene: &Scene, path: &CameraPath, frames: u32, fps: f32) -> Camera {
    let time = frame_time(frames.max(1) - 1, fps);
    path.camera_at(&scene.camera, &scene.orbit(), time)
}

/// A path that holds `camera` on every frame (lens and up come from the scene's camera, as for
/// any path, so `camera` must share them: use [`last_camera`]).
pub fn held_at(camera: &Camera) -> CameraPath {
    CameraPath::Keyframes(vec![Keyframe {
        time: 0.0,
        position: camera.position.to_array(),
        target: camera.target.to_array(),
    }])
}

/// Render `spec` on a fresh renderer for `scene`, into `sink` (offscreen or a window).
pub fn measure(
    ctx: &Arc<Context>,
    sink: &mut dyn FrameSink,
    scene: &Scene,
    spec: &RunSpec<'_>,
) -> Result<Measured> {
    let frames = spec.frames.max(1);
    // Tables and sweeps time what a technique costs per frame: a frame skipped because
    // nothing changed would say nothing about it (`bench` leaves the choice to the user).
    let config = RenderConfig {
        skip_unchanged: false,
        ..spec.config
    };
    let mut renderer = Renderer::new(ctx, scene.clone(), config)?;
    let base = renderer.scene.camera;
    let orbit = renderer.scene.orbit();
    let mut bar = Progress::new((spec.warmup + frames) as u64, spec.label, spec.progress);
    let mut timings = Vec::with_capacity((spec.warmup + frames) as usize);
    let first = spec.path.camera_at(&base, &orbit, 0.0);
    sink.begin(spec.label);
    // Each frame polls for Ctrl-C: a signal stops the run between frames.
    let _scope = crate::interrupt::graceful();
    for i in 0..spec.warmup {
        let (camera, time) = if spec.warmup_along_path {
            let before = (spec.warmup - i) as f32 / spec.fps;
            (spec.path.camera_at(&base, &orbit, -before), -before)
        } else {
            (first, 0.0)
        };
        renderer.set_time(time);
        timings.extend(sink.frame(&mut renderer, &camera)?);
        bar.inc();
    }
    let after_warmup = if spec.snapshot_after_warmup {
        timings.extend(renderer.finish()?);
        Some(read_frame(&mut renderer, first)?)
    } else {
        None
    };
    let mut camera = first;
    let mut probe = spec.flicker.then(FlickerProbe::default);
    for i in 0..frames {
        camera = spec.path.camera_at(&base, &orbit, frame_time(i, spec.fps));
        renderer.set_time(frame_time(i, spec.fps));
        timings.extend(sink.frame(&mut renderer, &camera)?);
        if let Some(p) = &mut probe {
            p.after_frame(&mut renderer)?;
        }
        bar.inc();
    }
    let flicker = probe.map(FlickerProbe::into_flicker);
    timings.extend(renderer.finish()?);
    bar.finish();
    let last = read_frame(&mut renderer, camera)?;
    let warmup_work: Vec<u64> = timings
        .iter()
        .filter(|t| t.frame < spec.warmup as u64)
        .map(warmup::work)
        .collect();
    let warmup_settled = warmup::settled(
        &warmup_work,
        spec.config.temporal.rotation_limit.max(4) as usize,
        spec.config.width as u64 * spec.config.height as u64,
    );
    // Along the path is the tables' and sweeps' `--warmup converged`; a fixed count is held
    // at the first camera, as bench's.
    let outcome = warmup::Outcome {
        mode: if spec.warmup_along_path {
            "converged"
        } else {
            "frames"
        },
        frames: spec.warmup,
        settled: warmup_settled || !spec.warmup_along_path,
    };
    let config = report_config(
        ctx,
        &renderer,
        spec.path,
        RunLength {
            fps: spec.fps,
            frames,
            warmup: outcome,
        },
        sink.present_mode(),
    );
    let names: Vec<&str> = crate::renderer::all_passes()
        .iter()
        .map(|p| p.name())
        .collect();
    let report = Report::new(
        &ctx.info,
        spec.config.width,
        spec.config.height,
        config,
        &names,
        &timings,
        spec.warmup as u64,
    );
    Ok(Measured {
        report,
        last,
        after_warmup,
        warmup_settled,
        flicker,
    })
}

/// Frame rate, measured frames and warmup of a run, for its report.
pub struct RunLength {
    pub fps: f32,
    pub frames: u32,
    pub warmup: warmup::Outcome,
}

/// A report's `config` object (docs/formats.md: the bench format), the same for bench, tables and
/// sweeps: the scene and path, the run's length, the render configuration and the device.
pub fn report_config(
    ctx: &Context,
    renderer: &Renderer,
    path: &CameraPath,
    run: RunLength,
    present_mode: Option<&'static str>,
) -> serde_json::Value {
    let config = &renderer.config;
    serde_json::json!({
        "scene": renderer.scene.name,
        "triangles": renderer.scene.mesh.triangle_count(),
        "path": path.name(),
        "fps": run.fps,
        // Path time of the measured frames (the warmup frames come first on the path).
        "seconds": run.frames as f32 / run.fps,
        "frames": run.frames,
        "warmup": run.warmup,
        "rsm_size": config.rsm_size,
        "pcf_samples": config.pcf.samples(),
        "pcf_radius_texels": config.pcf.radius_texels,
        "render": config,
        "device_type": ctx.info.device_type,
        "api_version": ctx.info.api_version,
        "window": present_mode.is_some(),
        "present_mode": present_mode,
    })
}

/// One buffer of the frame last rendered.
fn read_buffer(renderer: &mut Renderer, b: Buffer) -> Result<ImageData> {
    if b == Buffer::Ao {
        return ambient_visibility(renderer);
    }
    renderer.read(b.target())
}

/// Ambient visibility as composited, from the effect whose term darkens the ambient light: a
/// visibility term as it is (red), a bounce-and-modulation term's factor (alpha) in the red
/// channel of a single-channel image, as a visibility is stored.
fn ambient_visibility(renderer: &mut Renderer) -> Result<ImageData> {
    let ambient = renderer.term_kinds().into_iter().find(|(_, kind)| {
        matches!(
            kind,
            TermKind::AmbientVisibility | TermKind::BounceAndModulation
        )
    });
    let Some((id, _)) = ambient else {
        // No effect darkens the ambient light: the read names the missing buffer.
        return renderer.read(Target::Ao);
    };
    let (kind, m) = renderer.read_term(id)?;
    if kind == TermKind::AmbientVisibility {
        return Ok(m);
    }
    let mut bytes = Vec::with_capacity(m.width as usize * m.height as usize * 4);
    for y in 0..m.height {
        for x in 0..m.width {
            bytes.extend_from_slice(&m.texel(x, y)[3].to_le_bytes());
        }
    }
    Ok(ImageData {
        width: m.width,
        height: m.height,
        format: ash::vk::Format::R32_SFLOAT,
        bytes,
    })
}

/// Every buffer of the frame last rendered (the GPU must be idle: after `finish`).
pub fn read_frame(renderer: &mut Renderer, camera: Camera) -> Result<LastFrame> {
    let config = renderer.config;
    let mut buffers = Vec::new();
    for b in Buffer::ALL {
        if b.present(&config) {
            buffers.push((b, read_buffer(renderer, b)?));
        }
    }
    let position = renderer.read(Target::GPosition)?;
    let scale = renderer.config.aa.mode.supersampling();
    let geometry = super::metrics::geometry_mask(&position);
    let (geometry, supersampled) = if scale > 1 {
        let normal = renderer.read(Target::GNormal)?;
        let w = position.width as usize;
        let out_w = w / scale as usize;
        let any = |i: usize| {
            let (x, y) = (i % out_w * scale as usize, i / out_w * scale as usize);
            (0..scale as usize * scale as usize)
                .any(|k| geometry[(y + k / scale as usize) * w + x + k % scale as usize])
        };
        let out_len = geometry.len() / (scale * scale) as usize;
        ((0..out_len).map(any).collect(), Some((position, normal)))
    } else {
        (geometry, None)
    };
    Ok(LastFrame {
        camera,
        buffers,
        geometry,
        supersampled,
    })
}

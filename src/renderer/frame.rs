//! Per-frame constants (`Frame` in shaders/include/frame.glsl), std140.

use super::config::{AoEstimator, Epsilon, RenderConfig};
use crate::scene::{Camera, SpotLight};
use glam::{Mat4, Vec3};

/// The PCF kernel: a regular grid (the thesis's 49-sample baseline, or hard shadows), or a disc
/// of Vogel-spiral samples that is rotated and scaled every frame and accumulated (the thesis's
/// 9-sample PCF with the cache; many samples without reuse for references).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kernel", rename_all = "lowercase")]
pub enum PcfKernel {
    Grid { side: u32 },
    Disc { samples: u32 },
}

/// PCF configuration: the kernel spread over +-`radius_texels` shadow-map texels.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Pcf {
    pub kernel: PcfKernel,
    pub radius_texels: f32,
}

impl Pcf {
    /// The thesis's baseline soft shadow: 49 samples on a 7x7 grid.
    pub const DEFAULT: Pcf = Pcf {
        kernel: PcfKernel::Grid { side: 7 },
        radius_texels: 3.0,
    };
    pub const HARD: Pcf = Pcf {
        kernel: PcfKernel::Grid { side: 1 },
        radius_texels: 0.0,
    };
    /// The thesis's 9-sample PCF, rotated and scaled per frame and accumulated.
    pub const NINE: Pcf = Pcf {
        kernel: PcfKernel::Disc { samples: 9 },
        radius_texels: 3.0,
    };

    /// `hard`, `9` (the accumulated disc), another square count for a grid (25, 49, ...), or
    /// `disc:N` for an N-sample disc.
    pub fn parse(s: &str) -> Result<Pcf, String> {
        if s == "hard" || s == "1" {
            return Ok(Pcf::HARD);
        }
        if let Some(n) = s.strip_prefix("disc:") {
            let samples: u32 = n
                .parse()
                .map_err(|_| format!("--pcf disc:N takes a sample count, not {s:?}"))?;
            if !(1..=4096).contains(&samples) {
                return Err(format!("--pcf {s}: disc samples must be in 1..=4096"));
            }
            return Ok(Pcf {
                kernel: PcfKernel::Disc { samples },
                ..Pcf::NINE
            });
        }
        let n: u32 = s.parse().map_err(|_| {
            format!("--pcf takes 'hard', 9, a square sample count like 49, or disc:N, not {s:?}")
        })?;
        if n == 9 {
            return Ok(Pcf::NINE);
        }
        let side = (n as f64).sqrt().round() as u32;
        if side * side != n || !(2..=32).contains(&side) {
            return Err(format!(
                "--pcf {n}: the sample count must be 9 or a square between 4 and 1024 (25, 49, ...)"
            ));
        }
        Ok(Pcf {
            kernel: PcfKernel::Grid { side },
            radius_texels: Pcf::DEFAULT.radius_texels,
        })
    }

    pub fn samples(&self) -> u32 {
        match self.kernel {
            PcfKernel::Grid { side } => side * side,
            PcfKernel::Disc { samples } => samples,
        }
    }

    /// (kernel code for the shader: 0 grid, 1 disc; grid side or disc samples).
    pub fn shader_params(&self) -> (u32, u32) {
        match self.kernel {
            PcfKernel::Grid { side } => (0, side),
            PcfKernel::Disc { samples } => (1, samples),
        }
    }
}

/// Everything that changes per frame, besides the configuration.
pub struct FrameInputs<'a> {
    pub camera: &'a Camera,
    /// Last frame's camera view-projection (eq 1); equal to this frame's on the first frame.
    pub prev_view_proj: Mat4,
    pub light: &'a SpotLight,
    pub ambient: Vec3,
    pub frame: u64,
    /// False on the first frame and after a resize or camera cut: every pixel is new.
    pub history_valid: bool,
    /// Bounding radius of the scene: the AO radius is relative to it.
    pub scene_radius: f32,
}

/// The uniform block's bytes, in declaration order (std140: every member is 16-byte aligned).
pub struct FrameUniforms {
    words: Vec<u32>,
}

impl FrameUniforms {
    pub const SIZE: usize = 3 * 64 + 13 * 16;

    pub fn new(config: &RenderConfig, f: &FrameInputs<'_>) -> Self {
        let mut w: Vec<u32> = Vec::with_capacity(Self::SIZE / 4);
        let aspect = config.width as f32 / config.height as f32;
        let light = f.light;
        for m in [
            f.camera.view_proj(aspect),
            f.prev_view_proj,
            light.view_proj(),
        ] {
            w.extend(m.to_cols_array().iter().map(|x| x.to_bits()));
        }
        let vec4 = |v: [f32; 4], w: &mut Vec<u32>| w.extend(v.iter().map(|x| x.to_bits()));
        let tan_half_fov = (0.5 * f.camera.vfov_deg).to_radians().tan();
        vec4(f.camera.position.extend(tan_half_fov).to_array(), &mut w);
        let cos_outer = light.outer_deg.to_radians().cos();
        let cos_inner = light.inner_deg.to_radians().cos();
        let axis = light.direction.normalize_or(Vec3::NEG_Y);
        let light_half_fov = (0.5 * light.frustum_fov_deg()).to_radians();
        vec4(light.position.extend(cos_outer).to_array(), &mut w);
        vec4(axis.extend(cos_inner).to_array(), &mut w);
        vec4(light.intensity.extend(light.near).to_array(), &mut w);
        let pcf = config.pcf;
        let rsm = config.rsm_size as f32;
        vec4(
            [light.far, light_half_fov.tan(), rsm, pcf.radius_texels],
            &mut w,
        );
        vec4(f.ambient.extend(0.0).to_array(), &mut w);
        let (pcf_kernel, pcf_count) = pcf.shader_params();
        w.extend([config.width, config.height, f.frame as u32, pcf_count]);
        let t = &config.temporal;
        w.extend([f.history_valid as u32, 0, 0, t.rotation_limit]);
        let (eps, eps_mode) = match t.epsilon {
            Epsilon::Relative { scale } => (scale, 0.0),
            Epsilon::Absolute { epsilon } => (epsilon, 1.0),
        };
        vec4(
            [
                t.accumulate.code() as f32,
                t.accumulate.parameter(),
                eps,
                eps_mode,
            ],
            &mut w,
        );
        let ao = &config.ao;
        let radius = ao.radius * f.scene_radius.max(f32::MIN_POSITIVE);
        vec4(
            [radius, ao.attenuation[0], ao.attenuation[1], ao.near_px],
            &mut w,
        );
        let (dirs, steps) = ao.directions_steps();
        let (count, estimator) = match ao.estimator {
            AoEstimator::Thesis => (steps, 0),
            AoEstimator::Crytek => (ao.samples, 1),
        };
        w.extend([dirs, count, ao.patterns, estimator]);
        let offset = if ao.patterns > 1 { 0.5 } else { 0.0 };
        vec4(
            [t.rotation_deg.to_radians(), offset, pcf_kernel as f32, 0.0],
            &mut w,
        );
        let ind = &config.indirect;
        vec4(
            [
                ind.vpls as f32,
                ind.visibility as u32 as f32,
                ind.half_res as u32 as f32,
                0.0,
            ],
            &mut w,
        );
        debug_assert_eq!(w.len() * 4, Self::SIZE);
        Self { words: w }
    }

    pub fn bytes(&self) -> Vec<u8> {
        self.words.iter().flat_map(|w| w.to_le_bytes()).collect()
    }
}

//! Per-frame constants (`Frame` in shaders/include/frame.glsl), std140.

use crate::scene::{Camera, SpotLight};
use glam::{Mat4, Vec3};

/// PCF configuration: `side` x `side` depth comparisons spread over +-`radius` shadow texels.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Pcf {
    pub side: u32,
    pub radius_texels: f32,
}

impl Pcf {
    /// The thesis's baseline soft shadow: 49 samples.
    pub const DEFAULT: Pcf = Pcf {
        side: 7,
        radius_texels: 3.0,
    };
    pub const HARD: Pcf = Pcf {
        side: 1,
        radius_texels: 0.0,
    };

    /// `hard` or a square sample count (9, 25, 49, ...).
    pub fn parse(s: &str) -> Result<Pcf, String> {
        if s == "hard" || s == "1" {
            return Ok(Pcf::HARD);
        }
        let n: u32 = s.parse().map_err(|_| {
            format!("--pcf takes 'hard' or a square sample count like 9 or 49, not {s:?}")
        })?;
        let side = (n as f64).sqrt().round() as u32;
        if side * side != n || !(2..=15).contains(&side) {
            return Err(format!(
                "--pcf {n}: the sample count must be a square between 4 and 225 (9, 25, 49, ...)"
            ));
        }
        Ok(Pcf {
            side,
            radius_texels: Pcf::DEFAULT.radius_texels,
        })
    }

    pub fn samples(&self) -> u32 {
        self.side * self.side
    }
}

/// Bytes of the uniform block, in declaration order.
pub struct FrameUniforms {
    words: Vec<u32>,
}

impl FrameUniforms {
    pub const SIZE: usize = 2 * 64 + 7 * 16;

    #[allow(clippy::too_many_arguments)]
    pub fn new(
        camera: &Camera,
        aspect: f32,
        light: &SpotLight,
        ambient: Vec3,
        width: u32,
        height: u32,
        frame: u64,
        pcf: Pcf,
        rsm_size: u32,
    ) -> Self {
        let mut w = Vec::with_capacity(Self::SIZE / 4);
        let mat = |m: Mat4, w: &mut Vec<u32>| {
            w.extend(m.to_cols_array().iter().map(|f| f.to_bits()));
        };
        mat(camera.view_proj(aspect), &mut w);
        mat(light.view_proj(), &mut w);
        let mut vec4 = |v: [f32; 4]| w.extend(v.iter().map(|f| f.to_bits()));
        let cos_outer = light.outer_deg.to_radians().cos();
        let cos_inner = light.inner_deg.to_radians().cos();
        let half_fov = (0.5 * light.frustum_fov_deg()).to_radians();
        vec4(camera.position.extend(1.0).to_array());
        vec4(light.position.extend(cos_outer).to_array());
        vec4(
            light
                .direction
                .normalize_or(Vec3::NEG_Y)
                .extend(cos_inner)
                .to_array(),
        );
        vec4(light.intensity.extend(light.near).to_array());
        vec4([
            light.far,
            half_fov.tan(),
            rsm_size as f32,
            pcf.radius_texels,
        ]);
        vec4(ambient.extend(0.0).to_array());
        w.extend([width, height, frame as u32, pcf.side]);
        Self { words: w }
    }

    pub fn bytes(&self) -> Vec<u8> {
        self.words.iter().flat_map(|w| w.to_le_bytes()).collect()
    }
}

//! The reference's final image: the renderer's composite (shaders/composite.comp) applied to
//! the reference buffers: ambient × albedo × AO visibility + direct radiance + albedo/π ·
//! (π·E₁)/π, then Reinhard c/(1 + c) and the sRGB encoding, for the terms a run estimates.

use super::trace::Reference;
use glam::Vec3;

/// The reference buffers a configuration's final image estimates: each effect says which of
/// them it estimates (`Registration::estimates`, gathered by `effects::estimated_terms`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Terms {
    pub ambient_occlusion: bool,
    pub direct: bool,
    pub indirect: bool,
}

impl Terms {
    /// Every term (the `ssgi reference` command's final image).
    pub const ALL: Terms = Terms {
        ambient_occlusion: true,
        direct: true,
        indirect: true,
    };
    pub const NONE: Terms = Terms {
        ambient_occlusion: false,
        direct: false,
        indirect: false,
    };
    pub const AMBIENT_OCCLUSION: Terms = Terms {
        ambient_occlusion: true,
        ..Terms::NONE
    };
    pub const DIRECT: Terms = Terms {
        direct: true,
        ..Terms::NONE
    };
    pub const INDIRECT: Terms = Terms {
        indirect: true,
        ..Terms::NONE
    };

    /// The terms either estimates.
    pub fn union(self, other: Terms) -> Terms {
        Terms {
            ambient_occlusion: self.ambient_occlusion || other.ambient_occlusion,
            direct: self.direct || other.direct,
            indirect: self.indirect || other.indirect,
        }
    }
}

fn srgb_encode(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Tonemapped, sRGB-encoded RGB in [0, 1], three values per pixel; background black.
pub fn final_image(r: &Reference, ambient: Vec3, terms: Terms) -> Vec<f32> {
    let (ao, direct, indirect) = (r.ao.mean(), r.direct.mean(), r.indirect.mean());
    let rgb = |v: &[f32], i: usize| Vec3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    let mut out = vec![0.0f32; 3 * r.primary.len()];
    for (i, p) in r.primary.iter().enumerate() {
        let Some(p) = p else { continue };
        let albedo = p.surface.albedo;
        let visibility = if terms.ambient_occlusion { ao[i] } else { 1.0 };
        let mut c = ambient * albedo * visibility;
        if terms.direct {
            c += rgb(&direct, i);
        }
        if terms.indirect {
            c += albedo / std::f32::consts::PI * rgb(&indirect, i) / std::f32::consts::PI;
        }
        if !c.is_finite() {
            c = Vec3::ZERO; // as the composite: non-finite input shows black
        }
        let mapped = c / (Vec3::ONE + c);
        for k in 0..3 {
            out[3 * i + k] = srgb_encode(mapped[k].clamp(0.0, 1.0));
        }
    }
    out
}

/// The final image quantized as the renderer's RGBA8 output is (round to nearest).
pub fn to_rgb8(values: &[f32]) -> Vec<u8> {
    values
        .iter()
        .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect()
}

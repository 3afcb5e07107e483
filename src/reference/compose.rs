//! The reference's final image: the renderer's composite (shaders/composite.comp) applied to
//! the reference buffers: ambient × albedo × AO visibility + direct radiance + albedo/π ·
//! (π·E₁)/π, then Reinhard c/(1 + c) and the sRGB encoding, for the effects a run enabled.

use super::trace::Reference;
use crate::renderer::config::Effects;
use glam::Vec3;

fn srgb_encode(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Tonemapped, sRGB-encoded RGB in [0, 1], three values per pixel; background black.
pub fn final_image(r: &Reference, ambient: Vec3, effects: Effects) -> Vec<f32> {
    let (ao, direct, indirect) = (r.ao.mean(), r.direct.mean(), r.indirect.mean());
    let rgb = |v: &[f32], i: usize| Vec3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    let mut out = vec![0.0f32; 3 * r.primary.len()];
    for (i, p) in r.primary.iter().enumerate() {
        let Some(p) = p else { continue };
        let albedo = p.surface.albedo;
        let visibility = if effects.ao { ao[i] } else { 1.0 };
        let mut c = ambient * albedo * visibility;
        if effects.direct {
            c += rgb(&direct, i);
        }
        if effects.indirect {
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

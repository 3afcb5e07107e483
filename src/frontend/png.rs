//! PNG output: the tonemapped image as is, and false-colour views of G-buffer / RSM targets.

use crate::resources::targets::Target;
use crate::scene::Aabb;
use crate::vk::ImageData;

pub use crate::files::write_png_rgba8 as write_rgba8;

fn to_u8(v: f32) -> u8 {
    if v.is_finite() {
        (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
    } else {
        0
    }
}

/// A viewable RGBA8 picture of `data`: positions mapped from the scene bounds to 0..1,
/// normals as n/2 + 1/2, depth and flux (the RSM's stored albedo x intensity) normalised by their
/// range over the image, radiance
/// Reinhard-tonemapped.
pub fn visualize(target: Target, data: &ImageData, bounds: &Aabb) -> Vec<u8> {
    if let Some(rgba) = data.rgba8() {
        return rgba;
    }
    let n = (data.width * data.height) as usize;
    let texels: Vec<[f32; 4]> = (0..n)
        .map(|i| data.texel(i as u32 % data.width, i as u32 / data.width))
        .collect();
    let ext = bounds.extent().max(glam::Vec3::splat(1e-6));
    let (lo, hi) = match target {
        Target::GDepth | Target::RsmDepth => texels
            .iter()
            .map(|t| t[0])
            .filter(|d| *d < 1.0)
            .fold((f32::MAX, f32::MIN), |(a, b), d| (a.min(d), b.max(d))),
        Target::RsmFlux | Target::SsdoBounce => (
            0.0,
            texels
                .iter()
                .map(|t| t[0].max(t[1]).max(t[2]))
                .filter(|v| v.is_finite())
                .fold(1e-20f32, f32::max),
        ),
        _ => (0.0, 1.0),
    };
    let range = (hi - lo).max(1e-20);
    texels
        .iter()
        .flat_map(|t| {
            let rgb = match target {
                Target::GPosition
                | Target::GPositionHistory
                | Target::RsmPosition
                | Target::AoPositionLevel1
                | Target::AoPositionLevel2
                | Target::AoPositionLevel3 => {
                    if t[3] == 0.0 {
                        [0.0; 3]
                    } else {
                        let p = (glam::Vec3::new(t[0], t[1], t[2]) - bounds.min) / ext;
                        p.to_array()
                    }
                }
                Target::GNormal | Target::GNormalHistory | Target::RsmNormal => {
                    [t[0] * 0.5 + 0.5, t[1] * 0.5 + 0.5, t[2] * 0.5 + 0.5]
                }
                Target::GDepth | Target::RsmDepth => {
                    let v = if t[0] >= 1.0 {
                        0.0
                    } else {
                        1.0 - (t[0] - lo) / range
                    };
                    [v, v, v]
                }
                // Scaled by the brightest channel: flux and bounce span any range.
                Target::RsmFlux | Target::SsdoBounce => [t[0] / range, t[1] / range, t[2] / range],
                Target::Ao | Target::Shadow => [t[0], t[0], t[0]],
                // Linear albedo in 0..1, as stored (fp16).
                Target::GAlbedo => [t[0], t[1], t[2]],
                Target::SsdoModulation => [t[3], t[3], t[3]],
                // Samples per block: 50 (the paper's most) is white.
                Target::SsdoSamples => [t[0] / 50.0, t[0] / 50.0, t[0] / 50.0],
                Target::DiscardMask => [t[0], 0.0, 0.0],
                // Figure 4.10: red where recomputed from scratch (disoccluded), blue for the
                // refresh tile, yellow accumulating, grey converged, black background.
                Target::State => match t[0] as u32 {
                    0 => [0.25, 0.25, 0.25],
                    1 => [0.9, 0.8, 0.1],
                    2 => [0.9, 0.05, 0.05],
                    3 => [0.1, 0.3, 0.9],
                    _ => [0.0, 0.0, 0.0],
                },
                _ => [
                    t[0] / (1.0 + t[0]),
                    t[1] / (1.0 + t[1]),
                    t[2] / (1.0 + t[2]),
                ],
            };
            // The albedo keeps its alpha (0 over the background), as the 8-bit albedo did.
            let alpha = if target == Target::GAlbedo {
                to_u8(t[3])
            } else {
                255
            };
            [to_u8(rgb[0]), to_u8(rgb[1]), to_u8(rgb[2]), alpha]
        })
        .collect()
}

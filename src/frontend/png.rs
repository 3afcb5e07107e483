//! PNG output: the tonemapped image as is, and false-colour views of G-buffer / RSM targets.

use crate::resources::targets::{Look, Target};
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
    let look = target.look();
    let (lo, hi) = match look {
        Look::Depth => texels
            .iter()
            .map(|t| t[0])
            .filter(|d| *d < 1.0)
            .fold((f32::MAX, f32::MIN), |(a, b), d| (a.min(d), b.max(d))),
        Look::Brightest => (
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
            let rgb = match look {
                Look::Position => {
                    if t[3] == 0.0 {
                        [0.0; 3]
                    } else {
                        let p = (glam::Vec3::new(t[0], t[1], t[2]) - bounds.min) / ext;
                        p.to_array()
                    }
                }
                Look::Normal => [t[0] * 0.5 + 0.5, t[1] * 0.5 + 0.5, t[2] * 0.5 + 0.5],
                Look::Depth => {
                    let v = if t[0] >= 1.0 {
                        0.0
                    } else {
                        1.0 - (t[0] - lo) / range
                    };
                    [v, v, v]
                }
                Look::Brightest => [t[0] / range, t[1] / range, t[2] / range],
                Look::Red => [t[0], t[0], t[0]],
                Look::Albedo => [t[0], t[1], t[2]],
                Look::Alpha => [t[3], t[3], t[3]],
                Look::Count { full } => {
                    // `full` is a constant the view declares; max(1) keeps 0 from dividing.
                    let v = t[0] / full.max(1) as f32;
                    [v, v, v]
                }
                Look::Mask => [t[0], 0.0, 0.0],
                // Figure 4.10: red where recomputed from scratch (disoccluded), blue for the
                // refresh tile, yellow accumulating, grey converged, black background.
                Look::State => match t[0] as u32 {
                    0 => [0.25, 0.25, 0.25],
                    1 => [0.9, 0.8, 0.1],
                    2 => [0.9, 0.05, 0.05],
                    3 => [0.1, 0.3, 0.9],
                    _ => [0.0, 0.0, 0.0],
                },
                Look::Radiance | Look::Motion => [
                    t[0] / (1.0 + t[0]),
                    t[1] / (1.0 + t[1]),
                    t[2] / (1.0 + t[2]),
                ],
            };
            // The albedo keeps its alpha (0 over the background), as the 8-bit albedo did.
            let alpha = if look == Look::Albedo {
                to_u8(t[3])
            } else {
                255
            };
            [to_u8(rgb[0]), to_u8(rgb[1]), to_u8(rgb[2]), alpha]
        })
        .collect()
}

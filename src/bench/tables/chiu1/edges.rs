//! Where antialiasing matters, and how close an image comes to the reference there: the edge
//! pixels of a frame from its 16x supersampled G-buffer, and RMSE over a pixel mask.

use crate::error::{Error, Result};
use crate::vk::ImageData;
use glam::Vec3;

/// Two samples lie on one surface when their eye distances differ by at most this fraction of
/// the larger (a surface at a grazing angle spans a few per cent of depth within one pixel of a
/// 256-pixel view; a depth step beyond 5% is an edge the reconstruction's σz = 10 weighs at
/// most 0.78)...
pub const SAME_SURFACE_DISTANCE: f32 = 0.05;
/// ... and their normals by at most 25 degrees (cos 25° = 0.906).
pub const SAME_SURFACE_COS: f32 = 0.906;

/// Output pixels (row-major, `position.width / 4` wide) whose 16 samples of the 4x G-buffer
/// do not all lie on the surface of the first: background mixed with geometry, eye distances
/// or normals apart by more than the bounds above. `eye` is the camera position.
pub fn edge_mask(position: &ImageData, normal: &ImageData, eye: Vec3) -> Result<Vec<bool>> {
    let (w, h) = (position.width / 4, position.height / 4);
    if w == 0 || h == 0 || (normal.width, normal.height) != (position.width, position.height) {
        return Err(Error::Config(format!(
            "edge mask: a 4x G-buffer (position {}x{}, normal {}x{})",
            position.width, position.height, normal.width, normal.height
        )));
    }
    let sample = |x: u32, y: u32| {
        let p = position.texel(x, y);
        let n = normal.texel(x, y);
        let geometry = p[3] != 0.0;
        let distance = (Vec3::new(p[0], p[1], p[2]) - eye).length();
        (geometry, distance, Vec3::new(n[0], n[1], n[2]))
    };
    let mut mask = vec![false; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let first = sample(4 * x, 4 * y);
            let differs = (0..16).any(|k| {
                let s = sample(4 * x + k % 4, 4 * y + k / 4);
                if s.0 != first.0 {
                    return true;
                }
                if !s.0 {
                    return false;
                }
                let larger = s.1.max(first.1);
                // Guarded: two samples at the eye itself (distance 0) count as one surface.
                (s.1 - first.1).abs() > SAME_SURFACE_DISTANCE * larger
                    || s.2.dot(first.2) < SAME_SURFACE_COS
            });
            mask[(y * w + x) as usize] = differs;
        }
    }
    Ok(mask)
}

/// RMSE of the RGB channels (0..1 as stored) of `image` against `reference` over the pixels
/// `mask` selects (all pixels when `None`); `None` when the mask selects none.
pub fn rmse(
    image: &ImageData,
    reference: &ImageData,
    mask: Option<&[bool]>,
) -> Result<Option<f64>> {
    if (image.width, image.height) != (reference.width, reference.height) {
        return Err(Error::Config(format!(
            "image {}x{} against a reference of {}x{}",
            image.width, image.height, reference.width, reference.height
        )));
    }
    let (mut sum, mut count) = (0.0f64, 0usize);
    for y in 0..image.height {
        for x in 0..image.width {
            let i = (y * image.width + x) as usize;
            if mask.is_some_and(|m| !m.get(i).copied().unwrap_or(false)) {
                continue;
            }
            let (a, b) = (image.texel(x, y), reference.texel(x, y));
            sum += (0..3).map(|k| ((a[k] - b[k]) as f64).powi(2)).sum::<f64>();
            count += 3;
        }
    }
    Ok((count > 0).then(|| (sum / count as f64).sqrt()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use ash::vk::Format;

    fn image(w: u32, h: u32, texel: impl Fn(u32, u32) -> [f32; 4]) -> ImageData {
        let mut bytes = Vec::new();
        for y in 0..h {
            for x in 0..w {
                for c in texel(x, y) {
                    bytes.extend(c.to_le_bytes());
                }
            }
        }
        ImageData {
            width: w,
            height: h,
            format: Format::R32G32B32A32_SFLOAT,
            bytes,
        }
    }

    /// A wall at distance 10 with, in the left half of the 4x image up to column 5, a nearer
    /// plane (distance 5): output pixel column 1 holds the step (samples 4 and 5 near, 6 and 7
    /// far), columns 0 and 2-3 do not.
    #[test]
    fn a_depth_step_inside_a_pixel_is_an_edge() {
        let position = image(16, 8, |x, _| {
            let z = if x <= 5 { 5.0 } else { 10.0 };
            [0.0, 0.0, -z, 1.0]
        });
        let normal = image(16, 8, |_, _| [0.0, 0.0, 1.0, 0.0]);
        let mask = edge_mask(&position, &normal, Vec3::ZERO).unwrap();
        assert_eq!(mask, [false, true, false, false, false, true, false, false]);
    }

    #[test]
    fn background_against_geometry_and_a_crease_are_edges_but_a_slope_is_not() {
        // Column 0: background in one sample. Column 1: normals 90 degrees apart. Column 2:
        // depth rising 2% per sample column, 5.7% across the pixel (an edge); column 3: 0.1%
        // per sample column (one surface).
        let position = image(16, 4, |x, y| {
            let z = match x / 4 {
                2 => 10.0 * (1.0 + 0.02 * (x % 4) as f32),
                3 => 10.0 * (1.0 + 0.001 * (x % 4) as f32),
                _ => 10.0,
            };
            let w = if x == 0 && y == 3 { 0.0 } else { 1.0 };
            [0.0, 0.0, -z, w]
        });
        let normal = image(16, 4, |x, _| {
            if x == 5 {
                [1.0, 0.0, 0.0, 0.0]
            } else {
                [0.0, 0.0, 1.0, 0.0]
            }
        });
        let mask = edge_mask(&position, &normal, Vec3::ZERO).unwrap();
        assert_eq!(mask, [true, true, true, false]);
    }

    #[test]
    fn rmse_over_a_mask() {
        let a = image(2, 1, |x, _| [x as f32, 0.0, 0.0, 1.0]);
        let b = image(2, 1, |_, _| [0.0, 0.0, 0.0, 1.0]);
        let all = rmse(&a, &b, None).unwrap().unwrap();
        assert!((all - (1.0f64 / 6.0).sqrt()).abs() < 1e-12);
        let right = rmse(&a, &b, Some(&[false, true])).unwrap().unwrap();
        assert!((right - (1.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert_eq!(rmse(&a, &b, Some(&[false, false])).unwrap(), None);
        assert!(rmse(&a, &image(1, 1, |_, _| [0.0; 4]), None).is_err());
    }
}

//! FLIP (NVIDIA's perceptual image difference) of tonemapped LDR images, through `nv_flip`.
//!
//! `nv_flip` 0.1 asserts on bad input (short buffers, size mismatch) and computes
//! `width * height * 3` in `u32`, so the sizes are checked here and reported as errors.

use crate::error::{Error, Result};

/// Pixels per degree of visual angle: FLIP's default (0.7 m from a 0.7 m wide 3840-pixel
/// monitor), which sets the size of the differences FLIP can see.
pub const PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// FLIP of a test image against its reference.
#[derive(Clone, Debug, PartialEq)]
pub struct FlipResult {
    /// Mean of `per_pixel`: the single number FLIP's authors recommend reporting.
    pub mean: f64,
    /// Per-pixel error in 0..=1, row-major.
    pub per_pixel: Vec<f32>,
}

/// FLIP error of `test_rgb8` against `reference_rgb8`, both sRGB-encoded RGB8 (3 bytes per
/// pixel, row-major, no alpha), at [`PIXELS_PER_DEGREE`].
pub fn flip_ldr(
    test_rgb8: &[u8],
    reference_rgb8: &[u8],
    width: u32,
    height: u32,
) -> Result<FlipResult> {
    let bytes = u32::try_from(u64::from(width) * u64::from(height) * 3)
        .ok()
        .filter(|&b| b > 0)
        .ok_or_else(|| Error::Config(format!("FLIP cannot compare {width}x{height} images")))?
        as usize;
    for (name, data) in [("test", test_rgb8), ("reference", reference_rgb8)] {
        if data.len() != bytes {
            return Err(Error::Config(format!(
                "FLIP {name} image has {} bytes, a {width}x{height} RGB8 image {bytes}",
                data.len()
            )));
        }
    }
    let reference = nv_flip::FlipImageRgb8::with_data(width, height, reference_rgb8);
    let test = nv_flip::FlipImageRgb8::with_data(width, height, test_rgb8);
    let per_pixel = nv_flip::flip(reference, test, PIXELS_PER_DEGREE).to_vec();
    let mean = per_pixel.iter().map(|&v| f64::from(v)).sum::<f64>() / per_pixel.len() as f64;
    Ok(FlipResult { mean, per_pixel })
}

/// Mean of `per_pixel` over the pixels where `mask` is set (the geometry), `None` when none
/// is; an error when the lengths differ.
pub fn masked_mean(per_pixel: &[f32], mask: &[bool]) -> Result<Option<f64>> {
    if per_pixel.len() != mask.len() {
        return Err(Error::Config(format!(
            "mask has {} entries for {} pixels",
            mask.len(),
            per_pixel.len()
        )));
    }
    let (sum, n) = per_pixel
        .iter()
        .zip(mask)
        .filter(|(_, &m)| m)
        .fold((0.0f64, 0usize), |(s, n), (&v, _)| {
            (s + f64::from(v), n + 1)
        });
    Ok((n > 0).then(|| sum / n as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: u32 = 32;
    const H: u32 = 24;

    /// A smooth grey gradient, so that perturbations are not clipped at 0 or 255.
    fn gradient() -> Vec<u8> {
        (0..W * H)
            .flat_map(|i| {
                let v = (64 + (i % W) * 4) as u8;
                [v, v, v.saturating_sub(20)]
            })
            .collect()
    }

    fn offset(image: &[u8], by: u8) -> Vec<u8> {
        image.iter().map(|v| v.saturating_add(by)).collect()
    }

    #[test]
    fn identical_images_have_no_error() {
        let image = gradient();
        let f = flip_ldr(&image, &image, W, H).unwrap();
        assert_eq!(f.per_pixel.len(), (W * H) as usize);
        assert!(f.mean < 1e-6, "{}", f.mean);
    }

    #[test]
    fn black_against_white_is_large() {
        let black = vec![0u8; (W * H * 3) as usize];
        let white = vec![255u8; (W * H * 3) as usize];
        let f = flip_ldr(&black, &white, W, H).unwrap();
        assert!(f.mean > 0.5, "{}", f.mean);
    }

    #[test]
    fn stronger_perturbation_scores_higher() {
        let reference = gradient();
        let means: Vec<f64> = [4u8, 16, 64]
            .iter()
            .map(|&by| {
                flip_ldr(&offset(&reference, by), &reference, W, H)
                    .unwrap()
                    .mean
            })
            .collect();
        assert!(
            means[0] > 0.0 && means[0] < means[1] && means[1] < means[2],
            "{means:?}"
        );
    }

    #[test]
    fn bad_sizes_are_errors() {
        let image = gradient();
        assert!(flip_ldr(&image, &image, W + 1, H).is_err());
        assert!(flip_ldr(&image, &image[3..], W, H).is_err());
        assert!(flip_ldr(&[], &[], 0, 0).is_err());
        assert!(flip_ldr(&[], &[], 65536, 65536).is_err());
    }

    #[test]
    fn masked_mean_averages_covered_pixels() {
        assert_eq!(
            masked_mean(&[0.5, 0.25, 1.0], &[true, true, false]).unwrap(),
            Some(0.375)
        );
        assert_eq!(masked_mean(&[0.5], &[false]).unwrap(), None);
        assert!(masked_mean(&[0.5], &[]).is_err());
    }
}

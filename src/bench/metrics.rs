//! Error of an image against a reference of the same size: root-mean-square error and maximum
//! absolute difference, over chosen channels and (optionally) only where a mask is set — the
//! geometry pixels, so that background does not dilute the error.

use crate::error::{Error, Result};
use crate::vk::ImageData;
use serde::Serialize;

/// Which values of each texel are compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Channels {
    /// Red, green and blue, each a separate sample of the error.
    Rgb,
    /// The first channel only (scalar buffers such as AO visibility).
    Red,
    /// Rec. 709 luminance `0.2126 r + 0.7152 g + 0.0722 b` of the stored values.
    Luminance,
}

impl Channels {
    fn values(self, t: [f32; 4]) -> ([f64; 3], usize) {
        let [r, g, b, _] = t.map(f64::from);
        match self {
            Channels::Rgb => ([r, g, b], 3),
            Channels::Red => ([r, 0.0, 0.0], 1),
            Channels::Luminance => ([0.2126 * r + 0.7152 * g + 0.0722 * b, 0.0, 0.0], 1),
        }
    }
}

/// The error of one image against its reference.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ImageError {
    /// Root of the mean squared difference over every compared value; `None` when no pixel
    /// was compared (an empty mask).
    pub rmse: Option<f64>,
    /// Largest absolute difference of any compared value.
    pub max_abs: Option<f64>,
    /// Pixels compared (inside the mask).
    pub pixels: usize,
    /// Pixels inside the mask where either image holds a NaN or infinity; they are left out
    /// of `rmse` and `max_abs` and reported here instead.
    pub non_finite: usize,
}

/// Geometry pixels of a G-buffer world-position image: alpha is 0 on the background.
pub fn geometry_mask(position: &ImageData) -> Vec<bool> {
    (0..position.height)
        .flat_map(|y| (0..position.width).map(move |x| (x, y)))
        .map(|(x, y)| position.texel(x, y)[3] != 0.0)
        .collect()
}

/// Error of `image` against `reference`. `mask`, when given, has one entry per pixel in row
/// order and selects the pixels compared.
pub fn image_error(
    image: &ImageData,
    reference: &ImageData,
    channels: Channels,
    mask: Option<&[bool]>,
) -> Result<ImageError> {
    if (image.width, image.height) != (reference.width, reference.height) {
        return Err(Error::Config(format!(
            "cannot compare a {}x{} image with a {}x{} reference",
            image.width, image.height, reference.width, reference.height
        )));
    }
    let count = image.width as usize * image.height as usize;
    if let Some(m) = mask {
        if m.len() != count {
            return Err(Error::Config(format!(
                "error mask has {} entries for {count} pixels",
                m.len()
            )));
        }
    }
    let mut sum_sq = 0.0f64;
    let mut values = 0usize;
    let mut max_abs = 0.0f64;
    let mut pixels = 0usize;
    let mut non_finite = 0usize;
    for y in 0..image.height {
        for x in 0..image.width {
            let i = y as usize * image.width as usize + x as usize;
            if mask.is_some_and(|m| !m[i]) {
                continue;
            }
            let (a, n) = channels.values(image.texel(x, y));
            let (b, _) = channels.values(reference.texel(x, y));
            if a[..n].iter().chain(&b[..n]).any(|v| !v.is_finite()) {
                non_finite += 1;
                continue;
            }
            pixels += 1;
            for c in 0..n {
                let d = (a[c] - b[c]).abs();
                sum_sq += d * d;
                max_abs = max_abs.max(d);
                values += 1;
            }
        }
    }
    let compared = values > 0;
    Ok(ImageError {
        rmse: compared.then(|| (sum_sq / values as f64).sqrt()),
        max_abs: compared.then_some(max_abs),
        pixels,
        non_finite,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ash::vk;

    /// An RGBA32F image from texels in row order.
    fn image(width: u32, height: u32, texels: &[[f32; 4]]) -> ImageData {
        assert_eq!(texels.len(), (width * height) as usize);
        ImageData {
            width,
            height,
            format: vk::Format::R32G32B32A32_SFLOAT,
            bytes: texels
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect(),
        }
    }

    #[test]
    fn image_against_itself_is_zero() {
        let a = image(
            2,
            2,
            &[
                [0.1, 0.2, 0.3, 1.0],
                [5.0, -1.0, 0.0, 1.0],
                [0.7, 0.7, 0.7, 0.0],
                [1e6, 2e-6, 3.0, 1.0],
            ],
        );
        for channels in [Channels::Rgb, Channels::Red, Channels::Luminance] {
            let e = image_error(&a, &a, channels, None).unwrap();
            assert_eq!(e.rmse, Some(0.0));
            assert_eq!(e.max_abs, Some(0.0));
            assert_eq!(e.pixels, 4);
            assert_eq!(e.non_finite, 0);
        }
    }

    #[test]
    fn known_differences() {
        // Pixel 0 differs by (0.3, 0, 0.4), pixel 1 by (0, 0.1, 0).
        let a = image(2, 1, &[[0.3, 0.5, 0.4, 1.0], [0.0, 0.1, 0.0, 1.0]]);
        let b = image(2, 1, &[[0.0, 0.5, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0]]);
        let rgb = image_error(&a, &b, Channels::Rgb, None).unwrap();
        let expected = ((0.09 + 0.16 + 0.01) / 6.0f64).sqrt();
        assert!((rgb.rmse.unwrap() - expected).abs() < 1e-7, "{rgb:?}");
        assert!((rgb.max_abs.unwrap() - 0.4).abs() < 1e-7);
        let red = image_error(&a, &b, Channels::Red, None).unwrap();
        assert!((red.rmse.unwrap() - (0.09f64 / 2.0).sqrt()).abs() < 1e-7);
        assert!((red.max_abs.unwrap() - 0.3).abs() < 1e-7);
        let lum = image_error(&a, &b, Channels::Luminance, None).unwrap();
        let (l0, l1) = (0.2126 * 0.3 + 0.0722 * 0.4, 0.7152 * 0.1);
        let expected = ((l0 * l0 + l1 * l1) / 2.0f64).sqrt();
        assert!((lum.rmse.unwrap() - expected).abs() < 1e-7, "{lum:?}");
        assert!((lum.max_abs.unwrap() - l1.max(l0)).abs() < 1e-7);
    }

    #[test]
    fn mask_selects_pixels() {
        let a = image(3, 1, &[[1.0; 4], [0.5; 4], [9.0; 4]]);
        let b = image(3, 1, &[[1.0; 4], [0.0; 4], [0.0; 4]]);
        let mask = [true, true, false];
        let e = image_error(&a, &b, Channels::Red, Some(&mask)).unwrap();
        assert_eq!(e.pixels, 2);
        assert!((e.rmse.unwrap() - (0.25f64 / 2.0).sqrt()).abs() < 1e-9);
        assert_eq!(e.max_abs, Some(0.5));
        let none = image_error(&a, &b, Channels::Red, Some(&[false; 3])).unwrap();
        assert_eq!((none.rmse, none.max_abs, none.pixels), (None, None, 0));
    }

    #[test]
    fn geometry_mask_reads_alpha() {
        let pos = image(
            3,
            1,
            &[[1.0, 2.0, 3.0, 1.0], [0.0; 4], [0.0, 0.0, 0.0, 1.0]],
        );
        assert_eq!(geometry_mask(&pos), [true, false, true]);
    }

    #[test]
    fn non_finite_values_are_counted_not_averaged() {
        let a = image(2, 1, &[[f32::NAN, 0.0, 0.0, 1.0], [0.2, 0.0, 0.0, 1.0]]);
        let b = image(2, 1, &[[0.0; 4], [0.0; 4]]);
        let e = image_error(&a, &b, Channels::Red, None).unwrap();
        assert_eq!((e.pixels, e.non_finite), (1, 1));
        assert!((e.max_abs.unwrap() - 0.2).abs() < 1e-7);
    }

    #[test]
    fn mismatched_sizes_are_errors() {
        let a = image(2, 1, &[[0.0; 4]; 2]);
        let b = image(1, 2, &[[0.0; 4]; 2]);
        let e = image_error(&a, &b, Channels::Rgb, None).unwrap_err();
        assert!(
            e.to_string().contains("2x1") && e.to_string().contains("1x2"),
            "{e}"
        );
        let e = image_error(&a, &a, Channels::Rgb, Some(&[true])).unwrap_err();
        assert!(e.to_string().contains("mask"), "{e}");
    }
}

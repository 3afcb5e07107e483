//! Error of a rendered buffer against its ground truth, for the time-versus-error benchmark:
//! per-value statistics over the geometry pixels ([`buffer_error`]), per-pixel absolute error
//! for error maps ([`abs_error_per_pixel`]), FLIP on tonemapped LDR images ([`flip_ldr`]) and
//! false-colour PNGs of any per-pixel error ([`write_error_map`]).
//!
//! Buffers are row-major, `channels` (1 or 3) floats per pixel, with one mask entry per pixel
//! that selects the covered (geometry) pixels, so that the background does not dilute the error.

mod error_map;
mod flip;

pub use error_map::{error_map_rgba, write_error_map, NAN_COLOUR};
pub use flip::{flip_ldr, masked_mean, FlipResult, PIXELS_PER_DEGREE};

use crate::error::{Error, Result};
use serde::{Serialize, Serializer};

/// Error statistics of one buffer against its reference, over the compared values: those of
/// pixels inside the mask whose values are finite in both buffers.
///
/// With no compared pixel (`pixels == 0`) every error is 0 and `psnr` infinite: no error was
/// measured, and the output stays NaN-free.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BufferError {
    /// Root of the mean squared difference.
    pub rmse: f64,
    /// Mean of `(x − r)² / (r² + ε)`: the squared error relative to the reference, so that
    /// dark and bright regions weigh alike. ε is `1e-2 ×` the mean of `r²` (see
    /// [`buffer_error`]).
    pub rel_mse: f64,
    /// Largest absolute difference.
    pub max_abs: f64,
    /// `10·log10(peak² / MSE)` in dB, `peak` the largest compared reference value. Infinite
    /// when MSE is 0 (identical buffers); −∞ when the reference has no positive value but
    /// the buffers differ. Non-finite values serialize as `null` (JSON has no infinity and
    /// the CSV/Markdown writers would print `inf`); `rmse` tells the two cases apart.
    #[serde(serialize_with = "finite_or_null")]
    pub psnr: f64,
    /// Pixels compared.
    pub pixels: usize,
    /// Pixels inside the mask with a NaN or infinity in either buffer: left out of every
    /// statistic and counted here, since one NaN would otherwise poison the means.
    pub non_finite: usize,
}

fn finite_or_null<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else {
        s.serialize_none()
    }
}

/// Error of `values` against `reference`.
///
/// ε in `rel_mse` keeps pixels where the reference is (near) black from dominating with a
/// huge or infinite quotient. A fixed ε would make the metric depend on the unit of the
/// buffer (radiance in arbitrary scale), so ε is relative to the reference: `1e-2 ×` the mean
/// of `r²` over the compared values. Scaling both buffers by any factor then leaves `rel_mse`
/// unchanged. For an all-black reference ε falls back to `1e-2 ×` the mean of `x²` (scale-safe
/// too; `rel_mse` is then exactly 100 for any non-zero test buffer), and to 0 when both
/// buffers are black, where every difference is 0 and contributes nothing.
///
/// `peak` for PSNR is the largest compared reference value rather than a fixed 1.0, because
/// HDR radiance has no fixed white; like `rel_mse`, PSNR is then invariant to the scale.
pub fn buffer_error(
    values: &[f32],
    reference: &[f32],
    channels: usize,
    mask: &[bool],
) -> Result<BufferError> {
    check_shapes(values, reference, channels, mask)?;
    let covered = || {
        values
            .chunks_exact(channels)
            .zip(reference.chunks_exact(channels))
            .zip(mask)
            .filter(|(_, &m)| m)
            .map(|(pair, _)| pair)
    };
    let non_finite = covered().filter(|(x, r)| !all_finite(x, r)).count();
    let compared = || {
        covered()
            .filter(|(x, r)| all_finite(x, r))
            .flat_map(|(x, r)| x.iter().zip(r))
            .map(|(&x, &r)| (f64::from(x), f64::from(r)))
    };
    let n = compared().count();
    if n == 0 {
        return Ok(BufferError {
            rmse: 0.0,
            rel_mse: 0.0,
            max_abs: 0.0,
            psnr: f64::INFINITY,
            pixels: 0,
            non_finite,
        });
    }
    let mean_sq =
        |pick: fn((f64, f64)) -> f64| compared().map(|p| pick(p) * pick(p)).sum::<f64>() / n as f64;
    let mean_sq_ref = mean_sq(|(_, r)| r);
    let eps = 1e-2
        * if mean_sq_ref > 0.0 {
            mean_sq_ref
        } else {
            mean_sq(|(x, _)| x)
        };
    let peak = compared().map(|(_, r)| r).fold(0.0f64, f64::max);
    let (mut sq, mut rel, mut max_abs) = (0.0f64, 0.0f64, 0.0f64);
    for (x, r) in compared() {
        let d = x - r;
        sq += d * d;
        // ε is 0 only when both buffers are black, and then d is 0 too: skip the 0/0.
        if d != 0.0 {
            rel += d * d / (r * r + eps);
        }
        max_abs = max_abs.max(d.abs());
    }
    let mse = sq / n as f64;
    let psnr = if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (peak * peak / mse).log10()
    };
    Ok(BufferError {
        rmse: mse.sqrt(),
        rel_mse: rel / n as f64,
        max_abs,
        psnr,
        pixels: n / channels,
        non_finite,
    })
}

/// Per pixel, the mean absolute difference over its channels: 0 outside the mask, NaN where
/// a value is not finite (shown in [`NAN_COLOUR`] by [`write_error_map`]).
pub fn abs_error_per_pixel(
    values: &[f32],
    reference: &[f32],
    channels: usize,
    mask: &[bool],
) -> Result<Vec<f32>> {
    check_shapes(values, reference, channels, mask)?;
    Ok(values
        .chunks_exact(channels)
        .zip(reference.chunks_exact(channels))
        .zip(mask)
        .map(|((x, r), &m)| match m {
            false => 0.0,
            true if !all_finite(x, r) => f32::NAN,
            true => {
                let sum: f64 = x
                    .iter()
                    .zip(r)
                    .map(|(&x, &r)| (f64::from(x) - f64::from(r)).abs())
                    .sum();
                (sum / channels as f64) as f32
            }
        })
        .collect())
}

fn all_finite(x: &[f32], r: &[f32]) -> bool {
    x.iter().chain(r).all(|v| v.is_finite())
}

fn check_shapes(values: &[f32], reference: &[f32], channels: usize, mask: &[bool]) -> Result<()> {
    if channels != 1 && channels != 3 {
        return Err(Error::Config(format!(
            "error metrics take 1 or 3 channels per pixel, not {channels}"
        )));
    }
    if values.len() != reference.len() {
        return Err(Error::Config(format!(
            "cannot compare {} values with a reference of {}",
            values.len(),
            reference.len()
        )));
    }
    if !values.len().is_multiple_of(channels) || values.len() / channels != mask.len() {
        return Err(Error::Config(format!(
            "error mask has {} entries for {} values of {channels} channel(s)",
            mask.len(),
            values.len()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs())
    }

    /// Values exactly representable in f32 even after scaling by 1000.
    const REF: [f32; 6] = [0.25, 0.5, 1.0, 0.125, 0.75, 0.0];

    #[test]
    fn identical_buffers_have_no_error() {
        let e = buffer_error(&REF, &REF, 3, &[true; 2]).unwrap();
        assert_eq!((e.rmse, e.rel_mse, e.max_abs), (0.0, 0.0, 0.0));
        assert_eq!(e.psnr, f64::INFINITY);
        assert_eq!((e.pixels, e.non_finite), (2, 0));
        let json = serde_json::to_value(e).unwrap();
        assert!(json["psnr"].is_null(), "{json}");
        assert_eq!(json["rmse"], 0.0);
    }

    #[test]
    fn constant_offset_gives_exact_errors() {
        let test: Vec<f32> = REF.iter().map(|r| r + 0.125).collect();
        let e = buffer_error(&test, &REF, 1, &[true; 6]).unwrap();
        assert_eq!(e.rmse, 0.125);
        assert_eq!(e.max_abs, 0.125);
        // peak = 1.0: 10·log10(1 / 0.125²) = 10·log10(64).
        assert!(close(e.psnr, 10.0 * 64f64.log10(), 1e-12), "{e:?}");
        let eps = 1e-2 * REF.iter().map(|&r| f64::from(r).powi(2)).sum::<f64>() / 6.0;
        let rel = REF
            .iter()
            .map(|&r| 0.125f64.powi(2) / (f64::from(r).powi(2) + eps))
            .sum::<f64>()
            / 6.0;
        assert!(close(e.rel_mse, rel, 1e-12), "{e:?} {rel}");
        let json = serde_json::to_value(e).unwrap();
        assert!(json["psnr"].is_f64(), "{json}");
    }

    #[test]
    fn rel_mse_and_psnr_ignore_scale() {
        let test = [0.5f32, 0.25, 1.5, 0.0, 0.875, 0.125];
        let scale = |v: &[f32]| v.iter().map(|x| x * 1000.0).collect::<Vec<f32>>();
        let a = buffer_error(&test, &REF, 3, &[true; 2]).unwrap();
        let b = buffer_error(&scale(&test), &scale(&REF), 3, &[true; 2]).unwrap();
        assert!(a.rel_mse > 0.0);
        assert!(close(a.rel_mse, b.rel_mse, 1e-9), "{a:?} {b:?}");
        assert!(close(a.psnr, b.psnr, 1e-9), "{a:?} {b:?}");
        assert!(close(b.rmse, 1000.0 * a.rmse, 1e-9));
    }

    #[test]
    fn black_reference_stays_finite() {
        let e = buffer_error(&[0.5, 2.0], &[0.0, 0.0], 1, &[true; 2]).unwrap();
        assert!(close(e.rel_mse, 100.0, 1e-12), "{e:?}");
        assert_eq!(e.psnr, f64::NEG_INFINITY);
        let zero = buffer_error(&[0.0; 2], &[0.0; 2], 1, &[true; 2]).unwrap();
        assert_eq!((zero.rel_mse, zero.psnr), (0.0, f64::INFINITY));
    }

    #[test]
    fn mask_excludes_pixels() {
        let test = [0.25f32, 0.5, 9.0];
        let reference = [0.25f32, 0.0, 0.0];
        let e = buffer_error(&test, &reference, 1, &[true, true, false]).unwrap();
        assert_eq!(e.pixels, 2);
        assert_eq!(e.max_abs, 0.5);
        assert_eq!(e.rmse, (0.25f64 / 2.0).sqrt());
        let none = buffer_error(&test, &reference, 1, &[false; 3]).unwrap();
        assert_eq!(none.pixels, 0);
        assert_eq!((none.rmse, none.rel_mse, none.max_abs), (0.0, 0.0, 0.0));
        assert!(serde_json::to_string(&none).is_ok());
        let map = abs_error_per_pixel(&test, &reference, 1, &[true, true, false]).unwrap();
        assert_eq!(map, [0.0, 0.5, 0.0]);
    }

    #[test]
    fn non_finite_values_are_counted_not_averaged() {
        let test = [f32::NAN, 0.0, 0.0, 0.5, 0.5, 0.5, 7.0, 7.0, 7.0];
        let mut reference = [0.0f32; 9];
        reference[8] = f32::INFINITY;
        let e = buffer_error(&test, &reference, 3, &[true; 3]).unwrap();
        assert_eq!((e.pixels, e.non_finite), (1, 2));
        assert_eq!((e.rmse, e.max_abs), (0.5, 0.5));
        let masked = buffer_error(&test, &reference, 3, &[false, true, true]).unwrap();
        assert_eq!(masked.non_finite, 1);
        let map = abs_error_per_pixel(&test, &reference, 3, &[true; 3]).unwrap();
        assert!(map[0].is_nan() && map[2].is_nan());
        assert_eq!(map[1], 0.5);
    }

    #[test]
    fn bad_shapes_are_errors() {
        let two = [0.0f32; 2];
        assert!(buffer_error(&two, &[0.0; 3], 1, &[true; 2]).is_err());
        assert!(buffer_error(&two, &two, 2, &[true]).is_err());
        assert!(buffer_error(&two, &two, 1, &[true]).is_err());
        assert!(buffer_error(&two, &two, 3, &[]).is_err());
        assert!(abs_error_per_pixel(&two, &two, 1, &[true; 3]).is_err());
    }
}

//! Errors of a rendered frame against the CPU ground truth (`crate::reference`): per buffer
//! RMSE, relative MSE, maximum and PSNR over the pixels both cover, and FLIP for the final
//! image. The shadow buffer is compared only where the light reaches (inside the cone, facing
//! it): elsewhere the direct light is zero whatever the visibility says.

use super::measure::{Buffer, LastFrame};
use crate::error::{Error, Result};
use crate::reference::compose::{final_image, to_rgb8, Terms};
use crate::reference::error_metrics::{buffer_error, flip_ldr, masked_mean, BufferError};
use crate::reference::{RefBuffer, Reference};
use crate::scene::Scene;
use crate::vk::ImageData;
use serde::Serialize;
use std::collections::BTreeMap;

/// One buffer's error against an expected frame (the ground truth or the converged
/// estimator).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct FrameError {
    #[serde(flatten)]
    pub error: BufferError,
    /// Mean FLIP over covered pixels (final image only).
    pub flip: Option<f64>,
}

/// The ground truth's own accuracy, per buffer.
#[derive(Clone, Debug, Serialize)]
pub struct TruthQuality {
    pub samples_per_pixel: u64,
    pub standard_error: f64,
    /// One tenth of the smallest error measured against this buffer: the bound the standard
    /// error must stay under.
    pub bound: Option<f64>,
    pub bound_met: bool,
}

/// The smallest non-zero RMSE of `errors`: a tenth of it bounds the ground truth's standard
/// error (a zero error is an exact match and sets no bound).
pub fn smallest_rmse<'a>(errors: impl Iterator<Item = &'a FrameError>) -> Option<f64> {
    errors
        .map(|e| e.error.rmse)
        .filter(|e| *e > 0.0)
        .min_by(f64::total_cmp)
}

/// The ground truth's accuracy for buffer `b` over the pixels `mask` compares, against the
/// bound a tenth of `smallest` (the smallest error measured against it; None: no bound).
pub fn quality(
    reference: &Reference,
    b: RefBuffer,
    mask: &[bool],
    smallest: Option<f64>,
) -> TruthQuality {
    let e = reference.estimate(b);
    let standard_error = e.standard_error(mask);
    let bound = smallest.map(|s| s / 10.0);
    TruthQuality {
        samples_per_pixel: 2 * e.per_half as u64,
        standard_error,
        bound,
        bound_met: bound.is_none_or(|b| standard_error <= b),
    }
}

/// The reference buffer a rendered buffer estimates (`None` for the final image).
pub fn reference_buffer(b: Buffer) -> Option<RefBuffer> {
    match b {
        Buffer::Final => None,
        Buffer::Ao => Some(RefBuffer::Ao),
        Buffer::Direct => Some(RefBuffer::Direct),
        Buffer::Shadow => Some(RefBuffer::Shadow),
        Buffer::Indirect => Some(RefBuffer::Indirect),
    }
}

/// Values per pixel a buffer is compared with: 1 for visibilities, 3 for colours.
pub fn channels(b: Buffer) -> usize {
    match b {
        Buffer::Ao | Buffer::Shadow => 1,
        Buffer::Final | Buffer::Direct | Buffer::Indirect => 3,
    }
}

/// The first `channels` values of every texel, row order.
pub fn values(image: &ImageData, channels: usize) -> Vec<f32> {
    let mut out = Vec::with_capacity(image.width as usize * image.height as usize * channels);
    for y in 0..image.height {
        for x in 0..image.width {
            out.extend_from_slice(&image.texel(x, y)[..channels]);
        }
    }
    out
}

/// The pixels a buffer is compared over: covered by both the G-buffer (`gpu_geometry`) and
/// the traced primary hits; for shadows, also lit by the cone and facing the light.
pub fn mask(b: Buffer, reference: &Reference, scene: &Scene, gpu_geometry: &[bool]) -> Vec<bool> {
    reference
        .primary
        .iter()
        .zip(gpu_geometry)
        .map(|(p, &g)| match p {
            Some(p) if g => {
                b != Buffer::Shadow
                    || scene.light.irradiance(p.surface.position, p.normal) != glam::Vec3::ZERO
            }
            _ => false,
        })
        .collect()
}

/// The ground-truth values of `b` for a run estimating `terms` (the final image composited
/// from those reference buffers).
pub fn truth_values(b: Buffer, reference: &Reference, scene: &Scene, terms: Terms) -> Vec<f32> {
    match reference_buffer(b) {
        Some(rb) => reference.estimate(rb).mean(),
        None => final_image(reference, scene.ambient, terms),
    }
}

/// One rendered buffer and its ground truth, as compared: values per pixel, the values, the
/// truth and the pixels compared.
struct Compared {
    ch: usize,
    mask: Vec<bool>,
    got: Vec<f32>,
    truth: Vec<f32>,
}

fn compared(
    b: Buffer,
    image: &ImageData,
    last: &LastFrame,
    reference: &Reference,
    scene: &Scene,
    terms: Terms,
) -> Compared {
    let ch = channels(b);
    Compared {
        ch,
        mask: mask(b, reference, scene, &last.geometry),
        got: values(image, ch),
        truth: truth_values(b, reference, scene, terms),
    }
}

/// Every buffer of `last` against the ground truth.
pub fn errors(
    last: &LastFrame,
    reference: &Reference,
    scene: &Scene,
    terms: Terms,
) -> Result<BTreeMap<Buffer, FrameError>> {
    if last.geometry.len() != reference.primary.len() {
        return Err(Error::Config(format!(
            "the ground truth has {} pixels, the frame {}",
            reference.primary.len(),
            last.geometry.len()
        )));
    }
    let mut out = BTreeMap::new();
    for (b, image) in &last.buffers {
        let Compared {
            ch,
            mask: m,
            got,
            truth,
        } = compared(*b, image, last, reference, scene, terms);
        out.insert(
            *b,
            frame_error(*b, &got, &truth, ch, &m, (image.width, image.height))?,
        );
    }
    Ok(out)
}

/// `got` against `expected` for buffer `b` of `size` (width, height): the buffer's error over
/// the pixels of `m`, and FLIP for the final image.
fn frame_error(
    b: Buffer,
    got: &[f32],
    expected: &[f32],
    ch: usize,
    m: &[bool],
    (width, height): (u32, u32),
) -> Result<FrameError> {
    let error = buffer_error(got, expected, ch, m)?;
    let flip = if b == Buffer::Final {
        let f = flip_ldr(&to_rgb8(got), &to_rgb8(expected), width, height)?;
        masked_mean(&f.per_pixel, m)?
    } else {
        None
    };
    Ok(FrameError { error, flip })
}

/// The frame's size (width, height); (0, 0) for a frame without buffers.
fn size(last: &LastFrame) -> (u32, u32) {
    last.buffers
        .first()
        .map_or((0, 0), |(_, i)| (i.width, i.height))
}

/// The pixels `last` and `converged` both cover, and the buffers both have, as compared:
/// (buffer, channels, values of `last`, values of `converged`).
#[allow(clippy::type_complexity)]
fn against_converged(
    last: &LastFrame,
    converged: &LastFrame,
) -> (Vec<bool>, Vec<(Buffer, usize, Vec<f32>, Vec<f32>)>) {
    let mask = last
        .geometry
        .iter()
        .zip(&converged.geometry)
        .map(|(a, b)| *a && *b)
        .collect();
    let buffers = last
        .buffers
        .iter()
        .filter_map(|(b, image)| {
            let c = converged.buffer(*b)?;
            let ch = channels(*b);
            Some((*b, ch, values(image, ch), values(c, ch)))
        })
        .collect();
    (mask, buffers)
}

/// Every buffer of `last` against the same buffers of `converged` (the estimator with many
/// samples), over the pixels both cover; FLIP for the final image, as against the truth.
pub fn errors_against(
    last: &LastFrame,
    converged: &LastFrame,
) -> Result<BTreeMap<Buffer, FrameError>> {
    let mut out = BTreeMap::new();
    let (m, buffers) = against_converged(last, converged);
    for (b, ch, got, conv) in buffers {
        out.insert(b, frame_error(b, &got, &conv, ch, &m, size(last))?);
    }
    Ok(out)
}

/// Error maps of `last` against the converged estimator: `<stem>-<buffer>-vs-converged.png`,
/// on the same scale as the maps against the ground truth (radiance scaled by the converged
/// buffer's RMS). They separate what the technique's sampling and reuse add (lag, blur,
/// noise) from its bias.
pub fn write_converged_maps(
    last: &LastFrame,
    converged: &LastFrame,
    dir: &std::path::Path,
    stem: &str,
) -> Result<Vec<std::path::PathBuf>> {
    use crate::reference::error_metrics::{abs_error_per_pixel, write_error_map};
    let (w, h) = size(last);
    let mut written = Vec::new();
    let (m, buffers) = against_converged(last, converged);
    for (b, ch, got, conv) in buffers {
        let per_pixel = abs_error_per_pixel(&got, &conv, ch, &m)?;
        let path = dir.join(format!("{stem}-{}-vs-converged.png", b.name()));
        write_error_map(&path, &per_pixel, w, h, map_scale(b, &conv, &m))?;
        written.push(path);
    }
    Ok(written)
}

/// Scale of the error maps: visibilities and the final image are in 0..1 (a difference of
/// 0.5 is the top colour); radiance buffers are scaled by the ground truth's RMS over the
/// compared pixels, so maps of different scenes and lights read alike.
fn map_scale(b: Buffer, truth: &[f32], mask: &[bool]) -> f32 {
    match b {
        Buffer::Ao | Buffer::Shadow | Buffer::Final => 0.5,
        Buffer::Direct | Buffer::Indirect => {
            let (mut sum, mut n) = (0.0f64, 0usize);
            for (v, m) in truth.chunks_exact(3).zip(mask) {
                if *m {
                    sum += v.iter().map(|x| (*x as f64).powi(2)).sum::<f64>() / 3.0;
                    n += 1;
                }
            }
            ((sum / n.max(1) as f64).sqrt() as f32).max(f32::MIN_POSITIVE)
        }
    }
}

/// The final image's FLIP per pixel against the ground truth as the magma map
/// `write_error_maps` writes (`<stem>-final-flip.png`): RGBA8 pixels of the frame's size.
pub fn final_flip_map(
    last: &LastFrame,
    reference: &Reference,
    scene: &Scene,
    terms: Terms,
) -> Result<Option<(Vec<u8>, u32, u32)>> {
    let Some(image) = last.buffer(Buffer::Final) else {
        return Ok(None);
    };
    let Compared { got, truth, .. } = compared(Buffer::Final, image, last, reference, scene, terms);
    let (w, h) = (image.width, image.height);
    let f = flip_ldr(&to_rgb8(&got), &to_rgb8(&truth), w, h)?;
    let rgba = crate::reference::error_metrics::error_map_rgba(&f.per_pixel, w, h, 1.0)
        .map_err(Error::Config)?;
    Ok(Some((rgba, w, h)))
}

/// Error maps of `last` against the ground truth: `<stem>-<buffer>.png` (absolute error per
/// pixel, magma ramp, see `map_scale`) and `<stem>-final-flip.png` (FLIP per pixel, 0..1).
pub fn write_error_maps(
    last: &LastFrame,
    reference: &Reference,
    scene: &Scene,
    terms: Terms,
    dir: &std::path::Path,
    stem: &str,
) -> Result<Vec<std::path::PathBuf>> {
    use crate::reference::error_metrics::{abs_error_per_pixel, write_error_map};
    let mut written = Vec::new();
    for (b, image) in &last.buffers {
        let Compared {
            ch,
            mask: m,
            got,
            truth,
        } = compared(*b, image, last, reference, scene, terms);
        let per_pixel = abs_error_per_pixel(&got, &truth, ch, &m)?;
        let path = dir.join(format!("{stem}-{}.png", b.name()));
        write_error_map(
            &path,
            &per_pixel,
            image.width,
            image.height,
            map_scale(*b, &truth, &m),
        )?;
        written.push(path);
        if *b == Buffer::Final {
            let f = flip_ldr(&to_rgb8(&got), &to_rgb8(&truth), image.width, image.height)?;
            let path = dir.join(format!("{stem}-final-flip.png"));
            write_error_map(&path, &f.per_pixel, image.width, image.height, 1.0)?;
            written.push(path);
        }
    }
    Ok(written)
}

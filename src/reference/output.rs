//! A reference on disk: one 32-bit float OpenEXR per buffer (scalar buffers repeated in R, G
//! and B: the `image` crate's EXR writer takes RGB or RGBA), false-colour PNG previews, and the
//! final image as the PNG the renderer would write.

use super::compose::to_rgb8;
use crate::error::{Error, Result};
use crate::files::write_atomic;
use crate::reference::error_metrics::write_error_map;
use image::{ExtendedColorType, ImageEncoder};
use std::io::Cursor;
use std::path::Path;

/// Write `values` (`channels` = 1 or 3 per pixel) as a float RGB OpenEXR image.
pub fn write_exr(
    path: &Path,
    values: &[f32],
    channels: usize,
    width: u32,
    height: u32,
) -> Result<()> {
    let rgb: Vec<f32> = match channels {
        1 => values.iter().flat_map(|&v| [v, v, v]).collect(),
        _ => values.to_vec(),
    };
    let bytes: Vec<u8> = rgb.iter().flat_map(|v| v.to_le_bytes()).collect();
    let mut out = Cursor::new(Vec::new());
    image::codecs::openexr::OpenExrEncoder::new(&mut out)
        .write_image(&bytes, width, height, ExtendedColorType::Rgb32F)
        .map_err(|e| Error::ImageWrite {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_atomic(path, &out.into_inner())
}

/// A false-colour preview: the value (luminance of RGB buffers) on the magma ramp, from 0 to
/// `max` (1 for visibilities; the 99th percentile of covered pixels for radiance, so a few
/// hot pixels near the light do not flatten the rest).
pub fn write_preview(
    path: &Path,
    values: &[f32],
    channels: usize,
    mask: &[bool],
    width: u32,
    height: u32,
    unit_range: bool,
) -> Result<()> {
    let scalar: Vec<f32> = values
        .chunks_exact(channels)
        .zip(mask)
        .map(|(v, &m)| match (m, channels) {
            (false, _) => 0.0,
            (true, 1) => v[0],
            (true, _) => 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2],
        })
        .collect();
    let max = if unit_range {
        1.0
    } else {
        percentile(&scalar, mask, 0.99).max(f32::MIN_POSITIVE)
    };
    write_error_map(path, &scalar, width, height, max)
}

fn percentile(values: &[f32], mask: &[bool], q: f64) -> f32 {
    let mut v: Vec<f32> = values
        .iter()
        .zip(mask)
        .filter(|(x, m)| **m && x.is_finite())
        .map(|(x, _)| *x)
        .collect();
    if v.is_empty() {
        return 1.0;
    }
    v.sort_by(f32::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

/// The final image as an sRGB PNG.
pub fn write_final_png(path: &Path, values: &[f32], width: u32, height: u32) -> Result<()> {
    let rgba: Vec<u8> = to_rgb8(values)
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    crate::files::write_png_rgba8(path, width, height, &rgba)
}

/// Everything `ssgi reference` writes into `out`: reference.json, `<buffer>.exr` and
/// `<buffer>.png` for each buffer, `final.exr`/`final.png` (all effects composited).
/// Returns the JSON written.
pub fn write_all(session: &super::run::Session<'_>, out: &Path) -> Result<serde_json::Value> {
    use super::trace::RefBuffer;
    let r = &session.reference;
    let (w, h) = (r.width, r.height);
    let mask = r.geometry();
    let mut buffers = serde_json::Map::new();
    for b in RefBuffer::ALL {
        let e = r.estimate(b);
        let mean = e.mean();
        write_exr(
            &out.join(format!("{}.exr", b.name())),
            &mean,
            e.channels,
            w,
            h,
        )?;
        let unit = matches!(b, RefBuffer::Ao | RefBuffer::Shadow);
        write_preview(
            &out.join(format!("{}.png", b.name())),
            &mean,
            e.channels,
            &mask,
            w,
            h,
            unit,
        )?;
        let se = e.standard_error(&mask);
        let rms = e.rms(&mask);
        buffers.insert(
            b.name().into(),
            serde_json::json!({
                "samples_per_pixel": 2 * e.per_half as u64,
                "standard_error": se,
                "relative_standard_error": if rms > 0.0 { Some(se / rms) } else { None },
                "rms": rms,
            }),
        );
    }
    let final_rgb =
        super::compose::final_image(r, session.scene.ambient, super::compose::Terms::ALL);
    write_exr(&out.join("final.exr"), &final_rgb, 3, w, h)?;
    write_final_png(&out.join("final.png"), &final_rgb, w, h)?;
    let json = serde_json::json!({
        "scene": session.scene.name,
        "size": [w, h],
        "camera": r.camera,
        "light": session.scene.light,
        "ambient": session.scene.ambient.to_array(),
        "settings": r.settings,
        "primary_hits": "traced through pixel centres (the G-buffer's rasterization samples), view depth in the camera's near..far",
        "covered_pixels": mask.iter().filter(|m| **m).count(),
        "buffers": buffers,
        "rays": r.rays,
        "seconds": r.seconds,
        "rays_per_second": r.rays_per_second(),
        "threads": rayon::current_num_threads(),
        "cache_key": session.key,
        "from_cache": session.from_cache,
    });
    let text = serde_json::to_string_pretty(&json).map_err(|e| Error::Config(e.to_string()))?;
    write_atomic(&out.join("reference.json"), text.as_bytes())?;
    Ok(json)
}

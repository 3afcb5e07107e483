//! False-colour PNGs of per-pixel error, in FLIP's magma colour ramp.

use crate::error::{Error, Result};
use std::path::Path;

/// Colour of NaN pixels (a non-finite value in the compared buffers): pure green, which the
/// magma ramp (black, purple, orange, pale yellow) never reaches.
pub const NAN_COLOUR: [u8; 3] = [0, 255, 0];

/// Write `per_pixel` (row-major, `width × height`) as a PNG: 0 maps to magma's black, `max`
/// and above to its top colour (pale yellow), NaN to [`NAN_COLOUR`]. A fixed `max` across a
/// series of maps keeps their colours comparable.
pub fn write_error_map(
    path: &Path,
    per_pixel: &[f32],
    width: u32,
    height: u32,
    max: f32,
) -> Result<()> {
    let rgba =
        error_map_rgba(per_pixel, width, height, max).map_err(|message| Error::ImageWrite {
            path: path.to_path_buf(),
            message,
        })?;
    crate::files::write_png_rgba8(path, width, height, &rgba)
}

/// The map [`write_error_map`] writes, as RGBA8 (sRGB-encoded) pixels; the error says why
/// the values or the scale cannot make one.
pub fn error_map_rgba(
    per_pixel: &[f32],
    width: u32,
    height: u32,
    max: f32,
) -> std::result::Result<Vec<u8>, String> {
    if per_pixel.len() as u64 != u64::from(width) * u64::from(height) {
        return Err(format!(
            "{} error values for a {width}x{height} map",
            per_pixel.len()
        ));
    }
    if !(max.is_finite() && max > 0.0) {
        return Err(format!("error map scale {max} is not positive"));
    }
    // nv_flip's `apply_color_lut` indexes modulo the LUT size, wrapping errors above 1 back
    // to black, so the ramp is read out and indexed here with clamping.
    let lut = nv_flip::magma_lut().to_vec();
    Ok(per_pixel
        .iter()
        .flat_map(|&v| {
            let [r, g, b] = if v.is_nan() {
                NAN_COLOUR
            } else {
                let i = ((v / max).clamp(0.0, 1.0) * 255.0).round() as usize;
                [lut[3 * i], lut[3 * i + 1], lut[3 * i + 2]]
            };
            [r, g, b, 255]
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_is_written_and_decodes() {
        let dir = std::env::temp_dir().join(format!("ssgi-error-map-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("map.png");
        let values = [0.0, 0.5, 2.0, f32::NAN, f32::INFINITY, -1.0];
        write_error_map(&path, &values, 3, 2, 1.0).unwrap();
        let image = image::open(&path).unwrap().into_rgb8();
        assert_eq!(image.dimensions(), (3, 2));
        let px = |x, y| image.get_pixel(x, y).0;
        let lut = nv_flip::magma_lut().to_vec();
        assert_eq!(px(0, 0), [lut[0], lut[1], lut[2]]);
        assert_eq!(px(2, 0), [lut[765], lut[766], lut[767]]);
        assert_eq!(px(1, 1), px(2, 0));
        assert_eq!(px(2, 1), px(0, 0));
        assert_eq!(px(0, 1), NAN_COLOUR);
        assert_ne!(px(1, 0), px(0, 0));
        assert!(write_error_map(&path, &values, 4, 2, 1.0).is_err());
        assert!(write_error_map(&path, &values, 3, 2, 0.0).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

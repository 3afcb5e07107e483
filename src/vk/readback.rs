//! Copy an image back to the host (tests, PNG output, G-buffer dumps).

use super::context::Context;
use super::memory::{Buffer, Image};
use super::recorder::Recorder;
use super::submission::one_shot;
use super::sync::{Access, Tracker};
use crate::error::{Error, Result};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::sync::Arc;

/// Host copy of an image, tightly packed rows.
#[derive(Clone, Debug)]
pub struct ImageData {
    pub width: u32,
    pub height: u32,
    pub format: vk::Format,
    pub bytes: Vec<u8>,
}

pub use super::memory::bytes_per_pixel;

/// IEEE half to single precision (normals, subnormals, infinities, NaN).
pub fn f16_to_f32(h: u16) -> f32 {
    let sign = ((h >> 15) as u32) << 31;
    let exp = ((h >> 10) & 0x1f) as u32;
    let mant = (h & 0x3ff) as u32;
    let bits = match (exp, mant) {
        (0, 0) => sign,
        (0, m) => {
            // Subnormal: renormalise.
            let shift = m.leading_zeros() - 21;
            let m = (m << shift) & 0x3ff;
            sign | ((113 - shift) << 23) | (m << 13)
        }
        (31, 0) => sign | 0x7f80_0000,
        (31, m) => sign | 0x7f80_0000 | (m << 13),
        (e, m) => sign | ((e + 112) << 23) | (m << 13),
    };
    f32::from_bits(bits)
}

impl ImageData {
    /// The texel as RGBA floats (unorm formats scaled to 0..1, depth in `r`).
    pub fn texel(&self, x: u32, y: u32) -> [f32; 4] {
        let bpp = bytes_per_pixel(self.format).unwrap_or(4);
        let i = (y as usize * self.width as usize + x as usize) * bpp;
        let b = &self.bytes[i..i + bpp];
        let f32_at = |k: usize| f32::from_le_bytes([b[k], b[k + 1], b[k + 2], b[k + 3]]);
        match self.format {
            vk::Format::R32G32B32A32_SFLOAT => [f32_at(0), f32_at(4), f32_at(8), f32_at(12)],
            vk::Format::R16G16B16A16_SFLOAT => {
                let h = |k: usize| f16_to_f32(u16::from_le_bytes([b[k], b[k + 1]]));
                [h(0), h(2), h(4), h(6)]
            }
            vk::Format::D32_SFLOAT | vk::Format::R32_SFLOAT => [f32_at(0), 0.0, 0.0, 1.0],
            vk::Format::R32_UINT => [
                u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
                0.0,
                0.0,
                1.0,
            ],
            vk::Format::B8G8R8A8_UNORM | vk::Format::B8G8R8A8_SRGB => [
                b[2] as f32 / 255.0,
                b[1] as f32 / 255.0,
                b[0] as f32 / 255.0,
                b[3] as f32 / 255.0,
            ],
            _ => [
                b[0] as f32 / 255.0,
                b[1] as f32 / 255.0,
                b[2] as f32 / 255.0,
                b[3] as f32 / 255.0,
            ],
        }
    }

    /// RGBA8 pixels for PNG output, when the image is 8-bit.
    pub fn rgba8(&self) -> Option<Vec<u8>> {
        match self.format {
            vk::Format::R8G8B8A8_UNORM | vk::Format::R8G8B8A8_SRGB => Some(self.bytes.clone()),
            vk::Format::B8G8R8A8_UNORM | vk::Format::B8G8R8A8_SRGB => Some(
                self.bytes
                    .chunks_exact(4)
                    .flat_map(|p| [p[2], p[1], p[0], p[3]])
                    .collect(),
            ),
            _ => None,
        }
    }
}

/// Copy `image` to the host. The tracker records the transitions, so the image's state stays
/// known to the next frame.
pub fn read_image(ctx: &Arc<Context>, tracker: &mut Tracker, image: &Image) -> Result<ImageData> {
    let bpp = bytes_per_pixel(image.desc.format).ok_or_else(|| {
        Error::Config(format!(
            "readback of {:?} ({}) is not supported",
            image.desc.format, image.name
        ))
    })?;
    let size = image.desc.width as u64 * image.desc.height as u64 * bpp as u64;
    let staging = Buffer::new(
        ctx,
        "readback",
        size,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    one_shot(ctx, |cmd| {
        tracker.image(image, Access::TransferSrc);
        tracker.buffer(&staging, Access::TransferDst);
        tracker.flush(&ctx.device, cmd);
        Recorder::new(ctx, cmd).copy_image_to_buffer(image, &staging);
        tracker.buffer(&staging, Access::HostRead);
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })?;
    let bytes = staging
        .mapped()
        .ok_or_else(|| Error::Config("readback buffer is not host-visible".into()))?
        [..size as usize]
        .to_vec();
    Ok(ImageData {
        width: image.desc.width,
        height: image.desc.height,
        format: image.desc.format,
        bytes,
    })
}

/// Copy the whole of `buffer` (created with `TRANSFER_SRC`) to the host; as [`read_image`],
/// the tracker keeps its state known.
pub fn read_buffer(ctx: &Arc<Context>, tracker: &mut Tracker, buffer: &Buffer) -> Result<Vec<u8>> {
    let staging = Buffer::new(
        ctx,
        "readback",
        buffer.size,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    one_shot(ctx, |cmd| {
        tracker.buffer(buffer, Access::TransferSrc);
        tracker.buffer(&staging, Access::TransferDst);
        tracker.flush(&ctx.device, cmd);
        Recorder::new(ctx, cmd).copy_buffer(buffer, &staging, buffer.size);
        tracker.buffer(&staging, Access::HostRead);
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })?;
    Ok(staging
        .mapped()
        .ok_or_else(|| Error::Config("readback buffer is not host-visible".into()))?
        [..buffer.size as usize]
        .to_vec())
}

#[cfg(test)]
mod tests {
    use super::f16_to_f32;

    #[test]
    fn half_conversion() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x7bff), 65504.0);
        assert_eq!(f16_to_f32(0x0001), 5.960_464_5e-8);
        assert!(f16_to_f32(0x7c00).is_infinite());
        assert!(f16_to_f32(0x7e00).is_nan());
    }
}

//! The CPU evaluation of SVGF's spatial passes (shaders/svgf/): each pixel's reciprocal depth
//! and its gradient from the G-buffer, and the edge-avoiding a-trous iterations, written from
//! the article's equations so that a test can check the passes on read-back images.

use super::config::SvgfConfig;
use glam::{Mat4, Vec2, Vec3, Vec4};

/// The G-buffer as the spatial passes see it, row-major.
pub struct Surface {
    pub width: u32,
    pub height: u32,
    /// Reciprocal view depth (0: no geometry) and its gradient along x and y [per pixel].
    pub depth: Vec<Vec3>,
    pub normal: Vec<Vec3>,
}

/// The shaders' relative floors of the depth and luminance scales (svgf.glsl).
const DEPTH_FLOOR: f32 = 1e-3;
const LUMINANCE_FLOOR: f32 = 1e-3;
const LUMINANCE_TINY: f32 = 1e-30;
const LUMA: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);
/// The B3 spline's weights at 0, 1 and 2 taps.
const KERNEL: [f32; 3] = [0.375, 0.25, 0.0625];

impl Surface {
    /// From G-buffer positions (w = 0: background) and normals seen through `view_proj`.
    pub fn new(
        width: u32,
        height: u32,
        position: &[Vec4],
        normal: &[Vec3],
        view_proj: Mat4,
    ) -> Self {
        let z = |p: Vec4| {
            let w = (view_proj * p.truncate().extend(1.0)).w;
            if p.w != 0.0 && w > 0.0 {
                1.0 / w
            } else {
                0.0
            }
        };
        let zs: Vec<f32> = position.iter().map(|&p| z(p)).collect();
        let at = |x: i64, y: i64| {
            let inside = x >= 0 && y >= 0 && x < width as i64 && y < height as i64;
            if inside {
                zs[(y * width as i64 + x) as usize]
            } else {
                0.0
            }
        };
        let mut depth = Vec::with_capacity(zs.len());
        for y in 0..height as i64 {
            for x in 0..width as i64 {
                let c = at(x, y);
                depth.push(if c == 0.0 {
                    Vec3::ZERO
                } else {
                    Vec3::new(
                        c,
                        gradient(c, at(x - 1, y), at(x + 1, y)),
                        gradient(c, at(x, y - 1), at(x, y + 1)),
                    )
                });
            }
        }
        Self {
            width,
            height,
            depth,
            normal: normal.to_vec(),
        }
    }

    fn get(&self, x: i64, y: i64) -> Option<usize> {
        let inside = x >= 0 && y >= 0 && x < self.width as i64 && y < self.height as i64;
        let i = (y * self.width as i64 + x) as usize;
        (inside && self.depth[i].x > 0.0).then_some(i)
    }
}

/// The one-sided difference of smaller magnitude, 0 without a neighbour.
fn gradient(z: f32, before: f32, after: f32) -> f32 {
    let (db, da) = (z - before, after - z);
    match (before > 0.0, after > 0.0) {
        (true, true) => {
            if da.abs() <= db.abs() {
                da
            } else {
                db
            }
        }
        (false, true) => da,
        (true, false) => db,
        (false, false) => 0.0,
    }
}

/// The edge-stopping weight of tap q (svgf.glsl's `edge_weight`).
#[allow(clippy::too_many_arguments)]
fn edge_weight(
    c: &SvgfConfig,
    z_p: Vec3,
    l_p: f32,
    phi_l: f32,
    n_p: Vec3,
    z_q: f32,
    l_q: f32,
    n_q: Vec3,
    offset: Vec2,
) -> f32 {
    let phi_z = c.sigma_depth * Vec2::new(z_p.y, z_p.z).dot(offset).abs() + DEPTH_FLOOR * z_p.x;
    let w_n = if c.sigma_normal > 0.0 {
        n_p.dot(n_q).max(0.0).powf(c.sigma_normal)
    } else {
        1.0
    };
    w_n * (-(z_p.x - z_q).abs() / phi_z - (l_p - l_q).abs() / phi_l).exp()
}

/// One a-trous iteration with taps `step` pixels apart: rgb = colour, a = variance.
pub fn atrous(c: &SvgfConfig, s: &Surface, input: &[Vec4], step: i64) -> Vec<Vec4> {
    let mut out = vec![Vec4::ZERO; input.len()];
    for y in 0..s.height as i64 {
        for x in 0..s.width as i64 {
            let Some(p) = s.get(x, y) else { continue };
            let (mut var_sum, mut var_weights) = (0.0f32, 0.0f32);
            for dy in -1..=1i64 {
                for dx in -1..=1i64 {
                    if let Some(q) = s.get(x + dx, y + dy) {
                        let k = [0.5, 0.25][dx.unsigned_abs() as usize]
                            * [0.5, 0.25][dy.unsigned_abs() as usize];
                        var_sum += k * input[q].w;
                        var_weights += k;
                    }
                }
            }
            let centre = input[p];
            let l_p = centre.truncate().dot(LUMA);
            let sigma = (var_sum / var_weights).max(0.0).sqrt();
            let phi_l = c.sigma_luminance * sigma + LUMINANCE_FLOOR * l_p.abs() + LUMINANCE_TINY;
            let (mut sum, mut var, mut weights) = (Vec3::ZERO, 0.0f32, 0.0f32);
            for j in -2..=2i64 {
                for i in -2..=2i64 {
                    let Some(q) = s.get(x + i * step, y + j * step) else {
                        continue;
                    };
                    let v = input[q];
                    let offset = Vec2::new((i * step) as f32, (j * step) as f32);
                    let w = KERNEL[i.unsigned_abs() as usize]
                        * KERNEL[j.unsigned_abs() as usize]
                        * edge_weight(
                            c,
                            s.depth[p],
                            l_p,
                            phi_l,
                            s.normal[p],
                            s.depth[q].x,
                            v.truncate().dot(LUMA),
                            s.normal[q],
                            offset,
                        );
                    sum += w * v.truncate();
                    var += w * w * v.w;
                    weights += w;
                }
            }
            out[p] = if weights > 0.0 {
                (sum / weights).extend(var / (weights * weights))
            } else {
                centre
            };
        }
    }
    out
}

/// `iterations` a-trous iterations (the i-th with taps 2^i apart).
pub fn filter(c: &SvgfConfig, s: &Surface, integrated: &[Vec4], iterations: u32) -> Vec<Vec4> {
    (0..iterations).fold(integrated.to_vec(), |v, i| atrous(c, s, &v, 1 << i))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat, evenly lit plane facing the camera passes through unchanged however noisy the
    /// variance says it is; a depth step splits the kernel.
    #[test]
    fn a_constant_stays_constant_and_an_edge_holds() {
        let (w, h) = (16u32, 8u32);
        let n = (w * h) as usize;
        // Two planes at view depths 2 and 4 (reciprocals 0.5 and 0.25), split at x = 8.
        let depth = (0..n)
            .map(|i| Vec3::new(if i as u32 % w < 8 { 0.5 } else { 0.25 }, 0.0, 0.0))
            .collect();
        let s = Surface {
            width: w,
            height: h,
            depth,
            normal: vec![Vec3::Z; n],
        };
        let input: Vec<Vec4> = (0..n)
            .map(|i| {
                let v = if i as u32 % w < 8 { 1.0 } else { 3.0 };
                Vec4::new(v, v, v, 0.5)
            })
            .collect();
        let out = filter(&SvgfConfig::default(), &s, &input, 3);
        for (i, o) in out.iter().enumerate() {
            let v = input[i].x;
            assert!((o.x - v).abs() < 1e-5 * v, "pixel {i}: {o} from {v}");
            assert!(o.w < input[i].w, "the variance falls as it is averaged");
        }
    }
}

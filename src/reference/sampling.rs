//! Deterministic sample points for the reference: a randomly shifted R2 sequence per pixel,
//! buffer and half, and the warps from the unit square to directions.
//!
//! Each pixel's estimate is split into two halves whose shifts come from independent hashes:
//! each half is an unbiased randomized quasi-Monte Carlo estimate, the halves are independent,
//! so `|a - b| / 2` estimates the standard error of their mean (see `estimate.rs`).

use glam::{Vec2, Vec3};

/// PCG-style integer hash (Jarzynski & Olano 2020, "Hash functions for GPU rendering"):
/// deterministic, well mixed, no state.
pub fn hash(mut v: u32) -> u32 {
    v = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let w = ((v >> ((v >> 28) + 4)) ^ v).wrapping_mul(277803737);
    (w >> 22) ^ w
}

/// Hash of several words (chained).
pub fn hash_words(words: &[u32]) -> u32 {
    words
        .iter()
        .fold(0x9e37_79b9, |h, &w| hash(h ^ w.wrapping_mul(0x85eb_ca6b)))
}

/// A uniform float in [0, 1) from the top 24 bits of a hash.
pub fn unit_float(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The per-pixel, per-half Cranley-Patterson shift of the R2 sequence.
pub fn shift(pixel: u32, buffer: u32, half: u32, seed: u32) -> Vec2 {
    let h = hash_words(&[pixel, buffer, half, seed]);
    Vec2::new(unit_float(h), unit_float(hash(h)))
}

/// Point `i` of the R2 sequence (Roberts 2018), shifted by `s` (mod 1). In f64 so that the
/// fraction keeps its precision far along the sequence (i·α of a million needs more than
/// f32's 24 bits).
pub fn r2(i: u32, s: Vec2) -> Vec2 {
    const A1: f64 = 0.754_877_666_246_692_7;
    const A2: f64 = 0.569_840_290_998_053_2;
    let x = (0.5 + i as f64 * A1 + s.x as f64).fract();
    let y = (0.5 + i as f64 * A2 + s.y as f64).fract();
    // fract of a non-negative f64 is in [0, 1); the cast can round up to 1.0 for values
    // within 2^-25 of 1, so clamp below 1.
    Vec2::new((x as f32).min(ONE_MINUS_ULP), (y as f32).min(ONE_MINUS_ULP))
}

const ONE_MINUS_ULP: f32 = 1.0 - f32::EPSILON / 2.0;

/// An orthonormal basis (t, b) completing unit `n` (Duff et al. 2017, branchless).
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// Cosine-weighted direction in the hemisphere around unit `n` (pdf cos θ / π), and cos θ.
pub fn cosine_hemisphere(n: Vec3, u: Vec2) -> (Vec3, f32) {
    let r = u.x.sqrt();
    let phi = std::f32::consts::TAU * u.y;
    let cos_theta = (1.0 - u.x).max(0.0).sqrt();
    let (t, b) = basis(n);
    let d = t * (r * phi.cos()) + b * (r * phi.sin()) + n * cos_theta;
    (d, cos_theta)
}

/// A point uniform on the disc of radius `r` around `c` perpendicular to unit `axis`.
pub fn disc_point(c: Vec3, axis: Vec3, r: f32, u: Vec2) -> Vec3 {
    let (t, b) = basis(axis);
    let rho = r * u.x.sqrt();
    let phi = std::f32::consts::TAU * u.y;
    c + t * (rho * phi.cos()) + b * (rho * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::X,
            Vec3::NEG_Z,
            Vec3::new(0.3, -0.4, 0.866).normalize(),
        ] {
            let (t, b) = basis(n);
            for (x, y) in [(t, b), (t, n), (b, n)] {
                assert!(x.dot(y).abs() < 1e-6);
            }
            assert!((t.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn cosine_hemisphere_mean_cosine_is_two_thirds() {
        // E[cos θ] under pdf cos θ / π is 2/3.
        let s = shift(7, 0, 0, 1);
        let n = 4096;
        let mean: f32 = (0..n)
            .map(|i| cosine_hemisphere(Vec3::Y, r2(i, s)))
            .map(|(d, c)| {
                assert!((d.y - c).abs() < 1e-5 && d.y >= 0.0);
                c
            })
            .sum::<f32>()
            / n as f32;
        assert!((mean - 2.0 / 3.0).abs() < 1e-3, "{mean}");
    }

    #[test]
    fn r2_stays_in_the_unit_square_far_along() {
        let s = Vec2::new(0.999_999, 0.999_999);
        for i in [0, 1, 1 << 20, u32::MAX] {
            let p = r2(i, s);
            assert!(
                (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y),
                "{p}"
            );
        }
    }
}

//! Seeded randomness, the same on every run: the xorshift generator (refresh tile order,
//! the stress run's jitter) and the rotation texture of the SSAO sampling pattern.

/// xorshift64*: small, seedable, good enough for shuffles and noise textures.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.max(1))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    pub fn below(&mut self, n: u32) -> u32 {
        (((self.next_u64() >> 32) * n as u64) >> 32) as u32
    }
}

/// 4x4 random unit 2D vectors (RGBA32F texels: cos, sin, 0, 0): the per-pixel rotation of the
/// SSAO pattern, fixed seed so runs are reproducible.
pub fn random_vectors() -> Vec<u8> {
    let mut rng = Rng::new(0x0a05_eed1);
    (0..16)
        .flat_map(|_| {
            let a = rng.next_f32() * std::f32::consts::TAU;
            [a.cos(), a.sin(), 0.0, 0.0]
        })
        .flat_map(|f| f.to_le_bytes())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn random_vectors_are_unit() {
        let bytes = random_vectors();
        assert_eq!(bytes.len(), 16 * 16);
        for t in bytes.chunks(16) {
            let f = |i: usize| f32::from_le_bytes([t[i], t[i + 1], t[i + 2], t[i + 3]]);
            assert!((f(0).hypot(f(4)) - 1.0).abs() < 1e-5);
        }
    }
}

//! CPU side of the temporal machinery: the tiled-refresh schedule (Nehab et al. 2007) and the
//! random rotations of the sampling pattern.

/// Tile side of the refresh (the thesis: 64x64 for SSAO).
pub const REFRESH_TILE: u32 = 64;

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

/// One tile per frame, drawn from a random permutation of all tiles without repetition; a new
/// permutation starts when every tile has been refreshed.
#[derive(Clone, Debug)]
pub struct RefreshSchedule {
    tile: u32,
    tiles_x: u32,
    tiles_y: u32,
    order: Vec<u32>,
    next: usize,
    rng: Rng,
}

impl RefreshSchedule {
    pub fn new(width: u32, height: u32) -> Self {
        Self::with_tile(width, height, REFRESH_TILE)
    }

    /// Tiles of `tile` x `tile` pixels.
    pub fn with_tile(width: u32, height: u32, tile: u32) -> Self {
        Self {
            tile,
            tiles_x: width.div_ceil(tile),
            tiles_y: height.div_ceil(tile),
            order: Vec::new(),
            next: 0,
            rng: Rng::new(0x005e_ed0f_7e11),
        }
    }

    pub fn tile_count(&self) -> u32 {
        self.tiles_x * self.tiles_y
    }

    /// Pixel origin of the next tile.
    pub fn next_tile(&mut self) -> (u32, u32) {
        if self.next >= self.order.len() {
            self.order = (0..self.tile_count()).collect();
            for i in (1..self.order.len()).rev() {
                let j = self.rng.below(i as u32 + 1) as usize;
                self.order.swap(i, j);
            }
            self.next = 0;
        }
        let t = self.order[self.next];
        self.next += 1;
        (
            (t % self.tiles_x) * self.tile,
            (t / self.tiles_x) * self.tile,
        )
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
    fn every_tile_once_per_cycle() {
        let mut s = RefreshSchedule::new(300, 130); // 5 x 3 tiles, partial edge tiles
        assert_eq!(s.tile_count(), 15);
        for _ in 0..3 {
            let mut seen: Vec<(u32, u32)> = (0..15).map(|_| s.next_tile()).collect();
            seen.sort();
            seen.dedup();
            assert_eq!(seen.len(), 15);
            assert!(seen
                .iter()
                .all(|&(x, y)| x < 300 && y < 130 && x % 64 == 0 && y % 64 == 0));
        }
    }

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

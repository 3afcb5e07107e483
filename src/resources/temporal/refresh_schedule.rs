//! The tiled refresh (Nehab et al. 2007): which tile of the image is recomputed from scratch
//! each frame, on a grid shifted from cycle to cycle.

use crate::resources::random::Rng;

/// A refresh tile: the pixels [x0, x1) x [y0, y1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub struct RefreshRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

/// Grid shift of each refresh cycle in half tiles. A refreshed tile is blended in along a ramp a
/// quarter tile wide (shaders/include/effect.glsl, `refresh_weight`), so only its central half
/// is replaced outright; with the grid shifted by half a tile in x, y or both from cycle to
/// cycle, every pixel lies in the central half of some tile once every four cycles.
const GRID_SHIFTS: [(u32, u32); 4] = [(0, 0), (1, 1), (1, 0), (0, 1)];

/// One tile per frame, drawn from a random permutation of the tiles of this cycle's grid
/// without repetition; a new cycle, on the next shifted grid, starts when every tile has been
/// refreshed. Tiles cut by the image border are clipped.
#[derive(Clone, Debug)]
pub struct RefreshSchedule {
    tile: u32,
    width: u32,
    height: u32,
    order: Vec<RefreshRect>,
    next: usize,
    cycle: usize,
    rng: Rng,
}

impl RefreshSchedule {
    /// Tiles of `tile` x `tile` pixels.
    pub fn with_tile(width: u32, height: u32, tile: u32) -> Self {
        Self {
            tile,
            width,
            height,
            order: Vec::new(),
            next: 0,
            cycle: 0,
            rng: Rng::new(0x005e_ed0f_7e11),
        }
    }

    /// Side of the tiles (0: no refresh).
    pub fn tile(&self) -> u32 {
        self.tile
    }

    /// Width of the blend ramp at a tile's inner edges: a quarter tile.
    pub fn feather(&self) -> u32 {
        (self.tile / 4).max(1)
    }

    /// Start of the first tile along an axis for a grid shifted by `shift` pixels (negative:
    /// a tile cut by the image border).
    fn first_start(&self, shift: u32) -> i64 {
        if shift > 0 {
            shift as i64 - self.tile as i64
        } else {
            0
        }
    }

    /// Tile spans along one axis of `extent` pixels for a grid shifted by `shift` pixels.
    fn spans(&self, extent: u32, shift: u32) -> Vec<(u32, u32)> {
        let first = self.first_start(shift);
        (0..)
            .map(|k| first + k * self.tile as i64)
            .take_while(|&start| start < extent as i64)
            .map(|start| {
                let end = (start + self.tile as i64).min(extent as i64);
                (start.max(0) as u32, end as u32)
            })
            .collect()
    }

    /// Tiles in the grid of cycle `cycle`, counted without building it (`frames_to_cover`
    /// runs on every frame the camera moves).
    fn grid_len(&self, cycle: usize) -> usize {
        let (sx, sy) = GRID_SHIFTS[cycle % GRID_SHIFTS.len()];
        let half = self.tile / 2;
        let count = |extent: u32, shift: u32| {
            let covered = (extent as i64 - self.first_start(shift)).max(0) as usize;
            covered.div_ceil(self.tile as usize)
        };
        count(self.width, sx * half) * count(self.height, sy * half)
    }

    /// The tiles of the grid of cycle `cycle`.
    pub fn grid(&self, cycle: usize) -> Vec<RefreshRect> {
        let (sx, sy) = GRID_SHIFTS[cycle % GRID_SHIFTS.len()];
        let half = self.tile / 2;
        let xs = self.spans(self.width, sx * half);
        let ys = self.spans(self.height, sy * half);
        ys.iter()
            .flat_map(|&(y0, y1)| {
                xs.iter()
                    .map(move |&(x0, x1)| RefreshRect { x0, y0, x1, y1 })
            })
            .collect()
    }

    /// Frames from now until every pixel has lain in the core of a tile drawn since: the rest
    /// of this cycle and four shifted cycles (feathered), or one more cycle (`shifted` false:
    /// hard tiles replace everything they cover).
    /// 0 without a refresh (tile 0).
    pub fn frames_to_cover(&self, shifted: bool) -> u32 {
        if self.tile == 0 {
            return 0;
        }
        let rest = self.order.len().saturating_sub(self.next);
        let cycles: usize = if shifted {
            (0..GRID_SHIFTS.len())
                .map(|k| self.grid_len(self.cycle + k))
                .sum()
        } else {
            self.grid_len(0)
        };
        (rest + cycles) as u32
    }

    /// The next tile; `shifted`: on the grid of the current cycle, else on the unshifted grid
    /// (hard refresh, the thesis's fixed tiles).
    pub fn next_tile(&mut self, shifted: bool) -> RefreshRect {
        if self.next >= self.order.len() {
            self.order = self.grid(if shifted { self.cycle } else { 0 });
            self.cycle += 1;
            for i in (1..self.order.len()).rev() {
                let j = self.rng.below(i as u32 + 1) as usize;
                self.order.swap(i, j);
            }
            self.next = 0;
        }
        let t = self.order[self.next];
        self.next += 1;
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thesis's SSAO refresh tile side (64x64), which these tests schedule.
    const REFRESH_TILE: u32 = 64;

    #[test]
    fn every_pixel_once_per_cycle_on_shifted_grids() {
        let (w, h) = (300, 130); // partial edge tiles
        let mut s = RefreshSchedule::with_tile(w, h, REFRESH_TILE);
        for cycle in 0..8 {
            let tiles = s.grid(cycle).len();
            let mut hits = vec![0u32; (w * h) as usize];
            for _ in 0..tiles {
                let r = s.next_tile(true);
                assert!(
                    r.x0 < r.x1 && r.x1 <= w && r.y0 < r.y1 && r.y1 <= h,
                    "{r:?}"
                );
                assert!(r.x1 - r.x0 <= 64 && r.y1 - r.y0 <= 64);
                for y in r.y0..r.y1 {
                    for x in r.x0..r.x1 {
                        hits[(y * w + x) as usize] += 1;
                    }
                }
            }
            assert!(hits.iter().all(|&n| n == 1), "cycle {cycle}");
        }
        assert_eq!(s.grid(0).len(), 5 * 3);
        assert_eq!(s.grid(1).len(), 6 * 3); // shifted by 32: [0, 32), ..., [288, 300)
        for cycle in 0..4 {
            assert_eq!(s.grid_len(cycle), s.grid(cycle).len(), "cycle {cycle}");
        }
    }

    /// Distance of x from the nearest inner tile edge, as the shader's refresh_weight measures
    /// it (edges on the image border do not count).
    fn inner_distance(x: u32, (x0, x1): (u32, u32), extent: u32) -> f32 {
        let c = x as f32 + 0.5;
        let lo = if x0 == 0 { f32::MAX } else { c - x0 as f32 };
        let hi = if x1 >= extent {
            f32::MAX
        } else {
            x1 as f32 - c
        };
        lo.min(hi)
    }

    #[test]
    fn every_pixel_is_in_a_tile_core_within_four_cycles() {
        let (w, h) = (200, 150);
        let s = RefreshSchedule::with_tile(w, h, REFRESH_TILE);
        let feather = s.feather() as f32;
        let mut core = vec![false; (w * h) as usize];
        for cycle in 0..4 {
            for r in s.grid(cycle) {
                for y in r.y0..r.y1 {
                    for x in r.x0..r.x1 {
                        let d = inner_distance(x, (r.x0, r.x1), w).min(inner_distance(
                            y,
                            (r.y0, r.y1),
                            h,
                        ));
                        core[(y * w + x) as usize] |= d >= feather;
                    }
                }
            }
        }
        assert!(core.iter().all(|&c| c));
    }
}

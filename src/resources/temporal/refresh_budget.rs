//! The refresh's cost: evaluations per frame and per tile of an effect's sampling, and the
//! largest tile a refresh budget (a fraction of a full frame) allows.

/// Where an effect evaluates its patterns: at every pixel, or at half resolution (low-resolution
/// samples upsampled, with full-resolution fix-ups where the upsampling fails).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    FullRes,
    HalfRes,
}

impl Sampling {
    /// Evaluations of a full frame with one pattern: its pixels, or its low-resolution samples.
    pub fn frame_evaluations(self, width: u32, height: u32) -> u64 {
        match self {
            Sampling::FullRes => width as u64 * height as u64,
            Sampling::HalfRes => width.div_ceil(2) as u64 * height.div_ceil(2) as u64,
        }
    }
}

/// Evaluations per pattern of a refresh tile of side `s`: every pixel of it at full
/// resolution; at half resolution (a bound) the low-resolution samples it is upsampled from.
pub fn tile_evaluations(s: u32, sampling: Sampling) -> u64 {
    let side = match sampling {
        Sampling::FullRes => s as u64,
        // The low-resolution samples its pixels are upsampled from: pixel x reads samples
        // x / 2 and (odd x) x / 2 + 1, so at most s / 2 + 2 per axis (indirect_spread.comp's
        // refresh_samples).
        Sampling::HalfRes if s == 0 => 0,
        Sampling::HalfRes => s as u64 / 2 + 2,
    };
    side * side
}

/// The largest refresh tile side, at most `max_tile`, whose refresh (every one of `limit`
/// patterns at each of its evaluations) costs at most `budget` of a full frame's evaluations;
/// 0 when not even a single pixel fits (the refresh is then off for this effect).
pub fn budget_tile(
    max_tile: u32,
    sampling: Sampling,
    (width, height): (u32, u32),
    limit: u32,
    budget: f32,
) -> u32 {
    let allowed = budget as f64 * sampling.frame_evaluations(width, height) as f64;
    let fits = |s: u32| (tile_evaluations(s, sampling) * limit as u64) as f64 <= allowed;
    (1..=max_tile).take_while(|&s| fits(s)).last().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn budget_tile_stays_within_the_budget() {
        // 256x256 AO, 36 patterns, 5%: 3276.8 evaluations allowed, 9x9x36 = 2916 fit.
        assert_eq!(budget_tile(64, Sampling::FullRes, (256, 256), 36, 0.05), 9);
        assert_eq!(budget_tile(64, Sampling::FullRes, (512, 512), 36, 0.05), 19);
        assert_eq!(budget_tile(64, Sampling::FullRes, (64, 64), 36, 0.05), 2);
        // The thesis's tile where the budget allows it.
        assert_eq!(budget_tile(64, Sampling::FullRes, (512, 512), 1, 1.0), 64);
        // Nothing fits: no refresh.
        assert_eq!(budget_tile(64, Sampling::FullRes, (8, 8), 36, 0.05), 0);
        for size in [64, 100, 256, 512, 1920] {
            for limit in [1, 4, 36, 256] {
                for budget in [0.01, 0.05, 0.2] {
                    for sampling in [Sampling::FullRes, Sampling::HalfRes] {
                        let s = budget_tile(64, sampling, (size, size), limit, budget);
                        let cost = tile_evaluations(s, sampling) * limit as u64;
                        let allowed = budget as f64 * sampling.frame_evaluations(size, size) as f64;
                        assert!(
                            cost as f64 <= allowed,
                            "{size} {limit} {budget} {sampling:?}"
                        );
                        let bigger = tile_evaluations(s + 1, sampling) * limit as u64;
                        assert!(s == 64 || bigger as f64 > allowed);
                    }
                }
            }
        }
    }
}

//! A per-pixel Monte Carlo estimate kept as two independent halves, so that it can grow by
//! more samples later (a cached reference is refined, not recomputed) and report its own
//! standard error: for half means a and b of n samples each, E[(a − b)²] = 2σ²/n and the mean
//! (a + b)/2 has variance σ²/(2n) = E[(a − b)²]/4.

#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    pub channels: usize,
    /// Samples in each half, per pixel.
    pub per_half: u32,
    /// Per half: the sum of the samples, `channels` values per pixel, row order.
    pub sums: [Vec<f64>; 2],
}

impl Estimate {
    pub fn new(channels: usize, pixels: usize) -> Self {
        Self {
            channels,
            per_half: 0,
            sums: [vec![0.0; channels * pixels], vec![0.0; channels * pixels]],
        }
    }

    /// The estimate: both halves' mean (0 before any sample).
    pub fn mean(&self) -> Vec<f32> {
        let n = 2.0 * self.per_half.max(1) as f64;
        self.sums[0]
            .iter()
            .zip(&self.sums[1])
            .map(|(a, b)| ((a + b) / n) as f32)
            .collect()
    }

    /// Root mean square over the masked values of the estimated standard error of each
    /// value: the standard error of an RMSE measured against this estimate.
    pub fn standard_error(&self, mask: &[bool]) -> f64 {
        let n = self.per_half.max(1) as f64;
        let (mut sum, mut count) = (0.0, 0usize);
        for (i, (a, b)) in self.sums[0].iter().zip(&self.sums[1]).enumerate() {
            if mask.get(i / self.channels) == Some(&true) {
                let d = (a - b) / n / 2.0;
                sum += d * d;
                count += 1;
            }
        }
        if count == 0 {
            0.0
        } else {
            (sum / count as f64).sqrt()
        }
    }

    /// Root mean square of the estimate over the masked values (the scale of relative errors).
    pub fn rms(&self, mask: &[bool]) -> f64 {
        let mean = self.mean();
        let (mut sum, mut count) = (0.0f64, 0usize);
        for (i, v) in mean.iter().enumerate() {
            if mask.get(i / self.channels) == Some(&true) {
                sum += (*v as f64).powi(2);
                count += 1;
            }
        }
        if count == 0 {
            0.0
        } else {
            (sum / count as f64).sqrt()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_error_of_two_halves() {
        let mut e = Estimate::new(1, 2);
        e.per_half = 4;
        e.sums = [vec![4.0, 2.0], vec![2.0, 2.0]];
        assert_eq!(e.mean(), vec![0.75, 0.5]);
        // Pixel 0: halves 1.0 and 0.5 -> se 0.25; pixel 1: 0.
        assert!((e.standard_error(&[true, false]) - 0.25).abs() < 1e-12);
        assert!((e.standard_error(&[true, true]) - (0.0625f64 / 2.0).sqrt()).abs() < 1e-12);
        assert_eq!(e.standard_error(&[false, false]), 0.0);
    }
}

//! Candid covariance-free incremental PCA (Weng, Zhang & Hwang 2003) as Chen, Lei & Chang 2012
//! apply it to images, in f64 on the CPU: the model the GPU filter (this folder's effect) is
//! checked against, frame by frame (tests/ccipca.rs).
//!
//! Each frame is one sample: an image of `pixels` x `channels` values, i.e. one vector whose
//! dimensions are pixel channels. No mean is subtracted: Chen et al.'s eq 1 writes the image
//! as a weighted sum of bases only, so the first basis follows the (uncentered) image itself.
//! Basis `i` is stored unnormalized as v_i = lambda_i e_i. Per frame, with the residual u_1 = x:
//!
//! - a basis that is still zero takes the residual: v_i = u_i (Weng's case i = n);
//! - otherwise v_i <- (1 - a_p) v_i + a_p (u_i . v_i / |v_i|) u_i, per pixel p, with the step
//!   a_p = (1 + l) / (n_p + l) from the pixel's own sample count n_p (Chen et al.'s per-pixel
//!   weighting: a pixel new to the view takes large steps while the others take small ones);
//! - then the residual loses its projection on the new basis: u_{i+1} = u_i - (u_i . v_i /
//!   |v_i|^2) v_i.
//!
//! The reconstruction is x - u_{k+1}: the sample projected on the k bases. `l` is the
//! amnesic parameter: (1 + l) / (n + l) weights new samples more than the plain mean 1 / n
//! would, so older (differently lit) frames fade; a_1 = 1 and the steps fall monotonically.

/// Weng et al.'s amnesic parameter l: "typically 2 to 4"; 2 keeps the most averaging.
pub const AMNESIC: f64 = 2.0;

/// The CCIPCA step for a dimension seen `n` >= 1 times.
pub fn step(n: u32) -> f64 {
    (1.0 + AMNESIC) / (n.max(1) as f64 + AMNESIC)
}

pub struct Ccipca {
    channels: usize,
    max_age: u32,
    /// v_i, unnormalized, `pixels * channels` values each.
    bases: Vec<Vec<f64>>,
    /// Samples each pixel has seen (capped at `max_age`).
    ages: Vec<u32>,
}

impl Ccipca {
    /// `bases` bases of images of `pixels` pixels with `channels` values each; a pixel's step
    /// stops shrinking after `max_age` samples.
    pub fn new(pixels: usize, channels: usize, bases: usize, max_age: u32) -> Self {
        Self {
            channels,
            max_age: max_age.max(1),
            bases: vec![vec![0.0; pixels * channels]; bases],
            ages: vec![0; pixels],
        }
    }

    pub fn bases(&self) -> &[Vec<f64>] {
        &self.bases
    }

    /// Every pixel starts over (all bases zero, no samples seen).
    pub fn reset(&mut self) {
        for b in &mut self.bases {
            b.fill(0.0);
        }
        self.ages.fill(0);
    }

    /// The projection of `x` on the bases as they are, x - u_{k+1} (each basis taking its
    /// projection out of the residual in turn; a zero basis takes nothing).
    pub fn project(&self, x: &[f32]) -> Vec<f64> {
        let mut u: Vec<f64> = x.iter().map(|&v| v as f64).collect();
        for v in &self.bases {
            let vv = dot(v, v);
            if vv > 0.0 {
                let coeff = dot(&u, v) / vv;
                u.iter_mut().zip(v).for_each(|(uj, vj)| *uj -= coeff * vj);
            }
        }
        x.iter().zip(&u).map(|(&xj, uj)| xj as f64 - uj).collect()
    }

    /// Take sample `x` (`pixels * channels` values) and return its reconstruction from the
    /// updated bases (the article's order; [`Ccipca::project`] before this is the other).
    pub fn update(&mut self, x: &[f32]) -> Vec<f64> {
        let c = self.channels;
        assert_eq!(x.len(), self.ages.len() * c, "sample size");
        for a in &mut self.ages {
            *a = (*a + 1).min(self.max_age);
        }
        let steps: Vec<f64> = self.ages.iter().map(|&n| step(n)).collect();
        let mut u: Vec<f64> = x.iter().map(|&v| v as f64).collect();
        for v in &mut self.bases {
            let vv = dot(v, v);
            if vv > 0.0 {
                let s = dot(&u, v) / vv.sqrt();
                for (j, (vj, uj)) in v.iter_mut().zip(&u).enumerate() {
                    let a = steps[j / c];
                    *vj = (1.0 - a) * *vj + a * s * uj;
                }
            } else {
                v.copy_from_slice(&u);
            }
            let norm = dot(v, v);
            let coeff = if norm > 0.0 { dot(&u, v) / norm } else { 0.0 };
            for (uj, vj) in u.iter_mut().zip(v.iter()) {
                *uj -= coeff * vj;
            }
        }
        x.iter().zip(&u).map(|(&xj, uj)| xj as f64 - uj).collect()
    }

    /// Chen et al.'s Algorithm 2: Gram-Schmidt of the bases in order, each losing its
    /// projection on those before it (their lengths, the eigenvalue estimates, otherwise kept).
    pub fn orthogonalize(&mut self) {
        for i in 1..self.bases.len() {
            let (done, rest) = self.bases.split_at_mut(i);
            let v = &mut rest[0];
            for b in done.iter() {
                let bb = dot(b, b);
                if bb > 0.0 {
                    let coeff = dot(v, b) / bb;
                    for (vj, bj) in v.iter_mut().zip(b) {
                        *vj -= coeff * bj;
                    }
                }
            }
        }
    }
}

pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// |cos| of the angle between `a` and `b` (0 when either is zero).
pub fn abs_cos(a: &[f64], b: &[f64]) -> f64 {
    let d = (dot(a, a) * dot(b, b)).sqrt();
    if d > 0.0 {
        dot(a, b).abs() / d
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// xorshift64* and Box-Muller: reproducible normal deviates without a dependency.
    struct Normal(u64);

    impl Normal {
        fn uniform(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let r = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
            ((r >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        }

        fn sample(&mut self) -> f64 {
            let (u1, u2) = (self.uniform(), self.uniform());
            (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
        }
    }

    /// An orthonormal basis of R^d from Gram-Schmidt of random vectors.
    fn random_orthonormal(d: usize, rng: &mut Normal) -> Vec<Vec<f64>> {
        let mut q: Vec<Vec<f64>> = Vec::new();
        while q.len() < d {
            let mut v: Vec<f64> = (0..d).map(|_| rng.sample()).collect();
            for b in &q {
                let c = dot(&v, b);
                v.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
            }
            let n = dot(&v, &v).sqrt();
            if n > 1e-6 {
                q.push(v.iter().map(|x| x / n).collect());
            }
        }
        q
    }

    /// Samples with covariance Q diag(lambda) Q^T: CCIPCA finds the leading eigenvectors.
    #[test]
    fn finds_leading_eigenvectors_of_a_known_covariance() {
        let d = 48;
        let mut rng = Normal(0x9E37_79B9_7F4A_7C15);
        let q = random_orthonormal(d, &mut rng);
        let lambda: Vec<f64> = (0..d)
            .map(|i| match i {
                0 => 16.0,
                1 => 8.0,
                2 => 4.0,
                _ => 0.25,
            })
            .collect();
        let mut pca = Ccipca::new(d, 1, 3, u32::MAX);
        for _ in 0..6000 {
            let mut x = vec![0.0f64; d];
            for (qi, li) in q.iter().zip(&lambda) {
                let z = rng.sample() * li.sqrt();
                x.iter_mut().zip(qi).for_each(|(xj, qj)| *xj += z * qj);
            }
            let x: Vec<f32> = x.iter().map(|&v| v as f32).collect();
            pca.update(&x);
        }
        for i in 0..3 {
            let cos = abs_cos(&pca.bases()[i], &q[i]);
            assert!(cos > 0.99, "basis {i}: |cos| {cos}");
            // v_i's length estimates the eigenvalue.
            let length = dot(&pca.bases()[i], &pca.bases()[i]).sqrt();
            assert!(
                (length / lambda[i] - 1.0).abs() < 0.25,
                "basis {i}: length {length} for eigenvalue {}",
                lambda[i]
            );
        }
    }

    #[test]
    fn orthogonalized_bases_are_orthogonal() {
        let mut rng = Normal(7);
        let mut pca = Ccipca::new(32, 3, 4, 64);
        for b in &mut pca.bases {
            b.iter_mut().for_each(|v| *v = rng.sample());
        }
        pca.bases[1] = pca.bases[0].iter().map(|v| v + 0.1).collect();
        pca.orthogonalize();
        for i in 0..4 {
            for j in 0..i {
                let cos = abs_cos(&pca.bases()[i], &pca.bases()[j]);
                assert!(cos < 1e-9, "bases {j} and {i}: |cos| {cos}");
            }
        }
    }

    /// A sample lying in the span of the bases is reconstructed exactly: the first frame's
    /// basis is the frame itself.
    #[test]
    fn first_frame_is_its_own_reconstruction() {
        let mut pca = Ccipca::new(4, 3, 3, 64);
        let x: Vec<f32> = (0..12).map(|i| i as f32 * 0.25).collect();
        let r = pca.update(&x);
        for (a, b) in r.iter().zip(&x) {
            assert!((a - *b as f64).abs() < 1e-12);
        }
        assert_eq!(step(1), 1.0);
        assert!(step(2) < step(1) && step(100) < step(2));
    }
}

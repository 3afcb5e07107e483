//! Pareto front of (cost, error) points, for `ssgi sweep`: which renderer configurations are
//! worth their GPU time, i.e. no other configuration is at least as fast and at least as
//! accurate while strictly better in one of the two.

use std::cmp::Ordering;

/// Lexicographic (x, y) order; `total_cmp` so sorting never panics. Adding 0.0 turns -0.0
/// into 0.0, so on finite values this agrees exactly with IEEE `<` and `==` (plain `total_cmp`
/// would order -0.0 before 0.0 and break up runs of equal x).
fn by_x_then_y(a: (f64, f64), b: (f64, f64)) -> Ordering {
    let key = |p: (f64, f64)| (p.0 + 0.0, p.1 + 0.0);
    let (a, b) = (key(a), key(b));
    a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1))
}

/// For each point, whether it is Pareto-optimal when minimising both coordinates.
///
/// A point is dominated when another point is `<=` in both coordinates and `<` in at least
/// one; exact duplicates therefore do not dominate each other and are both optimal. Points
/// with a NaN or infinite coordinate are never optimal and never dominate (a failed or
/// unmeasured configuration must not hide real ones).
///
/// O(n log n): sort the finite points by x then y and sweep, keeping the smallest y among
/// points with strictly smaller x. Within a run of equal x, only the points at the run's
/// smallest y can be optimal, and they are iff that y is below every y seen at smaller x.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<bool> {
    let mut optimal = vec![false; points.len()];
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    order.sort_by(|&a, &b| by_x_then_y(points[a], points[b]));

    let mut best_y = f64::INFINITY; // smallest y at strictly smaller x
    let mut start = 0;
    while start < order.len() {
        let x = points[order[start]].0;
        let end = start
            + order[start..]
                .iter()
                .take_while(|&&i| points[i].0 == x)
                .count();
        // Sorted by y within the run, so the first is lowest.
        let run_min = points[order[start]].1;
        if run_min < best_y {
            for &i in &order[start..end] {
                optimal[i] = points[i].1 == run_min;
            }
            best_y = run_min;
        }
        start = end;
    }
    optimal
}

/// The optimal points (`optimal` as returned by [`pareto_front`]) sorted by x (then y), with
/// exact duplicates merged: the vertices of the front, ready to draw left to right. Pairs
/// past the shorter of the two slices are ignored.
pub fn front_polyline(points: &[(f64, f64)], optimal: &[bool]) -> Vec<(f64, f64)> {
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .zip(optimal)
        .filter(|(p, &o)| o && p.0.is_finite() && p.1.is_finite())
        .map(|(&p, _)| p)
        .collect();
    front.sort_by(|&a, &b| by_x_then_y(a, b));
    front.dedup();
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, O(n²).
    fn brute_force(points: &[(f64, f64)]) -> Vec<bool> {
        let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        points
            .iter()
            .map(|p| {
                finite(p)
                    && !points
                        .iter()
                        .any(|q| finite(q) && q.0 <= p.0 && q.1 <= p.1 && (q.0 < p.0 || q.1 < p.1))
            })
            .collect()
    }

    /// xorshift64*: deterministic, no dependency.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
        }
        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
        fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    const SPECIAL: [f64; 6] = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
    ];

    /// One coordinate drawn according to `kind`, sometimes replaced by a special value.
    fn coordinate(rng: &mut Rng, kind: u64, grid: u64, special_rate: u64) -> f64 {
        if special_rate > 0 && rng.below(special_rate) == 0 {
            return SPECIAL[rng.below(SPECIAL.len() as u64) as usize];
        }
        match kind {
            0 => rng.unit(),                                 // continuous, ties unlikely
            1 => rng.below(grid) as f64,                     // integer grid, many ties
            2 => rng.below(grid) as f64 - grid as f64 / 2.0, // negatives too
            _ => (rng.unit() * 4.0 - 2.0).exp(),             // log-spread, like error metrics
        }
    }

    fn random_set(rng: &mut Rng) -> Vec<(f64, f64)> {
        let n = match rng.below(4) {
            0 => rng.below(4),
            1 => rng.below(20),
            2 => rng.below(100),
            _ => 100 + rng.below(300),
        } as usize;
        let (kx, ky) = (rng.below(4), rng.below(4));
        let grid = 1 + rng.below(12);
        let special_rate = [0, 0, 3, 10, 50][rng.below(5) as usize];
        let mut points: Vec<(f64, f64)> = (0..n)
            .map(|_| {
                (
                    coordinate(rng, kx, grid, special_rate),
                    coordinate(rng, ky, grid, special_rate),
                )
            })
            .collect();
        // Exact duplicates of earlier points, including of non-finite ones.
        if n > 0 && rng.below(2) == 0 {
            for _ in 0..rng.below(n as u64 + 1) {
                let p = points[rng.below(points.len() as u64) as usize];
                points.push(p);
            }
        }
        // A shuffle so duplicates and ties land anywhere.
        for i in (1..points.len()).rev() {
            points.swap(i, rng.below(i as u64 + 1) as usize);
        }
        points
    }

    #[test]
    fn hand_made_example() {
        let points = [
            (1.0, 9.0),           // 0 optimal: fastest
            (2.0, 5.0),           // 1 optimal
            (2.0, 6.0),           // 2 dominated by 1 (same x, worse y)
            (3.0, 5.0),           // 3 dominated by 1 (same y, slower)
            (4.0, 2.0),           // 4 optimal
            (4.0, 2.0),           // 5 duplicate of 4: both optimal
            (5.0, 3.0),           // 6 dominated by 4
            (6.0, 1.0),           // 7 optimal: most accurate
            (f64::NAN, 0.0),      // 8 NaN: never optimal
            (0.5, f64::INFINITY), // 9 infinite: never optimal, dominates nothing
            (7.0, f64::NAN),      // 10
        ];
        let optimal = pareto_front(&points);
        let expected = [
            true, true, false, false, true, true, false, true, false, false, false,
        ];
        assert_eq!(optimal, expected);
        assert_eq!(optimal, brute_force(&points));
        assert_eq!(
            front_polyline(&points, &optimal),
            vec![(1.0, 9.0), (2.0, 5.0), (4.0, 2.0), (6.0, 1.0)]
        );
    }

    #[test]
    fn small_and_degenerate_sets() {
        let nan = f64::NAN;
        let cases: Vec<Vec<(f64, f64)>> = vec![
            vec![],
            vec![(1.0, 1.0)],
            vec![(nan, nan)],
            vec![(1.0, 1.0); 5],
            vec![(0.0, 0.0), (-0.0, -0.0), (0.0, -0.0)],
            vec![(-0.0, 5.0), (0.0, 1.0), (-0.0, 1.0)],
            vec![(-0.0, 5.0), (0.0, 1.0)],
            vec![(1.0, 2.0), (2.0, 1.0)],
            vec![(1.0, 1.0), (1.0, 2.0), (2.0, 1.0)],
            vec![(f64::NEG_INFINITY, 0.0), (1.0, 1.0)],
            (0..10).map(|i| (i as f64, 10.0 - i as f64)).collect(),
            (0..10).map(|i| (i as f64, i as f64)).collect(),
        ];
        for points in &cases {
            assert_eq!(pareto_front(points), brute_force(points), "{points:?}");
        }
        assert_eq!(pareto_front(&[(1.0, 1.0); 5]), vec![true; 5]);
        assert_eq!(
            pareto_front(&[(1.0, 1.0), (1.0, 2.0), (2.0, 1.0)]),
            vec![true, false, false]
        );
    }

    #[test]
    fn matches_brute_force_on_random_sets() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut optimal_seen, mut dominated_seen) = (0, 0);
        for case in 0..10_000 {
            let points = random_set(&mut rng);
            let fast = pareto_front(&points);
            let slow = brute_force(&points);
            assert_eq!(fast, slow, "case {case}: {points:?}");
            optimal_seen += fast.iter().filter(|&&o| o).count();
            dominated_seen += fast.iter().filter(|&&o| !o).count();

            // The polyline is the optimal set, sorted, each distinct point once.
            let line = front_polyline(&points, &fast);
            assert!(line
                .windows(2)
                .all(|w| w[0].0 <= w[1].0 && w[0].1 >= w[1].1));
            for &p in &line {
                assert!(points.iter().zip(&fast).any(|(&q, &o)| o && q == p));
            }
            for (q, _) in points.iter().zip(&fast).filter(|(_, &o)| o) {
                assert!(line.iter().any(|p| p == q), "case {case}: {q:?} missing");
            }
        }
        // The generator exercised both outcomes substantially.
        assert!(optimal_seen > 5_000 && dominated_seen > 50_000);
    }

    #[test]
    fn front_polyline_ignores_length_mismatch() {
        let points = [(2.0, 1.0), (1.0, 2.0), (3.0, 0.0)];
        assert_eq!(
            front_polyline(&points, &[true, true]),
            vec![(1.0, 2.0), (2.0, 1.0)]
        );
    }
}

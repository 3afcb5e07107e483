//! The sampling patterns the AO and PCF passes accumulate cover their domains: the offsets
//! the shaders really use (shaders/include/patterns.glsl, evaluated on the device by the probe
//! shaders/probes/pattern_offsets.comp) against the analytic uniform distributions, with
//! Kolmogorov-Smirnov-style maximum deviations of the empirical CDFs.

mod common;

use ash::vk;
use gpu_allocator::MemoryLocation;
use ssgi::bench::tables::reuse::rows::{REFERENCE_AO_PATTERNS, REFERENCE_PCF};
use ssgi::config::pcf::Pcf;
use ssgi::config::{TemporalConfig, MAX_PATTERNS};
use ssgi::effects::ao::config::AoConfig;
use ssgi::effects::ao::params::REFERENCE_PATTERN_BASE;
use ssgi::shaders::{DescriptorKind, ProbePush, ReflectedBinding, PATTERN_OFFSETS_COMP};
use ssgi::vk::recorder::Recorder;
use ssgi::vk::{one_shot, Access, Buffer, Context, DescriptorPool, Pipeline, SetWriter, Tracker};
use std::f32::consts::TAU;
use std::sync::Arc;

const PCF_DISC: u32 = 0;
const CRYTEK_BALL: u32 = 1;
const THESIS_PATTERN: u32 = 2;
const EQ8_STEPS: u32 = 3;
const RADICAL_INVERSES: u32 = 4;
const HALTON_HEMISPHERE: u32 = 5;

/// The acceptance bound of issue 18: the radial distribution of the used offsets within 2%
/// of the uniform-area CDF.
const UNIFORM_TOLERANCE: f32 = 0.02;

/// The probe's output for `patterns` patterns from `first` at `pixels` pixels: one vec4 per
/// tap, pattern-major, pixel-major (pixel y is (y, 3y)).
fn probe(ctx: &Arc<Context>, push: ProbePush, pixels: u32) -> Vec<[f32; 4]> {
    let taps = if push.kind == THESIS_PATTERN || push.kind >= RADICAL_INVERSES {
        1
    } else {
        push.count
    };
    let width = taps * push.patterns;
    let len = (width * pixels) as usize;
    let buffer = Buffer::new(
        ctx,
        "pattern offsets",
        16 * len as u64,
        vk::BufferUsageFlags::STORAGE_BUFFER,
        MemoryLocation::GpuToCpu,
    )
    .unwrap();
    let declared = [ReflectedBinding {
        set: 0,
        binding: 0,
        kind: DescriptorKind::StorageBuffer,
        count: 1,
    }];
    let pipeline =
        Pipeline::compute(ctx, "pattern_offsets", &PATTERN_OFFSETS_COMP, &declared).unwrap();
    let pool = DescriptorPool::new(ctx).unwrap();
    let set = pool
        .allocate(pipeline.set_layouts[0], "pattern offsets")
        .unwrap();
    SetWriter::new().storage_buffer(0, &buffer).write(ctx, set);
    one_shot(ctx, |cmd| {
        let mut tracker = Tracker::new();
        tracker.buffer(&buffer, Access::ComputeStorageWrite);
        tracker.flush(&ctx.device, cmd);
        let rec = Recorder::new(ctx, cmd);
        rec.bind(&pipeline, &[set]);
        rec.push(&pipeline, &push.to_bytes());
        rec.dispatch_2d(&pipeline, width, pixels);
        tracker.buffer(&buffer, Access::HostRead);
        tracker.flush(&ctx.device, cmd);
        Ok(())
    })
    .unwrap();
    buffer.mapped().unwrap()[..16 * len]
        .chunks_exact(16)
        .map(|c| {
            std::array::from_fn(|i| f32::from_le_bytes(c[4 * i..4 * i + 4].try_into().unwrap()))
        })
        .collect()
}

fn sorted(mut v: Vec<f32>) -> Vec<f32> {
    v.sort_by(f32::total_cmp);
    v
}

/// Largest deviation of the empirical CDF of `x` from the uniform CDF on [0, 1].
fn ks_uniform(x: &[f32]) -> f32 {
    let x = sorted(x.to_vec());
    let n = x.len() as f32;
    x.iter()
        .enumerate()
        .map(|(i, v)| ((i + 1) as f32 / n - v).max(v - i as f32 / n))
        .fold(0.0, f32::max)
}

/// Kuiper's statistic against the uniform distribution on a circle of circumference 1: the
/// largest deviation above plus the largest below, invariant under rotations (the PCF's
/// per-pixel turn moves where a KS statistic would anchor).
fn kuiper_uniform(x: &[f32]) -> f32 {
    let x = sorted(x.to_vec());
    let n = x.len() as f32;
    let above = x
        .iter()
        .enumerate()
        .map(|(i, v)| (i + 1) as f32 / n - v)
        .fold(0.0, f32::max);
    let below = x
        .iter()
        .enumerate()
        .map(|(i, v)| v - i as f32 / n)
        .fold(0.0, f32::max);
    above + below
}

/// Largest deviation of the empirical joint CDF of `p` from the product of uniforms on
/// [0, 1]^2, on a 64 x 64 grid of corners.
fn ks_uniform_2d(p: &[(f32, f32)]) -> f32 {
    let n = p.len() as f32;
    let mut worst = 0.0f32;
    for a in 1..=64 {
        for b in 1..=64 {
            let (a, b) = (a as f32 / 64.0, b as f32 / 64.0);
            let inside = p.iter().filter(|(x, y)| *x < a && *y < b).count() as f32;
            worst = worst.max((inside / n - a * b).abs());
        }
    }
    worst
}

/// Two-sample statistic: the largest difference of the empirical CDFs of `a` and `b`.
fn ks_two_sample(a: &[f32], b: &[f32]) -> f32 {
    let (a, b) = (sorted(a.to_vec()), sorted(b.to_vec()));
    a.iter()
        .chain(&b)
        .map(|t| {
            let fa = a.partition_point(|v| v <= t) as f32 / a.len() as f32;
            let fb = b.partition_point(|v| v <= t) as f32 / b.len() as f32;
            (fa - fb).abs()
        })
        .fold(0.0, f32::max)
}

#[test]
fn pcf_disc_taps_fill_the_disc_over_the_rotation_limit() {
    let ctx = common::context();
    let limit = TemporalConfig::default().rotation_limit;
    let count = Pcf::NINE.samples();
    let pixels = 4;
    let out = probe(
        &ctx,
        ProbePush {
            kind: PCF_DISC,
            count,
            first_pattern: 0,
            patterns: limit,
            ..Default::default()
        },
        pixels,
    );
    let per_pixel = (count * limit) as usize;
    let mut converged_r2 = Vec::new();
    for (pixel, offsets) in out.chunks_exact(per_pixel).enumerate() {
        // Uniform in the disc: r^2 / R^2 uniform, the angle uniform.
        let r2: Vec<f32> = offsets.iter().map(|o| o[0] * o[0] + o[1] * o[1]).collect();
        let angle: Vec<f32> = offsets
            .iter()
            .map(|o| o[1].atan2(o[0]).rem_euclid(TAU) / TAU)
            .collect();
        let (radial, angular) = (ks_uniform(&r2), kuiper_uniform(&angle));
        eprintln!("pixel {pixel}: radial KS {radial:.4}, angular Kuiper {angular:.4}");
        assert!(
            radial <= UNIFORM_TOLERANCE,
            "pixel {pixel}: radial {radial}"
        );
        assert!(
            angular <= UNIFORM_TOLERANCE,
            "pixel {pixel}: angular {angular}"
        );
        // Inside the kernel radius (1 + 2^-20: fp32 rounding of the square root).
        assert!(r2.iter().all(|r| *r < 1.0 + 1e-6), "pixel {pixel}");
        converged_r2.extend(r2);
    }
    // Pattern 0 (the fixed pattern without reuse) is the classic spiral sqrt((j + 1/2) / n).
    for (j, o) in out[..count as usize].iter().enumerate() {
        let expected = ((j as f32 + 0.5) / count as f32).sqrt();
        let r = o[0].hypot(o[1]);
        assert!((r - expected).abs() < 1e-6, "tap {j}: {r} vs {expected}");
    }
    // The reference's 1024-tap disc (pattern 0 without reuse) has the radial distribution the
    // accumulated 9-tap disc converges to.
    let reference = probe(
        &ctx,
        ProbePush {
            kind: PCF_DISC,
            count: REFERENCE_PCF.samples(),
            first_pattern: 0,
            patterns: 1,
            ..Default::default()
        },
        1,
    );
    let reference_r2: Vec<f32> = reference
        .iter()
        .map(|o| o[0] * o[0] + o[1] * o[1])
        .collect();
    let (own, between) = (
        ks_uniform(&reference_r2),
        ks_two_sample(&reference_r2, &converged_r2),
    );
    eprintln!(
        "1024-tap reference: radial KS {own:.5}, against the converged 9-tap disc {between:.4}"
    );
    // Its radii are sqrt((j + 1/2) / 1024): half a stratum from uniform, plus fp32 rounding.
    assert!(own <= 0.5 / 1024.0 + 1e-5, "reference radial {own}");
    assert!(
        between <= UNIFORM_TOLERANCE,
        "reference vs converged {between}"
    );
    common::assert_clean(&ctx);
}

#[test]
fn crytek_kernel_is_uniform_in_the_ball() {
    let ctx = common::context();
    let limit = TemporalConfig::default().rotation_limit;
    for count in [16, AoConfig::default().samples] {
        for (first, patterns) in [(0, limit), (REFERENCE_PATTERN_BASE, REFERENCE_AO_PATTERNS)] {
            let out = probe(
                &ctx,
                ProbePush {
                    kind: CRYTEK_BALL,
                    count,
                    first_pattern: first,
                    patterns,
                    ..Default::default()
                },
                1,
            );
            let r: Vec<f32> = out
                .iter()
                .map(|o| (o[0] * o[0] + o[1] * o[1] + o[2] * o[2]).sqrt())
                .collect();
            assert!(r.iter().all(|r| *r < 1.0 + 1e-6));
            // Uniform in the ball: r^3 uniform; the direction uniform on the sphere, i.e.
            // (1 - cos theta) / 2 and the azimuth uniform (Archimedes); radius and direction
            // independent, which a kernel with radius and depth both rising with the sample
            // index (an egg) fails by 0.25.
            let r3: Vec<f32> = r.iter().map(|r| r * r * r).collect();
            let with_direction: Vec<(&[f32; 4], f32)> = out
                .iter()
                .zip(r.iter().copied())
                .filter(|(_, r)| *r > 1e-6)
                .collect();
            let depth: Vec<f32> = with_direction
                .iter()
                .map(|(o, r)| 0.5 * (1.0 - o[2] / r))
                .collect();
            let azimuth: Vec<f32> = with_direction
                .iter()
                .map(|(o, _)| o[1].atan2(o[0]).rem_euclid(TAU) / TAU)
                .collect();
            let joint: Vec<(f32, f32)> = with_direction
                .iter()
                .map(|(o, r)| (r * r * r, 0.5 * (1.0 - o[2] / r)))
                .collect();
            let stats = [
                ("radial", ks_uniform(&r3)),
                ("depth", ks_uniform(&depth)),
                ("azimuth", kuiper_uniform(&azimuth)),
                ("radius x depth", ks_uniform_2d(&joint)),
            ];
            eprintln!("{count} samples, patterns {first}..+{patterns}: {stats:.4?}");
            for (name, s) in stats {
                assert!(
                    s <= UNIFORM_TOLERANCE,
                    "{count} samples from pattern {first}: {name} {s}"
                );
            }
            // Half the ball lies behind any plane through its centre (a flat wall: 0.5).
            for n in [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.48, 0.6, 0.64]] {
                let behind = out
                    .iter()
                    .filter(|o| o[0] * n[0] + o[1] * n[1] + o[2] * n[2] > 0.0)
                    .count() as f32
                    / out.len() as f32;
                assert!(
                    (behind - 0.5).abs() <= 0.01,
                    "{count} samples from pattern {first}: {behind} behind the plane {n:?}"
                );
            }
        }
    }
    common::assert_clean(&ctx);
}

/// Points by which a prefix of n patterns may miss a perfectly even spread: van der Corput's
/// n D*_n <= log2(n) / 3 + 1, doubled because the flipped top digit shifts the points by 1/2
/// (an anchored interval becomes at most two).
fn prefix_bound(n: usize) -> f32 {
    2.0 * ((n as f32).log2() / 3.0 + 1.0)
}

#[test]
fn ao_rotations_cover_the_sector_without_repeating() {
    let ctx = common::context();
    let (directions, _) = AoConfig::default().directions_steps();
    let limit = TemporalConfig::default().rotation_limit as usize;
    let run = |first, patterns| {
        probe(
            &ctx,
            ProbePush {
                kind: THESIS_PATTERN,
                count: directions,
                first_pattern: first,
                patterns,
                ..Default::default()
            },
            1,
        )
    };
    let sector = TAU / directions as f32;
    let split = |out: &[[f32; 4]]| -> (Vec<f32>, Vec<f32>) {
        (
            out.iter().map(|o| o[0] / sector).collect(),
            out.iter().map(|o| (o[1] - 0.9) / 0.2).collect(),
        )
    };
    let (rotation, scale) = split(&run(0, MAX_PATTERNS));
    assert!(rotation.iter().all(|r| (0.0..1.0).contains(r)));
    assert!(scale.iter().all(|s| (-1e-6..1.0 + 1e-6).contains(s)));
    // Pattern 0: half a sector, scale 1.
    assert!((rotation[0] - 0.5).abs() < 1e-6 && (scale[0] - 0.5).abs() < 1e-5);
    let mut worst = (0.0f32, 0usize);
    for n in (1..=limit).chain((limit + 1..=MAX_PATTERNS as usize).step_by(61)) {
        for (name, x) in [("rotation", &rotation), ("scale", &scale)] {
            let points = n as f32 * ks_uniform(&x[..n]);
            assert!(
                points <= prefix_bound(n),
                "{name}: the first {n} patterns are {points} points from even"
            );
            if points > worst.0 {
                worst = (points, n);
            }
        }
    }
    eprintln!(
        "largest prefix deviation: {:.2} points at n = {}",
        worst.0, worst.1
    );
    // No rotation repeats within the rotation limit (10 degrees x j with 8 directions
    // revisits 9 angles): the closest two are at least a quarter of an even spacing apart.
    let circular_gap = |a: f32, b: f32| (a - b).abs().min(1.0 - (a - b).abs());
    let mut closest = f32::INFINITY;
    for i in 0..limit {
        for j in 0..i {
            closest = closest.min(circular_gap(rotation[i], rotation[j]));
        }
    }
    eprintln!("closest rotations within the limit: {closest:.4} of a sector");
    assert!(
        closest >= 0.25 / limit as f32,
        "closest rotations {closest}"
    );
    // The reference's patterns cover the sector as evenly, and none is an accumulated one.
    let (reference, _) = split(&run(REFERENCE_PATTERN_BASE, REFERENCE_AO_PATTERNS));
    let n = reference.len();
    assert!(n as f32 * ks_uniform(&reference) <= prefix_bound(n));
    let nearest = reference
        .iter()
        .flat_map(|r| rotation[..limit].iter().map(move |a| circular_gap(*r, *a)))
        .fold(f32::INFINITY, f32::min);
    eprintln!("reference rotations: nearest accumulated one {nearest:.4} of a sector");
    assert!(
        nearest > 1e-3,
        "a reference rotation repeats an accumulated one"
    );
    common::assert_clean(&ctx);
}

#[test]
fn eq8_steps_run_from_near_to_far() {
    let ctx = common::context();
    let (near, far) = (1.5f32, 20.0f32);
    for steps in [2u32, 4] {
        let out = probe(
            &ctx,
            ProbePush {
                kind: EQ8_STEPS,
                count: steps,
                first_pattern: 0,
                patterns: 1,
                near_px: near,
                far_px: far,
            },
            1,
        );
        // S_i = near (far / near)^(i / (m - 1)), i = 0 .. m - 1 (fp32 pow: 1e-5 relative).
        for (i, o) in out.iter().enumerate() {
            let expected = near * (far / near).powf(i as f32 / (steps - 1) as f32);
            assert!(
                (o[0] - expected).abs() <= 1e-5 * expected,
                "{steps} steps, step {i}: {} vs {expected}",
                o[0]
            );
        }
        assert_eq!(out[0][0], near, "the first step is near");
    }
    common::assert_clean(&ctx);
}

/// Eq 6 on the CPU in f64: n's digits in `base` mirrored about the point.
fn radical_inverse(mut n: u32, base: u32) -> f64 {
    let (mut r, mut f) = (0.0, 1.0 / base as f64);
    while n != 0 {
        r += f * (n % base) as f64;
        n /= base;
        f /= base as f64;
    }
    r
}

fn halton_probe(ctx: &Arc<Context>, kind: u32, first: u32, count: u32, rows: u32) -> Vec<[f32; 4]> {
    probe(
        ctx,
        ProbePush {
            kind,
            count: 1,
            first_pattern: first,
            patterns: count,
            near_px: 0.0,
            far_px: 0.0,
        },
        rows,
    )
}

/// Szentandrasi's Halton sampling (issue 13): the shader's radical inverses equal eq 6 for the
/// first 1,000 indices in bases 2, 3 and 5, and eq 8's period holds for the documented period
/// 10 of the direction's bases 2 and 5: |phi_b(i) - phi_b(i + 10 m)| < 1 / b.
#[test]
fn halton_radical_inverses_follow_eq6_and_the_period_of_eq8() {
    let ctx = common::context();
    let n = 1000u32;
    let out = halton_probe(&ctx, RADICAL_INVERSES, 0, n + 50, 1);
    for i in 0..n {
        for (c, base) in [(0, 2u32), (1, 3), (2, 5)] {
            let expected = radical_inverse(i, base);
            let got = out[i as usize][c] as f64;
            // f32 digits accumulated in float: within a few ulps of the definition.
            assert!(
                (got - expected).abs() <= 4.0 * f32::EPSILON as f64 * expected.max(1e-30),
                "phi_{base}({i}) = {got}, eq 6 gives {expected}"
            );
        }
    }
    for i in 0..n as usize {
        for m in 1..=5usize {
            let j = i + 10 * m;
            for (c, base) in [(0, 2.0f32), (2, 5.0)] {
                let d = (out[i][c] - out[j][c]).abs();
                assert!(
                    d < 1.0 / base,
                    "eq 8, base {base}: |phi({i}) - phi({j})| = {d}"
                );
            }
        }
    }
    common::assert_clean(&ctx);
}

/// The hemisphere directions the estimators use are unit vectors on the normal's side,
/// uniform in solid angle (cos theta uniform in [0, 1], the azimuth uniform) over each of 8
/// pixels' first 500 samples (50 periods), whatever the pixel's shift; the steps are uniform
/// in [0, 1).
#[test]
fn halton_hemisphere_is_uniform_in_solid_angle() {
    let ctx = common::context();
    let rows = 8u32;
    let count = 500u32;
    let out = halton_probe(&ctx, HALTON_HEMISPHERE, 0, count, rows);
    for y in 0..rows {
        let a = 0.7 * y as f32;
        let n = glam::Vec3::new(
            a.sin() * (2.3 * a).cos(),
            a.cos(),
            a.sin() * (2.3 * a).sin(),
        )
        .normalize();
        let row = &out[(y * count) as usize..((y + 1) * count) as usize];
        let mut cos_t = Vec::new();
        let mut azimuth = Vec::new();
        let mut steps = Vec::new();
        // A fixed tangent to measure the azimuth from.
        let t = n.any_orthonormal_vector();
        let b = n.cross(t);
        for o in row {
            let w = glam::Vec3::new(o[0], o[1], o[2]);
            assert!(
                (w.length() - 1.0).abs() < 1e-5,
                "row {y}: |omega| = {}",
                w.length()
            );
            let c = w.dot(n);
            assert!(c >= -1e-6, "row {y}: omega below the surface ({c})");
            cos_t.push(c.clamp(0.0, 1.0));
            azimuth.push((w.dot(b).atan2(w.dot(t)) / TAU).rem_euclid(1.0));
            steps.push(o[3]);
            assert!((0.0..1.0).contains(&o[3]), "row {y}: step {}", o[3]);
        }
        let (kc, ka, ks) = (
            ks_uniform(&cos_t),
            kuiper_uniform(&azimuth),
            ks_uniform(&steps),
        );
        eprintln!("row {y}: KS cos theta {kc}, Kuiper azimuth {ka}, KS step {ks}");
        assert!(kc < UNIFORM_TOLERANCE, "row {y}: cos theta KS {kc}");
        assert!(ka < UNIFORM_TOLERANCE, "row {y}: azimuth Kuiper {ka}");
        assert!(ks < UNIFORM_TOLERANCE, "row {y}: step KS {ks}");
    }
    common::assert_clean(&ctx);
}

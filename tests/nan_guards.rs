//! A NaN in one indirect estimate stays where it was planted (`Renderer::plant_nan`, before
//! the guards): CCIPCA's image-wide sums and bases, SVGF's moments and the cached indirect
//! light's history stay finite, and the image outside the pixel's neighbourhood is the image of a run without
//! the NaN. Without the guards one NaN blackens CCIPCA's whole image (its sums are
//! image-wide) and sticks in a history until a restart.

mod common;

use ssgi::config::pcf::Pcf;
use ssgi::config::{Effects, IndirectConfig, IndirectFilter, RenderConfig};
use ssgi::renderer::Renderer;
use ssgi::resources::targets::Target;
use ssgi::scene::cornell_box;
use ssgi::vk::ImageData;

const SIZE: u32 = 48;
/// An even pixel on the back wall: a sample of the half-resolution gather too.
const PLANTED: [u32; 2] = [20, 20];

fn config(filter: IndirectFilter) -> RenderConfig {
    RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 64,
        pcf: Pcf::HARD,
        effects: Effects {
            indirect: true,
            ..Effects::NONE
        },
        indirect: IndirectConfig {
            vpls: 16,
            filter,
            ..Default::default()
        },
        skip_unchanged: false,
        ..Default::default()
    }
}

/// The texels of the RGBA32F indirect target (rgb; a = estimates accumulated, with reuse).
fn texels(image: &ImageData) -> Vec<[f32; 4]> {
    (0..image.height)
        .flat_map(|y| (0..image.width).map(move |x| (x, y)))
        .map(|(x, y)| image.texel(x, y))
        .collect()
}

/// Renders `frames` frames of `c` (planting the NaN before frame `plant`, if given) and returns the
/// indirect light of the last two frames and the renderer.
fn run(c: RenderConfig, frames: u32, plant: Option<u32>) -> (Vec<Vec<[f32; 4]>>, Renderer) {
    let ctx = common::context();
    let mut r = Renderer::new(&ctx, cornell_box(), c).unwrap();
    let camera = r.scene.camera;
    let mut images = Vec::new();
    for frame in 0..frames {
        if plant == Some(frame) {
            r.plant_nan(PLANTED);
        }
        r.render_frame(&camera).unwrap();
        if frame + 2 >= frames {
            images.push(texels(&common::read(&mut r, Target::Indirect)));
        }
    }
    r.finish().unwrap();
    common::assert_clean(&ctx);
    (images, r)
}

/// Chebyshev distance of pixel `i` from the planted pixel.
fn distance(i: usize) -> u32 {
    let (x, y) = ((i as u32) % SIZE, (i as u32) / SIZE);
    x.abs_diff(PLANTED[0]).max(y.abs_diff(PLANTED[1]))
}

/// Largest difference between `a` and `b` outside `radius` of the planted pixel, relative to
/// the largest value of `b`; and whether any value of `a` is not finite.
fn compare(a: &[[f32; 4]], b: &[[f32; 4]], radius: u32) -> (f32, usize) {
    let peak = b
        .iter()
        .flat_map(|t| &t[..3])
        .fold(0.0f32, |m, v| m.max(v.abs()));
    let mut worst = 0.0f32;
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        if distance(i) > radius {
            for k in 0..3 {
                worst = worst.max((p[k] - q[k]).abs() / peak);
            }
        }
    }
    let bad = a.iter().flatten().filter(|v| !v.is_finite()).count();
    (worst, bad)
}

/// CCIPCA: the NaN enters the noisy sample at frame 6 of 8. The guard makes it 0 there, so the
/// image-wide sums and every basis stay finite (before the guard covered the residual and the
/// sums, frame 6 came out black everywhere); outside the basis filter's reach (radius 2) the
/// image moves only by the planted sample's share of the image-wide sums.
#[test]
fn a_nan_sample_stays_out_of_ccipcas_sums_and_bases() {
    let (clean, _) = run(config(IndirectFilter::Ccipca), 8, None);
    let (planted, mut r) = run(config(IndirectFilter::Ccipca), 8, Some(6));
    let bases = r.read_buffer(ssgi::effects::ccipca::ID, "bases").unwrap();
    let bad_bases = bases
        .chunks_exact(4)
        .filter(|b| !f32::from_le_bytes([b[0], b[1], b[2], b[3]]).is_finite())
        .count();
    assert_eq!(bad_bases, 0, "non-finite basis values");
    for (frame, (a, b)) in planted.iter().zip(&clean).enumerate() {
        let (outside, bad) = compare(a, b, 4);
        let (inside, _) = compare(a, b, 0);
        eprintln!(
            "frame {}: largest difference outside the neighbourhood {outside:.2e}, anywhere \
             {inside:.2e} (relative to the peak); {bad} non-finite values",
            6 + frame
        );
        assert_eq!(bad, 0, "frame {}: the NaN reached the image", 6 + frame);
        assert!(outside <= BOUND_CCIPCA, "frame {}: {outside}", 6 + frame);
    }
    // Frame 7's bases hold the planted pixel's zero sample: its neighbourhood moves.
    let (inside, _) = compare(&planted[1], &clean[1], 0);
    assert!(
        inside > 1e-3,
        "the planted NaN changed nothing ({inside}): not planted?"
    );
}

/// The cached indirect light: the NaN replaces one low-resolution sample's estimate at frame
/// 4 of 6 (still accumulating). The merge drops it, so the histories the sample reaches keep
/// their last value and count there (a GPU whose `clamp` maps NaN to 0, as lavapipe's does,
/// would otherwise store a finite but wrong 0 and count it); the image outside the
/// upsampling's reach is exactly the clean run's.
#[test]
fn a_nan_estimate_stays_out_of_the_indirect_history() {
    let (clean, _) = run(config(IndirectFilter::Accumulate), 6, None);
    let (planted, mut r) = run(config(IndirectFilter::Accumulate), 6, Some(4));
    for a in r.audit().unwrap() {
        assert_eq!(a.bad_values(), 0, "{a:?}");
    }
    for (frame, (a, b)) in planted.iter().zip(&clean).enumerate() {
        let (outside, bad) = compare(a, b, 8);
        eprintln!(
            "frame {}: largest difference outside the neighbourhood {outside:.2e}; {bad} \
             non-finite values",
            4 + frame
        );
        assert_eq!(bad, 0, "frame {}: the NaN reached the image", 4 + frame);
        assert_eq!(outside, 0.0, "frame {}", 4 + frame);
    }
    let p = (PLANTED[1] * SIZE + PLANTED[0]) as usize;
    let (got, want) = (planted[0][p][3], clean[0][p][3] - 1.0);
    assert_eq!(
        got, want,
        "estimates at the planted pixel: the NaN was not dropped"
    );
    let held = (0..planted[0].len()).filter(|&i| planted[0][i][3] != clean[0][i][3]);
    assert!(
        held.clone().all(|i| distance(i) <= 8),
        "a count changed far away"
    );
}

/// SVGF: the NaN enters the noisy sample at frame 4 of 6. The gather's guard makes it 0, so
/// the moments, histories and image stay finite, and with one a-trous iteration (radius 2) the
/// image outside the reach of two frames' filtering (4 pixels) is exactly the clean run's.
#[test]
fn a_nan_sample_stays_out_of_svgfs_moments() {
    let mut c = config(IndirectFilter::Svgf);
    c.svgf.iterations = 1;
    let (clean, _) = run(c, 6, None);
    let (planted, mut r) = run(c, 6, Some(4));
    for a in r.audit().unwrap() {
        assert_eq!(a.bad_values(), 0, "{a:?}");
    }
    for (frame, (a, b)) in planted.iter().zip(&clean).enumerate() {
        let (outside, bad) = compare(a, b, 4);
        let (inside, _) = compare(a, b, 0);
        eprintln!(
            "frame {}: largest difference outside the neighbourhood {outside:.2e}, anywhere \
             {inside:.2e}; {bad} non-finite values",
            4 + frame
        );
        assert_eq!(bad, 0, "frame {}: the NaN reached the image", 4 + frame);
        assert_eq!(outside, 0.0, "frame {}", 4 + frame);
        assert!(
            inside > 0.0,
            "frame {}: the planted NaN changed nothing",
            4 + frame
        );
    }
}

/// Largest relative change CCIPCA's image may show outside the planted pixel's neighbourhood:
/// the projection's coefficients are sums over the image's SIZE^2 pixels, of which the planted
/// sample is one (measured: 3.9e-5 and 3.5e-5, a tenth of this).
const BOUND_CCIPCA: f32 = 1.0 / (SIZE * SIZE) as f32;

//! The thesis's 9-sample PCF, rotated and scaled every frame and accumulated with the cache,
//! against a 1024-sample PCF with the same kernel radius and against the 49-sample baseline.

mod common;

use ssgi::config::pcf::{Pcf, PcfKernel};
use ssgi::config::{Effects, RenderConfig, TemporalConfig};
use ssgi::renderer::Renderer;
use ssgi::resources::targets::Target;
use ssgi::scene::Scene;
use ssgi::vk::FrameTiming;

const SIZE: u32 = 128;

/// Top view of the floor left of the tall block, where its shadow falls.
fn shadow_view() -> Scene {
    common::cornell_from_above(-0.5, -0.2, 50.0)
}

fn config(pcf: Pcf, reuse: bool) -> RenderConfig {
    RenderConfig {
        width: SIZE,
        height: SIZE,
        rsm_size: 256,
        pcf,
        effects: Effects {
            direct: true,
            ..Effects::NONE
        },
        ssdo: Default::default(),
        temporal: TemporalConfig {
            reuse,
            ..Default::default()
        },
        // Every frame reads the cache's counters: a converged frame must run, not be skipped
        // (tests/skip.rs covers skipping).
        skip_unchanged: false,
        ..Default::default()
    }
}

/// Shadow visibility of geometry pixels after `frames` static frames, with the frame timings.
fn visibility(
    ctx: &std::sync::Arc<ssgi::vk::Context>,
    c: RenderConfig,
    frames: u32,
) -> (Vec<Option<f32>>, Vec<FrameTiming>) {
    let mut r = Renderer::new(ctx, shadow_view(), c).unwrap();
    let camera = r.scene.camera;
    let mut timings = Vec::new();
    for _ in 0..frames {
        timings.extend(r.render_frame(&camera).unwrap());
    }
    timings.extend(r.finish().unwrap());
    let shadow = r.read(Target::Shadow).unwrap();
    let pos = r.read(Target::GPosition).unwrap();
    let values = (0..SIZE * SIZE)
        .map(|i| {
            let (x, y) = (i % SIZE, i / SIZE);
            (pos.texel(x, y)[3] != 0.0).then(|| shadow.texel(x, y)[0])
        })
        .collect();
    (values, timings)
}

#[test]
fn nine_sample_pcf_with_reuse_converges_to_the_1024_sample_kernel() {
    let ctx = common::context();
    let frames = 36 + 4 + 2; // rotation limit + one refresh cycle (4 tiles) + margin
    let (reused, timings) = visibility(&ctx, config(Pcf::NINE, true), frames);
    let reference_pcf = Pcf {
        kernel: PcfKernel::Disc { samples: 1024 },
        ..Pcf::NINE
    };
    let (reference, _) = visibility(&ctx, config(reference_pcf, false), 1);
    let (single, _) = visibility(&ctx, config(Pcf::NINE, false), 1);
    let (grid49, _) = visibility(&ctx, config(Pcf::DEFAULT, false), 1);

    let pairs = |a: &[Option<f32>], b: &[Option<f32>]| -> Vec<(f32, f32)> {
        a.iter()
            .zip(b)
            .filter_map(|(x, y)| Some(((*x)?, (*y)?)))
            .collect()
    };
    let rmse = |p: &[(f32, f32)]| {
        (p.iter().map(|(a, b)| (a - b) * (a - b)).sum::<f32>() / p.len() as f32).sqrt()
    };
    let converged = rmse(&pairs(&reused, &reference));
    let one_frame = rmse(&pairs(&single, &reference));
    let penumbra = reference
        .iter()
        .flatten()
        .filter(|v| **v > 0.05 && **v < 0.95)
        .count();
    eprintln!("RMSE vs 1024-sample disc: accumulated {converged}, single 9-sample frame {one_frame}; {penumbra} penumbra pixels");
    assert!(
        penumbra > 100,
        "the view must contain shadow edges ({penumbra} penumbra pixels)"
    );
    assert!(
        converged < 0.02,
        "accumulated 9-sample PCF RMSE {converged}"
    );
    assert!(
        converged < 0.5 * one_frame,
        "accumulation must beat one frame: {converged} vs {one_frame}"
    );

    // Edges stay where the 49-sample grid puts them: same side of 1/2 almost everywhere, and
    // where the grid is fully lit or fully dark the accumulated disc agrees.
    let with_grid = pairs(&reused, &grid49);
    let same_side = with_grid
        .iter()
        .filter(|(a, b)| (*a > 0.5) == (*b > 0.5))
        .count();
    assert!(
        same_side as f32 >= 0.99 * with_grid.len() as f32,
        "{same_side} of {} on the same side",
        with_grid.len()
    );
    let full: Vec<&(f32, f32)> = with_grid
        .iter()
        .filter(|(_, g)| *g == 0.0 || *g == 1.0)
        .collect();
    let agree = full.iter().filter(|(a, g)| (a - g).abs() < 0.2).count();
    assert!(
        agree as f32 >= 0.99 * full.len() as f32,
        "{agree} of {} umbra/lit pixels agree",
        full.len()
    );

    // After convergence nothing is recomputed: the camera stood still, so no refresh tile is
    // drawn (docs/techniques.md, "Refresh only where it serves"), and every pixel has its 36
    // patterns.
    for t in &timings[frames as usize - 3..] {
        let c = t
            .counters
            .iter()
            .find(|(n, _)| *n == "shadow_computed_pixels")
            .unwrap()
            .1;
        assert_eq!(
            c, 0,
            "frame {}: shadow pixels computed after convergence",
            t.frame
        );
    }
    common::assert_clean(&ctx);
}

//! Work sized to the work: the compacted half-resolution gather lists each low-resolution
//! sample the upsampling reads exactly once (against the rule evaluated on the CPU from the
//! read-back state), the fix-up and refresh spread each pixel's VPLs over a workgroup and
//! still equal eq 9 evaluated on the CPU, and the work-efficiency counters count what was
//! launched and what worked.

mod common;

use common::rsm::{cpu_gather, v3};
use glam::Vec3;
use ssgi::config::pcf::Pcf;
use ssgi::config::{Effects, IndirectConfig, Refresh, RenderConfig, TemporalConfig};
use ssgi::renderer::Renderer;
use ssgi::resources::targets::Target;
use ssgi::scene::{cornell_box, Camera};
use ssgi::vk::{FrameTiming, ImageData};

const STATE_ACCUMULATING: u32 = 1;
const STATE_NEW: u32 = 2;

fn config(size: u32, indirect: IndirectConfig, temporal: TemporalConfig) -> RenderConfig {
    RenderConfig {
        width: size,
        height: size,
        rsm_size: 32,
        pcf: Pcf::HARD,
        effects: Effects {
            indirect: true,
            ..Effects::NONE
        },
        indirect,
        temporal,
        skip_unchanged: false,
        ..Default::default()
    }
}

fn counter(t: &FrameTiming, name: &str) -> u64 {
    t.counters
        .iter()
        .find(|(n, _)| *n == name)
        .map(|c| c.1)
        .unwrap_or_else(|| panic!("frame {} has no counter {name}: {:?}", t.frame, t.counters))
}

/// The counters of the last frame rendered (read after `finish`).
fn last_frame(r: &mut Renderer, frames: u64) -> FrameTiming {
    let t = r
        .finish()
        .unwrap()
        .into_iter()
        .max_by_key(|t| t.frame)
        .unwrap();
    assert_eq!(t.frame, frames - 1, "the last frame's counters");
    t
}

/// Eight still frames (the rotation limit of 4 converges them), then two that pan: a strip of
/// new pixels and resampled histories beside converged ones. The last frame's counters.
fn converge_then_pan(r: &mut Renderer) -> FrameTiming {
    let base = r.scene.camera;
    let frames = 10u64;
    for i in 0..frames {
        let mut camera: Camera = base;
        if i + 2 >= frames {
            let shift = Vec3::new(0.02 * (i + 3 - frames) as f32, 0.0, 0.0);
            camera.position += shift;
            camera.target += shift;
        }
        r.render_frame(&camera).unwrap();
    }
    last_frame(r, frames)
}

/// The classification's rule on the CPU: a low-resolution sample on geometry with a new or
/// accumulating full-resolution pixel within one pixel of its texel.
fn needed_samples(state: &ImageData, pos: &ImageData) -> u64 {
    let (w, h) = (state.width as i32, state.height as i32);
    let mut n = 0;
    for ly in 0..(h + 1) / 2 {
        for lx in 0..(w + 1) / 2 {
            let (fx, fy) = (2 * lx, 2 * ly);
            if pos.texel(fx as u32, fy as u32)[3] == 0.0 {
                continue;
            }
            let working = (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (fx + dx, fy + dy)));
            let needed = working
                .filter(|&(x, y)| x >= 0 && y >= 0 && x < w && y < h)
                .any(|(x, y)| {
                    let s = state.texel(x as u32, y as u32)[0] as u32;
                    s == STATE_NEW || s == STATE_ACCUMULATING
                });
            n += needed as u64;
        }
    }
    n
}

/// Converge, then turn the camera a little: new pixels at the edges, accumulating ones where
/// the history lost estimates, converged ones elsewhere. The list must hold exactly the
/// samples the CPU rule finds, once each, and the gather launch --vpl-lanes lanes per sample.
#[test]
fn compacted_gather_lists_each_needed_sample_once() {
    let ctx = common::context();
    let ind = IndirectConfig {
        vpls: 64,
        visibility: false,
        half_res: true,
        ..Default::default()
    };
    let temporal = TemporalConfig {
        rotation_limit: 4,
        refresh: Refresh::Off,
        ..Default::default()
    };
    let mut r = Renderer::new(&ctx, cornell_box(), config(96, ind, temporal)).unwrap();
    let t = converge_then_pan(&mut r);
    let state = r.read_state(ssgi::effects::indirect::ID).unwrap();
    let pos = r.read(Target::GPosition).unwrap();
    let expected = needed_samples(&state, &pos);
    let listed = counter(&t, "indirect_lowres_samples");
    let all = (48 * 48) as u64;
    eprintln!("{listed} samples listed, {expected} needed by the CPU rule, of {all}");
    assert!(
        expected > 50 && expected < all / 2,
        "the pan must leave a mix of needed and converged samples: {expected} of {all}"
    );
    assert_eq!(listed, expected, "each needed sample listed once");
    assert_eq!(counter(&t, "indirect_computed_pixels"), expected);
    // --vpl-lanes 16: four samples per 64-lane workgroup, 64 / 16 VPLs per lane.
    assert_eq!(
        counter(&t, "indirect_gather_active_invocations"),
        16 * expected
    );
    assert_eq!(
        counter(&t, "indirect_gather_invocations"),
        expected.div_ceil(4) * 64,
        "16 lanes per listed sample, in workgroups of 64"
    );
    assert_eq!(counter(&t, "indirect_gather_serial_evaluations"), 4);
    drop(r);
    common::assert_clean(&ctx);
}

/// The pixels of one lane's state (AO's or the shadows') that need a new estimate.
fn working_pixels(state: &ImageData) -> u64 {
    let mut n = 0;
    for y in 0..state.height {
        for x in 0..state.width {
            let s = state.texel(x, y)[0] as u32;
            n += (s == STATE_NEW || s == STATE_ACCUMULATING) as u64;
        }
    }
    n
}

/// AO and the cached shadows run over the reprojection's list of single pixels: on a pan
/// after convergence each computes exactly the new and accumulating pixels its state marks,
/// once each, on one lane each, in workgroups of 64.
#[test]
fn pixel_lists_hold_exactly_the_working_pixels() {
    let ctx = common::context();
    let temporal = TemporalConfig {
        rotation_limit: 4,
        refresh: Refresh::Off,
        ..Default::default()
    };
    let c = RenderConfig {
        width: 96,
        height: 96,
        rsm_size: 32,
        pcf: Pcf::NINE,
        effects: Effects {
            direct: true,
            ao: true,
            ..Effects::NONE
        },
        temporal,
        skip_unchanged: false,
        ..Default::default()
    };
    let mut r = Renderer::new(&ctx, cornell_box(), c).unwrap();
    let t = converge_then_pan(&mut r);
    for (id, prefix) in [
        (ssgi::effects::ao::ID, "ssao"),
        (ssgi::effects::direct::ID, "shadow"),
    ] {
        let working = working_pixels(&r.read_state(id).unwrap());
        eprintln!(
            "{prefix}: {working} new or accumulating pixels of {}",
            96 * 96
        );
        assert!(
            working > 100 && working < 96 * 96 / 2,
            "{prefix}: the pan must leave a mix: {working}"
        );
        let get = |name: &str| counter(&t, &format!("{prefix}_{name}"));
        assert_eq!(
            get("computed_pixels"),
            working,
            "{prefix}: every listed pixel once"
        );
        assert_eq!(get("active_invocations"), working, "{prefix}");
        assert_eq!(
            get("invocations"),
            working.div_ceil(64) * 64,
            "{prefix}: one lane each"
        );
    }
    drop(r);
    common::assert_clean(&ctx);
}

/// The fix-up spreads each discarded pixel's 1024 VPLs (every texel of a 32x32 RSM) over 64
/// lanes: its value is still eq 9 summed on the CPU, and its counters say 64 lanes per pixel,
/// 16 VPLs per lane.
#[test]
fn spread_fixup_matches_eq_9_on_the_cpu() {
    let ctx = common::context();
    let ind = IndirectConfig {
        vpls: 0,
        visibility: false,
        half_res: true,
        ..Default::default()
    };
    let temporal = TemporalConfig {
        reuse: false,
        ..Default::default()
    };
    let size = 96;
    let mut r = Renderer::new(&ctx, cornell_box(), config(size, ind, temporal)).unwrap();
    let camera = r.scene.camera;
    r.render_frame(&camera).unwrap();
    let t = last_frame(&mut r, 1);
    let gpu = r.read(Target::Indirect).unwrap();
    let mask = r.read(Target::DiscardMask).unwrap();
    let gpos = r.read(Target::GPosition).unwrap();
    let gnrm = r.read(Target::GNormal).unwrap();
    let rsm = [Target::RsmPosition, Target::RsmNormal, Target::RsmFlux].map(|t| r.read(t).unwrap());
    let light = r.scene.light;
    let mut discarded = 0u64;
    let mut lit = 0;
    for y in 0..size {
        for x in 0..size {
            if gpos.texel(x, y)[3] == 0.0 || mask.texel(x, y)[0] as u32 != 1 {
                continue;
            }
            discarded += 1;
            let rsm = [&rsm[0], &rsm[1], &rsm[2]];
            let cpu = cpu_gather(&light, rsm, v3(gpos.texel(x, y)), v3(gnrm.texel(x, y)));
            let g = v3(gpu.texel(x, y));
            for c in 0..3 {
                // fp32 sums of 1024 terms in two different orders.
                let tolerance = (1e-4 * cpu[c].abs() + 1e-6 * cpu.max_element()).max(1e-7);
                assert!(
                    (g[c] - cpu[c]).abs() <= tolerance,
                    "({x},{y}) channel {c}: GPU {} vs CPU {}",
                    g[c],
                    cpu[c]
                );
            }
            lit += (cpu.max_element() > 0.0) as u32;
        }
    }
    eprintln!("{discarded} fix-up pixels, {lit} lit");
    assert!(
        discarded >= 20 && lit >= 10,
        "{discarded} fix-ups, {lit} lit"
    );
    assert_eq!(counter(&t, "indirect_fixup_pixels"), discarded);
    assert_eq!(counter(&t, "indirect_fixup_invocations"), 64 * discarded);
    assert_eq!(
        counter(&t, "indirect_fixup_active_invocations"),
        64 * discarded
    );
    assert_eq!(counter(&t, "indirect_fixup_serial_evaluations"), 1024 / 64);
    drop(r);
    common::assert_clean(&ctx);
}

/// Pixel `(x, y)`'s value as the half-resolution accumulation makes it from `gather`
/// (indirect_upsample.comp): the bilinear blend of the low-resolution samples (full-resolution
/// texels 2i) that carry weight and lie on the pixel's surface (normals within cos 0.9, within
/// two pixel footprints of its tangent plane); `None` where none does (the refresh leaves such a
/// pixel to the fix-up).
fn upsampled(
    gpos: &ssgi::vk::ImageData,
    gnrm: &ssgi::vk::ImageData,
    camera: &ssgi::scene::Camera,
    (x, y): (u32, u32),
    gather: impl Fn(Vec3, Vec3) -> Vec3,
) -> Option<Vec3> {
    let (p, n) = (v3(gpos.texel(x, y)), v3(gnrm.texel(x, y)));
    let tan_half = (0.5 * camera.vfov_deg.to_radians()).tan();
    let footprint = 2.0 * (p - camera.position).length() * tan_half / gpos.height as f32;
    let low_size = (gpos.width.div_ceil(2), gpos.height.div_ceil(2));
    let w = ((x & 1) as f32 * 0.5, (y & 1) as f32 * 0.5);
    let (mut sum, mut weights) = (Vec3::ZERO, 0.0f32);
    for (ox, oy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let low = (x / 2 + ox, y / 2 + oy);
        let wx = if ox == 1 { w.0 } else { 1.0 - w.0 };
        let wy = if oy == 1 { w.1 } else { 1.0 - w.1 };
        if wx * wy == 0.0 || low.0 >= low_size.0 || low.1 >= low_size.1 {
            continue;
        }
        let q = gpos.texel(2 * low.0, 2 * low.1);
        let nq = v3(gnrm.texel(2 * low.0, 2 * low.1));
        let same = nq.dot(n) >= 0.9 && n.dot(v3(q) - p).abs() <= 2.0 * footprint;
        if q[3] != 0.0 && same {
            sum += wx * wy * gather(v3(q), nq);
            weights += wx * wy;
        }
    }
    (weights > 0.0).then(|| sum / weights)
}

/// A converged still view whose light then moves (`--invalidate off`, so nothing restarts):
/// only the refresh tile is recomputed that frame. Inside it every pixel is eq 9 for the new
/// light on the CPU at the low-resolution samples, upsampled as the half-resolution accumulation
/// upsamples it (the estimator the accumulated pixels hold); a pixel the upsampling discards
/// keeps its value; outside the tile every value is as it was.
#[test]
fn spread_refresh_recomputes_its_tile_as_eq_9() {
    let ctx = common::context();
    let ind = IndirectConfig {
        vpls: 0,
        visibility: false,
        half_res: true,
        ..Default::default()
    };
    let temporal = TemporalConfig {
        rotation_limit: 4,
        refresh: Refresh::Hard,
        // A budget that allows the largest tile (16x16) at 64x64.
        refresh_budget: 1.0,
        invalidate: false,
        ..Default::default()
    };
    let size = 64;
    let mut r = Renderer::new(&ctx, cornell_box(), config(size, ind, temporal)).unwrap();
    let camera = r.scene.camera;
    for _ in 0..8 {
        r.render_frame(&camera).unwrap();
    }
    let before = r.read(Target::Indirect).unwrap();
    let mut light = r.scene.light;
    light.position += Vec3::new(0.15, -0.05, 0.1);
    r.set_light(light);
    r.render_frame(&camera).unwrap();
    let t = last_frame(&mut r, 9);
    let after = r.read(Target::Indirect).unwrap();
    let gpos = r.read(Target::GPosition).unwrap();
    let gnrm = r.read(Target::GNormal).unwrap();
    let rsm = [Target::RsmPosition, Target::RsmNormal, Target::RsmFlux].map(|t| r.read(t).unwrap());
    let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
    let mut changed = 0u64;
    for y in 0..size {
        for x in 0..size {
            if gpos.texel(x, y)[3] == 0.0 || before.texel(x, y) == after.texel(x, y) {
                continue;
            }
            changed += 1;
            (lo, hi) = ((lo.0.min(x), lo.1.min(y)), (hi.0.max(x), hi.1.max(y)));
        }
    }
    assert!(changed > 0, "the light moved: the refresh tile must change");
    let (w, h) = (hi.0 - lo.0 + 1, hi.1 - lo.1 + 1);
    eprintln!("{changed} pixels changed in a {w}x{h} rectangle at {lo:?}");
    assert!(
        w <= 16 && h <= 16,
        "a refresh tile is at most 16x16: {w}x{h}"
    );
    let mut moved = 0;
    for y in lo.1..=hi.1 {
        for x in lo.0..=hi.0 {
            if gpos.texel(x, y)[3] == 0.0 {
                continue;
            }
            let rsm = [&rsm[0], &rsm[1], &rsm[2]];
            let gather = |p: Vec3, n: Vec3| cpu_gather(&light, rsm, p, n);
            let g = v3(after.texel(x, y));
            let old = v3(before.texel(x, y));
            let Some(cpu) = upsampled(&gpos, &gnrm, &camera, (x, y), gather) else {
                assert_eq!(g, old, "({x},{y}): discarded, yet refreshed");
                continue;
            };
            for c in 0..3 {
                let tolerance = (1e-4 * cpu[c].abs() + 1e-6 * cpu.max_element()).max(1e-7);
                assert!(
                    (g[c] - cpu[c]).abs() <= tolerance,
                    "({x},{y}) channel {c}: refreshed {} vs CPU {}",
                    g[c],
                    cpu[c]
                );
            }
            moved += ((old - g).abs().max_element() > 1e-3 * g.max_element()) as u32;
        }
    }
    assert!(
        moved > 10,
        "the move changes the tile's light: {moved} pixels"
    );
    // The 4 patterns of every low-resolution sample on geometry that the tile's pixels are
    // upsampled from: at most a 10x10 window for a 16x16 tile, about a third of its pixels.
    let evaluations = counter(&t, "indirect_refresh_evaluations");
    eprintln!("{evaluations} refresh evaluations (sample, pattern) for {changed} changed pixels");
    assert!(
        evaluations.is_multiple_of(4) && evaluations >= changed && evaluations <= 4 * 10 * 10,
        "{evaluations} refresh evaluations for {changed} changed pixels"
    );
    // 1024 VPLs per pattern: 64 lanes per (sample, pattern) estimate.
    assert_eq!(
        counter(&t, "indirect_refresh_active_invocations"),
        64 * evaluations
    );
    assert_eq!(
        counter(&t, "indirect_refresh_serial_evaluations"),
        1024 / 64
    );
    drop(r);
    common::assert_clean(&ctx);
}

/// Work lists past the device's maxComputeWorkGroupCount[0] continue in y (at Vulkan's least
/// 65,535 that is past 16.8 Mpx of 16x16 blocks, `--aa ssaa16` at 1920x1080). With the limit
/// lowered to 3 groups (`Renderer::limit_list_groups`), every list of a converging then
/// panning view (pixel lists, the indirect light's blocks, its fix-ups and low-resolution
/// samples; SSDO's and GTAO's under motion) is dispatched as 3 x n groups, the spare groups of
/// the last row doing nothing: each effect's image is the one the unlimited dispatch makes.
#[test]
fn lists_past_the_group_limit_continue_in_y() {
    use ssgi::effects::ao::config::{AoConfig, AoEstimator};
    let ctx = common::context();
    let temporal = TemporalConfig {
        rotation_limit: 4,
        ..Default::default()
    };
    let thesis = RenderConfig {
        width: 64,
        height: 64,
        rsm_size: 32,
        pcf: Pcf::NINE,
        effects: Effects::ALL,
        temporal,
        skip_unchanged: false,
        ..Default::default()
    };
    let gtao = RenderConfig {
        ao: AoConfig {
            estimator: AoEstimator::Gtao,
            ..Default::default()
        },
        ..thesis
    };
    let ssdo = RenderConfig {
        effects: Effects {
            ao: false,
            ssdo: true,
            ..Effects::ALL
        },
        ..thesis
    };
    for (name, c) in [("thesis", thesis), ("gtao", gtao), ("ssdo", ssdo)] {
        let mut images = Vec::new();
        for limit in [None, Some(3)] {
            let mut r = Renderer::new(&ctx, cornell_box(), c).unwrap();
            if let Some(groups) = limit {
                r.limit_list_groups(groups);
            }
            let t = converge_then_pan(&mut r);
            let listed = counter(&t, "indirect_computed_pixels");
            assert!(listed > 3 * 64, "{name}: the pan lists {listed} samples");
            let mut got = vec![r.read(Target::Output).unwrap().bytes];
            for target in [Target::Indirect, Target::Shadow] {
                got.push(r.read(target).unwrap().bytes);
            }
            if c.effects.ao {
                got.push(r.read(Target::Ao).unwrap().bytes);
            }
            images.push(got);
            drop(r);
        }
        for (k, (a, b)) in images[0].iter().zip(&images[1]).enumerate() {
            assert!(a == b, "{name}: image {k} differs with 3 groups per row");
        }
    }
    common::assert_clean(&ctx);
}

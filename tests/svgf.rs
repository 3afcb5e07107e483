//! SVGF (`--indirect-filter svgf`): the a-trous passes against the CPU evaluation in
//! src/effects/svgf/model.rs, the variance against the moments it comes from, the temporal
//! moments restarting exactly where a CPU reprojection finds the surface new to the view, and
//! the still lighting's longer running mean (`--svgf-alpha-still`) against its closed form.

mod common;

use common::{counter, CpuReprojection};
use glam::{Vec3, Vec4};
use ssgi::config::pcf::Pcf;
use ssgi::config::{Effects, IndirectConfig, IndirectFilter, RenderConfig};
use ssgi::effects::svgf::config::{SvgfConfig, SvgfHistory};
use ssgi::effects::svgf::model::{filter, Surface};
use ssgi::effects::svgf::{HISTORY_VIEW, INTEGRATED_VIEW};
use ssgi::renderer::Renderer;
use ssgi::resources::targets::Target;
use ssgi::scene::cornell_box;
use ssgi::vk::ImageData;

fn config(size: u32, vpls: u32, svgf: SvgfConfig) -> RenderConfig {
    RenderConfig {
        width: size,
        height: size,
        rsm_size: 64,
        pcf: Pcf::HARD,
        effects: Effects {
            indirect: true,
            ..Effects::NONE
        },
        indirect: IndirectConfig {
            vpls,
            filter: IndirectFilter::Svgf,
            ..Default::default()
        },
        svgf,
        // Every frame takes a new sample (tests/skip.rs covers skipping).
        skip_unchanged: false,
        ..Default::default()
    }
}

fn texels(image: &ImageData) -> Vec<Vec4> {
    (0..image.height)
        .flat_map(|y| (0..image.width).map(move |x| (x, y)))
        .map(|(x, y)| Vec4::from(image.texel(x, y)))
        .collect()
}

fn luminance(v: Vec4) -> f32 {
    v.truncate().dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The output after `frames` still frames equals the CPU's a-trous iterations of the read-back
/// integrated colour and variance, on the read-back G-buffer; where a pixel holds 4 samples
/// or more its variance is its moments' E[l^2] - E[l]^2. Once with the article's parameters
/// after 6 frames, once with others after 2 (the variance then estimated spatially).
#[test]
fn atrous_iterations_match_a_cpu_evaluation() {
    let ctx = common::context();
    let size = 48;
    let other = SvgfConfig {
        iterations: 3,
        sigma_luminance: 1.0,
        sigma_normal: 0.0,
        sigma_depth: 2.0,
        ..SvgfConfig::default()
    };
    for (frames, svgf) in [(6, SvgfConfig::default()), (2, other)] {
        let mut r = Renderer::new(&ctx, cornell_box(), config(size, 4, svgf)).unwrap();
        let camera = r.scene.camera;
        for _ in 0..frames {
            r.render_frame(&camera).unwrap();
        }
        let integrated = texels(&common::read(&mut r, Target::Effect(&INTEGRATED_VIEW)));
        let history = texels(&common::read(&mut r, Target::Effect(&HISTORY_VIEW)));
        let gpu = texels(&common::read(&mut r, Target::Indirect));
        let position = texels(&common::read(&mut r, Target::GPosition));
        let normal: Vec<Vec3> = texels(&common::read(&mut r, Target::GNormal))
            .into_iter()
            .map(|n| n.truncate())
            .collect();
        r.finish().unwrap();
        let surface = Surface::new(size, size, &position, &normal, camera.view_proj(1.0));
        let cpu = filter(&svgf, &surface, &integrated, svgf.iterations);
        let (mut worst, mut largest, mut checked_variance) = (0.0f32, 0.0f32, 0);
        for (i, p) in position.iter().enumerate() {
            if p.w == 0.0 {
                assert_eq!(gpu[i], Vec4::ZERO, "background pixel {i}");
                continue;
            }
            let (got, want) = (gpu[i].truncate(), cpu[i].truncate());
            worst = worst.max((got - want).abs().max_element());
            largest = largest.max(want.max_element());
            let (n, m1, m2) = (history[i].x, history[i].y, history[i].z);
            assert_eq!(n, frames as f32, "pixel {i}: samples in its history");
            let variance = integrated[i].w;
            assert!(
                variance.is_finite() && variance >= 0.0,
                "pixel {i}: {variance}"
            );
            if n >= 4.0 {
                let want = (m2 - m1 * m1).max(0.0);
                assert!(
                    (variance - want).abs() <= 1e-5 * m2 + 1e-30,
                    "pixel {i}: variance {variance}, moments give {want}"
                );
                checked_variance += 1;
            }
        }
        eprintln!(
            "{frames} frames, {} iterations: largest difference {worst:.3e} of {largest:.3e}, \
             {checked_variance} temporal variances checked",
            svgf.iterations
        );
        assert!(
            largest > 0.0 && worst <= 1e-4 * largest,
            "{worst} of {largest}"
        );
        assert!(frames < 4 || checked_variance > 1000, "{checked_variance}");
    }
    common::assert_clean(&ctx);
}

/// After three still frames the camera moves sideways: the pixels whose history restarts (one
/// sample, moments of the new sample alone) are those a CPU reprojection of the two
/// G-buffers finds new to the view (the nearest texel does not hold the surface; with the
/// bilinear tap and its fallback, no texel of the 3x3 block around it), the others hold four
/// samples, and the disocclusion counter counts the restarted pixels exactly. The kept pixels'
/// first moment is the CPU's reading of the still frames' moments (`history_taps`) merged with
/// the new sample. Once for each way of reading the history.
#[test]
fn moments_restart_where_the_surface_is_new_to_the_view() {
    let ctx = common::context();
    let size = 64;
    for mode in [SvgfHistory::Nearest, SvgfHistory::Bilinear] {
        let svgf = SvgfConfig {
            history: mode,
            ..SvgfConfig::default()
        };
        let reach = (mode == SvgfHistory::Bilinear) as i64;
        let mut r = Renderer::new(&ctx, cornell_box(), config(size, 4, svgf)).unwrap();
        let c0 = r.scene.camera;
        let c1 = common::moved_sideways(c0);
        let mut timings = Vec::new();
        for camera in [c0, c0, c0] {
            timings.extend(r.render_frame(&camera).unwrap());
        }
        let still = texels(&common::read(&mut r, Target::Effect(&HISTORY_VIEW)));
        timings.extend(r.render_frame(&c1).unwrap());
        let history = texels(&common::read(&mut r, Target::Effect(&HISTORY_VIEW)));
        let noisy = texels(&common::read(&mut r, Target::IndirectNoisy));
        let pos1 = common::read(&mut r, Target::GPosition);
        let pos0 = common::read(&mut r, Target::GPositionHistory);
        let nrm1 = common::read(&mut r, Target::GNormal);
        let nrm0 = common::read(&mut r, Target::GNormalHistory);
        timings.extend(r.finish().unwrap());
        let last = timings.last().unwrap();
        let counted = counter(last, "svgf_disoccluded_pixels").expect("svgf's counter");
        let cpu = common::cpu_disocclusion([&pos0, &pos1], [&nrm0, &nrm1], (c0, c1), reach);
        let reprojection = CpuReprojection::new([&pos0, &pos1], [&nrm0, &nrm1], (c0, c1));
        let (mut resampled, mut resampled_right, mut fallback) = (0u64, 0u64, 0u64);
        let (mut agree, mut total, mut restarted, mut cpu_new) = (0u64, 0u64, 0u64, 0u64);
        for (i, new) in cpu.iter().enumerate() {
            let Some(new) = *new else {
                assert_eq!(history[i], Vec4::ZERO, "background pixel {i}");
                continue;
            };
            let h = history[i];
            let gpu_new = h.x == 1.0;
            assert!(gpu_new || h.x == 4.0, "pixel {i}: {} samples", h.x);
            if gpu_new {
                // The new sample's moments alone.
                let l = luminance(noisy[i]);
                assert!(
                    (h.y - l).abs() <= 1e-6 * l,
                    "pixel {i}: E[l] {} for {l}",
                    h.y
                );
                assert!(
                    (h.z - l * l).abs() <= 1e-5 * l * l,
                    "pixel {i}: E[l^2] {}",
                    h.z
                );
            }
            let (x, y) = (i as u32 % size, i as u32 / size);
            if let (false, Some((taps, from_block))) =
                (gpu_new, history_taps(&reprojection, x, y, mode))
            {
                // n = 4: the new sample's weight is max(alpha, 1/4) = 1/4.
                let previous: f32 = taps
                    .iter()
                    .map(|&((tx, ty), w)| w * still[(ty * size as i64 + tx) as usize].y)
                    .sum();
                let want = previous + (luminance(noisy[i]) - previous) * 0.25;
                let scale = taps
                    .iter()
                    .map(|&((tx, ty), _)| still[(ty * size as i64 + tx) as usize].y)
                    .fold(luminance(noisy[i]), f32::max);
                resampled += 1;
                resampled_right += ((h.y - want).abs() <= 1e-5 * scale + 1e-30) as u64;
                fallback += from_block as u64;
            }
            restarted += gpu_new as u64;
            cpu_new += new as u64;
            agree += (gpu_new == new) as u64;
            total += 1;
        }
        let fraction = agree as f64 / total as f64;
        eprintln!(
            "{:?}: restarted {restarted} (counter {counted}), CPU new {cpu_new}, agreement {fraction:.5} \
             over {total} pixels; first moment as the CPU resamples it at {resampled_right} of \
             {resampled} kept pixels ({fallback} from the 3x3 fallback)",
            svgf.history
        );
        assert!(
            resampled > total / 2 && resampled_right as f64 >= 0.995 * resampled as f64,
            "resampled moments right at {resampled_right} of {resampled}"
        );
        assert_eq!(
            counted, restarted,
            "the counter counts the restarted pixels"
        );
        assert!(
            cpu_new as f64 > 0.01 * total as f64 && cpu_new < total / 2,
            "the move should disocclude some pixels: {cpu_new} of {total}"
        );
        assert!(fraction >= 0.995, "restarts agree on {fraction}");
    }
    common::assert_clean(&ctx);
}

/// A texel of last frame and its weight.
type Tap = ((i64, i64), f32);

/// svgf_temporal.comp's history taps for pixel (x, y): last frame's texels with their
/// weights, summing to 1. The nearest texel where it holds the surface; with `Bilinear` the
/// bilinear tap around its previous position, renormalised over the texels that hold its
/// surface, and where none does the equal mean of those of the 3x3 block around the nearest
/// (then `true`). None where nothing holds it (the history restarts).
fn history_taps(
    cpu: &CpuReprojection,
    x: u32,
    y: u32,
    history: SvgfHistory,
) -> Option<(Vec<Tap>, bool)> {
    let f = cpu.previous(x, y)??;
    if history == SvgfHistory::Nearest {
        let t = (f.x.floor() as i64, f.y.floor() as i64);
        return cpu.holds((x, y), t).then(|| (vec![(t, 1.0)], false));
    }
    let corner = f - 0.5;
    let base = corner.floor();
    let a = corner - base;
    let (bx, by) = (base.x as i64, base.y as i64);
    let mut taps: Vec<Tap> = [(0, 0), (1, 0), (0, 1), (1, 1)]
        .into_iter()
        .map(|(ox, oy)| {
            let w = if ox == 1 { a.x } else { 1.0 - a.x } * if oy == 1 { a.y } else { 1.0 - a.y };
            ((bx + ox, by + oy), w)
        })
        .filter(|&(t, w)| w > 0.0 && cpu.holds((x, y), t))
        .collect();
    let fallback = taps.is_empty();
    if fallback {
        let (tx, ty) = (f.x.floor() as i64, f.y.floor() as i64);
        taps = (0..9)
            .map(|i| ((tx + i % 3 - 1, ty + i / 3 - 1), 1.0))
            .filter(|&(t, _)| cpu.holds((x, y), t))
            .collect();
    }
    let total: f32 = taps.iter().map(|t| t.1).sum();
    (total > 0.0).then(|| {
        let taps = taps.into_iter().map(|(t, w)| (t, w / total)).collect();
        (taps, fallback)
    })
}

/// With `--skip-unchanged on` and a still view the filter keeps recording until its running
/// means have forgotten their first samples (`SvgfConfig::settle_frames`: 6 for alpha 0.5,
/// and alpha_still as large: the still lighting's weights are the same),
/// then two more frames for both halves of the ping-ponged images; after that frames record
/// nothing and the output stays the last one.
#[test]
fn skipping_waits_until_the_means_settle() {
    let ctx = common::context();
    let svgf = SvgfConfig {
        alpha: 0.5,
        alpha_moments: 0.5,
        alpha_still: 0.5,
        ..SvgfConfig::default()
    };
    assert_eq!(svgf.settle_frames(), 6);
    let mut c = config(32, 4, svgf);
    c.skip_unchanged = true;
    let mut r = Renderer::new(&ctx, cornell_box(), c).unwrap();
    let (timings, outputs) = common::held_frames(&mut r, 14, Target::Indirect);
    let filtered = common::frames_recording(&timings, "svgf_temporal");
    eprintln!("frames that filtered: {filtered:?}");
    assert!(
        filtered.contains(&5) && !filtered.contains(&13),
        "{filtered:?}"
    );
    assert!(filtered.len() < 12, "{filtered:?}");
    assert_eq!(outputs[12], outputs[13], "a skipped frame keeps the output");
    common::assert_clean(&ctx);
}

/// Mean over pixels of the squared change of the integrated luminance between consecutive
/// frames, averaged over `frames` (indices into `series`, each > 0).
fn mean_change(series: &[Vec<f32>], frames: std::ops::Range<usize>) -> f64 {
    let count = frames.len() as f64;
    frames
        .map(|k| {
            let (a, b) = (&series[k - 1], &series[k]);
            a.iter()
                .zip(b)
                .map(|(x, y)| f64::from(x - y).powi(2))
                .sum::<f64>()
                / a.len() as f64
        })
        .sum::<f64>()
        / count
}

/// `--svgf-alpha-still`: once the lighting has held still for alpha's settle time (18 frames at
/// 0.2) the running means take the smaller weight, until the light moves. A still view's
/// samples are independent from frame to frame, so its integrated colour changes per frame by
/// w (x - mean): with 0.05 against 0.2 the mean squared change is w^2 (1 + w / (2 - w))
/// sigma^2, 0.058x as much. Before the switch both runs weigh alike and agree bit for bit;
/// after a light move both take 0.2 again.
#[test]
fn a_still_light_lengthens_the_running_mean() {
    let ctx = common::context();
    let size = 32;
    let (still, moved) = (60, 70);
    let run = |alpha_still: f32| -> Vec<Vec<f32>> {
        let svgf = SvgfConfig {
            iterations: 0,
            alpha_still,
            ..SvgfConfig::default()
        };
        assert_eq!(svgf.lit_settle_frames(), 18);
        let mut r = Renderer::new(&ctx, cornell_box(), config(size, 1, svgf)).unwrap();
        let camera = r.scene.camera;
        let mut series = Vec::new();
        for frame in 0..moved {
            if frame == still {
                let mut light = r.scene.light;
                light.position += Vec3::new(0.05, 0.0, 0.0);
                r.set_light(light);
            }
            r.render_frame(&camera).unwrap();
            let integrated = common::read(&mut r, Target::Effect(&INTEGRATED_VIEW));
            series.push(texels(&integrated).into_iter().map(luminance).collect());
        }
        r.finish().unwrap();
        series
    };
    let longer = run(0.05);
    let article = run(0.2);
    assert_eq!(
        longer[17], article[17],
        "the same weights before the switch"
    );
    let held = mean_change(&longer, 45..still) / mean_change(&article, 45..still);
    let after = mean_change(&longer, still + 2..moved) / mean_change(&article, still + 2..moved);
    eprintln!(
        "mean squared change, alpha_still 0.05 over 0.2: held {held:.3}, \
         after the light moved {after:.3}"
    );
    assert!(held < 0.25, "held: {held}");
    assert!(
        (0.5..2.0).contains(&after),
        "after the light moved: {after}"
    );
    common::assert_clean(&ctx);
}

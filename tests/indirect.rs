//! One-bounce indirect light from the reflective shadow map: the full gather against a CPU
//! evaluation of eq 9, convergence of the sampled gather with reuse, the screen-space
//! visibility test, the half-resolution discard mask, and the work skipped after convergence.

mod common;

use glam::Vec3;
use ssgi::renderer::config::{Effects, IndirectConfig, RenderConfig, TemporalConfig};
use ssgi::renderer::pcf::Pcf;
use ssgi::renderer::targets::Target;
use ssgi::renderer::Renderer;
use ssgi::scene::{cornell_box, Camera, Material, MeshBuilder, Scene, SpotLight};
use ssgi::vk::{Context, FrameTiming, ImageData};
use std::sync::Arc;

fn config(size: u32, rsm: u32, indirect: IndirectConfig, temporal: TemporalConfig) -> RenderConfig {
    RenderConfig {
        width: size,
        height: size,
        rsm_size: rsm,
        pcf: Pcf::HARD,
        effects: Effects {
            direct: false,
            ao: false,
            indirect: true,
        },
        indirect,
        temporal,
        ..Default::default()
    }
}

fn no_reuse() -> TemporalConfig {
    TemporalConfig {
        reuse: false,
        ..Default::default()
    }
}

fn run(
    ctx: &Arc<Context>,
    scene: Scene,
    c: RenderConfig,
    frames: u32,
) -> (Renderer, Vec<FrameTiming>) {
    let mut r = Renderer::new(ctx, scene, c).unwrap();
    let camera = r.scene.camera;
    let mut timings = Vec::new();
    for _ in 0..frames {
        timings.extend(r.render_frame(&camera).unwrap());
    }
    timings.extend(r.finish().unwrap());
    (r, timings)
}

fn v3(t: [f32; 4]) -> Vec3 {
    Vec3::new(t[0], t[1], t[2])
}

/// Eq 9 summed over every RSM texel on the CPU, with the shader's texel-size distance floor.
fn cpu_gather(light: &SpotLight, rsm: [&ImageData; 3], p: Vec3, n: Vec3) -> Vec3 {
    let [pos, nrm, flux] = rsm;
    let size = pos.width;
    let tan_half = (0.5 * light.frustum_fov_deg()).to_radians().tan();
    let axis = light.direction.normalize();
    let mut sum = Vec3::ZERO;
    for y in 0..size {
        for x in 0..size {
            let q = pos.texel(x, y);
            if q[3] == 0.0 {
                continue;
            }
            let q = v3(q);
            let d = q - p;
            let d2 = d.length_squared();
            if d2 <= 0.0 {
                continue;
            }
            let depth = (q - light.position).dot(axis).max(0.0);
            let texel = 2.0 * depth * tan_half / size as f32;
            let dir = d / d2.sqrt();
            let nq = v3(nrm.texel(x, y));
            sum += v3(flux.texel(x, y)) * n.dot(dir).max(0.0) * nq.dot(-dir).max(0.0)
                / d2.max(texel * texel);
        }
    }
    sum
}

#[test]
fn full_gather_matches_eq_9_on_the_cpu() {
    let ctx = common::context();
    let ind = IndirectConfig {
        vpls: 0,
        visibility: false,
        half_res: false,
    };
    let (mut r, _) = run(&ctx, cornell_box(), config(64, 32, ind, no_reuse()), 1);
    let gpu = r.read(Target::Indirect).unwrap();
    let gpos = r.read(Target::GPosition).unwrap();
    let gnrm = r.read(Target::GNormal).unwrap();
    let rsm = [Target::RsmPosition, Target::RsmNormal, Target::RsmFlux].map(|t| r.read(t).unwrap());
    let light = r.scene.light;
    let mut checked = 0;
    let mut lit = 0;
    for y in (2..64).step_by(6) {
        for x in (2..64).step_by(6) {
            let p = gpos.texel(x, y);
            if p[3] == 0.0 {
                continue;
            }
            let cpu = cpu_gather(
                &light,
                [&rsm[0], &rsm[1], &rsm[2]],
                v3(p),
                v3(gnrm.texel(x, y)),
            );
            let g = v3(gpu.texel(x, y));
            for c in 0..3 {
                let tolerance = 1e-3 * cpu[c].abs() + 1e-6 * cpu.max_element();
                assert!(
                    (g[c] - cpu[c]).abs() <= tolerance.max(1e-7),
                    "({x},{y}) channel {c}: GPU {} vs CPU {}",
                    g[c],
                    cpu[c]
                );
            }
            lit += (cpu.max_element() > 0.0) as u32;
            checked += 1;
        }
    }
    assert!(
        checked >= 60 && lit >= 40,
        "checked {checked} pixels, {lit} with indirect light"
    );
    drop(r);
    common::assert_clean(&ctx);
}

fn relative_rmse(a: &ImageData, b: &ImageData, mask: &ImageData) -> f32 {
    let (mut se, mut sum, mut n) = (0.0f64, 0.0f64, 0u32);
    for y in 0..a.height {
        for x in 0..a.width {
            if mask.texel(x, y)[3] == 0.0 {
                continue;
            }
            let (p, q) = (v3(a.texel(x, y)), v3(b.texel(x, y)));
            se += (p - q).length_squared() as f64 / 3.0;
            sum += (q.x + q.y + q.z) as f64 / 3.0;
            n += 1;
        }
    }
    ((se / n as f64).sqrt() / (sum / n as f64)) as f32
}

#[test]
fn sampled_gather_with_reuse_converges_to_the_full_gather() {
    let ctx = common::context();
    let size = 64;
    let sampled = IndirectConfig::default(); // 512 VPLs, half resolution
    let full = IndirectConfig { vpls: 0, ..sampled };
    // Rotation limit (36 patterns) plus one refresh cycle of the 16 tiles at 64x64.
    let (mut r, timings) = run(
        &ctx,
        cornell_box(),
        config(size, 64, sampled, TemporalConfig::default()),
        36 + 16 + 2,
    );
    let accumulated = r.read(Target::Indirect).unwrap();
    let mask = r.read(Target::GPosition).unwrap();
    let (mut one, _) = run(
        &ctx,
        cornell_box(),
        config(size, 64, sampled, no_reuse()),
        1,
    );
    let single = one.read(Target::Indirect).unwrap();
    let (mut reference, _) = run(&ctx, cornell_box(), config(size, 64, full, no_reuse()), 1);
    let reference = reference.read(Target::Indirect).unwrap();
    let converged = relative_rmse(&accumulated, &reference, &mask);
    let one_frame = relative_rmse(&single, &reference, &mask);
    eprintln!("relative RMSE vs full gather: accumulated {converged}, one frame {one_frame}");
    assert!(
        converged < 0.02,
        "accumulated 512-VPL gather: relative RMSE {converged}"
    );
    assert!(
        converged < 0.5 * one_frame,
        "accumulation must beat one frame ({one_frame})"
    );

    // Skipping after convergence: the RSM is not re-rendered and only the refresh tile (16x16
    // pixels: 10x10 low-resolution gathers with the apron) is recomputed.
    for t in &timings[timings.len() - 3..] {
        let get = |name: &str| {
            t.counters
                .iter()
                .find(|(n, _)| *n == name)
                .map(|c| c.1)
                .unwrap()
        };
        assert!(
            get("indirect_computed_pixels") <= 16 * 16,
            "frame {}: {:?}",
            t.frame,
            t.counters
        );
        assert!(
            get("indirect_fixup_pixels") <= 16 * 16,
            "frame {}: {:?}",
            t.frame,
            t.counters
        );
        assert!(
            t.skipped.contains(&"light_view"),
            "frame {} re-rendered the RSM",
            t.frame
        );
    }
    drop((r, one));
    common::assert_clean(&ctx);
}

/// The thesis's Figure 3.15 case: a lit wall E, a tall wall B that the light does not see,
/// and a floor R behind B. Without the visibility test E's VPLs light R through B.
fn wall_scene() -> Scene {
    let mut b = MeshBuilder::new();
    let white = b.add_material(Material::colour("white", [0.8, 0.8, 0.8]));
    let v = Vec3::new;
    // Floor.
    b.add_flat_polygon(
        white,
        &[
            v(-2.0, 0.0, -1.5),
            v(-2.0, 0.0, 1.5),
            v(2.0, 0.0, 1.5),
            v(2.0, 0.0, -1.5),
        ],
        Vec3::Y,
    );
    // E: lit wall facing +x.
    b.add_flat_polygon(
        white,
        &[
            v(-1.5, 0.0, -1.0),
            v(-1.5, 2.0, -1.0),
            v(-1.5, 2.0, 1.0),
            v(-1.5, 0.0, 1.0),
        ],
        Vec3::X,
    );
    // B: blocking wall at x = 0, taller than E.
    b.add_flat_polygon(
        white,
        &[
            v(0.0, 0.0, -1.5),
            v(0.0, 0.0, 1.5),
            v(0.0, 2.2, 1.5),
            v(0.0, 2.2, -1.5),
        ],
        Vec3::X,
    );
    let mut scene = cornell_box();
    scene.name = "wall".into();
    scene.mesh = b.build();
    scene.camera = Camera::new(v(2.2, 3.0, 3.2), v(-0.3, 0.4, 0.0), 50.0, 0.05, 30.0);
    scene.light = SpotLight {
        position: v(-0.4, 1.0, 0.0),
        direction: v(-1.0, 0.0, 0.0),
        intensity: Vec3::splat(4.0),
        inner_deg: 30.0,
        outer_deg: 40.0,
        near: 0.05,
        far: 10.0,
    };
    scene
}

#[test]
fn visibility_test_removes_light_through_a_wall() {
    let ctx = common::context();
    let mut totals = Vec::new();
    for visibility in [false, true] {
        let ind = IndirectConfig {
            vpls: 512,
            visibility,
            half_res: false,
        };
        let (mut r, _) = run(&ctx, wall_scene(), config(96, 64, ind, no_reuse()), 1);
        let pos = r.read(Target::GPosition).unwrap();
        let ind_img = r.read(Target::Indirect).unwrap();
        let scene = &r.scene;
        let (mut sum, mut n) = (0.0f64, 0);
        for y in 0..96 {
            for x in 0..96 {
                let p = pos.texel(x, y);
                // Receiver: the floor behind B, every point of it hidden from E (checked on
                // the CPU against E's corners and centre).
                if p[3] == 0.0 || p[1].abs() > 1e-3 || p[0] < 0.3 || p[2].abs() > 0.9 {
                    continue;
                }
                let q = v3(p) + Vec3::Y * 1e-3;
                let hidden = [
                    (-1.5, 0.05, -0.95),
                    (-1.5, 1.95, -0.95),
                    (-1.5, 1.95, 0.95),
                    (-1.5, 0.05, 0.95),
                    (-1.5, 1.0, 0.0),
                ]
                .iter()
                .all(|&(a, b, c)| scene.mesh.occluded(q, Vec3::new(a + 1e-3, b, c)));
                assert!(hidden, "receiver point {q} sees E");
                sum += ind_img.texel(x, y)[0] as f64;
                n += 1;
            }
        }
        assert!(n > 200, "only {n} receiver pixels visible");
        totals.push(sum);
        drop(r);
    }
    eprintln!(
        "receiver indirect: without test {}, with test {}",
        totals[0], totals[1]
    );
    assert!(
        totals[0] > 0.0,
        "without the test the VPLs light the receiver through the wall"
    );
    assert!(
        totals[1] <= 0.1 * totals[0],
        "with the test: {} of {}",
        totals[1],
        totals[0]
    );
    common::assert_clean(&ctx);
}

/// The half-resolution discard mask equals the acceptance rule applied on the CPU to the
/// read-back G-buffer (normals within ~25 degrees, tangent-plane distance within two
/// footprints, for the four low-resolution neighbours).
#[test]
fn discard_mask_matches_the_cpu_rule() {
    let ctx = common::context();
    let size = 96u32;
    let ind = IndirectConfig {
        vpls: 16,
        visibility: false,
        half_res: true,
    };
    let (mut r, _) = run(&ctx, cornell_box(), config(size, 32, ind, no_reuse()), 1);
    let pos = r.read(Target::GPosition).unwrap();
    let nrm = r.read(Target::GNormal).unwrap();
    let mask = r.read(Target::DiscardMask).unwrap();
    let cam = r.scene.camera;
    let tan_half = (0.5 * cam.vfov_deg).to_radians().tan();
    let low = size.div_ceil(2) as i32;
    let (mut agree, mut total, mut discarded) = (0, 0, 0);
    for y in 0..size {
        for x in 0..size {
            let p = pos.texel(x, y);
            if p[3] == 0.0 {
                continue;
            }
            let (pv, n) = (v3(p), v3(nrm.texel(x, y)));
            let footprint = 2.0 * pv.distance(cam.position) * tan_half / size as f32;
            let fx = (x as f32 + 0.5) * 0.5 - 0.5;
            let fy = (y as f32 + 0.5) * 0.5 - 0.5;
            let (bx, by) = (fx.floor() as i32, fy.floor() as i32);
            let accepted = (0..4).any(|k| {
                let (lx, ly) = (bx + (k & 1), by + (k >> 1));
                if lx < 0 || ly < 0 || lx >= low || ly >= low {
                    return false;
                }
                let g = pos.texel(2 * lx as u32, 2 * ly as u32);
                g[3] != 0.0
                    && v3(nrm.texel(2 * lx as u32, 2 * ly as u32)).dot(n) >= 0.9
                    && n.dot(v3(g) - pv).abs() <= 2.0 * footprint
            });
            let gpu = mask.texel(x, y)[0] as u32 == 1;
            agree += (gpu != accepted) as u32;
            discarded += (!accepted) as u32;
            total += 1;
        }
    }
    let fraction = agree as f64 / total as f64;
    eprintln!("discard mask agreement {fraction:.5}; {discarded} of {total} discarded on the CPU");
    assert!(
        discarded > 0,
        "the Cornell box's edges must discard some pixels"
    );
    assert!(fraction >= 0.999, "mask agrees on {fraction}");
    drop(r);
    common::assert_clean(&ctx);
}

//! SSDO (issue 13): an open plane is neither darkened nor lit by a bounce, a floor beside the
//! Cornell box's red wall receives a red bounce, the GPU's one-step result equals a CPU
//! evaluation of eqs 2 and 4 with the same Halton samples on the read-back G-buffer, both forms
//! agree where they should, the bilateral filter smooths a plane without bleeding across a depth
//! edge, and half resolution with joint bilateral upsampling follows full resolution without
//! bleeding either.

mod common;

use glam::{Mat4, Vec2, Vec3, Vec4};
use ssgi::config::pcf::Pcf;
use ssgi::config::{Effects, RenderConfig, TemporalConfig};
use ssgi::effects::ssdo;
use ssgi::effects::ssdo::config::{AdaptiveSamples, SsdoConfig, SsdoForm};
use ssgi::renderer::Renderer;
use ssgi::resources::targets::Target;
use ssgi::scene::{cornell_box, Camera, Material, MeshBuilder, Scene, SpotLight};
use ssgi::vk::ImageData;
use std::sync::Arc;

fn config(size: u32, ssdo: SsdoConfig) -> RenderConfig {
    RenderConfig {
        width: size,
        height: size,
        rsm_size: 256,
        pcf: Pcf::HARD,
        effects: Effects {
            direct: true,
            ssdo: true,
            ..Effects::NONE
        },
        ssdo,
        temporal: TemporalConfig {
            reuse: false,
            ..Default::default()
        },
        ..Default::default()
    }
}

fn render(ctx: &Arc<ssgi::vk::Context>, scene: Scene, c: RenderConfig) -> Renderer {
    render_counted(ctx, scene, c).0
}

/// One frame, and the GPU counters it reported.
fn render_counted(
    ctx: &Arc<ssgi::vk::Context>,
    scene: Scene,
    c: RenderConfig,
) -> (Renderer, Vec<(&'static str, u64)>) {
    let mut r = Renderer::new(ctx, scene, c).expect("renderer");
    let camera = r.scene.camera;
    r.render_frame(&camera).unwrap();
    let timings = r.finish().unwrap();
    let counters = timings.last().expect("a frame's timing").counters.clone();
    (r, counters)
}

/// Every geometry pixel's SSDO texel (bounce rgb, modulation a).
fn ssdo_texels(r: &mut Renderer) -> Vec<Option<[f32; 4]>> {
    let s = r.read(Target::Effect(&ssdo::BOUNCE_VIEW)).unwrap();
    let pos = r.read(Target::GPosition).unwrap();
    (0..s.width * s.height)
        .map(|i| {
            let (x, y) = (i % s.width, i / s.width);
            (pos.texel(x, y)[3] != 0.0).then(|| s.texel(x, y))
        })
        .collect()
}

#[test]
fn open_plane_is_unmodulated_and_receives_no_bounce() {
    let ctx = common::context();
    for form in [SsdoForm::OneStep, SsdoForm::TwoStep] {
        for filter in [0, 11] {
            let ssdo = SsdoConfig {
                form,
                filter,
                radius: 0.01, // 2.8 m on the 283 m plane
                ..Default::default()
            };
            let mut r = render(&ctx, common::open_plane(), config(64, ssdo));
            let texels: Vec<[f32; 4]> = ssdo_texels(&mut r).into_iter().flatten().collect();
            assert!(texels.len() > 1000, "{form:?}: the plane fills the view");
            for t in &texels {
                assert!(
                    (t[3] - 1.0).abs() <= 1e-3,
                    "{form:?}, filter {filter}: modulation {}",
                    t[3]
                );
                assert!(
                    t[0] == 0.0 && t[1] == 0.0 && t[2] == 0.0,
                    "{form:?}, filter {filter}: bounce {t:?}"
                );
            }
        }
    }
    common::assert_clean(&ctx);
}

fn project(view_proj: Mat4, p: Vec3, size: u32) -> (u32, u32) {
    let c = view_proj * p.extend(1.0);
    let ndc = c.truncate() / c.w;
    (
        ((ndc.x * 0.5 + 0.5) * size as f32) as u32,
        ((ndc.y * 0.5 + 0.5) * size as f32) as u32,
    )
}

#[test]
fn floor_beside_the_red_wall_receives_a_red_bounce() {
    let ctx = common::context();
    let size = 96;
    let ssdo = SsdoConfig {
        samples: 50,
        ..Default::default()
    };
    let mut r = render(&ctx, cornell_box(), config(size, ssdo));
    let s = r.read(Target::Effect(&ssdo::BOUNCE_VIEW)).unwrap();
    let vp = r.scene.camera.view_proj(1.0);
    // The floor 5 cm from the red (left, x = -1) wall, and the middle of the floor.
    let mean = |centre: Vec3| -> Vec3 {
        let (cx, cy) = project(vp, centre, size);
        let mut sum = Vec3::ZERO;
        for y in cy - 1..=cy + 1 {
            for x in cx - 1..=cx + 1 {
                let t = s.texel(x, y);
                sum += Vec3::new(t[0], t[1], t[2]);
            }
        }
        sum / 9.0
    };
    let by_wall = mean(Vec3::new(-0.95, 0.0, 0.2));
    eprintln!("bounce on the floor beside the red wall {by_wall}");
    assert!(by_wall.x > 0.0, "no bounce beside the red wall");
    assert!(
        by_wall.x > 2.0 * by_wall.y && by_wall.x > 2.0 * by_wall.z,
        "the bounce beside the red wall is not red: {by_wall}"
    );
    common::assert_clean(&ctx);
}

// ---- the CPU evaluation of eqs 2 and 4, with the shaders' Halton samples ----

fn fract(x: f32) -> f32 {
    x - x.floor()
}

/// shaders/include/patterns.glsl's interleaved gradient noise.
fn ign(x: i32, y: i32) -> f32 {
    fract(52.982_92 * fract(x as f32 * 0.067_110_56 + y as f32 * 0.005_837_15))
}

/// shaders/include/halton.glsl, line by line.
fn radical_inverse(mut n: u32, base: u32) -> f32 {
    let inv = 1.0 / base as f32;
    let (mut f, mut r) = (inv, 0.0f32);
    while n != 0 {
        r += f * (n % base) as f32;
        n /= base;
        f *= inv;
    }
    r
}

fn basis_around(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let c = n.x * n.y * a;
    (
        Vec3::new(1.0 + s * n.x * n.x * a, s * c, -s * n.x),
        Vec3::new(c, s + n.y * n.y * a, -n.y),
    )
}

/// Sample i of pixel (x, y): the unit direction and the step r.
fn hemisphere_sample(i: u32, x: i32, y: i32, n: Vec3, r_max: f32) -> (Vec3, f32) {
    let shift = Vec2::new(ign(x, y), ign(y + 37, x + 11));
    let u = Vec2::new(
        fract(radical_inverse(i, 2) + shift.x),
        fract(radical_inverse(i, 5) + shift.y),
    );
    let cos_t = u.x;
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * u.y;
    let (t, b) = basis_around(n);
    let omega = sin_t * (phi.cos() * t + phi.sin() * b) + cos_t * n;
    let golden = 0x8000_0000u32.wrapping_add(i.wrapping_mul(0x9E37_79B9));
    let unorm = (golden >> 8) as f32 / 16_777_216.0;
    (omega, r_max * fract(unorm + fract(shift.x + shift.y)))
}

struct Buffers {
    position: ImageData,
    normal: ImageData,
    albedo: ImageData,
    direct: ImageData,
}

impl Buffers {
    /// The G-buffer and direct light of the frame `r` last rendered.
    fn read(r: &mut Renderer) -> Self {
        Self {
            position: r.read(Target::GPosition).unwrap(),
            normal: r.read(Target::GNormal).unwrap(),
            albedo: r.read(Target::GAlbedo).unwrap(),
            direct: r.read(Target::Direct).unwrap(),
        }
    }
}

fn v3(t: [f32; 4]) -> Vec3 {
    Vec3::new(t[0], t[1], t[2])
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// What the GPU computes for pixel (x, y) in one step (bounce x modulation, modulation), and
/// with `--ssdo ssao` (the unoccluded fraction of the same samples), or None when a sample sits within a hair of a decision (a pixel edge or the occlusion test's
/// thresholds), where fp32 rounding on the two sides may decide differently.
fn cpu_ssdo(
    b: &Buffers,
    scene: &Scene,
    vp: Mat4,
    (x, y): (u32, u32),
    samples: u32,
    r_max: f32,
) -> Option<(Vec4, f32)> {
    let size = b.position.width;
    let p4 = b.position.texel(x, y);
    if p4[3] == 0.0 {
        return None;
    }
    let (p, n) = (v3(p4), v3(b.normal.texel(x, y)));
    let light = &scene.light;
    let area = std::f32::consts::PI * r_max * r_max / samples as f32;
    let d2_floor = area / std::f32::consts::TAU;
    let (mut lit, mut unoccluded, mut bounce) = (0.0f32, 0.0f32, Vec3::ZERO);
    let mut free = 0u32;
    for i in 0..samples {
        let (omega, r) = hemisphere_sample(i, x as i32, y as i32, n, r_max);
        let s = p + r * omega;
        // L_in: ambient plus the spot over its cosine-power lobe (shaders/ssdo/ssdo.glsl).
        let to_light = light.position - p;
        let dist2 = to_light.length_squared().max(light.min_distance_sq());
        let l = to_light.normalize();
        let e = luminance(light.intensity) * light.spot_factor(-l) / dist2;
        let lobe = 9.0 / std::f32::consts::TAU * omega.dot(l).max(0.0).powf(8.0);
        let weight = (luminance(scene.ambient) + e * lobe) * n.dot(omega).max(0.0);
        unoccluded += weight;
        let clip = vp * s.extend(1.0);
        let mut occluded = None;
        if clip.w > 0.0 {
            let px = (clip.x / clip.w * 0.5 + 0.5) * size as f32;
            let py = (clip.y / clip.w * 0.5 + 0.5) * size as f32;
            // 0.01 px: the pixel shift's fp32 rounding (an FMA here or there) moves a sample
            // by about 1e-3 px at this size.
            if (px - px.round()).abs() < 0.01 || (py - py.round()).abs() < 0.01 {
                return None;
            }
            let (qx, qy) = (px.floor(), py.floor());
            if qx >= 0.0 && qy >= 0.0 && qx < size as f32 && qy < size as f32 {
                let (qx, qy) = (qx as u32, qy as u32);
                let q4 = b.position.texel(qx, qy);
                if q4[3] != 0.0 {
                    let (q, qn) = (v3(q4), v3(b.normal.texel(qx, qy)));
                    let height = (s - q).dot(qn);
                    let gap = clip.w - (vp * q.extend(1.0)).w;
                    let near_threshold = (height + 1e-4 * clip.w).abs() < 1e-4 * clip.w;
                    if near_threshold || (gap - r_max).abs() < 1e-3 * r_max {
                        return None;
                    }
                    if height < -1e-4 * clip.w && gap < r_max {
                        occluded = Some((q, qn, qx, qy));
                    }
                }
            }
        }
        let Some((q, qn, qx, qy)) = occluded else {
            lit += weight;
            free += 1;
            continue;
        };
        let to_receiver = p - q;
        let d2 = to_receiver.length_squared();
        let dir = to_receiver.normalize();
        let (cos_s, cos_r) = (qn.dot(dir), n.dot(-dir));
        if cos_s <= 0.0 || cos_r <= 0.0 {
            continue;
        }
        let sender = scene.ambient * v3(b.albedo.texel(qx, qy)) + v3(b.direct.texel(qx, qy));
        bounce += sender * (area * cos_s * cos_r / d2.max(d2_floor));
    }
    let m = if unoccluded > 0.0 {
        lit / unoccluded
    } else {
        1.0
    };
    Some(((bounce * m).extend(m), free as f32 / samples as f32))
}

#[test]
fn one_step_equals_a_cpu_evaluation_of_eqs_2_and_4() {
    let ctx = common::context();
    let size = 96u32;
    let samples = 20;
    let ssdo = SsdoConfig {
        samples,
        filter: 0,
        ..Default::default()
    };
    let mut r = render(&ctx, cornell_box(), config(size, ssdo));
    let b = Buffers::read(&mut r);
    let gpu = r.read(Target::Effect(&ssdo::BOUNCE_VIEW)).unwrap();
    let vp = r.scene.camera.view_proj(1.0);
    let r_max = ssdo.radius * r.scene.mesh.bounds.radius();
    let mut checked = 0;
    let mut with_bounce = 0;
    for y in (4..size - 4).step_by(7) {
        for x in (4..size - 4).step_by(7) {
            let Some((cpu, _)) = cpu_ssdo(&b, &r.scene, vp, (x, y), samples, r_max) else {
                continue;
            };
            let g = Vec4::from(gpu.texel(x, y));
            // The GPU result is stored in fp16 (2^-11 relative), the CPU's in f32.
            let scale = cpu.truncate().max_element().max(1e-6);
            let bounce_err = (g.truncate() - cpu.truncate()).abs().max_element() / scale;
            assert!(
                bounce_err <= 1e-3 || (g.truncate() - cpu.truncate()).abs().max_element() < 1e-6,
                "pixel ({x}, {y}): GPU bounce {g}, CPU {cpu}"
            );
            assert!(
                (g.w - cpu.w).abs() <= 1e-3 * cpu.w.max(1e-3),
                "pixel ({x}, {y}): GPU modulation {}, CPU {}",
                g.w,
                cpu.w
            );
            checked += 1;
            with_bounce += usize::from(cpu.truncate().max_element() > 0.0);
        }
    }
    eprintln!("{checked} pixels checked, {with_bounce} with a bounce");
    assert!(
        checked >= 40 && with_bounce >= 10,
        "{checked} / {with_bounce}"
    );
    common::assert_clean(&ctx);
}

/// `--ssdo ssao` (section 3.1 on SSDO's pipeline): every channel holds the unoccluded fraction
/// of the same Halton samples, equal to a CPU evaluation on the read-back G-buffer; there is no
/// bounce target, and the result is the frame's AO.
#[test]
fn ssao_form_equals_a_cpu_evaluation_of_section_3_1() {
    let ctx = common::context();
    let size = 96u32;
    let samples = 20;
    let ssdo = SsdoConfig {
        form: SsdoForm::Ssao,
        samples,
        filter: 0,
        ..Default::default()
    };
    let mut r = render(&ctx, cornell_box(), config(size, ssdo));
    let b = Buffers::read(&mut r);
    let gpu = r.read(Target::Ao).unwrap();
    assert!(
        r.read(Target::Effect(&ssdo::BOUNCE_VIEW)).is_err(),
        "SSAO has no bounce"
    );
    let vp = r.scene.camera.view_proj(1.0);
    let r_max = ssdo.radius * r.scene.mesh.bounds.radius();
    let (mut checked, mut occluded) = (0, 0);
    for y in (4..size - 4).step_by(5) {
        for x in (4..size - 4).step_by(5) {
            let Some((_, cpu)) = cpu_ssdo(&b, &r.scene, vp, (x, y), samples, r_max) else {
                continue;
            };
            let g = gpu.texel(x, y);
            for c in g {
                assert!(
                    (c - cpu).abs() <= 1e-3,
                    "pixel ({x}, {y}): GPU {g:?}, CPU {cpu}"
                );
            }
            checked += 1;
            occluded += usize::from(cpu < 1.0);
        }
    }
    eprintln!("{checked} pixels checked, {occluded} occluded");
    assert!(checked >= 100 && occluded >= 20, "{checked} / {occluded}");
    common::assert_clean(&ctx);
}

/// The two forms see the same samples: their modulation factors agree (to fp16), and the
/// two-step bounce (from senders darkened by their own modulation, not darkened at the
/// receiver) differs from the one-step one where occlusion is strong.
#[test]
fn both_forms_share_the_modulation_factor() {
    let ctx = common::context();
    let run = |form| {
        let ssdo = SsdoConfig {
            form,
            filter: 0,
            ..Default::default()
        };
        let mut r = render(&ctx, cornell_box(), config(64, ssdo));
        ssdo_texels(&mut r)
    };
    let one = run(SsdoForm::OneStep);
    let two = run(SsdoForm::TwoStep);
    let mut differ = 0;
    for (a, b) in one.iter().zip(&two) {
        let (Some(a), Some(b)) = (a, b) else {
            assert_eq!(a.is_some(), b.is_some());
            continue;
        };
        assert!(
            (a[3] - b[3]).abs() <= 1e-3,
            "modulation {} vs {}",
            a[3],
            b[3]
        );
        differ += usize::from(a[..3] != b[..3]);
    }
    assert!(differ > 0, "the two forms' bounces are identical");
    common::assert_clean(&ctx);
}

/// Two parallel walls 0.5 m apart, the near one over x >= 0, seen head-on: the far wall's
/// pixels beside the edge are occluded by the near wall, the near wall's are not.
fn stepped_walls() -> Scene {
    let mut b = MeshBuilder::new();
    let m = b.add_material(Material::colour("wall", [0.7, 0.7, 0.7]));
    let h = 10.0;
    for (x0, z) in [(-h, 0.0), (0.0, 0.5)] {
        b.add_flat_polygon(
            m,
            &[
                Vec3::new(x0, -h, z),
                Vec3::new(h, -h, z),
                Vec3::new(h, h, z),
                Vec3::new(x0, h, z),
            ],
            Vec3::Z,
        );
    }
    let mut scene = cornell_box();
    scene.name = "stepped-walls".into();
    scene.mesh = b.build();
    scene.camera = Camera::new(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 60.0, 0.1, 100.0);
    scene.light = SpotLight {
        position: Vec3::new(0.0, 0.0, 6.0),
        direction: Vec3::NEG_Z,
        ..scene.light
    };
    scene
}

/// The bilateral filter: on the far wall the noise of the modulation factor along the edge
/// (where the true value is the same) drops by at least 4x at 11x11; beside the depth edge the
/// near wall stays unoccluded (1 within 1%) and the far wall's band keeps its mean within 1%.
#[test]
fn bilateral_filter_smooths_planes_without_bleeding_across_edges() {
    let ctx = common::context();
    let size = 128u32;
    let scene = stepped_walls();
    let radius = 0.8 / scene.mesh.bounds.radius();
    let run = |filter| {
        let ssdo = SsdoConfig {
            samples: 10,
            radius,
            filter,
            ..Default::default()
        };
        let mut r = render(&ctx, stepped_walls(), config(size, ssdo));
        let s = r.read(Target::Effect(&ssdo::MODULATION_VIEW)).unwrap();
        (0..size * size)
            .map(|i| s.texel(i % size, i / size)[3])
            .collect::<Vec<f32>>()
    };
    let raw = run(0);
    let filtered = run(11);
    let at = |v: &[f32], x: u32, y: u32| v[(y * size + x) as usize];
    // The edge is at x = 0: column size / 2. Far wall: columns left of it.
    let edge = size / 2;
    let rows = 16..size - 16;
    let column_variance = |v: &[f32], x: u32| {
        let vals: Vec<f32> = rows.clone().map(|y| at(v, x, y)).collect();
        let mean = vals.iter().sum::<f32>() / vals.len() as f32;
        vals.iter().map(|a| (a - mean).powi(2)).sum::<f32>() / vals.len() as f32
    };
    let band = |v: &[f32], xs: std::ops::Range<u32>| {
        let mut sum = 0.0;
        let mut n = 0;
        for x in xs {
            for y in rows.clone() {
                sum += at(v, x, y);
                n += 1;
            }
        }
        sum / n as f32
    };
    for x in edge - 8..edge - 2 {
        let (vr, vf) = (column_variance(&raw, x), column_variance(&filtered, x));
        eprintln!("column {x}: variance raw {vr:.3e}, filtered {vf:.3e}");
        assert!(vr > 0.0 && vf * 4.0 <= vr, "column {x}: {vr} -> {vf}");
    }
    let far = 5 + 2;
    let (far_raw, far_filtered) = (
        band(&raw, edge - far..edge - 2),
        band(&filtered, edge - far..edge - 2),
    );
    eprintln!("far wall beside the edge: mean {far_raw} raw, {far_filtered} filtered");
    assert!(
        far_raw < 0.99,
        "the far wall beside the edge is not occluded ({far_raw})"
    );
    assert!(
        (far_filtered - far_raw).abs() <= 0.01 * far_raw,
        "far wall: {far_raw} -> {far_filtered}"
    );
    for x in edge + 1..edge + 7 {
        for y in rows.clone() {
            let (r0, f0) = (at(&raw, x, y), at(&filtered, x, y));
            assert!((r0 - 1.0).abs() <= 1e-3, "near wall ({x}, {y}) raw {r0}");
            assert!(
                (f0 - 1.0).abs() <= 0.01,
                "near wall ({x}, {y}) filtered {f0}"
            );
        }
    }
    common::assert_clean(&ctx);
}

/// The adaptive pre-pass (`--ssdo-samples adaptive`): every block's count equals a CPU
/// evaluation of the change measure on the read-back G-buffer (creases: 1 - n . n'; steps:
/// distance from the centre's tangent plane in block sizes), planes take the fewest samples and
/// the box's edges and corners more.
#[test]
fn adaptive_counts_follow_creases_and_edges() {
    let ctx = common::context();
    let size = 96u32;
    let adaptive = AdaptiveSamples::PAPER;
    let ssdo = SsdoConfig {
        samples: adaptive.max(),
        adaptive: Some(adaptive),
        filter: 0,
        ..Default::default()
    };
    let (mut r, counters) = render_counted(&ctx, cornell_box(), config(size, ssdo));
    let counts = r.read(Target::Effect(&ssdo::SAMPLES_VIEW)).unwrap();
    let pos = r.read(Target::GPosition).unwrap();
    let normal = r.read(Target::GNormal).unwrap();
    let vp = r.scene.camera.view_proj(1.0);
    let tan_half = (0.5 * r.scene.camera.vfov_deg).to_radians().tan();
    let scale = adaptive.scale as i32;
    assert_eq!(counts.width, size.div_ceil(adaptive.scale));
    let last = size as i32 - 1;
    let (mut flat, mut busy, mut checked) = (0, 0, 0);
    for ty in 0..counts.height as i32 {
        for tx in 0..counts.width as i32 {
            let c = (
                (tx * scale + scale / 2).min(last),
                (ty * scale + scale / 2).min(last),
            );
            let p4 = pos.texel(c.0 as u32, c.1 as u32);
            let got = counts.texel(tx as u32, ty as u32)[0] as u32;
            let mut change = 0.0f32;
            if p4[3] != 0.0 {
                let (p, n) = (v3(p4), v3(normal.texel(c.0 as u32, c.1 as u32)));
                let depth = (vp * p.extend(1.0)).w;
                let block = scale as f32 * 2.0 * tan_half * depth / size as f32;
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let q = (
                            (c.0 + dx * scale).clamp(0, last) as u32,
                            (c.1 + dy * scale).clamp(0, last) as u32,
                        );
                        let q4 = pos.texel(q.0, q.1);
                        if q4[3] == 0.0 {
                            continue;
                        }
                        let qn = v3(normal.texel(q.0, q.1));
                        let crease = 1.0 - n.dot(qn).clamp(-1.0, 1.0);
                        let step = ((v3(q4) - p).dot(n).abs() / block).min(1.0);
                        change = change.max(crease.max(step));
                    }
                }
            }
            // A change within 1e-4 of a threshold may round either way on the two sides.
            if adaptive
                .thresholds()
                .iter()
                .any(|t| (change - t).abs() < 1e-4)
            {
                continue;
            }
            let periods = adaptive
                .thresholds()
                .iter()
                .filter(|t| change > **t)
                .count() as u32;
            let expected = adaptive.min + 10 * periods;
            assert_eq!(got, expected, "block ({tx}, {ty}): change {change}");
            checked += 1;
            if p4[3] != 0.0 {
                flat += usize::from(got == adaptive.min);
                busy += usize::from(got == adaptive.max());
            }
        }
    }
    eprintln!("{checked} blocks checked: {flat} with the fewest samples, {busy} with the most");
    assert!(flat > 100 && busy > 20, "{flat} flat, {busy} busy blocks");
    // The GPU counters (the timing report's) count the geometry pixels and their blocks' samples.
    let (mut pixels, mut samples) = (0u64, 0u64);
    for y in 0..size {
        for x in 0..size {
            if pos.texel(x, y)[3] != 0.0 {
                pixels += 1;
                samples += counts.texel(x / adaptive.scale, y / adaptive.scale)[0] as u64;
            }
        }
    }
    let counter = |name| counters.iter().find(|(n, _)| *n == name).map(|c| c.1);
    assert_eq!(
        counter("ssdo_computed_pixels"),
        Some(pixels),
        "{counters:?}"
    );
    assert_eq!(counter("ssdo_samples"), Some(samples), "{counters:?}");
    eprintln!(
        "mean samples per pixel {:.2} (GPU counters)",
        samples as f64 / pixels as f64
    );
    common::assert_clean(&ctx);
}

/// Half resolution with joint bilateral upsampling (`--ssdo-scale 0.5`, the paper's rows with
/// subsampling): on the Cornell box the upsampled modulation factor and bounce stay within RMSE
/// 0.01 of the full-resolution result (both 50 samples, filters of the same footprint) over the
/// planes' interiors, where the 5x5 neighbourhood lies on one plane, and within 0.04 at the
/// creases.
#[test]
fn half_resolution_follows_full_resolution() {
    let ctx = common::context();
    let size = 128u32;
    // The filters cover the same footprint: 11 grid texels at half resolution span 21 pixels.
    let run = |scale| {
        let ssdo = SsdoConfig {
            samples: 50,
            scale,
            filter: if scale == 1 { 21 } else { 11 },
            ..Default::default()
        };
        let mut r = render(&ctx, cornell_box(), config(size, ssdo));
        let s = r.read(Target::Effect(&ssdo::BOUNCE_VIEW)).unwrap();
        assert_eq!(
            (s.width, s.height),
            (size, size),
            "scale {scale}: the result's size"
        );
        let pos = r.read(Target::GPosition).unwrap();
        let normal = r.read(Target::GNormal).unwrap();
        (s, pos, normal)
    };
    let (full, pos, normal) = run(1);
    let (half, _, _) = run(2);
    // Interior: every pixel within 2 has a geometry sample with the same normal.
    let interior = |x: u32, y: u32| {
        let n = v3(normal.texel(x, y));
        (y.saturating_sub(2)..(y + 3).min(size)).all(|qy| {
            (x.saturating_sub(2)..(x + 3).min(size))
                .all(|qx| pos.texel(qx, qy)[3] != 0.0 && v3(normal.texel(qx, qy)).dot(n) > 0.999)
        })
    };
    let (mut inner, mut edge) = ([0.0f64; 2], [0.0f64; 2]);
    let (mut n_inner, mut n_edge) = (0usize, 0usize);
    for y in 0..size {
        for x in 0..size {
            if pos.texel(x, y)[3] == 0.0 {
                continue;
            }
            let (a, b) = (full.texel(x, y), half.texel(x, y));
            assert!(b.iter().all(|c| c.is_finite()), "({x}, {y}): {b:?}");
            let dm = f64::from(a[3] - b[3]).powi(2);
            let db = (v3(a) - v3(b)).length_squared() as f64 / 3.0;
            let (acc, n) = if interior(x, y) {
                (&mut inner, &mut n_inner)
            } else {
                (&mut edge, &mut n_edge)
            };
            acc[0] += dm;
            acc[1] += db;
            *n += 1;
        }
    }
    let rmse = |acc: [f64; 2], n: usize| acc.map(|v| (v / n as f64).sqrt());
    let (inner, edge) = (rmse(inner, n_inner), rmse(edge, n_edge));
    eprintln!(
        "half vs full resolution: interior ({n_inner} px) RMSE modulation {:.4}, bounce {:.4}; \
         creases ({n_edge} px) {:.4}, {:.4}",
        inner[0], inner[1], edge[0], edge[1]
    );
    assert!(n_inner > 8000, "{n_inner} interior pixels");
    // Measured 0.0058 (modulation) and 0.0042 (bounce) on lavapipe; 0.01 is the documented
    // bound: the joint bilateral upsampling may cost a hundredth in the interior, no more.
    assert!(
        inner[0] <= 0.01 && inner[1] <= 0.01,
        "interior RMSE {inner:?}"
    );
    assert!(edge[0] <= 0.04 && edge[1] <= 0.04, "crease RMSE {edge:?}");
    common::assert_clean(&ctx);
}

/// The upsampling does not bleed across a depth edge: beside the stepped walls' edge the near
/// wall stays unoccluded (1 within 1%) at half resolution, and the occluded band of the far wall
/// keeps its full-resolution mean within 3% when the filters cover the same footprint (21x21 at
/// full resolution, 11x11 at half: an 11x11 filter at half resolution reaches twice as far, which
/// flattens the occlusion gradient beside the edge).
#[test]
fn upsampling_does_not_bleed_across_edges() {
    let ctx = common::context();
    let size = 128u32;
    let scene = stepped_walls();
    let radius = 0.8 / scene.mesh.bounds.radius();
    let run = |scale, filter| {
        let ssdo = SsdoConfig {
            samples: 50,
            radius,
            scale,
            filter,
            ..Default::default()
        };
        let mut r = render(&ctx, stepped_walls(), config(size, ssdo));
        let s = r.read(Target::Effect(&ssdo::MODULATION_VIEW)).unwrap();
        (0..size * size)
            .map(|i| s.texel(i % size, i / size)[3])
            .collect::<Vec<f32>>()
    };
    let (full, half) = (run(1, 21), run(2, 11));
    let at = |v: &[f32], x: u32, y: u32| v[(y * size + x) as usize];
    let edge = size / 2;
    let rows = 16..size - 16;
    for x in edge..edge + 7 {
        for y in rows.clone() {
            let m = at(&half, x, y);
            assert!((m - 1.0).abs() <= 0.01, "near wall ({x}, {y}): {m}");
        }
    }
    let band = |v: &[f32]| {
        let xs = edge - 7..edge;
        let n = xs.len() * rows.len();
        xs.flat_map(|x| rows.clone().map(move |y| (x, y)))
            .map(|(x, y)| at(v, x, y))
            .sum::<f32>()
            / n as f32
    };
    for x in edge - 10..edge {
        let col = |v: &[f32]| rows.clone().map(|y| at(v, x, y)).sum::<f32>() / rows.len() as f32;
        eprintln!("column {x}: {} full, {} half", col(&full), col(&half));
    }
    let (bf, bh) = (band(&full), band(&half));
    eprintln!("far wall beside the edge: mean {bf} full, {bh} half resolution");
    assert!(
        bf < 0.99,
        "the far wall beside the edge is not occluded ({bf})"
    );
    assert!((bh - bf).abs() <= 0.03 * bf, "far wall: {bf} -> {bh}");
    common::assert_clean(&ctx);
}

/// With the cache (`--reuse on`, beyond the paper): on a static view the accumulated modulation
/// factor and bounce converge, after the rotation limit's patterns of K samples, to what one
/// uncached pass with all those samples computes (the mean of the patterns' ratios against the
/// ratio of their sums: close, not equal), and converged pixels cost nothing: the last frames
/// compute no pixel and take no sample. A pixel whose gated mean restarted (an outlier pair of
/// 10-sample estimates, a few pixels here) takes up to the rotation limit's patterns again
/// before it counts as converged, so the run is twice that. Under motion every history value
/// stays finite.
#[test]
fn cached_ssdo_converges_to_the_many_sample_result_and_then_skips() {
    let ctx = common::context();
    let size = 64u32;
    let k = 10;
    for form in [SsdoForm::OneStep, SsdoForm::Ssao] {
        let mut c = config(
            size,
            SsdoConfig {
                form,
                samples: k,
                filter: 0,
                ..Default::default()
            },
        );
        c.temporal.reuse = true;
        let limit = c.temporal.rotation_limit;
        let mut r = Renderer::new(&ctx, cornell_box(), c).expect("renderer");
        let camera = r.scene.camera;
        let mut timings = Vec::new();
        for _ in 0..2 * limit + 4 {
            r.render_frame(&camera).unwrap();
            timings.extend(r.finish().unwrap());
        }
        let counter = |t: &ssgi::vk::FrameTiming, name| {
            t.counters.iter().find(|(n, _)| *n == name).map(|c| c.1)
        };
        assert_eq!(
            counter(&timings[0], "ssdo_samples"),
            Some(u64::from(size * size * k))
        );
        let still = |t: &ssgi::vk::FrameTiming| counter(t, "ssdo_computed_pixels").unwrap_or(0);
        let late = still(&timings[limit as usize + 1]);
        eprintln!("{form:?}: {late} pixels still accumulating after the rotation limit");
        assert!(
            late <= 16,
            "{late} pixels restarted their mean by noise alone"
        );
        for t in &timings[2 * limit as usize + 1..] {
            assert_eq!(
                counter(t, "ssdo_computed_pixels"),
                Some(0),
                "frame {}",
                t.frame
            );
            assert_eq!(counter(t, "ssdo_samples"), Some(0), "frame {}", t.frame);
        }
        let cached = r.read(Target::Effect(&ssdo::MODULATION_VIEW)).unwrap();
        let pos = r.read(Target::GPosition).unwrap();
        let mut u = config(
            size,
            SsdoConfig {
                form,
                samples: k * limit,
                filter: 0,
                ..Default::default()
            },
        );
        u.temporal.reuse = false;
        let mut reference = render(&ctx, cornell_box(), u);
        let once = reference
            .read(Target::Effect(&ssdo::MODULATION_VIEW))
            .unwrap();
        let (mut dm, mut db, mut n, mut rms) = (0.0f64, 0.0f64, 0usize, 0.0f64);
        for y in 0..size {
            for x in 0..size {
                if pos.texel(x, y)[3] == 0.0 {
                    continue;
                }
                let (a, b) = (cached.texel(x, y), once.texel(x, y));
                dm += f64::from(a[3] - b[3]).powi(2);
                db += (v3(a) - v3(b)).length_squared() as f64 / 3.0;
                rms += v3(b).length_squared() as f64 / 3.0;
                n += 1;
            }
        }
        let (dm, db) = ((dm / n as f64).sqrt(), (db / n as f64).sqrt());
        let rms = (rms / n as f64).sqrt();
        eprintln!(
            "{form:?}: cached vs {} samples at once: RMSE factor {dm:.4}, bounce {db:.4} \
             ({:.2}% of its RMS)",
            k * limit,
            100.0 * db / rms.max(1e-30)
        );
        // The cache darkens the mean bounce by the mean factor, as one pass over all the
        // samples does: within 2% (darkening each pattern by its own factor was 3.6% low).
        assert!(
            dm <= 0.01 && db <= 0.02 * rms,
            "{form:?}: RMSE {dm}, {db} (RMS {rms})"
        );
    }
    // Orbiting: histories resampled every frame stay finite.
    let mut c = config(size, SsdoConfig::default());
    c.temporal.reuse = true;
    let mut r = Renderer::new(&ctx, cornell_box(), c).expect("renderer");
    let base = r.scene.camera;
    for i in 0..12 {
        let angle = i as f32 * 0.03;
        let mut camera = base;
        let offset = camera.position - camera.target;
        camera.position = camera.target + glam::Quat::from_rotation_y(angle) * offset;
        r.render_frame(&camera).unwrap();
    }
    r.finish().unwrap();
    let s = r.read(Target::Effect(&ssdo::MODULATION_VIEW)).unwrap();
    for y in 0..size {
        for x in 0..size {
            assert!(s.texel(x, y).iter().all(|v| v.is_finite()), "({x}, {y})");
        }
    }
    common::assert_clean(&ctx);
}

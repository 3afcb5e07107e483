//! The tracer against closed forms and an independent numerical integral (issue 11's
//! acceptance): each within 1 % at the reference's default sample counts.

use super::trace::{DEFAULT_AO_SAMPLES, DEFAULT_INDIRECT_SAMPLES};
use super::*;
use crate::scene::{Camera, Material, MeshBuilder, Scene, SpotLight};
use glam::Vec3;
use std::f32::consts::PI;

/// A square of half-size `s` in the plane y = `y`, normal ±Y.
fn square(b: &mut MeshBuilder, m: usize, y: f32, s: f32, up: bool) {
    let c = [(-s, -s), (s, -s), (s, s), (-s, s)].map(|(x, z)| Vec3::new(x, y, z));
    b.add_flat_polygon(m, &c, if up { Vec3::Y } else { Vec3::NEG_Y });
}

fn light(position: Vec3, outer: f32) -> SpotLight {
    SpotLight::aimed(
        position,
        position - Vec3::Y,
        Vec3::new(3.0, 2.0, 1.0),
        outer,
        outer,
        0.01,
        100.0,
    )
}

fn settings(radius: f32, attenuation: [f32; 2]) -> Settings {
    Settings {
        ao: AoDefinition {
            radius,
            attenuation,
        },
        light_radius: 0.0,
        seed: 1,
    }
}

fn mean_over_geometry(r: &Reference, buffer: RefBuffer, channel: usize) -> f64 {
    let e = r.estimate(buffer);
    let m = e.mean();
    let geometry = r.geometry();
    let values: Vec<f64> = (0..geometry.len())
        .filter(|&i| geometry[i])
        .map(|i| m[i * e.channels + channel] as f64)
        .collect();
    assert!(!values.is_empty(), "no pixel sees geometry");
    values.iter().sum::<f64>() / values.len() as f64
}

/// A small receiver facing down at height h above a large floor, seen from below.
fn receiver_over_floor(h: f32, floor: f32, l: SpotLight) -> Scene {
    let mut b = MeshBuilder::new();
    let white = b.add_material(Material::colour("white", [0.5, 0.5, 0.5]));
    square(&mut b, white, 0.0, floor, true);
    square(&mut b, white, h, 0.05, false);
    Scene {
        name: "test".into(),
        mesh: b.build(),
        camera: Camera::new(
            Vec3::new(0.0, 0.5 * h, 0.0),
            Vec3::new(0.0, h, 0.0001),
            10.0,
            0.001,
            100.0,
        ),
        light: l,
        ambient: Vec3::ZERO,
        orbit: None,
        light_path: None,
        objects: Vec::new(),
    }
}

fn traced(scene: &Scene, s: Settings, buffer: RefBuffer, samples: u32) -> Reference {
    let accel = Accel::new(&scene.mesh);
    let mut r = Reference::new(&accel, scene, scene.camera, 4, 4, s);
    assert!(
        r.geometry().iter().all(|g| *g),
        "the receiver fills the view"
    );
    r.refine(&accel, scene, buffer, samples, &|_| {});
    r
}

#[test]
fn ao_of_a_plane_at_distance_h_binary_and_with_falloff() {
    let (h, radius) = (0.5f32, 1.0f32);
    // The light is irrelevant for AO; keep it below the receiver.
    let scene = receiver_over_floor(h, 20.0, light(Vec3::new(0.0, 0.1, 0.0), 60.0));
    let k = (h / radius).powi(2) as f64;
    // Binary visibility within R: a ray at angle θ hits at h / cos θ, inside R iff
    // cos θ ≥ h/R; the cosine-weighted occluded fraction is 1 − (h/R)².
    let r = traced(
        &scene,
        settings(radius, [0.0, 0.0]),
        RefBuffer::Ao,
        DEFAULT_AO_SAMPLES,
    );
    let v = mean_over_geometry(&r, RefBuffer::Ao, 0);
    assert!((v - k).abs() < 0.01 * k, "binary: {v} vs {k}");
    // D(x) = 1 + x²: occlusion = ∫_k^1 u R²/(u R² + h²) du (u = cos²θ)
    //                          = 1 − k − k ln((1 + k) / (2k)).
    let r = traced(
        &scene,
        settings(radius, [0.0, 1.0]),
        RefBuffer::Ao,
        DEFAULT_AO_SAMPLES,
    );
    let v = mean_over_geometry(&r, RefBuffer::Ao, 0);
    let expect = k + k * ((1.0 + k) / (2.0 * k)).ln();
    assert!(
        (v - expect).abs() < 0.01 * expect,
        "falloff: {v} vs {expect}"
    );
}

#[test]
fn direct_light_is_inverse_square_with_hard_shadows() {
    let mut b = MeshBuilder::new();
    let white = b.add_material(Material::colour("white", [0.6, 0.6, 0.6]));
    square(&mut b, white, 0.0, 2.0, true);
    // A blocker at half the light's height over x in [0.2, 0.4] (all z): its shadow on the
    // floor is x in [0.4, 0.8] for a light over the origin.
    let c = [(0.2, -3.0), (0.4, -3.0), (0.4, 3.0), (0.2, 3.0)].map(|(x, z)| Vec3::new(x, 1.0, z));
    b.add_flat_polygon(white, &c, Vec3::Y);
    let l = light(Vec3::new(0.0, 2.0, 0.0), 80.0);
    let scene = Scene {
        name: "test".into(),
        mesh: b.build(),
        camera: Camera::new(
            Vec3::new(0.0, 0.6, 0.0),
            Vec3::new(0.0, 0.0, -0.0001),
            140.0,
            0.01,
            10.0,
        ),
        light: l,
        ambient: Vec3::ZERO,
        orbit: None,
        light_path: None,
        objects: Vec::new(),
    };
    let accel = Accel::new(&scene.mesh);
    let mut r = Reference::new(
        &accel,
        &scene,
        scene.camera,
        32,
        32,
        settings(1.0, [0.0, 1.0]),
    );
    r.refine(&accel, &scene, RefBuffer::Direct, 1, &|_| {});
    let direct = r.direct.mean();
    let shadow = r.shadow.mean();
    let (mut lit, mut dark) = (0, 0);
    for (i, p) in r.primary.iter().enumerate() {
        let Some(p) = p else { continue };
        let q = p.surface.position;
        if q.y.abs() > 1e-4 {
            continue; // the blocker itself
        }
        let in_shadow = q.x > 0.4 && q.x < 0.8;
        let near_edge = (q.x - 0.4).abs() < 0.02 || (q.x - 0.8).abs() < 0.02;
        if near_edge {
            continue;
        }
        let d = l.position - q;
        let cos = d.normalize().y;
        let expect = 0.6 / PI * l.intensity * cos / d.length_squared();
        let got = Vec3::from_slice(&direct[3 * i..3 * i + 3]);
        if in_shadow {
            assert_eq!((got, shadow[i]), (Vec3::ZERO, 0.0), "at {q}");
            dark += 1;
        } else {
            assert!(
                (got - expect).abs().max_element() <= 0.01 * expect.max_element(),
                "{got} vs {expect} at {q}"
            );
            assert_eq!(shadow[i], 1.0);
            lit += 1;
        }
    }
    assert!(lit > 50 && dark > 20, "lit {lit}, shadowed {dark}");
    assert_eq!(
        r.direct.standard_error(&r.geometry()),
        0.0,
        "the point light is exact"
    );
}

#[test]
fn one_bounce_matches_a_numerical_integral() {
    // Floor y = 0 of albedo 0.5, spot light at height a over the origin pointing down with a
    // 50° cone, receiver facing down at height h > a (outside the cone: no direct light and
    // no shadow on the floor). π·E₁ at the receiver = π ∫ (ρ/π) E(q) cos_p cos_q / |p − q|² dA.
    let (a, h, rho) = (0.3f32, 1.0f32, 0.5f64);
    let l = light(Vec3::new(0.0, a, 0.0), 50.0);
    let scene = receiver_over_floor(h, 20.0, l);
    let r = traced(
        &scene,
        settings(1.0, [0.0, 1.0]),
        RefBuffer::Indirect,
        DEFAULT_INDIRECT_SAMPLES,
    );
    let got = mean_over_geometry(&r, RefBuffer::Indirect, 0);
    // Midpoint rule in polar coordinates around the light's foot point, over the lit disc.
    let p = Vec3::new(0.0, h, 0.0);
    let r_max = a as f64 * 50f64.to_radians().tan();
    let (nr, nphi) = (2000, 256);
    let mut sum = 0.0f64;
    for i in 0..nr {
        let rr = (i as f64 + 0.5) / nr as f64 * r_max;
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) / nphi as f64 * std::f64::consts::TAU;
            let q = Vec3::new((rr * phi.cos()) as f32, 0.0, (rr * phi.sin()) as f32);
            let e_q = l.irradiance(q, Vec3::Y).x as f64;
            let d = p - q;
            let d2 = d.length_squared() as f64;
            let cos_q = d.y as f64 / d2.sqrt();
            let cos_p = cos_q; // parallel planes
            let da = rr * (r_max / nr as f64) * (std::f64::consts::TAU / nphi as f64);
            sum += rho / std::f64::consts::PI * e_q * cos_p * cos_q / d2 * da;
        }
    }
    let expect = std::f64::consts::PI * sum;
    assert!((got - expect).abs() < 0.01 * expect, "{got} vs {expect}");
}

//! One Monte Carlo sample of each reference quantity at a primary hit.
//!
//! Units match the renderer's buffers, so they compare without conversion:
//! - AO: ambient visibility 1 − occlusion, occlusion = ∫ (cos θ / π) · [t(ω) ≤ R] / D(t(ω)/R) dω
//!   over the hemisphere of the shading normal, t(ω) the distance to the first surface,
//!   D(x) = 1 + a x + b x² the thesis's attenuation (eq 7) with the renderer's radius R;
//! - direct: outgoing radiance albedo/π · E · V, E the spot light's irradiance with the
//!   renderer's cone and inverse-square law, V the light's visibility (exact for the point
//!   light; a disc of radius r facing the receiver for the optional spherical light);
//! - shadow: V alone;
//! - indirect: π·E₁, E₁ the irradiance of one diffuse bounce of the spot light with full
//!   visibility on both segments (light → q and q → p). Eq 9's sum Σ Φ cos cos / d² is π·E₁,
//!   which is what the renderer's indirect buffer holds before the composite's ρ/π · 1/π.

use super::sampling::{cosine_hemisphere, disc_point};
use super::surface::Surface;
use crate::scene::accel::Accel;
use crate::scene::{Mesh, SpotLight};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The AO definition: the renderer's world radius and attenuation coefficients.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct AoDefinition {
    pub radius: f32,
    pub attenuation: [f32; 2],
}

/// Start of a ray leaving a surface at `p`: 8 float spacings of p's largest coordinate, the
/// precision p itself is known to, so the ray does not hit p's own neighbourhood; it scales
/// with the coordinates, never a fixed world distance. (The triangle p lies on is skipped.)
pub fn ray_start(p: Vec3) -> f32 {
    8.0 * f32::EPSILON * p.abs().max_element().max(f32::MIN_POSITIVE)
}

/// A primary hit as the G-buffer holds it: the surface and its normal facing the eye.
#[derive(Clone, Copy, Debug)]
pub struct Primary {
    pub surface: Surface,
    pub normal: Vec3,
}

/// One sample of ambient visibility.
pub fn ao_sample(accel: &Accel, p: &Primary, def: &AoDefinition, u: Vec2) -> f32 {
    match ao_sample_hit(accel, p, def, u) {
        Some((_, occlusion)) => 1.0 - occlusion,
        None => 1.0,
    }
}

/// The occluder one AO sample meets within the radius, if any: its position and triangle, and
/// its occlusion 1 / D(t / R).
pub fn ao_sample_hit(
    accel: &Accel,
    p: &Primary,
    def: &AoDefinition,
    u: Vec2,
) -> Option<((Vec3, usize), f32)> {
    let (dir, _) = cosine_hemisphere(p.normal, u);
    let pos = p.surface.position;
    let hit = accel.closest(
        pos,
        dir,
        ray_start(pos),
        def.radius,
        Some(p.surface.triangle),
    )?;
    let x = hit.t / def.radius;
    let d = 1.0 + def.attenuation[0] * x + def.attenuation[1] * x * x;
    Some(((hit.position, hit.triangle), 1.0 / d))
}

/// One sample of direct radiance and light visibility.
pub fn direct_sample(
    accel: &Accel,
    p: &Primary,
    light: &SpotLight,
    light_radius: f32,
    u: Vec2,
) -> (Vec3, f32) {
    let pos = p.surface.position;
    let irradiance = light.irradiance(pos, p.normal);
    if irradiance == Vec3::ZERO && p.normal.dot(light.position - pos) <= 0.0 {
        return (Vec3::ZERO, 0.0); // facing away: self-shadowed, as the renderer's direct pass
    }
    let to = if light_radius > 0.0 {
        let axis = (pos - light.position).normalize_or(light.direction);
        disc_point(light.position, axis, light_radius, u)
    } else {
        light.position
    };
    let v = if accel.occluded(pos, to, Some(p.surface.triangle)) {
        0.0
    } else {
        1.0
    };
    (p.surface.albedo / PI * irradiance * v, v)
}

/// One sample of π·E₁ (see the module comment), cosine-weighted around the normal: the
/// estimator of E₁ = ∫ L cos θ dω is π·L, L = ρ_q/π · E_direct(q), so a sample is π·ρ_q·E_q.
pub fn indirect_sample(
    accel: &Accel,
    mesh: &Mesh,
    p: &Primary,
    light: &SpotLight,
    u: Vec2,
) -> Vec3 {
    let (dir, _) = cosine_hemisphere(p.normal, u);
    let pos = p.surface.position;
    let Some(hit) = accel.closest(
        pos,
        dir,
        ray_start(pos),
        f32::INFINITY,
        Some(p.surface.triangle),
    ) else {
        return Vec3::ZERO;
    };
    let q = Surface::at(mesh, &hit);
    // q reflects from the side facing the light (as the RSM orients its normals); p must be
    // on that side.
    let nq = q.facing(light.position);
    if nq.dot(pos - q.position) <= 0.0 {
        return Vec3::ZERO;
    }
    let e_q = light.irradiance(q.position, nq);
    if e_q == Vec3::ZERO || accel.occluded(q.position, light.position, Some(q.triangle)) {
        return Vec3::ZERO;
    }
    PI * q.albedo * e_q
}

//! Eq 9 on the CPU: the RSM gather the GPU passes are checked against.

use glam::Vec3;
use ssgi::scene::SpotLight;
use ssgi::vk::ImageData;

pub fn v3(t: [f32; 4]) -> Vec3 {
    Vec3::new(t[0], t[1], t[2])
}

/// Flux of the VPL at RSM texel (x, y), world position q, from the stored albedo x intensity:
/// times the CPU's cone factor and the texel's solid angle ((2 tan(fov/2) / N)^2 cos^3 off the
/// axis).
pub fn vpl_flux(light: &SpotLight, flux: &ImageData, x: u32, y: u32, q: Vec3) -> Vec3 {
    let side = 2.0 * (0.5 * light.frustum_fov_deg()).to_radians().tan() / flux.width as f32;
    let dir = (q - light.position).normalize();
    let cos_axis = dir.dot(light.direction.normalize()).max(0.0);
    v3(flux.texel(x, y)) * light.spot_factor(dir) * side * side * cos_axis.powi(3)
}

/// Eq 9 summed over every RSM texel on the CPU, with the shader's texel-size distance floor.
pub fn cpu_gather(light: &SpotLight, rsm: [&ImageData; 3], p: Vec3, n: Vec3) -> Vec3 {
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
            sum += vpl_flux(light, flux, x, y, q) * n.dot(dir).max(0.0) * nq.dot(-dir).max(0.0)
                / d2.max(texel * texel);
        }
    }
    sum
}

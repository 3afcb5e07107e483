//! Automatic views of a loaded model. A model that encloses space (a building: Sponza,
//! Sibenik, the conference room) gets a camera inside, placed and aimed by ray casting so that
//! walls fill the view, a headlight, and an orbit that turns inside. Any other model gets a
//! camera from outside that fits its vertices into the view, and a ground plane.
//!
//! All distances are relative to the model's bounding box, so the rules hold at any scale.

use super::accel::Accel;
use super::camera::Camera;
use super::mesh::{Aabb, Mesh};
use super::path::Orbit;
use glam::Vec3;

/// Rays cast from each candidate eye point (a Fibonacci sphere).
const PROBE_RAYS: usize = 64;
/// A candidate eye point is inside a room when at least this share of its probe rays meets
/// the front of a surface (Sponza's open roof lets about a tenth escape) ...
const ENCLOSED_SHARE: f32 = 0.75;
/// ... and at most this share meets the back of one (more: the point is inside a solid) ...
const BACK_SHARE: f32 = 0.1;
/// ... and a quarter of its rays travel at least this share of the box's smaller horizontal
/// side: there is room around it (inside a solid whose normals point inwards every ray would
/// meet a "front" face close by).
const OPEN_SHARE: f32 = 0.2;
/// Candidate eye points: a grid over the box's floor plan at these heights (fractions of the
/// box's height above its bottom: eye level in a building is low against its height).
const GRID: usize = 6;
const EYE_HEIGHTS: [f32; 3] = [0.12, 0.25, 0.4];
/// Candidate points whose views are compared, and the yaw/pitch steps of those views.
const POINTS_COMPARED: usize = 4;
const YAWS: usize = 16;
const PITCHES_DEG: [f32; 2] = [0.0, -12.0];
/// Rays per side of a candidate view's coverage grid.
const VIEW_RAYS: usize = 12;
/// Views whose background share is at most this (3 of the 144 grid rays) count as covered,
/// and the deepest of them wins: a long view along a nave beats a close wall.
const BACKGROUND_TOLERANCE: f32 = 0.02;
/// Field of view of the camera inside a building (wider than a model's: a room is seen from
/// within it).
pub const INTERIOR_FOV_DEG: f32 = 60.0;
/// Share of the view a fitted model's vertices may span (a margin at the frame's border).
const FIT_MARGIN: f32 = 0.96;
/// Sides the outside camera may look from: yaws about +Y (from +Z, the front of most
/// models) and elevations above the horizontal (the ground shows beneath the model). The
/// one whose fitted view the model covers most wins: a tall statue seen from above, a long
/// dragon from three quarters.
const OUTSIDE_YAWS: usize = 8;
const OUTSIDE_ELEVATIONS_DEG: [f32; 2] = [20.0, 35.0];
/// Vertices used to fit the outside camera (every n-th beyond this many).
const FIT_VERTICES: usize = 50_000;

/// A camera inside a model and the orbit that goes with it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InteriorView {
    pub camera: Camera,
    pub orbit: Orbit,
    /// Median distance to what the view sees (sizes the headlight).
    pub depth: f32,
}

/// How one probe ray ended.
#[derive(Clone, Copy, PartialEq)]
enum Probe {
    Front(f32),
    Back,
    Miss,
}

fn probe(accel: &Accel, mesh: &Mesh, origin: Vec3, dir: Vec3, far: f32) -> Probe {
    let Some(hit) = accel.closest(origin, dir, 0.0, far, None) else {
        return Probe::Miss;
    };
    let idx = &mesh.indices[3 * hit.triangle..3 * hit.triangle + 3];
    let n = |k: usize| Vec3::from(mesh.vertices[idx[k] as usize].normal);
    let shading = n(0) * (1.0 - hit.uv.x - hit.uv.y) + n(1) * hit.uv.x + n(2) * hit.uv.y;
    if shading.dot(dir) < 0.0 {
        Probe::Front(hit.t)
    } else {
        Probe::Back
    }
}

/// Unit directions spread evenly over the sphere.
fn fibonacci_sphere(n: usize) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..n)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let r = (1.0 - y * y).max(0.0).sqrt();
            let a = golden * i as f32;
            Vec3::new(r * a.cos(), y, r * a.sin())
        })
        .collect()
}

fn median(mut v: Vec<f32>) -> f32 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f32::total_cmp);
    v[v.len() / 2]
}

/// A view's coverage: the share of its grid rays that miss or meet a back face, and the
/// median and nearest distance of the rest.
struct Coverage {
    background: f32,
    depth: f32,
    nearest: f32,
}

fn coverage(accel: &Accel, mesh: &Mesh, camera: &Camera, far: f32) -> Coverage {
    let (f, r, u) = camera.frame();
    let t = (0.5 * camera.vfov_deg).to_radians().tan();
    let mut hits = Vec::with_capacity(VIEW_RAYS * VIEW_RAYS);
    let mut background = 0;
    for j in 0..VIEW_RAYS {
        for i in 0..VIEW_RAYS {
            let x = ((i as f32 + 0.5) / VIEW_RAYS as f32 * 2.0 - 1.0) * t;
            let y = ((j as f32 + 0.5) / VIEW_RAYS as f32 * 2.0 - 1.0) * t;
            let dir = (f + r * x + u * y).normalize();
            match probe(accel, mesh, camera.position, dir, far) {
                Probe::Front(d) => hits.push(d),
                _ => background += 1,
            }
        }
    }
    let nearest = hits.iter().copied().fold(f32::INFINITY, f32::min);
    Coverage {
        background: background as f32 / (VIEW_RAYS * VIEW_RAYS) as f32,
        depth: median(hits),
        nearest,
    }
}

/// A camera inside `mesh` that sees surfaces (not the sky, not the back of a wall) in as much
/// of its view as possible, or None when no point of the bounding box is enclosed: the model
/// is an object to be seen from outside.
pub fn interior_view(mesh: &Mesh, accel: &Accel) -> Option<InteriorView> {
    let b = mesh.bounds;
    let diagonal = b.diagonal();
    if b.is_empty() || diagonal <= 0.0 || !diagonal.is_finite() {
        return None;
    }
    let far = 2.0 * diagonal;
    let dirs = fibonacci_sphere(PROBE_RAYS);
    // Enclosed candidate points, scored by how open the space around them is.
    let mut points: Vec<(f32, Vec3)> = Vec::new();
    for &h in &EYE_HEIGHTS {
        for gz in 0..GRID {
            for gx in 0..GRID {
                let cell = Vec3::new(
                    (gx as f32 + 0.5) / GRID as f32,
                    h,
                    (gz as f32 + 0.5) / GRID as f32,
                );
                let p = b.min + b.extent() * cell;
                let probes: Vec<Probe> = dirs
                    .iter()
                    .map(|&d| probe(accel, mesh, p, d, far))
                    .collect();
                let share = |want: fn(&Probe) -> bool| {
                    probes.iter().filter(|p| want(p)).count() as f32 / PROBE_RAYS as f32
                };
                let front = share(|p| matches!(p, Probe::Front(_)));
                let back = share(|p| matches!(p, Probe::Back));
                if front < ENCLOSED_SHARE || back > BACK_SHARE {
                    continue;
                }
                let mut distances: Vec<f32> = probes
                    .iter()
                    .filter_map(|p| match p {
                        Probe::Front(d) => Some(*d),
                        _ => None,
                    })
                    .collect();
                distances.sort_by(f32::total_cmp);
                let upper_quartile = distances[distances.len() * 3 / 4];
                if upper_quartile < OPEN_SHARE * b.extent().x.min(b.extent().z) {
                    continue;
                }
                points.push((median(distances), p));
            }
        }
    }
    points.sort_by(|a, c| c.0.total_cmp(&a.0));
    points.truncate(POINTS_COMPARED);

    // The best view from those points: least background (within the tolerance), then the
    // deepest.
    let mut best: Option<(f32, f32, Camera, Coverage)> = None;
    for &(_, p) in &points {
        for yaw in 0..YAWS {
            for &pitch in &PITCHES_DEG {
                let a = yaw as f32 / YAWS as f32 * std::f32::consts::TAU;
                let e = pitch.to_radians();
                let dir = Vec3::new(a.sin() * e.cos(), e.sin(), a.cos() * e.cos());
                let camera = Camera::new(p, p + dir, INTERIOR_FOV_DEG, 1e-3 * diagonal, far);
                let c = coverage(accel, mesh, &camera, far);
                let covered = |bg: f32| bg.max(BACKGROUND_TOLERANCE);
                let better = best.as_ref().is_none_or(|(bg, depth, ..)| {
                    let (a, b) = (covered(c.background), covered(*bg));
                    a < b || (a == b && c.depth > *depth)
                });
                if better {
                    best = Some((c.background, c.depth, camera, c));
                }
            }
        }
    }
    let (_, _, mut camera, c) = best?;
    camera.target = camera.position + (camera.target - camera.position) * c.depth;
    // Near: well inside the nearest surface seen, and a fixed share of the model at most, so
    // depth keeps its precision (far / near <= 2000 / 1e-3 x the diagonal's share).
    camera.near = (0.25 * c.nearest).clamp(1e-4 * diagonal, 1e-3 * diagonal);
    camera.far = far;
    let (forward, ..) = camera.frame();
    let flat = Vec3::new(forward.x, 0.0, forward.z).normalize_or(Vec3::Z);
    // Orbit a point a quarter of the view's depth ahead, starting at the camera.
    let radius = 0.25 * c.depth;
    let orbit = Orbit::Inside {
        center: camera.position + flat * radius,
        radius,
        height: camera.position.y,
        open_towards: None,
        start: -flat,
    };
    Some(InteriorView {
        camera,
        orbit,
        depth: c.depth,
    })
}

/// The outside camera on `mesh` (one of `OUTSIDE_YAWS` x `OUTSIDE_ELEVATIONS_DEG`, fitted
/// by [`fit_from`]) whose view the model covers most (ties: the first, the front).
pub fn outside_view(mesh: &Mesh, accel: &Accel, vfov_deg: f32, scene_bounds: &Aabb) -> Camera {
    let mut best: Option<(f32, Camera)> = None;
    for &elevation in &OUTSIDE_ELEVATIONS_DEG {
        for k in 0..OUTSIDE_YAWS {
            let yaw = 360.0 * k as f32 / OUTSIDE_YAWS as f32;
            let camera = fit_from(mesh, vfov_deg, scene_bounds, yaw, elevation);
            let covered = 1.0 - coverage(accel, mesh, &camera, camera.far).background;
            if best.as_ref().is_none_or(|(c, _)| covered > *c) {
                best = Some((covered, camera));
            }
        }
    }
    best.map_or_else(
        || fit_from(mesh, vfov_deg, scene_bounds, 0.0, OUTSIDE_ELEVATIONS_DEG[0]),
        |(_, c)| c,
    )
}

/// A camera `elevation_deg` above the horizontal on the side of `mesh` at `yaw_deg` about +Y
/// from +Z, looking at it, as close as it can be with every vertex inside `FIT_MARGIN` of a
/// square view of `vfov_deg` (wider images only add room at the sides). Near and far bracket
/// `scene_bounds` (the model and whatever was added around it).
pub fn fit_from(
    mesh: &Mesh,
    vfov_deg: f32,
    scene_bounds: &Aabb,
    yaw_deg: f32,
    elevation_deg: f32,
) -> Camera {
    let b = mesh.bounds;
    let (e, a) = (elevation_deg.to_radians(), yaw_deg.to_radians());
    let back = Vec3::new(a.sin() * e.cos(), e.sin(), a.cos() * e.cos());
    let forward = -back;
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let t = (0.5 * vfov_deg).to_radians().tan() * FIT_MARGIN;
    let step = (mesh.vertices.len() / FIT_VERTICES).max(1);
    let points: Vec<Vec3> = mesh
        .vertices
        .iter()
        .step_by(step)
        .map(|v| v.pos())
        .collect();
    let mut center = b.center();
    let mut distance = 0.0;
    // Fit, then centre the projected extent and fit again (twice converges to a pixel).
    for _ in 0..3 {
        distance = points
            .iter()
            .map(|&p| {
                let v = p - center;
                let depth = v.dot(forward);
                (v.dot(right).abs().max(v.dot(up).abs()) / t - depth).max(0.0)
            })
            .fold(0.0f32, f32::max);
        let eye = center - forward * distance;
        let (mut lo, mut hi) = (
            glam::Vec2::splat(f32::INFINITY),
            glam::Vec2::splat(-f32::INFINITY),
        );
        for &p in &points {
            let v = p - eye;
            let z = v.dot(forward).max(f32::MIN_POSITIVE);
            let ndc = glam::Vec2::new(v.dot(right), v.dot(up)) / z;
            lo = lo.min(ndc);
            hi = hi.max(ndc);
        }
        let mid = 0.5 * (lo + hi);
        center += (right * mid.x + up * mid.y) * distance;
    }
    let radius = b
        .radius()
        .max(1e-6 * b.center().abs().max_element())
        .max(1e-6);
    let distance = distance.max(radius * 1e-3);
    let reach = (scene_bounds.center() - center).length() + scene_bounds.radius();
    Camera::new(
        center - forward * distance,
        center,
        vfov_deg,
        ((distance - radius) * 0.5).max(distance * 1e-3),
        (distance + reach) * 1.5,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::box_room;
    use crate::scene::MeshBuilder;
    use crate::scene::{cornell_box, Material};

    #[test]
    fn a_closed_room_is_an_interior_and_its_view_sees_only_walls() {
        // The box room with its open front closed: a closed room.
        let mut b = MeshBuilder::new();
        let empty = MeshBuilder::new().build();
        b.append(&box_room(&empty, "empty").mesh, 1.0, Vec3::ZERO);
        let white = b.add_material(Material::colour("front", [0.7; 3]));
        let v = Vec3::new;
        b.add_flat_polygon(
            white,
            &[
                v(-1.0, 0.0, 1.0),
                v(1.0, 0.0, 1.0),
                v(1.0, 2.0, 1.0),
                v(-1.0, 2.0, 1.0),
            ],
            Vec3::NEG_Z,
        );
        let mesh = b.build();
        let accel = Accel::new(&mesh);
        let view = interior_view(&mesh, &accel).expect("a closed room is an interior");
        let p = view.camera.position;
        assert!(p.cmpgt(mesh.bounds.min).all() && p.cmplt(mesh.bounds.max).all());
        let c = coverage(&accel, &mesh, &view.camera, 10.0);
        assert_eq!(c.background, 0.0);
    }

    #[test]
    fn an_object_is_seen_from_outside_and_fills_the_view() {
        let scene = crate::scene::pyramids();
        let accel = Accel::new(&scene.mesh);
        // The pyramids' ground is open to the sky: not an interior.
        assert!(interior_view(&scene.mesh, &accel).is_none());
        let open_box = cornell_box();
        let camera = fit_from(&open_box.mesh, 40.0, &open_box.mesh.bounds, 0.0, 20.0);
        // Every corner of the box projects inside the margin.
        let vp = camera.view_proj(1.0);
        for v in &open_box.mesh.vertices {
            let clip = vp * v.pos().extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(clip.w > camera.near, "{clip}");
            assert!(
                ndc.x.abs() <= FIT_MARGIN + 1e-3 && ndc.y.abs() <= FIT_MARGIN + 1e-3,
                "{ndc}"
            );
        }
        // And some vertex touches it: the fit is tight.
        let widest = open_box
            .mesh
            .vertices
            .iter()
            .map(|v| {
                let clip = vp * v.pos().extend(1.0);
                (clip.x / clip.w).abs().max((clip.y / clip.w).abs())
            })
            .fold(0.0f32, f32::max);
        assert!(widest > FIT_MARGIN - 0.02, "{widest}");
    }
}

//! Built-in scenes that need no files: the Cornell box, the pyramids, and the box room that
//! hosts a loaded model ("Buddha & Box").

use super::builder::MeshBuilder;
use super::camera::Camera;
use super::light::SpotLight;
use super::mesh::{Material, Mesh};
use super::path::Orbit;
use super::world::Scene;
use glam::Vec3;

/// McGuire's Cornell box albedos.
pub const CORNELL_WHITE: [f32; 3] = [0.725, 0.71, 0.68];
pub const CORNELL_RED: [f32; 3] = [0.63, 0.065, 0.05];
pub const CORNELL_GREEN: [f32; 3] = [0.14, 0.45, 0.091];
pub const DEFAULT_AMBIENT: Vec3 = Vec3::splat(0.03);

/// Box footprints as (x, z) corners, from McGuire's CornellBox-Original.obj.
const SHORT_BOX: [[f32; 2]; 4] = [[0.53, 0.75], [0.70, 0.17], [0.13, 0.00], [-0.05, 0.57]];
const SHORT_BOX_HEIGHT: f32 = 0.60;
const TALL_BOX: [[f32; 2]; 4] = [[-0.53, 0.09], [0.04, -0.09], [-0.14, -0.67], [-0.71, -0.49]];
const TALL_BOX_HEIGHT: f32 = 1.20;

pub fn cornell_camera() -> Camera {
    Camera::new(
        Vec3::new(0.0, 1.0, 3.4),
        Vec3::new(0.0, 1.0, 0.0),
        40.0,
        0.05,
        20.0,
    )
}

/// Spot light just under the ceiling where the box's area light is, pointing down, with the
/// area light's warm-white colour.
pub fn cornell_light() -> SpotLight {
    SpotLight {
        position: Vec3::new(0.0, 1.95, -0.03),
        direction: Vec3::NEG_Y,
        intensity: Vec3::new(6.0, 5.2, 4.2),
        inner_deg: 55.0,
        outer_deg: 65.0,
        near: 0.05,
        far: 10.0,
    }
}

/// The Cornell box with planar, axis-aligned walls (the original's slight skew removed), open
/// at the front (z = 0.99), without the light quad and the boxes' bottoms.
pub fn cornell_box() -> Scene {
    let mut b = MeshBuilder::new();
    let (min, max) = (Vec3::new(-1.01, 0.0, -1.04), Vec3::new(1.00, 1.99, 0.99));
    let room = Room::add_to(&mut b, min, max);
    add_prism(&mut b, room.white, &SHORT_BOX, SHORT_BOX_HEIGHT);
    add_prism(&mut b, room.white, &TALL_BOX, TALL_BOX_HEIGHT);
    Scene {
        name: "cornell-box".into(),
        mesh: b.build(),
        camera: cornell_camera(),
        light: cornell_light(),
        ambient: DEFAULT_AMBIENT,
        orbit: Some(room_orbit(min, max)),
        light_path: None,
        objects: Vec::new(),
    }
}

/// The orbit of the built-in rooms, which are open at the front (+z): the eye at the Cornell
/// camera's height, 0.85 of the half-width from the room's vertical axis, looking down at
/// the axis 0.6 m above the floor, sweeping the back half of the room (see
/// [`Orbit::Inside`]). Its view meets only walls, floor and ceiling, and it stays above the
/// boxes and a model of the box room (at most 0.9 m tall).
fn room_orbit(min: Vec3, max: Vec3) -> Orbit {
    let c = 0.5 * (min + max);
    Orbit::Inside {
        center: Vec3::new(c.x, min.y + 0.6, c.z),
        radius: 0.85 * 0.5 * (max.x - min.x).min(max.z - min.z),
        height: cornell_camera().position.y,
        open_towards: Some(Vec3::Z),
        start: Vec3::Z,
    }
}

/// Rings and segments of [`sphere`]: 32 x 16 quads keep the silhouette within 0.5% of the
/// radius.
const SPHERE_SEGMENTS: u32 = 32;
const SPHERE_RINGS: u32 = 16;

/// A sphere of radius 1 at the origin (scene files' `sphere`): smooth normals, one white
/// material (MTL's default Kd 0.8), wound counter-clockwise seen from outside. The caps are
/// triangle fans, so no triangle has zero area.
pub fn sphere() -> Mesh {
    uv_sphere(SPHERE_SEGMENTS, SPHERE_RINGS)
}

/// [`sphere`] with `segments` around and `rings` from pole to pole (a coarse one puts smooth
/// normals far from their facets' planes).
pub fn uv_sphere(segments: u32, rings: u32) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut b = MeshBuilder::new();
    let m = b.add_material(Material::colour("sphere", Material::DEFAULT_DIFFUSE));
    let point = |ring: u32, seg: u32| {
        let theta = std::f32::consts::PI * ring as f32 / rings as f32;
        let phi = std::f32::consts::TAU * seg as f32 / segments as f32;
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.cos(),
            -theta.sin() * phi.sin(),
        )
    };
    let mut index = |p: Vec3, u: f32, v: f32| b.push_vertex(super::mesh::Vertex::new(p, p, [u, v]));
    let mut rows = Vec::new();
    for ring in 0..=rings {
        let row: Vec<u32> = (0..=segments)
            .map(|seg| {
                index(
                    point(ring, seg),
                    seg as f32 / segments as f32,
                    ring as f32 / rings as f32,
                )
            })
            .collect();
        rows.push(row);
    }
    for ring in 0..rings as usize {
        for seg in 0..segments as usize {
            let (a, b0) = (rows[ring][seg], rows[ring][seg + 1]);
            let (c, d) = (rows[ring + 1][seg], rows[ring + 1][seg + 1]);
            // Counter-clockwise from outside: phi grows towards -z, theta downwards.
            if ring > 0 {
                b.push_triangle(m, [a, c, b0]);
            }
            if ring + 1 < rings as usize {
                b.push_triangle(m, [b0, c, d]);
            }
        }
    }
    b.build()
}

/// Material slots of a room.
pub struct Room {
    pub white: usize,
}

impl Room {
    /// Floor, ceiling, back wall (white), left wall (red), right wall (green) of the box
    /// `min..max`, normals pointing into the room, front (max z) open.
    pub fn add_to(b: &mut MeshBuilder, min: Vec3, max: Vec3) -> Room {
        let white = b.add_material(Material::colour("white", CORNELL_WHITE));
        let red = b.add_material(Material::colour("red", CORNELL_RED));
        let green = b.add_material(Material::colour("green", CORNELL_GREEN));
        let (x0, y0, z0) = (min.x, min.y, min.z);
        let (x1, y1, z1) = (max.x, max.y, max.z);
        let v = Vec3::new;
        let walls = [
            (
                white,
                [v(x0, y0, z0), v(x1, y0, z0), v(x1, y0, z1), v(x0, y0, z1)],
                Vec3::Y,
            ),
            (
                white,
                [v(x0, y1, z0), v(x1, y1, z0), v(x1, y1, z1), v(x0, y1, z1)],
                Vec3::NEG_Y,
            ),
            (
                white,
                [v(x0, y0, z0), v(x1, y0, z0), v(x1, y1, z0), v(x0, y1, z0)],
                Vec3::Z,
            ),
            (
                red,
                [v(x0, y0, z0), v(x0, y1, z0), v(x0, y1, z1), v(x0, y0, z1)],
                Vec3::X,
            ),
            (
                green,
                [v(x1, y0, z0), v(x1, y1, z0), v(x1, y1, z1), v(x1, y0, z1)],
                Vec3::NEG_X,
            ),
        ];
        for (material, corners, normal) in walls {
            b.add_flat_polygon(material, &corners, normal);
        }
        Room { white }
    }
}

/// A vertical prism over a convex footprint: top and sides, normals pointing out, no bottom.
fn add_prism(b: &mut MeshBuilder, material: usize, footprint: &[[f32; 2]], height: f32) {
    let base: Vec<Vec3> = footprint
        .iter()
        .map(|&[x, z]| Vec3::new(x, 0.0, z))
        .collect();
    let top: Vec<Vec3> = base.iter().map(|p| *p + Vec3::Y * height).collect();
    b.add_flat_polygon(material, &top, Vec3::Y);
    let centre = base.iter().sum::<Vec3>() / base.len() as f32;
    for i in 0..base.len() {
        let (p, q) = (base[i], base[(i + 1) % base.len()]);
        let edge = q - p;
        let mut n = Vec3::new(edge.z, 0.0, -edge.x);
        if n.dot(p - centre) < 0.0 {
            n = -n;
        }
        b.add_flat_polygon(material, &[p, q, top[(i + 1) % top.len()], top[i]], n);
    }
}

/// A square pyramid with apex above the centre; four sloped faces, no bottom.
fn add_pyramid(b: &mut MeshBuilder, material: usize, centre: Vec3, half: f32, height: f32) {
    let apex = centre + Vec3::Y * height;
    let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, z)| centre + Vec3::new(x * half, 0.0, z * half));
    for i in 0..4 {
        let (p, q) = (c[i], c[(i + 1) % 4]);
        let mut n = (q - p).cross(apex - p);
        let out = (p + q) * 0.5 - centre;
        if n.dot(out) < 0.0 {
            n = -n;
        }
        b.add_flat_polygon(material, &[p, q, apex], n);
    }
}

/// 8 × 8 m grey ground with a 3 × 3 grid of pyramids (0.5–1.5 m tall, four colours), seen
/// from 30° above the horizon, lit by a spot light above and to the side.
pub fn pyramids() -> Scene {
    let mut b = MeshBuilder::new();
    let ground = b.add_material(Material::colour("ground", [0.7, 0.7, 0.7]));
    let colours = [
        b.add_material(Material::colour("red", [0.7, 0.15, 0.1])),
        b.add_material(Material::colour("blue", [0.1, 0.25, 0.7])),
        b.add_material(Material::colour("yellow", [0.75, 0.6, 0.1])),
        b.add_material(Material::colour("white", [0.75, 0.75, 0.75])),
    ];
    let h = 4.0;
    b.add_flat_polygon(
        ground,
        &[
            Vec3::new(-h, 0.0, -h),
            Vec3::new(h, 0.0, -h),
            Vec3::new(h, 0.0, h),
            Vec3::new(-h, 0.0, h),
        ],
        Vec3::Y,
    );
    const HEIGHTS: [f32; 9] = [0.9, 1.5, 0.6, 1.2, 0.5, 1.0, 1.4, 0.7, 1.1];
    for (k, height) in HEIGHTS.iter().enumerate() {
        let (i, j) = ((k % 3) as f32 - 1.0, (k / 3) as f32 - 1.0);
        let centre = Vec3::new(i * 2.5, 0.0, j * 2.5);
        add_pyramid(&mut b, colours[k % colours.len()], centre, 0.7, *height);
    }
    let target = Vec3::new(0.0, 0.4, 0.0);
    let pitch = 30f32.to_radians();
    let camera = Camera::new(
        target + Vec3::new(0.0, pitch.sin(), pitch.cos()) * 10.5,
        target,
        40.0,
        0.1,
        40.0,
    );
    let light_pos = Vec3::new(-3.0, 6.0, 3.0);
    // Intensity chosen so the ground under the light's axis receives about 1.5 W/m².
    let light = SpotLight::aimed(
        light_pos,
        Vec3::ZERO,
        Vec3::new(100.0, 95.0, 88.0),
        35.0,
        45.0,
        0.1,
        30.0,
    );
    Scene {
        name: "pyramids".into(),
        mesh: b.build(),
        camera,
        light,
        ambient: DEFAULT_AMBIENT,
        orbit: None,
        light_path: None,
        objects: Vec::new(),
    }
}

/// Antialiasing's test scene: a grey wall 6 x 6 m, and 1.2 m in front of it a red 1.4 x 1.0 m
/// quad turned 35 degrees about the vertical and tilted 20 degrees back, seen from 5 m with a
/// 40 degree lens (the wall fills the view, the quad's four edges cross it at slants), lit by
/// a spot from the upper left so the quad throws a shadow with slanted edges onto the wall.
pub fn tilted_quad() -> Scene {
    let mut b = MeshBuilder::new();
    let wall = b.add_material(Material::colour("wall", [0.6, 0.6, 0.6]));
    let quad = b.add_material(Material::colour("quad", [0.8, 0.25, 0.1]));
    let h = 3.0;
    b.add_flat_polygon(
        wall,
        &[
            Vec3::new(-h, -h, 0.0),
            Vec3::new(h, -h, 0.0),
            Vec3::new(h, h, 0.0),
            Vec3::new(-h, h, 0.0),
        ],
        Vec3::Z,
    );
    let turn = glam::Quat::from_rotation_y(35f32.to_radians())
        * glam::Quat::from_rotation_x(-20f32.to_radians());
    let centre = Vec3::new(0.0, 0.0, 1.2);
    let corners = [(-0.7, -0.5), (0.7, -0.5), (0.7, 0.5), (-0.7, 0.5)]
        .map(|(x, y)| centre + turn * Vec3::new(x, y, 0.0));
    b.add_flat_polygon(quad, &corners, turn * Vec3::Z);
    let light = SpotLight::aimed(
        Vec3::new(-2.5, 2.5, 4.0),
        Vec3::ZERO,
        Vec3::new(30.0, 30.0, 30.0),
        40.0,
        45.0,
        0.1,
        20.0,
    );
    Scene {
        name: "tilted-quad".into(),
        mesh: b.build(),
        camera: Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 40.0, 0.1, 20.0),
        light,
        ambient: DEFAULT_AMBIENT,
        orbit: None,
        light_path: None,
        objects: Vec::new(),
    }
}

/// Target size of a model placed in the box room: this tall, and at most this wide/deep so
/// it stays clear of the 2 m walls.
pub const BOX_MODEL_HEIGHT: f32 = 0.9;
pub const BOX_MODEL_MAX_WIDTH: f32 = 1.6;

/// `model` scaled uniformly to ~0.9 m tall (narrower if needed to fit), centred on the floor
/// of a white 2 × 2 × 2 m room with red left and green right walls, with the Cornell camera
/// and light.
pub fn box_room(model: &Mesh, name: &str) -> Scene {
    let mut b = MeshBuilder::new();
    let (min, max) = (Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 2.0, 1.0));
    Room::add_to(&mut b, min, max);
    let ext = model.bounds.extent();
    let limits = [
        BOX_MODEL_HEIGHT / ext.y,
        BOX_MODEL_MAX_WIDTH / ext.x,
        BOX_MODEL_MAX_WIDTH / ext.z,
    ];
    // Flat models have a zero extent on some axis (limit = inf); ignore those.
    let scale = limits
        .into_iter()
        .filter(|s| s.is_finite() && *s > 0.0)
        .fold(f32::INFINITY, f32::min);
    let scale = if scale.is_finite() { scale } else { 1.0 };
    let c = model.bounds.center();
    let offset = Vec3::new(-c.x * scale, -model.bounds.min.y * scale, -c.z * scale);
    b.append(model, scale, offset);
    Scene {
        name: format!("box:{name}"),
        mesh: b.build(),
        camera: cornell_camera(),
        light: cornell_light(),
        ambient: DEFAULT_AMBIENT,
        orbit: Some(room_orbit(min, max)),
        light_path: None,
        objects: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_closed_winding(mesh: &Mesh) {
        for t in 0..mesh.triangle_count() {
            let [a, b, c] = mesh.triangle(t);
            let geometric = (b - a).cross(c - a).normalize();
            let i = mesh.indices[3 * t] as usize;
            let shading = Vec3::from(mesh.vertices[i].normal);
            assert!(
                geometric.dot(shading) > 0.999,
                "triangle {t}: {geometric} vs {shading}"
            );
        }
    }

    #[test]
    fn sphere_is_closed_round_and_wound_outwards() {
        let s = sphere();
        assert_eq!(
            s.triangle_count(),
            (2 * SPHERE_RINGS as usize - 2) * SPHERE_SEGMENTS as usize
        );
        for t in 0..s.triangle_count() {
            let [a, b, c] = s.triangle(t);
            let n = (b - a).cross(c - a);
            assert!(n.length() > 1e-6, "triangle {t} has no area");
            assert!(n.dot(a + b + c) > 0.0, "triangle {t} faces inwards");
        }
        for v in &s.vertices {
            assert!((v.pos().length() - 1.0).abs() < 1e-6);
        }
        assert!(s.bounds.min.abs_diff_eq(Vec3::splat(-1.0), 1e-6));
        assert!(s.bounds.max.abs_diff_eq(Vec3::splat(1.0), 1e-6));
    }

    #[test]
    fn cornell_box_layout() {
        let s = cornell_box();
        // 5 walls + 2 boxes × (top + 4 sides), 2 triangles each.
        assert_eq!(s.mesh.triangle_count(), 2 * (5 + 2 * 5));
        assert_eq!(s.mesh.materials.len(), 3);
        assert_eq!(s.mesh.materials[0].diffuse, CORNELL_WHITE);
        assert!(s
            .mesh
            .bounds
            .min
            .abs_diff_eq(Vec3::new(-1.01, 0.0, -1.04), 1e-6));
        assert!(s
            .mesh
            .bounds
            .max
            .abs_diff_eq(Vec3::new(1.0, 1.99, 0.99), 1e-6));
        assert_closed_winding(&s.mesh);
        // From inside, each wall is hit with its shading normal facing the viewer, and the
        // side walls have their colours.
        let inside = Vec3::new(0.0, 1.5, 0.8);
        let cases = [
            (Vec3::NEG_X, -1.01, CORNELL_RED),
            (Vec3::X, 1.0, CORNELL_GREEN),
            (Vec3::NEG_Y, 0.0, CORNELL_WHITE),
            (Vec3::Y, 1.99, CORNELL_WHITE),
            (Vec3::NEG_Z, -1.04, CORNELL_WHITE),
        ];
        for (dir, plane, colour) in cases {
            let hit = s.mesh.raycast(inside, dir, 10.0).unwrap();
            assert!((hit.position.dot(dir.abs()) - plane).abs() < 1e-5, "{dir}");
            assert_eq!(shading_normal(&s.mesh, hit.triangle), -dir);
            let m = s.mesh.material_of_triangle(hit.triangle).unwrap();
            assert_eq!(s.mesh.materials[m].diffuse, colour);
        }
        // The front is open.
        assert!(s.mesh.raycast(inside, Vec3::Z, 10.0).is_none());
    }

    fn shading_normal(mesh: &Mesh, t: usize) -> Vec3 {
        Vec3::from(mesh.vertices[mesh.indices[3 * t] as usize].normal)
    }

    #[test]
    fn cornell_box_boxes_face_out() {
        let s = cornell_box();
        for (fp, h) in [(SHORT_BOX, SHORT_BOX_HEIGHT), (TALL_BOX, TALL_BOX_HEIGHT)] {
            let c: Vec3 = fp
                .iter()
                .map(|&[x, z]| Vec3::new(x, h * 0.5, z))
                .sum::<Vec3>()
                / 4.0;
            let hit = s
                .mesh
                .raycast(Vec3::new(c.x, h + 0.3, c.z), Vec3::NEG_Y, 10.0)
                .unwrap();
            assert!((hit.position.y - h).abs() < 1e-5);
            assert_eq!(shading_normal(&s.mesh, hit.triangle), Vec3::Y);
            // Sideways from the box centre's height, from outside: the side faces face out.
            let side = s.mesh.raycast(c + Vec3::X * 0.6, Vec3::NEG_X, 1.0).unwrap();
            let n = shading_normal(&s.mesh, side.triangle);
            assert!(n.x > 0.0 && n.y == 0.0, "{n}");
        }
    }

    #[test]
    fn pyramids_are_in_view_and_lit() {
        let s = pyramids();
        assert_eq!(s.mesh.triangle_count(), 2 + 9 * 4);
        assert_closed_winding(&s.mesh);
        let vp = s.camera.view_proj(16.0 / 9.0);
        for v in &s.mesh.vertices {
            if v.position[1] > 0.0 {
                let clip = vp * v.pos().extend(1.0);
                let ndc = clip.truncate() / clip.w;
                assert!(
                    ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0,
                    "{:?} -> {ndc}",
                    v.position
                );
            }
        }
        let e = s.light.irradiance(Vec3::ZERO, Vec3::Y);
        assert!(e.x > 1.0 && e.x < 2.0, "{e}");
        let pitch = (s.camera.target - s.camera.position)
            .normalize()
            .y
            .asin()
            .to_degrees();
        assert!((pitch + 30.0).abs() < 0.5, "{pitch}");
    }

    #[test]
    fn box_room_scales_and_centres_the_model() {
        let model = cornell_box().mesh; // any mesh will do: 2.01 × 1.99 × 2.03
        let s = box_room(&model, "test");
        assert_eq!(s.name, "box:test");
        // The room's three materials plus the model's three.
        assert_eq!(s.mesh.materials.len(), 6);
        let placed = &s.mesh.vertices[s.mesh.vertices.len() - model.vertices.len()..];
        let b = crate::scene::mesh::Aabb::from_points(placed.iter().map(|v| v.pos()));
        assert!(b.min.y.abs() < 1e-6);
        assert!(b.extent().max_element() <= BOX_MODEL_MAX_WIDTH + 1e-5);
        assert!(b.center().x.abs() < 1e-5 && b.center().z.abs() < 1e-5);
        assert_closed_winding(&s.mesh);
    }
}

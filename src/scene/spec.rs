//! Turns a scene spec string into a [`Scene`]: built-ins, OBJ paths, asset names, `box:`.

use super::accel::Accel;
use super::builder::MeshBuilder;
use super::camera::Camera;
use super::error::SceneError;
use super::framing::{interior_view, outside_view, InteriorView};
use super::input::not_regular;
use super::light::SpotLight;
use super::mesh::{Material, Mesh};
use super::obj::load_obj;
use super::path::Orbit;
use super::procedural::{box_room, cornell_box, pyramids, tilted_quad, DEFAULT_AMBIENT};
use super::world::Scene;
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Environment variable naming the asset directory (e.g. `../shared/scenes`).
pub const ASSETS_ENV: &str = "SSGI_ASSETS";

/// Scenes built in code; the first is the default.
pub const BUILTIN_SCENES: [&str; 3] = ["cornell-box", "pyramids", "tilted-quad"];

/// Field of view of the automatic camera for a loaded model.
const AUTO_FOV_DEG: f32 = 40.0;

/// The asset directory from `SSGI_ASSETS`, if set and non-empty.
pub fn asset_dir_from_env() -> Option<PathBuf> {
    std::env::var_os(ASSETS_ENV)
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
}

/// Loads a scene from a spec:
/// - `cornell-box` (default), `pyramids` or `tilted-quad`: built in, no files;
/// - a path to an `.obj` file (also tried relative to the asset directory);
/// - an asset name: a sub-folder of the asset directory holding exactly one `.obj`;
/// - `box:<path or asset>`: that model inside a Cornell-style box room.
///
/// Scene files are `scene_load::load_scene`'s, which calls this for everything else.
///
/// `assets` is the asset directory; when None, `SSGI_ASSETS` is used.
pub fn load_spec(spec: &str, assets: Option<&Path>) -> Result<Scene, SceneError> {
    let assets = assets.map(Path::to_path_buf).or_else(asset_dir_from_env);
    let assets = assets.as_deref();
    match spec {
        "cornell-box" => Ok(cornell_box()),
        "pyramids" => Ok(pyramids()),
        "tilted-quad" => Ok(tilted_quad()),
        _ => {
            if let Some(inner) = spec.strip_prefix("box:") {
                let (name, mesh) = load_model(inner, assets)?;
                Ok(box_room(&mesh, &name))
            } else {
                let (name, mesh) = load_model(spec, assets)?;
                if let Some(message) = super::validate::scene_size_problem(mesh.bounds.radius()) {
                    return Err(SceneError::TooSmall {
                        spec: spec.to_string(),
                        message,
                    });
                }
                Ok(framed_model(name, mesh))
            }
        }
    }
}

/// The model a spec names (an OBJ path or an asset name, as [`load_spec`] finds it), alone:
/// its name (the file stem) and its mesh as loaded, with no ground, room or framing.
pub fn load_model(spec: &str, assets: Option<&Path>) -> Result<(String, Mesh), SceneError> {
    let assets = assets.map(Path::to_path_buf).or_else(asset_dir_from_env);
    let path = resolve_model(spec, assets.as_deref())?;
    Ok((model_name(&path), load_obj(&path)?))
}

fn model_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

fn is_obj(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"))
}

/// Finds the OBJ file a spec means. A spec ending in `.obj` is always taken as a file (a
/// missing one is reported by the loader with its path); a path to something that is not a
/// regular file (a FIFO, a device, a directory outside the assets) is refused, saying what
/// it is.
pub fn resolve_model(spec: &str, assets: Option<&Path>) -> Result<PathBuf, SceneError> {
    let as_path = Path::new(spec);
    if as_path.is_file() {
        return Ok(as_path.to_owned());
    }
    if let Some(dir) = assets {
        let in_assets = dir.join(spec);
        if in_assets.is_file() {
            return Ok(in_assets);
        }
        if in_assets.is_dir() && !spec.is_empty() {
            return single_obj_in(spec, &in_assets);
        }
    }
    if let Some(kind) = not_regular(as_path) {
        return Err(SceneError::UnknownScene {
            spec: spec.to_owned(),
            details: format!(
                "{} is {kind}, not a model file (a built-in scene, an OBJ or scene file, \
                 or an asset name)",
                as_path.display()
            ),
        });
    }
    if is_obj(as_path) {
        return Ok(as_path.to_owned());
    }
    Err(unknown_scene(spec, assets))
}

fn obj_files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && is_obj(p))
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    names
}

fn single_obj_in(name: &str, dir: &Path) -> Result<PathBuf, SceneError> {
    let objs = obj_files_in(dir);
    match objs.as_slice() {
        [one] => Ok(dir.join(one)),
        [] => Err(SceneError::UnknownScene {
            spec: name.to_owned(),
            details: format!("the asset folder {} holds no .obj file", dir.display()),
        }),
        _ => Err(SceneError::AmbiguousAsset {
            name: name.to_owned(),
            dir: dir.to_owned(),
            candidates: objs,
        }),
    }
}

/// Asset names available in `dir`: sub-folders holding at least one `.obj`.
pub fn list_assets(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_dir() && !obj_files_in(p).is_empty())
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    names
}

fn unknown_scene(spec: &str, assets: Option<&Path>) -> SceneError {
    let searched = match assets {
        Some(dir) if dir.is_dir() => {
            let names = list_assets(dir);
            let available = if names.is_empty() {
                "none".to_owned()
            } else {
                names.join(", ")
            };
            format!(
                "no asset folder '{spec}' in {} (assets there: {available})",
                dir.display()
            )
        }
        Some(dir) => match not_regular(dir) {
            Some(kind) => format!(
                "the asset directory {} is {kind}, not a directory",
                dir.display()
            ),
            None if dir.exists() => format!(
                "the asset directory {} is a regular file, not a directory",
                dir.display()
            ),
            None => format!("the asset directory {} does not exist", dir.display()),
        },
        None => "no asset directory is set".to_owned(),
    };
    SceneError::UnknownScene {
        spec: spec.to_owned(),
        details: format!(
            "not a built-in scene ({}), not an existing file, and {searched}. \
             Built-ins also take box:<model>. Set the asset directory with --assets DIR \
             or the {ASSETS_ENV} environment variable.",
            BUILTIN_SCENES.join(", ")
        ),
    }
}

/// A loaded model on its own. A model that encloses space (a building) is seen from inside,
/// from the eye point and direction whose view meets the fewest misses and back faces
/// ([`interior_view`]), lit by a headlight at the eye; any other model stands on a grey ground
/// plane twice its footprint ([`with_ground`]), seen by a camera that fits its vertices from
/// the side and height (20 or 35 degrees up) where it covers most of the view
/// ([`outside_view`]), lit by a spot above and in front of the camera. Either light has
/// intensity d² for the distance d to what it lights, so the irradiance there (facing the
/// light) is 1.
pub fn framed_model(name: String, mesh: Mesh) -> Scene {
    let accel = Accel::new(&mesh);
    let (mesh, view) = match interior_view(&mesh, &accel) {
        Some(view) => (mesh, interior(view)),
        None => {
            let ground = with_ground(&mesh);
            let view = outside(&mesh, &accel, &ground.bounds);
            (ground, view)
        }
    };
    Scene {
        name,
        mesh,
        camera: view.camera,
        light: view.light,
        ambient: DEFAULT_AMBIENT,
        orbit: Some(view.orbit),
        light_path: None,
        objects: Vec::new(),
    }
}

/// Camera, light and orbit chosen for a scene's geometry.
pub struct AutoView {
    pub camera: Camera,
    pub light: SpotLight,
    pub orbit: Orbit,
}

/// The automatic view of `mesh` as a whole (scene files without a camera): from inside a
/// building, otherwise from outside, as [`framed_model`] chooses (no ground is added).
pub fn auto_view(mesh: &Mesh) -> AutoView {
    let accel = Accel::new(mesh);
    match interior_view(mesh, &accel) {
        Some(view) => interior(view),
        None => outside(mesh, &accel, &mesh.bounds),
    }
}

fn interior(view: InteriorView) -> AutoView {
    AutoView {
        light: headlight(&view.camera),
        camera: view.camera,
        orbit: view.orbit,
    }
}

/// A spot at `camera`'s eye aimed at its target, its cone covering the square view's
/// corners (half-diagonal angle) with a soft margin; irradiance 1 at the target.
pub fn headlight(camera: &Camera) -> SpotLight {
    let half = (0.5 * camera.vfov_deg).to_radians().tan();
    let outer_deg = ((half * std::f32::consts::SQRT_2).atan().to_degrees() + 5.0).min(89.0);
    unit_spot(camera.position, camera.target, outer_deg, camera)
}

/// The automatic spot: at `position`, aimed at `target`, full intensity inside 0.8 of
/// `outer_deg`, intensity d² for the distance d to the target (irradiance 1 there, facing
/// the light), its shadow map over the camera's depth range.
fn unit_spot(position: Vec3, target: Vec3, outer_deg: f32, camera: &Camera) -> SpotLight {
    let d = position.distance(target);
    SpotLight::aimed(
        position,
        target,
        Vec3::splat(d * d),
        outer_deg * 0.8,
        outer_deg,
        camera.near,
        camera.far,
    )
}

/// Grey albedo of the ground a single model stands on.
const GROUND_ALBEDO: [f32; 3] = [0.6, 0.6, 0.6];

/// How far below the model's foot the ground goes when the model has a face lying there, as
/// a share of the ground's half-width: two coplanar faces z-fight (grey stripes through a
/// flat model on the ground), and 1e-3 of the scene's size is some 20 times the depth
/// buffer's resolution at the automatic camera's distance, yet far below a pixel there.
const GROUND_GAP: f32 = 1e-3;

/// `model` standing on a grey square ground at its foot, twice its largest extent wide
/// (`--scene <model>` for a model that is not a building; scene files' `ground = true`). Where
/// a face of the model lies at its foot (every corner within the gap of it), the ground goes
/// `GROUND_GAP` of its half-width lower, so the two do not z-fight.
pub fn with_ground(model: &Mesh) -> Mesh {
    let b = model.bounds;
    let ext = b.extent();
    let half = ext.x.max(ext.z).max(ext.y);
    let gap = GROUND_GAP * half;
    let lies_at_foot =
        (0..model.triangle_count()).any(|t| model.triangle(t).iter().all(|p| p.y - b.min.y <= gap));
    let c = b.center();
    let y = if lies_at_foot { b.min.y - gap } else { b.min.y };
    let mut builder = MeshBuilder::new();
    builder.append(model, 1.0, Vec3::ZERO);
    let ground = builder.add_material(Material::colour("ground", GROUND_ALBEDO));
    let corner = |dx: f32, dz: f32| Vec3::new(c.x + dx * half, y, c.z + dz * half);
    builder.add_flat_polygon(
        ground,
        &[
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
        ],
        Vec3::Y,
    );
    builder.build()
}

/// `model` seen from outside (its accel `accel`), in a scene whose bounds are
/// `scene_bounds`, lit from 45 degrees up on the camera's side.
fn outside(model: &Mesh, accel: &Accel, scene_bounds: &super::mesh::Aabb) -> AutoView {
    let camera = outside_view(model, accel, AUTO_FOV_DEG, scene_bounds);
    let center = camera.target;
    let radius = model.bounds.radius();
    let distance = (camera.position - center).length();
    let side = camera.position - center;
    let side = Vec3::new(side.x, 0.0, side.z).normalize_or(Vec3::Z);
    let position = center + (side + Vec3::Y).normalize() * distance;
    // Half-angle under which the bounding sphere is seen, plus a margin for the soft edge.
    let sphere_deg = (radius / distance).clamp(0.0, 0.99).asin().to_degrees();
    let outer_deg = (sphere_deg + 5.0).clamp(10.0, 80.0);
    let light = unit_spot(position, center, outer_deg, &camera);
    AutoView {
        camera,
        light,
        orbit: Orbit::around(center),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ground_keeps_clear_of_a_face_at_the_foot() {
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::colour("m", [0.5, 0.5, 0.5]));
        let flat = [
            Vec3::ZERO,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        b.add_flat_polygon(m, &flat, Vec3::Y);
        let ground_y = |mesh: &Mesh| {
            let last = mesh.triangle_count() - 1;
            mesh.triangle(last)[0].y
        };
        // A flat triangle in y = 0: the ground 1e-3 of its half-width (1) below.
        let flat_ground = ground_y(&with_ground(&b.build()));
        assert!((flat_ground + 1e-3).abs() < 1e-7, "{flat_ground}");
        // A tetrahedron standing on a point: the ground touches its foot.
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::colour("m", [0.5, 0.5, 0.5]));
        let apex = Vec3::ZERO;
        let top = [
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(0.0, 1.0, 1.0),
        ];
        for k in 0..3 {
            b.add_flat_polygon(m, &[apex, top[k], top[(k + 1) % 3]], Vec3::Y);
        }
        assert_eq!(ground_y(&with_ground(&b.build())), 0.0);
    }

    #[test]
    fn builtins_need_no_files() {
        for name in BUILTIN_SCENES {
            let s = load_spec(name, Some(Path::new("/nonexistent"))).unwrap();
            assert_eq!(s.name, name);
            assert!(s.mesh.triangle_count() > 0);
        }
    }

    #[test]
    fn unknown_spec_explains_itself() {
        let e = load_spec("teapot", Some(Path::new("/nonexistent-assets"))).unwrap_err();
        assert!(matches!(e, SceneError::UnknownScene { .. }));
        let msg = e.to_string();
        for needle in [
            "teapot",
            "cornell-box",
            "pyramids",
            "/nonexistent-assets",
            "--assets",
        ] {
            assert!(msg.contains(needle), "{needle} missing in: {msg}");
        }
        assert!(msg.contains(ASSETS_ENV));
    }

    /// A 1 x 2 x 1 block, closed, normals out.
    fn block() -> Mesh {
        let mut b = MeshBuilder::new();
        let m = b.add_material(Material::colour("block", [0.5; 3]));
        let v = Vec3::new;
        let (x0, y0, z0, x1, y1, z1) = (-0.5, 0.0, -0.5, 0.5, 2.0, 0.5);
        for (corners, n) in [
            (
                [v(x0, y0, z0), v(x1, y0, z0), v(x1, y0, z1), v(x0, y0, z1)],
                Vec3::NEG_Y,
            ),
            (
                [v(x0, y1, z0), v(x1, y1, z0), v(x1, y1, z1), v(x0, y1, z1)],
                Vec3::Y,
            ),
            (
                [v(x0, y0, z0), v(x1, y0, z0), v(x1, y1, z0), v(x0, y1, z0)],
                Vec3::NEG_Z,
            ),
            (
                [v(x0, y0, z1), v(x1, y0, z1), v(x1, y1, z1), v(x0, y1, z1)],
                Vec3::Z,
            ),
            (
                [v(x0, y0, z0), v(x0, y1, z0), v(x0, y1, z1), v(x0, y0, z1)],
                Vec3::NEG_X,
            ),
            (
                [v(x1, y0, z0), v(x1, y1, z0), v(x1, y1, z1), v(x1, y0, z1)],
                Vec3::X,
            ),
        ] {
            b.add_flat_polygon(m, &corners, n);
        }
        b.build()
    }

    #[test]
    fn a_single_model_stands_on_a_ground_lit_at_unit_irradiance() {
        let model = block();
        let s = framed_model("m".into(), model.clone());
        assert!(matches!(s.orbit(), Orbit::Around { .. }));
        // The ground: two more triangles at the model's foot, twice its footprint (here its
        // height, the largest extent), GROUND_GAP of its half-width (2) below the block's
        // bottom face.
        assert_eq!(s.mesh.triangle_count(), model.triangle_count() + 2);
        assert_eq!(s.mesh.bounds.min, Vec3::new(-2.0, -2.0 * GROUND_GAP, -2.0));
        assert_eq!(s.mesh.bounds.max.y, 2.0);
        let c = s.camera.target;
        let e = s.light.irradiance(c, -s.light.direction);
        assert!(e.abs_diff_eq(Vec3::ONE, 1e-4), "{e}");
        // The cone covers the model.
        let to_corner = (model.bounds.max - s.light.position).normalize();
        assert!(s.light.spot_factor(to_corner) > 0.0);
    }

    #[test]
    fn a_room_is_seen_from_inside_by_a_headlight() {
        let s = framed_model("room".into(), cornell_box().mesh);
        let p = s.camera.position;
        assert!(p.cmpgt(s.mesh.bounds.min).all() && p.cmplt(s.mesh.bounds.max).all());
        assert!(matches!(s.orbit(), Orbit::Inside { .. }));
        assert_eq!(s.light.position, p);
        let e = s.light.irradiance(s.camera.target, -s.light.direction);
        assert!(e.abs_diff_eq(Vec3::ONE, 1e-3), "{e}");
    }
}

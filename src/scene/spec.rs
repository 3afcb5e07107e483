//! Turns a scene spec string into a [`Scene`]: built-ins, OBJ paths, asset names, `box:`.

use super::camera::Camera;
use super::error::SceneError;
use super::light::SpotLight;
use super::mesh::Mesh;
use super::obj::load_obj;
use super::procedural::{box_room, cornell_box, pyramids, DEFAULT_AMBIENT};
use super::world::Scene;
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Environment variable naming the asset directory (e.g. `../shared/scenes`).
pub const ASSETS_ENV: &str = "SSGI_ASSETS";

/// Scenes built in code; the first is the default.
pub const BUILTIN_SCENES: [&str; 2] = ["cornell-box", "pyramids"];

/// Field of view of the automatic camera for a loaded model.
const AUTO_FOV_DEG: f32 = 40.0;

/// The asset directory from `SSGI_ASSETS`, if set and non-empty.
pub fn asset_dir_from_env() -> Option<PathBuf> {
    std::env::var_os(ASSETS_ENV)
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
}

/// Loads a scene from a spec:
/// - `cornell-box` (default) or `pyramids`: built in, no files;
/// - a path to an `.obj` file (also tried relative to the asset directory);
/// - an asset name: a sub-folder of the asset directory holding exactly one `.obj`;
/// - `box:<path or asset>`: that model inside a Cornell-style box room.
///
/// `assets` is the asset directory; when None, `SSGI_ASSETS` is used.
pub fn load_scene(spec: &str, assets: Option<&Path>) -> Result<Scene, SceneError> {
    let assets = assets.map(Path::to_path_buf).or_else(asset_dir_from_env);
    let assets = assets.as_deref();
    match spec {
        "cornell-box" => Ok(cornell_box()),
        "pyramids" => Ok(pyramids()),
        _ => {
            if let Some(inner) = spec.strip_prefix("box:") {
                let path = resolve_model(inner, assets)?;
                let mesh = load_obj(&path)?;
                Ok(box_room(&mesh, &model_name(&path)))
            } else {
                let path = resolve_model(spec, assets)?;
                let mesh = load_obj(&path)?;
                Ok(framed_model(model_name(&path), mesh))
            }
        }
    }
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
/// missing one is reported by the loader with its path).
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
        Some(dir) => format!("the asset directory {} does not exist", dir.display()),
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

/// A loaded model on its own: camera on +Z framing its bounding sphere, a spot light above
/// and in front aimed at the centre whose cone covers the bounds, with intensity = d² so the
/// irradiance at the centre (on a surface facing the light) is 1.
pub fn framed_model(name: String, mesh: Mesh) -> Scene {
    let camera = Camera::framing(&mesh.bounds, AUTO_FOV_DEG);
    let center = mesh.bounds.center();
    let radius = mesh.bounds.radius();
    let distance = (camera.position - center).length();
    let position = center + Vec3::new(0.0, 1.0, 1.0).normalize() * distance;
    // Half-angle under which the bounding sphere is seen, plus a margin for the soft edge.
    let sphere_deg = (radius / distance).clamp(0.0, 0.99).asin().to_degrees();
    let outer_deg = (sphere_deg + 5.0).clamp(10.0, 80.0);
    let light = SpotLight::aimed(
        position,
        center,
        Vec3::splat(distance * distance),
        outer_deg * 0.8,
        outer_deg,
        camera.near,
        camera.far,
    );
    Scene {
        name,
        mesh,
        camera,
        light,
        ambient: DEFAULT_AMBIENT,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_need_no_files() {
        for name in BUILTIN_SCENES {
            let s = load_scene(name, Some(Path::new("/nonexistent"))).unwrap();
            assert_eq!(s.name, name);
            assert!(s.mesh.triangle_count() > 0);
        }
    }

    #[test]
    fn unknown_spec_explains_itself() {
        let e = load_scene("teapot", Some(Path::new("/nonexistent-assets"))).unwrap_err();
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

    #[test]
    fn framed_model_light_gives_unit_irradiance() {
        let mesh = cornell_box().mesh;
        let s = framed_model("m".into(), mesh);
        let c = s.mesh.bounds.center();
        let e = s.light.irradiance(c, -s.light.direction);
        assert!(e.abs_diff_eq(Vec3::ONE, 1e-4), "{e}");
        // The cone covers the bounding sphere.
        let to_corner = (s.mesh.bounds.max - s.light.position).normalize();
        assert!(s.light.spot_factor(to_corner) > 0.0);
    }
}

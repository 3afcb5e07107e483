//! A scene file ([`SceneFile`]) made into a [`Scene`] with its camera and light paths, and
//! any loaded scene described back as a file whose every value is explicit (`--save-scene`),
//! so that loading what was saved gives the same scene.

use super::builder::MeshBuilder;
use super::camera::Camera;
use super::error::SceneError;
use super::light::{check_intensity, LightKind, SpotLight};
use super::mesh::{Aabb, Mesh};
use super::object::{euler_deg, DynamicObject};
use super::path::{CameraPath, LightPath, Orbit};
use super::procedural::{sphere, DEFAULT_AMBIENT};
use super::scene_file::{
    CameraEntry, LightEntry, MeshEntry, OrbitEntry, SceneFile, DEFAULT_OUTER_DEG, SPHERE,
};
use super::spec::{
    auto_view, framed_model, headlight, load_model, load_spec, with_ground, AutoView,
};
use super::toml_locate::locate;
use super::world::Scene;
use glam::{Quat, Vec3};
use std::path::{Path, PathBuf};

/// Field of view of a scene file's camera without one.
pub const DEFAULT_FOV_DEG: f32 = 40.0;

/// Depth range of a camera or light without one: far reaches the scene's farthest corner
/// (5% margin), near is this fraction of far (1:1000 keeps 24-bit depth and the shadow map's
/// comparisons precise at every scale, since both planes scale with the scene).
const AUTO_NEAR_OF_FAR: f32 = 1e-3;

/// A scene with the paths its file gives, and the mesh entries it was made of (model specs
/// that name files made absolute, so the description holds wherever it is saved).
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub scene: Scene,
    pub meshes: Vec<MeshEntry>,
    pub camera_path: Option<CameraPath>,
}

/// Whether a scene spec names a scene file.
pub fn is_scene_file(spec: &str) -> bool {
    Path::new(spec)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
}

/// Loads a scene from a spec: a scene file (`.toml`), or a built-in scene, OBJ path, asset
/// name or `box:<model>` ([`load_spec`]). `assets` is the asset directory; when None,
/// `SSGI_ASSETS` is used.
pub fn load_scene(spec: &str, assets: Option<&Path>) -> Result<Scene, SceneError> {
    if is_scene_file(spec) {
        return Ok(load_scene_file(Path::new(spec), assets)?.scene);
    }
    load_spec(spec, assets)
}

/// Any scene spec with the paths its file brings: a scene file, or what [`load_spec`] takes
/// (described as one mesh entry).
pub fn load(spec: &str, assets: Option<&Path>) -> Result<LoadedScene, SceneError> {
    if is_scene_file(spec) {
        return load_scene_file(Path::new(spec), assets);
    }
    let mut scene = load_spec(spec, assets)?;
    // Explicit, as a scene file's always is (the same orbit either way).
    scene.orbit = Some(scene.orbit());
    // A model that is not a building stands on its ground (`framed_model`), and its orbit goes
    // around it; the built-in scenes and rooms bring their own geometry.
    let model = !super::spec::BUILTIN_SCENES.contains(&spec) && !spec.starts_with("box:");
    let ground = model && matches!(scene.orbit, Some(Orbit::Around { .. }));
    let entry = MeshEntry {
        model: absolute_if_file(spec, None),
        ground: ground.then_some(true),
        ..Default::default()
    };
    Ok(LoadedScene {
        scene,
        meshes: vec![entry],
        camera_path: None,
    })
}

/// Reads, checks and builds the scene file at `path`; relative model and path files are
/// looked up beside it first.
pub fn load_scene_file(path: &Path, assets: Option<&Path>) -> Result<LoadedScene, SceneError> {
    let (file, text) = SceneFile::read_with_text(path)?;
    build_located(&file, Some(&text), path, assets)
}

/// A mesh entry's spec with a file it names (beside the scene file first) made absolute.
fn absolute_if_file(spec: &str, dir: Option<&Path>) -> String {
    let beside = dir.map(|d| d.join(spec)).filter(|p| p.is_file());
    let file = beside.or_else(|| Some(PathBuf::from(spec)).filter(|p| p.is_file()));
    match file.and_then(|p| p.canonicalize().ok()) {
        Some(p) => p.display().to_string(),
        None => spec.to_owned(),
    }
}

/// Builds a parsed scene file; `origin` is the file it came from (errors, relative paths).
pub fn build(
    file: &SceneFile,
    origin: &Path,
    assets: Option<&Path>,
) -> Result<LoadedScene, SceneError> {
    build_located(file, None, origin, assets)
}

/// [`build`], with the file's `text` when there is one to give errors their line.
fn build_located(
    file: &SceneFile,
    text: Option<&str>,
    origin: &Path,
    assets: Option<&Path>,
) -> Result<LoadedScene, SceneError> {
    let dir = origin.parent();
    let in_file = |key: String, e: SceneError| SceneError::SceneFile {
        path: origin.to_owned(),
        line: None,
        key,
        message: e.to_string(),
    };
    let mut builder = MeshBuilder::new();
    let mut meshes = Vec::with_capacity(file.meshes.len());
    let mut objects = Vec::new();
    // A file of one model left where it is takes the view `--scene <model>` gives it.
    let lone = file.meshes.len() == 1 && untransformed(&file.meshes[0]);
    let wants_view = lone && (file.camera.is_none() || file.orbit.is_none());
    let mut lone_view = None;
    for (i, entry) in file.meshes.iter().enumerate() {
        let model = absolute_if_file(&entry.model, dir);
        let (mesh, view) = entry_mesh(&model, entry.ground == Some(true), assets, wants_view)
            .map_err(|e| in_file(format!("mesh[{i}].model"), e))?;
        lone_view = view;
        let scale = entry.scale.unwrap_or(1.0);
        if entry.keyframes.is_empty() {
            let rotation = euler_deg(entry.rotation_deg.unwrap_or_default());
            let offset = Vec3::from(entry.position.unwrap_or_default());
            builder.append_placed(&mesh, scale, rotation, offset, entry.albedo);
        } else {
            // A moving object keeps its own space; its keys place it each frame.
            let mut own = MeshBuilder::new();
            own.append_placed(&mesh, scale, Quat::IDENTITY, Vec3::ZERO, entry.albedo);
            objects.push(DynamicObject {
                name: format!("mesh[{i}] {}", entry.model),
                mesh: own.build(),
                keys: entry.keyframes.clone(),
            });
        }
        meshes.push(MeshEntry {
            model,
            ..entry.clone()
        });
    }
    let mesh = builder.build();
    if mesh.triangle_count() == 0 {
        return Err(in_file(
            "mesh".into(),
            SceneError::UnknownScene {
                spec: origin.display().to_string(),
                details: "nothing stands still: at least one mesh must have no keyframes".into(),
            },
        ));
    }
    // Bounds of everything, moving objects wherever they go: depth ranges reach all of it.
    let mut bounds = mesh.bounds;
    for o in &objects {
        let s = o.swept_bounds();
        bounds.grow(s.min);
        bounds.grow(s.max);
    }
    if let Some(message) = super::validate::scene_size_problem(bounds.radius()) {
        // Said at the first scale that shrinks a mesh, if one does.
        let scaled = file
            .meshes
            .iter()
            .position(|m| m.scale.is_some_and(|s| s < 1.0));
        return Err(SceneError::SceneFile {
            path: origin.to_owned(),
            line: scaled.and_then(|i| text.and_then(|t| locate(t, "mesh", i, "scale").0)),
            key: scaled.map_or("mesh".into(), |i| format!("mesh[{i}].scale")),
            message,
        });
    }
    // A light's intensity is bounded by the scene's size (`light::max_intensity`).
    if let Some(i) = file.light.as_ref().and_then(|l| l.intensity) {
        check_intensity(i, bounds.radius()).map_err(|message| SceneError::SceneFile {
            path: origin.to_owned(),
            line: text.and_then(|t| locate(t, "light", 0, "intensity").0),
            key: "light.intensity".into(),
            message,
        })?;
    }
    // The automatic view costs ray casts over the whole mesh: only when something is missing.
    // (A missing light with a camera given is a headlight at that camera.)
    let auto: Option<AutoView> = (file.camera.is_none() || file.orbit.is_none())
        .then(|| lone_view.unwrap_or_else(|| auto_view(&mesh)));
    let camera = match (&file.camera, &auto) {
        (Some(c), _) => camera(c, &bounds),
        (None, Some(a)) => a.camera,
        (None, None) => unreachable_auto(),
    };
    let light_path =
        (!file.light_keyframes.is_empty()).then(|| LightPath::new(file.light_keyframes.clone()));
    let light = match (&file.light, &file.camera, &auto) {
        (Some(l), _, _) => light(l, &bounds, light_path.as_ref()),
        (None, Some(_), _) => headlight(&camera),
        (None, None, Some(a)) => a.light,
        (None, None, None) => unreachable_auto(),
    };
    let orbit = match (&file.orbit, &auto) {
        (Some(o), _) => orbit(o),
        (None, Some(a)) => a.orbit,
        (None, None) => unreachable_auto(),
    };
    let camera_path = camera_path(file, dir).map_err(|e| in_file("camera_path".into(), e))?;
    let name = file.name.clone().unwrap_or_else(|| {
        origin
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
    });
    Ok(LoadedScene {
        scene: Scene {
            name,
            mesh,
            camera,
            light,
            ambient: file.ambient.map_or(DEFAULT_AMBIENT, Vec3::from),
            orbit: Some(orbit),
            light_path,
            objects,
        },
        meshes,
        camera_path,
    })
}

/// The automatic view is computed whenever a part that needs it is missing.
fn unreachable_auto() -> ! {
    unreachable!("the automatic view is computed when camera, light or orbit is missing")
}

/// Whether a mesh entry leaves its model where `--scene` puts it: no transform, no keys.
fn untransformed(m: &MeshEntry) -> bool {
    m.position.is_none() && m.rotation_deg.is_none() && m.scale.is_none() && m.keyframes.is_empty()
}

/// The geometry a mesh entry names: the sphere, or a scene spec's mesh (on its ground when
/// `ground`); with `view`, also the camera, light and orbit `--scene <model>` gives it (a
/// built-in scene's own, a model's automatic framing; none for the sphere).
fn entry_mesh(
    model: &str,
    ground: bool,
    assets: Option<&Path>,
    view: bool,
) -> Result<(Mesh, Option<AutoView>), SceneError> {
    let (mesh, view) = if model == SPHERE {
        (sphere(), None)
    } else if is_scene_file(model) {
        return Err(SceneError::UnknownScene {
            spec: model.to_owned(),
            details: "a mesh entry names a model, not another scene file".into(),
        });
    } else if super::spec::BUILTIN_SCENES.contains(&model) || model.starts_with("box:") {
        let scene = load_spec(model, assets)?;
        let seen = view.then(|| AutoView {
            camera: scene.camera,
            light: scene.light,
            orbit: scene.orbit(),
        });
        (scene.mesh, seen)
    } else {
        let (name, mesh) = load_model(model, assets)?;
        let seen = view.then(|| {
            let scene = framed_model(name, mesh.clone());
            AutoView {
                camera: scene.camera,
                light: scene.light,
                orbit: scene.orbit(),
            }
        });
        (mesh, seen)
    };
    let mesh = if ground { with_ground(&mesh) } else { mesh };
    Ok((mesh, view))
}

/// Distance from `p` to the farthest corner of `bounds`.
pub fn reach(p: Vec3, bounds: &Aabb) -> f32 {
    (0..8)
        .map(|i| {
            let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
            p.distance(Vec3::new(
                pick(1, bounds.min.x, bounds.max.x),
                pick(2, bounds.min.y, bounds.max.y),
                pick(4, bounds.min.z, bounds.max.z),
            ))
        })
        .fold(0.0f32, f32::max)
}

/// Near and far reaching the whole scene from every point of `from`.
fn auto_range(from: impl IntoIterator<Item = Vec3>, bounds: &Aabb) -> (f32, f32) {
    let far = 1.05
        * from
            .into_iter()
            .map(|p| reach(p, bounds))
            .fold(0.0, f32::max);
    // An empty or point-sized scene still gets a valid range; any other keeps its own scale
    // (an absolute floor put a 1e-11-scale model behind the near plane: a black image).
    let far = if far > 0.0 && far.is_finite() {
        far
    } else {
        1e-3
    };
    (AUTO_NEAR_OF_FAR * far, far)
}

fn camera(c: &CameraEntry, bounds: &Aabb) -> Camera {
    let position = Vec3::from(c.position);
    let (near, far) = match (c.near, c.far) {
        (Some(n), Some(f)) => (n, f),
        _ => auto_range([position], bounds),
    };
    Camera {
        position,
        target: Vec3::from(c.target),
        up: c.up.map_or(Vec3::Y, Vec3::from),
        vfov_deg: c.fov_deg.unwrap_or(DEFAULT_FOV_DEG),
        near,
        far,
    }
}

/// The light a light entry describes, by its kind.
fn light(l: &LightEntry, bounds: &Aabb, path: Option<&LightPath>) -> SpotLight {
    match l.kind {
        LightKind::Spot => spot(l, bounds, path),
    }
}

/// The spot a light entry describes; without a depth range its shadow map reaches the whole
/// scene from the light and from every key of its path.
fn spot(l: &LightEntry, bounds: &Aabb, path: Option<&LightPath>) -> SpotLight {
    let position = Vec3::from(l.position);
    let (direction, aim) = match (l.target, l.direction) {
        (Some(t), _) => {
            let t = Vec3::from(t);
            ((t - position).normalize_or(Vec3::NEG_Y), t)
        }
        // Along the axis, as far as the scene's centre is.
        (None, d) => {
            let d = Vec3::from(d.unwrap_or([0.0, -1.0, 0.0]));
            let along = (bounds.center() - position).dot(d.normalize_or(Vec3::NEG_Y));
            (d, position + d.normalize_or(Vec3::NEG_Y) * along.max(0.0))
        }
    };
    let outer_deg = l.outer_deg.unwrap_or(DEFAULT_OUTER_DEG);
    // Irradiance 1 at the aim point, facing the light; a light at its aim point gets 1.
    let d = position.distance(aim);
    let intensity = l
        .intensity
        .map_or(Vec3::splat(if d > 0.0 { d * d } else { 1.0 }), Vec3::from);
    let (near, far) = match (l.near, l.far) {
        (Some(n), Some(f)) => (n, f),
        _ => {
            let keys = path.map(|p| p.keys().iter().map(|k| Vec3::from(k.position)));
            auto_range(
                std::iter::once(position).chain(keys.into_iter().flatten()),
                bounds,
            )
        }
    };
    SpotLight {
        position,
        direction,
        intensity,
        inner_deg: l.inner_deg.unwrap_or(0.8 * outer_deg),
        outer_deg,
        near,
        far,
    }
}

fn orbit(o: &OrbitEntry) -> Orbit {
    match *o {
        OrbitEntry::Around { center } => Orbit::Around {
            center: center.into(),
        },
        OrbitEntry::Inside {
            center,
            radius,
            height,
            start,
            open_towards,
        } => Orbit::Inside {
            center: center.into(),
            radius,
            height,
            start: start.into(),
            open_towards: open_towards.map(Vec3::from),
        },
    }
}

/// The file's camera path: inline keyframes, or a spec whose keyframe file is looked up
/// beside the scene file first.
fn camera_path(file: &SceneFile, dir: Option<&Path>) -> Result<Option<CameraPath>, SceneError> {
    if !file.camera_keyframes.is_empty() {
        return Ok(Some(CameraPath::Keyframes(file.camera_keyframes.clone())));
    }
    let Some(spec) = &file.camera_path else {
        return Ok(None);
    };
    let beside = dir.map(|d| d.join(spec)).filter(|p| p.is_file());
    match beside {
        Some(p) => CameraPath::from_file(&p).map(Some),
        None => CameraPath::parse(spec).map(Some),
    }
}

impl LoadedScene {
    /// The scene as a file with every value explicit: loading it gives this scene again.
    pub fn describe(&self) -> SceneFile {
        let s = &self.scene;
        let c = &s.camera;
        let l = &s.light;
        let v = |v: Vec3| v.to_array();
        let (camera_path, camera_keyframes) = match &self.camera_path {
            Some(CameraPath::Keyframes(k)) => (None, k.clone()),
            Some(p) => (Some(p.name()), Vec::new()),
            None => (None, Vec::new()),
        };
        SceneFile {
            name: Some(s.name.clone()),
            ambient: Some(v(s.ambient)),
            camera_path,
            camera_keyframes,
            light_keyframes: s
                .light_path
                .as_ref()
                .map(|p| p.keys().to_vec())
                .unwrap_or_default(),
            meshes: self.meshes.clone(),
            camera: Some(CameraEntry {
                position: v(c.position),
                target: v(c.target),
                up: Some(v(c.up)),
                fov_deg: Some(c.vfov_deg),
                near: Some(c.near),
                far: Some(c.far),
            }),
            light: Some(LightEntry {
                kind: LightKind::Spot,
                position: v(l.position),
                target: None,
                direction: Some(v(l.direction)),
                outer_deg: Some(l.outer_deg),
                inner_deg: Some(l.inner_deg),
                intensity: Some(v(l.intensity)),
                near: Some(l.near),
                far: Some(l.far),
            }),
            orbit: Some(match s.orbit() {
                Orbit::Around { center } => OrbitEntry::Around { center: v(center) },
                Orbit::Inside {
                    center,
                    radius,
                    height,
                    open_towards,
                    start,
                } => OrbitEntry::Inside {
                    center: v(center),
                    radius,
                    height,
                    start: v(start),
                    open_towards: open_towards.map(v),
                },
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    fn temp_dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("ssgi-scene-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    const BALL_IN_BOX: &str = r#"
name = "ball"
[[mesh]]
model = "cornell-box"
[[mesh]]
model = "sphere"
position = [0.3, 0.8, 0.4]
scale = 0.15
albedo = [0.8, 0.2, 0.1]
[camera]
position = [0, 1, 3.4]
target = [0, 1, 0]
[light]
position = [0, 1.9, 0]
target = [0, 0, 0]
outer_deg = 60
[[light_keyframes]]
time = 0
position = [0, 1.9, 0]
target = [0, 0, 0]
[[light_keyframes]]
time = 2
position = [0.5, 1.9, 0]
target = [-0.5, 0, 0]
"#;

    #[test]
    fn a_file_builds_its_meshes_camera_and_light() {
        let dir = temp_dir("build");
        let path = write(&dir, "ball.toml", BALL_IN_BOX);
        let loaded = load_scene_file(&path, None).unwrap();
        let s = &loaded.scene;
        let cornell = super::super::procedural::cornell_box();
        let ball = sphere();
        assert_eq!(
            s.mesh.triangle_count(),
            cornell.mesh.triangle_count() + ball.triangle_count()
        );
        // The sphere is placed: its bounds are the centre +- the radius.
        let tail = &s.mesh.vertices[cornell.mesh.vertices.len()..];
        for v in tail {
            let d = v.pos().distance(Vec3::new(0.3, 0.8, 0.4));
            assert!((d - 0.15).abs() < 1e-5, "{d}");
        }
        let red = s
            .mesh
            .materials
            .iter()
            .filter(|m| m.diffuse == [0.8, 0.2, 0.1]);
        assert_eq!(red.count(), 1);
        assert_eq!(s.camera.vfov_deg, DEFAULT_FOV_DEG);
        assert!(s.camera.far >= reach(s.camera.position, &s.mesh.bounds));
        // Irradiance 1 at the target; the shadow map reaches the scene from every key.
        let e = s.light.irradiance(Vec3::ZERO, Vec3::Y);
        assert!(e.abs_diff_eq(Vec3::ONE, 1e-4), "{e}");
        assert_eq!((s.light.inner_deg, s.light.outer_deg), (48.0, 60.0));
        assert!(s.light.far >= reach(Vec3::new(0.5, 1.9, 0.0), &s.mesh.bounds));
        let p = s.light_path.as_ref().unwrap();
        let mid = p.light_at(&s.light, 1.0);
        assert!(mid.position.abs_diff_eq(Vec3::new(0.25, 1.9, 0.0), 1e-6));
    }

    #[test]
    fn a_saved_scene_loads_as_the_same_scene() {
        let dir = temp_dir("roundtrip");
        let path = write(&dir, "ball.toml", BALL_IN_BOX);
        let first = load_scene_file(&path, None).unwrap();
        let saved = write(&dir, "saved.toml", &first.describe().to_toml());
        let second = load_scene_file(&saved, None).unwrap();
        assert_eq!(second.scene, first.scene);
        assert_eq!(second.meshes, first.meshes);
        assert_eq!(second.describe(), first.describe());
        // A built-in scene by name, and the automatic view of a file without camera or light.
        for spec in ["cornell-box", "pyramids"] {
            let a = load(spec, None).unwrap();
            let p = write(&dir, &format!("{spec}.toml"), &a.describe().to_toml());
            assert_eq!(load_scene_file(&p, None).unwrap().scene, a.scene, "{spec}");
        }
        let auto = write(&dir, "auto.toml", "[[mesh]]\nmodel = \"pyramids\"\n");
        let a = load_scene_file(&auto, None).unwrap();
        let p = write(&dir, "auto-saved.toml", &a.describe().to_toml());
        assert_eq!(load_scene_file(&p, None).unwrap().scene, a.scene);
    }

    /// A file of one built-in scene, or one model on its ground, is the scene `--scene` gives
    /// (but for the name, the file's stem).
    #[test]
    fn a_lone_model_is_framed_as_by_name() {
        let dir = temp_dir("lone");
        for spec in ["cornell-box", "tilted-quad"] {
            let p = write(
                &dir,
                "lone.toml",
                &format!("[[mesh]]\nmodel = \"{spec}\"\n"),
            );
            let file = load_scene_file(&p, None).unwrap().scene;
            let named = load(spec, None).unwrap().scene;
            assert_eq!(
                (file.camera, file.light, file.orbit(), file.mesh),
                (named.camera, named.light, named.orbit(), named.mesh),
                "{spec}"
            );
        }
        // Moved, it is a scene of its own: the automatic framing.
        let p = write(
            &dir,
            "moved.toml",
            "[[mesh]]\nmodel = \"cornell-box\"\nposition = [0, 0, 0]\n",
        );
        let moved = load_scene_file(&p, None).unwrap().scene;
        assert_ne!(
            moved.camera,
            load("cornell-box", None).unwrap().scene.camera
        );
    }

    /// A light far too bright for the scene's size is refused at its line, as
    /// `--light-intensity` is; a large model's own light (intensity d²) is not.
    #[test]
    fn a_light_too_bright_for_the_scene_is_refused() {
        let dir = temp_dir("bright");
        let text = |i: &str| {
            format!(
                "[[mesh]]\nmodel = \"cornell-box\"\n[light]\nposition = [0, 1.9, 0]\n\
                 target = [0, 0, 0]\nintensity = [{i}, 1, 1]\n"
            )
        };
        let p = write(&dir, "bright.toml", &text("1e30"));
        let e = load_scene_file(&p, None).unwrap_err().to_string();
        assert!(
            e.contains("bright.toml:6: light.intensity: [1e30, 1.0, 1.0] W/sr is more than"),
            "{e}"
        );
        let p = write(&dir, "fine.toml", &text("2e7"));
        load_scene_file(&p, None).unwrap();
        let big = write(
            &dir,
            "big.toml",
            "[[mesh]]\nmodel = \"sphere\"\nscale = 1e4\n[light]\nposition = [0, 3e4, 0]\n\
             target = [0, 0, 0]\n",
        );
        let s = load_scene_file(&big, None).unwrap().scene;
        assert_eq!(s.light.intensity, Vec3::splat(9e8));
    }

    #[test]
    fn a_missing_model_names_the_entry() {
        let dir = temp_dir("missing");
        let path = write(
            &dir,
            "bad.toml",
            "[[mesh]]\nmodel = \"cornell-box\"\n[[mesh]]\nmodel = \"nowhere.obj\"\n",
        );
        let e = load_scene_file(&path, None).unwrap_err().to_string();
        assert!(e.contains("bad.toml: mesh[1].model:"), "{e}");
        assert!(e.contains("nowhere.obj"), "{e}");
    }
}

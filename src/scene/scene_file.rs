//! Scene files (TOML): what a scene is made of and where its camera and light are, as a
//! user writes it. Parsing and checking only; `scene_load.rs` turns a file into a [`Scene`]
//! and back.
//!
//! ```toml
//! name = "sponza"                    # optional: the file's stem
//! ambient = [0.03, 0.03, 0.03]       # optional
//! camera_path = "../paths/sponza.json"  # optional: static, orbit[:S], dolly[:S], keyframe file
//!
//! [[mesh]]                           # one or more
//! model = "sponza"                   # what --scene takes, or the built-in shape "sphere"
//! position = [0, 0, 0]               # optional translation
//! rotation_deg = [0, 90, 0]          # optional, about x, then y, then z
//! scale = 1.0                        # optional, uniform
//! ground = true                      # optional: on the ground `--scene <model>` gives it
//! albedo = [0.8, 0.1, 0.1]           # optional: every material this colour, untextured
//! [[mesh.keyframes]]                 # optional: a moving object (time, position, rotation_deg)
//!
//! [camera]                           # optional: automatic framing
//! position = [..]
//! target = [..]
//! fov_deg = 40                       # optional
//! near = 0.05                        # optional pair: automatic from the scene's size
//! far = 50
//!
//! [light]                            # optional: automatic, a headlight at the camera
//! kind = "spot"                      # optional: spot (LightKind's names)
//! position = [..]
//! target = [..]                      # or direction = [..]
//! outer_deg = 45                     # optional; inner_deg: 0.8 x outer
//! intensity = [1, 1, 1]              # optional: irradiance 1 at the target, facing it
//!
//! [[light_keyframes]]                # optional light path: time (s), position, target
//! ```
//!
//! Errors name the file, the line and the key (`file:line: key: message`).

use super::error::SceneError;
use super::light::LightKind;
use super::object::ObjectKey;
use super::path::Keyframe;
use super::toml_locate::{key_at, locate};
use super::validate::HUGE_COORDINATE;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One mesh of the scene: a model and where it stands.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshEntry {
    /// A scene spec (`--scene`: built-in scene, asset name, OBJ path relative to the file
    /// first, `box:<model>`) whose geometry is taken, or [`SPHERE`].
    pub model: String,
    /// Stand the model on the grey ground `--scene <model>` gives a model that is not a
    /// building (a square twice its largest extent at its foot).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<bool>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f32; 3]>,
    /// Euler angles in degrees, applied about x, then y, then z.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation_deg: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f32>,
    /// Linear diffuse albedo replacing every material's (textures dropped).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<[f32; 3]>,
    /// A moving object's path (`[[mesh.keyframes]]`: time, position, rotation_deg); its
    /// keys place it, so `position` and `rotation_deg` are not given with them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keyframes: Vec<ObjectKey>,
}

/// The built-in shape a mesh entry may name: a sphere of radius 1 at the origin.
pub const SPHERE: &str = "sphere";

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraEntry {
    pub position: [f32; 3],
    pub target: [f32; 3],
    /// Up direction (default +y).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<[f32; 3]>,
    /// Full vertical field of view (default 40).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub near: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub far: Option<f32>,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightEntry {
    /// Which kind of light (`spot`, the default): the names are `LightKind`'s.
    #[serde(default, skip_serializing_if = "is_default")]
    pub kind: LightKind,
    pub position: [f32; 3],
    /// Aim: a point (`target`) or an axis (`direction`), exactly one of them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<[f32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f32; 3]>,
    /// Half-angle outside which the spot is dark (default 45).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_deg: Option<f32>,
    /// Half-angle inside which it is at full intensity (default 0.8 x outer).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_deg: Option<f32>,
    /// Radiant intensity on the axis, W/sr per RGB channel (default: irradiance 1 at the
    /// target, or at the scene's centre along the axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intensity: Option<[f32; 3]>,
    /// Shadow-map depth range (default: the whole scene from the light).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub near: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub far: Option<f32>,
}

/// Where `--path orbit` goes (default: chosen with the automatic framing).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    tag = "kind",
    rename_all = "lowercase",
    deny_unknown_fields,
    try_from = "OrbitKeys"
)]
pub enum OrbitEntry {
    /// A full turn about the vertical axis through `center`.
    Around { center: [f32; 3] },
    /// Inside a room: on a circle of `radius` at `height` around `center`'s vertical axis.
    Inside {
        center: [f32; 3],
        radius: f32,
        height: f32,
        start: [f32; 3],
        #[serde(default, skip_serializing_if = "Option::is_none")]
        open_towards: Option<[f32; 3]>,
    },
}

/// `[orbit]` as written, every key of either kind: read key by key, so a wrong type is
/// reported at its key's line (an internally tagged enum reads the table whole first and
/// loses its keys' places), then made an [`OrbitEntry`] (errors at the table's line).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OrbitKeys {
    kind: String,
    center: Option<[f32; 3]>,
    radius: Option<f32>,
    height: Option<f32>,
    start: Option<[f32; 3]>,
    open_towards: Option<[f32; 3]>,
}

impl TryFrom<OrbitKeys> for OrbitEntry {
    type Error = String;

    fn try_from(k: OrbitKeys) -> Result<Self, String> {
        let need = |key: &str| format!("kind = \"{}\" needs `{key}`", k.kind);
        match k.kind.as_str() {
            "around" => {
                for (key, given) in [
                    ("radius", k.radius.is_some()),
                    ("height", k.height.is_some()),
                    ("start", k.start.is_some()),
                    ("open_towards", k.open_towards.is_some()),
                ] {
                    if given {
                        return Err(format!(
                            "kind = \"around\" takes only `center`, not `{key}`"
                        ));
                    }
                }
                Ok(Self::Around {
                    center: k.center.ok_or_else(|| need("center"))?,
                })
            }
            "inside" => Ok(Self::Inside {
                center: k.center.ok_or_else(|| need("center"))?,
                radius: k.radius.ok_or_else(|| need("radius"))?,
                height: k.height.ok_or_else(|| need("height"))?,
                start: k.start.ok_or_else(|| need("start"))?,
                open_towards: k.open_towards,
            }),
            other => Err(format!("kind {other:?}: expected \"around\" or \"inside\"")),
        }
    }
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ambient: Option<[f32; 3]>,
    /// A camera path spec (`--path`); a keyframe file is relative to the scene file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_path: Option<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub camera_keyframes: Vec<Keyframe>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub light_keyframes: Vec<Keyframe>,
    #[serde(rename = "mesh", default)]
    pub meshes: Vec<MeshEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub light: Option<LightEntry>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orbit: Option<OrbitEntry>,
}

/// A value's problem, with the table and key it sits under (`mesh` index for arrays).
struct Fault {
    table: &'static str,
    index: usize,
    key: &'static str,
    message: String,
}

fn fault(table: &'static str, index: usize, key: &'static str, message: String) -> Fault {
    Fault {
        table,
        index,
        key,
        message,
    }
}

impl SceneFile {
    /// Parses and checks `text`, the contents of `path` (named in errors).
    pub fn parse(path: &Path, text: &str) -> Result<Self, SceneError> {
        let file: SceneFile = toml::from_str(text).map_err(|e| {
            let offset = e.span().map_or(0, |s| s.start);
            let (line, key) = key_at(text, offset);
            SceneError::SceneFile {
                path: path.to_owned(),
                line,
                key,
                message: e.message().trim().to_owned(),
            }
        })?;
        file.check().map_err(|f| {
            let (line, key) = locate(text, f.table, f.index, f.key);
            SceneError::SceneFile {
                path: path.to_owned(),
                line,
                key,
                message: f.message,
            }
        })?;
        Ok(file)
    }

    /// Reads and parses the file at `path`.
    pub fn read(path: &Path) -> Result<Self, SceneError> {
        Self::read_with_text(path).map(|(file, _)| file)
    }

    /// Reads and parses the file at `path`, keeping its text (to locate later errors).
    pub fn read_with_text(path: &Path) -> Result<(Self, String), SceneError> {
        let text = super::input::read_regular_text(path).map_err(|source| SceneError::Io {
            path: path.to_owned(),
            source,
        })?;
        Ok((Self::parse(path, &text)?, text))
    }

    /// The file's text (TOML).
    pub fn to_toml(&self) -> String {
        // Every field is a plain value, an array or a table of them: serializing cannot fail.
        toml::to_string(self).unwrap_or_else(|e| format!("# cannot write the scene: {e}\n"))
    }

    fn check(&self) -> Result<(), Fault> {
        if self.meshes.is_empty() {
            return Err(fault(
                "",
                0,
                "mesh",
                "no [[mesh]] table: a scene needs at least one mesh".into(),
            ));
        }
        if let Some(a) = self.ambient {
            colour(a).map_err(|m| fault("", 0, "ambient", m))?;
        }
        if self.camera_path.is_some() && !self.camera_keyframes.is_empty() {
            return Err(fault(
                "",
                0,
                "camera_path",
                "give camera_path or [[camera_keyframes]], not both".into(),
            ));
        }
        for (table, keys) in [
            ("camera_keyframes", &self.camera_keyframes),
            ("light_keyframes", &self.light_keyframes),
        ] {
            check_keyframes(table, keys)?;
        }
        if !self.light_keyframes.is_empty() && self.light.is_none() {
            return Err(fault(
                "light_keyframes",
                0,
                "time",
                "a light path needs a [light] table (its cone and intensity)".into(),
            ));
        }
        let mut key_index = 0;
        for (i, m) in self.meshes.iter().enumerate() {
            check_mesh(i, m)?;
            check_object_keys(i, key_index, m)?;
            key_index += m.keyframes.len();
        }
        if let Some(c) = &self.camera {
            check_camera(c)?;
        }
        if let Some(l) = &self.light {
            check_light(l)?;
        }
        if let Some(o) = &self.orbit {
            check_orbit(o)?;
        }
        Ok(())
    }
}

fn point(v: [f32; 3]) -> Result<(), String> {
    if v.iter()
        .all(|c| c.is_finite() && c.abs() <= HUGE_COORDINATE)
    {
        Ok(())
    } else {
        Err(format!(
            "{v:?}: every coordinate must be finite and at most {HUGE_COORDINATE:e} from 0"
        ))
    }
}

fn colour(v: [f32; 3]) -> Result<(), String> {
    if v.iter().all(|c| c.is_finite() && *c >= 0.0) {
        Ok(())
    } else {
        Err(format!("{v:?}: every channel must be finite and >= 0"))
    }
}

fn positive(v: f32) -> Result<(), String> {
    if v.is_finite() && v > 0.0 && v <= HUGE_COORDINATE {
        Ok(())
    } else {
        Err(format!(
            "{v}: must be above 0 and at most {HUGE_COORDINATE:e}"
        ))
    }
}

fn angle(v: f32, max: f32) -> Result<(), String> {
    if v.is_finite() && v > 0.0 && v <= max {
        Ok(())
    } else {
        Err(format!("{v}: must be above 0 and at most {max} degrees"))
    }
}

/// The camera or light keyframes under `table`, as a keyframe file's are checked.
fn check_keyframes(table: &'static str, keys: &[Keyframe]) -> Result<(), Fault> {
    super::path::check_keyframes(keys).map_err(|f| fault(table, f.index, f.key, f.message))
}

fn check_mesh(i: usize, m: &MeshEntry) -> Result<(), Fault> {
    let at = |key, message| fault("mesh", i, key, message);
    if m.model.trim().is_empty() {
        return Err(at("model", "empty model name".into()));
    }
    if let Some(p) = m.position {
        point(p).map_err(|e| at("position", e))?;
    }
    if let Some(r) = m.rotation_deg {
        if !r.iter().all(|a| a.is_finite() && a.abs() <= 360.0) {
            return Err(at(
                "rotation_deg",
                format!("{r:?}: angles must be finite, within +-360 degrees"),
            ));
        }
    }
    if let Some(s) = m.scale {
        positive(s).map_err(|e| at("scale", e))?;
    }
    if let Some(a) = m.albedo {
        if !a.iter().all(|c| c.is_finite() && (0.0..=1.0).contains(c)) {
            return Err(at(
                "albedo",
                format!("{a:?}: every channel must be in 0..=1"),
            ));
        }
    }
    Ok(())
}

/// A moving object's keys; `first` is the index of its first `[[mesh.keyframes]]` table in
/// the file (they are counted over every mesh, as the locator counts headers).
fn check_object_keys(i: usize, first: usize, m: &MeshEntry) -> Result<(), Fault> {
    if m.keyframes.is_empty() {
        return Ok(());
    }
    for (key, given) in [
        ("position", m.position.is_some()),
        ("rotation_deg", m.rotation_deg.is_some()),
    ] {
        if given {
            return Err(fault(
                "mesh",
                i,
                key,
                "a moving mesh is placed by its [[mesh.keyframes]]: give it there".into(),
            ));
        }
    }
    for (k, key) in m.keyframes.iter().enumerate() {
        let at = |what, message| fault("mesh.keyframes", first + k, what, message);
        if !key.time.is_finite() || (k > 0 && key.time < m.keyframes[k - 1].time) {
            return Err(at(
                "time",
                format!("{}: times must be finite and non-decreasing", key.time),
            ));
        }
        point(key.position).map_err(|e| at("position", e))?;
        if !key
            .rotation_deg
            .iter()
            .all(|a| a.is_finite() && a.abs() <= 36_000.0)
        {
            return Err(at(
                "rotation_deg",
                format!(
                    "{:?}: angles must be finite, within +-36000 degrees",
                    key.rotation_deg
                ),
            ));
        }
    }
    Ok(())
}

fn check_range(table: &'static str, near: Option<f32>, far: Option<f32>) -> Result<(), Fault> {
    match (near, far) {
        (None, None) => Ok(()),
        (Some(n), Some(f)) => {
            positive(n).map_err(|m| fault(table, 0, "near", m))?;
            positive(f).map_err(|m| fault(table, 0, "far", m))?;
            if f <= n {
                return Err(fault(
                    table,
                    0,
                    "far",
                    format!("far {f} must be beyond near {n}"),
                ));
            }
            match super::camera::depth_range_problem(n, f) {
                Some(m) => Err(fault(table, 0, "near", m)),
                None => Ok(()),
            }
        }
        (Some(_), None) => Err(fault(table, 0, "near", "give far with near".into())),
        (None, Some(_)) => Err(fault(table, 0, "far", "give near with far".into())),
    }
}

fn check_camera(c: &CameraEntry) -> Result<(), Fault> {
    point(c.position).map_err(|m| fault("camera", 0, "position", m))?;
    point(c.target).map_err(|m| fault("camera", 0, "target", m))?;
    if c.position == c.target {
        return Err(fault(
            "camera",
            0,
            "target",
            "the target is the position: no view direction".into(),
        ));
    }
    if let Some(up) = c.up {
        point(up).map_err(|m| fault("camera", 0, "up", m))?;
        let forward = glam::Vec3::from(c.target) - glam::Vec3::from(c.position);
        if glam::Vec3::from(up).cross(forward).length_squared() == 0.0 {
            return Err(fault(
                "camera",
                0,
                "up",
                "zero or parallel to the view direction".into(),
            ));
        }
    }
    if let Some(f) = c.fov_deg {
        angle(f, 179.0).map_err(|m| fault("camera", 0, "fov_deg", m))?;
    }
    check_range("camera", c.near, c.far)
}

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

/// A light entry's keys, by its kind.
fn check_light(l: &LightEntry) -> Result<(), Fault> {
    match l.kind {
        LightKind::Spot => check_spot(l),
    }
}

fn check_spot(l: &LightEntry) -> Result<(), Fault> {
    point(l.position).map_err(|m| fault("light", 0, "position", m))?;
    match (l.target, l.direction) {
        (Some(t), None) => {
            point(t).map_err(|m| fault("light", 0, "target", m))?;
            if t == l.position {
                return Err(fault(
                    "light",
                    0,
                    "target",
                    "the target is the position: no direction".into(),
                ));
            }
        }
        (None, Some(d)) => {
            point(d).map_err(|m| fault("light", 0, "direction", m))?;
            if d == [0.0; 3] {
                return Err(fault("light", 0, "direction", "zero direction".into()));
            }
        }
        (Some(_), Some(_)) => {
            return Err(fault(
                "light",
                0,
                "direction",
                "give target or direction, not both".into(),
            ))
        }
        (None, None) => {
            return Err(fault(
                "light",
                0,
                "position",
                "the light needs a target (or a direction)".into(),
            ))
        }
    }
    // A spot's cone is at most a hemisphere: its shadow map is one perspective frustum.
    if let Some(o) = l.outer_deg {
        angle(o, 89.0).map_err(|m| fault("light", 0, "outer_deg", m))?;
    }
    if let Some(i) = l.inner_deg {
        angle(i, 89.0).map_err(|m| fault("light", 0, "inner_deg", m))?;
        let outer = l.outer_deg.unwrap_or(DEFAULT_OUTER_DEG);
        if i > outer {
            return Err(fault(
                "light",
                0,
                "inner_deg",
                format!("{i} is wider than the outer angle {outer}"),
            ));
        }
    }
    // Its bound depends on the scene's size: checked when the scene is built.
    if let Some(c) = l.intensity {
        colour(c).map_err(|m| fault("light", 0, "intensity", m))?;
    }
    check_range("light", l.near, l.far)
}

fn check_orbit(o: &OrbitEntry) -> Result<(), Fault> {
    let at = |key, m| fault("orbit", 0, key, m);
    match o {
        OrbitEntry::Around { center } => point(*center).map_err(|m| at("center", m)),
        OrbitEntry::Inside {
            center,
            radius,
            height,
            start,
            open_towards,
        } => {
            point(*center).map_err(|m| at("center", m))?;
            positive(*radius).map_err(|m| at("radius", m))?;
            if !height.is_finite() || height.abs() > HUGE_COORDINATE {
                return Err(at("height", format!("{height}: must be finite")));
            }
            point(*start).map_err(|m| at("start", m))?;
            if let Some(d) = open_towards {
                point(*d).map_err(|m| at("open_towards", m))?;
            }
            Ok(())
        }
    }
}

/// The outer cone angle a light entry without one gets.
pub const DEFAULT_OUTER_DEG: f32 = 45.0;

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SceneFile, String> {
        SceneFile::parse(Path::new("s.toml"), text).map_err(|e| e.to_string())
    }

    #[test]
    fn a_minimal_file_has_one_mesh() {
        let f = parse("[[mesh]]\nmodel = \"bunny\"\n").unwrap();
        assert_eq!(f.meshes.len(), 1);
        assert_eq!(f.meshes[0].model, "bunny");
        assert!(f.camera.is_none() && f.light.is_none());
    }

    /// A light's kind is `spot` unless the table names another of LightKind's.
    #[test]
    fn a_light_is_a_spot_by_default() {
        let light = "position = [0, 1, 0]\ntarget = [0, 0, 0]\n";
        let plain = parse(&format!("[[mesh]]\nmodel = \"a\"\n[light]\n{light}")).unwrap();
        let named = parse(&format!(
            "[[mesh]]\nmodel = \"a\"\n[light]\nkind = \"spot\"\n{light}"
        ))
        .unwrap();
        assert_eq!(plain.light.as_ref().unwrap().kind, LightKind::Spot);
        assert_eq!(plain, named);
    }

    #[test]
    fn errors_name_line_and_key() {
        let cases = [
            ("name = \"x\"\n", "s.toml: mesh: no [[mesh]]"),
            (
                "[[mesh]]\nmodel = \"a\"\nscale = -2\n",
                "s.toml:3: mesh[0].scale: -2",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[[mesh]]\nmodel = \"b\"\nalbedo = [2, 0, 0]\n",
                "s.toml:5: mesh[1].albedo",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[camera]\nposition = [0, 0, 0]\ntarget = [0, 0, 1]\nnear = 2\nfar = 1\n",
                "s.toml:7: camera.far: far 1 must be beyond near 2",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[light]\nposition = [0, 1, 0]\ntarget = [0, 0, 0]\nouter_deg = 95\n",
                "s.toml:6: light.outer_deg",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[camera]\nposition = [0, 0, 0]\ntraget = [0, 0, 1]\n",
                "s.toml:5: camera.traget: unknown field `traget`",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[camera]\nposition = [0, \"x\", 0]\n",
                "s.toml:4: camera.position",
            ),
            ("[[mesh]\nmodel = 1\n", "s.toml:1:"),
            (
                "[[mesh]]\nmodel = \"a\"\n[[mesh.keyframes]]\ntime = 0\nposition = [0, 0, 0]\n[[mesh]]\nmodel = \"b\"\n[[mesh.keyframes]]\ntime = 1\nposition = [0, 0, 0]\n[[mesh.keyframes]]\ntime = 0.5\nposition = [1, 0, 0]\n",
                "s.toml:12: mesh.keyframes[2].time",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\nposition = [1, 0, 0]\n[[mesh.keyframes]]\ntime = 0\nposition = [0, 0, 0]\n",
                "s.toml:3: mesh[0].position: a moving mesh",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[light]\nposition = [0, 1, 0]\n",
                "s.toml:4: light.position: the light needs a target",
            ),
            // A kind LightKind does not name, refused with the names it does.
            (
                "[[mesh]]\nmodel = \"a\"\n[light]\nkind = \"candle\"\nposition = [0, 1, 0]\n",
                "s.toml:4: light.kind: unknown variant `candle`, expected `spot`",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[light]\nposition = [0, 1, 0]\ntarget = [0, 0, 0]\n[[light_keyframes]]\ntime = 1\nposition = [0, 1, 0]\ntarget = [0, 0, 0]\n[[light_keyframes]]\ntime = 0.5\nposition = [0, 1, 0]\ntarget = [1, 0, 0]\n",
                "s.toml:11: light_keyframes[1].time",
            ),
            // A wrong type inside [orbit] at its key's line, not the table's.
            (
                "[[mesh]]\nmodel = \"a\"\n[orbit]\nkind = \"inside\"\ncenter = [0, 1, 0]\nstart = 0\n",
                "s.toml:6: orbit.start: invalid type: integer `0`",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[orbit]\nkind = \"inside\"\ncenter = [0, 1, 0]\n",
                "s.toml:3: orbit: kind = \"inside\" needs `radius`",
            ),
            (
                "[[mesh]]\nmodel = \"a\"\n[orbit]\nkind = \"sideways\"\n",
                "s.toml:3: orbit: kind \"sideways\": expected",
            ),
        ];
        for (text, expected) in cases {
            let e = parse(text).expect_err(text);
            assert!(e.starts_with(expected), "{text}\n-> {e}\nwanted {expected}");
        }
    }

    #[test]
    fn writing_and_reading_gives_the_same_file() {
        let f = SceneFile {
            name: Some("t".into()),
            ambient: Some([0.1, 0.2, 0.3]),
            camera_path: Some("orbit:12s".into()),
            light_keyframes: vec![Keyframe {
                time: 0.5,
                position: [0.0, 1.5, 0.25],
                target: [0.1, 0.0, 0.0],
            }],
            meshes: vec![
                MeshEntry {
                    model: "cornell-box".into(),
                    ..Default::default()
                },
                MeshEntry {
                    model: SPHERE.into(),
                    position: Some([0.1, 0.2, 0.3]),
                    rotation_deg: Some([0.0, 33.3, 0.0]),
                    scale: Some(0.2),
                    albedo: Some([0.9, 0.1, 0.1]),
                    ground: None,
                    keyframes: Vec::new(),
                },
                MeshEntry {
                    model: SPHERE.into(),
                    scale: Some(0.1),
                    keyframes: vec![
                        ObjectKey {
                            time: 0.0,
                            position: [0.0, 0.1, 0.0],
                            rotation_deg: [0.0; 3],
                        },
                        ObjectKey {
                            time: 1.5,
                            position: [0.5, 0.1, 0.0],
                            rotation_deg: [0.0, 0.0, -286.5],
                        },
                    ],
                    ..Default::default()
                },
            ],
            camera: Some(CameraEntry {
                position: [0.0, 1.0, 3.4],
                target: [0.0, 1.0, 0.0],
                fov_deg: Some(40.0),
                near: Some(0.05),
                far: Some(20.0),
                up: None,
            }),
            light: Some(LightEntry {
                position: [0.0, 1.9, 0.0],
                direction: Some([0.0, -1.0, 0.0]),
                intensity: Some([6.0, 5.2, 4.2]),
                ..Default::default()
            }),
            orbit: Some(OrbitEntry::Inside {
                center: [0.0, 1.0, 0.0],
                radius: 0.85,
                height: 1.2,
                start: [0.0, 0.0, 1.0],
                open_towards: Some([0.0, 0.0, 1.0]),
            }),
            ..Default::default()
        };
        let text = f.to_toml();
        assert_eq!(parse(&text).unwrap(), f, "{text}");
    }
}

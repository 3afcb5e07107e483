//! Camera paths for walkthroughs: static, orbit, dolly, or keyframes from a JSON/TOML file.
//!
//! Every path is a function of time in seconds, and a run shows frame i at i / fps seconds
//! (`--fps`, default 60), so frame i puts the camera at the same place whatever the run's
//! length, and the motion per frame is the path's speed over the frame rate.

use super::camera::Camera;
use super::error::SceneError;
use super::validate::HUGE_COORDINATE;
use glam::Vec3;
use std::path::Path;

/// Frame rate that maps frame numbers to path time when none is given.
pub const DEFAULT_FPS: f32 = 60.0;
/// Seconds per turn of `orbit` (about 0.5 degrees per frame at 60 fps).
pub const DEFAULT_ORBIT_SECONDS: f32 = 12.0;
/// Seconds per in-and-out of `dolly`.
pub const DEFAULT_DOLLY_SECONDS: f32 = 6.0;

/// One keyframe at `time` seconds. Between keyframes position and target interpolate
/// linearly; before the first and after the last the camera holds. Times must be finite and
/// non-decreasing (equal times: a cut).
#[derive(serde::Deserialize, serde::Serialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Keyframe {
    pub time: f32,
    pub position: [f32; 3],
    pub target: [f32; 3],
}

#[derive(serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
struct KeyframeFile {
    keyframes: Vec<Keyframe>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum CameraPath {
    Static,
    /// Circles the scene's orbit axis ([`Orbit`]: around a model from outside, inside a
    /// room), 360 degrees of travel per `seconds`.
    Orbit {
        seconds: f32,
    },
    /// Towards the target by 30 % of the distance and back (ping-pong), once per `seconds`.
    Dolly {
        seconds: f32,
    },
    Keyframes(Vec<Keyframe>),
}

/// Fraction of the eye-target distance the dolly covers at its closest point.
pub const DOLLY_FRACTION: f32 = 0.3;

/// Half-angle of the sweep in a room open on one side: the camera swings this far either
/// side of the opening's axis. At 60 degrees the built-in rooms' orbit (0.85 from the axis,
/// looking down at it) still sees only walls and floor with a square view.
pub const OPEN_ROOM_SWEEP_DEG: f32 = 60.0;

/// Where the `orbit` path takes the camera in a scene; each scene sets its own
/// (`Scene::orbit`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Orbit {
    /// A model seen from outside: a full turn about the vertical axis through `center`, at
    /// the base camera's horizontal distance and height, looking at the axis at the base
    /// target's height (the base camera's pitch). Starts at the base camera.
    Around { center: Vec3 },
    /// Inside a room: the eye at `height` on a circle of `radius` about the vertical axis
    /// through `center`, looking at `center`. `open_towards`: the horizontal direction in
    /// which the room is open (the Cornell box's missing front); the camera then starts on
    /// that side, looking away from the opening, and sweeps ±[`OPEN_ROOM_SWEEP_DEG`] there
    /// and back instead of turning fully and looking out. Without it the camera turns fully,
    /// starting on the side `start` points to from the axis.
    Inside {
        center: Vec3,
        radius: f32,
        height: f32,
        open_towards: Option<Vec3>,
        start: Vec3,
    },
}

impl Orbit {
    /// A full turn around `center` from outside.
    pub fn around(center: Vec3) -> Self {
        Self::Around { center }
    }

    /// The camera `turns` turns' worth of travel (360 degrees each) along the orbit.
    fn camera(&self, base: &Camera, turns: f32) -> Camera {
        match *self {
            Self::Around { center } => around(base, center, turns),
            Self::Inside {
                center,
                radius,
                height,
                open_towards,
                start,
            } => {
                let (axis, swing) = match open_towards {
                    Some(open) => (open, sweep(turns, OPEN_ROOM_SWEEP_DEG.to_radians())),
                    None => (start, std::f32::consts::TAU * turns.rem_euclid(1.0)),
                };
                let angle = axis.x.atan2(axis.z) + swing;
                let out = Vec3::new(angle.sin(), 0.0, angle.cos());
                let mut position = center + out * radius;
                position.y = height;
                Camera {
                    position,
                    target: center,
                    ..*base
                }
            }
        }
    }
}

/// A triangle wave of amplitude `half` (radians) travelling a full turn's angle per turn:
/// 0 -> half -> -half -> 0 over 4 half / (2 pi) turns.
fn sweep(turns: f32, half: f32) -> f32 {
    let travel = std::f32::consts::TAU * turns;
    let u = (travel / (4.0 * half)).rem_euclid(1.0);
    half * if u < 0.25 {
        4.0 * u
    } else if u < 0.75 {
        2.0 - 4.0 * u
    } else {
        4.0 * u - 4.0
    }
}

/// Path time of frame `frame` at `fps` frames per second.
pub fn frame_time(frame: u32, fps: f32) -> f32 {
    frame as f32 / fps
}

/// A duration `12`, `12s` or `0.5s`: finite, above zero.
fn parse_seconds(what: &str, s: &str) -> Result<f32, SceneError> {
    let number = s.strip_suffix('s').unwrap_or(s);
    match number.parse::<f32>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(SceneError::CameraPath {
            path: what.into(),
            line: None,
            message: format!("{s:?} is not a duration in seconds above zero (e.g. 12s)"),
        }),
    }
}

impl CameraPath {
    /// `static`, `orbit[:SECONDS]`, `dolly[:SECONDS]` or the path of a `.json` / `.toml`
    /// keyframe file (times in seconds).
    pub fn parse(s: &str) -> Result<CameraPath, SceneError> {
        let (name, duration) = match s.split_once(':') {
            Some((n, d)) if n == "orbit" || n == "dolly" => (n, Some(d)),
            _ => (s, None),
        };
        let seconds = |default| {
            duration
                .map(|d| parse_seconds(s, d))
                .transpose()
                .map(|d| d.unwrap_or(default))
        };
        match name {
            "static" => Ok(Self::Static),
            "orbit" => Ok(Self::Orbit {
                seconds: seconds(DEFAULT_ORBIT_SECONDS)?,
            }),
            "dolly" => Ok(Self::Dolly {
                seconds: seconds(DEFAULT_DOLLY_SECONDS)?,
            }),
            _ => Self::from_file(Path::new(s)),
        }
    }

    /// Reads keyframes from JSON `{"keyframes": [{"time", "position", "target"}, ...]}` or the
    /// same in TOML (`[[keyframes]]`), chosen by extension.
    pub fn from_file(path: &Path) -> Result<CameraPath, SceneError> {
        let at = |line: Option<usize>, message: String| SceneError::CameraPath {
            path: path.to_owned(),
            line,
            message,
        };
        let err = |message: String| at(None, message);
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let is_json = match ext.as_deref() {
            Some("json") => true,
            Some("toml") => false,
            _ => {
                return Err(err(
                    "not a camera path: use static, orbit[:SECONDS], dolly[:SECONDS], or a \
                     .json/.toml keyframe file"
                        .into(),
                ))
            }
        };
        let text =
            super::input::read_regular_text(path).map_err(|e| err(format!("cannot read: {e}")))?;
        let file: KeyframeFile = if is_json {
            serde_json::from_str(&text).map_err(|e| err(format!("invalid JSON: {e}")))?
        } else {
            toml::from_str(&text).map_err(|e| {
                let offset = e.span().map_or(0, |s| s.start);
                let (line, key) = super::toml_locate::key_at(&text, offset);
                at(line, format!("{key}: {}", e.message().trim()))
            })?
        };
        if file.keyframes.is_empty() {
            return Err(err("no keyframes (need at least one)".into()));
        }
        check_keyframes(&file.keyframes).map_err(|f| {
            // A TOML file's key has a line; JSON's are named by index and key.
            let (line, key) = if is_json {
                (None, format!("keyframes[{}].{}", f.index, f.key))
            } else {
                super::toml_locate::locate(&text, "keyframes", f.index, f.key)
            };
            at(line, format!("{key}: {}", f.message))
        })?;
        Ok(Self::Keyframes(file.keyframes))
    }

    pub fn name(&self) -> String {
        match self {
            Self::Static => "static".into(),
            Self::Orbit { seconds } => format!("orbit:{seconds}s"),
            Self::Dolly { seconds } => format!("dolly:{seconds}s"),
            Self::Keyframes(k) => format!("keyframes({})", k.len()),
        }
    }

    /// Seconds the path takes before it holds or repeats: a turn, an in-and-out, the last
    /// keyframe's time after the first; 0 for a static camera.
    pub fn duration(&self) -> f32 {
        match self {
            Self::Static => 0.0,
            Self::Orbit { seconds } | Self::Dolly { seconds } => *seconds,
            Self::Keyframes(k) => match (k.first(), k.last()) {
                (Some(a), Some(b)) => b.time - a.time,
                _ => 0.0,
            },
        }
    }

    /// The camera `time` seconds into the path; lens and up come from `base`, and `orbit`
    /// says where the scene lets an orbit go.
    pub fn camera_at(&self, base: &Camera, orbit: &Orbit, time: f32) -> Camera {
        match self {
            Self::Static => *base,
            Self::Orbit { seconds } => orbit.camera(base, time / seconds),
            Self::Dolly { seconds } => {
                // Triangle wave 0 -> 1 -> 0 once per period.
                let u = (time / seconds).rem_euclid(1.0);
                let s = 1.0 - (2.0 * u - 1.0).abs();
                Camera {
                    position: base.position + (base.target - base.position) * (DOLLY_FRACTION * s),
                    ..*base
                }
            }
            Self::Keyframes(keys) => {
                let (position, target) =
                    interpolate(keys, time).unwrap_or((base.position, base.target));
                Camera {
                    position,
                    target,
                    ..*base
                }
            }
        }
    }
}

/// A moving spot light: position and target over time in seconds, interpolated as a camera
/// path's keyframes are (held outside them, mirrored before the first). The cone, intensity
/// and shadow-map depth range stay those of the scene's light.
#[derive(Clone, Debug, PartialEq)]
pub struct LightPath(Vec<Keyframe>);

impl LightPath {
    /// `keys` must be checked (finite, times non-decreasing), as scene files' are.
    pub fn new(keys: Vec<Keyframe>) -> Self {
        Self(keys)
    }

    /// Reads keyframes from a `.json` / `.toml` file as [`CameraPath::from_file`] does (its
    /// errors say "light path").
    pub fn from_file(path: &Path) -> Result<Self, SceneError> {
        match CameraPath::from_file(path) {
            Ok(CameraPath::Keyframes(keys)) => Ok(Self(keys)),
            Ok(_) => unreachable!("from_file reads keyframes only"),
            Err(SceneError::CameraPath {
                path,
                line,
                message,
            }) => Err(SceneError::LightPath {
                path,
                line,
                message,
            }),
            Err(e) => Err(e),
        }
    }

    pub fn keys(&self) -> &[Keyframe] {
        &self.0
    }

    /// Seconds from the first key to the last.
    pub fn duration(&self) -> f32 {
        match (self.0.first(), self.0.last()) {
            (Some(a), Some(b)) => b.time - a.time,
            _ => 0.0,
        }
    }

    /// `base` moved to where the path has it `time` seconds after its first key.
    pub fn light_at(&self, base: &super::light::SpotLight, time: f32) -> super::light::SpotLight {
        match interpolate(&self.0, time) {
            Some((position, target)) => super::light::SpotLight {
                position,
                direction: (target - position).normalize_or(base.direction),
                ..*base
            },
            None => *base,
        }
    }
}

/// The outside orbit after `turns` turns.
fn around(base: &Camera, center: Vec3, turns: f32) -> Camera {
    let offset = base.position - center;
    let mut radius = Vec3::new(offset.x, 0.0, offset.z).length();
    // Camera right above the centre: orbit at its distance instead of spinning in place.
    if radius <= 1e-6 * offset.length() || radius == 0.0 {
        radius = offset.length();
    }
    let start = offset.x.atan2(offset.z);
    let angle = start + std::f32::consts::TAU * turns.rem_euclid(1.0);
    let position = Vec3::new(
        center.x + radius * angle.sin(),
        base.position.y,
        center.z + radius * angle.cos(),
    );
    Camera {
        position,
        // Keep the base camera's pitch: look at the axis at the base target's height.
        target: Vec3::new(center.x, base.target.y, center.z),
        ..*base
    }
}

/// What is wrong with a list of keyframes: which keyframe, which key, why.
pub(super) struct KeyFault {
    pub index: usize,
    pub key: &'static str,
    pub message: String,
}

/// A keyframe file's or a scene file's camera or light keyframes: times finite
/// and non-decreasing, points finite and within [`HUGE_COORDINATE`], and a target apart from
/// the position (else there is no view direction: the camera would look down -z silently).
pub(super) fn check_keyframes(keys: &[Keyframe]) -> Result<(), KeyFault> {
    let fault = |index, key, message| KeyFault {
        index,
        key,
        message,
    };
    for (i, k) in keys.iter().enumerate() {
        if !k.time.is_finite() {
            return Err(fault(i, "time", format!("{}: must be finite", k.time)));
        }
        if i > 0 && k.time < keys[i - 1].time {
            return Err(fault(
                i,
                "time",
                format!(
                    "{} is before the previous keyframe's {}: times must not decrease",
                    k.time,
                    keys[i - 1].time
                ),
            ));
        }
        for (key, p) in [("position", k.position), ("target", k.target)] {
            if !p
                .iter()
                .all(|c| c.is_finite() && c.abs() <= HUGE_COORDINATE)
            {
                return Err(fault(
                    i,
                    key,
                    format!(
                        "{p:?}: every coordinate must be finite and at most \
                         {HUGE_COORDINATE:e} from 0"
                    ),
                ));
            }
        }
        if k.position == k.target {
            return Err(fault(
                i,
                "target",
                "the target is the position: no direction".into(),
            ));
        }
    }
    Ok(())
}

/// Position and target `elapsed` seconds after the first keyframe. None only for an empty
/// list. Before the first key (negative `elapsed`, a warmup along the path) the path is
/// mirrored: the camera walks it backwards at the same speed, so a warmup sees the motion the
/// measured frames will see and stays where the keyframes are valid (inside a building).
fn interpolate(keys: &[Keyframe], elapsed: f32) -> Option<(Vec3, Vec3)> {
    let first = keys.first()?;
    let last = keys.last()?;
    let time = first.time + elapsed.abs();
    let pair = |k: &Keyframe| (Vec3::from(k.position), Vec3::from(k.target));
    // The segment [a, b] holding `time`; equal times (a cut) take the later key.
    let Some(i) = keys.windows(2).position(|w| time < w[1].time) else {
        return Some(pair(last));
    };
    let (a, b) = (&keys[i], &keys[i + 1]);
    let span = b.time - a.time;
    let s = if span > 0.0 {
        ((time - a.time) / span).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let (pa, ta) = pair(a);
    let (pb, tb) = pair(b);
    Some((pa.lerp(pb, s), ta.lerp(tb, s)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> Camera {
        Camera::new(
            Vec3::new(0.0, 1.0, 3.4),
            Vec3::new(0.0, 1.0, 0.0),
            40.0,
            0.05,
            20.0,
        )
    }

    fn bounds() -> Orbit {
        Orbit::around(Vec3::new(0.0, 1.0, 0.0))
    }

    /// The Cornell-style room's sweep: starts on the open side looking in, reaches the sweep's
    /// half-angle after half-angle / 360 turns of travel, turns back, and never looks out.
    #[test]
    fn open_room_orbit_sweeps_without_facing_the_opening() {
        let b = base();
        let room = Orbit::Inside {
            center: Vec3::new(0.0, 1.0, 0.0),
            radius: 0.6,
            height: 1.0,
            open_towards: Some(Vec3::Z),
            start: Vec3::Z,
        };
        let orbit = CameraPath::Orbit { seconds: 12.0 };
        let first = orbit.camera_at(&b, &room, 0.0);
        assert!(first.position.abs_diff_eq(Vec3::new(0.0, 1.0, 0.6), 1e-6));
        assert_eq!(first.target, room_center());
        // 360 degrees per 12 s: the 60-degree extreme after 2 s.
        let edge = orbit.camera_at(&b, &room, 2.0);
        let a = 60f32.to_radians();
        assert!(edge
            .position
            .abs_diff_eq(Vec3::new(0.6 * a.sin(), 1.0, 0.6 * a.cos()), 1e-5));
        let mut fastest = 0f32;
        for i in 0..=720 {
            let c = orbit.camera_at(&b, &room, i as f32 / 60.0);
            let look = (c.target - c.position).normalize();
            // Never looks towards the open side by more than the sweep allows.
            assert!(look.z <= -a.cos() + 1e-5, "frame {i}: {look}");
            assert!(((c.position - room_center()).length() - 0.6).abs() < 1e-5);
            if i > 0 {
                let p = orbit.camera_at(&b, &room, (i - 1) as f32 / 60.0).position;
                fastest = fastest.max((c.position - p).length());
            }
        }
        // The speed of a full turn: 0.5 degrees per frame on the 0.6 circle.
        let chord = 2.0 * 0.6 * 0.25f32.to_radians().sin();
        assert!((fastest - chord).abs() < 1e-4, "{fastest} vs {chord}");
        let back = orbit.camera_at(&b, &room, 8.0);
        assert!(
            back.position.abs_diff_eq(first.position, 1e-4),
            "{}",
            back.position
        );
    }

    fn room_center() -> Vec3 {
        Vec3::new(0.0, 1.0, 0.0)
    }

    #[test]
    fn closed_room_orbit_turns_fully_inside() {
        let room = Orbit::Inside {
            center: Vec3::new(2.0, 1.0, -1.0),
            radius: 0.5,
            height: 1.5,
            open_towards: None,
            start: Vec3::X,
        };
        let orbit = CameraPath::Orbit { seconds: 4.0 };
        let first = orbit.camera_at(&base(), &room, 0.0);
        assert!(first.position.abs_diff_eq(Vec3::new(2.5, 1.5, -1.0), 1e-6));
        assert_eq!(first.target, Vec3::new(2.0, 1.0, -1.0));
        let half = orbit.camera_at(&base(), &room, 2.0);
        assert!(half.position.abs_diff_eq(Vec3::new(1.5, 1.5, -1.0), 1e-5));
    }

    #[test]
    fn builtins() {
        assert_eq!(CameraPath::parse("static").unwrap(), CameraPath::Static);
        let b = base();
        assert_eq!(CameraPath::Static.camera_at(&b, &bounds(), 3.0), b);
        let dolly = CameraPath::parse("dolly:4s").unwrap();
        assert_eq!(dolly, CameraPath::Dolly { seconds: 4.0 });
        let mid = dolly.camera_at(&b, &bounds(), 2.0);
        assert!(mid
            .position
            .abs_diff_eq(Vec3::new(0.0, 1.0, 3.4 * 0.7), 1e-5));
        assert!(dolly
            .camera_at(&b, &bounds(), 4.0)
            .position
            .abs_diff_eq(b.position, 1e-5));
        assert_eq!(dolly.camera_at(&b, &bounds(), 0.0), b);
        assert_eq!(
            CameraPath::parse("orbit").unwrap(),
            CameraPath::Orbit {
                seconds: DEFAULT_ORBIT_SECONDS
            }
        );
        assert_eq!(
            CameraPath::parse("orbit:2.5").unwrap(),
            CameraPath::Orbit { seconds: 2.5 }
        );
        for bad in [
            "orbit:0s",
            "orbit:-1",
            "orbit:fast",
            "dolly:nan",
            "orbit:inf",
        ] {
            let e = CameraPath::parse(bad).unwrap_err().to_string();
            assert!(e.contains("seconds"), "{bad}: {e}");
        }
    }

    #[test]
    fn orbit_keeps_distance_and_height() {
        let b = base();
        let orbit = CameraPath::Orbit { seconds: 8.0 };
        let q = orbit.camera_at(&b, &bounds(), 2.0);
        // A quarter turn from +z goes to +x.
        assert!(
            q.position.abs_diff_eq(Vec3::new(3.4, 1.0, 0.0), 1e-4),
            "{}",
            q.position
        );
        assert!(q.target.abs_diff_eq(Vec3::new(0.0, 1.0, 0.0), 1e-6));
        let first = orbit.camera_at(&b, &bounds(), 0.0);
        assert!(first.position.abs_diff_eq(b.position, 1e-5));
    }

    /// Frame i at a given frame rate is the camera at i / fps seconds (`camera_at` takes no
    /// run length, so a run's length cannot move it): the motion per frame is the path's speed
    /// over the frame rate.
    #[test]
    fn frame_i_is_the_camera_at_i_over_fps() {
        let b = base();
        let orbit = CameraPath::parse("orbit:12s").unwrap();
        let at = |frame| orbit.camera_at(&b, &bounds(), frame_time(frame, 60.0));
        // 12 s per turn at 60 fps: 0.5 degrees per frame.
        let step = (at(1).position - b.position).length();
        let chord = 2.0 * 3.4 * (0.25f32).to_radians().sin();
        assert!((step - chord).abs() < 1e-4, "{step} vs {chord}");
        assert!(at(720).position.abs_diff_eq(b.position, 1e-3));
        // Frame i is the camera at i / fps seconds, nothing else: a longer run's frame 100 is
        // this one, and it lies 100 steps of 0.5 degrees along the orbit.
        assert_eq!(at(100), orbit.camera_at(&b, &bounds(), 100.0 / 60.0));
        let turned = (at(100).position - b.position).length();
        let chord_100 = 2.0 * 3.4 * (25f32).to_radians().sin();
        assert!((turned - chord_100).abs() < 1e-3, "{turned} vs {chord_100}");
    }

    #[test]
    fn keyframes_interpolate_in_seconds() {
        let keys = vec![
            Keyframe {
                time: 0.0,
                position: [0.0; 3],
                target: [0.0, 0.0, -1.0],
            },
            Keyframe {
                time: 1.0,
                position: [1.0, 0.0, 0.0],
                target: [1.0, 0.0, -1.0],
            },
            Keyframe {
                time: 3.0,
                position: [1.0, 2.0, 0.0],
                target: [1.0, 2.0, -1.0],
            },
        ];
        let p = CameraPath::Keyframes(keys);
        assert_eq!(p.duration(), 3.0);
        let at = |t| p.camera_at(&base(), &bounds(), t).position;
        assert!(at(0.0).abs_diff_eq(Vec3::ZERO, 1e-6));
        assert!(at(0.5).abs_diff_eq(Vec3::new(0.5, 0.0, 0.0), 1e-6));
        assert!(at(2.0).abs_diff_eq(Vec3::new(1.0, 1.0, 0.0), 1e-6));
        assert!(at(3.0).abs_diff_eq(Vec3::new(1.0, 2.0, 0.0), 1e-6));
        // Held after the last keyframe.
        assert!(at(10.0).abs_diff_eq(Vec3::new(1.0, 2.0, 0.0), 1e-6));
        // Walked backwards before the first (a warmup along the path).
        assert!(at(-0.5).abs_diff_eq(at(0.5), 1e-6));
        assert!(at(-2.0).abs_diff_eq(at(2.0), 1e-6));
    }

    #[test]
    fn bad_keyframes() {
        let k = |t| Keyframe {
            time: t,
            position: [0.0; 3],
            target: [1.0; 3],
        };
        assert!(check_keyframes(&[k(1.0), k(0.0)]).is_err());
        assert!(check_keyframes(&[k(f32::NAN)]).is_err());
        assert!(check_keyframes(&[k(0.0), k(0.0)]).is_ok());
        let still = Keyframe {
            target: [0.0; 3],
            ..k(0.0)
        };
        let e = check_keyframes(&[k(0.0), still]).err().unwrap();
        assert_eq!((e.index, e.key), (1, "target"));
    }

    #[test]
    fn unknown_spec_is_an_error() {
        let e = CameraPath::parse("spiral").unwrap_err().to_string();
        assert!(e.contains("spiral") && e.contains("orbit"), "{e}");
    }
}

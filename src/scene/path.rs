//! Camera paths for walkthroughs: static, orbit, dolly, or keyframes from a JSON/TOML file.
//!
//! All paths are functions of the frame number, so a run is reproducible frame by frame.
//! Run progress is `u = frame / (frame_count - 1)` (0 on the first frame, 1 on the last),
//! except the orbit, which uses `frame / frame_count` so that a looping run does not show
//! the same view twice.

use super::camera::Camera;
use super::error::SceneError;
use super::mesh::Aabb;
use glam::Vec3;
use std::path::Path;

/// One keyframe. `time` is in any unit (seconds or 0..1): the first and last keyframe times
/// are mapped to the first and last frame of the run, and intermediate frames interpolate
/// linearly in between. Times must be finite and non-decreasing.
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
    /// One full turn around the vertical axis through the scene centre, at the base
    /// camera's horizontal distance and height.
    Orbit,
    /// Towards the target by 30 % of the distance and back (ping-pong).
    Dolly,
    Keyframes(Vec<Keyframe>),
}

/// Fraction of the eye-target distance the dolly covers at its closest point.
pub const DOLLY_FRACTION: f32 = 0.3;

impl CameraPath {
    /// `"static" | "orbit" | "dolly"` or the path of a `.json` / `.toml` keyframe file.
    pub fn parse(s: &str) -> Result<CameraPath, SceneError> {
        match s {
            "static" => Ok(Self::Static),
            "orbit" => Ok(Self::Orbit),
            "dolly" => Ok(Self::Dolly),
            _ => Self::from_file(Path::new(s)),
        }
    }

    /// Reads keyframes from JSON `{"keyframes": [{"time", "position", "target"}, ...]}` or the
    /// same in TOML (`[[keyframes]]`), chosen by extension.
    pub fn from_file(path: &Path) -> Result<CameraPath, SceneError> {
        let err = |message: String| SceneError::CameraPath {
            path: path.to_owned(),
            message,
        };
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let is_json =
            match ext.as_deref() {
                Some("json") => true,
                Some("toml") => false,
                _ => return Err(err(
                    "not a camera path: use static, orbit, dolly, or a .json/.toml keyframe file"
                        .into(),
                )),
            };
        let text = std::fs::read_to_string(path).map_err(|e| err(format!("cannot read: {e}")))?;
        let file: KeyframeFile = if is_json {
            serde_json::from_str(&text).map_err(|e| err(format!("invalid JSON: {e}")))?
        } else {
            toml::from_str(&text).map_err(|e| err(format!("invalid TOML: {e}")))?
        };
        check_keyframes(&file.keyframes).map_err(err)?;
        Ok(Self::Keyframes(file.keyframes))
    }

    pub fn name(&self) -> String {
        match self {
            Self::Static => "static".into(),
            Self::Orbit => "orbit".into(),
            Self::Dolly => "dolly".into(),
            Self::Keyframes(k) => format!("keyframes({})", k.len()),
        }
    }

    /// The camera for `frame` of a `frame_count`-frame run; lens and up come from `base`.
    pub fn camera_at(&self, base: &Camera, bounds: &Aabb, frame: u32, frame_count: u32) -> Camera {
        let u = if frame_count > 1 {
            (frame.min(frame_count - 1) as f32) / (frame_count - 1) as f32
        } else {
            0.0
        };
        match self {
            Self::Static => *base,
            Self::Orbit => orbit(base, bounds, frame, frame_count),
            Self::Dolly => {
                // Triangle wave 0 → 1 → 0 over the run.
                let s = 1.0 - (2.0 * u - 1.0).abs();
                Camera {
                    position: base.position + (base.target - base.position) * (DOLLY_FRACTION * s),
                    ..*base
                }
            }
            Self::Keyframes(keys) => {
                let (position, target) =
                    interpolate(keys, u).unwrap_or((base.position, base.target));
                Camera {
                    position,
                    target,
                    ..*base
                }
            }
        }
    }
}

fn orbit(base: &Camera, bounds: &Aabb, frame: u32, frame_count: u32) -> Camera {
    let center = if bounds.is_empty() {
        base.target
    } else {
        bounds.center()
    };
    let offset = base.position - center;
    let mut radius = Vec3::new(offset.x, 0.0, offset.z).length();
    // Camera right above the centre: orbit at the scene's radius instead of spinning in place.
    if radius <= 1e-6 * offset.length() || radius == 0.0 {
        radius = bounds.radius().max(offset.length()).max(1.0);
    }
    let start = offset.x.atan2(offset.z);
    let angle = start + std::f32::consts::TAU * (frame as f32 / frame_count.max(1) as f32);
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

fn check_keyframes(keys: &[Keyframe]) -> Result<(), String> {
    if keys.is_empty() {
        return Err("no keyframes (need at least one)".into());
    }
    for (i, k) in keys.iter().enumerate() {
        let finite =
            k.time.is_finite() && k.position.iter().chain(&k.target).all(|x| x.is_finite());
        if !finite {
            return Err(format!("keyframe {i}: non-finite value"));
        }
        if i > 0 && k.time < keys[i - 1].time {
            return Err(format!(
                "keyframe {i}: time {} is before the previous keyframe's {}",
                k.time,
                keys[i - 1].time
            ));
        }
    }
    Ok(())
}

/// Position and target at run progress `u` in [0, 1]. None only for an empty list.
fn interpolate(keys: &[Keyframe], u: f32) -> Option<(Vec3, Vec3)> {
    let first = keys.first()?;
    let last = keys.last()?;
    let time = first.time + (last.time - first.time) * u;
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

    fn bounds() -> Aabb {
        Aabb {
            min: Vec3::new(-1.0, 0.0, -1.0),
            max: Vec3::new(1.0, 2.0, 1.0),
        }
    }

    #[test]
    fn builtins() {
        assert_eq!(CameraPath::parse("static").unwrap(), CameraPath::Static);
        let b = base();
        assert_eq!(CameraPath::Static.camera_at(&b, &bounds(), 3, 10), b);
        let mid = CameraPath::Dolly.camera_at(&b, &bounds(), 5, 11);
        assert!(mid
            .position
            .abs_diff_eq(Vec3::new(0.0, 1.0, 3.4 * 0.7), 1e-5));
        assert_eq!(CameraPath::Dolly.camera_at(&b, &bounds(), 10, 11), b);
        assert_eq!(CameraPath::Dolly.camera_at(&b, &bounds(), 0, 1), b);
    }

    #[test]
    fn orbit_keeps_distance_and_height() {
        let b = base();
        let q = CameraPath::Orbit.camera_at(&b, &bounds(), 1, 4);
        // A quarter turn from +z goes to +x.
        assert!(
            q.position.abs_diff_eq(Vec3::new(3.4, 1.0, 0.0), 1e-4),
            "{}",
            q.position
        );
        assert!(q.target.abs_diff_eq(Vec3::new(0.0, 1.0, 0.0), 1e-6));
        let first = CameraPath::Orbit.camera_at(&b, &bounds(), 0, 4);
        assert!(first.position.abs_diff_eq(b.position, 1e-5));
    }

    #[test]
    fn keyframes_interpolate_in_time() {
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
        let at = |f, n| p.camera_at(&base(), &bounds(), f, n).position;
        assert!(at(0, 7).abs_diff_eq(Vec3::ZERO, 1e-6));
        assert!(at(1, 7).abs_diff_eq(Vec3::new(0.5, 0.0, 0.0), 1e-6)); // t = 0.5
        assert!(at(4, 7).abs_diff_eq(Vec3::new(1.0, 1.0, 0.0), 1e-6)); // t = 2
        assert!(at(6, 7).abs_diff_eq(Vec3::new(1.0, 2.0, 0.0), 1e-6));
        assert!(at(0, 1).abs_diff_eq(Vec3::ZERO, 1e-6));
    }

    #[test]
    fn bad_keyframes() {
        let k = |t| Keyframe {
            time: t,
            position: [0.0; 3],
            target: [1.0; 3],
        };
        assert!(check_keyframes(&[]).is_err());
        assert!(check_keyframes(&[k(1.0), k(0.0)]).is_err());
        assert!(check_keyframes(&[k(f32::NAN)]).is_err());
        assert!(check_keyframes(&[k(0.0), k(0.0)]).is_ok());
    }

    #[test]
    fn unknown_spec_is_an_error() {
        let e = CameraPath::parse("spiral").unwrap_err().to_string();
        assert!(e.contains("spiral") && e.contains("orbit"), "{e}");
    }
}

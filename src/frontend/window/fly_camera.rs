//! The viewer's fly camera as a pure step: held keys, Shift / Ctrl and the mouse drag since the
//! last frame, with the frame time, give the next camera. No window-system types, so it is
//! unit-tested here; `keys.rs` turns winit events into a [`FlyInput`].

use crate::scene::Camera;
use glam::Vec3;

/// Radians of yaw / pitch per pixel of mouse drag.
const SENSITIVITY: f64 = 0.003;
/// Pitch stays short of straight up / down, where yaw is undefined and the view would flip.
const PITCH_LIMIT_DEG: f32 = 89.0;
/// Normal speed in scene radii per second: any scene is crossed in a few seconds.
const RADII_PER_SECOND: f32 = 0.6;
/// Shift (held): this much faster.
const FAST: f32 = 4.0;
/// Ctrl (held): this much slower (a factor below 1).
const SLOW: f32 = 0.25;

/// What drives the camera between two frames. The movement fields are 1.0 while their key is
/// held, else 0.0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlyInput {
    pub forward: f32,
    pub back: f32,
    pub left: f32,
    pub right: f32,
    pub up: f32,
    pub down: f32,
    /// Shift held.
    pub fast: bool,
    /// Ctrl held.
    pub slow: bool,
    /// Mouse drag (pixels, x right, y down) since the last step.
    pub look: (f64, f64),
}

impl FlyInput {
    /// No key held and no drag: the camera stays as it is.
    pub fn is_idle(&self) -> bool {
        let moving = self.forward + self.back + self.left + self.right + self.up + self.down;
        moving == 0.0 && self.look == (0.0, 0.0)
    }
}

/// Normal movement speed (world units per second) in a scene of bounding-sphere `radius`.
pub fn base_speed(radius: f32) -> f32 {
    RADII_PER_SECOND * radius
}

/// The camera after `dt` seconds of `input` at `speed` (world units per second, before
/// Shift / Ctrl). Yaw turns about world +Y, pitch is clamped to +-89 degrees, the target keeps
/// its distance and `up` becomes +Y. An idle input returns `camera` bit for bit (the viewer's
/// screenshot test relies on an untouched camera matching the headless render).
pub fn step(camera: Camera, input: &FlyInput, dt: f32, speed: f32) -> Camera {
    if input.is_idle() {
        return camera;
    }
    let mut cam = camera;
    let dist = (cam.target - cam.position).length().max(1e-6);
    let (f, _, _) = cam.frame();
    let mut yaw = f.x.atan2(-f.z);
    let mut pitch = f.y.clamp(-1.0, 1.0).asin();
    yaw += (input.look.0 * SENSITIVITY) as f32;
    pitch -= (input.look.1 * SENSITIVITY) as f32;
    let limit = PITCH_LIMIT_DEG.to_radians();
    pitch = pitch.clamp(-limit, limit);
    let forward = Vec3::new(
        yaw.sin() * pitch.cos(),
        pitch.sin(),
        -yaw.cos() * pitch.cos(),
    );
    let right = forward.cross(Vec3::Y).normalize_or(Vec3::X);
    let mut speed = speed;
    if input.fast {
        speed *= FAST;
    }
    if input.slow {
        speed *= SLOW;
    }
    let dir = forward * (input.forward - input.back)
        + right * (input.right - input.left)
        + Vec3::Y * (input.up - input.down);
    cam.position += dir * speed * dt;
    cam.target = cam.position + forward * dist;
    cam.up = Vec3::Y;
    cam
}

#[cfg(test)]
mod tests {
    use super::*;

    const EPS: f32 = 1e-5;

    /// At `position`, looking along `dir` from 2 units away.
    fn camera(position: Vec3, dir: Vec3) -> Camera {
        Camera::new(position, position + dir.normalize() * 2.0, 60.0, 0.1, 100.0)
    }

    fn near(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < EPS
    }

    fn view_dir(c: &Camera) -> Vec3 {
        (c.target - c.position).normalize()
    }

    #[test]
    fn w_moves_forward_along_the_view_direction_by_speed_times_dt() {
        let dir = Vec3::new(1.0, 0.5, -2.0).normalize();
        let start = camera(Vec3::new(1.0, 2.0, 3.0), dir);
        let input = FlyInput {
            forward: 1.0,
            ..FlyInput::default()
        };
        let next = step(start, &input, 0.25, 2.0);
        assert!(near(next.position, start.position + dir * 0.5), "{next:?}");
        assert!(near(view_dir(&next), dir), "the view direction is kept");
        assert!(
            ((next.target - next.position).length() - 2.0).abs() < EPS,
            "the target keeps its distance"
        );
        assert_eq!(next.up, Vec3::Y);

        let back = FlyInput {
            back: 1.0,
            ..FlyInput::default()
        };
        assert!(near(
            step(start, &back, 0.25, 2.0).position,
            start.position - dir * 0.5
        ));
    }

    #[test]
    fn strafe_and_rise_use_the_horizontal_right_and_world_up() {
        let start = camera(Vec3::ZERO, Vec3::NEG_Z);
        let strafe = |input: FlyInput| step(start, &input, 1.0, 1.0).position;
        let d = FlyInput {
            right: 1.0,
            ..FlyInput::default()
        };
        let a = FlyInput {
            left: 1.0,
            ..FlyInput::default()
        };
        let e = FlyInput {
            up: 1.0,
            ..FlyInput::default()
        };
        let q = FlyInput {
            down: 1.0,
            ..FlyInput::default()
        };
        assert!(near(strafe(d), Vec3::X));
        assert!(near(strafe(a), -Vec3::X));
        assert!(near(strafe(e), Vec3::Y));
        assert!(near(strafe(q), -Vec3::Y));
    }

    #[test]
    fn shift_is_four_times_faster_and_ctrl_four_times_slower() {
        let start = camera(Vec3::ZERO, Vec3::NEG_Z);
        let moved = |fast, slow| {
            let input = FlyInput {
                forward: 1.0,
                fast,
                slow,
                ..FlyInput::default()
            };
            step(start, &input, 0.5, 3.0).position.length()
        };
        assert!((moved(false, false) - 1.5).abs() < EPS);
        assert!((moved(true, false) - 6.0).abs() < EPS);
        assert!((moved(false, true) - 0.375).abs() < EPS);
        assert!((moved(true, true) - 1.5).abs() < EPS, "both cancel out");
        assert!(
            (base_speed(2.0) - 1.2).abs() < EPS,
            "0.6 scene radii per second"
        );
    }

    #[test]
    fn mouse_drag_turns_yaw_and_pitch_in_place() {
        let start = camera(Vec3::new(0.0, 1.0, 0.0), Vec3::NEG_Z);
        let turn = |look| {
            let input = FlyInput {
                look,
                ..FlyInput::default()
            };
            step(start, &input, 1.0, 1.0)
        };
        // 100 px right: 0.3 rad of yaw to the right (towards +X), level.
        let right = turn((100.0, 0.0));
        assert_eq!(right.position, start.position, "looking does not move");
        assert!(near(
            view_dir(&right),
            Vec3::new(0.3f32.sin(), 0.0, -0.3f32.cos())
        ));
        // 100 px down: 0.3 rad of pitch downwards, same yaw.
        let down = turn((0.0, 100.0));
        assert!(near(
            view_dir(&down),
            Vec3::new(0.0, -0.3f32.sin(), -0.3f32.cos())
        ));
        // The drag is relative to the current direction: from yaw 0.3, another 100 px is 0.6.
        let again = step(
            right,
            &FlyInput {
                look: (100.0, 0.0),
                ..FlyInput::default()
            },
            1.0,
            1.0,
        );
        assert!(near(
            view_dir(&again),
            Vec3::new(0.6f32.sin(), 0.0, -0.6f32.cos())
        ));
    }

    #[test]
    fn pitch_is_clamped_so_the_camera_never_flips() {
        let start = camera(Vec3::ZERO, Vec3::new(0.3, 0.0, -1.0));
        let limit = 89f32.to_radians();
        for (drag, sign) in [(-1e6, 1.0), (1e6, -1.0)] {
            let input = FlyInput {
                look: (0.0, drag),
                ..FlyInput::default()
            };
            let mut cam = start;
            // Dragging on past the limit frame after frame stays at the limit.
            for _ in 0..3 {
                cam = step(cam, &input, 1.0, 1.0);
                let d = view_dir(&cam);
                assert!((d.y - sign * limit.sin()).abs() < 1e-4, "{d:?}");
                let yaw = d.x.atan2(-d.z);
                assert!(
                    (yaw - 0.3f32.atan2(1.0)).abs() < 1e-3,
                    "yaw kept, not flipped: {d:?}"
                );
                assert_eq!(cam.up, Vec3::Y);
            }
        }
    }

    #[test]
    fn zero_dt_does_not_move() {
        let start = camera(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, -0.2, -1.0));
        let input = FlyInput {
            forward: 1.0,
            right: 1.0,
            up: 1.0,
            fast: true,
            ..FlyInput::default()
        };
        let next = step(start, &input, 0.0, 10.0);
        assert_eq!(next.position, start.position);
        assert!(near(view_dir(&next), view_dir(&start)));
    }

    #[test]
    fn idle_input_leaves_the_camera_bit_for_bit() {
        let mut start = camera(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.1, -0.2, -1.0));
        start.up = Vec3::new(0.1, 1.0, 0.0);
        let idle = FlyInput {
            fast: true,
            slow: true,
            ..FlyInput::default()
        };
        assert!(idle.is_idle(), "modifiers alone do not move");
        assert_eq!(step(start, &idle, 0.1, 10.0), start);
    }
}
